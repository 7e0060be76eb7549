//! Contact reuse: the last step's contact of two bodies that barely moved
//! relative to each other, kept instead of found afresh (see
//! [`ContactSettings::reuse_distance`](crate::ContactSettings::reuse_distance)).

use crate::bodies::Colliders;
use crate::constraint::{Constraint, ContactInfo, ContactList, solver_masses};

/// The last step's contacts, walked beside this step's pairs (both in pair
/// order): a pair whose bodies moved less than `distance` relative to each
/// other since its contact's manifold was computed keeps the contact, its
/// normal, friction and points as they were and its separation moved along
/// the normal by that motion (exact for two boxes while their faces meet;
/// see `ContactSettings::reuse_distance` for circles), instead of going
/// through the narrow phase's `Narrow::pair` again. Box2D v3 reuses its
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
        let dynamic = bodies.dynamic;
        // Every removal moved the list to the bodies' new indices.
        debug_assert_eq!(dynamic.meta[row.a as usize].id, info.id_a);
        let relative = bodies.position(row.b) - dynamic.pos.at(row.a as usize);
        let moved = relative - info.anchor;
        // (A NaN is not within.)
        let within = moved.length_squared() < self.distance_sq;
        if !within {
            return None;
        }
        let separation = info.anchor_separation + moved.dot(row.normal);
        // Whether a body sleeps may have changed since.
        let (inv_mass_a, inv_mass_b, mass) = solver_masses(dynamic, row.a as usize, row.b);
        let row = Constraint {
            base_separation: separation,
            inv_mass_a,
            inv_mass_b,
            mass,
            normal_impulse: 0.0,
            tangent_impulse: 0.0,
            push_impulse: 0.0,
            max_normal_impulse: 0.0,
            ..*row
        };
        Some((
            row,
            ContactInfo {
                separation,
                ..*info
            },
        ))
    }
}
