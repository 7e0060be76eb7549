//! The packed body arrays the world steps: dynamic bodies in
//! structure-of-arrays form (hot data apart from cold), static bodies, and
//! the small per-body records (metadata, speed limits, sleep state).

use crate::Shape;
use crate::body::collider::ColliderRef;
use crate::body::def::{Body, BodyDef, BodyKind};
use crate::body::filter::CollisionFilter;
use crate::body::material::FrictionMix;
use crate::columns::{Columns, ColumnsMut, ColumnsRef};
use crate::id::BodyId;
use glam::Vec2;

/// `SleepState::island` of an awake body.
const AWAKE: u32 = u32::MAX;

/// How long a dynamic body has rested, and whether it sleeps.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct SleepState {
    /// Seconds the body has been slower than [`SLEEP_SPEED`](crate::constants::SLEEP_SPEED).
    pub rest_time: f32,
    /// The island the body sleeps in (the slot index of one of its bodies),
    /// or [`AWAKE`].
    island: u32,
}

impl SleepState {
    pub(crate) const fn awake() -> Self {
        Self {
            rest_time: 0.0,
            island: AWAKE,
        }
    }

    #[inline(always)]
    pub(crate) fn is_asleep(&self) -> bool {
        self.island != AWAKE
    }

    /// The island the body sleeps in, or `None` while it is awake.
    #[inline(always)]
    pub(crate) fn island(&self) -> Option<u32> {
        self.is_asleep().then_some(self.island)
    }

    /// Puts the body to sleep in `island` (the slot index of one of the
    /// island's bodies).
    pub(crate) fn sleep_in(&mut self, island: u32) {
        debug_assert!(island != AWAKE);
        self.island = island;
    }

    /// Whether the state is one a step can produce (for snapshots).
    pub(crate) fn is_valid(&self) -> bool {
        self.rest_time.is_finite() && self.rest_time >= 0.0
    }
}

/// What the step never touches: kept apart from the hot arrays.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct BodyMeta {
    pub id: BodyId,
    /// A kinematic body in the dynamic arrays (inverse mass 0, moved by
    /// its velocity alone).
    #[cfg_attr(feature = "serde", serde(default))]
    pub kinematic: bool,
    pub mass: f32,
    pub shape: Option<Shape>,
    pub drag_area: f32,
    /// How its friction combines with another body's.
    #[cfg_attr(feature = "serde", serde(default))]
    pub friction_mix: FrictionMix,
    pub restitution: f32,
    pub filter: CollisionFilter,
    pub sensor: bool,
    /// The solid side of a one-way platform (unit).
    #[cfg_attr(feature = "serde", serde(default))]
    pub one_way: Option<Vec2>,
    /// A conveyor's surface velocity (see `BodyDef::conveyor`).
    #[cfg_attr(feature = "serde", serde(default))]
    pub conveyor: Option<Vec2>,
    /// Seconds left in which this body passes through one-way platforms
    /// (see `World::drop_through`).
    #[cfg_attr(feature = "serde", serde(default))]
    pub drop_through: f32,
    /// Swept against every body when it moves fast (see `BodyDef::bullet`).
    #[cfg_attr(feature = "serde", serde(default))]
    pub bullet: bool,
    /// Moved by `World::move_character`: its contacts never push a dynamic
    /// body ahead of it (the mover's own push does), see
    /// `Constraint::new`.
    #[cfg_attr(feature = "serde", serde(default))]
    pub character: bool,
    /// Its share of the world's gravity (see `BodyDef::gravity_scale`).
    #[cfg_attr(feature = "serde", serde(default = "one"))]
    pub gravity_scale: f32,
    pub min_speed: Option<f32>,
    pub max_speed: Option<f32>,
    pub user_data: u64,
}

impl BodyMeta {
    /// The public view of a body from its cold data, at rest: the caller
    /// fills in what the hot arrays hold (velocity, force, drag area,
    /// sleep).
    fn view(&self, kind: BodyKind, position: Vec2, friction: f32) -> Body {
        Body {
            id: self.id,
            kind,
            position,
            velocity: Vec2::ZERO,
            force: Vec2::ZERO,
            mass: self.mass,
            shape: self.shape,
            drag_area: self.drag_area,
            friction,
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
            asleep: false,
        }
    }
}

/// Serde's default gravity scale.
#[cfg(feature = "serde")]
fn one() -> f32 {
    1.0
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
    pub(crate) fn new(min: f32, max: f32) -> Self {
        Self {
            min_sq: min * min,
            max,
            max_sq: (max * max).min(f32::MAX),
        }
    }

    /// Snaps a velocity below the minimum speed to exactly zero and scales
    /// one above the maximum to the maximum speed (`v * max / |v|`). `v`
    /// must have a finite `|v|^2` (see `guard_finite`). Returns whether a
    /// limit acted.
    #[inline(always)]
    pub(crate) fn apply(&self, v: &mut Vec2) -> bool {
        let s2 = v.length_squared();
        let mut acted = false;
        if s2 > self.max_sq {
            *v *= self.max / s2.sqrt();
            acted = true;
        }
        if s2 < self.min_sq {
            *v = Vec2::ZERO;
            acted = true;
        }
        acted
    }
}

/// Dynamic bodies in structure-of-arrays form: the step walks these slices.
/// Positions, velocities and forces are split further into x and y (see
/// [`Columns`]).
///
/// Removal swaps the last body into the hole, so the arrays stay packed.
#[derive(Clone, Debug, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct DynamicBodies {
    pub pos: Columns,
    pub vel: Columns,
    pub force: Columns,
    pub inv_mass: Vec<f32>,
    /// `Cd * A` per body, square metres.
    pub drag_area: Vec<f32>,
    /// `mu` per body.
    pub friction: Vec<f32>,
    /// Friction force magnitude `mu |N|` applied by game code this step, newtons.
    pub friction_force: Vec<f32>,
    pub limits: Vec<SpeedLimits>,
    /// Positions at the start of the last step; empty unless interpolation is on.
    pub prev_pos: Columns,
    /// Rest time and island of each body (see `sleep`).
    pub sleep: Vec<SleepState>,
    pub meta: Vec<BodyMeta>,
    /// Indices of the kinematic bodies among these (derived from `meta`:
    /// not saved, rebuilt on restore).
    #[cfg_attr(feature = "serde", serde(skip))]
    pub kinematic: Vec<u32>,
}

impl PartialEq for DynamicBodies {
    /// The state, not `kinematic`, which is derived from `meta` and not
    /// saved: a snapshot read back from a file (with the list empty) equals
    /// the one written.
    fn eq(&self, other: &Self) -> bool {
        let Self {
            pos,
            vel,
            force,
            inv_mass,
            drag_area,
            friction,
            friction_force,
            limits,
            prev_pos,
            sleep,
            meta,
            kinematic: _,
        } = self;
        *pos == other.pos
            && *vel == other.vel
            && *force == other.force
            && *inv_mass == other.inv_mass
            && *drag_area == other.drag_area
            && *friction == other.friction
            && *friction_force == other.friction_force
            && *limits == other.limits
            && *prev_pos == other.prev_pos
            && *sleep == other.sleep
            && *meta == other.meta
    }
}

/// Per-body values the force models read.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BodyParams {
    pub inv_mass: f32,
    /// Force accumulated by game code this step, newtons.
    pub force: Vec2,
    pub drag_area: f32,
    pub friction: f32,
    /// `mu |N|` applied by game code this step, newtons.
    pub friction_force: f32,
}

/// The arrays a body's forces are computed from, borrowed apart from the
/// positions and velocities that a step writes.
#[derive(Clone, Copy)]
pub(crate) struct BodyArrays<'a> {
    pub force: ColumnsRef<'a>,
    pub inv_mass: &'a [f32],
    pub drag_area: &'a [f32],
    pub friction: &'a [f32],
    pub friction_force: &'a [f32],
    pub limits: &'a [SpeedLimits],
}

impl BodyArrays<'_> {
    /// The arrays of the `n` bodies from `offset` on, indexed from 0 (so
    /// that a loop over `0..n` reads them with no bounds checks).
    pub(crate) fn run(&self, offset: usize, n: usize) -> BodyArrays<'_> {
        let r = offset..offset + n;
        BodyArrays {
            force: self.force.slice(r.clone()),
            inv_mass: &self.inv_mass[r.clone()],
            drag_area: &self.drag_area[r.clone()],
            friction: &self.friction[r.clone()],
            friction_force: &self.friction_force[r.clone()],
            limits: &self.limits[r],
        }
    }

    /// What the force models read for body `i`.
    #[inline(always)]
    pub(crate) fn params(&self, i: usize) -> BodyParams {
        BodyParams {
            inv_mass: self.inv_mass[i],
            force: self.force.at(i),
            drag_area: self.drag_area[i],
            friction: self.friction[i],
            friction_force: self.friction_force[i],
        }
    }
}

impl DynamicBodies {
    pub(crate) fn len(&self) -> usize {
        self.pos.len()
    }

    /// Positions and velocities to write, the rest to read.
    pub(crate) fn split(&mut self) -> (ColumnsMut<'_>, ColumnsMut<'_>, BodyArrays<'_>) {
        (
            self.pos.view_mut(),
            self.vel.view_mut(),
            BodyArrays {
                force: self.force.view(),
                inv_mass: &self.inv_mass,
                drag_area: &self.drag_area,
                friction: &self.friction,
                friction_force: &self.friction_force,
                limits: &self.limits,
            },
        )
    }

    pub(crate) fn push(
        &mut self,
        def: &BodyDef,
        meta: BodyMeta,
        limits: SpeedLimits,
        track_previous: bool,
    ) {
        self.pos.push(def.position);
        self.vel.push(def.velocity);
        self.force.push(Vec2::ZERO);
        if meta.kinematic {
            self.kinematic.push(self.pos.len() as u32 - 1);
        }
        self.inv_mass
            .push(if meta.kinematic { 0.0 } else { 1.0 / def.mass });
        self.drag_area.push(def.drag_area);
        self.friction.push(def.friction);
        self.friction_force.push(0.0);
        self.limits.push(limits);
        if track_previous {
            self.prev_pos.push(def.position);
        }
        self.sleep.push(SleepState::awake());
        self.meta.push(meta);
    }

    /// Removes body `i`; returns the id of the body moved into `i`, if any.
    pub(crate) fn swap_remove(&mut self, i: usize) -> Option<BodyId> {
        if !self.kinematic.is_empty() {
            let last = self.pos.len() as u32 - 1;
            self.kinematic.retain(|&k| k != i as u32);
            for k in &mut self.kinematic {
                if *k == last {
                    *k = i as u32;
                }
            }
        }
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

    /// Makes this a copy of `other`, reusing this one's buffers (no
    /// allocation when they are large enough).
    pub(crate) fn copy_from(&mut self, other: &Self) {
        self.pos.copy_from(&other.pos);
        self.vel.copy_from(&other.vel);
        self.force.copy_from(&other.force);
        self.inv_mass.clone_from(&other.inv_mass);
        self.drag_area.clone_from(&other.drag_area);
        self.friction.clone_from(&other.friction);
        self.friction_force.clone_from(&other.friction_force);
        self.limits.clone_from(&other.limits);
        self.prev_pos.copy_from(&other.prev_pos);
        self.sleep.clone_from(&other.sleep);
        self.meta.clone_from(&other.meta);
        self.kinematic.clone_from(&other.kinematic);
    }

    /// Rebuilds the list of kinematic bodies from their metadata.
    pub(crate) fn find_kinematic(&mut self) {
        self.kinematic.clear();
        let kinematic = self.meta.iter().enumerate().filter(|(_, m)| m.kinematic);
        self.kinematic.extend(kinematic.map(|(i, _)| i as u32));
    }

    /// Wakes every body and forgets how long each rested.
    pub(crate) fn wake_all(&mut self) {
        self.sleep.fill(SleepState::awake());
    }

    /// Whether every body is awake with no rest time.
    pub(crate) fn all_fresh(&self) -> bool {
        self.sleep.iter().all(|s| *s == SleepState::awake())
    }

    pub(crate) fn view(&self, i: usize) -> Body {
        let m = &self.meta[i];
        let kind = if m.kinematic {
            BodyKind::Kinematic
        } else {
            BodyKind::Dynamic
        };
        let mut body = m.view(kind, self.pos.at(i), self.friction[i]);
        body.velocity = self.vel.at(i);
        body.force = self.force.at(i);
        body.drag_area = self.drag_area[i];
        body.asleep = self.sleep[i].is_asleep();
        body
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
    /// Makes this a copy of `other`, reusing this one's buffers.
    pub(crate) fn copy_from(&mut self, other: &Self) {
        self.pos.clone_from(&other.pos);
        self.friction.clone_from(&other.friction);
        self.meta.clone_from(&other.meta);
    }

    pub(crate) fn len(&self) -> usize {
        self.pos.len()
    }

    pub(crate) fn push(&mut self, def: &BodyDef, meta: BodyMeta) {
        self.pos.push(def.position);
        self.friction.push(def.friction);
        self.meta.push(meta);
    }

    pub(crate) fn swap_remove(&mut self, i: usize) -> Option<BodyId> {
        self.pos.swap_remove(i);
        self.friction.swap_remove(i);
        self.meta.swap_remove(i);
        self.meta.get(i).map(|m| m.id)
    }

    pub(crate) fn view(&self, i: usize) -> Body {
        self.meta[i].view(BodyKind::Static, self.pos[i], self.friction[i])
    }
}

/// Both body arrays, read through collider references.
#[derive(Clone, Copy)]
pub(crate) struct Colliders<'a> {
    pub dynamic: &'a DynamicBodies,
    pub statics: &'a StaticBodies,
}

impl<'a> Colliders<'a> {
    /// The body's cold data.
    #[inline(always)]
    pub(crate) fn meta(&self, r: ColliderRef) -> &'a BodyMeta {
        match r.dynamic_index() {
            Some(i) => &self.dynamic.meta[i],
            None => &self.statics.meta[r.index()],
        }
    }

    /// The body's cold data, or `None` if the index is out of range (for
    /// checking snapshots).
    pub(crate) fn get_meta(&self, r: ColliderRef) -> Option<&'a BodyMeta> {
        match r.dynamic_index() {
            Some(i) => self.dynamic.meta.get(i),
            None => self.statics.meta.get(r.index()),
        }
    }

    /// The body's position.
    #[inline(always)]
    pub(crate) fn position(&self, r: ColliderRef) -> Vec2 {
        match r.dynamic_index() {
            Some(i) => self.dynamic.pos.at(i),
            None => self.statics.pos[r.index()],
        }
    }

    /// The shape and position of a body that has a shape.
    ///
    /// # Panics
    /// If the body has no shape: only shaped bodies become colliders.
    pub(crate) fn shape_at(&self, r: ColliderRef) -> (Shape, Vec2) {
        let shape = self.meta(r).shape.expect("a collider has a shape");
        (shape, self.position(r))
    }

    /// The order key of a pair: the two slot indices, lower first, so the
    /// order depends on ids, not on storage.
    #[inline(always)]
    pub(crate) fn pair_order(&self, a: ColliderRef, b: ColliderRef) -> u64 {
        pair_order(self.meta(a).id.index, self.meta(b).id.index)
    }
}

/// The order key of the pair of bodies in slots `x` and `y` (`BodyId`
/// indices): the lower slot first.
#[inline(always)]
pub(crate) fn pair_order(x: u32, y: u32) -> u64 {
    let (x, y) = (u64::from(x), u64::from(y));
    x.min(y) << 32 | x.max(y)
}

/// Bytes a vector holds on the heap.
pub(crate) fn heap<T>(v: &Vec<T>) -> usize {
    v.capacity() * std::mem::size_of::<T>()
}

impl DynamicBodies {
    /// Bytes the arrays hold on the heap.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.pos.heap_bytes()
            + self.vel.heap_bytes()
            + self.force.heap_bytes()
            + heap(&self.inv_mass)
            + heap(&self.drag_area)
            + heap(&self.friction)
            + heap(&self.friction_force)
            + heap(&self.limits)
            + self.prev_pos.heap_bytes()
            + heap(&self.sleep)
            + heap(&self.meta)
            + heap(&self.kinematic)
    }
}

impl StaticBodies {
    /// Bytes the arrays hold on the heap.
    pub(crate) fn heap_bytes(&self) -> usize {
        heap(&self.pos) + heap(&self.friction) + heap(&self.meta)
    }
}
