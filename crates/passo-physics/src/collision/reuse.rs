//! Contact reuse: the last step's contact of two bodies that barely moved
//! relative to each other, kept instead of found afresh (see
//! [`ContactSettings::reuse_distance`](crate::ContactSettings::reuse_distance)).

use crate::body::store::Colliders;
use crate::contact::constraint::{Constraint, ContactInfo, ContactList, solver_masses};
use glam::Vec2;

/// The last step's contacts, walked beside this step's pairs (both in pair
/// order): a pair whose bodies moved less than `distance` relative to each
/// other since its contact's manifold was computed keeps the contact, its
/// normal, friction and points as they were and its separation moved along
/// the normal by that motion (exact for two boxes while their faces meet;
/// see `ContactSettings::reuse_distance` for circles), instead of going
/// through the narrow phase's `PairContext::pair` again. Box2D v3 reuses its
/// contacts the same way.
pub(crate) struct Reuse<'a> {
    pub last: &'a ContactList,
    /// The reuse distance squared (zero: nothing is reused).
    pub distance_sq: f32,
}

impl Reuse<'_> {
    /// Where the walk for the pairs from `key` on starts.
    #[cfg(feature = "parallel")]
    pub(crate) fn start(&self, key: u64) -> usize {
        self.last.infos.partition_point(|info| info.order() < key)
    }

    /// The pair `key`'s contact kept from the last step, if it may be:
    /// `next` is the walk's place in the last step's contacts, moved past
    /// every pair before `key`.
    #[inline(always)]
    pub(crate) fn kept(
        &self,
        bodies: Colliders<'_>,
        next: &mut usize,
        key: u64,
    ) -> Option<(Constraint, ContactInfo)> {
        let infos = &self.last.infos;
        while infos.get(*next).is_some_and(|info| info.order() < key) {
            *next += 1;
        }
        let info = infos
            .get(*next)
            .filter(|info| info.reusable && info.order() == key)?;
        let row = &self.last.rows[*next];
        // Every removal moved the list to the bodies' new indices.
        debug_assert_eq!(bodies.dynamic.meta[row.a as usize].id, info.id_a);
        let moved = moved(bodies, row, info);
        // (A NaN is not within.)
        let within = moved.length_squared() < self.distance_sq;
        if !within {
            return None;
        }
        // Built where it is returned: no copy to change.
        let kept = Kept::new(bodies, row, info, moved);
        Some((kept.row(row), kept.info(info)))
    }
}

/// Keeps the last step's contacts (`last`) in place, if they may all be
/// kept, one for each of `keys` (this step's pairs, in order): every pair
/// had a contact, so the walk of [`Reuse`] would look at no pair afresh,
/// and each may be kept (see [`Reuse::kept`]): their bodies moved less
/// than the reuse distance (`distance_sq`, squared) relative to each
/// other. Then `last` holds the list the walk would make, and `true` is
/// returned. With `impulses`, each keeps the impulses it ended the last
/// step with, which are those the warm start would give it (see
/// [`EventTracker::fresh`](crate::contact_world::events::EventTracker::fresh)).
///
/// The pairs are matched first, all of them, and only then are the
/// bodies' motions looked at: in a rain, where some pair changes each
/// step, the check stops at the first change having read little. Each
/// contact is then checked and kept in one go (one walk over the list
/// instead of two). Should one of them not be kept, those before it were
/// changed only in what keeping a contact gives afresh (its separation,
/// masses and impulses, see `Kept`), which the walk over `last` does not
/// read: it finds the same contacts.
pub(crate) fn reuse_all(
    bodies: Colliders<'_>,
    keys: impl ExactSizeIterator<Item = u64>,
    (distance_sq, impulses): (f32, bool),
    last: &mut ContactList,
) -> bool {
    let matched =
        keys.len() == last.len() && keys.zip(&last.infos).all(|(key, info)| info.order() == key);
    if !matched {
        return false;
    }
    for (row, info) in last.rows.iter_mut().zip(&mut last.infos) {
        let moved = moved(bodies, row, info);
        // (A NaN is not within.)
        if !(info.reusable && moved.length_squared() < distance_sq) {
            return false;
        }
        let kept = Kept::new(bodies, row, info, moved);
        let ended = (row.normal_impulse, row.tangent_impulse, row.push_impulse);
        *row = kept.row(row);
        if impulses {
            (row.normal_impulse, row.tangent_impulse, row.push_impulse) = ended;
        }
        info.separation = kept.separation;
    }
    true
}

/// How far B moved relative to A since the contact's manifold was
/// computed.
#[inline(always)]
fn moved(bodies: Colliders<'_>, row: &Constraint, info: &ContactInfo) -> Vec2 {
    let relative = bodies.position(row.b) - bodies.dynamic.pos.at(row.a as usize);
    relative - info.anchor
}

/// What keeping a contact changes: its separation, moved along the normal
/// by the bodies' relative motion, and the bodies' masses as they are now
/// (whether a body sleeps may have changed since).
struct Kept {
    separation: f32,
    inv_mass_a: f32,
    inv_mass_b: f32,
    mass: f32,
}

impl Kept {
    /// Keeping contact `row` (with `info`) whose bodies moved by `moved`
    /// relative to each other.
    #[inline(always)]
    fn new(bodies: Colliders<'_>, row: &Constraint, info: &ContactInfo, moved: Vec2) -> Self {
        let (inv_mass_a, inv_mass_b, mass) = solver_masses(bodies.dynamic, row.a as usize, row.b);
        Self {
            separation: info.anchor_separation + moved.dot(row.normal),
            inv_mass_a,
            inv_mass_b,
            mass,
        }
    }

    /// The row as this step solves it, with no impulse yet (the warm
    /// start gives them).
    #[inline(always)]
    fn row(&self, row: &Constraint) -> Constraint {
        Constraint {
            base_separation: self.separation,
            inv_mass_a: self.inv_mass_a,
            inv_mass_b: self.inv_mass_b,
            mass: self.mass,
            normal_impulse: 0.0,
            tangent_impulse: 0.0,
            push_impulse: 0.0,
            max_normal_impulse: 0.0,
            ..*row
        }
    }

    #[inline(always)]
    fn info(&self, info: &ContactInfo) -> ContactInfo {
        ContactInfo {
            separation: self.separation,
            ..*info
        }
    }
}
