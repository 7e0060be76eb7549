//! What a step hands to the next and tells the game: the impulses each
//! contact carries (warm starting), who touched whom (begin and end
//! events) and who is inside which sensor.

use crate::body::collider::ColliderRef;
use crate::body::store::{Colliders, DynamicBodies, StaticBodies, pair_order};
use crate::collision::narrow_phase::SensorCandidate;
use crate::contact::constraint::{Constraint, ContactInfo, ContactList};
use crate::geometry::cast::cast_shape;
use crate::geometry::manifold::collide;
use crate::parallel::{for_chunks, goes_parallel};
use crate::{BodyId, ContactEvents, ContactPair, SensorPair};
use glam::Vec2;

/// Impulses a contact carries to the next step.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Cached {
    key: (BodyId, BodyId),
    normal_impulse: f32,
    tangent_impulse: f32,
    /// The push out of overlap (split impulse) of the last substep.
    #[cfg_attr(feature = "serde", serde(default))]
    push_impulse: f32,
}

impl Cached {
    /// Whether the impulses are ones a step can produce (for snapshots):
    /// finite, and the normal and push impulses never negative.
    pub(crate) fn is_valid(&self) -> bool {
        self.normal_impulse.is_finite()
            && self.normal_impulse >= 0.0
            && self.tangent_impulse.is_finite()
            && self.push_impulse.is_finite()
            && self.push_impulse >= 0.0
    }

    /// The pair's order key.
    pub(crate) fn key(&self) -> (BodyId, BodyId) {
        self.key
    }

    /// The pair's slots as one integer, in the key's order.
    #[inline(always)]
    pub(crate) fn order(&self) -> u64 {
        u64::from(self.key.0.index) << 32 | u64::from(self.key.1.index)
    }
}

/// The contact state carried from one step to the next, and the events of
/// the last step.
#[derive(Clone, Debug, Default)]
pub(crate) struct EventTracker {
    /// Impulses by pair after the last step, sorted by pair.
    pub cache: Vec<Cached>,
    touching: Vec<(BodyId, BodyId)>,
    /// Touching pairs after the last step, sorted.
    pub touching_prev: Vec<(BodyId, BodyId)>,
    sensors: Vec<SensorPair>,
    /// Sensor overlaps after the last step, sorted.
    pub sensors_prev: Vec<SensorPair>,
    /// Bodies that went into a sensor and out again within this step.
    crossed: Vec<SensorPair>,
    /// Events of the last step.
    pub events: ContactEvents,
    /// Whether each awake contact's row still carries the impulses its
    /// entry in `cache` has: set when the cache is recorded from the rows,
    /// cleared when an entry is changed alone ([`forget_impulses`](Self::forget_impulses))
    /// or a state is restored. A step that keeps every contact in place
    /// then keeps their impulses and needs no warm start.
    pub fresh: bool,
}

impl EventTracker {
    /// Gives each contact the impulses its pair had after the last step;
    /// the cache and the contacts are both sorted by key. In chunks on the
    /// thread pool when `parallel` and the contacts are many: each chunk
    /// finds where it starts in the cache, and each contact's impulses
    /// depend on its pair alone.
    pub(crate) fn warm_start(&self, contacts: &mut ContactList, parallel: bool) {
        debug_assert!(contacts.infos.is_sorted_by_key(ContactInfo::key));
        let cache = &self.cache[..];
        let parts = (&mut contacts.rows[..], &contacts.infos[..]);
        for_chunks(parallel, parts, |offset, (rows, infos)| {
            let from = match (offset, infos.first()) {
                (0, _) | (_, None) => 0,
                (_, Some(first)) => {
                    let order = info_order(first);
                    cache.partition_point(|c| c.order() < order)
                }
            };
            warm_start_from(&cache[from..], rows, infos);
            0
        });
    }

    /// Where the pair `key` is in the cache, if it is.
    fn cached_at(&self, key: (BodyId, BodyId)) -> Option<usize> {
        let order = pair_order(key.0.index, key.1.index);
        let at = self.cache.partition_point(|c| c.order() < order);
        self.cache.get(at).filter(|c| c.key == key).map(|_| at)
    }

    /// Sets to zero the impulses the pair `key` warm starts the next step
    /// with (none if it has none).
    pub(crate) fn forget_impulses(&mut self, key: (BodyId, BodyId)) {
        self.fresh = false;
        if let Some(at) = self.cached_at(key) {
            let c = &mut self.cache[at];
            (c.normal_impulse, c.tangent_impulse, c.push_impulse) = (0.0, 0.0, 0.0);
        }
    }

    /// Whether the pair `key` pressed on each other at the end of the last
    /// step (its contact left a normal or push impulse).
    pub(crate) fn pressed(&self, key: (BodyId, BodyId)) -> bool {
        self.cached_at(key).is_some_and(|at| {
            let c = &self.cache[at];
            c.normal_impulse > 0.0 || c.push_impulse > 0.0
        })
    }

    /// Finds which candidates end the step inside their sensor, and which
    /// went in and out again within the step: the visitor's path from
    /// where it was at the start of the step (`start`, per dynamic body) to
    /// where it ended, relative to the sensor's, overlapped the sensor.
    /// Bodies in a sensor stay awake, so it keeps seeing them.
    pub(crate) fn find_sensor_overlaps(
        &mut self,
        candidates: &[SensorCandidate],
        dynamic: &mut DynamicBodies,
        statics: &StaticBodies,
        start: &[Vec2],
    ) {
        self.sensors.clear();
        self.crossed.clear();
        for c in candidates {
            let view = Colliders { dynamic, statics };
            let (shape_s, pos_s) = view.shape_at(c.sensor);
            let (shape_v, pos_v) = view.shape_at(c.visitor);
            if collide(&shape_s, pos_s, &shape_v, pos_v, 0.0).is_some_and(|m| m.separation < 0.0) {
                self.sensors.push(c.pair);
                for body in [c.sensor, c.visitor] {
                    if let Some(i) = body.dynamic_index() {
                        dynamic.sleep[i].rest_time = 0.0;
                    }
                }
                continue;
            }
            if self.sensors_prev.binary_search(&c.pair).is_ok() {
                continue; // it was inside: leaving is an end event
            }
            let was = |body: ColliderRef, now: Vec2| {
                body.dynamic_index()
                    .and_then(|i| start.get(i).copied())
                    .unwrap_or(now)
            };
            // The sensor held where it ended, the visitor moved by the
            // difference of their displacements.
            let from = was(c.visitor, pos_v) + (pos_s - was(c.sensor, pos_s));
            if cast_shape(&shape_v, from, pos_v - from, &shape_s, pos_s).is_some() {
                self.crossed.push(c.pair);
            }
        }
    }

    /// After the last substep: caches every contact's impulses for warm
    /// starting, and works out which pairs began and ended touching and
    /// which bodies entered and left sensors. `solved` and `asleep` are
    /// each sorted by key. With `parallel`, many contacts and none asleep,
    /// the cache is filled in chunks on the thread pool.
    pub(crate) fn record(
        &mut self,
        solved: &ContactList,
        asleep: &ContactList,
        step: u64,
        parallel: bool,
    ) {
        if asleep.is_empty() && goes_parallel(parallel, solved.len()) {
            self.record_pairs_in_chunks(solved);
        } else {
            self.record_pairs(solved, asleep);
        }
        self.fresh = true;
        self.events.clear();
        self.events.step = step;
        let events = &mut self.events;
        diff(&self.touching_prev, &self.touching, |k, began| {
            let pair = ContactPair { a: k.0, b: k.1 };
            if began {
                events.begin.push(pair);
            } else {
                events.end.push(pair);
            }
        });
        std::mem::swap(&mut self.touching, &mut self.touching_prev);
        self.sensors.sort_unstable();
        self.sensors.dedup();
        diff(&self.sensors_prev, &self.sensors, |&pair, began| {
            if began {
                events.sensor_begin.push(pair);
            } else {
                events.sensor_end.push(pair);
            }
        });
        if !self.crossed.is_empty() {
            // In and out within the step: both events, in pair order with
            // the others.
            self.crossed.sort_unstable();
            self.crossed.dedup();
            for list in [&mut events.sensor_begin, &mut events.sensor_end] {
                list.extend_from_slice(&self.crossed);
                list.sort_unstable();
            }
        }
        std::mem::swap(&mut self.sensors, &mut self.sensors_prev);
    }

    /// The cache and the touching pairs of `solved` and `asleep`, one
    /// contact after the other. Every pair is written to `touching` and
    /// only those touching are kept: no branch on whether each one touches,
    /// which changes from contact to contact.
    ///
    /// The lists keep their length from the last step, so only their
    /// growth is initialised.
    fn record_pairs(&mut self, solved: &ContactList, asleep: &ContactList) {
        let len = solved.len() + asleep.len();
        self.cache.resize(len, NO_CACHED);
        self.touching.resize(len, NO_PAIR);
        let mut slots = self.cache.iter_mut();
        let pairs = &mut self.touching[..];
        let mut touching = 0;
        let mut record = |c: &Constraint, info: &ContactInfo| {
            let key = info.key();
            if let Some(slot) = slots.next() {
                *slot = cached(key, c);
            }
            // At most one pair a contact so far: in bounds.
            if let Some(pair) = pairs.get_mut(touching) {
                *pair = key;
            }
            touching += usize::from(info.is_touching(c));
        };
        if asleep.is_empty() {
            solved.iter().for_each(|(c, info)| record(c, info));
        } else {
            merged(solved, asleep).for_each(|(c, info)| record(c, info));
        }
        self.touching.truncate(touching);
    }

    /// [`record_pairs`](Self::record_pairs) of `solved` alone, in chunks on the thread
    /// pool: each contact's entries depend on it alone, a pair not touching
    /// is written as [`NO_PAIR`], and those are taken out after. The lists
    /// keep their length from the last step, so only their growth is
    /// initialised.
    fn record_pairs_in_chunks(&mut self, solved: &ContactList) {
        self.cache.resize(solved.len(), NO_CACHED);
        self.touching.resize(solved.len(), NO_PAIR);
        let parts = (
            &mut self.cache[..],
            &mut self.touching[..],
            &solved.rows[..],
            &solved.infos[..],
        );
        for_chunks(true, parts, |_, (cache, touching, rows, infos)| {
            for (k, (c, info)) in rows.iter().zip(infos).enumerate() {
                let key = info.key();
                cache[k] = cached(key, c);
                touching[k] = if info.is_touching(c) { key } else { NO_PAIR };
            }
            0
        });
        self.touching.retain(|&pair| pair != NO_PAIR);
    }
}

/// A pair of no bodies: the slots no body has.
const NO_PAIR: (BodyId, BodyId) = {
    let none = BodyId {
        index: u32::MAX,
        generation: u32::MAX,
    };
    (none, none)
};

/// The cache entry of no pair, to grow the cache with.
const NO_CACHED: Cached = Cached {
    key: NO_PAIR,
    normal_impulse: 0.0,
    tangent_impulse: 0.0,
    push_impulse: 0.0,
};

/// What contact `c` of pair `key` carries to the next step.
#[inline(always)]
fn cached(key: (BodyId, BodyId), c: &Constraint) -> Cached {
    Cached {
        key,
        normal_impulse: c.normal_impulse,
        tangent_impulse: c.tangent_impulse,
        push_impulse: c.push_impulse,
    }
}

/// The pair's slots as one integer, lower slot first: the order of
/// [`Cached::order`].
#[inline(always)]
fn info_order(info: &ContactInfo) -> u64 {
    pair_order(info.id_a.index, info.id_b.index)
}

/// The warm start of `rows` (with their `infos`) from `cache`, which
/// starts at or before their first pair.
///
/// Both lists are in the order of their pairs' slots (one step's pairs have
/// distinct slots), so the merge compares one integer a pair; a slot's
/// generation must match as well (a body removed and another added in its
/// slot is another pair).
///
/// A pile at rest has the same pairs step after step: the entry where the
/// walk stands is then the contact's own, taken without working out
/// either order.
fn warm_start_from(cache: &[Cached], rows: &mut [Constraint], infos: &[ContactInfo]) {
    let mut j = 0;
    for (c, info) in rows.iter_mut().zip(infos) {
        let key = info.key();
        let hit = match cache.get(j) {
            Some(hit) if hit.key == key => hit,
            _ => {
                let order = info_order(info);
                while j < cache.len() && cache[j].order() < order {
                    j += 1;
                }
                match cache.get(j) {
                    Some(hit) if hit.key == key => hit,
                    Some(_) => continue,
                    None => break,
                }
            }
        };
        c.normal_impulse = hit.normal_impulse;
        c.tangent_impulse = hit.tangent_impulse;
        c.push_impulse = hit.push_impulse;
        // The next pair's order is higher than this one's.
        j += 1;
    }
}

/// Two contact lists sorted by key, merged into key order (on equal keys,
/// which do not occur, `a` first).
fn merged<'a>(
    a: &'a ContactList,
    b: &'a ContactList,
) -> impl Iterator<Item = (&'a Constraint, &'a ContactInfo)> {
    let (mut i, mut j) = (0, 0);
    std::iter::from_fn(move || {
        let take_a = j == b.len() || (i < a.len() && a.infos[i].key() < b.infos[j].key());
        if take_a {
            i += 1;
            (i <= a.len()).then(|| (&a.rows[i - 1], &a.infos[i - 1]))
        } else {
            j += 1;
            Some((&b.rows[j - 1], &b.infos[j - 1]))
        }
    })
}

/// Walks two sorted lists and reports what is only in `now` (`true`) or
/// only in `before` (`false`).
fn diff<T: Ord>(before: &[T], now: &[T], mut f: impl FnMut(&T, bool)) {
    // A pile at rest touches as it did: the common start is passed over
    // with one comparison an entry.
    let same = before.iter().zip(now).take_while(|(b, n)| b == n).count();
    let (mut i, mut j) = (same, same);
    loop {
        match (before.get(i), now.get(j)) {
            (Some(b), Some(n)) if b == n => {
                i += 1;
                j += 1;
            }
            (Some(b), Some(n)) if b < n => {
                f(b, false);
                i += 1;
            }
            (Some(b), None) => {
                f(b, false);
                i += 1;
            }
            (_, Some(n)) => {
                f(n, true);
                j += 1;
            }
            (None, None) => return,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::collider::ColliderRef;

    fn id(index: u32, generation: u32) -> BodyId {
        BodyId { index, generation }
    }

    /// A contact between `a` and `b` (A given first, in either slot order),
    /// with the impulses `n` and whether it touches.
    fn contact(a: BodyId, b: BodyId, n: f32, touching: bool) -> (Constraint, ContactInfo) {
        let row = Constraint {
            a: 0,
            b: ColliderRef::fixed(0),
            normal: glam::Vec2::Y,
            base_separation: 0.0,
            inv_mass_a: 1.0,
            inv_mass_b: 0.0,
            mass: 1.0,
            friction: 0.5,
            normal_impulse: n,
            tangent_impulse: -n,
            push_impulse: 2.0 * n,
            max_normal_impulse: if touching { n } else { 0.0 },
            tangent_speed: 0.0,
        };
        let info = ContactInfo {
            id_a: a,
            id_b: b,
            separation: 0.01,
            points: [glam::Vec2::ZERO; 2],
            point_count: 1,
            restitution: 0.0,
            impact_u: 0.0,
            half_an_h: 0.0,
            anchor: glam::Vec2::ZERO,
            anchor_separation: 0.01,
            reusable: false,
            lead: 0.0,
        };
        (row, info)
    }

    fn list(contacts: &[(Constraint, ContactInfo)]) -> ContactList {
        let mut list = ContactList::default();
        for &(row, info) in contacts {
            list.push(row, info);
        }
        list
    }

    #[test]
    fn warm_start_in_chunks_gives_what_it_gives_in_one_go() {
        // 6 000 contacts (enough for chunks on the pool): pairs (i, i + 1)
        // and (i, i + 7); last step had every third of them, and some of
        // those with a body since replaced (another generation).
        let pairs: Vec<_> = (0..3000u32)
            .flat_map(|i| [(i, i + 1), (i, i + 7)])
            .collect();
        let mut tracker = EventTracker::default();
        let last: Vec<_> = pairs
            .iter()
            .enumerate()
            .filter(|(k, _)| k % 3 == 0)
            .map(|(k, &(a, b))| contact(id(a, 0), id(b, u32::from(k % 5 == 0)), k as f32, true))
            .collect();
        tracker.record(&list(&last), &ContactList::default(), 1, false);
        let now: Vec<_> = pairs
            .iter()
            .map(|&(a, b)| contact(id(a, 0), id(b, 0), 0.0, false))
            .collect();
        let (mut one_go, mut chunked) = (list(&now), list(&now));
        tracker.warm_start(&mut one_go, false);
        tracker.warm_start(&mut chunked, true);
        assert_eq!(one_go, chunked);
        let warmed = one_go
            .rows
            .iter()
            .filter(|c| c.normal_impulse > 0.0)
            .count();
        // Every third pair but those with a replaced body.
        assert_eq!(
            warmed,
            (0..6000).filter(|k| k % 3 == 0 && k % 5 != 0).count()
        );
    }

    #[test]
    fn recording_in_chunks_gives_what_it_gives_in_one_go() {
        // 6 000 contacts (enough for chunks on the pool), every third
        // touching; two steps, so that the second has begins and ends, and
        // the lists shrink from one step to the next.
        let pairs: Vec<_> = (0..3000u32)
            .flat_map(|i| [(i, i + 1), (i, i + 7)])
            .collect();
        let step = |skip: usize, shift: usize| {
            let contacts: Vec<_> = pairs
                .iter()
                .enumerate()
                .filter(|(k, _)| !k.is_multiple_of(skip))
                .map(|(k, &(a, b))| {
                    contact(id(a, 0), id(b, 0), k as f32, (k + shift).is_multiple_of(3))
                })
                .collect();
            list(&contacts)
        };
        let (first, second) = (step(7, 0), step(5, 1));
        let (mut one_go, mut chunked) = (EventTracker::default(), EventTracker::default());
        for (k, now) in [&first, &second].into_iter().enumerate() {
            one_go.record(now, &ContactList::default(), k as u64, false);
            chunked.record(now, &ContactList::default(), k as u64, true);
            assert_eq!(one_go.cache, chunked.cache, "step {k}");
            assert_eq!(one_go.touching_prev, chunked.touching_prev, "step {k}");
            assert_eq!(one_go.events, chunked.events, "step {k}");
        }
        assert_eq!(one_go.cache.len(), second.len());
        assert!(!one_go.events.begin.is_empty() && !one_go.events.end.is_empty());
    }

    #[test]
    fn warm_start_matches_pairs_by_slot_and_generation() {
        let mut tracker = EventTracker::default();
        // Last step: pairs (1, 4), (2, 3) and (3, 9), each with its
        // impulses; (2, 3) and (3, 9) touching.
        let last = list(&[
            contact(id(4, 0), id(1, 0), 1.0, false),
            contact(id(2, 0), id(3, 0), 2.0, true),
            contact(id(3, 0), id(9, 0), 3.0, true),
        ]);
        tracker.record(&last, &ContactList::default(), 1, false);
        let pair = |a, b| ContactPair { a, b };
        let touching = [pair(id(2, 0), id(3, 0)), pair(id(3, 0), id(9, 0))];
        assert_eq!(tracker.events.begin, touching);
        // This step: (1, 4) again with A and B the other way round, (2, 3)
        // where slot 3 now holds another body (a new generation), a new
        // pair (2, 5), and (3, 9) again.
        let mut now = list(&[
            contact(id(1, 0), id(4, 0), 0.0, false),
            contact(id(2, 0), id(3, 1), 0.0, false),
            contact(id(2, 0), id(5, 0), 0.0, false),
            contact(id(3, 0), id(9, 0), 0.0, false),
        ]);
        tracker.warm_start(&mut now, false);
        let impulses: Vec<_> = now
            .rows
            .iter()
            .map(|c| (c.normal_impulse, c.tangent_impulse, c.push_impulse))
            .collect();
        assert_eq!(
            impulses,
            [
                (1.0, -1.0, 2.0),
                (0.0, 0.0, 0.0),
                (0.0, 0.0, 0.0),
                (3.0, -3.0, 6.0),
            ],
            "the same pairs carry their impulses, another body in a slot does not"
        );
        // None of them touches now: the two touching pairs end.
        tracker.record(&now, &ContactList::default(), 2, false);
        assert!(tracker.events.begin.is_empty());
        assert_eq!(tracker.events.end, touching);
        assert_eq!(tracker.touching_prev, []);
        assert_eq!(tracker.cache.len(), 4);
    }

    #[test]
    fn diff_reports_what_began_and_what_ended() {
        let mut seen = Vec::new();
        diff(&[1, 3, 5, 7], &[2, 3, 7, 8], |&x, began| {
            seen.push((x, began))
        });
        assert_eq!(
            seen,
            [(1, false), (2, true), (5, false), (8, true)],
            "in merged order"
        );
    }
}
