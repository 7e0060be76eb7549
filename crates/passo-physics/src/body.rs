//! Bodies: the handle, the definition a body is made from, the read-only view
//! the world hands out, and the packed arrays the world steps.

use crate::constants::{DEFAULT_DRAG_AREA, DEFAULT_FRICTION};
use crate::error::{finite_vec, non_negative, positive};
use crate::sleep::SleepState;
use crate::{CollisionFilter, PhysicsError, Shape};
use glam::Vec2;
use std::fmt;

/// A small `Copy` handle to a body in a [`World`](crate::World).
///
/// The handle carries a generation: when a body is removed its slot's
/// generation is bumped, so an old id never reaches the body that reuses the
/// slot; lookups with it return `None`.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BodyId {
    pub(crate) index: u32,
    pub(crate) generation: u32,
}

impl BodyId {
    /// The slot index (stable while the body lives; reused after removal).
    pub fn index(self) -> u32 {
        self.index
    }

    /// The slot generation (bumped each time the slot is freed).
    pub fn generation(self) -> u32 {
        self.generation
    }
}

impl fmt::Debug for BodyId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "BodyId({}v{})", self.index, self.generation)
    }
}

/// Whether a body moves.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum BodyKind {
    /// Moved by forces, impulses and contacts. Has a finite mass.
    #[default]
    Dynamic,
    /// Never moves (ground, walls): infinite mass, zero velocity. Forces and
    /// impulses on it are ignored; its position can still be set by hand.
    Static,
}

/// Everything needed to create a body. Start from [`Default`] and set what
/// differs: `BodyDef { position, ..Default::default() }`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BodyDef {
    /// Dynamic or static. Default [`BodyKind::Dynamic`].
    pub kind: BodyKind,
    /// Position of the centre, metres. Default `(0, 0)`.
    pub position: Vec2,
    /// Linear velocity, metres per second. Default `(0, 0)`. Ignored for
    /// static bodies.
    pub velocity: Vec2,
    /// Mass, kilograms, finite and > 0 for a dynamic body. Default 1.
    /// Ignored for static bodies (their mass is infinite).
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
    /// Restitution (bounciness) in `[0, 1]` used by contacts. Default 0.
    pub restitution: f32,
    /// Which bodies this one may touch. Default: layer 1, touches all.
    pub filter: CollisionFilter,
    /// A sensor reports bodies overlapping its shape (see
    /// [`World::events`](crate::World::events)) but never pushes them.
    /// Default `false`.
    pub sensor: bool,
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
            restitution: 0.0,
            filter: CollisionFilter::default(),
            sensor: false,
            min_speed: None,
            max_speed: None,
            user_data: 0,
        }
    }
}

impl BodyDef {
    /// A dynamic body of 1 kg at `position`, every other field default.
    pub fn dynamic(position: Vec2) -> Self {
        Self {
            position,
            ..Self::default()
        }
    }

    /// A static body at `position` with the given shape.
    pub fn fixed(position: Vec2, shape: Shape) -> Self {
        Self {
            kind: BodyKind::Static,
            position,
            shape: Some(shape),
            ..Self::default()
        }
    }

    /// Checks every field, naming the first one that is wrong.
    pub fn validate(&self) -> Result<(), PhysicsError> {
        finite_vec("BodyDef::position", self.position)?;
        finite_vec("BodyDef::velocity", self.velocity)?;
        if self.kind == BodyKind::Dynamic {
            positive("BodyDef::mass", self.mass)?;
        }
        if let Some(shape) = &self.shape {
            shape.validate()?;
        }
        non_negative("BodyDef::drag_area", self.drag_area)?;
        non_negative("BodyDef::friction", self.friction)?;
        non_negative("BodyDef::restitution", self.restitution)?;
        if self.restitution > 1.0 {
            return Err(PhysicsError::OutOfRange {
                what: "BodyDef::restitution",
                value: self.restitution,
                allowed: "in [0, 1]",
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
    /// Velocity, metres per second (always zero for static bodies).
    pub velocity: Vec2,
    /// Force accumulated since the last step, newtons.
    pub force: Vec2,
    /// Mass, kilograms (`f32::INFINITY` for static bodies).
    pub mass: f32,
    /// Collision shape, if any.
    pub shape: Option<Shape>,
    /// Drag area `Cd * A`, square metres.
    pub drag_area: f32,
    /// Friction coefficient.
    pub friction: f32,
    /// Restitution in `[0, 1]`.
    pub restitution: f32,
    /// Collision filter.
    pub filter: CollisionFilter,
    /// Whether the body is a sensor.
    pub sensor: bool,
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
            restitution: self.restitution,
            filter: self.filter,
            sensor: self.sensor,
            min_speed: self.min_speed,
            max_speed: self.max_speed,
            user_data: self.user_data,
        }
    }
}

/// What the step never touches: kept apart from the hot arrays.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct BodyMeta {
    pub id: BodyId,
    pub mass: f32,
    pub shape: Option<Shape>,
    pub drag_area: f32,
    pub restitution: f32,
    pub filter: CollisionFilter,
    pub sensor: bool,
    pub min_speed: Option<f32>,
    pub max_speed: Option<f32>,
    pub user_data: u64,
}

/// Flushes velocity components smaller than the smallest normal `f32`
/// (1.2e-38 m/s) to zero. A component that decays under drag while the
/// other does not (the horizontal speed of a body falling at terminal
/// speed) would otherwise become a subnormal float and stay one, and
/// arithmetic on subnormals makes the whole step several times slower.
#[inline(always)]
pub(crate) fn flush_subnormal(v: Vec2) -> Vec2 {
    Vec2::select(v.abs().cmplt(Vec2::splat(f32::MIN_POSITIVE)), Vec2::ZERO, v)
}

/// Speed limits of one body, resolved from its overrides and the world's
/// defaults (`max_sq` is at most `f32::MAX`).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct SpeedLimits {
    pub min_sq: f32,
    pub max: f32,
    pub max_sq: f32,
}

impl SpeedLimits {
    pub fn new(min: f32, max: f32) -> Self {
        Self {
            min_sq: min * min,
            max,
            max_sq: (max * max).min(f32::MAX),
        }
    }

    /// Snaps a velocity below the minimum speed to exactly zero and scales
    /// one above the maximum to the maximum speed (`v * max / |v|`). `v`
    /// must have a finite `|v|^2` (see `guard_finite`).
    #[inline(always)]
    pub fn apply(&self, v: &mut Vec2) {
        let s2 = v.length_squared();
        if s2 > self.max_sq {
            *v *= self.max / s2.sqrt();
        }
        if s2 < self.min_sq {
            *v = Vec2::ZERO;
        }
    }
}

/// Dynamic bodies in structure-of-arrays form: the step walks these slices.
///
/// Removal swaps the last body into the hole, so the arrays stay packed.
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct DynamicBodies {
    pub pos: Vec<Vec2>,
    pub vel: Vec<Vec2>,
    pub force: Vec<Vec2>,
    pub inv_mass: Vec<f32>,
    /// `Cd * A` per body, square metres.
    pub drag_area: Vec<f32>,
    /// `mu` per body.
    pub friction: Vec<f32>,
    /// Friction force magnitude `mu |N|` applied by game code this step, newtons.
    pub friction_force: Vec<f32>,
    pub limits: Vec<SpeedLimits>,
    /// Positions at the start of the last step; empty unless interpolation is on.
    pub prev_pos: Vec<Vec2>,
    /// Rest time and island of each body (see `sleep`).
    pub sleep: Vec<SleepState>,
    pub meta: Vec<BodyMeta>,
}

/// The arrays a body's forces are computed from, borrowed apart from the
/// positions and velocities that a step writes.
pub(crate) struct BodyArrays<'a> {
    pub force: &'a [Vec2],
    pub inv_mass: &'a [f32],
    pub drag_area: &'a [f32],
    pub friction: &'a [f32],
    pub friction_force: &'a [f32],
    pub limits: &'a [SpeedLimits],
}

impl BodyArrays<'_> {
    /// What the force models read for body `i`.
    #[inline(always)]
    pub fn params(&self, i: usize) -> crate::forces::BodyParams {
        crate::forces::BodyParams {
            inv_mass: self.inv_mass[i],
            force: self.force[i],
            drag_area: self.drag_area[i],
            friction: self.friction[i],
            friction_force: self.friction_force[i],
        }
    }
}

impl DynamicBodies {
    pub fn len(&self) -> usize {
        self.pos.len()
    }

    /// Positions and velocities to write, the rest to read.
    pub fn split(&mut self) -> (&mut [Vec2], &mut [Vec2], BodyArrays<'_>) {
        (
            &mut self.pos,
            &mut self.vel,
            BodyArrays {
                force: &self.force,
                inv_mass: &self.inv_mass,
                drag_area: &self.drag_area,
                friction: &self.friction,
                friction_force: &self.friction_force,
                limits: &self.limits,
            },
        )
    }

    pub fn push(&mut self, def: &BodyDef, meta: BodyMeta, limits: SpeedLimits, keep_prev: bool) {
        self.pos.push(def.position);
        self.vel.push(def.velocity);
        self.force.push(Vec2::ZERO);
        self.inv_mass.push(1.0 / def.mass);
        self.drag_area.push(def.drag_area);
        self.friction.push(def.friction);
        self.friction_force.push(0.0);
        self.limits.push(limits);
        if keep_prev {
            self.prev_pos.push(def.position);
        }
        self.sleep.push(SleepState::awake());
        self.meta.push(meta);
    }

    /// Removes body `i`; returns the id of the body moved into `i`, if any.
    pub fn swap_remove(&mut self, i: usize) -> Option<BodyId> {
        self.pos.swap_remove(i);
        self.vel.swap_remove(i);
        self.force.swap_remove(i);
        self.inv_mass.swap_remove(i);
        self.drag_area.swap_remove(i);
        self.friction.swap_remove(i);
        self.friction_force.swap_remove(i);
        self.limits.swap_remove(i);
        if !self.prev_pos.is_empty() {
            self.prev_pos.swap_remove(i);
        }
        self.sleep.swap_remove(i);
        self.meta.swap_remove(i);
        self.meta.get(i).map(|m| m.id)
    }

    pub fn view(&self, i: usize) -> Body {
        let m = &self.meta[i];
        Body {
            id: m.id,
            kind: BodyKind::Dynamic,
            position: self.pos[i],
            velocity: self.vel[i],
            force: self.force[i],
            mass: m.mass,
            shape: m.shape,
            drag_area: self.drag_area[i],
            friction: self.friction[i],
            restitution: m.restitution,
            filter: m.filter,
            sensor: m.sensor,
            min_speed: m.min_speed,
            max_speed: m.max_speed,
            user_data: m.user_data,
            asleep: self.sleep[i].is_asleep(),
        }
    }
}

/// Static bodies: never integrated.
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct StaticBodies {
    pub pos: Vec<Vec2>,
    pub friction: Vec<f32>,
    pub meta: Vec<BodyMeta>,
}

impl StaticBodies {
    pub fn len(&self) -> usize {
        self.pos.len()
    }

    pub fn push(&mut self, def: &BodyDef, meta: BodyMeta) {
        self.pos.push(def.position);
        self.friction.push(def.friction);
        self.meta.push(meta);
    }

    pub fn swap_remove(&mut self, i: usize) -> Option<BodyId> {
        self.pos.swap_remove(i);
        self.friction.swap_remove(i);
        self.meta.swap_remove(i);
        self.meta.get(i).map(|m| m.id)
    }

    pub fn view(&self, i: usize) -> Body {
        let m = &self.meta[i];
        Body {
            id: m.id,
            kind: BodyKind::Static,
            position: self.pos[i],
            velocity: Vec2::ZERO,
            force: Vec2::ZERO,
            mass: f32::INFINITY,
            shape: m.shape,
            drag_area: m.drag_area,
            friction: self.friction[i],
            restitution: m.restitution,
            filter: m.filter,
            sensor: m.sensor,
            min_speed: m.min_speed,
            max_speed: m.max_speed,
            user_data: m.user_data,
            asleep: false,
        }
    }
}
