//! Continuous collision beyond the speculative reach: fast bodies swept
//! along their paths and stopped at their first impact.
//!
//! Speculative contacts stop a body at anything it can reach this step,
//! but they are looked for only up to its reach ([`SPECULATIVE_REACH`]
//! times its smallest half extent), so the pairs of a scene stay bounded at
//! any speed and any step. A body that moved farther than its contacts
//! covered, and farther than its own smallest half extent (less could not
//! carry it past anything), is swept along its path:
//! - against static and kinematic bodies, each with its own motion this
//!   step;
//! - as a bullet ([`BodyDef::bullet`](crate::BodyDef::bullet)), against
//!   every dynamic body too, fast ones included.
//!
//! Shapes do not rotate, so each sweep is exact ([`cast_shape`]). The body
//! is put back to just before its first impact with its velocity kept: at
//! the next step the obstacle lies within its reach, and a contact stops
//! it. This is what Box2D v3 does with its fast bodies and bullets.
//!
//! What is no impact:
//! - a path whose core (the shape shrunk by the slop) never meets the
//!   target, so a body sliding fast along the ground it sits in, or
//!   grazing a corner, is not stopped;
//! - a hit through a face a flush neighbour covers (seamless ground);
//! - a one-way platform met from anywhere but its solid side, or by a
//!   body dropping through;
//! - a target the core already overlaps at the start (the contacts deal
//!   with it).
//!
//! Every sweep reads the positions at the start of the step and the
//! displacements of the substeps, and no body is moved until all are done,
//! so the result does not depend on the order of the bodies.
//!
//! [`SPECULATIVE_REACH`]: crate::constants::SPECULATIVE_REACH

use crate::Shape;
use crate::aabb::Aabb;
use crate::bodies::{BodyMeta, DynamicBodies, StaticBodies};
use crate::cast::cast_shape;
use crate::collider::ColliderRef;
use crate::constants::LINEAR_SLOP;
use crate::manifold::Faces;
use crate::proxies::{NO_PROXY, Proxies, ProxyMargin};
use crate::solver::Motion;
use glam::Vec2;

/// The sweeps of one step, with their buffer kept between steps.
#[derive(Clone, Debug, Default)]
pub(crate) struct Sweeps {
    /// Bodies to move back, with their displacement this step.
    stops: Vec<(u32, Vec2)>,
}

/// A body being swept.
struct Mover<'a> {
    shape: Shape,
    /// The shape shrunk by the slop.
    core: Shape,
    start: Vec2,
    travel: Vec2,
    meta: &'a BodyMeta,
}

impl Sweeps {
    /// Sweeps every body that moved beyond its reach this step and moves
    /// back those that hit something. Returns how many were stopped.
    pub(crate) fn run(
        &mut self,
        dynamic: &mut DynamicBodies,
        statics: &StaticBodies,
        proxies: &Proxies,
        motion: &mut Motion,
    ) -> usize {
        self.stops.clear();
        let bodies = &*dynamic;
        for i in 0..bodies.len() {
            let meta = &bodies.meta[i];
            let Some(shape) = meta.shape else { continue };
            if meta.kinematic || meta.sensor || bodies.sleep[i].is_asleep() {
                continue;
            }
            let travel = motion.delta[i];
            let covered = match proxies.of_body.get(i) {
                Some(&p) if p != NO_PROXY => proxies.margins[p as usize] - ProxyMargin::STATIC,
                _ => 0.0,
            };
            let distance = travel.length();
            if distance <= covered.max(shape.half_extents().min_element()) {
                continue;
            }
            let mover = Mover {
                shape,
                core: shrunk(shape),
                start: motion.start[i],
                travel,
                meta,
            };
            if let Some(hit) = first_impact(&mover, i, bodies, statics, proxies, motion) {
                self.stops.push((i as u32, hit.displacement(&mover)));
            }
        }
        for &(i, displacement) in &self.stops {
            let i = i as usize;
            motion.delta[i] = displacement;
            dynamic.pos[i] = motion.start[i] + displacement;
        }
        self.stops.len()
    }
}

/// The first impact of a swept body.
#[derive(Clone, Copy, Debug)]
struct Impact {
    /// How far along the travel (relative to the target's) it happens.
    fraction: f32,
    /// The target's travel this step.
    carried: Vec2,
}

impl Impact {
    /// The mover's displacement this step: to the impact, then carried
    /// along with the target for the rest of the step, so it ends where
    /// it met the target, seen from the target's final place. Backed off
    /// by the slop, it ends a little short of the target, within the next
    /// step's speculative distance.
    fn displacement(&self, mover: &Mover<'_>) -> Vec2 {
        let relative = (mover.travel - self.carried).length();
        let t = (self.fraction - LINEAR_SLOP / relative).max(0.0);
        mover.travel * t + self.carried * (1.0 - t)
    }
}

/// The first impact of `mover` (body `i`) with a static or kinematic body,
/// or as a bullet with any body; `None` if it hits nothing.
fn first_impact(
    mover: &Mover<'_>,
    i: usize,
    bodies: &DynamicBodies,
    statics: &StaticBodies,
    proxies: &Proxies,
    motion: &Motion,
) -> Option<Impact> {
    let mut first: Option<Impact> = None;
    let mut meet = |fraction: Option<f32>, carried: Vec2| {
        if let Some(fraction) = fraction
            && first.is_none_or(|f| fraction < f.fraction)
        {
            first = Some(Impact { fraction, carried });
        }
    };
    let swept = swept_box(&mover.shape, mover.start, mover.travel);
    proxies.statics_in(&swept, |s| {
        let (meta, pos) = (&statics.meta[s as usize], statics.pos[s as usize]);
        let faces = proxies.covered_faces(ColliderRef::fixed(s));
        meet(impact(mover, meta, pos, Vec2::ZERO, faces), Vec2::ZERO);
    });
    for &k in &bodies.kinematic {
        let k = k as usize;
        let faces = proxies.covered_faces(ColliderRef::dynamic(k as u32));
        let (start, travel) = (motion.start[k], motion.delta[k]);
        meet(impact(mover, &bodies.meta[k], start, travel, faces), travel);
    }
    if mover.meta.bullet {
        for j in 0..bodies.len() {
            let meta = &bodies.meta[j];
            let Some(shape) = meta.shape else { continue };
            if j == i || meta.kinematic {
                continue;
            }
            // The cheap test first: do the two swept boxes meet at all?
            if !swept.overlaps(&swept_box(&shape, motion.start[j], motion.delta[j])) {
                continue;
            }
            let (start, travel) = (motion.start[j], motion.delta[j]);
            meet(impact(mover, meta, start, travel, Faces::default()), travel);
        }
    }
    first
}

/// The fraction of `mover`'s travel at which it first hits the body of
/// `meta`, which starts at `pos` and moves by `travel` this step (both
/// move in straight lines, so this is one sweep of the relative motion).
fn impact(
    mover: &Mover<'_>,
    meta: &BodyMeta,
    pos: Vec2,
    travel: Vec2,
    faces: Faces,
) -> Option<f32> {
    let target = meta.shape?;
    if meta.sensor || !mover.meta.filter.allows(&meta.filter) {
        return None;
    }
    let relative = mover.travel - travel;
    let core = cast_shape(&mover.core, mover.start, relative, &target, pos)?;
    if core.fraction == 0.0 || faces.covers(core.normal) {
        return None;
    }
    if let Some(solid) = meta.one_way
        && (core.normal.dot(solid) <= 0.0 || mover.meta.drop_through > 0.0)
    {
        return None;
    }
    // Where the whole shape first touches, on the way to the core's hit.
    let hit = cast_shape(&mover.shape, mover.start, relative, &target, pos);
    Some(hit.map_or(core.fraction, |h| h.fraction))
}

/// `shape` shrunk by the slop (by at most half its size).
fn shrunk(shape: Shape) -> Shape {
    let by = |size: f32| (size - LINEAR_SLOP).max(0.5 * size);
    match shape {
        Shape::Circle { radius } => Shape::Circle { radius: by(radius) },
        Shape::Box { half_extents } => Shape::Box {
            half_extents: Vec2::new(by(half_extents.x), by(half_extents.y)),
        },
    }
}

/// The box `shape` sweeps moving from `start` by `travel`.
fn swept_box(shape: &Shape, start: Vec2, travel: Vec2) -> Aabb {
    let half = shape.half_extents();
    let a = Aabb::from_centre(start, half);
    let b = Aabb::from_centre(start + travel, half);
    Aabb {
        min: a.min.min(b.min),
        max: a.max.max(b.max),
    }
}
