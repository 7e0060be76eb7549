//! # passo-bevy
//!
//! Passo's 2D physics in [Bevy](https://bevyengine.org): a plugin that
//! steps a [`passo_physics::World`] in `FixedUpdate`, bodies made from
//! components, `Transform`s written back (and interpolated between ticks
//! if asked), contact and sensor events as messages, queries as a system
//! parameter, the character mover as a component, scenes and Tiled levels
//! as a command, and rollback through `bevy_ggrs` (feature `ggrs`).
//!
//! ```
//! use bevy::prelude::*;
//! use bevy::time::TimeUpdateStrategy;
//! use passo_bevy::prelude::*;
//! use std::time::Duration;
//!
//! let mut app = App::new();
//! app.add_plugins((MinimalPlugins, PassoPlugin::default().with_rate(60.0)))
//!     // Run exactly one tick per update, whatever the machine's clock.
//!     .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(1.0 / 60.0)));
//! let ball = app
//!     .world_mut()
//!     .spawn((RigidBody::Dynamic, Collider::circle(0.5), Transform::from_xyz(0.0, 10.0, 0.0)))
//!     .id();
//! for _ in 0..61 {
//!     app.update();
//! }
//! // One second of semi-implicit Euler: y = 10 - g dt² (1 + 2 + ... + 60).
//! let dt = 1.0f32 / 60.0;
//! let y = app.world().get::<Position>(ball).unwrap().0.y;
//! assert!((y - (10.0 - 9.81 * dt * dt * 1830.0)).abs() < 1e-3, "{y}");
//! ```
//!
//! Bevy and Passo use different versions of `glam`: every vector in this
//! crate's API is Bevy's, and the plugin converts at the boundary. The
//! [`PassoWorld`] resource is Passo's world itself, with Passo's vectors
//! (`passo_physics::glam::Vec2`), for what the components do not cover:
//! joints, impulses, force zones, contact hooks, snapshots.
#![warn(missing_docs, unreachable_pub)]
#![forbid(unsafe_code)]

use std::collections::BTreeMap;

use bevy::app::PostUpdate;
use bevy::ecs::intern::Interned;
use bevy::ecs::schedule::ScheduleLabel;
use bevy::prelude::*;
use bevy::transform::TransformSystems;
use passo_physics as passo;

pub mod components;
mod convert;
#[cfg(feature = "debug-draw")]
pub mod debug_draw;
pub mod diagnostics;
pub mod messages;
pub mod queries;
#[cfg(feature = "ggrs")]
pub mod rollback;
pub mod scene;
mod step;
mod sync;

pub use components::{
    BodyError, Bullet, Collider, Filter, GravityScale, KinematicTarget, LinearVelocity, Mass,
    Mover, MoverOutcome, OneWay, PassoBody, PhysicsMaterial, Position, PreviousPosition, RigidBody,
    Sensor, TransformInterpolation,
};
pub use messages::{
    BodyPair, ContactBegan, ContactEnded, JointBroke, SceneLoadFailed, SensorEntered, SensorExited,
    SensorVisit,
};
pub use passo_physics;
pub use queries::{QueryFilter, RayHit, ShapeHit, SpatialQuery};
pub use scene::{LoadScene, PassoLevel, SceneColour};

/// The crate's README: its snippet runs as a test.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadMe;

/// The guide's Bevy chapter (`docs/guide/src/bevy.md`): its Rust snippets
/// run as tests.
#[cfg(doctest)]
#[doc = include_str!("../../../docs/guide/src/bevy.md")]
pub struct GuideChapter;

/// Everything a game usually needs: `use passo_bevy::prelude::*;`.
pub mod prelude {
    pub use crate::{
        BodyError, Bullet, Collider, ContactBegan, ContactEnded, Filter, GravityScale, JointBroke,
        KinematicTarget, LinearVelocity, LoadScene, Mass, Mover, MoverOutcome, OneWay, PassoBody,
        PassoLevel, PassoPlugin, PassoSystems, PassoTimestep, PassoWorld, PhysicsMaterial,
        Position, PreviousPosition, QueryFilter, RigidBody, SceneColour, SceneLoadFailed, Sensor,
        SensorEntered, SensorExited, SpatialQuery, TransformInterpolation,
    };
    pub use passo_physics::{CharacterMover, CollisionFilter, FrictionMix, WorldSettings};
}

#[cfg(feature = "debug-draw")]
pub use debug_draw::{PassoDebugDraw, PassoDebugDrawPlugin};

/// The physics world: a resource holding Passo's [`World`](passo::World).
/// Reach through it for everything the components do not cover; the
/// plugin steps it.
#[derive(Resource, Clone, Debug, Deref, DerefMut)]
pub struct PassoWorld(pub passo::World);

/// Which entity owns each body, kept by the plugin. Bodies with no entity
/// (a level's tiles) are not in it.
#[derive(Resource, Clone, Debug, Default)]
pub struct BodyEntities {
    by_body: BTreeMap<passo::BodyId, Entity>,
    by_entity: BTreeMap<Entity, passo::BodyId>,
}

impl BodyEntities {
    /// The entity of a body.
    pub fn entity(&self, body: passo::BodyId) -> Option<Entity> {
        self.by_body.get(&body).copied()
    }

    /// The body of an entity.
    pub fn body(&self, entity: Entity) -> Option<passo::BodyId> {
        self.by_entity.get(&entity).copied()
    }

    /// Every body that has an entity, in body id order.
    pub fn iter(&self) -> impl Iterator<Item = (passo::BodyId, Entity)> + '_ {
        self.by_body.iter().map(|(&b, &e)| (b, e))
    }

    pub(crate) fn insert(&mut self, body: passo::BodyId, entity: Entity) {
        self.by_body.insert(body, entity);
        self.by_entity.insert(entity, body);
    }

    pub(crate) fn remove(&mut self, body: passo::BodyId) {
        if let Some(entity) = self.by_body.remove(&body) {
            self.by_entity.remove(&entity);
        }
    }
}

/// The length of a physics tick, seconds: `Some(dt)` steps by exactly
/// `dt` (set by [`PassoPlugin::with_rate`] and by [`LoadScene`]); `None`
/// steps by the schedule's clock (`Time<Fixed>`'s timestep in
/// `FixedUpdate`).
#[derive(Resource, Clone, Copy, Debug, Default, PartialEq)]
pub struct PassoTimestep(pub Option<f32>);

/// The plugin's systems: the first three in the physics schedule, in
/// this order, every tick; [`Interpolate`](Self::Interpolate) in
/// `PostUpdate`, every frame. Put the
/// game's tick logic (inputs, movers' velocities, forces) before
/// [`Prepare`](Self::Prepare), and what reads the results (messages,
/// positions) after [`Writeback`](Self::Writeback).
#[derive(SystemSet, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PassoSystems {
    /// Component changes reach the world: bodies remade, settings
    /// changed, teleports and velocities applied.
    Prepare,
    /// Platforms steered, characters moved, the world stepped, messages
    /// written.
    Step,
    /// Positions, velocities and transforms written back.
    Writeback,
    /// In `PostUpdate`, every frame, before transforms propagate: bodies
    /// with [`TransformInterpolation`] drawn between their last two ticks.
    /// Order a camera that follows a body after it.
    Interpolate,
}

/// Steps a Passo world in a schedule (by default `FixedUpdate`, at
/// Bevy's fixed timestep).
///
/// ```
/// use bevy::prelude::*;
/// use passo_bevy::prelude::*;
///
/// App::new().add_plugins((
///     MinimalPlugins,
///     // 120 ticks a second, the world's default settings (gravity 9.81 m/s²).
///     PassoPlugin::default().with_rate(120.0),
/// ));
/// ```
pub struct PassoPlugin {
    schedule: Interned<dyn ScheduleLabel>,
    rate_hz: Option<f64>,
    settings: passo::WorldSettings,
}

impl Default for PassoPlugin {
    /// `FixedUpdate` at Bevy's fixed timestep, with the world's default
    /// settings.
    fn default() -> Self {
        Self::new(FixedUpdate)
    }
}

impl PassoPlugin {
    /// Steps the world in `schedule` (for rollback, `bevy_ggrs`'s
    /// `GgrsSchedule`). Outside `FixedUpdate`, set the tick with
    /// [`with_rate`](Self::with_rate).
    pub fn new(schedule: impl ScheduleLabel) -> Self {
        Self {
            schedule: schedule.intern(),
            rate_hz: None,
            settings: passo::WorldSettings::default(),
        }
    }

    /// Ticks `hz` times a second, each of exactly `1 / hz` seconds, and
    /// sets Bevy's fixed clock to that rate.
    pub fn with_rate(mut self, hz: f64) -> Self {
        self.rate_hz = Some(hz);
        self
    }

    /// The world's settings: gravity and forces, integrator, contacts.
    /// Invalid settings are reported and the defaults used.
    pub fn with_settings(mut self, settings: passo::WorldSettings) -> Self {
        self.settings = settings;
        self
    }
}

impl Plugin for PassoPlugin {
    fn build(&self, app: &mut App) {
        let world = passo::World::new(self.settings).unwrap_or_else(|error| {
            error!("Passo: invalid world settings ({error}); the defaults are used");
            passo::World::default()
        });
        let dt = match self.rate_hz {
            Some(hz) if hz.is_finite() && hz > 0.0 => {
                app.insert_resource(Time::<Fixed>::from_hz(hz));
                Some((1.0 / hz) as f32)
            }
            Some(hz) => {
                error!("Passo: a rate of {hz} Hz cannot tick; Bevy's fixed timestep is used");
                None
            }
            None => None,
        };
        app.insert_resource(PassoWorld(world))
            .insert_resource(PassoTimestep(dt))
            .init_resource::<BodyEntities>()
            .add_message::<ContactBegan>()
            .add_message::<ContactEnded>()
            .add_message::<SensorEntered>()
            .add_message::<SensorExited>()
            .add_message::<JointBroke>()
            .add_message::<SceneLoadFailed>()
            .add_observer(sync::on_add_rigid_body)
            .add_observer(sync::on_remove_rigid_body)
            .add_observer(sync::on_remove_part::<Collider>)
            .add_observer(sync::on_remove_part::<Mass>)
            .add_observer(sync::on_remove_setting::<PhysicsMaterial>)
            .add_observer(sync::on_remove_setting::<Filter>)
            .add_observer(sync::on_remove_setting::<Sensor>)
            .add_observer(sync::on_remove_setting::<OneWay>)
            .add_observer(sync::on_remove_setting::<GravityScale>)
            .add_observer(sync::on_remove_setting::<Bullet>)
            .add_observer(sync::on_remove_setting::<KinematicTarget>)
            .add_observer(sync::on_remove_setting::<Mover>)
            .configure_sets(
                self.schedule,
                (
                    PassoSystems::Prepare,
                    PassoSystems::Step,
                    PassoSystems::Writeback,
                )
                    .chain(),
            )
            .add_systems(
                self.schedule,
                (
                    sync::apply_changes.in_set(PassoSystems::Prepare),
                    step::step_world.in_set(PassoSystems::Step),
                    sync::write_back.in_set(PassoSystems::Writeback),
                ),
            )
            .configure_sets(
                PostUpdate,
                PassoSystems::Interpolate.before(TransformSystems::Propagate),
            )
            .add_systems(
                PostUpdate,
                sync::interpolate_transforms.in_set(PassoSystems::Interpolate),
            );
        diagnostics::register(app);
    }
}
