//! One physics tick, in the order Passo needs: platforms steered, then
//! characters moved (they meet each platform where it will be), then the
//! world stepped, then what happened written as messages.

use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use passo_physics as passo;

use crate::components::{KinematicTarget, Mover, MoverOutcome, PassoBody};
use crate::convert::to_passo;
use crate::diagnostics::StepDiagnostics;
use crate::messages::{
    BodyPair, ContactBegan, ContactEnded, JointBroke, SensorEntered, SensorExited, SensorVisit,
};
use crate::scene::PassoLevel;
use crate::{BodyEntities, PassoTimestep, PassoWorld};

/// The message writers of a tick.
#[derive(SystemParam)]
pub(crate) struct TickMessages<'w> {
    began: MessageWriter<'w, ContactBegan>,
    ended: MessageWriter<'w, ContactEnded>,
    entered: MessageWriter<'w, SensorEntered>,
    exited: MessageWriter<'w, SensorExited>,
    broke: MessageWriter<'w, JointBroke>,
}

/// The tick's length: the plugin's own, or the schedule's clock (Bevy's
/// fixed clock in `FixedUpdate`). `None`, with a warning, for a length
/// the world cannot step (0, negative, not finite or over an hour).
pub(crate) fn tick_length(timestep: &PassoTimestep, time: &Time) -> Option<f32> {
    let dt = timestep.0.unwrap_or_else(|| time.delta_secs());
    if dt > 0.0 && dt <= passo::constants::MAX_STEP {
        Some(dt)
    } else {
        warn_once!(
            "Passo: a tick of {dt} s cannot be stepped (it must be > 0 and at most {} s): \
             the world was not stepped",
            passo::constants::MAX_STEP
        );
        None
    }
}

/// Steers platforms, moves characters, steps the world and writes its
/// messages. Runs in [`PassoSystems::Step`](crate::PassoSystems).
#[allow(clippy::too_many_arguments)]
pub(crate) fn step_world(
    mut world: ResMut<PassoWorld>,
    entities: Res<BodyEntities>,
    timestep: Res<PassoTimestep>,
    time: Res<Time>,
    level: Option<Res<PassoLevel>>,
    targets: Query<(&PassoBody, &KinematicTarget)>,
    mut movers: Query<(&PassoBody, &Mover, &mut MoverOutcome)>,
    mut messages: TickMessages,
    mut diagnostics: StepDiagnostics,
) {
    let Some(dt) = tick_length(&timestep, &time) else {
        return;
    };
    let world = &mut world.0;

    // 1. Platforms: a level's paths, then the game's targets, by body id.
    if let Some(level) = &level {
        let t_end = world.stats().steps.saturating_add(1) as f64 * f64::from(dt);
        passo_scene::BuiltScene::drive_platforms(&level.platforms, world, t_end, dt);
    }
    let mut steered: Vec<_> = targets.iter().collect();
    steered.sort_unstable_by_key(|t| *t.0);
    for (&PassoBody(id), target) in steered {
        if let Err(error) = world.try_set_kinematic_target(id, to_passo(target.0), dt) {
            warn_once!("Passo: a KinematicTarget was refused: {error}");
        }
    }

    // 2. Characters, by body id.
    let mut moving: Vec<_> = movers.iter_mut().collect();
    moving.sort_unstable_by_key(|m| *m.0);
    for (&PassoBody(id), mover, mut outcome) in moving {
        let translation = to_passo(mover.velocity) * dt;
        match world.move_character(id, translation, &mover.settings, dt) {
            Ok(done) => {
                outcome.outcome = done;
                outcome.error = None;
            }
            Err(error) => {
                warn_once!("Passo: a Mover's move was refused: {error}");
                outcome.error = Some(error);
            }
        }
    }

    // 3. The step.
    let started = diagnostics.start();
    world.step(dt);
    diagnostics.finish(started, world);

    // 4. What happened, in the world's order.
    let events = world.events();
    // A world with nothing shaped has no events this step: what it holds
    // is from an earlier one.
    let fresh = events.step == world.stats().steps;
    let none = passo::ContactEvents::default();
    let events = if fresh { events } else { &none };
    let pair = |p| BodyPair::new(p, &entities);
    let visit = |p| SensorVisit::new(p, &entities);
    messages
        .began
        .write_batch(events.begin.iter().map(|p| ContactBegan(pair(p))));
    messages
        .ended
        .write_batch(events.end.iter().map(|p| ContactEnded(pair(p))));
    messages
        .entered
        .write_batch(events.sensor_begin.iter().map(|p| SensorEntered(visit(p))));
    messages
        .exited
        .write_batch(events.sensor_end.iter().map(|p| SensorExited(visit(p))));
    for broken in world.broken_joints() {
        messages.broke.write(JointBroke {
            id: broken.id,
            def: broken.def,
            force: broken.force,
        });
    }
}
