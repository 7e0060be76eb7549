//! Rollback with bevy_ggrs: two players on the platformer level, stepped
//! by the Passo plugin in GGRS's schedule, in a sync test that rolls the
//! game back and re-simulates it every frame. Prints what a snapshot
//! costs per frame.
//!
//! ```text
//! cargo run -p passo-bevy --example rollback --release -- [--frames N] [--check-distance D]
//! ```
//!
//! It exits with an error if any frame's checksum (the world's state
//! hash) differs after a rollback.

mod game;

use std::process::ExitCode;

use bevy::prelude::*;
use game::{Mismatches, sync_test_app};
use passo_bevy::PassoWorld;
use passo_bevy::passo_physics::WorldSnapshot;

fn main() -> ExitCode {
    let mut frames = 1000;
    let mut check_distance = 7;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let value = args.next().and_then(|v| v.parse::<usize>().ok());
        match (arg.as_str(), value) {
            ("--frames", Some(v)) => frames = v,
            ("--check-distance", Some(v)) if (1..8).contains(&v) => check_distance = v,
            _ => {
                eprintln!("usage: rollback [--frames N] [--check-distance 1..7]");
                return ExitCode::FAILURE;
            }
        }
    }

    let scenes = format!("{}/../../assets/scenes", env!("CARGO_MANIFEST_DIR"));
    let mut app = sync_test_app(&scenes, check_distance, false);
    let mut memory = (usize::MAX, 0);
    let mut wire = (usize::MAX, 0);
    for _ in 0..frames {
        app.update();
        let snapshot = app.world().resource::<PassoWorld>().snapshot();
        let bytes = snapshot.heap_bytes() + size_of::<WorldSnapshot>();
        memory = (memory.0.min(bytes), memory.1.max(bytes));
        let encoded = postcard::to_allocvec(&snapshot).map_or(0, |v| v.len());
        wire = (wire.0.min(encoded), wire.1.max(encoded));
    }

    let world = app.world().resource::<PassoWorld>();
    let mismatches = &app.world().resource::<Mismatches>().0;
    let table = format!(
        "| frames | rolled back each frame | bodies | snapshot in memory, bytes | snapshot in postcard, bytes | mismatches |\n\
         |---:|---:|---:|---:|---:|---:|\n\
         | {frames} | {check_distance} | {} | {}–{} | {}–{} | {} |\n",
        world.len(),
        memory.0,
        memory.1,
        wire.0,
        wire.1,
        mismatches.len()
    );
    print!("{table}");
    if mismatches.is_empty() {
        ExitCode::SUCCESS
    } else {
        eprintln!("desync: mismatched checksums at frames {mismatches:?}");
        ExitCode::FAILURE
    }
}
