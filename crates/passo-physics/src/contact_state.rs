//! The contact state a snapshot carries: what the next step needs from the
//! last one, and the checks a restored state must pass.

use crate::bodies::{Colliders, DynamicBodies, StaticBodies};
use crate::collider::ColliderRef;
use crate::constraint::{Constraint, ContactInfo, ContactList};
use crate::events::Cached;
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
}

impl ContactState {
    /// The sleeping contacts as a list.
    pub(crate) fn sleeping(&self) -> ContactList {
        ContactList {
            rows: self.asleep.clone(),
            infos: self.asleep_infos.clone(),
        }
    }

    /// Checks the state against the bodies: the sleeping contacts each name
    /// a sleeping shaped dynamic body and a sleeping or static shaped one
    /// that exist, in key order, with finite values; the carried impulses
    /// are finite, the normal ones never negative.
    pub(crate) fn validate(
        &self,
        dynamic: &DynamicBodies,
        statics: &StaticBodies,
    ) -> Result<(), String> {
        if self.asleep.len() != self.asleep_infos.len() {
            return Err("sleeping contact lists of different lengths".into());
        }
        if !self.asleep_infos.is_sorted_by_key(ContactInfo::key) {
            return Err("sleeping contacts out of order".into());
        }
        if let Some(c) = self.cache.iter().find(|c| !c.is_valid()) {
            return Err(format!(
                "carried impulses of {:?} are not finite or negative",
                c.key()
            ));
        }
        let bodies = Colliders { dynamic, statics };
        let sleeping = |r: ColliderRef| {
            r.dynamic_index()
                .is_none_or(|i| dynamic.sleep.get(i).is_some_and(|s| s.is_asleep()))
        };
        let id = |r: ColliderRef| {
            bodies
                .get_meta(r)
                .filter(|m| m.shape.is_some())
                .map(|m| m.id)
        };
        for (c, info) in self.asleep.iter().zip(&self.asleep_infos) {
            // Body A is dynamic; a damaged index may not even fit a reference.
            let a_sleeps = dynamic
                .sleep
                .get(c.a as usize)
                .is_some_and(|s| s.is_asleep());
            let ia = dynamic
                .meta
                .get(c.a as usize)
                .filter(|m| m.shape.is_some())
                .map(|m| m.id);
            let ib = id(c.b);
            let named = ia.is_some()
                && ib.is_some()
                && (ia == Some(info.id_a) && ib == Some(info.id_b)
                    || ia == Some(info.id_b) && ib == Some(info.id_a));
            if !(named && a_sleeps && sleeping(c.b) && c.is_valid()) {
                return Err(format!(
                    "sleeping contact {:?}-{:?} is inconsistent with the bodies",
                    info.id_a, info.id_b
                ));
            }
        }
        Ok(())
    }
}
