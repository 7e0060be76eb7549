//! The world: owns every body, runs the step stage by stage.

use crate::body::{
    BodyMeta, DynamicBodies, SpeedLimits, StaticBodies, check_max_speed, flush_subnormal,
};
use crate::constants::{DEFAULT_MAX_SPEED, DEFAULT_MIN_SPEED};
use crate::contact::{ContactWorld, StepParams};
use crate::error::{finite_vec, non_negative};
use crate::forces::{BodyParams, Dissipation, Drive, potential_energy};
use crate::integrator::{Forces, integrate_body};
use crate::kernel::PointMassKernel;
use crate::parallel::{chunks2, chunks3};
use crate::sleep::wake_all;
use crate::solver::{self, SolverBodies};
use crate::{
    Body, BodyDef, BodyId, BodyKind, ContactSettings, ForceForm, ForceModel, ForceModels,
    Integrator, PhysicsError,
};
use glam::Vec2;
use std::sync::Arc;

/// How a world steps. Start from [`Default`] and change what differs.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct WorldSettings {
    /// The force models the world evaluates. Default: gravity only.
    pub forces: ForceModels,
    /// Time-stepping method. Default [`Integrator::SemiImplicitEuler`].
    pub integrator: Integrator,
    /// Stable or plain explicit drag and friction (Euler methods only).
    /// Default [`ForceForm::Stable`].
    pub force_form: ForceForm,
    /// Below this speed, metres per second, a velocity becomes exactly zero.
    /// >= 0; 0 turns the snap off. Default 0.001 ([`DEFAULT_MIN_SPEED`]).
    pub min_speed: f32,
    /// Velocities are clamped to this speed, metres per second. > 0;
    /// `f32::INFINITY` turns the clamp off. Default 1000 ([`DEFAULT_MAX_SPEED`]).
    pub max_speed: f32,
    /// Keep each body's position from before the last step, so a renderer
    /// can draw [`World::interpolated_position`]. Costs one copy of the
    /// positions per step. Default `false`.
    pub interpolation: bool,
    /// How contacts between shaped bodies are solved; `None` turns
    /// collisions off. Default `Some(ContactSettings::default())`. The
    /// contact stage runs only while the world holds a shaped dynamic body
    /// and another shaped body; it then advances in
    /// [`ContactSettings::substeps`] substeps.
    pub contacts: Option<ContactSettings>,
}

impl Default for WorldSettings {
    fn default() -> Self {
        Self {
            forces: ForceModels::default(),
            integrator: Integrator::default(),
            force_form: ForceForm::default(),
            min_speed: DEFAULT_MIN_SPEED,
            max_speed: DEFAULT_MAX_SPEED,
            interpolation: false,
            contacts: Some(ContactSettings::default()),
        }
    }
}

impl WorldSettings {
    /// Checks every value, naming the first one that is wrong.
    pub fn validate(&self) -> Result<(), PhysicsError> {
        self.forces.validate()?;
        non_negative("WorldSettings::min_speed", self.min_speed)?;
        check_max_speed("WorldSettings::max_speed", self.max_speed)?;
        if let Some(contacts) = &self.contacts {
            contacts.validate()?;
        }
        Ok(())
    }
}

/// One stage of [`World::step`]. A world runs only the stages its settings
/// and bodies ask for; [`World::active_stages`] lists them in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Stage {
    /// Copy positions for interpolation.
    StorePrevious,
    /// Weight `m g`.
    Gravity,
    /// Constant force field.
    ForceField,
    /// Spring to an anchor.
    Spring,
    /// Central (orbital) gravity.
    CentralGravity,
    /// The game's own [`ForceModel`]s.
    CustomForces,
    /// Quadratic drag.
    QuadraticDrag,
    /// Linear drag.
    LinearDrag,
    /// Top-down surface friction.
    SurfaceFriction,
    /// Integration of velocities and positions with the given method.
    Integrate(Integrator),
    /// Broad phase, narrow phase and the contact solver.
    Contacts,
    /// Minimum-speed snap and maximum-speed clamp.
    SpeedLimits,
}

/// Counters the world keeps across steps.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct StepStats {
    /// Steps taken since the world was made.
    pub steps: u64,
    /// Body-steps in which a force produced a non-finite velocity (a custom
    /// model returning NaN, or an overflow from an enormous force on a tiny
    /// mass). That step's motion is dropped: the body's velocity becomes
    /// zero and it stays where it was, so the world never stores a NaN.
    pub non_finite_resets: u64,
}

/// Where a live body's data sits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) enum Location {
    Dynamic(u32),
    Static(u32),
    Free,
}

#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Slot {
    pub(crate) generation: u32,
    pub(crate) location: Location,
}

/// A 2D physics world: bodies in packed arrays, force models, an integrator.
///
/// ```
/// use passo_physics::{BodyDef, World, glam::Vec2};
///
/// let mut world = World::default(); // gravity (0, -9.81) m/s²
/// let ball = world.add_body(BodyDef::dynamic(Vec2::new(0.0, 10.0))).unwrap();
/// for _ in 0..60 {
///     world.step(1.0 / 60.0);
/// }
/// let y = world.body(ball).unwrap().position.y;
/// assert!((y - (10.0 - 0.5 * 9.81 - 0.5 * 9.81 / 60.0)).abs() < 1e-4);
/// ```
#[derive(Clone)]
pub struct World {
    settings: WorldSettings,
    pub(crate) custom: Vec<Arc<dyn ForceModel>>,
    pub(crate) slots: Vec<Slot>,
    pub(crate) free: Vec<u32>,
    pub(crate) dynamic: DynamicBodies,
    pub(crate) statics: StaticBodies,
    /// Number of dynamic bodies with their own speed limits.
    pub(crate) speed_overrides: usize,
    /// Whether game code applied friction since the last step.
    pub(crate) game_friction: bool,
    /// Shaped bodies of each kind: the contact stage runs only with some.
    pub(crate) shaped_dynamic: usize,
    pub(crate) shaped_static: usize,
    /// Static bodies were added, removed or moved since the last step.
    pub(crate) statics_dirty: bool,
    /// The contact stage's state, made the first time it runs.
    pub(crate) contacts: Option<Box<ContactWorld>>,
    /// Position corrections of the multi-stage integrators, with contacts.
    correction: Vec<Vec2>,
    /// Large worlds may run stages on rayon's pool (`parallel` feature).
    parallel: bool,
    pub(crate) stats: StepStats,
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
            speed_overrides: 0,
            game_friction: false,
            shaped_dynamic: 0,
            shaped_static: 0,
            statics_dirty: false,
            contacts: None,
            correction: Vec::new(),
            parallel: true,
            stats: StepStats::default(),
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
        self.wake_all();
        let limits_changed = settings.min_speed != self.settings.min_speed
            || settings.max_speed != self.settings.max_speed;
        self.settings = settings;
        if limits_changed {
            for i in 0..self.dynamic.len() {
                self.dynamic.limits[i] = self.resolve_limits(&self.dynamic.meta[i]);
            }
        }
        if settings.interpolation {
            if self.dynamic.prev_pos.len() != self.dynamic.len() {
                self.dynamic.prev_pos.clone_from(&self.dynamic.pos);
            }
        } else {
            self.dynamic.prev_pos = Vec::new();
        }
        Ok(())
    }

    /// Adds a force model of the game's own; it acts on every dynamic body.
    pub fn add_force_model(&mut self, model: Arc<dyn ForceModel>) {
        self.wake_all();
        self.custom.push(model);
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
            Location::Dynamic(i) => Some(self.dynamic.sleep[i as usize].is_asleep()),
            _ => Some(false),
        }
    }

    /// Number of sleeping bodies.
    pub fn sleeping_len(&self) -> usize {
        self.dynamic.sleep.iter().filter(|s| s.is_asleep()).count()
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
        match &mut self.contacts {
            Some(cw) => cw.wake_all(&mut self.dynamic),
            None => wake_all(&mut self.dynamic),
        }
    }

    fn wake_index(&mut self, i: usize) {
        if let Some(cw) = &mut self.contacts {
            cw.wake_body(&mut self.dynamic, i);
        }
    }

    /// A body changed: a dynamic one wakes its island; a static one may
    /// have held anything up, so every body wakes.
    fn wake_after_change(&mut self, location: Location) {
        match location {
            Location::Dynamic(i) => self.wake_index(i as usize),
            Location::Static(_) => self.wake_all(),
            Location::Free => {}
        }
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
        def.validate()?;
        let index = match self.free.pop() {
            Some(index) => index,
            None => {
                let index = u32::try_from(self.slots.len()).expect("more than u32::MAX bodies");
                self.slots.push(Slot {
                    generation: 0,
                    location: Location::Free,
                });
                index
            }
        };
        self.count_shape(def.kind, def.shape.is_some(), 1);
        let slot = &mut self.slots[index as usize];
        let id = BodyId {
            index,
            generation: slot.generation,
        };
        let meta = BodyMeta {
            id,
            mass: if def.kind == BodyKind::Dynamic {
                def.mass
            } else {
                f32::INFINITY
            },
            shape: def.shape,
            drag_area: def.drag_area,
            restitution: def.restitution,
            filter: def.filter,
            sensor: def.sensor,
            min_speed: def.min_speed,
            max_speed: def.max_speed,
            user_data: def.user_data,
        };
        match def.kind {
            BodyKind::Dynamic => {
                slot.location = Location::Dynamic(self.dynamic.len() as u32);
                let limits = self.resolve_limits(&meta);
                if def.min_speed.is_some() || def.max_speed.is_some() {
                    self.speed_overrides += 1;
                }
                self.dynamic
                    .push(&def, meta, limits, self.settings.interpolation);
            }
            BodyKind::Static => {
                slot.location = Location::Static(self.statics.len() as u32);
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
        let body = self.view(location);
        self.count_shape(body.kind, body.shape.is_some(), -1);
        let moved = match location {
            Location::Dynamic(i) => {
                let meta = &self.dynamic.meta[i as usize];
                if meta.min_speed.is_some() || meta.max_speed.is_some() {
                    self.speed_overrides -= 1;
                }
                // What rested on it must fall.
                self.wake_index(i as usize);
                let last = self.dynamic.len() as u32 - 1;
                if let Some(cw) = &mut self.contacts {
                    cw.body_moved(last, i);
                }
                self.dynamic.swap_remove(i as usize)
            }
            Location::Static(i) => {
                self.statics_dirty = true;
                self.wake_all();
                self.statics.swap_remove(i as usize)
            }
            Location::Free => unreachable!("locate never returns a free slot"),
        };
        if let Some(moved) = moved {
            self.slots[moved.index as usize].location = location;
        }
        let slot = &mut self.slots[id.index as usize];
        slot.location = Location::Free;
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
            .filter(|s| s.location != Location::Free)
            .map(|s| self.view(s.location))
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

    /// Moves a body (a teleport: no velocity is implied, and an interpolated
    /// drawing jumps too).
    pub fn set_position(&mut self, id: BodyId, position: Vec2) -> Result<(), PhysicsError> {
        finite_vec("position", position)?;
        let location = self.locate(id).ok_or(PhysicsError::StaleBody(id))?;
        match location {
            Location::Dynamic(i) => {
                self.dynamic.pos[i as usize] = position;
                if let Some(prev) = self.dynamic.prev_pos.get_mut(i as usize) {
                    *prev = position;
                }
            }
            Location::Static(i) => {
                self.statics.pos[i as usize] = position;
                self.statics_dirty = true;
            }
            Location::Free => unreachable!(),
        }
        self.wake_after_change(location);
        Ok(())
    }

    /// Sets a body's velocity, metres per second. Ignored for static bodies.
    pub fn set_velocity(&mut self, id: BodyId, velocity: Vec2) -> Result<(), PhysicsError> {
        finite_vec("velocity", velocity)?;
        if let Some(i) = self.dynamic_index(id)? {
            self.dynamic.vel[i] = velocity;
            self.wake_index(i);
        }
        Ok(())
    }

    /// Adds a force, newtons, to the body's accumulator for the next step
    /// (acceleration = F / m). Forces are cleared after each step. Ignored
    /// for static bodies.
    pub fn apply_force(&mut self, id: BodyId, force: Vec2) -> Result<(), PhysicsError> {
        finite_vec("force", force)?;
        if let Some(i) = self.dynamic_index(id)? {
            self.dynamic.force[i] += force;
            self.wake_index(i);
        }
        Ok(())
    }

    /// Changes the body's velocity now by `impulse / m` (impulse in newton
    /// seconds): a jump, a hit. Ignored for static bodies.
    pub fn apply_impulse(&mut self, id: BodyId, impulse: Vec2) -> Result<(), PhysicsError> {
        finite_vec("impulse", impulse)?;
        if let Some(i) = self.dynamic_index(id)? {
            self.dynamic.vel[i] += impulse * self.dynamic.inv_mass[i];
            self.wake_index(i);
        }
        Ok(())
    }

    /// Applies kinetic friction `-mu |N| v_hat` for the next step, with the
    /// normal force magnitude `normal` in newtons (the seed's
    /// `ApplyFriction(mu, N)`). With [`ForceForm::Stable`] it slows the body
    /// by at most its speed: it stops, never reverses. Accumulates like a
    /// force and is cleared after each step. Ignored for static bodies.
    pub fn apply_friction(&mut self, id: BodyId, mu: f32, normal: f32) -> Result<(), PhysicsError> {
        non_negative("mu", mu)?;
        crate::error::finite("normal", normal)?;
        if let Some(i) = self.dynamic_index(id)? {
            self.dynamic.friction_force[i] += mu * normal.abs();
            self.wake_index(i);
            self.game_friction = true;
        }
        Ok(())
    }

    /// Sets a body's friction coefficient `mu` (>= 0), for surface friction
    /// and contacts.
    pub fn set_friction(&mut self, id: BodyId, mu: f32) -> Result<(), PhysicsError> {
        non_negative("friction", mu)?;
        let location = self.locate(id).ok_or(PhysicsError::StaleBody(id))?;
        match location {
            Location::Dynamic(i) => self.dynamic.friction[i as usize] = mu,
            Location::Static(i) => self.statics.friction[i as usize] = mu,
            Location::Free => unreachable!(),
        }
        self.wake_after_change(location);
        Ok(())
    }

    /// Sets a body's restitution, in `[0, 1]`.
    pub fn set_restitution(&mut self, id: BodyId, restitution: f32) -> Result<(), PhysicsError> {
        non_negative("restitution", restitution)?;
        if restitution > 1.0 {
            return Err(PhysicsError::OutOfRange {
                what: "restitution",
                value: restitution,
                allowed: "in [0, 1]",
            });
        }
        let location = self.locate(id).ok_or(PhysicsError::StaleBody(id))?;
        match location {
            Location::Dynamic(i) => self.dynamic.meta[i as usize].restitution = restitution,
            Location::Static(i) => self.statics.meta[i as usize].restitution = restitution,
            Location::Free => unreachable!(),
        }
        self.wake_after_change(location);
        Ok(())
    }

    /// Sets a body's drag area `Cd A`, square metres (>= 0): a glider
    /// opening its wings.
    pub fn set_drag_area(&mut self, id: BodyId, drag_area: f32) -> Result<(), PhysicsError> {
        non_negative("drag_area", drag_area)?;
        match self.locate(id).ok_or(PhysicsError::StaleBody(id))? {
            Location::Dynamic(i) => {
                self.dynamic.drag_area[i as usize] = drag_area;
                self.dynamic.meta[i as usize].drag_area = drag_area;
                self.wake_index(i as usize);
            }
            Location::Static(i) => self.statics.meta[i as usize].drag_area = drag_area,
            Location::Free => unreachable!(),
        }
        Ok(())
    }

    /// Where to draw a body between the last two steps: `lerp(previous,
    /// current, alpha)` with `alpha` in `[0, 1]` (clamped). Without
    /// [`WorldSettings::interpolation`] this is the current position.
    pub fn interpolated_position(&self, id: BodyId, alpha: f32) -> Option<Vec2> {
        Some(match self.locate(id)? {
            Location::Dynamic(i) => self.lerp_dynamic(i as usize, alpha),
            Location::Static(i) => self.statics.pos[i as usize],
            Location::Free => unreachable!(),
        })
    }

    // ----- diagnostics -----

    /// The force the world's force models exert on a body in its current
    /// state, newtons: weight, drag, friction, fields, springs, custom
    /// models, in their plain form (not the forces game code applied). For
    /// drawing force vectors; zero for a static body.
    pub fn model_force(&self, id: BodyId) -> Option<Vec2> {
        let i = match self.locate(id)? {
            Location::Dynamic(i) => i as usize,
            _ => return Some(Vec2::ZERO),
        };
        let b = &self.dynamic;
        let params = BodyParams {
            inv_mass: b.inv_mass[i],
            force: Vec2::ZERO,
            drag_area: b.drag_area[i],
            friction: b.friction[i],
            friction_force: 0.0,
        };
        let drive = Drive::new(&self.settings.forces, &self.custom);
        let dissipation = Dissipation::new(&self.settings.forces, false);
        let a = drive.accel(b.pos[i], b.vel[i], &params) + dissipation.accel(b.vel[i], &params);
        Some(a * b.meta[i].mass)
    }

    /// Kinetic energy `sum 1/2 m |v|^2`, joules (summed in f64, in storage order).
    pub fn kinetic_energy(&self) -> f64 {
        (0..self.dynamic.len())
            .map(|i| {
                0.5 * f64::from(self.dynamic.meta[i].mass)
                    * f64::from(self.dynamic.vel[i].length_squared())
            })
            .sum()
    }

    /// Potential energy of the conservative force models, joules: gravity
    /// (`-m g . p`, zero at the origin), the force field, the spring,
    /// central gravity and custom models.
    pub fn potential_energy(&self) -> f64 {
        (0..self.dynamic.len())
            .map(|i| {
                potential_energy(
                    &self.settings.forces,
                    &self.custom,
                    self.dynamic.pos[i],
                    self.dynamic.meta[i].mass,
                )
            })
            .sum()
    }

    /// Kinetic plus potential energy, joules.
    pub fn total_energy(&self) -> f64 {
        self.kinetic_energy() + self.potential_energy()
    }

    /// Linear momentum `sum m v`, kilogram metres per second (f64).
    pub fn momentum(&self) -> [f64; 2] {
        let mut p = [0.0f64; 2];
        for i in 0..self.dynamic.len() {
            let m = f64::from(self.dynamic.meta[i].mass);
            p[0] += m * f64::from(self.dynamic.vel[i].x);
            p[1] += m * f64::from(self.dynamic.vel[i].y);
        }
        p
    }

    /// A 64-bit FNV-1a hash of every body's position and velocity bits, in
    /// id order. Equal states give equal hashes on every platform; use it to
    /// check determinism.
    pub fn state_hash(&self) -> u64 {
        const PRIME: u64 = 0x0000_0100_0000_01b3;
        let mut h: u64 = 0xcbf2_9ce4_8422_2325;
        let mut eat = |word: u32| {
            for byte in word.to_le_bytes() {
                h = (h ^ u64::from(byte)).wrapping_mul(PRIME);
            }
        };
        for b in self.bodies() {
            for x in [b.position.x, b.position.y, b.velocity.x, b.velocity.y] {
                eat(x.to_bits());
            }
        }
        h
    }

    /// The stages [`step`](Self::step) runs with the current settings and
    /// bodies, in order.
    pub fn active_stages(&self) -> Vec<Stage> {
        let f = &self.settings.forces;
        let mut stages = Vec::new();
        if self.settings.interpolation {
            stages.push(Stage::StorePrevious);
        }
        let models = [
            (f.gravity.is_some(), Stage::Gravity),
            (f.force_field.is_some(), Stage::ForceField),
            (f.spring.is_some(), Stage::Spring),
            (f.central_gravity.is_some(), Stage::CentralGravity),
            (!self.custom.is_empty(), Stage::CustomForces),
            (f.quadratic_drag.is_some(), Stage::QuadraticDrag),
            (f.linear_drag.is_some(), Stage::LinearDrag),
            (f.surface_friction.is_some(), Stage::SurfaceFriction),
        ];
        stages.extend(models.iter().filter(|(on, _)| *on).map(|(_, s)| *s));
        stages.push(Stage::Integrate(self.settings.integrator));
        if self.contact_settings().is_some() {
            stages.push(Stage::Contacts);
        }
        if self.has_speed_limits() {
            stages.push(Stage::SpeedLimits);
        }
        stages
    }

    // ----- the step -----

    /// Advances the world by `dt` seconds, stage by stage; each stage runs
    /// only if the settings and bodies ask for it ([`active_stages`](Self::active_stages)):
    ///
    /// 1. store previous positions (interpolation);
    /// 2. without contacts, one pass per body: integrate velocity with every
    ///    active force model, clamp speed, integrate position;
    /// 3. with contacts, broad and narrow phase, then `substeps` times:
    ///    integrate velocities, warm start, solve contacts, clamp speeds,
    ///    integrate positions, relax; then restitution and a last clamp;
    /// 4. clear force accumulators.
    ///
    /// Run it from a fixed-timestep loop (`passo-loop`) with a constant `dt`:
    /// a variable `dt` makes the result depend on the frame rate.
    ///
    /// # Panics
    /// If `dt` is not finite and > 0: a zero, negative or NaN timestep is a
    /// programming error, not a state the world can be in.
    pub fn step(&mut self, dt: f32) {
        assert!(
            dt.is_finite() && dt > 0.0,
            "World::step: dt must be finite and > 0 seconds, got {dt}"
        );
        self.store_previous_positions();
        match self.contact_settings() {
            Some(contacts) => self.step_with_contacts(dt, &contacts),
            None => {
                // Sleeping belongs to the contact stage: without it, no body
                // sleeps (the idle step wakes them all).
                if let Some(cw) = &mut self.contacts {
                    cw.idle_step(&mut self.dynamic, &self.statics);
                }
                self.step_bodies(dt);
            }
        }
        self.clear_forces();
        self.stats.steps += 1;
    }

    fn store_previous_positions(&mut self) {
        if self.settings.interpolation {
            self.dynamic.prev_pos.copy_from_slice(&self.dynamic.pos);
        }
    }

    /// The contact settings if the contact stage runs: contacts are on, a
    /// shaped dynamic body exists and something else is shaped.
    fn contact_settings(&self) -> Option<ContactSettings> {
        let contacts = self.settings.contacts?;
        (self.shaped_dynamic > 0 && self.shaped_dynamic + self.shaped_static >= 2)
            .then_some(contacts)
    }

    fn speed_limits(&self) -> Option<Option<SpeedLimits>> {
        self.has_speed_limits()
            .then(|| (self.speed_overrides == 0).then(|| self.world_limits()))
    }

    /// Integrates velocities, clamps speeds and moves bodies, one body at a
    /// time: a single pass over the arrays.
    fn step_bodies(&mut self, dt: f32) {
        let integrator = self.settings.integrator;
        let limits = self.speed_limits();
        let kernel = PointMassKernel::new(
            &self.settings.forces,
            integrator,
            self.settings.force_form,
            !self.custom.is_empty() || self.game_friction,
            limits,
        );
        if let Some(kernel) = kernel {
            self.stats.non_finite_resets += kernel.run(&mut self.dynamic, dt, self.parallel);
            return;
        }
        let forces = forces(&self.settings, &self.custom, self.game_friction);
        let (pos, vel, arrays) = self.dynamic.split();
        let resets = chunks2(self.parallel, pos, vel, |offset, pos, vel| {
            let mut resets = 0;
            for (k, (p, v)) in pos.iter_mut().zip(vel.iter_mut()).enumerate() {
                let i = offset + k;
                let (mut nv, c) = integrate_velocity(
                    integrator,
                    &forces,
                    *p,
                    *v,
                    &arrays.params(i),
                    dt,
                    &mut resets,
                );
                if let Some(uniform) = limits {
                    uniform.unwrap_or(arrays.limits[i]).apply(&mut nv);
                }
                *v = nv;
                *p += nv * dt + c;
            }
            resets
        });
        self.stats.non_finite_resets += resets;
    }

    // Structure of arrays: one index walks several slices at once.
    #[allow(clippy::needless_range_loop)]
    fn step_with_contacts(&mut self, dt: f32, settings: &ContactSettings) {
        let substeps = settings.substeps;
        let h = dt / substeps as f32;
        let gravity = self.settings.forces.gravity.unwrap_or(Vec2::ZERO);
        let mut cw = self
            .contacts
            .take()
            .unwrap_or_else(|| Box::new(ContactWorld::new()));
        if self.statics_dirty {
            cw.statics_changed();
            self.statics_dirty = false;
        }
        let parallel = self.parallel;
        let params = StepParams {
            gravity,
            dt,
            h,
            parallel,
        };
        if !settings.sleeping {
            cw.wake_all(&mut self.dynamic);
        }
        cw.begin_step(&mut self.dynamic, &self.statics, settings, &params);
        let any_asleep = !cw.asleep.is_empty() || self.dynamic.sleep.iter().any(|s| s.is_asleep());
        // With every body asleep nothing moves: the substeps would only
        // confirm it.
        let substeps = if any_asleep && self.dynamic.sleep.iter().all(|s| s.is_asleep()) {
            0
        } else {
            substeps
        };
        let integrator = self.settings.integrator;
        let limits = self.speed_limits();
        let mut resets = 0;
        let mut correction = std::mem::take(&mut self.correction);
        let corrects = integrator != Integrator::SemiImplicitEuler;
        // Zero for semi-implicit Euler; sized for every body so per-body
        // loops can walk it beside the velocities.
        correction.clear();
        correction.resize(self.dynamic.len(), Vec2::ZERO);
        // Only contacts with an awake body are solved (sleeping ones wait
        // in `cw.asleep`).
        let ContactWorld {
            constraints: solved,
            infos: solved_infos,
            start,
            delta,
            push,
            ..
        } = &mut *cw;
        // The velocity update of the common case needs no general path.
        let kernel = PointMassKernel::new(
            &self.settings.forces,
            integrator,
            self.settings.force_form,
            !self.custom.is_empty() || self.game_friction,
            None,
        );
        for _ in 0..substeps {
            // Integrate velocities.
            let b = &mut self.dynamic;
            if let Some(kernel) = &kernel {
                resets += kernel.velocities(b, h, parallel);
            } else {
                let forces = forces(&self.settings, &self.custom, self.game_friction);
                let (pos, vel, arrays) = b.split();
                let pos: &[Vec2] = pos;
                resets += chunks2(parallel, vel, &mut correction, |offset, vel, correction| {
                    let mut resets = 0;
                    for (k, (v, c)) in vel.iter_mut().zip(correction.iter_mut()).enumerate() {
                        let i = offset + k;
                        (*v, *c) = integrate_velocity(
                            integrator,
                            &forces,
                            pos[i],
                            *v,
                            &arrays.params(i),
                            h,
                            &mut resets,
                        );
                    }
                    resets
                });
            }
            if any_asleep {
                // Sleeping bodies hold still: no forces, no correction.
                for ((v, c), s) in b.vel.iter_mut().zip(&mut correction).zip(&b.sleep) {
                    if s.is_asleep() {
                        (*v, *c) = (Vec2::ZERO, Vec2::ZERO);
                    }
                }
            }
            // Warm start and solve contacts.
            push.fill(Vec2::ZERO);
            let mut bodies = SolverBodies {
                vel: &mut b.vel,
                push,
                delta,
            };
            solver::begin_substep(solved, &mut bodies, settings.warm_starting);
            for _ in 0..settings.iterations {
                solver::solve(solved, &mut bodies, settings, h, true);
            }
            // Clamp speeds and integrate positions, pushed apart where overlapping.
            {
                let (pos, vel, arrays) = b.split();
                let (push, start, correction): (&[Vec2], &[Vec2], &[Vec2]) =
                    (push, start, &correction);
                chunks3(parallel, pos, vel, delta, |offset, pos, vel, delta| {
                    for (k, ((p, v), d)) in pos
                        .iter_mut()
                        .zip(vel.iter_mut())
                        .zip(delta.iter_mut())
                        .enumerate()
                    {
                        let i = offset + k;
                        if let Some(uniform) = limits {
                            uniform.unwrap_or(arrays.limits[i]).apply(v);
                        }
                        let c = if corrects { correction[i] } else { Vec2::ZERO };
                        *p += (*v + push[i]) * h + c;
                        *d = *p - start[i];
                    }
                    0
                });
            }
            // Relax: velocity iterations at the new positions.
            let mut bodies = SolverBodies {
                vel: &mut b.vel,
                push,
                delta,
            };
            for _ in 0..settings.relax_iterations {
                solver::solve(solved, &mut bodies, settings, h, false);
            }
        }
        let b = &mut self.dynamic;
        let mut bodies = SolverBodies {
            vel: &mut b.vel,
            push,
            delta,
        };
        solver::restitution(
            solved,
            solved_infos,
            &mut bodies,
            settings.restitution_threshold,
        );
        solver::store_separations(solved, solved_infos, &bodies);
        if let Some(uniform) = limits {
            for i in 0..b.vel.len() {
                uniform.unwrap_or(b.limits[i]).apply(&mut b.vel[i]);
            }
        }

        cw.end_step(
            &mut self.dynamic,
            &self.statics,
            settings.sleeping.then_some(dt),
        );
        self.contacts = Some(cw);
        self.correction = correction;
        self.stats.non_finite_resets += resets;
    }

    fn clear_forces(&mut self) {
        self.dynamic.force.fill(Vec2::ZERO);
        if self.game_friction {
            self.dynamic.friction_force.fill(0.0);
            self.game_friction = false;
        }
    }

    // ----- helpers -----

    fn count_shape(&mut self, kind: BodyKind, shaped: bool, delta: isize) {
        if shaped {
            let count = match kind {
                BodyKind::Dynamic => &mut self.shaped_dynamic,
                BodyKind::Static => &mut self.shaped_static,
            };
            *count = count
                .checked_add_signed(delta)
                .expect("shape count underflow");
        }
    }

    fn world_limits(&self) -> SpeedLimits {
        SpeedLimits::new(self.settings.min_speed, self.settings.max_speed)
    }

    fn resolve_limits(&self, meta: &BodyMeta) -> SpeedLimits {
        SpeedLimits::new(
            meta.min_speed.unwrap_or(self.settings.min_speed),
            meta.max_speed.unwrap_or(self.settings.max_speed),
        )
    }

    fn has_speed_limits(&self) -> bool {
        self.speed_overrides > 0
            || self.settings.min_speed > 0.0
            || self.settings.max_speed < f32::INFINITY
    }

    fn locate(&self, id: BodyId) -> Option<Location> {
        let slot = self.slots.get(id.index as usize)?;
        (slot.generation == id.generation && slot.location != Location::Free)
            .then_some(slot.location)
    }

    /// The array index of a dynamic body, `None` for a static one.
    fn dynamic_index(&self, id: BodyId) -> Result<Option<usize>, PhysicsError> {
        match self.locate(id).ok_or(PhysicsError::StaleBody(id))? {
            Location::Dynamic(i) => Ok(Some(i as usize)),
            _ => Ok(None),
        }
    }

    fn view(&self, location: Location) -> Body {
        match location {
            Location::Dynamic(i) => self.dynamic.view(i as usize),
            Location::Static(i) => self.statics.view(i as usize),
            Location::Free => unreachable!("a free slot has no body"),
        }
    }

    fn lerp_dynamic(&self, i: usize, alpha: f32) -> Vec2 {
        let current = self.dynamic.pos[i];
        match self.dynamic.prev_pos.get(i) {
            Some(prev) => prev.lerp(current, alpha.clamp(0.0, 1.0)),
            None => current,
        }
    }
}

/// The forces of a step, constants hoisted out of the body loop.
fn forces<'a>(
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

/// One body's new velocity and position correction over `h`. A non-finite
/// result (a broken custom force, an overflow) drops the body's motion for
/// this step and counts a reset.
#[inline(always)]
fn integrate_velocity(
    integrator: Integrator,
    forces: &Forces<'_>,
    p: Vec2,
    v: Vec2,
    params: &BodyParams,
    h: f32,
    resets: &mut u64,
) -> (Vec2, Vec2) {
    let (v, c) = integrate_body(integrator, forces, p, v, params, h);
    guard_finite(v, c, resets)
}

/// Drops a step that produced a non-finite velocity or correction, or a
/// speed whose square overflows `f32` (over 1.8e19 m/s): the body stays
/// where it was with zero velocity, and the reset is counted. Subnormal
/// velocity components are flushed to zero.
#[inline(always)]
fn guard_finite(v: Vec2, c: Vec2, resets: &mut u64) -> (Vec2, Vec2) {
    if v.length_squared().is_finite() && c.is_finite() {
        (flush_subnormal(v), c)
    } else {
        *resets += 1;
        (Vec2::ZERO, Vec2::ZERO)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{CentralGravity, QuadraticDrag, Shape};

    fn ball(x: f32) -> BodyDef {
        BodyDef::dynamic(Vec2::new(x, 0.0))
    }

    #[test]
    fn removed_ids_never_reach_the_body_that_reuses_the_slot() {
        let mut world = World::default();
        let a = world.add_body(ball(1.0)).unwrap();
        let b = world.add_body(ball(2.0)).unwrap();
        let removed = world.remove_body(a).unwrap();
        assert_eq!(removed.position.x, 1.0);
        let c = world.add_body(ball(3.0)).unwrap();
        assert_eq!(c.index(), a.index(), "the slot is reused");
        assert_ne!(c, a);
        assert_eq!(world.body(a), None);
        assert!(world.remove_body(a).is_none());
        assert_eq!(
            world.set_velocity(a, Vec2::ONE),
            Err(PhysicsError::StaleBody(a))
        );
        assert_eq!(world.body(b).unwrap().position.x, 2.0);
        assert_eq!(world.body(c).unwrap().position.x, 3.0);
        assert_eq!(world.len(), 2);
    }

    #[test]
    fn swap_remove_keeps_every_other_id_pointing_at_its_body() {
        let mut world = World::default();
        let ids: Vec<_> = (0..10)
            .map(|i| world.add_body(ball(i as f32)).unwrap())
            .collect();
        for &id in ids.iter().step_by(3) {
            world.remove_body(id).unwrap();
        }
        for (i, &id) in ids.iter().enumerate() {
            match world.body(id) {
                Some(b) => assert_eq!(b.position.x, i as f32),
                None => assert_eq!(i % 3, 0),
            }
        }
        let order: Vec<_> = world.bodies().map(|b| b.position.x).collect();
        assert_eq!(
            order,
            [1.0, 2.0, 4.0, 5.0, 7.0, 8.0],
            "bodies() is in id order"
        );
    }

    #[test]
    fn forces_accumulate_and_are_cleared_after_each_step() {
        let mut world = World::new(WorldSettings {
            forces: ForceModels::none(),
            min_speed: 0.0,
            ..Default::default()
        })
        .unwrap();
        let id = world
            .add_body(BodyDef {
                mass: 2.0,
                ..Default::default()
            })
            .unwrap();
        world.apply_force(id, Vec2::new(1.0, 0.0)).unwrap();
        world.apply_force(id, Vec2::new(3.0, 2.0)).unwrap();
        assert_eq!(world.body(id).unwrap().force, Vec2::new(4.0, 2.0));
        world.step(0.5);
        // a = F / m = (2, 1); v = a dt.
        assert_eq!(world.body(id).unwrap().velocity, Vec2::new(1.0, 0.5));
        assert_eq!(world.body(id).unwrap().force, Vec2::ZERO);
        world.step(0.5);
        assert_eq!(world.body(id).unwrap().velocity, Vec2::new(1.0, 0.5));
    }

    #[test]
    fn impulse_changes_velocity_by_j_over_m() {
        let mut world = World::default();
        let id = world
            .add_body(BodyDef {
                mass: 4.0,
                ..Default::default()
            })
            .unwrap();
        world.apply_impulse(id, Vec2::new(2.0, 8.0)).unwrap();
        assert_eq!(world.body(id).unwrap().velocity, Vec2::new(0.5, 2.0));
    }

    #[test]
    fn static_bodies_never_move_and_ignore_forces() {
        let mut world = World::default();
        let ground = world
            .add_body(BodyDef::fixed(Vec2::new(0.0, -1.0), Shape::rect(10.0, 1.0)))
            .unwrap();
        world.apply_force(ground, Vec2::new(1e6, 1e6)).unwrap();
        world.apply_impulse(ground, Vec2::new(1e6, 1e6)).unwrap();
        world.set_velocity(ground, Vec2::new(5.0, 5.0)).unwrap();
        for _ in 0..100 {
            world.step(1.0 / 60.0);
        }
        let b = world.body(ground).unwrap();
        assert_eq!(b.position, Vec2::new(0.0, -1.0));
        assert_eq!(b.velocity, Vec2::ZERO);
        assert_eq!(b.mass, f32::INFINITY);
        assert_eq!(world.kinetic_energy(), 0.0);
    }

    #[test]
    fn bad_body_definitions_are_rejected_with_the_field_named() {
        let mut world = World::default();
        let cases = [
            (
                BodyDef {
                    mass: 0.0,
                    ..ball(0.0)
                },
                "BodyDef::mass must be > 0, got 0",
            ),
            (
                BodyDef {
                    mass: -2.0,
                    ..ball(0.0)
                },
                "BodyDef::mass must be > 0, got -2",
            ),
            (
                BodyDef {
                    mass: f32::NAN,
                    ..ball(0.0)
                },
                "BodyDef::mass must be finite (got NaN or infinity)",
            ),
            (
                BodyDef {
                    position: Vec2::new(f32::INFINITY, 0.0),
                    ..ball(0.0)
                },
                "BodyDef::position must be finite (got NaN or infinity)",
            ),
            (
                BodyDef {
                    velocity: Vec2::new(0.0, f32::NAN),
                    ..ball(0.0)
                },
                "BodyDef::velocity must be finite (got NaN or infinity)",
            ),
            (
                BodyDef {
                    restitution: 1.5,
                    ..ball(0.0)
                },
                "BodyDef::restitution must be in [0, 1], got 1.5",
            ),
            (
                BodyDef {
                    shape: Some(Shape::circle(0.0)),
                    ..ball(0.0)
                },
                "Shape::Circle::radius must be > 0, got 0",
            ),
            (
                BodyDef {
                    max_speed: Some(-1.0),
                    ..ball(0.0)
                },
                "BodyDef::max_speed must be > 0, got -1",
            ),
        ];
        for (def, message) in cases {
            let err = world.add_body(def).unwrap_err();
            assert_eq!(err.to_string(), message);
        }
        assert!(world.is_empty(), "nothing was added");
        // A static body needs no mass.
        let ground = BodyDef {
            mass: 0.0,
            ..BodyDef::fixed(Vec2::ZERO, Shape::circle(1.0))
        };
        assert!(world.add_body(ground).is_ok());
    }

    #[test]
    fn non_finite_forces_and_settings_are_rejected() {
        let mut world = World::default();
        let id = world.add_body(ball(0.0)).unwrap();
        let nan = Vec2::new(f32::NAN, 0.0);
        assert!(world.apply_force(id, nan).is_err());
        assert!(world.apply_impulse(id, nan).is_err());
        assert!(world.set_position(id, nan).is_err());
        assert!(world.set_velocity(id, nan).is_err());
        assert!(world.apply_friction(id, -1.0, 10.0).is_err());
        assert!(world.apply_friction(id, 0.5, f32::INFINITY).is_err());
        let mut bad = WorldSettings::default();
        bad.forces.gravity = Some(nan);
        assert_eq!(
            world.set_settings(bad).unwrap_err().to_string(),
            "ForceModels::gravity must be finite (got NaN or infinity)"
        );
        let bad = WorldSettings {
            min_speed: -1.0,
            ..Default::default()
        };
        assert!(World::new(bad).is_err());
        let mut bad = WorldSettings::default();
        bad.forces.quadratic_drag = Some(QuadraticDrag { density: -1.0 });
        assert!(World::new(bad).is_err());
        assert_eq!(world.body(id).unwrap().force, Vec2::ZERO);
    }

    #[test]
    #[should_panic(expected = "dt must be finite and > 0 seconds, got 0")]
    fn zero_timestep_panics_with_a_clear_message() {
        World::default().step(0.0);
    }

    #[test]
    #[should_panic(expected = "dt must be finite and > 0 seconds, got NaN")]
    fn nan_timestep_panics_with_a_clear_message() {
        World::default().step(f32::NAN);
    }

    struct Broken;
    impl ForceModel for Broken {
        fn force(&self, _: Vec2, _: Vec2, _: f32) -> Vec2 {
            Vec2::new(f32::NAN, 0.0)
        }
    }

    #[test]
    fn a_force_model_returning_nan_never_reaches_the_state() {
        for integrator in Integrator::ALL {
            let mut world = World::new(WorldSettings {
                integrator,
                ..Default::default()
            })
            .unwrap();
            world.add_force_model(Arc::new(Broken));
            let id = world
                .add_body(BodyDef {
                    velocity: Vec2::X,
                    ..ball(2.0)
                })
                .unwrap();
            world.step(0.1);
            let b = world.body(id).unwrap();
            assert_eq!((b.position, b.velocity), (Vec2::new(2.0, 0.0), Vec2::ZERO));
            assert_eq!(world.stats().non_finite_resets, 1);
        }
    }

    #[test]
    fn an_overflowing_force_is_clamped_not_turned_into_nan() {
        let mut world = World::new(WorldSettings {
            forces: ForceModels::none(),
            max_speed: f32::INFINITY,
            ..Default::default()
        })
        .unwrap();
        let id = world
            .add_body(BodyDef {
                mass: 1e-30,
                ..ball(0.0)
            })
            .unwrap();
        world
            .apply_force(id, Vec2::new(f32::MAX, f32::MAX))
            .unwrap();
        world.step(1.0);
        let b = world.body(id).unwrap();
        assert!(b.position.is_finite() && b.velocity.is_finite());
        assert_eq!(world.stats().non_finite_resets, 1);

        // A finite velocity whose square overflows (1e30 m/s) is dropped too.
        let mut world = World::new(WorldSettings {
            forces: ForceModels::none(),
            ..Default::default()
        })
        .unwrap();
        let id = world.add_body(ball(0.0)).unwrap();
        world.apply_force(id, Vec2::new(1e30, 1e30)).unwrap();
        world.step(1.0);
        assert_eq!(world.body(id).unwrap().velocity, Vec2::ZERO);
        assert_eq!(world.stats().non_finite_resets, 1);

        // A large but sane velocity is clamped to exactly the maximum speed.
        let id = world.add_body(ball(0.0)).unwrap();
        world.apply_force(id, Vec2::new(3e6, 4e6)).unwrap();
        world.step(1.0);
        let v = world.body(id).unwrap().velocity;
        assert_eq!(v, Vec2::new(600.0, 800.0));
        assert_eq!(v.length(), DEFAULT_MAX_SPEED);
    }

    #[test]
    fn interpolation_draws_between_the_last_two_positions() {
        let mut world = World::new(WorldSettings {
            forces: ForceModels::none(),
            interpolation: true,
            ..Default::default()
        })
        .unwrap();
        let id = world
            .add_body(BodyDef {
                velocity: Vec2::new(2.0, 0.0),
                ..ball(0.0)
            })
            .unwrap();
        world.step(0.5);
        assert_eq!(world.interpolated_position(id, 0.0), Some(Vec2::ZERO));
        assert_eq!(
            world.interpolated_position(id, 0.5),
            Some(Vec2::new(0.5, 0.0))
        );
        assert_eq!(
            world.interpolated_position(id, 1.0),
            Some(Vec2::new(1.0, 0.0))
        );
        world.set_position(id, Vec2::new(9.0, 0.0)).unwrap();
        assert_eq!(
            world.interpolated_position(id, 0.0),
            Some(Vec2::new(9.0, 0.0))
        );
    }

    #[test]
    fn without_interpolation_no_previous_positions_are_kept() {
        let mut world = World::default();
        world.add_body(ball(0.0)).unwrap();
        world.step(0.1);
        assert!(world.dynamic.prev_pos.is_empty());
        assert!(!world.active_stages().contains(&Stage::StorePrevious));
    }

    #[test]
    fn active_stages_list_only_what_the_settings_ask_for() {
        let world = World::new(WorldSettings {
            max_speed: f32::INFINITY,
            min_speed: 0.0,
            ..Default::default()
        })
        .unwrap();
        assert_eq!(
            world.active_stages(),
            [
                Stage::Gravity,
                Stage::Integrate(Integrator::SemiImplicitEuler)
            ]
        );
        let mut forces = ForceModels::none();
        forces.central_gravity = Some(CentralGravity {
            centre: Vec2::ZERO,
            gm: 1.0,
        });
        forces.quadratic_drag = Some(QuadraticDrag::default());
        let world = World::new(WorldSettings {
            forces,
            integrator: Integrator::Rk4,
            interpolation: true,
            ..Default::default()
        })
        .unwrap();
        assert_eq!(
            world.active_stages(),
            [
                Stage::StorePrevious,
                Stage::CentralGravity,
                Stage::QuadraticDrag,
                Stage::Integrate(Integrator::Rk4),
                Stage::SpeedLimits
            ]
        );
    }

    #[test]
    fn material_setters_check_their_input_and_take_effect() {
        let mut world = World::default();
        let id = world.add_body(ball(0.0)).unwrap();
        world.set_friction(id, 0.1).unwrap();
        world.set_restitution(id, 0.9).unwrap();
        world.set_drag_area(id, 2.0).unwrap();
        let b = world.body(id).unwrap();
        assert_eq!((b.friction, b.restitution, b.drag_area), (0.1, 0.9, 2.0));
        assert!(world.set_friction(id, -1.0).is_err());
        assert!(world.set_restitution(id, 1.1).is_err());
        assert!(world.set_drag_area(id, f32::NAN).is_err());
        let ground = world
            .add_body(BodyDef::fixed(Vec2::ZERO, Shape::circle(1.0)))
            .unwrap();
        world.set_friction(ground, 0.02).unwrap();
        assert_eq!(world.body(ground).unwrap().friction, 0.02);
        world.remove_body(id);
        assert_eq!(
            world.set_friction(id, 0.5),
            Err(PhysicsError::StaleBody(id))
        );
    }

    #[test]
    fn model_force_is_weight_plus_drag() {
        let mut settings = WorldSettings::default();
        settings.forces.quadratic_drag = Some(crate::QuadraticDrag { density: 2.0 });
        let mut world = World::new(settings).unwrap();
        let id = world
            .add_body(BodyDef {
                mass: 3.0,
                velocity: Vec2::new(0.0, -4.0),
                drag_area: 0.5,
                ..Default::default()
            })
            .unwrap();
        // m g = -29.43 N; drag 1/2 rho v^2 CdA = 8 N upward.
        let f = world.model_force(id).unwrap();
        assert!((f - Vec2::new(0.0, -29.43 + 8.0)).length() < 1e-4, "{f}");
        world.apply_force(id, Vec2::new(100.0, 0.0)).unwrap();
        assert_eq!(
            world.model_force(id).unwrap().x,
            0.0,
            "game forces are not included"
        );
    }

    #[test]
    fn energy_and_momentum_diagnostics() {
        let mut world = World::default();
        world
            .add_body(BodyDef {
                mass: 2.0,
                position: Vec2::new(0.0, 10.0),
                velocity: Vec2::new(3.0, 4.0),
                ..Default::default()
            })
            .unwrap();
        assert!((world.kinetic_energy() - 25.0).abs() < 1e-9);
        assert!((world.potential_energy() - 2.0 * 9.81 * 10.0).abs() < 1e-4);
        assert_eq!(world.momentum(), [6.0, 8.0]);
    }

    #[test]
    fn equal_states_hash_equal_and_any_bit_changes_the_hash() {
        let make = |x: f32| {
            let mut w = World::default();
            w.add_body(ball(x)).unwrap();
            w
        };
        assert_eq!(make(1.0).state_hash(), make(1.0).state_hash());
        assert_ne!(
            make(1.0).state_hash(),
            make(f32::from_bits(1.0f32.to_bits() + 1)).state_hash()
        );
    }
}
