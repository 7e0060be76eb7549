//! The components a game puts on its entities to make them Passo bodies,
//! and the ones the plugin keeps up to date.
//!
//! Spawn an entity with a [`RigidBody`] and it gets a body in the
//! [`PassoWorld`](crate::PassoWorld) when the spawn is applied. The other
//! components here shape the body; each has a default, so a [`RigidBody`]
//! alone is a 1 kg point mass. Change one later and the body follows at
//! the next physics tick; remove the [`RigidBody`] (or despawn the entity)
//! and the body goes.

use bevy::math::Vec2;
use bevy::prelude::{Component, Transform};
use passo_physics as passo;

use crate::convert::{to_bevy, to_passo};

/// Makes the entity a Passo body: dynamic (moved by forces and contacts),
/// static (never moves) or kinematic (moves at the velocity the game
/// gives it, pushes dynamic bodies, is pushed by nothing).
///
/// Where it starts: its [`Position`] if the entity has one, else its
/// [`Transform`]'s `x` and `y`. Changing it later rebuilds the body (it
/// keeps its position and velocity; its contacts start afresh and its
/// joints go).
#[derive(Component, Clone, Copy, Debug, Default, PartialEq, Eq)]
#[require(Transform, LinearVelocity)]
pub enum RigidBody {
    /// Moved by gravity, forces and contacts.
    #[default]
    Dynamic,
    /// Never moves: ground, walls.
    Static,
    /// Moves at its [`LinearVelocity`] (or towards its
    /// [`KinematicTarget`]) whatever touches it: platforms, doors,
    /// characters driven by a [`Mover`].
    Kinematic,
}

impl RigidBody {
    pub(crate) fn kind(self) -> passo::BodyKind {
        match self {
            Self::Dynamic => passo::BodyKind::Dynamic,
            Self::Static => passo::BodyKind::Static,
            Self::Kinematic => passo::BodyKind::Kinematic,
        }
    }

    pub(crate) fn from_kind(kind: passo::BodyKind) -> Self {
        match kind {
            passo::BodyKind::Dynamic => Self::Dynamic,
            passo::BodyKind::Static => Self::Static,
            passo::BodyKind::Kinematic => Self::Kinematic,
        }
    }
}

/// The body's shape. Without one, a body is a point: it feels forces but
/// touches nothing. Bodies do not rotate, so a box stays axis-aligned.
/// Changing it rebuilds the body (see [`RigidBody`]).
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct Collider(pub passo::Shape);

impl Collider {
    /// A circle of `radius` metres.
    pub fn circle(radius: f32) -> Self {
        Self(passo::Shape::circle(radius))
    }

    /// An axis-aligned box, `width` × `height` metres.
    pub fn rectangle(width: f32, height: f32) -> Self {
        Self(passo::Shape::rect(width, height))
    }

    /// A capsule filling a `width` × `height` box, metres: upright (round
    /// top and bottom, the usual character shape) when it is taller than
    /// wide, lying down otherwise.
    pub fn capsule(width: f32, height: f32) -> Self {
        Self(passo::Shape::capsule(width, height))
    }

    /// A convex polygon around the body's position, at most
    /// [`MAX_POLYGON_VERTICES`](passo::MAX_POLYGON_VERTICES) points.
    ///
    /// # Errors
    /// Fewer than 3 points, too many, non-finite ones, or a polygon that
    /// is not convex.
    pub fn polygon(points: &[Vec2]) -> Result<Self, passo::PhysicsError> {
        let points: Vec<passo::glam::Vec2> = points.iter().map(|&p| to_passo(p)).collect();
        passo::Shape::polygon(&points).map(Self)
    }

    /// The shape's half width and half height, metres.
    pub fn half_extents(&self) -> Vec2 {
        to_bevy(self.0.half_extents())
    }
}

/// Mass in kilograms, > 0 (default 1). Static and kinematic bodies
/// ignore it. Changing it rebuilds the body (see [`RigidBody`]).
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct Mass(pub f32);

impl Default for Mass {
    fn default() -> Self {
        Self(1.0)
    }
}

/// How the body's surface behaves in contacts.
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct PhysicsMaterial {
    /// Coulomb friction coefficient, >= 0 (default 0.5).
    pub friction: f32,
    /// Bounce, in `[0, 1]` (default 0).
    pub restitution: f32,
    /// How two bodies' friction coefficients combine.
    pub friction_mix: passo::FrictionMix,
}

impl Default for PhysicsMaterial {
    fn default() -> Self {
        let def = passo::BodyDef::default();
        Self {
            friction: def.friction,
            restitution: def.restitution,
            friction_mix: def.friction_mix,
        }
    }
}

/// Which bodies this one touches: the layers it is on and the layers it
/// collides with (see [`CollisionFilter`](passo::CollisionFilter)).
#[derive(Component, Clone, Copy, Debug, Default, PartialEq)]
pub struct Filter(pub passo::CollisionFilter);

/// The body is a sensor: it reports what enters and leaves it
/// ([`SensorEntered`](crate::SensorEntered),
/// [`SensorExited`](crate::SensorExited)) and pushes nothing.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Sensor;

/// A one-way platform: it blocks only bodies moving against this
/// direction (a unit vector; `Vec2::Y` blocks bodies falling onto its
/// top). A body can fall through one with
/// [`World::drop_through`](passo::World::drop_through).
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct OneWay(pub Vec2);

impl Default for OneWay {
    fn default() -> Self {
        Self(Vec2::Y)
    }
}

/// How strongly the world's gravity pulls this body (default 1; 0 floats).
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct GravityScale(pub f32);

impl Default for GravityScale {
    fn default() -> Self {
        Self(1.0)
    }
}

/// The body's velocity, metres per second. The plugin writes it after
/// every physics tick; write it yourself (before [`PassoSystems::Prepare`])
/// to set the velocity. A kinematic body moves at it.
///
/// [`PassoSystems::Prepare`]: crate::PassoSystems::Prepare
#[derive(Component, Clone, Copy, Debug, Default, PartialEq)]
pub struct LinearVelocity(pub Vec2);

/// The body's position after the last physics tick, metres. The plugin
/// writes it after every tick and inserts it when the body is made;
/// write it yourself to teleport the body. Draw from the [`Transform`],
/// which the plugin sets from this (or, with [`TransformInterpolation`],
/// between the last two ticks).
#[derive(Component, Clone, Copy, Debug, Default, PartialEq)]
pub struct Position(pub Vec2);

/// Steers a kinematic body so it reaches this point at the end of the
/// next physics tick, every tick: a platform following a path the game
/// computes. The body pushes what is in its way and carries what rides
/// it.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq)]
pub struct KinematicTarget(pub Vec2);

/// Sweeps the body continuously so it never passes through thin walls,
/// however fast (bullets). Dynamic bodies only.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Bullet;

/// Draws the entity between the last two physics ticks, so motion looks
/// smooth when the frame rate and the tick rate differ: its
/// [`Transform`] is `lerp(previous, current, overstep)` after every frame,
/// with the overstep fraction of Bevy's fixed clock. Without it the
/// [`Transform`] jumps to each tick's position.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq)]
#[require(PreviousPosition)]
pub struct TransformInterpolation;

/// Where the body was before the last physics tick: what
/// [`TransformInterpolation`] draws from. Kept by the plugin.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq)]
pub struct PreviousPosition(pub Vec2);

/// A character driven by Passo's [character mover](passo::CharacterMover):
/// a kinematic body with a shape that walks, climbs steps and slopes,
/// snaps down small drops, rides platforms and pushes dynamic bodies.
/// Set [`velocity`](Self::velocity) every tick (gravity included: the
/// mover does not fall by itself); read where it ended in
/// [`MoverOutcome`].
#[derive(Component, Clone, Copy, Debug, Default, PartialEq)]
#[require(MoverOutcome)]
pub struct Mover {
    /// The mover's settings: skin, step height, slope limit, snapping.
    pub settings: passo::CharacterMover,
    /// How fast the character wants to move this tick, metres per second.
    pub velocity: Vec2,
}

/// What the last tick's move did: on the ground, against a wall, what it
/// stands on, how far it went (see [`MoveOutcome`](passo::MoveOutcome)).
/// `error` holds why the last move was refused (the body is not kinematic
/// or has no shape, or the settings are out of range), or `None`.
#[derive(Component, Clone, Debug, Default, PartialEq)]
pub struct MoverOutcome {
    /// The outcome of the last move.
    pub outcome: passo::MoveOutcome,
    /// Why the last move was refused, if it was.
    pub error: Option<passo::PhysicsError>,
}

/// The entity's body in the [`PassoWorld`](crate::PassoWorld). Inserted by
/// the plugin when it makes the body; use it with the world's own API
/// (joints, impulses, force zones).
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[component(immutable)]
pub struct PassoBody(pub passo::BodyId);

impl PassoBody {
    /// The body's id in the world.
    pub fn id(self) -> passo::BodyId {
        self.0
    }
}

/// Why the plugin could not make this entity's body (a mass of 0, a
/// position outside the world, a shape out of range). Removed when a
/// later change makes it valid.
#[derive(Component, Clone, Debug, PartialEq)]
pub struct BodyError(pub passo::PhysicsError);
