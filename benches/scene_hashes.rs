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
        .map_or_else(|| PathBuf::from(passo_benches::SCENES_DIR), PathBuf::from);
    for path in passo_benches::scene_files(&dir) {
        let scene = Scene::load(&path).expect("a shipped scene loads");
        let mut built = scene.build().expect("a shipped scene builds");
        let dt = (1.0 / scene.file.rate_hz) as f32;
        for _ in 0..300 {
            built.step(dt);
        }
        let name = path.file_stem().unwrap().to_string_lossy();
        println!("{name} {:016x}", built.world.state_hash());
    }
}
