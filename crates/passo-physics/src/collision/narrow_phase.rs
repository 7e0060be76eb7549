//! The narrow phase: exact geometry for each candidate pair, in a fixed
//! order. A pair becomes a contact row (touching, or speculative: close
//! enough to touch within the step), a sensor candidate, or nothing.

use crate::body::collider::ColliderRef;
use crate::body::filter::CollisionFilter;
use crate::body::store::{Colliders, pair_order};
use crate::collision::pair_sort::{KeyedPair, sort_by_key};
use crate::collision::proxies::{Proxies, ProxyMargin};
use crate::collision::reuse::{Reuse, reuse_all};
use crate::constants::{ONE_WAY_DEPTH, SPECULATIVE_DISTANCE};
use crate::contact::constraint::{Constraint, ContactInfo, ContactList, key};
use crate::geometry::corners::{beyond_corner, over_a_step};
use crate::geometry::manifold::{Faces, Manifold, collide_seamless};
use crate::parallel::for_chunks_max;
use crate::switches::TestSwitches;
use crate::{BodyId, SensorPair, Shape};
use glam::Vec2;

/// A sensor and a body that may be inside it at the end of the step.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SensorCandidate {
    pub pair: SensorPair,
    pub sensor: ColliderRef,
    pub visitor: ColliderRef,
}

/// What the narrow phase makes of one candidate pair.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Outcome {
    /// Filtered out, or too far apart.
    Skip,
    /// A sensor and a body that may end the step inside it.
    Sensor(SensorCandidate),
    /// A contact to solve.
    Contact(Constraint, ContactInfo),
}

/// A collider as the narrow phase sees it.
#[derive(Clone, Copy)]
struct Collider {
    shape: Shape,
    body: ColliderRef,
    id: BodyId,
    sensor: bool,
    filter: CollisionFilter,
    /// Static or kinematic: contacts and forces do not move it.
    immovable: bool,
    /// The solid side of a one-way platform.
    one_way: Option<Vec2>,
    /// Passes through one-way platforms for now.
    dropping: bool,
}

/// What the narrow phase reads (shared by the threads that run it).
pub(crate) struct PairContext<'a> {
    pub proxies: &'a Proxies,
    pub bodies: Colliders<'a>,
    /// Gravitational acceleration (for restitution's impact speed).
    pub gravity: Vec2,
    /// The substep, seconds.
    pub h: f32,
    /// How deep contacts let bodies sink, metres: steps no higher are
    /// climbed (see [`over_a_step`]).
    pub slop: f32,
    /// Whether a pair (by its contact's [`key`]) pressed on each other at the
    /// end of the last step: a body standing on a one-way platform stays
    /// on it, however deep a load presses it in (see
    /// [`PairContext::one_way_allows`]).
    pub pressed: &'a (dyn Fn((BodyId, BodyId)) -> bool + Sync),
}

impl PairContext<'_> {
    fn collider(&self, body: ColliderRef) -> Collider {
        let meta = self.bodies.meta(body);
        Collider {
            shape: meta.shape.expect("a collider has a shape"),
            body,
            id: meta.id,
            sensor: meta.sensor,
            filter: meta.filter,
            immovable: body.is_static() || meta.kinematic,
            one_way: meta.one_way,
            dropping: meta.drop_through > 0.0,
        }
    }

    /// The body behind a pair end (a proxy or a static body).
    pub(crate) fn body_of(&self, end: ColliderRef) -> ColliderRef {
        match end.dynamic_index() {
            Some(p) => ColliderRef::dynamic(self.proxies.body[p]),
            None => end,
        }
    }

    /// The order key of a candidate pair.
    /// (From the proxies' slots, not the bodies' cold data: one small
    /// array instead of a cache line a body.)
    pub(crate) fn key(&self, pa: u32, pb: ColliderRef) -> KeyedPair {
        let slot = &self.proxies.slot;
        let b = match pb.dynamic_index() {
            Some(q) => slot[q],
            None => self.bodies.meta(pb).id.index,
        };
        (pair_order(slot[pa as usize], b), pa, pb)
    }

    /// The contact (or sensor candidate) of proxy `pa` with `pb`.
    ///
    /// Inlined, with [`Constraint::new`], into the loops over the pairs:
    /// the outcome (a hundred bytes) is then built where it is kept instead
    /// of being returned through memory and copied (BENCHMARKS.md, "Why the
    /// code is shaped this way", has the timing).
    #[inline(always)]
    pub(crate) fn pair(&self, pa: u32, pb: ColliderRef) -> Outcome {
        let margins = &self.proxies.margins;
        let a_body = ColliderRef::dynamic(self.proxies.body[pa as usize]);
        let (margin_a, margin_b) = (
            margins[pa as usize],
            pb.dynamic_index()
                .map_or(ProxyMargin::STATIC, |q| margins[q]),
        );
        let (ca, cb) = (self.collider(a_body), self.collider(self.body_of(pb)));
        if !ca.filter.allows(&cb.filter) || (ca.sensor && cb.sensor) {
            return Outcome::Skip;
        }
        // Kinematic bodies meet only dynamic ones (sensors see them all).
        if ca.immovable && cb.immovable && !(ca.sensor || cb.sensor) {
            return Outcome::Skip;
        }
        if ca.sensor || cb.sensor {
            let (s, v) = if ca.sensor { (ca, cb) } else { (cb, ca) };
            return Outcome::Sensor(SensorCandidate {
                pair: SensorPair {
                    sensor: s.id,
                    visitor: v.id,
                },
                sensor: s.body,
                visitor: v.body,
            });
        }
        // A static or kinematic body is always B (two of them never meet);
        // otherwise the lower id is A, so a contact's orientation does not
        // depend on storage order.
        let ((ca, margin_a), (cb, margin_b)) =
            if cb.immovable || (!ca.immovable && ca.id.index() <= cb.id.index()) {
                ((ca, margin_a), (cb, margin_b))
            } else {
                ((cb, margin_b), (ca, margin_a))
            };
        let position = |c: &Collider| self.bodies.position(c.body);
        // Seamless ground: B's faces that a neighbour covers.
        let faces = if cb.immovable {
            self.proxies.covered_faces(cb.body)
        } else {
            Faces::default()
        };
        let (pa, pb) = (position(&ca), position(&cb));
        let found = collide_seamless(&ca.shape, pa, &cb.shape, pb, margin_a + margin_b, faces);
        // A step no higher than the slop: the face the body climbs onto;
        // beyond each other's corner: the face the motion meets first.
        let found = found.map(|m| {
            let closing = || self.step_velocity(&cb) - self.step_velocity(&ca);
            let dt = self.proxies.margin.dt;
            let (sa, sb) = (&ca.shape, &cb.shape);
            over_a_step(sa, pa, sb, pb, closing, self.slop, faces)
                .or_else(|| beyond_corner(sa, pa, sb, pb, closing, dt, faces))
                .unwrap_or(m)
        });
        match found {
            Some(m) if !self.may_close(&ca, margin_a, &cb, margin_b, &m) => Outcome::Skip,
            Some(m) if !self.one_way_allows(&ca, &cb, &m) => Outcome::Skip,
            Some(mut m) => {
                // Two dynamic bodies on exactly the same spot (spawned
                // there) have no direction between them; each pair gets its
                // own, so a pile spreads out in every direction, not along
                // one line.
                let same_spot = pa == pb && !cb.immovable;
                if same_spot {
                    m.normal = spread_direction(ca.id, cb.id);
                }
                // A body level with a static or kinematic one's centre has
                // no side to leave by along y either; the tie gave +y, from
                // A to B, which pushed A down and out through the bottom.
                // It leaves upwards (unless B's top is covered).
                if cb.immovable && pa.y == pb.y && m.normal == Vec2::Y && !faces.covers(Vec2::Y) {
                    m.normal = Vec2::NEG_Y;
                }
                let a = ca.body.index() as u32;
                let (row, mut info) =
                    Constraint::new(&m, a, cb.body, self.bodies, self.gravity, self.h);
                // What a later step may keep as it is: not a pair whose
                // result hangs on game input or a body's history (a one-way
                // platform, a body dropping through one, a kinematic body's
                // press, a bounce), nor two bodies on one spot. The face a
                // step or a corner picked by the closing velocity (see
                // `over_a_step`, `beyond_corner`) is kept with the rest, as
                // far as the reuse distance.
                let kinematic = cb.immovable && !cb.body.is_static();
                info.anchor = pb - pa;
                info.reusable = info.restitution == 0.0
                    && !(kinematic || same_spot || ca.dropping || cb.dropping)
                    && ca.one_way.is_none()
                    && cb.one_way.is_none();
                Outcome::Contact(row, info)
            }
            None => Outcome::Skip,
        }
    }
}

impl PairContext<'_> {
    /// How fast `c` may move this step: a dynamic body's velocity with
    /// what gravity adds over the step, a kinematic body's own, a static
    /// body's zero.
    fn step_velocity(&self, c: &Collider) -> Vec2 {
        match c.body.dynamic_index() {
            Some(i) if c.immovable => self.bodies.dynamic.vel.at(i),
            Some(i) => self.bodies.dynamic.vel.at(i) + self.gravity * self.proxies.margin.dt,
            None => Vec2::ZERO,
        }
    }

    /// Whether a contact with a one-way platform holds: it comes from the
    /// platform's solid side (the normal from the platform to the other
    /// body has a positive part along the solid side's normal), the other
    /// body is not dropping through, and either it is no deeper in the
    /// platform than [`ONE_WAY_DEPTH`], or it was no deeper before its
    /// motion over the last step (it fell in faster than its contacts
    /// reach, with continuous collision off), or it pressed on the
    /// platform at the end of the last step (it stood on it, and a load
    /// pressed it in). A body inside deeper than that was coming through
    /// (from below, or dropping through) and goes on through. A pair
    /// without a one-way platform always holds.
    fn one_way_allows(&self, a: &Collider, b: &Collider, m: &Manifold) -> bool {
        // `m.normal` points from A to B.
        let (platform, other, solid, away) = match (a.one_way, b.one_way) {
            (_, Some(n)) => (b, a, n, -m.normal),
            (Some(n), None) => (a, b, n, m.normal),
            (None, None) => return true,
        };
        if away.dot(solid) <= 0.0 || other.dropping {
            return false;
        }
        let depth = -m.separation;
        if depth <= ONE_WAY_DEPTH {
            return true;
        }
        let vel = |c: &Collider| {
            c.body
                .dynamic_index()
                .map_or(Vec2::ZERO, |i| self.bodies.dynamic.vel.at(i))
        };
        let sank = -(vel(other) - vel(platform)).dot(solid) * self.proxies.margin.dt;
        depth - sank <= ONE_WAY_DEPTH || (self.pressed)(key(a.id, b.id))
    }

    /// Whether the gap of `m` between `a` and `b` (with proxy margins
    /// `margin_a` and `margin_b`) may close within the step: a contact is
    /// kept within [`SPECULATIVE_DISTANCE`], or as far as the two bodies
    /// can move towards each other along the normal, each at its speed
    /// now plus what gravity adds this step, and neither farther than its
    /// margin. Two bodies falling side by side have no gap to close, and
    /// would otherwise make a contact that never acts (the margins count
    /// each body's speed in any direction). Either body may be stopped in
    /// the step: each one's own speed counts, not the difference. A body
    /// turned by a contact during the step meets another awake dynamic
    /// body it was not heading for at the next step.
    #[inline(always)]
    fn may_close(
        &self,
        a: &Collider,
        margin_a: f32,
        b: &Collider,
        margin_b: f32,
        m: &Manifold,
    ) -> bool {
        // A static or kinematic B (always B when there is one), or a body
        // asleep (held still this step), is met whichever way a contact
        // turns the other during the step, as far as its margin reaches: a
        // thin wall stops a body that glances off something on its way.
        let asleep = |c: &Collider| {
            c.body
                .dynamic_index()
                .is_some_and(|i| self.bodies.dynamic.sleep[i].is_asleep())
        };
        if m.separation <= SPECULATIVE_DISTANCE || b.immovable || asleep(a) || asleep(b) {
            return true;
        }
        let margin = self.proxies.margin;
        let vel = |c: &Collider| {
            c.body
                .dynamic_index()
                .map_or(Vec2::ZERO, |i| self.bodies.dynamic.vel.at(i))
        };
        // A body that may travel beyond its reach (fast, or a long step)
        // may be turned far from where it was heading: as far as it
        // reaches, in every direction.
        if margin.beyond_reach(vel(a), &a.shape) || margin.beyond_reach(vel(b), &b.shape) {
            return true;
        }
        let ProxyMargin { fall, dt, .. } = margin;
        // (A longer reach, `+ dt` or `/ dt` for `* dt`, keeps contacts that
        // never act: it changes only the work, and the bits through the
        // order the solver meets contacts in.)
        let travel = |speed: f32, margin: f32| {
            ((speed.max(0.0) + fall) * dt).min(ProxyMargin::reached(margin))
        };
        let reach =
            travel(vel(a).dot(m.normal), margin_a) + travel(-vel(b).dot(m.normal), margin_b);
        m.separation <= SPECULATIVE_DISTANCE + reach
    }
}

/// The contact of pair `(key, pa, pb)`: kept from the last step (`reuse`,
/// walked at `next`), or found afresh.
#[inline(always)]
fn outcome(
    narrow: &PairContext<'_>,
    reuse: &Reuse<'_>,
    next: &mut usize,
    (key, pa, pb): KeyedPair,
) -> Outcome {
    if reuse.distance_sq > 0.0
        && let Some((row, info)) = reuse.kept(narrow.bodies, next, key)
    {
        return Outcome::Contact(row, info);
    }
    narrow.pair(pa, pb)
}

/// A unit direction of its own for the pair of bodies `a` and `b`, from an
/// integer hash of their ids (arithmetic only, so every platform gives the
/// same bits).
fn spread_direction(a: BodyId, b: BodyId) -> Vec2 {
    let mut h = u64::from(a.index()) << 32 | u64::from(b.index());
    loop {
        // SplitMix64.
        h = h.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = h;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        let unit = |bits: u64| (bits & 0xFF_FFFF) as f32 / 8_388_608.0 - 1.0;
        let v = Vec2::new(unit(z), unit(z >> 32));
        let len_sq = v.length_squared();
        if len_sq > 0.01 && len_sq <= 1.0 {
            return v / len_sq.sqrt();
        }
    }
}

/// The narrow phase's buffers, kept between steps.
#[derive(Clone, Debug, Default)]
pub(crate) struct NarrowPhase {
    /// Candidate pairs in key order: `last_keys` sorted.
    keyed: Vec<KeyedPair>,
    /// This step's keyed pairs in the broad phase's order, before the sort.
    keys: Vec<KeyedPair>,
    /// The last step's, which `keyed` holds sorted: a pile at rest finds
    /// the same pairs in the same order step after step, and skips the
    /// sort.
    last_keys: Vec<KeyedPair>,
    /// The pairs found again when sleeping bodies wake (see
    /// `ContactWorld::wake_reached`).
    pub woken: Vec<KeyedPair>,
    /// Runs that sorted their pairs (see `StepCounters`).
    pub(crate) pair_sorts: u64,
    /// Runs that reused every contact in place.
    pub(crate) contacts_reused_in_place: u64,
    /// The shortcuts turned off (`walk_always`).
    pub(crate) switches: TestSwitches,
    /// The proxies' slots the last keys were made with.
    last_slots: Vec<u32>,
    /// The sort's other buffer.
    scratch: Vec<KeyedPair>,
    /// The sort's counters, one a slot.
    counts: Vec<u32>,
    /// What each task found, when the pairs are split across threads.
    #[cfg(feature = "parallel")]
    tasks: Vec<TaskFound>,
    /// Sensor-visitor pairs close enough to overlap by the end of the step.
    pub sensor_candidates: Vec<SensorCandidate>,
}

impl NarrowPhase {
    /// Runs the narrow phase over the proxies' pairs: contacts go to
    /// `contacts` in key order, sensor candidates to `sensor_candidates`.
    /// The last step's contacts (`last`) are kept where they may be (see
    /// [`Reuse`], within the reuse distance, squared here); `last` is left
    /// holding a buffer for the next step's turn.
    ///
    /// The order is fixed by the pair's body ids. Sorting the small keyed
    /// pairs (not the contacts) keeps this cheap, and the contacts come out
    /// sorted for the warm-start merge. Each pair's outcome depends on that
    /// pair alone, so the pairs can be split across threads. When every
    /// pair keeps its contact (a pile at rest), the last step's list is
    /// made this step's in place: the same contacts as the walk below would
    /// copy out one by one, at a third of the cost; with `impulses` they
    /// keep their impulses too (see [`reuse_all`]). Returns whether the
    /// contacts were kept in place.
    pub(crate) fn run(
        &mut self,
        narrow: &PairContext<'_>,
        (reuse_distance_sq, impulses): (f32, bool),
        last: &mut ContactList,
        parallel: bool,
        contacts: &mut ContactList,
    ) -> bool {
        self.sort_pairs(narrow, parallel);
        self.sensor_candidates.clear();
        let keys = self.keyed.iter().map(|k| k.0);
        let in_place = reuse_distance_sq > 0.0 && !self.switches.walk_always;
        if in_place && reuse_all(narrow.bodies, keys, (reuse_distance_sq, impulses), last) {
            std::mem::swap(contacts, last);
            self.contacts_reused_in_place += 1;
            return true;
        }
        let reuse = Reuse {
            last,
            distance_sq: reuse_distance_sq,
        };
        self.find_contacts(narrow, &reuse, parallel, contacts);
        false
    }

    /// The proxies' pairs with their keys, in key order, in `keyed`.
    fn sort_pairs(&mut self, narrow: &PairContext<'_>, parallel: bool) {
        let proxies = narrow.proxies;
        // The same pairs as the last step's, of the same bodies: the same
        // keys, which `last_keys` holds and `keyed` holds sorted: a pile
        // at rest need not make them again. (With `!=`, a body pooled into
        // a removed one's place keeps the old keys: they only order the
        // pairs and match kept contacts, by dynamic index, so nothing
        // shows; `contact_reuse.rs` pools one.)
        if proxies.pairs_same && proxies.slot == self.last_slots {
            #[cfg(test)]
            debug_assert_eq!(self.last_keys, self.keys_of(narrow));
            return;
        }
        self.last_slots.clone_from(&proxies.slot);
        // The keys, and the highest slot in them (for the sort).
        let (pairs, statics) = (proxies.pairs.len(), proxies.static_pairs.len());
        // Every key is written below: the list is only sized (clearing it
        // first wrote each entry twice, on one thread).
        self.keys
            .resize(pairs + statics, (0, 0, ColliderRef::fixed(0)));
        let (dynamic_keys, static_keys) = self.keys.split_at_mut(pairs);
        let highest = for_chunks_max(
            parallel,
            (dynamic_keys, &proxies.pairs[..]),
            |(keys, pairs)| {
                key_all(keys, pairs, |&(a, b)| {
                    narrow.key(a, ColliderRef::dynamic(b))
                })
            },
        )
        .max(for_chunks_max(
            parallel,
            (static_keys, &proxies.static_pairs[..]),
            |(keys, pairs)| key_all(keys, pairs, |&(p, s)| narrow.key(p, ColliderRef::fixed(s))),
        ));
        // The same keys in the same order as the last step's: `keyed` holds
        // them sorted already.
        if self.keys != self.last_keys {
            self.pair_sorts += 1;
            self.keyed.clone_from(&self.keys);
            let slots = highest as usize + 1;
            sort_by_key(
                &mut self.keyed,
                slots,
                &mut self.scratch,
                &mut self.counts,
                parallel,
            );
        }
        std::mem::swap(&mut self.keys, &mut self.last_keys);
    }

    /// The keys of the proxies' pairs, made afresh (for tests).
    #[cfg(test)]
    fn keys_of(&self, narrow: &PairContext<'_>) -> Vec<KeyedPair> {
        let proxies = narrow.proxies;
        let dynamic = proxies
            .pairs
            .iter()
            .map(|&(a, b)| narrow.key(a, ColliderRef::dynamic(b)));
        let statics = proxies
            .static_pairs
            .iter()
            .map(|&(p, s)| narrow.key(p, ColliderRef::fixed(s)));
        dynamic.chain(statics).collect()
    }

    /// Each pair of `keyed` through the exact geometry, or kept from the
    /// last step (`reuse`).
    fn find_contacts(
        &mut self,
        narrow: &PairContext<'_>,
        reuse: &Reuse<'_>,
        parallel: bool,
        contacts: &mut ContactList,
    ) {
        #[cfg(feature = "parallel")]
        if crate::parallel::goes_parallel(parallel, self.keyed.len()) {
            let (keyed, tasks) = (&self.keyed, &mut self.tasks);
            return in_tasks(
                narrow,
                reuse,
                keyed,
                tasks,
                contacts,
                &mut self.sensor_candidates,
            );
        }
        // On one thread each outcome goes straight to its list: no buffer
        // of outcomes (a hundred bytes a pair) to fill and read back.
        let _ = parallel;
        contacts.clear();
        let mut next = 0;
        for &pair in &self.keyed {
            let outcome = outcome(narrow, reuse, &mut next, pair);
            record_outcome(outcome, contacts, &mut self.sensor_candidates);
        }
    }
}

/// Writes each pair's key (`key`) to `keys` and returns the highest slot in
/// them.
#[inline(always)]
fn key_all(
    keys: &mut [KeyedPair],
    pairs: &[(u32, u32)],
    key: impl Fn(&(u32, u32)) -> KeyedPair,
) -> u64 {
    let mut highest = 0;
    for (k, pair) in keys.iter_mut().zip(pairs) {
        *k = key(pair);
        // (A larger bound, from `|` or `^`, only picks the sort for many
        // slots: the same order.)
        highest = highest.max(k.0 & 0xFFFF_FFFF);
    }
    highest
}

/// Puts a pair's outcome in its list.
#[inline(always)]
fn record_outcome(
    outcome: Outcome,
    contacts: &mut ContactList,
    sensors: &mut Vec<SensorCandidate>,
) {
    match outcome {
        Outcome::Skip => {}
        Outcome::Sensor(candidate) => sensors.push(candidate),
        Outcome::Contact(row, info) => contacts.push(row, info),
    }
}

/// The contacts and sensor candidates one task of the narrow phase found,
/// in the order of its pairs.
#[cfg(feature = "parallel")]
#[derive(Clone, Debug, Default)]
struct TaskFound {
    contacts: ContactList,
    sensors: Vec<SensorCandidate>,
}

/// The narrow phase over `keyed` on rayon's pool, in runs of
/// `PARALLEL_CHUNK` pairs: each task keeps what it finds in its own lists,
/// then, once the lists' lengths give each task its place, copies its
/// contacts into `contacts` side by side with the others. The contacts
/// come out in the pairs' order, as on one thread; no thread reads what
/// another wrote but for the (rare) sensor candidates.
///
/// `contacts` is resized, not cleared and refilled: rows kept from the
/// last step are overwritten, and only the growth is initialised.
#[cfg(feature = "parallel")]
fn in_tasks(
    narrow: &PairContext<'_>,
    reuse: &Reuse<'_>,
    keyed: &[KeyedPair],
    tasks: &mut Vec<TaskFound>,
    contacts: &mut ContactList,
    sensors: &mut Vec<SensorCandidate>,
) {
    use rayon::prelude::*;
    let chunk = crate::constants::PARALLEL_CHUNK;
    let count = keyed.len().div_ceil(chunk);
    // (`<=` resizes to the length it has: nothing.)
    if tasks.len() < count {
        tasks.resize_with(count, TaskFound::default);
    }
    let tasks = &mut tasks[..count];
    tasks
        .par_iter_mut()
        .zip(keyed.par_chunks(chunk))
        .for_each(|(task, pairs)| {
            task.contacts.clear();
            task.sensors.clear();
            let mut next = pairs.first().map_or(0, |&(key, _, _)| reuse.start(key));
            for &pair in pairs {
                let outcome = outcome(narrow, reuse, &mut next, pair);
                record_outcome(outcome, &mut task.contacts, &mut task.sensors);
            }
        });
    for t in tasks.iter() {
        sensors.extend_from_slice(&t.sensors);
    }
    let total: usize = tasks.iter().map(|t| t.contacts.len()).sum();
    let Some(filler) = tasks.iter().find_map(|t| t.contacts.iter().next()) else {
        contacts.clear();
        return;
    };
    let (row, info) = (*filler.0, *filler.1);
    contacts.rows.resize(total, row);
    contacts.infos.resize(total, info);
    copy_into(tasks, &mut contacts.rows, &mut contacts.infos);
}

/// Copies the tasks' contacts, in order, into `rows` and `infos` (as long
/// as all of them): halves of the tasks into halves of the lists, on
/// rayon's pool.
#[cfg(feature = "parallel")]
fn copy_into(tasks: &[TaskFound], rows: &mut [Constraint], infos: &mut [ContactInfo]) {
    if let [task] = tasks {
        rows.copy_from_slice(&task.contacts.rows);
        infos.copy_from_slice(&task.contacts.infos);
        return;
    }
    let (first, second) = tasks.split_at(tasks.len() / 2);
    let n = first.iter().map(|t| t.contacts.len()).sum();
    let (rows_first, rows_second) = rows.split_at_mut(n);
    let (infos_first, infos_second) = infos.split_at_mut(n);
    rayon::join(
        || copy_into(first, rows_first, infos_first),
        || copy_into(second, rows_second, infos_second),
    );
}

#[cfg(test)]
mod tests;
