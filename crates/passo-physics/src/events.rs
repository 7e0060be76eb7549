//! What a step hands to the next and tells the game: the impulses each
//! contact carries (warm starting), who touched whom (begin and end
//! events) and who is inside which sensor.

use crate::bodies::{Colliders, DynamicBodies, StaticBodies};
use crate::constraint::{Constraint, ContactInfo, ContactList};
use crate::manifold::collide;
use crate::narrow_phase::SensorCandidate;
use crate::{BodyId, ContactEvents, ContactPair, SensorPair};

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
    /// Events of the last step.
    pub events: ContactEvents,
}

impl EventTracker {
    /// Gives each contact the impulses its pair had after the last step;
    /// the cache and the contacts are both sorted by key.
    pub(crate) fn warm_start(&self, contacts: &mut ContactList) {
        debug_assert!(contacts.infos.is_sorted_by_key(ContactInfo::key));
        let cache = &self.cache;
        let mut j = 0;
        for (c, info) in contacts.rows.iter_mut().zip(&contacts.infos) {
            let k = info.key();
            while j < cache.len() && cache[j].key < k {
                j += 1;
            }
            if j < cache.len() && cache[j].key == k {
                c.normal_impulse = cache[j].normal_impulse;
                c.tangent_impulse = cache[j].tangent_impulse;
                c.push_impulse = cache[j].push_impulse;
            }
        }
    }

    /// Finds which candidates end the step inside their sensor. Bodies in
    /// a sensor stay awake, so it keeps seeing them.
    pub(crate) fn find_sensor_overlaps(
        &mut self,
        candidates: &[SensorCandidate],
        dynamic: &mut DynamicBodies,
        statics: &StaticBodies,
    ) {
        self.sensors.clear();
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
            }
        }
    }

    /// After the last substep: caches every contact's impulses for warm
    /// starting, and works out which pairs began and ended touching and
    /// which bodies entered and left sensors. `solved` and `asleep` are
    /// each sorted by key.
    pub(crate) fn record(&mut self, solved: &ContactList, asleep: &ContactList, step: u64) {
        self.cache.clear();
        self.touching.clear();
        for (c, info) in merged(solved, asleep) {
            let k = info.key();
            self.cache.push(Cached {
                key: k,
                normal_impulse: c.normal_impulse,
                tangent_impulse: c.tangent_impulse,
                push_impulse: c.push_impulse,
            });
            if info.is_touching(c) {
                self.touching.push(k);
            }
        }
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
        std::mem::swap(&mut self.sensors, &mut self.sensors_prev);
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
    let (mut i, mut j) = (0, 0);
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
    use super::diff;

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
