//! Prints the state hash of every shipped scene after each of 300 ticks at
//! its own rate, one `scene tick hash` line per tick: the probe that
//! `tests/cross_profile.rs` builds under several profiles and compiler
//! flags, and the `cross_platform` program builds for aarch64 and wasm32,
//! and compares, so the same scene gives the same bits however and wherever
//! Passo is compiled.
//!
//! `cargo run --release -p passo-benches --bin scene_hashes [DIR]`;
//! `--lanes` prints the solver's lane width in this build instead.

use std::io::Write as _;
use std::path::PathBuf;

fn main() {
    if std::env::args().nth(1).as_deref() == Some("--lanes") {
        println!("{}", passo_physics::SOLVER_LANES);
        return;
    }
    let dir = std::env::args()
        .nth(1)
        .map_or_else(|| PathBuf::from(passo_benches::SCENES_DIR), PathBuf::from);
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    if let Err(e) = passo_benches::hashes::write_table(&dir, &mut out).and_then(|()| out.flush()) {
        eprintln!("scene_hashes: {e}");
        std::process::exit(1);
    }
}
