//! How many bodies of each sort the step plans with, counted as bodies
//! come, go and change, and checked against a recount.

use crate::body::store::{BodyMeta, DynamicBodies, StaticBodies};

/// Counts of bodies the step plans with: each stage that only some bodies
/// need (contacts, restitution, one-way drop-through, per-body speed
/// limits) runs only while its count is above zero.
///
/// Every change goes through [`add`](Self::add) and
/// [`remove`](Self::remove) of one body's [`share`](Self::share): an edit
/// removes the body's share before it and adds the share after it. (The
/// drop-through countdown, which walks every body, recounts `dropping`
/// itself.)
/// [`recount`](Self::recount) counts from the bodies themselves; the world
/// checks the two agree after every step in debug builds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct BodyCensus {
    /// Dynamic and kinematic bodies with a shape.
    pub(crate) shaped_dynamic: usize,
    /// Static bodies with a shape.
    pub(crate) shaped_static: usize,
    /// Bodies of any kind with a restitution above zero.
    pub(crate) bouncy: usize,
    /// Dynamic bodies dropping through one-way platforms.
    pub(crate) dropping: usize,
    /// Dynamic bodies with their own speed limits.
    pub(crate) speed_overrides: usize,
    /// Dynamic bodies whose gravity scale is not 1.
    pub(crate) gravity_scaled: usize,
    /// Conveyors, of any kind.
    pub(crate) conveyors: usize,
}

impl BodyCensus {
    /// What one body counts for.
    pub(crate) fn share(meta: &BodyMeta, is_static: bool) -> Self {
        let moving = !is_static;
        Self {
            shaped_dynamic: usize::from(moving && meta.shape.is_some()),
            shaped_static: usize::from(is_static && meta.shape.is_some()),
            bouncy: usize::from(meta.restitution > 0.0),
            dropping: usize::from(moving && meta.drop_through > 0.0),
            speed_overrides: usize::from(moving && has_overrides(meta)),
            gravity_scaled: usize::from(moving && !meta.kinematic && meta.gravity_scale != 1.0),
            conveyors: usize::from(meta.conveyor.is_some()),
        }
    }

    /// Counts a body in.
    pub(crate) fn add(&mut self, share: Self) {
        self.shaped_dynamic += share.shaped_dynamic;
        self.shaped_static += share.shaped_static;
        self.bouncy += share.bouncy;
        self.dropping += share.dropping;
        self.speed_overrides += share.speed_overrides;
        self.gravity_scaled += share.gravity_scaled;
        self.conveyors += share.conveyors;
    }

    /// Counts a body out.
    ///
    /// # Panics
    /// If a count would go below zero: the census and the bodies disagree.
    pub(crate) fn remove(&mut self, share: Self) {
        let out = |count: &mut usize, n: usize| {
            *count = count.checked_sub(n).expect("body census below zero");
        };
        out(&mut self.shaped_dynamic, share.shaped_dynamic);
        out(&mut self.shaped_static, share.shaped_static);
        out(&mut self.bouncy, share.bouncy);
        out(&mut self.dropping, share.dropping);
        out(&mut self.speed_overrides, share.speed_overrides);
        out(&mut self.gravity_scaled, share.gravity_scaled);
        out(&mut self.conveyors, share.conveyors);
    }

    /// The census counted from the bodies.
    pub(crate) fn recount(dynamic: &DynamicBodies, statics: &StaticBodies) -> Self {
        let mut census = Self::default();
        dynamic
            .meta
            .iter()
            .for_each(|m| census.add(Self::share(m, false)));
        statics
            .meta
            .iter()
            .for_each(|m| census.add(Self::share(m, true)));
        census
    }
}

/// Whether a dynamic body has speed limits of its own (a kinematic body's
/// are never applied).
pub(crate) fn has_overrides(meta: &BodyMeta) -> bool {
    !meta.kinematic && (meta.min_speed.is_some() || meta.max_speed.is_some())
}
