//! What queries search: bounding-volume trees over the shaped bodies, and
//! the contacts of each body, built when a query first needs them after
//! the world changed. A game that never queries never pays for them; one
//! that casts rays every frame pays one tree build per step over the
//! moving bodies (the static tree is kept until a static body changes),
//! and each query then costs what is near the ray, not what the world
//! holds.

use crate::Aabb;
use crate::body::store::{DynamicBodies, StaticBodies};
use crate::geometry::static_tree::StaticTree;
use std::sync::{Mutex, MutexGuard};

/// When an index was built: the step count and the world's edit counter.
pub(crate) type Version = (u64, u64);

/// When the per-body contact lists were built: the step count, the
/// world's edit counter and the contact world's revision. The edit counter
/// counts restores: a snapshot from before the first contact step leaves
/// no contact world, whose revision then counts again from zero, so step
/// count and revision alone can repeat those of an abandoned timeline.
pub(crate) type ContactsVersion = (u64, u64, u64);

/// The trees and the contact lists of one version of the world.
#[derive(Debug, Default)]
pub(crate) struct QueryIndex {
    /// Static bodies; items are static indices.
    pub(crate) statics: StaticTree,
    static_items: Vec<u32>,
    statics_built: Option<u64>,
    /// Dynamic and kinematic bodies; items are dynamic indices.
    pub(crate) moving: StaticTree,
    moving_items: Vec<u32>,
    moving_built: Option<Version>,
    /// Contacts of each slot: `contact_list[offsets[s]..offsets[s + 1]]`
    /// are positions in the world's contact order.
    offsets: Vec<u32>,
    contact_list: Vec<u32>,
    contacts_built: Option<ContactsVersion>,
}

impl QueryIndex {
    /// Brings the trees up to date: the static one if a static body
    /// changed since `static_edits`, the moving one if anything moved.
    pub(crate) fn update_trees(
        &mut self,
        dynamic: &DynamicBodies,
        statics: &StaticBodies,
        version: Version,
        static_edits: u64,
    ) {
        if self.statics_built != Some(static_edits) {
            self.static_items.clear();
            let shaped = statics.meta.iter().enumerate().filter_map(|(i, m)| {
                let shape = m.shape?;
                Some((i, Aabb::from_centre(statics.pos[i], shape.half_extents())))
            });
            let (items, boxes): (Vec<u32>, Vec<Aabb>) =
                shaped.map(|(i, aabb)| (i as u32, aabb)).unzip();
            self.static_items = items;
            self.statics.rebuild(boxes);
            self.statics_built = Some(static_edits);
        }
        if self.moving_built != Some(version) {
            self.moving_items.clear();
            let items = &mut self.moving_items;
            let boxes = dynamic.meta.iter().enumerate().filter_map(|(i, m)| {
                let shape = m.shape?;
                items.push(i as u32);
                Some(Aabb::from_centre(dynamic.pos.at(i), shape.half_extents()))
            });
            self.moving.rebuild(boxes);
            self.moving_built = Some(version);
        }
    }

    /// The static index of an item of the static tree.
    pub(crate) fn static_item(&self, item: u32) -> usize {
        self.static_items[item as usize] as usize
    }

    /// The dynamic index of an item of the moving tree.
    pub(crate) fn moving_item(&self, item: u32) -> usize {
        self.moving_items[item as usize] as usize
    }

    /// Brings the per-body contact lists up to date. `pairs` yields the
    /// slot indices of both bodies of every contact, in the world's
    /// contact order; `slots` is the number of slots.
    pub(crate) fn update_contacts(
        &mut self,
        version: ContactsVersion,
        slots: usize,
        pairs: impl Iterator<Item = (u32, u32)> + Clone,
    ) {
        if self.contacts_built == Some(version) {
            return;
        }
        // A counting sort by slot: the positions of each slot's contacts,
        // in contact order.
        self.offsets.clear();
        self.offsets.resize(slots + 1, 0);
        for (a, b) in pairs.clone() {
            self.offsets[a as usize + 1] += 1;
            self.offsets[b as usize + 1] += 1;
        }
        for s in 0..slots {
            self.offsets[s + 1] += self.offsets[s];
        }
        self.contact_list.clear();
        self.contact_list.resize(self.offsets[slots] as usize, 0);
        let mut next = self.offsets.clone();
        for (k, (a, b)) in pairs.enumerate() {
            for s in [a, b] {
                self.contact_list[next[s as usize] as usize] = k as u32;
                next[s as usize] += 1;
            }
        }
        self.contacts_built = Some(version);
    }

    /// The positions, in the world's contact order, of the contacts of the
    /// body in `slot`.
    pub(crate) fn contacts_of(&self, slot: u32) -> &[u32] {
        let s = slot as usize;
        match (self.offsets.get(s), self.offsets.get(s + 1)) {
            (Some(&from), Some(&to)) => &self.contact_list[from as usize..to as usize],
            _ => &[],
        }
    }
}

/// The world's query index behind a lock, so queries (which take `&World`)
/// can build it. A clone of a world starts with an empty index.
#[derive(Debug, Default)]
pub(crate) struct QueryCache(Mutex<QueryIndex>);

impl QueryCache {
    /// The index, locked. A panic inside a query cannot leave it half
    /// built in a way that matters: every part records the version it was
    /// built for only once it is complete, so a poisoned lock is taken over.
    pub(crate) fn lock(&self) -> MutexGuard<'_, QueryIndex> {
        self.0
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }
}

impl Clone for QueryCache {
    fn clone(&self) -> Self {
        Self::default()
    }
}
