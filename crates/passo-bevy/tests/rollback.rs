//! Rollback through bevy_ggrs: a sync test of 1 000 frames that rolls
//! the physics back 7 frames every frame and checks that the same bits
//! come out, and a game that hides state from rollback is caught.

#[path = "../examples/rollback/game.rs"]
mod game;

use bevy::prelude::*;
use game::{Mismatches, Player, sync_test_app};
use passo_bevy::prelude::*;

fn scenes() -> String {
    format!("{}/../../assets/scenes", env!("CARGO_MANIFEST_DIR"))
}

/// 1 000 frames, each rolled back and re-simulated 7 frames deep: every
/// checksum (the world's state hash) matches, and the players moved.
#[test]
fn a_sync_test_of_1000_frames_finds_no_mismatch() {
    let mut app = sync_test_app(&scenes(), 7, false);
    let mut start = Vec::new();
    app.update();
    let mut players = app.world_mut().query::<(&Player, &Position)>();
    for (_, at) in players.iter(app.world()) {
        start.push(at.0);
    }
    for _ in 0..1000 {
        app.update();
    }
    assert_eq!(app.world().resource::<Mismatches>().0, Vec::<i32>::new());
    let frames = app.world().resource::<bevy_ggrs::RollbackFrameCount>().0;
    assert!(frames >= 1000, "{frames}");
    // The world's tick count rolls back with it: one tick per frame, not
    // counting the 7 re-simulated frames of each.
    let steps = app.world().resource::<PassoWorld>().stats().steps;
    assert_eq!(steps, frames as u64);
    let moved: Vec<f32> = players
        .iter(app.world())
        .zip(&start)
        .map(|((_, at), from)| (at.0 - *from).length())
        .collect();
    assert!(moved.iter().all(|&d| d > 1.0), "{moved:?}");
}

/// The same test catches a game that changes the physics from state it
/// does not roll back.
#[test]
fn a_sync_test_catches_state_hidden_from_rollback() {
    let mut app = sync_test_app(&scenes(), 2, true);
    for _ in 0..60 {
        app.update();
    }
    assert!(!app.world().resource::<Mismatches>().0.is_empty());
}
