//! Bodies: the handle, the definition a body is made from, the read-only view
//! the world hands out, and the packed arrays the world steps.

use crate::body::filter::CollisionFilter;
use crate::body::material::FrictionMix;
use crate::constants::{DEFAULT_DRAG_AREA, DEFAULT_FRICTION};
use crate::constants::{MAX_DRAG_AREA, MAX_FRICTION};
use crate::error::{at_most, finite_vec, mass, non_negative, position, positive, unit_interval};
use crate::id::BodyId;
use crate::{PhysicsError, Shape};
use glam::Vec2;

/// Whether a body moves.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum BodyKind {
    /// Moved by forces, impulses and contacts. Has a finite mass.
    #[default]
    Dynamic,
    /// Never moves (ground, walls): infinite mass, zero velocity. Forces and
    /// impulses on it are ignored; its position can still be set by hand
    /// (a teleport: riders are not carried and drawing is not
    /// interpolated; move a [`Kinematic`](Self::Kinematic) body instead).
    Static,
    /// Moved by its velocity alone (moving platforms, doors, lifts):
    /// infinite mass, so forces, impulses and contacts do not change it;
    /// game code sets its velocity ([`World::set_velocity`], or
    /// [`World::set_kinematic_target`] to reach a position by the next
    /// step). It pushes and carries dynamic bodies (through contact
    /// friction) and is interpolated like them; it does not collide with
    /// static or other kinematic bodies.
    ///
    /// [`World::set_velocity`]: crate::World::set_velocity
    /// [`World::set_kinematic_target`]: crate::World::set_kinematic_target
    Kinematic,
}

/// Everything needed to create a body. Start from [`Default`] and set what
/// differs: `BodyDef { position, ..Default::default() }`.
///
/// ```
/// use passo_physics::{BodyDef, Shape, World, glam::Vec2};
///
/// let mut world = World::default();
/// // The ground: static, 10 m wide, its top at y = 0.
/// world.add_body(BodyDef::new_static(Vec2::new(0.0, -0.5), Shape::rect(10.0, 1.0))).unwrap();
/// // A 2 kg crate, 0.5 m wide, dropped from 1 m, a little slippery.
/// let crate_ = world
///     .add_body(BodyDef {
///         position: Vec2::new(0.0, 1.25),
///         mass: 2.0,
///         shape: Some(Shape::rect(0.5, 0.5)),
///         friction: 0.3,
///         ..Default::default()
///     })
///     .unwrap();
/// for _ in 0..120 {
///     world.step(1.0 / 60.0);
/// }
/// // It rests on the ground, its centre half its height above it.
/// let y = world.body(crate_).unwrap().position.y;
/// assert!((y - 0.25).abs() < 0.006, "at {y}");
///
/// // A body that cannot be is refused with an error, not a panic.
/// assert!(world.add_body(BodyDef { mass: -1.0, ..Default::default() }).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BodyDef {
    /// Dynamic, static or kinematic. Default [`BodyKind::Dynamic`].
    pub kind: BodyKind,
    /// Position of the centre, metres. Default `(0, 0)`.
    pub position: Vec2,
    /// Linear velocity, metres per second. Default `(0, 0)`. Ignored for
    /// static bodies.
    pub velocity: Vec2,
    /// Mass, kilograms, finite and > 0 for a dynamic body. Default 1.
    /// Ignored for static and kinematic bodies (their mass is infinite).
    pub mass: f32,
    /// Collision shape; `None` (the default) makes a point mass that takes
    /// part in no contact.
    pub shape: Option<Shape>,
    /// Drag area `Cd * A`, square metres, >= 0, used by quadratic drag.
    /// Default 0.1 ([`DEFAULT_DRAG_AREA`]).
    pub drag_area: f32,
    /// Kinetic friction coefficient `mu`, >= 0, used by surface friction and
    /// contacts. Default 0.6 ([`DEFAULT_FRICTION`]).
    pub friction: f32,
    /// How this body's friction combines with another's in a contact.
    /// Default [`FrictionMix::GeometricMean`].
    pub friction_mix: FrictionMix,
    /// Restitution (bounciness) in `[0, 1]` used by contacts. Default 0.
    pub restitution: f32,
    /// Which bodies this one may touch. Default: layer 1, touches all.
    pub filter: CollisionFilter,
    /// A sensor reports bodies overlapping its shape (see
    /// [`World::events`](crate::World::events)) but never pushes them.
    /// Default `false`.
    pub sensor: bool,
    /// Makes a static or kinematic body a one-way platform: the outward
    /// normal of its solid side (any finite non-zero vector; `(0, 1)` for a
    /// platform to land on from above). Bodies meeting it from that side
    /// land and stand on it; bodies coming from anywhere else pass through
    /// with their velocity unchanged, and so does a body already partly
    /// inside it. Default `None` (solid from every side).
    pub one_way: Option<Vec2>,
    /// A conveyor belt: the velocity its surface moves at, m/s. What
    /// touches the body is carried along its surface at that speed (within
    /// friction's limit), the body itself staying where it is; the part
    /// along the contact's normal is ignored. Default `None`.
    #[cfg_attr(feature = "serde", serde(default))]
    pub conveyor: Option<Vec2>,
    /// A bullet: a dynamic body swept against every other body when it
    /// moves farther in a step than its speculative contacts reach, so it
    /// never passes through a thin dynamic body either (a projectile
    /// through a crate). Every fast body is swept against static and
    /// kinematic bodies; bullets cost a pass over the bodies each step
    /// they move that fast, so keep them few. Dynamic bodies only. Default
    /// `false`. See
    /// [`SPECULATIVE_REACH`](crate::constants::SPECULATIVE_REACH).
    pub bullet: bool,
    /// How much of the world's gravity acts on the body: 1 all of it (the
    /// default), 0 none (a balloon's cargo, a floating pickup), -1 upward,
    /// 2 twice. Finite, in `[-MAX_GRAVITY_SCALE, MAX_GRAVITY_SCALE]`. Dynamic
    /// bodies only (kinematic and static ones feel no force).
    #[cfg_attr(feature = "serde", serde(default = "one"))]
    pub gravity_scale: f32,
    /// Minimum speed override, metres per second, >= 0; `None` (the default)
    /// uses the world's.
    pub min_speed: Option<f32>,
    /// Maximum speed override, metres per second, > 0 (may be infinite);
    /// `None` (the default) uses the world's.
    pub max_speed: Option<f32>,
    /// Free for the game: an entity id, an index into its own tables.
    /// Default 0.
    pub user_data: u64,
}

impl Default for BodyDef {
    fn default() -> Self {
        Self {
            kind: BodyKind::Dynamic,
            position: Vec2::ZERO,
            velocity: Vec2::ZERO,
            mass: 1.0,
            shape: None,
            drag_area: DEFAULT_DRAG_AREA,
            friction: DEFAULT_FRICTION,
            friction_mix: FrictionMix::GeometricMean,
            restitution: 0.0,
            filter: CollisionFilter::default(),
            sensor: false,
            one_way: None,
            conveyor: None,
            bullet: false,
            gravity_scale: 1.0,
            min_speed: None,
            max_speed: None,
            user_data: 0,
        }
    }
}

impl BodyDef {
    /// A dynamic body of 1 kg at `position` with the given shape, every
    /// other field default.
    pub fn new_dynamic(position: Vec2, shape: Shape) -> Self {
        Self {
            position,
            shape: Some(shape),
            ..Self::default()
        }
    }

    /// A dynamic point mass of 1 kg at `position`: no shape, so it takes
    /// part in no contact (a particle, a projectile under force models).
    pub fn point_mass(position: Vec2) -> Self {
        Self {
            position,
            ..Self::default()
        }
    }

    /// A static body (ground, walls: [`BodyKind::Static`]) at `position`
    /// with the given shape.
    pub fn new_static(position: Vec2, shape: Shape) -> Self {
        Self {
            kind: BodyKind::Static,
            position,
            shape: Some(shape),
            ..Self::default()
        }
    }

    /// A kinematic body (a moving platform) at `position` with the given
    /// shape, moving at `velocity`.
    pub fn new_kinematic(position: Vec2, shape: Shape, velocity: Vec2) -> Self {
        Self {
            kind: BodyKind::Kinematic,
            position,
            velocity,
            shape: Some(shape),
            ..Self::default()
        }
    }

    /// A dynamic point mass of 1 kg at `position`.
    #[deprecated(
        since = "0.1.0",
        note = "makes a point mass with no shape: use `BodyDef::point_mass`, or `BodyDef::new_dynamic` for a body that collides"
    )]
    pub fn dynamic(position: Vec2) -> Self {
        Self::point_mass(position)
    }

    /// A static body at `position` with the given shape.
    #[deprecated(since = "0.1.0", note = "use `BodyDef::new_static`")]
    pub fn fixed(position: Vec2, shape: Shape) -> Self {
        Self::new_static(position, shape)
    }

    /// The same definition with this velocity, metres per second.
    #[must_use]
    pub fn with_velocity(self, velocity: Vec2) -> Self {
        Self { velocity, ..self }
    }

    /// The same definition with this mass, kilograms.
    #[must_use]
    pub fn with_mass(self, mass: f32) -> Self {
        Self { mass, ..self }
    }

    /// The same definition with this friction coefficient and the usual
    /// mixing (see [`FrictionMix`]).
    #[must_use]
    pub fn with_friction(self, friction: f32) -> Self {
        Self { friction, ..self }
    }

    /// The same definition with this friction coefficient and mixing rule
    /// (ice: `with_friction_mix(0.05, FrictionMix::Min)`).
    #[must_use]
    pub fn with_friction_mix(self, friction: f32, friction_mix: FrictionMix) -> Self {
        Self {
            friction,
            friction_mix,
            ..self
        }
    }

    /// The same definition with this restitution, in `[0, 1]`.
    #[must_use]
    pub fn with_restitution(self, restitution: f32) -> Self {
        Self {
            restitution,
            ..self
        }
    }

    /// The same definition with this collision filter.
    #[must_use]
    pub fn with_filter(self, filter: CollisionFilter) -> Self {
        Self { filter, ..self }
    }

    /// The same definition as a sensor (reports overlaps, pushes nothing).
    #[must_use]
    pub fn as_sensor(self) -> Self {
        Self {
            sensor: true,
            ..self
        }
    }

    /// The same definition as a one-way platform, solid from the side
    /// `normal` points to (see [`one_way`](Self::one_way)).
    #[must_use]
    pub fn with_one_way(self, normal: Vec2) -> Self {
        Self {
            one_way: Some(normal),
            ..self
        }
    }

    /// The same definition with this game data.
    #[must_use]
    pub fn with_user_data(self, user_data: u64) -> Self {
        Self { user_data, ..self }
    }

    /// Checks every field, naming the first one that is wrong.
    pub fn validate(&self) -> Result<(), PhysicsError> {
        position("BodyDef::position", self.position)?;
        finite_vec("BodyDef::velocity", self.velocity)?;
        if self.kind == BodyKind::Dynamic {
            mass("BodyDef::mass", self.mass)?;
        }
        if let Some(shape) = &self.shape {
            shape.validate()?;
            if shape.is_level_only() && self.kind == BodyKind::Dynamic {
                return Err(PhysicsError::OutOfRange {
                    what: "BodyDef::shape",
                    value: 0.0,
                    allowed: "a segment, chain segment or polygon only on static and kinematic bodies",
                });
            }
        }
        check_drag_area("BodyDef::drag_area", self.drag_area)?;
        check_gravity_scale("BodyDef::gravity_scale", self.gravity_scale)?;
        if let Some(v) = self.conveyor {
            finite_vec("BodyDef::conveyor", v)?;
        }
        check_friction("BodyDef::friction", self.friction)?;
        unit_interval("BodyDef::restitution", self.restitution)?;
        if let Some(normal) = self.one_way {
            check_one_way("BodyDef::one_way", normal)?;
            if self.kind == BodyKind::Dynamic {
                return Err(PhysicsError::OutOfRange {
                    what: "BodyDef::one_way",
                    value: normal.length(),
                    allowed: "set only on static and kinematic bodies",
                });
            }
        }
        if self.bullet && self.kind != BodyKind::Dynamic {
            return Err(PhysicsError::OutOfRange {
                what: "BodyDef::bullet",
                value: 1.0,
                allowed: "set only on dynamic bodies",
            });
        }
        if let Some(min) = self.min_speed {
            non_negative("BodyDef::min_speed", min)?;
        }
        if let Some(max) = self.max_speed {
            check_max_speed("BodyDef::max_speed", max)?;
        }
        Ok(())
    }
}

/// A friction coefficient: in `[0, MAX_FRICTION]`.
pub(crate) fn check_friction(what: &'static str, mu: f32) -> Result<f32, PhysicsError> {
    at_most(what, mu, MAX_FRICTION, "in [0, 1000] (MAX_FRICTION)")
}

/// A drag area: in `[0, MAX_DRAG_AREA]` square metres.
pub(crate) fn check_drag_area(what: &'static str, area: f32) -> Result<f32, PhysicsError> {
    at_most(what, area, MAX_DRAG_AREA, "in [0, 1e6] m² (MAX_DRAG_AREA)")
}

/// The unit vector along `v`, or `None` for a zero or non-finite `v`.
/// Scaled by its largest component first, so a subnormal vector (whose
/// length rounds to zero) or one whose length overflows still has its
/// direction.
pub(crate) fn unit_direction(v: Vec2) -> Option<Vec2> {
    (v / v.abs().max_element()).try_normalize()
}

/// A one-way normal must be finite and not zero; returns it normalised.
pub(crate) fn check_one_way(what: &'static str, normal: Vec2) -> Result<Vec2, PhysicsError> {
    finite_vec(what, normal)?;
    unit_direction(normal).ok_or(PhysicsError::OutOfRange {
        what,
        value: 0.0,
        allowed: "a non-zero direction",
    })
}

/// A maximum speed must be > 0; infinity (no clamp) is allowed.
pub(crate) fn check_max_speed(what: &'static str, max: f32) -> Result<f32, PhysicsError> {
    if max == f32::INFINITY {
        Ok(max)
    } else {
        positive(what, max)
    }
}

/// A copy of one body's state, as returned by [`World::body`](crate::World::body).
///
/// Change a body through the world's methods (`set_velocity`, `apply_force`,
/// ...), which check their input.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Body {
    /// The body's handle.
    pub id: BodyId,
    /// Dynamic or static.
    pub kind: BodyKind,
    /// Position of the centre, metres.
    pub position: Vec2,
    /// Velocity, metres per second (always zero for static bodies; as set
    /// by game code for kinematic ones).
    pub velocity: Vec2,
    /// Force accumulated since the last step, newtons.
    pub force: Vec2,
    /// Mass, kilograms (`f32::INFINITY` for static and kinematic bodies).
    pub mass: f32,
    /// Collision shape, if any.
    pub shape: Option<Shape>,
    /// Drag area `Cd * A`, square metres.
    pub drag_area: f32,
    /// Friction coefficient.
    pub friction: f32,
    /// How its friction combines with another body's.
    pub friction_mix: FrictionMix,
    /// Restitution in `[0, 1]`.
    pub restitution: f32,
    /// Collision filter.
    pub filter: CollisionFilter,
    /// Whether the body is a sensor.
    pub sensor: bool,
    /// The solid side of a one-way platform (unit), if it is one.
    pub one_way: Option<Vec2>,
    /// Its surface's velocity, if it is a conveyor.
    pub conveyor: Option<Vec2>,
    /// Whether the body is a bullet (see [`BodyDef::bullet`]).
    pub bullet: bool,
    /// Its share of the world's gravity (see [`BodyDef::gravity_scale`]).
    pub gravity_scale: f32,
    /// Minimum speed override, if any.
    pub min_speed: Option<f32>,
    /// Maximum speed override, if any.
    pub max_speed: Option<f32>,
    /// The game's own data.
    pub user_data: u64,
    /// Whether the body sleeps: it rested long enough that the contact
    /// stage stopped solving it (see [`ContactSettings::sleeping`]).
    ///
    /// [`ContactSettings::sleeping`]: crate::ContactSettings::sleeping
    pub asleep: bool,
}

impl Body {
    /// The definition that recreates this body in its current state (the
    /// accumulated force is not part of a definition).
    pub fn to_def(&self) -> BodyDef {
        BodyDef {
            kind: self.kind,
            position: self.position,
            velocity: self.velocity,
            mass: if self.kind == BodyKind::Dynamic {
                self.mass
            } else {
                BodyDef::default().mass
            },
            shape: self.shape,
            drag_area: self.drag_area,
            friction: self.friction,
            friction_mix: self.friction_mix,
            restitution: self.restitution,
            filter: self.filter,
            sensor: self.sensor,
            one_way: self.one_way,
            conveyor: self.conveyor,
            bullet: self.bullet,
            gravity_scale: self.gravity_scale,
            min_speed: self.min_speed,
            max_speed: self.max_speed,
            user_data: self.user_data,
        }
    }
}

/// Serde's default gravity scale.
#[cfg(feature = "serde")]
fn one() -> f32 {
    1.0
}

/// Checks a gravity scale: finite, within `MAX_GRAVITY_SCALE` of zero.
pub(crate) fn check_gravity_scale(what: &'static str, scale: f32) -> Result<f32, PhysicsError> {
    crate::error::finite(what, scale)?;
    if scale.abs() <= crate::constants::MAX_GRAVITY_SCALE {
        Ok(scale)
    } else {
        Err(PhysicsError::OutOfRange {
            what,
            value: scale,
            allowed: "in [-1000, 1000] (MAX_GRAVITY_SCALE)",
        })
    }
}
