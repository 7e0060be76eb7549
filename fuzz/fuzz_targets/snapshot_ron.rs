//! Snapshots in RON: parsed, checked, restored and stepped.
#![no_main]

use libfuzzer_sys::fuzz_target;
use passo_physics::{World, WorldSnapshot};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(snapshot) = ron::from_str::<WorldSnapshot>(text) else {
        return;
    };
    if let Ok(mut world) = World::from_snapshot(snapshot) {
        world.step(1.0 / 60.0);
    }
});
