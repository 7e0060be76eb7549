//! Prints the state hash of every shipped scene after 300 ticks at its own
//! rate, one line each: the probe `tests/cross_profile.rs` builds under
//! several profiles and compiler flags and compares, so the same scene
//! gives the same bits however Passo is compiled.
//!
//! `cargo run --release -p passo-benches --bin scene_hashes [DIR]`

use passo_scene::Scene;
use std::path::PathBuf;

fn main() {
    let dir = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes"));
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("the scenes folder")
        .map(|e| e.expect("a folder entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    paths.sort();
    for path in paths {
        let scene = Scene::load(&path).expect("a shipped scene loads");
        let mut built = scene.build().expect("a shipped scene builds");
        let dt = (1.0 / scene.file.rate_hz) as f32;
        for tick in 1..=300 {
            built.step(tick, dt);
        }
        let name = path.file_stem().unwrap().to_string_lossy();
        println!("{name} {:016x}", built.world.state_hash());
    }
}
