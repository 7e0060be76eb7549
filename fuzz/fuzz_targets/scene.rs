//! RON scene files: parsed and checked, then built and stepped when small.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(scene) = passo_scene::Scene::parse(text, "fuzz.ron") else {
        return;
    };
    // A valid scene may hold a million bodies: build only small ones, so a
    // run measures the checks rather than the physics.
    if text.len() < 4096
        && let Ok(mut built) = scene.build()
        && built.world.len() <= 64
    {
        for _ in 0..3 {
            built.step(1.0 / 60.0);
        }
    }
});
