//! Contacts: settings, filters, what a game can read about contacts, and
//! the per-step bookkeeping (broad phase, narrow phase, warm starting,
//! begin/end events).

use crate::body::{DynamicBodies, StaticBodies};
use crate::broad_phase::BroadPhase;
use crate::constants::{
    CONTACT_PUSH_SPEED, DEFAULT_SUBSTEPS, LINEAR_SLOP, POSITION_CORRECTION, RESTITUTION_THRESHOLD,
    SPECULATIVE_DISTANCE,
};
use crate::error::{non_negative, positive};
use crate::manifold::collide;
use crate::sleep::{Islands, SleepState};
use crate::solver::{Constraint, ContactInfo, STATIC_BODY};
use crate::static_tree::StaticTree;
use crate::{Aabb, BodyId, PhysicsError, Shape};
use glam::Vec2;

/// How contacts are solved. `WorldSettings::contacts: None` turns the
/// contact stage off altogether.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct ContactSettings {
    /// Substeps per step, >= 1. Default 4 ([`DEFAULT_SUBSTEPS`]).
    pub substeps: u32,
    /// Iterations per substep over every contact (friction, normal, push),
    /// >= 1. Default 2.
    pub iterations: u32,
    /// Velocity iterations per substep after bodies moved ("relax": they see
    /// the new separations), >= 0. Default 1.
    pub relax_iterations: u32,
    /// Fraction of the overlap beyond the slop removed per substep, in
    /// `(0, 1]`. Default 0.2 ([`POSITION_CORRECTION`]).
    pub position_correction: f32,
    /// Cap on the push-apart speed, metres per second, > 0. Default 3.
    pub push_out_speed: f32,
    /// Allowed penetration, metres, >= 0. Default 0.005 ([`LINEAR_SLOP`]).
    pub slop: f32,
    /// Impacts slower than this do not bounce, metres per second, >= 0. Default 1.
    pub restitution_threshold: f32,
    /// Continuous collision: contacts are created ahead of time from each
    /// body's travel this step (speculative contacts), so fast bodies cannot
    /// pass through thin walls. Default `true`.
    pub continuous: bool,
    /// Start each step from the last step's impulses. Default `true`.
    pub warm_starting: bool,
    /// Islands of touching bodies that have all been slower than
    /// [`SLEEP_SPEED`] for [`TIME_TO_SLEEP`] fall asleep: their contacts
    /// are kept but no longer solved, and they cost little until an awake
    /// body reaches them or game code changes one of them. Default `true`.
    ///
    /// [`SLEEP_SPEED`]: crate::constants::SLEEP_SPEED
    /// [`TIME_TO_SLEEP`]: crate::constants::TIME_TO_SLEEP
    pub sleeping: bool,
}

impl Default for ContactSettings {
    fn default() -> Self {
        Self {
            substeps: DEFAULT_SUBSTEPS,
            iterations: 2,
            relax_iterations: 1,
            position_correction: POSITION_CORRECTION,
            push_out_speed: CONTACT_PUSH_SPEED,
            slop: LINEAR_SLOP,
            restitution_threshold: RESTITUTION_THRESHOLD,
            continuous: true,
            warm_starting: true,
            sleeping: true,
        }
    }
}

impl ContactSettings {
    /// Checks every value, naming the first one that is wrong.
    pub fn validate(&self) -> Result<(), PhysicsError> {
        let count = |what, n: u32, min: u32| {
            if n >= min && n <= 1024 {
                Ok(())
            } else {
                Err(PhysicsError::OutOfRange {
                    what,
                    value: n as f32,
                    allowed: if min == 1 {
                        "in [1, 1024]"
                    } else {
                        "in [0, 1024]"
                    },
                })
            }
        };
        count("ContactSettings::substeps", self.substeps, 1)?;
        count("ContactSettings::iterations", self.iterations, 1)?;
        count(
            "ContactSettings::relax_iterations",
            self.relax_iterations,
            0,
        )?;
        positive(
            "ContactSettings::position_correction",
            self.position_correction,
        )?;
        if self.position_correction > 1.0 {
            return Err(PhysicsError::OutOfRange {
                what: "ContactSettings::position_correction",
                value: self.position_correction,
                allowed: "in (0, 1]",
            });
        }
        positive("ContactSettings::push_out_speed", self.push_out_speed)?;
        non_negative("ContactSettings::slop", self.slop)?;
        non_negative(
            "ContactSettings::restitution_threshold",
            self.restitution_threshold,
        )?;
        Ok(())
    }
}

/// Which bodies may touch: A and B collide when `A.layers & B.mask != 0`
/// and `B.layers & A.mask != 0`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct CollisionFilter {
    /// The layers the body is on. Default `1`.
    pub layers: u32,
    /// The layers the body collides with. Default all (`u32::MAX`).
    pub mask: u32,
}

impl Default for CollisionFilter {
    fn default() -> Self {
        Self {
            layers: 1,
            mask: u32::MAX,
        }
    }
}

impl CollisionFilter {
    /// Whether bodies with these filters may touch.
    pub fn allows(&self, other: &Self) -> bool {
        self.layers & other.mask != 0 && other.layers & self.mask != 0
    }
}

/// A contact between two bodies after the last step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// First body.
    pub a: BodyId,
    /// Second body.
    pub b: BodyId,
    /// Unit normal from `a` to `b`.
    pub normal: Vec2,
    /// Separation along the normal at the end of the step, metres
    /// (negative: overlap). A speculative contact has a positive separation.
    pub separation: f32,
    /// Contact points (world space) found at the start of the step.
    pub points: [Vec2; 2],
    /// Number of valid points, 1 or 2.
    pub point_count: u8,
    /// Normal impulse of the last substep, newton seconds.
    pub normal_impulse: f32,
    /// Friction impulse of the last substep, newton seconds.
    pub tangent_impulse: f32,
    /// Whether the bodies touch: the solver pushed them apart this step, or
    /// they overlap.
    pub touching: bool,
}

impl Contact {
    /// The same contact seen from `b`.
    pub fn flipped(&self) -> Self {
        Self {
            a: self.b,
            b: self.a,
            normal: -self.normal,
            ..*self
        }
    }
}

/// Two bodies that started or stopped touching during the last step.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ContactPair {
    /// One body (the one with the lower index).
    pub a: BodyId,
    /// The other body.
    pub b: BodyId,
}

/// A body that entered or left a sensor during the last step.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SensorPair {
    /// The sensor.
    pub sensor: BodyId,
    /// The body that entered or left it.
    pub visitor: BodyId,
}

/// What happened to contacts and sensors in the last step, in a fixed order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContactEvents {
    /// Pairs that started touching.
    pub begin: Vec<ContactPair>,
    /// Pairs that stopped touching (or whose body was removed).
    pub end: Vec<ContactPair>,
    /// Bodies that entered a sensor.
    pub sensor_begin: Vec<SensorPair>,
    /// Bodies that left a sensor (or were removed).
    pub sensor_end: Vec<SensorPair>,
}

impl ContactEvents {
    fn clear(&mut self) {
        self.begin.clear();
        self.end.clear();
        self.sensor_begin.clear();
        self.sensor_end.clear();
    }
}

/// Impulses a contact carries to the next step.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Cached {
    key: (BodyId, BodyId),
    normal_impulse: f32,
    tangent_impulse: f32,
}

/// A sensor and a body that may be inside it at the end of the step.
#[derive(Clone, Copy, Debug)]
struct SensorCandidate {
    pair: SensorPair,
    /// Collider references (dynamic index or `STATIC_BODY | static index`).
    sensor: u32,
    visitor: u32,
}

/// A collider as the contact stage sees it.
#[derive(Clone, Copy)]
struct Collider {
    shape: Shape,
    /// Dynamic index, or `STATIC_BODY | static index`.
    body: u32,
    id: BodyId,
    sensor: bool,
    filter: CollisionFilter,
}

/// What a step tells the contact stage.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StepParams {
    /// Gravitational acceleration (for restitution's impact speed).
    pub gravity: Vec2,
    /// The step, seconds (for speculative margins).
    pub dt: f32,
    /// The substep, seconds.
    pub h: f32,
    /// Whether large loops may use the thread pool.
    pub parallel: bool,
}

/// No proxy (or no body) here.
const NO_PROXY: u32 = u32::MAX;

/// Sleeping bodies outside the sleep tree that trigger its rebuild, at the
/// least (below it they are simply binned with the awake ones).
const SLEEP_TREE_MIN: usize = 64;

/// How far a proxy is grown: half the speculative distance, plus the
/// body's possible travel this step with continuous collision.
#[derive(Clone, Copy, Debug, Default)]
struct ProxyMargin {
    /// Speed gravity can add this step, m/s.
    fall: f32,
    dt: f32,
    continuous: bool,
}

impl ProxyMargin {
    fn of(&self, velocity: Vec2) -> f32 {
        let travel = if self.continuous {
            (velocity.length() + self.fall) * self.dt
        } else {
            0.0
        };
        0.5 * SPECULATIVE_DISTANCE + travel
    }
}

/// What the narrow phase makes of one candidate pair.
#[derive(Clone, Copy, Debug)]
enum Outcome {
    /// Filtered out, or too far apart.
    Skip,
    /// A sensor and a body that may end the step inside it.
    Sensor(SensorCandidate),
    /// A contact to solve.
    Contact(Constraint, ContactInfo),
}

/// What the narrow phase reads (shared by the threads that run it).
struct Narrow<'a> {
    proxy_body: &'a [u32],
    margins: &'a [f32],
    dynamic: &'a DynamicBodies,
    statics: &'a StaticBodies,
    gravity: Vec2,
    h: f32,
}

impl Narrow<'_> {
    fn collider(&self, body: u32) -> Collider {
        let meta = if body & STATIC_BODY != 0 {
            &self.statics.meta[(body & !STATIC_BODY) as usize]
        } else {
            &self.dynamic.meta[body as usize]
        };
        Collider {
            shape: meta.shape.expect("a collider has a shape"),
            body,
            id: meta.id,
            sensor: meta.sensor,
            filter: meta.filter,
        }
    }

    fn position(&self, c: &Collider) -> Vec2 {
        if c.body & STATIC_BODY != 0 {
            self.statics.pos[(c.body & !STATIC_BODY) as usize]
        } else {
            self.dynamic.pos[c.body as usize]
        }
    }

    /// The contact (or sensor candidate) of proxy `pa` with proxy or static
    /// body `pb`.
    fn pair(&self, pa: u32, pb: u32) -> Outcome {
        let a_body = self.proxy_body[pa as usize];
        let (b_body, margin) = if pb & STATIC_BODY == 0 {
            (
                self.proxy_body[pb as usize],
                self.margins[pa as usize] + self.margins[pb as usize],
            )
        } else {
            (pb, self.margins[pa as usize] + 0.5 * SPECULATIVE_DISTANCE)
        };
        let (ca, cb) = (self.collider(a_body), self.collider(b_body));
        if !ca.filter.allows(&cb.filter) || (ca.sensor && cb.sensor) {
            return Outcome::Skip;
        }
        if ca.sensor || cb.sensor {
            let (s, v) = if ca.sensor { (ca, cb) } else { (cb, ca) };
            return Outcome::Sensor(SensorCandidate {
                pair: SensorPair {
                    sensor: s.id,
                    visitor: v.id,
                },
                sensor: s.body,
                visitor: v.body,
            });
        }
        // A static body is always B; otherwise the lower id is A, so a
        // contact's orientation does not depend on storage order.
        let (ca, cb) = if cb.body & STATIC_BODY != 0 || ca.id.index <= cb.id.index {
            (ca, cb)
        } else {
            (cb, ca)
        };
        match collide(
            &ca.shape,
            self.position(&ca),
            &cb.shape,
            self.position(&cb),
            margin,
        ) {
            Some(m) => {
                let (row, info) = Constraint::new(
                    &m,
                    ca.body,
                    cb.body,
                    ca.id,
                    cb.id,
                    self.dynamic,
                    self.statics,
                    self.gravity,
                    self.h,
                );
                Outcome::Contact(row, info)
            }
            None => Outcome::Skip,
        }
    }
}

/// Everything the contact stage keeps between steps. Created the first time
/// the stage runs, so a world without colliders never allocates it.
#[derive(Clone, Debug, Default)]
pub(crate) struct ContactWorld {
    broad_phase: BroadPhase,
    tree: StaticTree,
    /// Static collider per tree item: static index.
    tree_items: Vec<u32>,
    tree_dirty: bool,
    /// Dynamic colliders this step: proxy -> dynamic index.
    proxy_body: Vec<u32>,
    proxies: Vec<Aabb>,
    /// Per-body travel margin this step, by proxy.
    margins: Vec<f32>,
    pairs: Vec<(u32, u32)>,
    /// What the narrow phase found for each keyed pair.
    outcomes: Vec<Outcome>,
    /// Candidate pairs with their order key (the two slot indices, lower
    /// first): `(key, proxy, proxy or STATIC_BODY | static index)`.
    keyed: Vec<(u64, u32, u32)>,
    /// Contacts with an awake body, solved this step; sorted by pair.
    pub constraints: Vec<Constraint>,
    /// The rest of each contact, beside `constraints`.
    pub infos: Vec<ContactInfo>,
    /// Contacts between sleeping bodies (or a sleeping and a static one),
    /// kept as they were when their island fell asleep; sorted by pair.
    pub asleep: Vec<Constraint>,
    /// The rest of each sleeping contact, beside `asleep`.
    pub asleep_infos: Vec<ContactInfo>,
    /// Room for merging sleeping contacts, kept between steps.
    scratch: (Vec<Constraint>, Vec<ContactInfo>),
    /// Per proxy: whether its body sleeps (empty when none does).
    proxy_asleep: Vec<bool>,
    /// Per dynamic body: its proxy this step, or `NO_PROXY`.
    body_proxy: Vec<u32>,
    /// How far proxies are grown this step.
    proxy_margin: ProxyMargin,
    /// Sleeping bodies, in a tree rebuilt only now and then (see
    /// `update_sleep_tree`); items are `sleep_tree_bodies` entries.
    sleep_tree: StaticTree,
    /// Dynamic index per sleep-tree item (`NO_PROXY` once removed).
    sleep_tree_bodies: Vec<u32>,
    /// Per dynamic body: whether it is in the sleep tree.
    tree_member: Vec<bool>,
    /// Sleeping bodies one proxy reaches (scratch).
    hits: Vec<u32>,
    /// Some body fell asleep or woke since the sleep tree last looked.
    sleepers_changed: bool,
    /// Island bookkeeping for sleeping.
    pub islands: Islands,
    /// Positions at the start of the step.
    pub start: Vec<Vec2>,
    /// Displacement since the start of the step, per dynamic body
    /// (separations are updated from it).
    pub delta: Vec<Vec2>,
    /// Push velocities of the current substep, per dynamic body.
    pub push: Vec<Vec2>,
    cache: Vec<Cached>,
    touching: Vec<(BodyId, BodyId)>,
    touching_prev: Vec<(BodyId, BodyId)>,
    /// Sensor-visitor pairs close enough to overlap by the end of the step.
    sensor_candidates: Vec<SensorCandidate>,
    sensors: Vec<SensorPair>,
    sensors_prev: Vec<SensorPair>,
    pub events: ContactEvents,
}

/// A pair's order key: the body with the lower slot index first.
pub(crate) fn key(a: BodyId, b: BodyId) -> (BodyId, BodyId) {
    if a.index <= b.index { (a, b) } else { (b, a) }
}

impl ContactWorld {
    pub fn new() -> Self {
        Self {
            tree_dirty: true,
            ..Self::default()
        }
    }

    /// Static bodies changed: rebuild the tree at the next step.
    pub fn statics_changed(&mut self) {
        self.tree_dirty = true;
    }

    fn rebuild_tree(&mut self, statics: &StaticBodies) {
        self.tree_items.clear();
        let mut boxes = Vec::new();
        for (i, meta) in statics.meta.iter().enumerate() {
            if let Some(shape) = &meta.shape {
                self.tree_items.push(i as u32);
                boxes.push(Aabb::from_centre(statics.pos[i], shape.half_extents()));
            }
        }
        self.tree = StaticTree::build(boxes);
        self.tree_dirty = false;
    }

    /// Broad and narrow phase at the start of a step: builds the contact
    /// constraints (with last step's impulses when warm starting) and the
    /// sensor overlaps.
    pub fn begin_step(
        &mut self,
        dynamic: &mut DynamicBodies,
        statics: &StaticBodies,
        settings: &ContactSettings,
        step: &StepParams,
    ) {
        let StepParams {
            gravity,
            dt,
            h,
            parallel,
        } = *step;
        if self.tree_dirty {
            self.rebuild_tree(statics);
        }
        self.start.clear();
        self.start.extend_from_slice(&dynamic.pos);
        self.delta.clear();
        self.delta.resize(dynamic.len(), Vec2::ZERO);
        self.push.clear();
        self.push.resize(dynamic.len(), Vec2::ZERO);

        // Proxies: shaped dynamic bodies, grown by their possible travel.
        // Pairs of two sleeping bodies, and of a sleeping and a static one,
        // are not looked for: their contacts wait in `asleep`. Most sleeping
        // bodies are not even binned: they sit in the sleep tree, and only
        // those an awake proxy reaches get a proxy.
        self.proxy_body.clear();
        self.proxies.clear();
        self.margins.clear();
        self.proxy_asleep.clear();
        let any_asleep = !self.asleep.is_empty() || dynamic.sleep.iter().any(|s| s.is_asleep());
        self.proxy_margin = ProxyMargin {
            fall: gravity.length() * dt,
            dt,
            continuous: settings.continuous,
        };
        self.body_proxy.clear();
        self.body_proxy.resize(dynamic.len(), NO_PROXY);
        self.tree_member.resize(dynamic.len(), false);
        if any_asleep {
            self.update_sleep_tree(dynamic);
        }
        for (i, meta) in dynamic.meta.iter().enumerate() {
            if meta.shape.is_none() {
                continue;
            }
            let asleep = dynamic.sleep[i].is_asleep();
            if !(asleep && self.tree_member[i]) {
                self.add_proxy(dynamic, i, any_asleep);
            }
        }
        self.pairs.clear();
        self.broad_phase
            .find_pairs(&self.proxies, &self.proxy_asleep, parallel, &mut self.pairs);
        let binned = self.proxies.len();
        for p in 0..binned {
            if self.proxy_asleep.get(p) == Some(&true) {
                continue;
            }
            let aabb = self.proxies[p];
            let pairs = &mut self.pairs;
            let items = &self.tree_items;
            self.tree.query(&aabb, |item| {
                pairs.push((p as u32, STATIC_BODY | items[item as usize]))
            });
            if any_asleep {
                // Sleeping bodies in the sleep tree that this proxy reaches.
                self.hits.clear();
                let (hits, bodies) = (&mut self.hits, &self.sleep_tree_bodies);
                self.sleep_tree.query(&aabb, |item| {
                    let body = bodies[item as usize];
                    if body != NO_PROXY && dynamic.sleep[body as usize].is_asleep() {
                        hits.push(body);
                    }
                });
                for k in 0..self.hits.len() {
                    let q = self.proxy_of(dynamic, self.hits[k] as usize);
                    self.pairs.push((p as u32, q));
                }
            }
        }

        // Narrow phase in a fixed order: by the pair's body ids. Sorting the
        // small pairs (not the contacts) keeps this cheap, and the contacts
        // come out sorted for the warm-start merge below.
        self.keyed.clear();
        for &(pa, pb) in &self.pairs {
            let a_body = self.proxy_body[pa as usize];
            let b_body = if pb & STATIC_BODY != 0 {
                pb
            } else {
                self.proxy_body[pb as usize]
            };
            let key = pair_order(dynamic, statics, a_body, b_body);
            self.keyed.push((key, pa, pb));
        }
        self.keyed.sort_unstable_by_key(|k| k.0);
        let mut outcomes = std::mem::take(&mut self.outcomes);
        outcomes.clear();
        outcomes.resize(self.keyed.len(), Outcome::Skip);
        let narrow = Narrow {
            proxy_body: &self.proxy_body,
            margins: &self.margins,
            dynamic,
            statics,
            gravity,
            h,
        };
        let keyed = &self.keyed;
        #[cfg(feature = "parallel")]
        if crate::parallel::goes_parallel(parallel, keyed.len()) {
            use rayon::prelude::*;
            let c = crate::constants::PARALLEL_CHUNK;
            outcomes
                .par_chunks_mut(c)
                .zip(keyed.par_chunks(c))
                .for_each(|(out, pairs)| {
                    for (o, &(_, pa, pb)) in out.iter_mut().zip(pairs) {
                        *o = narrow.pair(pa, pb);
                    }
                });
        } else {
            for (o, &(_, pa, pb)) in outcomes.iter_mut().zip(keyed) {
                *o = narrow.pair(pa, pb);
            }
        }
        #[cfg(not(feature = "parallel"))]
        {
            let _ = parallel;
            for (o, &(_, pa, pb)) in outcomes.iter_mut().zip(keyed) {
                *o = narrow.pair(pa, pb);
            }
        }
        self.constraints.clear();
        self.infos.clear();
        self.sensor_candidates.clear();
        for o in &outcomes {
            match o {
                Outcome::Skip => {}
                Outcome::Sensor(candidate) => self.sensor_candidates.push(*candidate),
                Outcome::Contact(row, info) => {
                    self.constraints.push(*row);
                    self.infos.push(*info);
                }
            }
        }
        self.outcomes = outcomes;
        if settings.sleeping && any_asleep {
            self.wake_reached(dynamic, statics, step, settings.slop);
        }

        // Warm starting: last step's impulses (both sorted by key).
        if settings.warm_starting {
            warm_start(&self.cache, &mut self.constraints, &self.infos);
        }
    }

    /// Adds a proxy for dynamic body `i` (which has a shape).
    fn add_proxy(&mut self, dynamic: &DynamicBodies, i: usize, any_asleep: bool) -> u32 {
        let shape = dynamic.meta[i].shape.expect("a proxy's body has a shape");
        let margin = self.proxy_margin.of(dynamic.vel[i]);
        let p = self.proxies.len() as u32;
        self.body_proxy[i] = p;
        self.proxy_body.push(i as u32);
        self.proxies
            .push(Aabb::from_centre(dynamic.pos[i], shape.half_extents()).grown(margin));
        self.margins.push(margin);
        if any_asleep {
            self.proxy_asleep.push(dynamic.sleep[i].is_asleep());
        }
        p
    }

    /// The proxy of dynamic body `i`, made now if it has none.
    fn proxy_of(&mut self, dynamic: &DynamicBodies, i: usize) -> u32 {
        match self.body_proxy[i] {
            NO_PROXY => self.add_proxy(dynamic, i, true),
            p => p,
        }
    }

    /// Rebuilds the sleep tree over every sleeping shaped body when enough
    /// sleeping bodies are missing from it (they are binned each step until
    /// then) or enough of its bodies woke (they are skipped until then):
    /// a tree build costs `O(n log n)`, so it waits for a quarter of the
    /// tree's size to change.
    fn update_sleep_tree(&mut self, dynamic: &DynamicBodies) {
        let (mut missing, mut woke) = (0, 0);
        for (i, s) in dynamic.sleep.iter().enumerate() {
            let shaped = dynamic.meta[i].shape.is_some();
            missing += usize::from(shaped && s.is_asleep() && !self.tree_member[i]);
            woke += usize::from(self.tree_member[i] && !s.is_asleep());
        }
        // A quiet step (nobody fell asleep or woke in the last one) takes
        // in the stragglers, so a settled world bins nothing.
        let quiet = !std::mem::take(&mut self.sleepers_changed);
        let size = self.sleep_tree.len();
        let stragglers = missing > 0 && quiet;
        if !stragglers && missing < (size / 4).max(SLEEP_TREE_MIN) && 2 * woke <= size {
            return;
        }
        self.tree_member.fill(false);
        self.sleep_tree_bodies.clear();
        // Room for every body: later rebuilds allocate nothing.
        let n = dynamic.len();
        self.sleep_tree_bodies.reserve(n);
        self.sleep_tree.reserve(n);
        self.hits.reserve(n);
        for (i, s) in dynamic.sleep.iter().enumerate() {
            if s.is_asleep() && dynamic.meta[i].shape.is_some() {
                self.sleep_tree_bodies.push(i as u32);
                self.tree_member[i] = true;
            }
        }
        let margin = self.proxy_margin.of(Vec2::ZERO);
        let boxes = self.sleep_tree_bodies.iter().map(|&i| {
            let half = dynamic.meta[i as usize]
                .shape
                .expect("shaped")
                .half_extents();
            Aabb::from_centre(dynamic.pos[i as usize], half).grown(margin)
        });
        self.sleep_tree.rebuild(boxes);
    }

    /// Wakes the sleeping islands an awake body reaches this step (a
    /// contact touching within the slop, or closing to it at the bodies'
    /// speeds), so they are solved in this step already. The contacts
    /// found with them held static, and the stored contacts of the woken
    /// bodies, are found again with everyone awake.
    fn wake_reached(
        &mut self,
        dynamic: &mut DynamicBodies,
        statics: &StaticBodies,
        step: &StepParams,
        slop: f32,
    ) {
        let mut woke = false;
        for c in &self.constraints {
            if c.is_static() {
                continue;
            }
            let (a, b) = (c.a as usize, c.b as usize);
            let (sa, sb) = (dynamic.sleep[a].is_asleep(), dynamic.sleep[b].is_asleep());
            let vn = (dynamic.vel[b] - dynamic.vel[a]).dot(c.normal);
            if sa != sb && c.base_separation + vn.min(0.0) * step.dt <= slop {
                self.islands.wake_body(dynamic, if sa { a } else { b });
                woke = true;
            }
        }
        if !woke {
            return;
        }
        self.islands.wake_marked(dynamic);
        self.sleepers_changed = true;
        // Every body that woke gets a proxy (those from the sleep tree
        // have none yet).
        for k in 0..self.asleep.len() {
            let c = self.asleep[k];
            for body in [c.a, c.b] {
                if body & STATIC_BODY == 0 && !dynamic.sleep[body as usize].is_asleep() {
                    let _ = self.proxy_of(dynamic, body as usize);
                }
            }
        }
        let proxy_asleep = &self.proxy_asleep;
        let body_proxy = &self.body_proxy;
        let woke_now = |body: u32| {
            body & STATIC_BODY == 0
                && !dynamic.sleep[body as usize].is_asleep()
                && proxy_asleep[body_proxy[body as usize] as usize]
        };
        let proxy = |body: u32| {
            if body & STATIC_BODY != 0 {
                body
            } else {
                body_proxy[body as usize]
            }
        };
        let keyed = &mut self.keyed;
        keyed.clear();
        let mut kept = 0;
        for i in 0..self.constraints.len() {
            let c = self.constraints[i];
            if woke_now(c.a) || woke_now(c.b) {
                let key = pair_order(dynamic, statics, c.a, c.b);
                keyed.push((key, proxy(c.a), proxy(c.b)));
            } else {
                self.constraints[kept] = c;
                self.infos[kept] = self.infos[i];
                kept += 1;
            }
        }
        self.constraints.truncate(kept);
        self.infos.truncate(kept);
        for c in &self.asleep {
            if woke_now(c.a) || woke_now(c.b) {
                let key = pair_order(dynamic, statics, c.a, c.b);
                keyed.push((key, proxy(c.a), proxy(c.b)));
            }
        }
        keyed.sort_unstable_by_key(|k| k.0);
        keyed.dedup_by_key(|k| k.0);
        let narrow = Narrow {
            proxy_body: &self.proxy_body,
            margins: &self.margins,
            dynamic,
            statics,
            gravity: step.gravity,
            h: step.h,
        };
        // Merge the contacts found again into the solved list, in key order.
        let mut merge = Merge::new(&mut self.constraints, &mut self.infos, &mut self.scratch);
        for &(_, pa, pb) in keyed.iter() {
            if let Outcome::Contact(row, info) = narrow.pair(pa, pb) {
                merge.push(row, info);
            }
        }
        merge.finish();
        self.drop_awake_contacts(dynamic);
    }

    /// After the last substep: cache impulses for warm starting, find which
    /// bodies are inside sensors now, and work out which pairs began and
    /// ended touching.
    ///
    /// With `sleep_dt` (sleeping on, the step's length) it also does the
    /// sleeping bookkeeping: rest times, waking islands an awake body
    /// touched, and putting islands that rested long enough to sleep.
    pub fn end_step(
        &mut self,
        dynamic: &mut DynamicBodies,
        statics: &StaticBodies,
        sleep_dt: Option<f32>,
    ) {
        self.sensors.clear();
        for c in &self.sensor_candidates {
            let (shape_s, pos_s) = collider_at(c.sensor, dynamic, statics);
            let (shape_v, pos_v) = collider_at(c.visitor, dynamic, statics);
            if collide(&shape_s, pos_s, &shape_v, pos_v, 0.0).is_some_and(|m| m.separation < 0.0) {
                self.sensors.push(c.pair);
                // Bodies in a sensor stay awake, so it keeps seeing them.
                for body in [c.sensor, c.visitor] {
                    if body & STATIC_BODY == 0 {
                        dynamic.sleep[body as usize].rest_time = 0.0;
                    }
                }
            }
        }
        if let Some(dt) = sleep_dt {
            self.update_sleep(dynamic, dt);
        }
        self.cache.clear();
        self.touching.clear();
        let (solved, asleep) = (self.constraints.len(), self.asleep.len());
        let (mut i, mut j) = (0, 0);
        // Merge the two sorted lists (solved, asleep) into key order.
        while i < solved || j < asleep {
            let (c, info) = if j == asleep
                || (i < solved && self.infos[i].key() < self.asleep_infos[j].key())
            {
                i += 1;
                (&self.constraints[i - 1], &self.infos[i - 1])
            } else {
                j += 1;
                (&self.asleep[j - 1], &self.asleep_infos[j - 1])
            };
            let k = info.key();
            self.cache.push(Cached {
                key: k,
                normal_impulse: c.normal_impulse,
                tangent_impulse: c.tangent_impulse,
            });
            if info.is_touching(c) {
                self.touching.push(k);
            }
        }
        self.events.clear();
        diff(&self.touching_prev, &self.touching, |k, began| {
            let pair = ContactPair { a: k.0, b: k.1 };
            if began {
                self.events.begin.push(pair);
            } else {
                self.events.end.push(pair);
            }
        });
        std::mem::swap(&mut self.touching, &mut self.touching_prev);
        self.sensors.sort_unstable();
        self.sensors.dedup();
        diff(&self.sensors_prev, &self.sensors, |&pair, began| {
            if began {
                self.events.sensor_begin.push(pair);
            } else {
                self.events.sensor_end.push(pair);
            }
        });
        std::mem::swap(&mut self.sensors, &mut self.sensors_prev);
    }

    /// A step in which the contact stage has nothing to do (its colliders
    /// were removed): every contact and overlap ends.
    pub fn idle_step(&mut self, dynamic: &mut DynamicBodies, statics: &StaticBodies) {
        self.constraints.clear();
        self.infos.clear();
        self.sensor_candidates.clear();
        self.wake_all(dynamic);
        self.end_step(dynamic, statics, None);
    }

    /// Rest times, waking and falling asleep after a step (see `sleep`).
    fn update_sleep(&mut self, dynamic: &mut DynamicBodies, dt: f32) {
        self.islands.rest(dynamic, &self.delta, dt);
        // An awake body touching a sleeping one wakes its island (for the
        // next step: during this one it held like a static body).
        let mut woke = false;
        for (c, info) in self.constraints.iter().zip(&self.infos) {
            if c.is_static() || !info.is_touching(c) {
                continue;
            }
            for body in [c.a, c.b] {
                if dynamic.sleep[body as usize].is_asleep() {
                    self.islands.wake_body(dynamic, body as usize);
                    woke = true;
                }
            }
        }
        if woke {
            self.islands.wake_marked(dynamic);
            self.drop_awake_contacts(dynamic);
            self.sleepers_changed = true;
        }
        if self
            .islands
            .fall_asleep(dynamic, &self.constraints, &self.infos)
        {
            self.sleepers_changed = true;
            self.store_sleeping_contacts(dynamic);
        }
    }

    /// Moves the solved contacts whose bodies all sleep now into `asleep`,
    /// keeping both lists in key order.
    fn store_sleeping_contacts(&mut self, dynamic: &DynamicBodies) {
        let mut merge = Merge::new(&mut self.asleep, &mut self.asleep_infos, &mut self.scratch);
        let mut kept = 0;
        for i in 0..self.constraints.len() {
            let (c, info) = (self.constraints[i], self.infos[i]);
            if has_awake_body(dynamic, &c) {
                self.constraints[kept] = c;
                self.infos[kept] = info;
                kept += 1;
            } else {
                merge.push(c, info);
            }
        }
        merge.finish();
        self.constraints.truncate(kept);
        self.infos.truncate(kept);
    }

    /// Forgets the stored contacts of bodies that woke: the next step finds
    /// them afresh.
    fn drop_awake_contacts(&mut self, dynamic: &DynamicBodies) {
        let mut kept = 0;
        for i in 0..self.asleep.len() {
            if !has_awake_body(dynamic, &self.asleep[i]) {
                self.asleep[kept] = self.asleep[i];
                self.asleep_infos[kept] = self.asleep_infos[i];
                kept += 1;
            }
        }
        self.asleep.truncate(kept);
        self.asleep_infos.truncate(kept);
    }

    /// Wakes dynamic body `i` and its island now.
    pub fn wake_body(&mut self, dynamic: &mut DynamicBodies, i: usize) {
        let was_asleep = dynamic.sleep[i].is_asleep();
        self.islands.wake_body(dynamic, i);
        if was_asleep {
            self.islands.wake_marked(dynamic);
            self.drop_awake_contacts(dynamic);
            self.sleepers_changed = true;
        }
    }

    /// Wakes every body.
    /// Nothing happens when every body is already awake with no rest time
    /// and nothing is stored: the step calls this while sleeping is off
    /// and while the stage is idle.
    pub fn wake_all(&mut self, dynamic: &mut DynamicBodies) {
        let nothing_to_do = self.asleep.is_empty()
            && self.sleep_tree.len() == 0
            && dynamic.sleep.iter().all(|s| *s == SleepState::awake());
        if nothing_to_do {
            return;
        }
        crate::sleep::wake_all(dynamic);
        self.asleep.clear();
        self.asleep_infos.clear();
        self.sleep_tree.rebuild([]);
        self.sleep_tree_bodies.clear();
        self.tree_member.fill(false);
        self.sleepers_changed = true;
    }

    /// Dynamic body `from` now sits at index `to` (a removal moved it).
    pub fn body_moved(&mut self, from: u32, to: u32) {
        for body in &mut self.sleep_tree_bodies {
            if *body == to {
                *body = NO_PROXY; // removed
            } else if *body == from {
                *body = to;
            }
        }
        // `from` is the last body: the removal moves it into `to`.
        self.tree_member.resize(from as usize + 1, false);
        self.tree_member.swap_remove(to as usize);
        for c in &mut self.asleep {
            if c.a == from {
                c.a = to;
            }
            if c.b == from {
                c.b = to;
            }
        }
    }

    /// Every contact after the last step: the solved ones, then those
    /// between sleeping bodies.
    pub fn all_contacts(&self) -> impl Iterator<Item = (&Constraint, &ContactInfo)> {
        let solved = self.constraints.iter().zip(&self.infos);
        solved.chain(self.asleep.iter().zip(&self.asleep_infos))
    }

    /// Sensor overlaps after the last step.
    pub fn sensor_overlaps(&self) -> &[SensorPair] {
        &self.sensors_prev
    }

    /// What the next step needs from the last one: warm-start impulses,
    /// and who touched whom (for begin and end events).
    pub fn carried_state(&self) -> ContactState {
        ContactState {
            cache: self.cache.clone(),
            touching: self.touching_prev.clone(),
            sensors: self.sensors_prev.clone(),
            asleep: self.asleep.clone(),
            asleep_infos: self.asleep_infos.clone(),
        }
    }

    /// A contact stage resuming from a carried state.
    pub fn resume(state: ContactState) -> Self {
        Self {
            cache: state.cache,
            touching_prev: state.touching,
            sensors_prev: state.sensors,
            asleep: state.asleep,
            asleep_infos: state.asleep_infos,
            ..Self::new()
        }
    }
}

/// Adds contacts, given in key order, to a contact list sorted by key: the
/// list's old content waits in a scratch pair of vectors (kept between
/// steps, so merging allocates nothing once warm).
struct Merge<'a> {
    rows: &'a mut Vec<Constraint>,
    infos: &'a mut Vec<ContactInfo>,
    old: &'a (Vec<Constraint>, Vec<ContactInfo>),
    next: usize,
}

impl<'a> Merge<'a> {
    fn new(
        rows: &'a mut Vec<Constraint>,
        infos: &'a mut Vec<ContactInfo>,
        scratch: &'a mut (Vec<Constraint>, Vec<ContactInfo>),
    ) -> Self {
        scratch.0.clear();
        scratch.1.clear();
        scratch.0.append(rows);
        scratch.1.append(infos);
        Self {
            rows,
            infos,
            old: scratch,
            next: 0,
        }
    }

    fn push(&mut self, row: Constraint, info: ContactInfo) {
        let (old, old_infos) = (&self.old.0, &self.old.1);
        while self.next < old.len() && old_infos[self.next].key() < info.key() {
            self.rows.push(old[self.next]);
            self.infos.push(old_infos[self.next]);
            self.next += 1;
        }
        self.rows.push(row);
        self.infos.push(info);
    }

    fn finish(self) {
        self.rows.extend_from_slice(&self.old.0[self.next..]);
        self.infos.extend_from_slice(&self.old.1[self.next..]);
    }
}

/// The order key of the pair of collider references `a` and `b` (dynamic
/// index, or `STATIC_BODY | static index`): the two slot indices, lower
/// first, so the order depends on ids, not on storage.
fn pair_order(dynamic: &DynamicBodies, statics: &StaticBodies, a: u32, b: u32) -> u64 {
    let slot = |body: u32| -> u64 {
        if body & STATIC_BODY != 0 {
            u64::from(statics.meta[(body & !STATIC_BODY) as usize].id.index)
        } else {
            u64::from(dynamic.meta[body as usize].id.index)
        }
    };
    let (x, y) = (slot(a), slot(b));
    x.min(y) << 32 | x.max(y)
}

/// Whether a contact has an awake dynamic body (so the solver works on it).
fn has_awake_body(dynamic: &DynamicBodies, c: &Constraint) -> bool {
    !dynamic.sleep[c.a as usize].is_asleep()
        || (!c.is_static() && !dynamic.sleep[c.b as usize].is_asleep())
}

/// Gives each contact the impulses its pair had after the last step;
/// `cache` and `infos` are both sorted by key.
fn warm_start(cache: &[Cached], constraints: &mut [Constraint], infos: &[ContactInfo]) {
    debug_assert!(infos.is_sorted_by_key(ContactInfo::key));
    let mut j = 0;
    for (c, info) in constraints.iter_mut().zip(infos) {
        let k = info.key();
        while j < cache.len() && cache[j].key < k {
            j += 1;
        }
        if j < cache.len() && cache[j].key == k {
            c.normal_impulse = cache[j].normal_impulse;
            c.tangent_impulse = cache[j].tangent_impulse;
        }
    }
}

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
    /// Checks the sleeping contacts against the bodies: each names a
    /// sleeping dynamic body and a sleeping or static one that exist, in
    /// key order, with finite values.
    pub fn validate(&self, dynamic: &DynamicBodies, statics: &StaticBodies) -> Result<(), String> {
        if self.asleep.len() != self.asleep_infos.len() {
            return Err("sleeping contact lists of different lengths".into());
        }
        if !self.asleep_infos.is_sorted_by_key(ContactInfo::key) {
            return Err("sleeping contacts out of order".into());
        }
        let sleeping = |i: u32| dynamic.sleep.get(i as usize).is_some_and(|s| s.is_asleep());
        for (c, info) in self.asleep.iter().zip(&self.asleep_infos) {
            let b_ok = if c.is_static() {
                statics.meta.get((c.b & !STATIC_BODY) as usize).is_some()
            } else {
                sleeping(c.b)
            };
            let ids = |i: u32| {
                if i & STATIC_BODY != 0 {
                    statics.meta.get((i & !STATIC_BODY) as usize).map(|m| m.id)
                } else {
                    dynamic.meta.get(i as usize).map(|m| m.id)
                }
            };
            let named = ids(c.a) == Some(info.id_a) && ids(c.b) == Some(info.id_b)
                || ids(c.a) == Some(info.id_b) && ids(c.b) == Some(info.id_a);
            if !(sleeping(c.a) && b_ok && named && c.is_valid()) {
                return Err(format!(
                    "sleeping contact {:?}-{:?} is inconsistent with the bodies",
                    info.id_a, info.id_b
                ));
            }
        }
        Ok(())
    }
}

/// The shape and position of a collider reference.
fn collider_at(body: u32, dynamic: &DynamicBodies, statics: &StaticBodies) -> (Shape, Vec2) {
    if body & STATIC_BODY != 0 {
        let s = (body & !STATIC_BODY) as usize;
        (
            statics.meta[s].shape.expect("collider has a shape"),
            statics.pos[s],
        )
    } else {
        let d = body as usize;
        (
            dynamic.meta[d].shape.expect("collider has a shape"),
            dynamic.pos[d],
        )
    }
}

/// Walks two sorted lists and reports what is only in `now` (`true`) or
/// only in `before` (`false`).
fn diff<T: Ord>(before: &[T], now: &[T], mut f: impl FnMut(&T, bool)) {
    let (mut i, mut j) = (0, 0);
    while i < before.len() || j < now.len() {
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
            (None, None) => unreachable!(),
        }
    }
}
