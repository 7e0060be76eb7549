//! The contact state a snapshot carries: what the next step needs from the
//! last one, and the checks a restored state must pass.

use crate::body::collider::ColliderRef;
use crate::body::store::{Colliders, DynamicBodies, StaticBodies, heap};
use crate::contact::constraint::{Constraint, ContactInfo, ContactList};
use crate::contact_world::events::Cached;
use crate::{BodyId, SensorPair};

/// The contact state a step hands to the next one.
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct ContactState {
    /// Impulses by body pair, sorted by pair.
    pub cache: Vec<Cached>,
    /// Touching pairs, sorted.
    pub touching: Vec<(BodyId, BodyId)>,
    /// Sensor overlaps, sorted.
    pub sensors: Vec<SensorPair>,
    /// Contacts of sleeping bodies, sorted by pair.
    #[cfg_attr(feature = "serde", serde(default))]
    pub asleep: Vec<Constraint>,
    /// The rest of each sleeping contact.
    #[cfg_attr(feature = "serde", serde(default))]
    pub asleep_infos: Vec<ContactInfo>,
    /// Contacts with an awake body, as the last step solved them, sorted
    /// by pair: not needed to step on, but queries after a restore
    /// ([`World::contacts_of`](crate::World::contacts_of), `is_standing`)
    /// answer what they answered when the state was saved.
    #[cfg_attr(feature = "serde", serde(default))]
    pub awake: Vec<Constraint>,
    /// The rest of each awake contact.
    #[cfg_attr(feature = "serde", serde(default))]
    pub awake_infos: Vec<ContactInfo>,
}

impl ContactState {
    /// Bytes the lists hold on the heap.
    pub(crate) fn heap_bytes(&self) -> usize {
        heap(&self.cache)
            + heap(&self.touching)
            + heap(&self.sensors)
            + heap(&self.asleep)
            + heap(&self.asleep_infos)
            + heap(&self.awake)
            + heap(&self.awake_infos)
    }

    /// The sleeping contacts as a list.
    pub(crate) fn sleeping(&self) -> ContactList {
        ContactList {
            rows: self.asleep.clone(),
            infos: self.asleep_infos.clone(),
        }
    }

    /// The awake contacts as a list.
    pub(crate) fn awake(&self) -> ContactList {
        ContactList {
            rows: self.awake.clone(),
            infos: self.awake_infos.clone(),
        }
    }

    /// Checks the state against the bodies: the sleeping contacts each name
    /// a sleeping shaped dynamic body and a sleeping or static shaped one
    /// that exist, in key order, with finite values; the carried impulses
    /// are finite, the normal and push ones never negative, and in key
    /// order, each pair once; the touching pairs and sensor overlaps in
    /// order, each once, a pair's lower slot first and no body paired with
    /// itself (the next step's events are the differences from them, which
    /// a list out of order turns into false ends and begins). They may name
    /// bodies removed since the step: those pairs end at the next step.
    pub(crate) fn validate(
        &self,
        dynamic: &DynamicBodies,
        statics: &StaticBodies,
    ) -> Result<(), String> {
        if let Some(&(a, b)) = self.touching.iter().find(|&&(a, b)| a.index >= b.index) {
            return Err(format!(
                "touching pair {a:?}-{b:?} names one body twice or the higher slot first"
            ));
        }
        if let Some(w) = self.touching.windows(2).find(|w| w[0] >= w[1]) {
            return Err(format!("touching pairs {:?} out of order or twice", w[1]));
        }
        if let Some(p) = self
            .sensors
            .iter()
            .find(|p| p.sensor.index == p.visitor.index)
        {
            return Err(format!(
                "sensor overlap {:?} names one body twice",
                p.sensor
            ));
        }
        if let Some(w) = self.sensors.windows(2).find(|w| w[0] >= w[1]) {
            return Err(format!("sensor overlaps {:?} out of order or twice", w[1]));
        }
        if let Some(c) = self.cache.iter().find(|c| !c.is_valid()) {
            return Err(format!(
                "carried impulses of {:?} are not finite or negative",
                c.key()
            ));
        }
        // As a step leaves them: each pair's lower slot first, and the pairs
        // in the order of their slots, each pair once (the warm start
        // merges them with the contacts in that order, in chunks on the
        // pool).
        if let Some(c) = self
            .cache
            .iter()
            .find(|c| c.key().0.index >= c.key().1.index)
        {
            return Err(format!(
                "carried impulses of {:?} name one body twice or the higher slot first",
                c.key()
            ));
        }
        if let Some(w) = self.cache.windows(2).find(|w| w[0].order() >= w[1].order()) {
            return Err(format!(
                "carried impulses of {:?} out of order or twice",
                w[1].key()
            ));
        }
        check_list(
            "sleeping",
            &self.asleep,
            &self.asleep_infos,
            true,
            dynamic,
            statics,
        )?;
        check_list(
            "awake",
            &self.awake,
            &self.awake_infos,
            false,
            dynamic,
            statics,
        )?;
        Ok(())
    }
}

/// Checks a list of carried contacts: as long as its infos, in key order,
/// each naming existing shaped bodies (body A dynamic) with finite values;
/// with `asleep`, both bodies sleep (or B is static).
fn check_list(
    what: &str,
    rows: &[Constraint],
    infos: &[ContactInfo],
    asleep: bool,
    dynamic: &DynamicBodies,
    statics: &StaticBodies,
) -> Result<(), String> {
    if rows.len() != infos.len() {
        return Err(format!("{what} contact lists of different lengths"));
    }
    if !infos.is_sorted_by_key(ContactInfo::key) {
        return Err(format!("{what} contacts out of order"));
    }
    let sleeping = |r: ColliderRef| {
        r.dynamic_index()
            .is_none_or(|i| dynamic.sleep.get(i).is_some_and(|s| s.is_asleep()))
    };
    for (c, info) in rows.iter().zip(infos) {
        let a_sleeps = dynamic
            .sleep
            .get(c.a as usize)
            .is_some_and(|s| s.is_asleep());
        let sleep_ok = !asleep || a_sleeps && sleeping(c.b);
        let valid = c.is_valid() && info.is_valid();
        if !(names_bodies(c, info, dynamic, statics) && sleep_ok && valid) {
            return Err(format!(
                "{what} contact {:?}-{:?} is inconsistent with the bodies",
                info.id_a, info.id_b
            ));
        }
    }
    Ok(())
}

/// Whether a contact's bodies (by index, body A dynamic) are the shaped
/// bodies its info names. Not so once one was removed, or moved by a
/// removal, since the step; a damaged index may not even fit a reference.
pub(crate) fn names_bodies(
    c: &Constraint,
    info: &ContactInfo,
    dynamic: &DynamicBodies,
    statics: &StaticBodies,
) -> bool {
    let bodies = Colliders { dynamic, statics };
    let ia = dynamic
        .meta
        .get(c.a as usize)
        .filter(|m| m.shape.is_some())
        .map(|m| m.id);
    let ib = bodies
        .get_meta(c.b)
        .filter(|m| m.shape.is_some())
        .map(|m| m.id);
    ia.is_some()
        && ib.is_some()
        && (ia == Some(info.id_a) && ib == Some(info.id_b)
            || ia == Some(info.id_b) && ib == Some(info.id_a))
}
