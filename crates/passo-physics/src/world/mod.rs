//! The world: owns every body in packed arrays, hands out ids, and keeps
//! the counters the step plans with. The step itself is in `step`, what
//! game code changes on a body in `edit`, and what it asks in `crate::query`
//! and `diagnostics`.

pub(crate) mod settings;
pub(crate) mod query_cache;
pub(crate) mod edit;
pub(crate) mod joints;
pub(crate) mod zones;
pub(crate) mod snapshot;

use crate::body::census::BodyCensus;
use crate::body::collider::ColliderRef;
use crate::body::store::{BodyMeta, DynamicBodies, SpeedLimits, StaticBodies};
use crate::contact_world::ContactWorld;
use crate::forces::integrator::Forces;
use crate::forces::kernel::PointMassKernel;
use crate::forces::models::{Dissipation, Drive};
use crate::forces::zones::ForceZone;
use crate::joint::solve::JointRows;
use crate::joint::{BrokenJoint, Joints};
use crate::switches::TestSwitches;
use crate::world::query_cache::QueryCache;
use crate::{
    Body, BodyDef, BodyId, BodyKind, ContactSettings, ForceModel, PhysicsError, StepCounters,
    WorldSettings,
};
use glam::Vec2;
use std::sync::Arc;

/// Counters the world keeps across steps.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct StepStats {
    /// Steps taken since the world was made. (Every counter here
    /// saturates at `u64::MAX` rather than wrapping, so a restored
    /// snapshot may hold any value.)
    pub steps: u64,
    /// Body-steps in which a force produced a non-finite velocity (a custom
    /// model returning NaN, or an overflow from an enormous force on a tiny
    /// mass). That step's motion is dropped: the body's velocity becomes
    /// zero and it stays where it was, so the world never stores a NaN.
    pub non_finite_resets: u64,
    /// Calls of the per-tick setters (`set_velocity`, `apply_force`, ...)
    /// that changed nothing: a stale id, or a value their `try_` form
    /// refuses (NaN, infinity, out of range).
    #[cfg_attr(feature = "serde", serde(default))]
    pub rejected_inputs: u64,
    /// Steps in which bodies were piled so densely in one grid cell that
    /// the broad phase bounded their pairs (each meets at most 64 of the
    /// bodies after it there, `CROWDED_CELL`), or a body met more than 128
    /// static bodies and was paired with the first 128: memory stays
    /// bounded and the pile is pushed apart by the contacts it has, more
    /// slowly than with all of them.
    #[cfg_attr(feature = "serde", serde(default))]
    pub crowded_steps: u64,
    /// Body-steps in which a fast body, moving farther than its speculative
    /// contacts reach, was swept along its path and stopped short of what
    /// it would have hit (see
    /// [`SPECULATIVE_REACH`](crate::constants::SPECULATIVE_REACH)).
    #[cfg_attr(feature = "serde", serde(default))]
    pub swept_stops: u64,
}

/// Counts of edits. Queries and snapshots keep the counts they were
/// built at, and build again when the world's differ.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Revisions {
    /// Edits that move, add or remove bodies (with the step count, it
    /// tells queries whether their index is current).
    pub(crate) edits: u64,
    /// Edits of static bodies that queries see (moved, added, removed, or
    /// restored from a snapshot).
    pub(crate) static_edits: u64,
    /// Every change to the static bodies, those edits and material or
    /// flag changes (friction, restitution, filter, sensor, one-way) too:
    /// a snapshot holds a copy of the static bodies at a revision, and
    /// copies them again only when it differs.
    pub(crate) statics: u64,
}

impl Revisions {
    /// A body was added, removed or moved by hand: queries rebuild their
    /// index (the static tree too if it was a static body).
    pub(crate) fn body_edited(&mut self, is_static: bool) {
        self.edits += 1;
        if is_static {
            self.static_edits += 1;
            self.statics += 1;
        }
    }

    /// A static body changed in what only snapshots carry.
    pub(crate) fn statics_changed(&mut self) {
        self.statics += 1;
    }
}

/// Where a live body's data sits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) enum Location {
    Dynamic(u32),
    Static(u32),
}

/// One entry of the id table: the generation of the slot, and where its
/// body sits while it lives (`None`: the slot is free).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Slot {
    pub(crate) generation: u32,
    pub(crate) location: Option<Location>,
}

/// A 2D physics world: bodies in packed arrays, force models, an integrator.
///
/// ```
/// use passo_physics::{BodyDef, World, glam::Vec2};
///
/// let mut world = World::default(); // gravity (0, -9.81) m/s²
/// let ball = world.add_body(BodyDef::point_mass(Vec2::new(0.0, 10.0))).unwrap();
/// for _ in 0..60 {
///     world.step(1.0 / 60.0);
/// }
/// let y = world.body(ball).unwrap().position.y;
/// assert!((y - (10.0 - 0.5 * 9.81 - 0.5 * 9.81 / 60.0)).abs() < 1e-4);
/// ```
#[derive(Clone)]
pub struct World {
    pub(crate) settings: WorldSettings,
    pub(crate) custom: Vec<Arc<dyn ForceModel>>,
    pub(crate) slots: Vec<Slot>,
    pub(crate) free: Vec<u32>,
    pub(crate) dynamic: DynamicBodies,
    pub(crate) statics: StaticBodies,
    /// How many bodies of each sort the step plans with.
    pub(crate) census: BodyCensus,
    /// Whether game code applied friction since the last step.
    pub(crate) game_friction: bool,
    /// Static bodies were added, removed or moved since the last step.
    pub(crate) statics_dirty: bool,
    /// The contact stage's state, made the first time it runs.
    pub(crate) contacts: Option<Box<ContactWorld>>,
    /// Some body may have rest time or sleep: a contact step with sleeping
    /// on ran (or a snapshot was restored) since every body was last woken.
    pub(crate) may_rest: bool,
    /// Counts of edits, which tell queries and snapshots what is current.
    pub(crate) revisions: Revisions,
    /// Trees and contact lists for queries, built on demand.
    pub(crate) query_cache: QueryCache,
    /// Which world this is (a clone is another), so a snapshot knows
    /// whether its static bodies are this world's as they are now.
    pub(crate) instance: Instance,
    /// Scratch of snapshot checks, kept so restoring allocates nothing.
    pub(crate) snapshot_scratch: Vec<bool>,
    /// Position corrections of the multi-stage integrators, with contacts.
    pub(crate) correction: Vec<Vec2>,
    /// Position and velocity of each kinematic body when the step began
    /// (scratch: integration treats them as any body, then they are put
    /// back on their own course).
    pub(crate) held: Vec<(Vec2, Vec2)>,
    /// Large worlds may run stages on rayon's pool (`parallel` feature).
    pub(crate) parallel: bool,
    /// The step's shortcuts turned off (for tests, see [`TestSwitches`]).
    pub(crate) switches: TestSwitches,
    pub(crate) stats: StepStats,
    /// The joints, and their rows of the current step (scratch).
    pub(crate) joints: Joints,
    pub(crate) joint_rows: JointRows,
    /// The joints that broke in the last step.
    pub(crate) broken_joints: Vec<BrokenJoint>,
    /// Force zones, by their sensor bodies, in the order they act.
    pub(crate) zones: Vec<(BodyId, ForceZone)>,
    /// The forces game code applied for this step, while the substeps add
    /// the zones' forces to them (scratch).
    pub(crate) applied_force: crate::columns::Columns,
    /// The game's contact hooks, if any.
    pub(crate) hooks: Option<Arc<dyn crate::ContactHooks>>,
}

impl Default for World {
    fn default() -> Self {
        Self::new(WorldSettings::default()).expect("default settings are valid")
    }
}

impl std::fmt::Debug for World {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("World")
            .field("settings", &self.settings)
            .field("dynamic_bodies", &self.dynamic.len())
            .field("static_bodies", &self.statics.len())
            .field("custom_forces", &self.custom.len())
            .field("stats", &self.stats)
            .finish()
    }
}

impl World {
    /// An empty world with the given settings.
    pub fn new(settings: WorldSettings) -> Result<Self, PhysicsError> {
        settings.validate()?;
        Ok(Self {
            settings,
            custom: Vec::new(),
            slots: Vec::new(),
            free: Vec::new(),
            dynamic: DynamicBodies::default(),
            statics: StaticBodies::default(),
            census: BodyCensus::default(),
            game_friction: false,
            statics_dirty: false,
            may_rest: false,
            revisions: Revisions::default(),
            query_cache: QueryCache::default(),
            instance: Instance::new(),
            snapshot_scratch: Vec::new(),
            contacts: None,
            correction: Vec::new(),
            held: Vec::new(),
            parallel: true,
            switches: TestSwitches::default(),
            stats: StepStats::default(),
            joints: Joints::default(),
            joint_rows: JointRows::default(),
            broken_joints: Vec::new(),
            zones: Vec::new(),
            applied_force: Default::default(),
            hooks: None,
        })
    }

    /// The current settings.
    pub fn settings(&self) -> &WorldSettings {
        &self.settings
    }

    /// Replaces the settings (a live slider, a different integrator). Takes
    /// effect on the next step. Turning interpolation on starts it from the
    /// current positions.
    pub fn set_settings(&mut self, settings: WorldSettings) -> Result<(), PhysicsError> {
        settings.validate()?;
        if settings.contacts.is_none() && self.joints.count > 0 {
            return Err(PhysicsError::InvalidJoint(
                "joints need contacts on: remove the joints before turning contacts off",
            ));
        }
        let limits_changed = settings.min_speed != self.settings.min_speed
            || settings.max_speed != self.settings.max_speed;
        if limits_changed && self.census.speed_overrides > 0 {
            for meta in self.dynamic.meta.iter().filter(|m| !m.kinematic) {
                settings.check_speed_limits(meta.min_speed, meta.max_speed)?;
            }
        }
        self.wake_all();
        self.forget_all_reuse();
        self.settings = settings;
        if limits_changed {
            for i in 0..self.dynamic.len() {
                self.dynamic.limits[i] = self.resolve_limits(&self.dynamic.meta[i]);
            }
        }
        if settings.interpolation {
            if self.dynamic.prev_pos.len() != self.dynamic.len() {
                self.dynamic.prev_pos.copy_from(&self.dynamic.pos);
            }
        } else {
            self.dynamic.prev_pos = Default::default();
        }
        Ok(())
    }

    /// Adds a force model of the game's own; it acts on every dynamic body.
    pub fn add_force_model(&mut self, model: Arc<dyn ForceModel>) {
        self.wake_all();
        self.custom.push(model);
    }

    /// Sets the game's contact hooks (see [`ContactHooks`](crate::ContactHooks)),
    /// or removes them with `None`. Every body wakes, so that the new
    /// hooks see every contact from the next step on.
    ///
    /// ```
    /// use passo_physics::{BodyDef, ContactHooks, PreSolve, Shape, World, glam::Vec2};
    /// use std::sync::Arc;
    ///
    /// /// The body with user data 7 is a belt moving right at 2 m/s.
    /// struct Belt;
    /// impl ContactHooks for Belt {
    ///     fn pre_solve(&self, contact: &mut PreSolve) {
    ///         for end in [contact.a, contact.b] {
    ///             if end.user_data == 7 {
    ///                 contact.conveyor(end.id, Vec2::new(2.0, 0.0));
    ///             }
    ///         }
    ///     }
    /// }
    ///
    /// let mut world = World::default();
    /// let belt = BodyDef::new_static(Vec2::new(0.0, -0.5), Shape::rect(40.0, 1.0));
    /// world.add_body(belt.with_user_data(7)).unwrap();
    /// let crate_ = world.add_body(BodyDef::new_dynamic(Vec2::new(0.0, 0.25), Shape::rect(0.5, 0.5))).unwrap();
    /// world.set_contact_hooks(Some(Arc::new(Belt)));
    /// for _ in 0..120 {
    ///     world.step(1.0 / 60.0);
    /// }
    /// let v = world.body(crate_).unwrap().velocity.x;
    /// assert!((v - 2.0).abs() < 0.02, "carried at {v} m/s");
    /// ```
    pub fn set_contact_hooks(&mut self, hooks: Option<Arc<dyn crate::ContactHooks>>) {
        self.wake_all();
        self.forget_all_reuse();
        self.hooks = hooks;
    }

    /// Whether the world has contact hooks.
    pub fn has_contact_hooks(&self) -> bool {
        self.hooks.is_some()
    }

    /// Removes every custom force model.
    pub fn clear_force_models(&mut self) {
        self.wake_all();
        self.custom.clear();
    }

    // ----- sleeping -----

    /// Whether the body sleeps (see [`ContactSettings::sleeping`]); `None`
    /// for a stale id. Static bodies never sleep.
    pub fn is_asleep(&self, id: BodyId) -> Option<bool> {
        match self.locate(id)? {
            Location::Dynamic(i) => Some(self.sleeps(i as usize)),
            _ => Some(false),
        }
    }

    /// Number of sleeping bodies.
    pub fn sleeping_len(&self) -> usize {
        (0..self.dynamic.len()).filter(|&i| self.sleeps(i)).count()
    }

    /// Whether dynamic body `i` sleeps: its island sleeps and game code
    /// has not woken it since the last step.
    fn sleeps(&self, i: usize) -> bool {
        self.dynamic.sleep[i].island().is_some_and(|island| {
            self.contacts
                .as_ref()
                .is_none_or(|cw| !cw.wakes_pending(island))
        })
    }

    /// Wakes a body and every body sleeping in its island, and restarts its
    /// rest time. Changing a body (force, impulse, velocity, position,
    /// material) does this already; call it when a custom force model
    /// starts acting on a sleeping body.
    pub fn wake(&mut self, id: BodyId) -> Result<(), PhysicsError> {
        if let Some(i) = self.dynamic_index(id)? {
            self.wake_index(i);
        }
        Ok(())
    }

    /// Wakes every body. Changing the settings, the force models or a
    /// static body does this already.
    pub fn wake_all(&mut self) {
        // Nothing rests before a step with sleeping on: building a world
        // (each static body added wakes every body) costs nothing here.
        if !std::mem::take(&mut self.may_rest) {
            return;
        }
        match &mut self.contacts {
            Some(cw) => cw.wake_all_later(&mut self.dynamic),
            None => self.dynamic.wake_all(),
        }
    }

    pub(crate) fn wake_index(&mut self, i: usize) {
        if let Some(cw) = &mut self.contacts {
            cw.wake_body(&mut self.dynamic, i);
        }
    }

    /// A body changed: a dynamic one wakes its island; a static one may
    /// have held anything up, so every body wakes (and the static bodies
    /// are a new revision for snapshots).
    pub(crate) fn wake_after_change(&mut self, location: Location) {
        match location {
            Location::Dynamic(i) => self.wake_index(i as usize),
            Location::Static(_) => {
                self.revisions.statics_changed();
                self.wake_all();
            }
        }
    }

    /// What the contact steps' shortcuts saved so far (see
    /// [`StepCounters`]); all zero before the first contact step.
    ///
    /// ```
    /// use passo_physics::{BodyDef, Shape, World, glam::Vec2};
    ///
    /// let mut world = World::default();
    /// world.add_body(BodyDef::new_static(Vec2::ZERO, Shape::rect(10.0, 1.0))).unwrap();
    /// let crate_def = BodyDef::new_dynamic(Vec2::new(0.0, 1.0), Shape::rect(1.0, 1.0));
    /// world.add_body(crate_def).unwrap();
    /// for _ in 0..120 {
    ///     world.step(1.0 / 60.0);
    /// }
    /// // A crate at rest: most steps reuse the last step's contacts.
    /// assert!(world.counters().contacts_reused_in_place > 60);
    /// ```
    pub fn counters(&self) -> StepCounters {
        let mut counters = StepCounters::default();
        if let Some(cw) = &self.contacts {
            cw.count(&mut counters);
        }
        counters.rods_in_blocks = self.joint_rows.rods_in_blocks() as u64;
        counters
    }

    /// Turns the step's shortcuts off, or on again, so a test can check
    /// they give what the long way gives. The results are the same bits
    /// either way; only the time taken differs.
    #[doc(hidden)]
    pub fn set_test_switches(&mut self, switches: TestSwitches) {
        // The contact step hands them on to its parts as it starts.
        self.switches = switches;
    }

    /// Lets large worlds run their per-body stages, broad-phase pair search
    /// and narrow phase on rayon's thread pool (with the `parallel` feature;
    /// the default is on). The results are the same bits either way; off, a
    /// step never hands work to another thread.
    pub fn set_parallel(&mut self, parallel: bool) {
        self.parallel = parallel;
    }

    /// Whether large worlds may use the thread pool.
    pub fn parallel(&self) -> bool {
        self.parallel
    }

    /// Counters kept across steps.
    pub fn stats(&self) -> StepStats {
        self.stats
    }

    // ----- bodies -----

    /// Adds a body; its definition is checked first.
    pub fn add_body(&mut self, def: BodyDef) -> Result<BodyId, PhysicsError> {
        self.settings.check_body(&def)?;
        let index = match self.free.pop() {
            Some(index) => index,
            None => {
                let index = u32::try_from(self.slots.len()).expect("more than u32::MAX bodies");
                self.slots.push(Slot {
                    generation: 0,
                    location: None,
                });
                index
            }
        };
        self.note_edit(def.kind == BodyKind::Static);
        if def.kind == BodyKind::Static {
            self.forget_all_reuse();
        }
        let slot = &mut self.slots[index as usize];
        let id = BodyId {
            index,
            generation: slot.generation,
        };
        let meta = BodyMeta {
            id,
            kinematic: def.kind == BodyKind::Kinematic,
            mass: if def.kind == BodyKind::Dynamic {
                def.mass
            } else {
                f32::INFINITY
            },
            shape: def.shape,
            drag_area: def.drag_area,
            friction_mix: def.friction_mix,
            restitution: def.restitution,
            filter: def.filter,
            sensor: def.sensor,
            one_way: def.one_way.and_then(crate::body::def::unit_direction),
            conveyor: def.conveyor,
            drop_through: 0.0,
            character: false,
            bullet: def.bullet,
            gravity_scale: if def.kind == BodyKind::Dynamic {
                def.gravity_scale
            } else {
                1.0
            },
            min_speed: def.min_speed,
            max_speed: def.max_speed,
            user_data: def.user_data,
        };
        self.census
            .add(BodyCensus::share(&meta, def.kind == BodyKind::Static));
        match def.kind {
            BodyKind::Dynamic | BodyKind::Kinematic => {
                slot.location = Some(Location::Dynamic(self.dynamic.len() as u32));
                let limits = self.resolve_limits(&meta);
                self.dynamic
                    .push(&def, meta, limits, self.settings.interpolation);
            }
            BodyKind::Static => {
                slot.location = Some(Location::Static(self.statics.len() as u32));
                self.statics.push(&def, meta);
                self.statics_dirty = true;
                self.wake_all();
            }
        }
        Ok(id)
    }

    /// Removes a body and returns its last state, or `None` for a stale id.
    /// The last body of the same kind moves into the freed array place, so
    /// storage order changes; ids stay valid.
    pub fn remove_body(&mut self, id: BodyId) -> Option<Body> {
        let location = self.locate(id)?;
        self.remove_joints_of(id);
        if !self.zones.is_empty() {
            self.forget_zone_of(id);
        }
        let body = self.view(location);
        let share = match location {
            Location::Dynamic(i) => BodyCensus::share(&self.dynamic.meta[i as usize], false),
            Location::Static(i) => BodyCensus::share(&self.statics.meta[i as usize], true),
        };
        self.census.remove(share);
        self.note_edit(body.kind == BodyKind::Static);
        let moved = match location {
            Location::Dynamic(i) => {
                if self.dynamic.meta[i as usize].kinematic
                    && let Some(cw) = &mut self.contacts
                {
                    cw.press_removed(i, self.dynamic.len());
                }
                // What rested on it wakes, and falls at the next step; its
                // island's other stored contacts answer queries until then.
                self.wake_index(i as usize);
                let last = self.dynamic.len() as u32 - 1;
                if let Some(cw) = &mut self.contacts {
                    cw.body_moved(last, i);
                }
                self.dynamic.swap_remove(i as usize)
            }
            Location::Static(i) => {
                self.statics_dirty = true;
                self.forget_all_reuse();
                self.wake_all();
                if let Some(cw) = &mut self.contacts {
                    // The last static body moves to `i`.
                    cw.lists_changed();
                }
                self.statics.swap_remove(i as usize)
            }
        };
        if let Some(moved) = moved {
            self.slots[moved.index as usize].location = Some(location);
        }
        let slot = &mut self.slots[id.index as usize];
        slot.location = None;
        // A slot whose generation would wrap is retired, so no id is ever reused.
        if let Some(next) = slot.generation.checked_add(1) {
            slot.generation = next;
            self.free.push(id.index);
        }
        Some(body)
    }

    /// Whether `id` names a live body.
    pub fn contains(&self, id: BodyId) -> bool {
        self.locate(id).is_some()
    }

    /// A copy of the body's state, or `None` for a stale id.
    pub fn body(&self, id: BodyId) -> Option<Body> {
        self.locate(id).map(|l| self.view(l))
    }

    /// Every body, in id order.
    pub fn bodies(&self) -> impl Iterator<Item = Body> + '_ {
        self.slots
            .iter()
            .filter_map(|s| s.location)
            .map(|l| self.view(l))
    }

    /// Number of bodies, dynamic and static.
    pub fn len(&self) -> usize {
        self.dynamic.len() + self.statics.len()
    }

    /// Whether the world has no body.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Number of dynamic bodies.
    pub fn dynamic_len(&self) -> usize {
        self.dynamic.len()
    }

    /// The contact settings if the contact stage runs: contacts are on,
    /// and a shaped dynamic or kinematic body exists and something else is
    /// shaped, or some joint exists (joints are solved in its substeps).
    pub(crate) fn contact_settings(&self) -> Option<ContactSettings> {
        let contacts = self.settings().contacts?;
        let shaped = self.census.shaped_dynamic > 0
            && self.census.shaped_dynamic + self.census.shaped_static >= 2;
        (shaped || self.joints.count > 0).then_some(contacts)
    }

    /// The fast kernel for the current settings, if it applies.
    pub(crate) fn kernel(&self, limits: Option<Option<SpeedLimits>>) -> Option<PointMassKernel> {
        let settings = self.settings();
        PointMassKernel::new(
            &settings.forces,
            settings.integrator,
            settings.force_form,
            !self.custom.is_empty() || self.game_friction,
            limits,
        )
    }

    // ----- helpers -----

    fn world_limits(&self) -> SpeedLimits {
        SpeedLimits::new(self.settings.min_speed, self.settings.max_speed)
    }

    pub(crate) fn resolve_limits(&self, meta: &BodyMeta) -> SpeedLimits {
        if meta.kinematic {
            // Game code sets a kinematic body's speed: no limit applies.
            return SpeedLimits::new(0.0, f32::INFINITY);
        }
        SpeedLimits::new(
            meta.min_speed.unwrap_or(self.settings.min_speed),
            meta.max_speed.unwrap_or(self.settings.max_speed),
        )
    }

    /// `Some` when speed limits apply: `Some(uniform)` with the world's
    /// limits for every body, `None` when some body has its own (kinematic
    /// bodies have none).
    pub(crate) fn speed_limits(&self) -> Option<Option<SpeedLimits>> {
        let uniform = self.census.speed_overrides == 0
            && self.dynamic.kinematic.is_empty()
            && !self.has_liquid();
        self.has_speed_limits()
            .then(|| uniform.then(|| self.world_limits()))
    }

    fn has_speed_limits(&self) -> bool {
        self.census.speed_overrides > 0
            || self.settings.min_speed > 0.0
            || self.settings.max_speed < f32::INFINITY
    }

    /// A live body's user data (0 for a stale id).
    pub(crate) fn body_user_data(&self, id: BodyId) -> u64 {
        self.meta_of(id).map_or(0, |m| m.user_data)
    }

    /// A live body's cold data, or `None` for a stale id.
    pub(crate) fn meta_of(&self, id: BodyId) -> Option<&BodyMeta> {
        Some(match self.locate(id)? {
            Location::Dynamic(i) => &self.dynamic.meta[i as usize],
            Location::Static(i) => &self.statics.meta[i as usize],
        })
    }

    pub(crate) fn locate(&self, id: BodyId) -> Option<Location> {
        let slot = self.slots.get(id.index as usize)?;
        slot.location.filter(|_| slot.generation == id.generation)
    }

    /// Where a live body sits, as a collider reference.
    pub(crate) fn collider_of(&self, id: BodyId) -> Option<ColliderRef> {
        self.locate(id).map(|l| match l {
            Location::Dynamic(i) => ColliderRef::dynamic(i),
            Location::Static(i) => ColliderRef::fixed(i),
        })
    }

    /// The array index of a dynamic body that forces move, `None` for a
    /// static or kinematic one.
    pub(crate) fn movable_index(&self, id: BodyId) -> Result<Option<usize>, PhysicsError> {
        Ok(self
            .dynamic_index(id)?
            .filter(|&i| !self.dynamic.meta[i].kinematic))
    }

    /// The array index of a dynamic or kinematic body, `None` for a static
    /// one.
    pub(crate) fn dynamic_index(&self, id: BodyId) -> Result<Option<usize>, PhysicsError> {
        match self.locate(id).ok_or(PhysicsError::StaleBody(id))? {
            Location::Dynamic(i) => Ok(Some(i as usize)),
            _ => Ok(None),
        }
    }

    /// A body was added, removed or moved by hand: queries rebuild their
    /// index (the static tree too if it was a static body).
    pub(crate) fn note_edit(&mut self, is_static: bool) {
        self.revisions.body_edited(is_static);
    }

    /// A static body changed what it covers of its neighbours (filter,
    /// sensor, one-way): the static tree and its covered faces are built
    /// again at the next step.
    pub(crate) fn static_shape_changed(&mut self, location: Location) {
        if matches!(location, Location::Static(_)) {
            self.statics_dirty = true;
        }
    }

    /// The cold data of a live body.
    pub(crate) fn meta_mut(&mut self, location: Location) -> &mut BodyMeta {
        match location {
            Location::Dynamic(i) => &mut self.dynamic.meta[i as usize],
            Location::Static(i) => &mut self.statics.meta[i as usize],
        }
    }

    pub(crate) fn view(&self, location: Location) -> Body {
        match location {
            Location::Dynamic(i) => {
                let mut body = self.dynamic.view(i as usize);
                body.asleep = self.sleeps(i as usize);
                body
            }
            Location::Static(i) => self.statics.view(i as usize),
        }
    }

    pub(crate) fn lerp_dynamic(&self, i: usize, alpha: f32) -> Vec2 {
        let current = self.dynamic.pos.at(i);
        match self.dynamic.prev_pos.get(i) {
            // A NaN alpha draws the current position.
            Some(prev) if !alpha.is_nan() => prev.lerp(current, alpha.clamp(0.0, 1.0)),
            _ => current,
        }
    }
}

/// A number no other world of this process has: a clone gets a new one.
#[derive(Debug, PartialEq, Eq)]
pub(crate) struct Instance(pub(crate) u64);

impl Instance {
    fn new() -> Self {
        static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);
        Self(NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed))
    }
}

impl Clone for Instance {
    fn clone(&self) -> Self {
        Self::new()
    }
}

/// The forces of a step, constants hoisted out of the body loop.
pub(crate) fn step_forces<'a>(
    settings: &WorldSettings,
    custom: &'a [Arc<dyn ForceModel>],
    game_friction: bool,
) -> Forces<'a> {
    Forces::new(
        Drive::new(&settings.forces, custom),
        Dissipation::new(&settings.forces, game_friction),
        settings.force_form,
        settings.integrator,
    )
}

pub(crate) mod chains;
mod tiles;

#[cfg(test)]
mod tests;
