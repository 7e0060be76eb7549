//! Rollback through bevy_ggrs: a sync test of 1 000 frames that rolls
//! the physics back 7 frames every frame and checks that the same bits
//! come out, and a game that hides state from rollback is caught.

mod common;

use std::time::Duration;

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_ggrs::prelude::*;
use bevy_ggrs::{GgrsConfig, LocalInputs, LocalPlayers, PlayerInputs, ReadInputs, Rollback};
use passo_bevy::prelude::*;
use passo_bevy::rollback::PassoRollbackApp;

type Config = GgrsConfig<u8>;

const LEFT: u8 = 1;
const RIGHT: u8 = 2;
const JUMP: u8 = 4;

/// A player's own state that must roll back with the world.
#[derive(Component, Clone, Copy, Default)]
struct Player {
    handle: usize,
    fall: f32,
}

#[derive(Resource, Default)]
struct Mismatches(Vec<i32>);

/// Local inputs: a fixed pattern of walking and jumping per player.
fn read_inputs(mut commands: Commands, players: Res<LocalPlayers>, mut frame: Local<u32>) {
    let f = *frame;
    *frame += 1;
    let inputs = players
        .0
        .iter()
        .map(|&handle| {
            let phase = (f / 40 + handle as u32) % 4;
            let walk = [RIGHT, RIGHT, LEFT, 0][phase as usize];
            let jump = if (f + 13 * handle as u32) % 55 < 3 {
                JUMP
            } else {
                0
            };
            (handle, walk | jump)
        })
        .collect();
    commands.insert_resource(LocalInputs::<Config>(inputs));
}

/// Inputs to the movers: walk at 4 m/s, jump at 6 m/s, fall under gravity.
fn steer(
    inputs: Res<PlayerInputs<Config>>,
    mut players: Query<(&mut Player, &mut Mover, &MoverOutcome)>,
) {
    let dt = 1.0 / 60.0;
    for (mut player, mut mover, outcome) in &mut players {
        let bits = inputs[player.handle].0;
        let walk = f32::from(bits & RIGHT != 0) - f32::from(bits & LEFT != 0);
        player.fall = if outcome.outcome.on_ground {
            if bits & JUMP != 0 { 6.0 } else { -1.0 }
        } else {
            (player.fall - 9.81 * dt).max(-20.0)
        };
        mover.velocity = Vec2::new(4.0 * walk, player.fall);
    }
}

/// Applies a push that depends on state bevy_ggrs does not roll back.
fn hidden_state(mut world: ResMut<PassoWorld>, mut pushes: Local<u32>) {
    *pushes += 1;
    let dynamic = world
        .bodies()
        .find(|b| b.kind == passo_bevy::passo_physics::BodyKind::Dynamic)
        .map(|b| b.id);
    if let Some(id) = dynamic {
        let kick = passo_bevy::passo_physics::glam::Vec2::new(0.0, (*pushes % 7) as f32 * 0.01);
        world.apply_impulse(id, kick);
    }
}

fn sync_test_app(check_distance: usize, cheat: bool) -> App {
    let mut builder = SessionBuilder::<Config>::new()
        .with_num_players(2)
        .unwrap()
        .with_check_distance(check_distance);
    for handle in 0..2 {
        builder = builder.add_player(PlayerType::Local, handle).unwrap();
    }
    let session = builder.start_synctest_session().unwrap();

    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        GgrsPlugin::<Config>::default(),
        PassoPlugin::new(GgrsSchedule).with_rate(60.0),
    ))
    .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
        1.0 / 60.0,
    )))
    .rollback_passo()
    .rollback_component_with_copy::<Player>()
    .rollback_component_with_clone::<MoverOutcome>()
    .init_resource::<Mismatches>()
    .add_observer(
        |mismatch: On<SyncTestMismatch>, mut seen: ResMut<Mismatches>| {
            seen.0.push(mismatch.event().current_frame);
        },
    )
    .add_systems(ReadInputs, read_inputs)
    .add_systems(GgrsSchedule, steer.before(PassoSystems::Prepare))
    .insert_resource(Session::SyncTest(session));
    if cheat {
        app.add_systems(
            GgrsSchedule,
            hidden_state.after(steer).before(PassoSystems::Prepare),
        );
    }

    app.world_mut()
        .commands()
        .queue(LoadScene::file(common::scene_path("platformer")));
    app.world_mut().flush();
    let level = app.world().resource::<PassoLevel>().clone();
    let mover = CharacterMover::default();
    for (handle, spawn) in ["player", "physics player"].into_iter().enumerate() {
        let at = level.spawn(spawn).unwrap() + Vec2::new(0.0, 0.5);
        app.world_mut().spawn((
            Player { handle, fall: 0.0 },
            RigidBody::Kinematic,
            Collider::capsule(0.4, 0.9),
            Mover {
                settings: mover,
                velocity: Vec2::ZERO,
            },
            Transform::from_xyz(at.x, at.y, 0.0),
            Rollback,
        ));
    }
    app
}

/// 1 000 frames, each rolled back and re-simulated 7 frames deep: every
/// checksum (the world's state hash) matches, and the players moved.
#[test]
fn a_sync_test_of_1000_frames_finds_no_mismatch() {
    let mut app = sync_test_app(7, false);
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
    let mut app = sync_test_app(2, true);
    for _ in 0..60 {
        app.update();
    }
    assert!(!app.world().resource::<Mismatches>().0.is_empty());
}
