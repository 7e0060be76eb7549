//! Snapshots: the whole state of a world, to save, send or roll back to.

use crate::body::census::BodyCensus;
use crate::body::store::{DynamicBodies, StaticBodies, heap};
use crate::contact_world::ContactWorld;
use crate::contact_world::state::ContactState;
use crate::joint::Joints;
use crate::world::{Location, Slot};
use crate::{BodyDef, BodyKind, PhysicsError, StepStats, World, WorldSettings};
use glam::Vec2;

/// Everything a world needs to continue exactly where it was: settings,
/// every body (position, velocity, accumulated force, material, ids and
/// their generations) and the contact state a step hands to the next
/// (warm-start impulses, touching pairs, sensor overlaps).
///
/// Stepping a world restored from a snapshot gives, bit for bit, what
/// stepping the original would have given: the rollback pattern of
/// networked games. With the `serde` feature a snapshot serializes to any
/// format (RON for people, a binary format for the wire).
///
/// Custom [`ForceModel`](crate::ForceModel)s are code, not data: a snapshot
/// records how many the world had, and the game adds them again after
/// [`World::from_snapshot`].
///
/// `WorldSnapshot::default()` is the state of an empty world with default
/// settings: a buffer for [`World::snapshot_into`] to fill.
///
/// Two snapshots are equal when they hold the same state, wherever they
/// came from (a world, a file).
#[derive(Clone, Debug, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct WorldSnapshot {
    pub(crate) settings: WorldSettings,
    pub(crate) slots: Vec<Slot>,
    pub(crate) free: Vec<u32>,
    pub(crate) dynamic: DynamicBodies,
    pub(crate) statics: StaticBodies,
    pub(crate) speed_overrides: usize,
    pub(crate) game_friction: bool,
    pub(crate) shaped_dynamic: usize,
    pub(crate) shaped_static: usize,
    pub(crate) stats: StepStats,
    pub(crate) contacts: Option<ContactState>,
    pub(crate) custom_force_models: usize,
    /// The joints, with their impulses.
    #[cfg_attr(feature = "serde", serde(default))]
    pub(crate) joints: Joints,
    /// The force zones, by their sensor bodies.
    #[cfg_attr(feature = "serde", serde(default))]
    pub(crate) zones: Vec<(crate::BodyId, crate::ForceZone)>,
    /// The world (instance) and version of static bodies these statics
    /// are a copy of, so restoring into that world as it is skips them.
    /// Not saved: a snapshot from a file always copies them.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub(crate) statics_source: Option<(u64, u64)>,
    /// Made by a world in this process (its fields cannot be changed from
    /// outside), so it needs no check; a snapshot read from a file is not.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub(crate) made_here: bool,
}

impl PartialEq for WorldSnapshot {
    fn eq(&self, other: &Self) -> bool {
        // Where the snapshot came from (`statics_source`, `made_here`) is
        // not state.
        self.settings == other.settings
            && self.slots == other.slots
            && self.free == other.free
            && self.dynamic == other.dynamic
            && self.statics == other.statics
            && self.speed_overrides == other.speed_overrides
            && self.game_friction == other.game_friction
            && self.shaped_dynamic == other.shaped_dynamic
            && self.shaped_static == other.shaped_static
            && self.stats == other.stats
            && self.contacts == other.contacts
            && self.custom_force_models == other.custom_force_models
            && self.joints == other.joints
            && self.zones == other.zones
    }
}

impl WorldSnapshot {
    /// Custom force models the world had (to add again after a restore).
    pub fn custom_force_models(&self) -> usize {
        self.custom_force_models
    }

    /// Bytes the snapshot holds on the heap (its arrays, with the room
    /// they keep for reuse): what a ring of snapshots costs.
    pub fn heap_bytes(&self) -> usize {
        heap(&self.slots)
            + heap(&self.free)
            + self.dynamic.heap_bytes()
            + self.statics.heap_bytes()
            + self.contacts.as_ref().map_or(0, ContactState::heap_bytes)
            + self.joints.heap_bytes()
            + heap(&self.zones)
    }

    /// Steps the world had taken.
    pub fn steps(&self) -> u64 {
        self.stats.steps
    }

    /// Checks that the snapshot is one a world could have produced: array
    /// lengths agree, ids and slots point at each other, every body passes
    /// the checks [`BodyDef::validate`](crate::BodyDef::validate) makes of a
    /// new body, the counters match the bodies, the carried contacts name
    /// bodies that exist, and the touching pairs and sensor overlaps the
    /// next step's events come from are in order, each once (they may
    /// name bodies removed since the step, whose pairs then end).
    /// Snapshots from files pass through this before a world is made from
    /// them.
    pub fn validate(&self) -> Result<(), PhysicsError> {
        self.validate_with(&mut Vec::new())
    }

    /// [`validate`](Self::validate) with a scratch buffer of the caller's.
    pub(crate) fn validate_with(&self, seen: &mut Vec<bool>) -> Result<(), PhysicsError> {
        self.settings.validate()?;
        self.check_lengths()?;
        for i in 0..self.dynamic.len() {
            self.check_dynamic(i)?;
        }
        for i in 0..self.statics.len() {
            self.check_static(i)?;
        }
        self.check_slots(seen)?;
        self.check_counters()?;
        self.check_joints()?;
        if let Some(contacts) = &self.contacts {
            contacts
                .validate(&self.dynamic, &self.statics)
                .map_err(PhysicsError::InvalidSnapshot)?;
        }
        Ok(())
    }

    fn check_lengths(&self) -> Result<(), PhysicsError> {
        let d = &self.dynamic;
        let n = d.pos.len();
        let lengths = [
            d.vel.len(),
            d.force.len(),
            d.inv_mass.len(),
            d.drag_area.len(),
            d.friction.len(),
            d.friction_force.len(),
            d.limits.len(),
            d.sleep.len(),
            d.meta.len(),
        ];
        if lengths.iter().any(|&l| l != n) {
            return bad(format!(
                "dynamic arrays of different lengths: {n} positions, {lengths:?}"
            ));
        }
        if !(d.prev_pos.is_empty() || d.prev_pos.len() == n) {
            return bad(format!(
                "{} previous positions for {n} bodies",
                d.prev_pos.len()
            ));
        }
        if d.prev_pos.is_empty() == self.settings.interpolation && n > 0 {
            return bad("previous positions do not match the interpolation setting".into());
        }
        let s = &self.statics;
        if s.friction.len() != s.pos.len() || s.meta.len() != s.pos.len() {
            return bad("static arrays of different lengths".into());
        }
        Ok(())
    }

    /// Dynamic body `i`: what a new body must be, and the hot data a step
    /// leaves (force, previous position, inverse mass, rest time).
    fn check_dynamic(&self, i: usize) -> Result<(), PhysicsError> {
        let d = &self.dynamic;
        let m = &d.meta[i];
        let body = d.view(i);
        if body.kind == BodyKind::Dynamic {
            crate::error::mass("mass", m.mass)
                .map_err(|e| invalid(format!("dynamic body {i}: {e}")))?;
        }
        // A body a step carried past `MAX_COORDINATE` keeps flying, and
        // loads back where it was: a restored position need only be finite.
        let def = body.to_def();
        crate::error::finite_vec("position", def.position)
            .and_then(|_| {
                BodyDef {
                    position: Vec2::ZERO,
                    ..def
                }
                .validate()
            })
            .and_then(|()| self.settings.check_restored_body(&def))
            .map_err(|e| invalid(format!("dynamic body {i}: {e}")))?;
        // A kinematic body has inverse mass zero and infinite mass.
        let mass_ok = if m.kinematic {
            d.inv_mass[i] == 0.0 && m.mass == f32::INFINITY
        } else {
            d.inv_mass[i].is_finite()
                && d.inv_mass[i] > 0.0
                && (m.mass * d.inv_mass[i] - 1.0).abs() < 1e-3
        };
        let ok = mass_ok
            && d.force.at(i).is_finite()
            && d.prev_pos.get(i).is_none_or(|p| p.is_finite())
            && d.friction_force[i].is_finite()
            && d.friction_force[i] >= 0.0
            && d.sleep[i].is_valid()
            && m.drop_through.is_finite()
            && m.drop_through >= 0.0;
        if !ok {
            return bad(format!(
                "dynamic body {i} has a non-finite or out-of-range value"
            ));
        }
        self.check_slot(m.id, Location::Dynamic(i as u32))
    }

    /// Static body `i`: what a new static body must be.
    fn check_static(&self, i: usize) -> Result<(), PhysicsError> {
        let s = &self.statics;
        s.view(i)
            .to_def()
            .validate()
            .map_err(|e| invalid(format!("static body {i}: {e}")))?;
        self.check_slot(s.meta[i].id, Location::Static(i as u32))
    }

    /// Every body has a live slot, the free list names free slots once each.
    fn check_slots(&self, seen: &mut Vec<bool>) -> Result<(), PhysicsError> {
        let bodies = self.dynamic.len() + self.statics.len();
        let live = self.slots.iter().filter(|s| s.location.is_some()).count();
        if live != bodies {
            return bad(format!("{live} live slots for {bodies} bodies"));
        }
        seen.clear();
        seen.resize(self.slots.len(), false);
        for &f in &self.free {
            let free = self
                .slots
                .get(f as usize)
                .is_some_and(|s| s.location.is_none());
            if !free || std::mem::replace(&mut seen[f as usize], true) {
                return bad(format!(
                    "free list names slot {f}, which is not free or is named twice"
                ));
            }
        }
        Ok(())
    }

    fn check_counters(&self) -> Result<(), PhysicsError> {
        let census = BodyCensus::recount(&self.dynamic, &self.statics);
        if (
            census.speed_overrides,
            census.shaped_dynamic,
            census.shaped_static,
        ) != (
            self.speed_overrides,
            self.shaped_dynamic,
            self.shaped_static,
        ) {
            return bad("body counters disagree with the bodies".into());
        }
        Ok(())
    }

    /// The joints: each well formed, naming live bodies, with contacts on.
    fn check_joints(&self) -> Result<(), PhysicsError> {
        self.joints.validate()?;
        if self.joints.count > 0 && self.settings.contacts.is_none() {
            return bad("joints with contacts off".into());
        }
        let live = |id: crate::BodyId| {
            self.slots
                .get(id.index as usize)
                .is_some_and(|s| s.generation == id.generation && s.location.is_some())
        };
        for (id, joint) in self.joints.iter() {
            let def = &joint.def;
            if !live(def.a) || def.b.is_some_and(|b| !live(b)) {
                return bad(format!("{id:?} names a body that does not exist"));
            }
        }
        for (i, (body, zone)) in self.zones.iter().enumerate() {
            zone.validate()?;
            let sensor_box = |meta: &crate::body::store::BodyMeta| {
                meta.sensor && matches!(meta.shape, Some(crate::Shape::Box { .. }))
            };
            let meta = match self.slots.get(body.index as usize) {
                Some(s) if s.generation == body.generation => match s.location {
                    Some(Location::Dynamic(d)) => self.dynamic.meta.get(d as usize),
                    Some(Location::Static(d)) => self.statics.meta.get(d as usize),
                    None => None,
                },
                _ => None,
            };
            if !meta.is_some_and(sensor_box) || self.zones[..i].iter().any(|z| z.0 == *body) {
                return bad(format!("the zone of {body:?} is not on one sensor box"));
            }
        }
        Ok(())
    }

    fn check_slot(&self, id: crate::BodyId, location: Location) -> Result<(), PhysicsError> {
        match self.slots.get(id.index as usize) {
            Some(slot) if slot.generation == id.generation && slot.location == Some(location) => {
                Ok(())
            }
            _ => Err(PhysicsError::InvalidSnapshot(format!(
                "{id:?} and its slot disagree"
            ))),
        }
    }
}

impl World {
    /// The world's whole state (see [`WorldSnapshot`]).
    pub fn snapshot(&self) -> WorldSnapshot {
        let mut out = WorldSnapshot::default();
        self.snapshot_into(&mut out);
        out
    }

    /// Writes the world's whole state into `out` (see [`snapshot`](Self::snapshot)),
    /// reusing its buffers: once `out` has held a world of this size, saving
    /// allocates nothing. Static bodies are not copied again when `out`
    /// already holds this world's static bodies as they are now. For
    /// rollback, which saves every tick.
    pub fn snapshot_into(&self, out: &mut WorldSnapshot) {
        out.settings = *self.settings();
        out.slots.clone_from(&self.slots);
        out.free.clone_from(&self.free);
        out.dynamic.copy_from(&self.dynamic);
        let source = Some((self.instance.0, self.revisions.statics));
        if out.statics_source != source {
            out.statics.copy_from(&self.statics);
            out.statics_source = source;
        }
        out.speed_overrides = self.census.speed_overrides;
        out.game_friction = self.game_friction;
        out.shaped_dynamic = self.census.shaped_dynamic;
        out.shaped_static = self.census.shaped_static;
        out.stats = self.stats;
        let WorldSnapshot {
            dynamic, contacts, ..
        } = out;
        match &self.contacts {
            Some(cw) => {
                let state = contacts.get_or_insert_with(ContactState::default);
                let locate = |id| self.collider_of(id);
                if cw.has_pending_wakes() {
                    // Rare: islands game code woke since the last step wake
                    // in the copy, as they will in this world when it next
                    // steps.
                    let mut copy = cw.clone();
                    copy.flush_wakes(dynamic);
                    copy.carry_into(dynamic, &self.statics, locate, state);
                } else {
                    cw.carry_into(&self.dynamic, &self.statics, locate, state);
                }
            }
            None => *contacts = None,
        }
        out.custom_force_models = self.custom.len();
        out.joints.clone_from(&self.joints);
        out.zones.clone_from(&self.zones);
        out.made_here = true;
    }

    /// Puts this world back in the state of `snapshot` (a rollback), after
    /// checking it as [`from_snapshot`](Self::from_snapshot) does when it
    /// was read from a file (one a world made needs no check), reusing
    /// the world's buffers: restoring a snapshot of this world allocates
    /// nothing once warm, and keeps the static tree when the static bodies
    /// did not change since. Custom force models are kept. Stepping on
    /// gives the same bits as [`restore`](Self::restore).
    pub fn restore_from(&mut self, snapshot: &WorldSnapshot) -> Result<(), PhysicsError> {
        // A snapshot a world made cannot have been edited; one from a file
        // is checked.
        if !snapshot.made_here {
            snapshot.validate_with(&mut self.snapshot_scratch)?;
        }
        self.restore_checked(snapshot);
        Ok(())
    }

    /// Puts this world back in the state of `snapshot`, which was checked.
    fn restore_checked(&mut self, snapshot: &WorldSnapshot) {
        let same_statics =
            snapshot.statics_source == Some((self.instance.0, self.revisions.statics));
        self.settings = snapshot.settings;
        self.slots.clone_from(&snapshot.slots);
        self.free.clone_from(&snapshot.free);
        self.dynamic.copy_from(&snapshot.dynamic);
        if !same_statics {
            self.statics.copy_from(&snapshot.statics);
            self.statics_dirty = true;
            // Other statics than the world had: queries rebuild their tree,
            // and a buffer that holds the statics of before is stale.
            self.note_edit(true);
        }
        self.game_friction = snapshot.game_friction;
        self.stats = snapshot.stats;
        self.joints.clone_from(&snapshot.joints);
        self.joint_rows.apart_stale = true;
        self.zones.clone_from(&snapshot.zones);
        self.broken_joints.clear();
        match (&snapshot.contacts, &mut self.contacts) {
            (Some(state), Some(cw)) => cw.restore(state, !same_statics),
            (Some(state), none) => *none = Some(Box::new(ContactWorld::resume(state.clone()))),
            (None, cw) => *cw = None,
        }
        self.after_restore();
        self.note_edit(!same_statics);
    }

    /// What a world derives from its arrays rather than saving: kinematic
    /// bodies, speed limits and the body census (whose counts the snapshot
    /// carries was checked against it, see `check_counters`).
    fn after_restore(&mut self) {
        self.dynamic.find_kinematic();
        for i in 0..self.dynamic.len() {
            self.dynamic.limits[i] = self.resolve_limits(&self.dynamic.meta[i]);
        }
        self.census = BodyCensus::recount(&self.dynamic, &self.statics);
        self.may_rest = true;
    }

    /// A world in the state of `snapshot`, after checking it
    /// ([`WorldSnapshot::validate`]). Custom force models must be added
    /// again.
    pub fn from_snapshot(snapshot: WorldSnapshot) -> Result<World, PhysicsError> {
        snapshot.validate()?;
        let mut world = World::new(snapshot.settings)?;
        world.restore_checked(&snapshot);
        Ok(world)
    }

    /// Puts this world back in the state of `snapshot` (a rollback), keeping
    /// its custom force models.
    pub fn restore(&mut self, snapshot: WorldSnapshot) -> Result<(), PhysicsError> {
        let custom = std::mem::take(&mut self.custom);
        let mut restored = World::from_snapshot(snapshot)?;
        restored.custom = custom;
        restored.parallel = self.parallel;
        *self = restored;
        Ok(())
    }
}

fn invalid(why: String) -> PhysicsError {
    PhysicsError::InvalidSnapshot(why)
}

fn bad<T>(why: String) -> Result<T, PhysicsError> {
    Err(invalid(why))
}
