//! Rollback with `bevy_ggrs` (feature `ggrs`): the world saved and
//! restored as a Passo snapshot every GGRS frame, and checked by its state
//! hash.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_ggrs::{GgrsConfig, GgrsPlugin, GgrsSchedule};
//! use passo_bevy::prelude::*;
//! use passo_bevy::rollback::PassoRollbackApp;
//!
//! type Config = GgrsConfig<u8>;
//! App::new()
//!     .add_plugins((MinimalPlugins, GgrsPlugin::<Config>::default()))
//!     // Step in GGRS's schedule, at its frame rate (60 by default).
//!     .add_plugins(PassoPlugin::new(GgrsSchedule).with_rate(60.0))
//!     .rollback_passo();
//! ```
//!
//! What rolls back: the whole physics world (bodies, contacts, joints,
//! sleep, the tick count) and each mover's [`MoverOutcome`]. After a
//! rollback the plugin writes every body's [`Position`](crate::Position),
//! [`LinearVelocity`](crate::LinearVelocity) and `Transform` from the
//! restored world, so the game's systems see the restored state. Register
//! the game's own components (its players' state, scores) with
//! `bevy_ggrs` as usual, and set each [`Mover`](crate::Mover)'s velocity
//! every frame from the inputs.
//!
//! Messages are written again for every re-simulated frame: a contact
//! that began in a frame that is rolled back and played again is reported
//! again. Play sounds and effects from confirmed frames, or from state.
//!
//! Bodies are made and removed outside the rolled-back frames: spawn
//! them before the session starts, or keep them and move them out of
//! play. A world rolled back past a body's creation no longer holds it.

use bevy::prelude::*;
use bevy_ggrs::{LoadWorld, LoadWorldSystems, RollbackApp, Strategy};
use passo_physics::{World, WorldSnapshot};

use crate::{MoverOutcome, PassoWorld};

/// Saves the world as a [`WorldSnapshot`] (a few hundred bytes plus
/// about 60 bytes a body) and restores it in place, reusing its buffers.
pub struct SnapshotStrategy;

impl Strategy for SnapshotStrategy {
    type Target = PassoWorld;
    type Stored = WorldSnapshot;

    fn store(target: &PassoWorld) -> WorldSnapshot {
        target.snapshot()
    }

    fn load(stored: &WorldSnapshot) -> PassoWorld {
        // A snapshot the world made itself is always valid.
        PassoWorld(World::from_snapshot(stored.clone()).expect("a world's own snapshot restores"))
    }

    fn update(target: &mut PassoWorld, stored: &WorldSnapshot) {
        target
            .restore_from(stored)
            .expect("a world's own snapshot restores");
    }
}

/// Registers the Passo world with `bevy_ggrs`.
pub trait PassoRollbackApp {
    /// Saves and restores the [`PassoWorld`] every GGRS frame, adds its
    /// state hash to GGRS's checksum (so a sync test or a desync report
    /// sees physics that diverge), rolls back each mover's
    /// [`MoverOutcome`], and writes the restored state back to the
    /// components after a rollback.
    fn rollback_passo(&mut self) -> &mut Self;
}

impl PassoRollbackApp for App {
    fn rollback_passo(&mut self) -> &mut Self {
        self.add_plugins(bevy_ggrs::ResourceSnapshotPlugin::<SnapshotStrategy>::default())
            .checksum_resource::<PassoWorld>(|world| world.state_hash())
            .rollback_component_with_clone::<MoverOutcome>()
            .add_systems(
                LoadWorld,
                crate::sync::write_back.after(LoadWorldSystems::Data),
            )
    }
}
