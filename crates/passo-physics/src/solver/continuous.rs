//! Continuous collision beyond the speculative reach: fast bodies swept
//! along their paths and stopped at their first impact.
//!
//! Speculative contacts stop a body at any static or kinematic body it can
//! reach this step in any direction, and at a dynamic body it heads for,
//! but they are looked for only up to its reach ([`SPECULATIVE_REACH`]
//! times its smallest half extent), so the pairs of a scene stay bounded at
//! any speed and any step. A body that moved farther than its contacts
//! covered, and farther than its own smallest half extent (less could not
//! carry it past anything), is swept along its path:
//! - against static and kinematic bodies, each with its own motion this
//!   step;
//! - as a bullet ([`BodyDef::bullet`](crate::BodyDef::bullet)), then
//!   against every dynamic body too, fast ones included, each on the path
//!   the first pass left it (a target stopped by a wall carries the bullet
//!   no farther than the wall).
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
//! Every sweep of a pass reads the positions at the start of the step and
//! the displacements as the pass found them, and no body is moved until
//! the pass is done, so the result does not depend on the order of the
//! bodies. A body that moved beyond its reach is also looked for in the
//! sensors where it ended (the narrow phase could not pair it with them).
//!
//! [`SPECULATIVE_REACH`]: crate::constants::SPECULATIVE_REACH

use crate::SensorPair;
use crate::Shape;
use crate::body::collider::ColliderRef;
use crate::body::store::{BodyMeta, DynamicBodies, StaticBodies};
use crate::collision::narrow_phase::SensorCandidate;
use crate::collision::proxies::{NO_PROXY, Proxies, ProxyMargin};
use crate::constants::LINEAR_SLOP;
use crate::geometry::aabb::Aabb;
use crate::geometry::cast::cast_shape;
use crate::geometry::manifold::Faces;
use crate::parallel::for_chunks_max;
use crate::solver::motion::Motion;
use glam::Vec2;

/// The sweeps of one step, with their buffers kept between steps.
#[derive(Clone, Debug, Default)]
pub(crate) struct Sweeps {
    /// Bodies to move back, with their displacement this step.
    stops: Vec<(u32, Vec2)>,
    /// Fast bullets, for the second pass.
    bullets: Vec<u32>,
    /// Bodies that moved farther than their contacts reached this step
    /// (their sensor overlaps are looked for at their final places).
    far: Vec<u32>,
    /// The dynamic and kinematic sensors (scratch).
    moving_sensors: Vec<u32>,
}

/// How far the contacts of the body with proxy `p` ([`NO_PROXY`]: none)
/// reached this step: its proxy's margin beyond a static body's.
#[inline(always)]
fn covered(proxies: &Proxies, p: u32) -> f32 {
    if p == NO_PROXY {
        0.0
    } else {
        ProxyMargin::reached(proxies.margins[p as usize])
    }
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
    /// back those that hit something, in two passes: every fast body
    /// against static and kinematic bodies, then fast bullets against the
    /// dynamic bodies on the paths the first pass left them. Returns how
    /// many stops were made. `parallel`: check the bodies' travel in chunks
    /// on the pool (see `for_chunks`).
    pub(crate) fn run(
        &mut self,
        dynamic: &mut DynamicBodies,
        statics: &StaticBodies,
        proxies: &Proxies,
        motion: &mut Motion,
        parallel: bool,
    ) -> usize {
        self.stops.clear();
        self.bullets.clear();
        self.far.clear();
        // Most steps no body moves beyond its reach: that is checked first,
        // in chunks on the pool when `parallel`, and the bodies are walked
        // one by one only if one did.
        let beyond = for_chunks_max(
            parallel,
            (&motion.delta[..], &proxies.of_body[..]),
            |(delta, proxy)| {
                // As `fast_body` tests it (a NaN distance is not within).
                let within = |(d, &p): (&Vec2, &u32)| d.length() <= covered(proxies, p);
                u64::from(!delta.iter().zip(proxy).all(within))
            },
        );
        if beyond == 0 {
            return 0;
        }
        let bodies = &*dynamic;
        for i in 0..bodies.len() {
            let Some(mover) = self.fast_body(i, bodies, proxies, motion) else {
                continue;
            };
            if let Some(hit) = first_impact(&mover, bodies, statics, proxies, motion) {
                self.stops.push((i as u32, hit.displacement(&mover)));
            }
            if mover.meta.bullet {
                self.bullets.push(i as u32);
            }
        }
        let mut stopped = self.apply(dynamic, motion);
        let bodies = &*dynamic;
        for &i in &self.bullets {
            let i = i as usize;
            // Along the path the first pass left it.
            let mover = mover_of(bodies, i, motion);
            if let Some(hit) = bullet_impact(&mover, i, bodies, motion) {
                self.stops.push((i as u32, hit.displacement(&mover)));
            }
        }
        stopped += self.apply(dynamic, motion);
        stopped
    }

    /// Body `i` as a mover if it moved farther this step than its contacts
    /// reached and than its own smallest half extent (less could not carry
    /// it past anything); notes it in `far` if it moved farther than its
    /// contacts reached.
    fn fast_body<'a>(
        &mut self,
        i: usize,
        bodies: &'a DynamicBodies,
        proxies: &Proxies,
        motion: &Motion,
    ) -> Option<Mover<'a>> {
        // The distance first: most bodies stay within their reach, and the
        // arrays it reads are small, where the body's cold data is not.
        let covered = proxies.of_body.get(i).map_or(0.0, |&p| covered(proxies, p));
        let distance = motion.delta[i].length();
        if distance <= covered {
            return None;
        }
        let meta = &bodies.meta[i];
        let shape = meta.shape?;
        if meta.kinematic || meta.sensor || bodies.sleep[i].is_asleep() {
            return None;
        }
        self.far.push(i as u32);
        // (A body moving exactly its half extent passes nothing either;
        // sweeping it too would only change where it stops, short of
        // what it meets.)
        (distance > shape.half_extents().min_element()).then(|| mover_of(bodies, i, motion))
    }

    /// Sensor candidates for the bodies that moved farther than their
    /// contacts reached (the narrow phase did not pair them with what lies
    /// beyond): every sensor whose box around its path this step overlaps
    /// the box around theirs, each from where it was at the step's start
    /// (`start`; a static sensor stays put) to where it ended.
    pub(crate) fn far_sensor_candidates(
        &mut self,
        dynamic: &DynamicBodies,
        statics: &StaticBodies,
        proxies: &Proxies,
        start: &[Vec2],
        out: &mut Vec<SensorCandidate>,
    ) {
        if self.far.is_empty() {
            return;
        }
        self.moving_sensors.clear();
        let sensors = (0..dynamic.len() as u32).filter(|&k| dynamic.meta[k as usize].sensor);
        self.moving_sensors.extend(sensors);
        let box_of = |shape: &Shape, at: Vec2| Aabb::from_centre(at, shape.half_extents());
        // The box around dynamic body `i`'s path this step.
        let path_of = |shape: &Shape, i: usize| {
            let end = box_of(shape, dynamic.pos.at(i));
            start
                .get(i)
                .map_or(end, |&from| end.union(&box_of(shape, from)))
        };
        for &i in &self.far {
            let i = i as usize;
            let visitor = &dynamic.meta[i];
            let Some(shape) = visitor.shape else { continue };
            let area = path_of(&shape, i);
            let mut meet = |sensor: &BodyMeta, at: ColliderRef| {
                if sensor.filter.allows(&visitor.filter) {
                    out.push(SensorCandidate {
                        pair: SensorPair {
                            sensor: sensor.id,
                            visitor: visitor.id,
                        },
                        sensor: at,
                        visitor: ColliderRef::dynamic(i as u32),
                    });
                }
            };
            proxies.statics_in(&area, |s| {
                let meta = &statics.meta[s as usize];
                if meta.sensor {
                    meet(meta, ColliderRef::fixed(s));
                }
            });
            for &k in &self.moving_sensors {
                let k = k as usize;
                let meta = &dynamic.meta[k];
                let Some(sensor_shape) = meta.shape else {
                    continue;
                };
                // The box around the sensor's own path too.
                if path_of(&sensor_shape, k).overlaps(&area) {
                    meet(meta, ColliderRef::dynamic(k as u32));
                }
            }
        }
    }

    /// Moves the stopped bodies; returns how many there were.
    fn apply(&mut self, dynamic: &mut DynamicBodies, motion: &mut Motion) -> usize {
        for &(i, displacement) in &self.stops {
            let i = i as usize;
            motion.delta[i] = displacement;
            dynamic.pos.set(i, motion.start[i] + displacement);
        }
        let n = self.stops.len();
        self.stops.clear();
        n
    }
}

/// Shaped body `i` as a mover along its displacement this step.
fn mover_of<'a>(bodies: &'a DynamicBodies, i: usize, motion: &Motion) -> Mover<'a> {
    let meta = &bodies.meta[i];
    let shape = meta.shape.expect("a swept body has a shape");
    Mover {
        shape,
        core: shrunk(shape),
        start: motion.start[i],
        travel: motion.delta[i],
        meta,
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

/// Keeps the earliest of the impacts it is given.
#[derive(Default)]
struct Earliest(Option<Impact>);

impl Earliest {
    fn meet(&mut self, fraction: Option<f32>, carried: Vec2) {
        // (Of two impacts at the same fraction the first met is kept; `<=`
        // would keep the last, which differs only if the two targets met
        // at the same instant move differently.)
        if let Some(fraction) = fraction
            && self.0.is_none_or(|f| fraction < f.fraction)
        {
            self.0 = Some(Impact { fraction, carried });
        }
    }
}

/// The first impact of `mover` with a static or kinematic body, each on
/// its own path this step; `None` if it hits none.
fn first_impact(
    mover: &Mover<'_>,
    bodies: &DynamicBodies,
    statics: &StaticBodies,
    proxies: &Proxies,
    motion: &Motion,
) -> Option<Impact> {
    let mut first = Earliest::default();
    let swept = swept_box(&mover.shape, mover.start, mover.travel);
    proxies.statics_in(&swept, |s| {
        let (meta, pos) = (&statics.meta[s as usize], statics.pos[s as usize]);
        let faces = proxies.covered_faces(ColliderRef::fixed(s));
        first.meet(impact(mover, meta, pos, Vec2::ZERO, faces), Vec2::ZERO);
    });
    for &k in &bodies.kinematic {
        let k = k as usize;
        let faces = proxies.covered_faces(ColliderRef::dynamic(k as u32));
        let (start, travel) = (motion.start[k], motion.delta[k]);
        first.meet(impact(mover, &bodies.meta[k], start, travel, faces), travel);
    }
    first.0
}

/// The first impact of bullet `mover` (body `i`) with another dynamic
/// body, each on the path the first pass left it (so a target stopped by
/// a wall carries the bullet no farther than the wall); `None` if none.
/// A pass over every body: bullets are meant to be few.
fn bullet_impact(
    mover: &Mover<'_>,
    i: usize,
    bodies: &DynamicBodies,
    motion: &Motion,
) -> Option<Impact> {
    let mut first = Earliest::default();
    let swept = swept_box(&mover.shape, mover.start, mover.travel);
    for j in 0..bodies.len() {
        let meta = &bodies.meta[j];
        let Some(shape) = meta.shape else { continue };
        // (A kinematic body was met in the first pass: the path that pass
        // left stops short of it, so meeting it again finds nothing. The
        // bullet's own body, met at the start, is no impact either.)
        if j == i || meta.kinematic {
            continue;
        }
        // The cheap test first: do the two swept boxes meet at all?
        let (start, travel) = (motion.start[j], motion.delta[j]);
        if swept.overlaps(&swept_box(&shape, start, travel)) {
            first.meet(impact(mover, meta, start, travel, Faces::default()), travel);
        }
    }
    first.0
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
        Shape::Capsule {
            half_segment,
            radius,
        } => Shape::Capsule {
            half_segment,
            radius: by(radius),
        },
        // Lines and polygons are never swept (they are static or
        // kinematic).
        level @ (Shape::Segment { .. } | Shape::ChainSegment { .. } | Shape::Polygon(_)) => level,
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
