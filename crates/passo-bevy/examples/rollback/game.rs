//! A small rollback game on the platformer level: two players driven by
//! a fixed pattern of inputs, stepped by the Passo plugin in bevy_ggrs's
//! schedule, checked by a sync test. Shared by the `rollback` example and
//! the rollback tests.

use std::time::Duration;

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_ggrs::prelude::*;
use bevy_ggrs::{GgrsConfig, LocalInputs, LocalPlayers, PlayerInputs, ReadInputs, Rollback};
use passo_bevy::prelude::*;
use passo_bevy::rollback::PassoRollbackApp;

/// One byte of input per player.
pub type Config = GgrsConfig<u8>;

const LEFT: u8 = 1;
const RIGHT: u8 = 2;
const JUMP: u8 = 4;

/// A player's own state that must roll back with the world.
#[derive(Component, Clone, Copy, Default)]
pub struct Player {
    /// Its GGRS handle.
    pub handle: usize,
    /// Its vertical speed, m/s.
    pub fall: f32,
}

/// The frames where the sync test saw a mismatch.
#[derive(Resource, Default)]
pub struct Mismatches(pub Vec<i32>);

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

/// The game in a sync test that rolls back `check_distance` frames every
/// frame. With `cheat`, a system pushes a crate from state GGRS does not
/// roll back: the test must see it.
pub fn sync_test_app(scenes: &str, check_distance: usize, cheat: bool) -> App {
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
        .queue(LoadScene::file(format!("{scenes}/platformer.ron")));
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
