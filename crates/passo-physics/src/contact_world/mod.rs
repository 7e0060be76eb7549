//! The contact stage's state between steps, and the two ends of a step
//! that surround the solver: finding the contacts (proxies, pairs, narrow
//! phase, waking what is reached, warm starting) and recording what
//! happened (sensors, sleeping, events).

pub(crate) mod island;
pub(crate) mod sleeping;
pub(crate) mod events;
pub(crate) mod state;

use crate::body::collider::ColliderRef;
use crate::body::store::{Colliders, DynamicBodies, StaticBodies};
use crate::collision::narrow_phase::{NarrowPhase, Outcome, PairContext};
use crate::collision::proxies::{Proxies, ProxyMargin};
use crate::contact::constraint::{Constraint, ContactInfo, ContactList, Merge};
use crate::contact_world::events::EventTracker;
use crate::contact_world::sleeping::{SleepingContacts, has_awake_body};
use crate::contact_world::state::{ContactState, names_bodies};
use crate::solver::continuous::Sweeps;
use crate::solver::motion::Motion;
use crate::solver::regions::ContactRegions;
use crate::solver::shock::Supports;
use crate::switches::TestSwitches;
use crate::{BodyId, ContactEvents, ContactSettings, SensorPair};
use glam::Vec2;

/// What the contact steps' shortcuts saved, counted since the world's
/// contact state was made: its first contact step, or a restored snapshot
/// (Box2D publishes the like as `b2Counters`). Each is a count of steps
/// or of builds, but for [`rods_in_blocks`](Self::rods_in_blocks), which
/// is of the last step; the difference of two readings covers the steps
/// between them.
/// Read them with [`World::counters`](crate::World::counters). They are
/// diagnostics, not state: a snapshot does not carry them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StepCounters {
    /// Broad-phase searches whose pairs were the last search's, because
    /// no body's box changed by a bit.
    pub grid_pairs_reused: u64,
    /// Broad-phase searches whose pairs were taken from the grown boxes
    /// of a settled scene, because every box stayed inside its grown one.
    pub grown_pairs_reused: u64,
    /// Searches whose pairs with static bodies were the last search's.
    pub static_pairs_reused: u64,
    /// Narrow-phase runs that sorted their pairs (the others had the last
    /// step's pairs, sorted already).
    pub pair_sorts: u64,
    /// Narrow-phase runs that reused every contact of the last step in
    /// place, none having moved beyond the reuse distance.
    pub contacts_reused_in_place: u64,
    /// Colourings of the contacts that took the last step's colours (a
    /// step that splits its contacts in regions colours each).
    pub colourings_reused: u64,
    /// Steps whose shock propagation kept the last step's order of the
    /// contacts that hold bodies up (the same contacts, each holding the
    /// same body up).
    pub supports_reused: u64,
    /// Builds of the tree that finds the sleeping bodies an awake body
    /// reaches: one when an island has fallen asleep, when half the tree's
    /// bodies have woken, or when the margins its boxes are grown by
    /// changed (with gravity or the step). Steps in between reuse it.
    pub sleep_tree_builds: u64,
    /// Rigid rods (distance joints of one length, no spring) the last step
    /// solved side by side in blocks; the other joints it solved one by
    /// one.
    pub rods_in_blocks: u64,
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
    /// Every dynamic body has a shape, as far as the world counts them (a
    /// hint: proxies are made one by one otherwise).
    pub all_shaped: bool,
}

/// Everything the contact stage keeps between steps. Created the first time
/// the stage runs, so a world without colliders never allocates it.
#[derive(Clone, Debug, Default)]
pub(crate) struct ContactWorld {
    proxies: Proxies,
    narrow: NarrowPhase,
    /// Contacts with an awake body, solved this step; sorted by pair.
    pub solved: ContactList,
    /// Stored contacts of sleeping islands, and how to find them.
    pub sleeping: SleepingContacts,
    /// Per-body buffers of the substeps.
    pub motion: Motion,
    /// The solved contacts by region and colour, as the substeps solve them.
    pub regions: ContactRegions,
    /// The contacts that hold bodies up, for shock propagation.
    pub supports: Supports,
    sweeps: Sweeps,
    events: EventTracker,
    /// Room for merging contacts found again, kept between steps.
    scratch: ContactList,
    /// The last step's contacts while the narrow phase runs (see
    /// [`Reuse`](crate::collision::reuse::Reuse)); otherwise the buffer of the step before.
    last: ContactList,
    /// Counts changes of the contact lists (a step, a wake that drops
    /// stored contacts, a removal), so what is built from them (the
    /// per-body contact index of queries) knows when it is stale.
    revision: u64,
    /// The shortcuts turned off (`warm_start_always`).
    pub(crate) switches: TestSwitches,
    /// Whether a removal moved bodies to other indices since the last step
    /// (or restore): until then every awake contact names the bodies it was
    /// found with; after it a row may name the wrong ones, and the list is
    /// moved to the bodies' new indices before the next step and in a
    /// snapshot (see [`relocate`]).
    bodies_moved: bool,
    /// Whether every awake contact is to be found afresh at the next step
    /// (see [`forget_all_reuse`](Self::forget_all_reuse)), not yet marked.
    reuse_forgotten: bool,
}

impl ContactWorld {
    /// Drops this step's contacts between bodies in `apart` (pairs by
    /// their order key, sorted): bodies a joint links, which do not
    /// collide unless the joint says so.
    pub(crate) fn drop_joined(&mut self, apart: &[(crate::BodyId, crate::BodyId)]) {
        if apart.is_empty() {
            return;
        }
        let solved = &mut self.solved;
        let mut kept = 0;
        for i in 0..solved.rows.len() {
            if apart.binary_search(&solved.infos[i].key()).is_err() {
                solved.rows[kept] = solved.rows[i];
                solved.infos[kept] = solved.infos[i];
                kept += 1;
            }
        }
        solved.rows.truncate(kept);
        solved.infos.truncate(kept);
    }

    /// Sets each contact's tangent speed from its bodies' conveyors
    /// (`conveyor` gives a body's surface velocity, if it has one; see
    /// `PreSolve::conveyor` for the sign).
    pub(crate) fn apply_conveyors(&mut self, conveyor: impl Fn(crate::BodyId) -> Option<Vec2>) {
        let solved = &mut self.solved;
        for (row, info) in solved.rows.iter_mut().zip(&mut solved.infos) {
            let tangent = row.normal.perp();
            let (a, b) = (conveyor(info.id_a), conveyor(info.id_b));
            if a.is_some() || b.is_some() {
                let speed = |v: Option<Vec2>| v.map_or(0.0, |v| v.dot(tangent));
                row.tangent_speed = speed(a) - speed(b);
                // Found afresh each step, as a hook's.
                info.reusable = false;
            }
        }
    }

    /// Runs the game's contact hooks over this step's contacts and sensor
    /// candidates, in key order (see `ContactHooks`): drops the pairs the
    /// filter refuses and the contacts a pre-solve disables, and takes the
    /// friction, restitution and tangent speed each pre-solve sets.
    /// `info` gives a body's id and user data.
    pub(crate) fn run_hooks(
        &mut self,
        hooks: &dyn crate::ContactHooks,
        dynamic: &DynamicBodies,
        info: impl Fn(crate::BodyId) -> crate::PairInfo,
        gravity: Vec2,
        h: f32,
    ) {
        let solved = &mut self.solved;
        let mut kept = 0;
        for i in 0..solved.rows.len() {
            let (mut row, mut ci) = (solved.rows[i], solved.infos[i]);
            let (a, b) = (info(ci.id_a), info(ci.id_b));
            if !hooks.filter_pair(&a, &b) {
                continue;
            }
            let mut pre = crate::PreSolve {
                a,
                b,
                normal: row.normal,
                separation: row.base_separation - ci.lead,
                enabled: true,
                friction: row.friction,
                restitution: ci.restitution,
                tangent_speed: 0.0,
            };
            hooks.pre_solve(&mut pre);
            if !pre.enabled {
                continue;
            }
            // A value out of range keeps what the contact had.
            if pre.friction.is_finite() && pre.friction >= 0.0 {
                row.friction = pre.friction;
            }
            row.tangent_speed = if pre.tangent_speed.is_finite() {
                pre.tangent_speed
            } else {
                0.0
            };
            let e = pre.restitution;
            if (0.0..=1.0).contains(&e) && e != ci.restitution {
                ci.restitution = e;
                (ci.impact_u, ci.half_an_h) = if e > 0.0 {
                    let holds = (row.inv_mass_a == 0.0, row.inv_mass_b == 0.0);
                    let normal = (row.normal, row.base_separation);
                    let (a, b) = (row.a as usize, row.b);
                    crate::contact::constraint::impact(dynamic, a, b, holds, normal, gravity, h)
                } else {
                    (0.0, 0.0)
                };
            }
            // A changed contact is found afresh each step.
            ci.reusable = false;
            solved.rows[kept] = row;
            solved.infos[kept] = ci;
            kept += 1;
        }
        solved.rows.truncate(kept);
        solved.infos.truncate(kept);
        (self.narrow.sensor_candidates)
            .retain(|c| hooks.filter_pair(&info(c.pair.sensor), &info(c.pair.visitor)));
    }

    pub(crate) fn new() -> Self {
        Self {
            proxies: Proxies::new(),
            ..Self::default()
        }
    }

    /// Static bodies changed: rebuild the static tree at the next step.
    pub(crate) fn statics_changed(&mut self) {
        self.proxies.statics_changed();
    }

    /// Finds the step's contacts: proxies, pairs, the narrow phase, waking
    /// the sleeping islands an awake body reaches, warm starting.
    pub(crate) fn begin_step(
        &mut self,
        dynamic: &mut DynamicBodies,
        statics: &StaticBodies,
        settings: &ContactSettings,
        step: &StepParams,
    ) {
        self.sleeping.flush(dynamic);
        self.motion.begin(dynamic.pos.view());
        let any_asleep = self.sleeping.any(dynamic);
        let margin = ProxyMargin {
            fall: step.gravity.length() * step.dt,
            dt: step.dt,
            continuous: settings.continuous,
        };
        self.proxies.begin(dynamic, statics, margin);
        self.sleeping.begin(dynamic, any_asleep, &margin);
        self.add_proxies(dynamic, any_asleep, step.all_shaped, step.parallel);
        self.proxies.widen_kinematic(dynamic);
        self.proxies.find_pairs(step.parallel);
        if any_asleep {
            self.pair_with_sleepers(dynamic);
        }
        let events = &self.events;
        let narrow = PairContext {
            proxies: &self.proxies,
            bodies: Colliders { dynamic, statics },
            gravity: step.gravity,
            h: step.h,
            slop: settings.slop,
            pressed: &|key| events.pressed(key),
        };
        let reuse_distance_sq = settings.reuse_distance * settings.reuse_distance;
        // Contacts kept in place keep the impulses they ended the last
        // step with when those are the cache's: the warm start would give
        // them the same.
        let impulses =
            settings.warm_starting && self.events.fresh && !self.switches.warm_start_always;
        let (last, solved) = (&mut self.last, &mut self.solved);
        let kept = self.narrow.run(
            &narrow,
            (reuse_distance_sq, impulses),
            last,
            step.parallel,
            solved,
        );
        let wakes = settings.sleeping && any_asleep;
        if wakes {
            self.wake_reached(dynamic, statics, step, settings.slop);
        }
        if settings.warm_starting {
            // (A wake adds contacts, which the warm start gives theirs.)
            if !(kept && impulses && !wakes) {
                self.events.warm_start(&mut self.solved, step.parallel);
            }
            if !dynamic.kinematic.is_empty() {
                // A press moving off a body it crushed: see `crush`.
                let (vel, meta) = (&dynamic.vel, &dynamic.meta);
                let kinematic = |b: ColliderRef| {
                    b.dynamic_index()
                        .filter(|&k| meta[k].kinematic)
                        .map(|k| vel.at(k))
                };
                let rows = &mut self.solved.rows;
                self.motion.crushes.release(rows, dynamic.len(), kinematic);
            }
        }
    }

    /// After the substeps: sweeps the bodies that moved beyond their reach
    /// and moves back those that hit something (see [`Sweeps`]; the
    /// bodies' travel checked on the pool when `parallel`). Returns how
    /// many were stopped.
    pub(crate) fn sweep_fast_bodies(
        &mut self,
        dynamic: &mut DynamicBodies,
        statics: &StaticBodies,
        parallel: bool,
    ) -> usize {
        let stops = self
            .sweeps
            .run(dynamic, statics, &self.proxies, &mut self.motion, parallel);
        let candidates = &mut self.narrow.sensor_candidates;
        self.sweeps.far_sensor_candidates(
            dynamic,
            statics,
            &self.proxies,
            &self.motion.start,
            candidates,
        );
        stops
    }

    /// Proxies for the shaped dynamic bodies, swept or grown by their
    /// possible travel. Sleeping bodies in the sleep tree get one only when an awake
    /// proxy reaches them (see [`pair_with_sleepers`](Self::pair_with_sleepers)).
    /// `all_shaped`: every dynamic body has a shape, as far as the world
    /// counts them.
    fn add_proxies(
        &mut self,
        dynamic: &DynamicBodies,
        any_asleep: bool,
        all_shaped: bool,
        parallel: bool,
    ) {
        // Every body awake and shaped: one proxy a body, written into
        // lists sized once (on the pool if many), not pushed one by one
        // (unless some body has no shape after all).
        if all_shaped && !any_asleep && self.proxies.add_all(dynamic, parallel) {
            return;
        }
        for (i, meta) in dynamic.meta.iter().enumerate() {
            if meta.shape.is_none() {
                continue;
            }
            if !(dynamic.sleep[i].is_asleep() && self.sleeping.in_tree(i)) {
                self.proxies.add(dynamic, i, any_asleep);
            }
        }
    }

    /// Pairs each awake proxy with the sleeping bodies of the sleep tree it
    /// reaches. Pairs of two sleeping bodies, and of a sleeping and a static
    /// one, are not looked for: their contacts are stored.
    fn pair_with_sleepers(&mut self, dynamic: &DynamicBodies) {
        let binned = self.proxies.boxes.len();
        for p in 0..binned {
            if self.proxies.is_asleep(p) {
                continue;
            }
            // Grown all round: a sleeping body holds still this step, as
            // a wall does (see `PairContext::may_close`).
            let aabb = self.proxies.around[p];
            for &body in self.sleeping.reached(&aabb, dynamic) {
                let q = self.proxies.proxy_or_add(dynamic, body as usize);
                self.proxies.pairs.push((p as u32, q));
            }
        }
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
        for c in &self.solved.rows {
            let Some(b) = c.b.dynamic_index() else {
                continue;
            };
            let a = c.a as usize;
            let (sa, sb) = (dynamic.sleep[a].is_asleep(), dynamic.sleep[b].is_asleep());
            let vn = (dynamic.vel.at(b) - dynamic.vel.at(a)).dot(c.normal);
            if sa != sb && c.base_separation + vn.min(0.0) * step.dt <= slop {
                self.sleeping.mark(dynamic, if sa { a } else { b });
                woke = true;
            }
        }
        if !woke {
            return;
        }
        self.sleeping.wake_marked_islands(dynamic);
        // Both bodies of every stored contact that woke get a proxy (those
        // from the sleep tree have none yet), the one still asleep too: a
        // speculative contact can join a woken body to another island.
        // Proxies made from here on are of bodies woken now (or still
        // asleep), whatever they record.
        let first_new_proxy = self.proxies.boxes.len();
        for k in 0..self.sleeping.list.len() {
            let c = self.sleeping.list.rows[k];
            if has_awake_body(dynamic, &c) {
                self.proxies.proxy_or_add(dynamic, c.a as usize);
                if let Some(b) = c.b.dynamic_index() {
                    self.proxies.proxy_or_add(dynamic, b);
                }
            }
        }
        let dynamic: &DynamicBodies = dynamic;
        let bodies = Colliders { dynamic, statics };
        let proxies = &self.proxies;
        let woke_now = |body: ColliderRef| {
            body.dynamic_index().is_some_and(|i| {
                let p = proxies.of_body[i] as usize;
                !dynamic.sleep[i].is_asleep() && (proxies.asleep[p] || p >= first_new_proxy)
            })
        };
        let keyed_pair = |c: &Constraint| {
            let a = ColliderRef::dynamic(c.a);
            let b = match c.b.dynamic_index() {
                Some(i) => ColliderRef::dynamic(proxies.of_body[i]),
                None => c.b,
            };
            (bodies.pair_order(a, c.b), proxies.of_body[c.a as usize], b)
        };
        let keyed = &mut self.narrow.woken;
        keyed.clear();
        let woken = |c: &Constraint| woke_now(ColliderRef::dynamic(c.a)) || woke_now(c.b);
        self.solved
            .retain(|c| !woken(c), |c, _| keyed.push(keyed_pair(&c)));
        for c in self.sleeping.list.rows.iter().filter(|c| woken(c)) {
            keyed.push(keyed_pair(c));
        }
        keyed.sort_unstable_by_key(|k| k.0);
        keyed.dedup_by_key(|k| k.0);
        let events = &self.events;
        let narrow = PairContext {
            proxies,
            bodies,
            gravity: step.gravity,
            h: step.h,
            slop,
            pressed: &|key| events.pressed(key),
        };
        // Merge the contacts found again into the solved list, in key order.
        let mut merge = Merge::new(&mut self.solved, &mut self.scratch);
        for &(_, pa, pb) in keyed.iter() {
            if let Outcome::Contact(row, info) = narrow.pair(pa, pb) {
                merge.push(row, info);
            }
        }
        merge.finish();
        self.sleeping.drop_awake(dynamic);
    }

    /// After the last substep: finds which bodies are inside sensors now,
    /// does the sleeping bookkeeping (with `sleep`, the step's length and
    /// the contact slop, when sleeping is on), caches impulses for warm
    /// starting and works out which pairs began and ended touching (on
    /// the thread pool when `parallel` and the contacts are many).
    pub(crate) fn end_step(
        &mut self,
        dynamic: &mut DynamicBodies,
        statics: &StaticBodies,
        links: &[(u32, u32)],
        sleep: Option<(f32, f32)>,
        step: u64,
        parallel: bool,
    ) {
        self.events.find_sensor_overlaps(
            &self.narrow.sensor_candidates,
            dynamic,
            statics,
            &self.motion.start,
        );
        if let Some((dt, slop)) = sleep {
            let moved = &self.motion.delta;
            (self.sleeping).after_step(&mut self.solved, dynamic, links, moved, dt, slop);
        }
        self.events
            .record(&self.solved, &self.sleeping.list, step, parallel);
        self.revision += 1;
        self.bodies_moved = false;
    }

    /// A step in which the contact stage has nothing to do (its colliders
    /// were removed, or contacts were turned off): every contact and
    /// overlap ends, and every body wakes.
    pub(crate) fn idle_step(
        &mut self,
        dynamic: &mut DynamicBodies,
        statics: &StaticBodies,
        step: u64,
    ) {
        self.solved.clear();
        self.narrow.sensor_candidates.clear();
        self.wake_all(dynamic);
        self.end_step(dynamic, statics, &[], None, step, false);
    }

    /// Wakes dynamic body `i` now and its island before anything needs it
    /// (see [`flush_wakes`](Self::flush_wakes)).
    pub(crate) fn wake_body(&mut self, dynamic: &mut DynamicBodies, i: usize) {
        self.sleeping.wake_body(dynamic, i);
        self.revision += 1;
    }

    /// Wakes every body (nothing to do when every body is awake).
    pub(crate) fn wake_all(&mut self, dynamic: &mut DynamicBodies) {
        self.sleeping.wake_all(dynamic);
        self.revision += 1;
    }

    /// Wakes every body for game code, keeping the stored contacts listed
    /// until the next step (see `SleepingContacts::wake_all_later`).
    pub(crate) fn wake_all_later(&mut self, dynamic: &mut DynamicBodies) {
        self.sleeping.wake_all_later(dynamic);
        self.revision += 1;
    }

    /// Wakes the islands game code woke since the last step.
    pub(crate) fn flush_wakes(&mut self, dynamic: &mut DynamicBodies) {
        if self.sleeping.has_pending() {
            self.sleeping.flush(dynamic);
            self.revision += 1;
        }
    }

    /// Whether game code woke `island` since the last step (its bodies
    /// count as awake already).
    pub(crate) fn wakes_pending(&self, island: u32) -> bool {
        self.sleeping.is_pending(island)
    }

    /// Whether any island waits to wake.
    pub(crate) fn has_pending_wakes(&self) -> bool {
        self.sleeping.has_pending()
    }

    /// The contact lists name bodies that changed (a static body was
    /// removed): what is built from them is stale.
    pub(crate) fn lists_changed(&mut self) {
        self.revision += 1;
        self.bodies_moved = true;
    }

    /// Kinematic body `k` (a dynamic index, of `bodies`) is being removed:
    /// what it pressed against an immovable body starts the next step cold,
    /// as when a press moves off (see `crush`). The last step's contacts
    /// are reported as they were.
    pub(crate) fn press_removed(&mut self, k: u32, bodies: usize) {
        let released = self
            .motion
            .crushes
            .released_by_removal(&self.solved.rows, bodies, k);
        for &r in released {
            self.events
                .forget_impulses(self.solved.infos[r as usize].key());
        }
    }

    /// Dynamic body `to` was removed, and `from` (the last one) now sits at
    /// its index.
    pub(crate) fn body_moved(&mut self, from: u32, to: u32) {
        self.sleeping.body_moved(from, to);
        self.revision += 1;
        self.bodies_moved = true;
    }

    /// The narrow phase's buffers (for tests).
    #[cfg(test)]
    pub(crate) fn narrow(&self) -> &NarrowPhase {
        &self.narrow
    }

    /// Turns the step's shortcuts off, or on again (see [`TestSwitches`]).
    pub(crate) fn set_switches(&mut self, switches: TestSwitches) {
        self.switches = switches;
        self.proxies.switches = switches;
        self.narrow.switches = switches;
        self.regions.set_switches(switches);
        self.supports.switches = switches;
    }

    /// What the step's shortcuts saved, and the work they did not save.
    pub(crate) fn count(&self, counters: &mut StepCounters) {
        let (p, n) = (&self.proxies, &self.narrow);
        counters.grid_pairs_reused = p.grid_pairs_reused;
        counters.grown_pairs_reused = p.grown_pairs_reused;
        counters.static_pairs_reused = p.static_pairs_reused;
        counters.pair_sorts = n.pair_sorts;
        counters.contacts_reused_in_place = n.contacts_reused_in_place;
        counters.colourings_reused = self.regions.colourings_reused();
        counters.supports_reused = self.supports.reused;
        counters.sleep_tree_builds = self.sleeping.tree_builds;
    }

    /// The proxies and their pairs, to change (for tests).
    #[cfg(test)]
    pub(crate) fn proxies_mut(&mut self) -> &mut Proxies {
        &mut self.proxies
    }

    /// Crowded grid buckets in this step's pair search (their pairs were
    /// bounded: bodies piled on one spot).
    pub(crate) fn crowded(&self) -> usize {
        self.proxies.crowded()
    }

    /// How many times the contact lists changed.
    pub(crate) fn revision(&self) -> u64 {
        self.revision
    }

    /// Every contact after the last step: the solved ones, then those
    /// between sleeping bodies.
    pub(crate) fn all_contacts(&self) -> impl Iterator<Item = (&Constraint, &ContactInfo)> + Clone {
        self.solved.iter().chain(self.sleeping.list.iter())
    }

    /// The contact at `position` in the order of
    /// [`all_contacts`](Self::all_contacts).
    pub(crate) fn contact_at(&self, position: usize) -> Option<(&Constraint, &ContactInfo)> {
        let solved = self.solved.len();
        let (list, k) = if position < solved {
            (&self.solved, position)
        } else {
            (&self.sleeping.list, position - solved)
        };
        Some((list.rows.get(k)?, list.infos.get(k)?))
    }

    /// Sensor overlaps after the last step.
    pub(crate) fn sensor_overlaps(&self) -> &[SensorPair] {
        &self.events.sensors_prev
    }

    /// Contact and sensor events of the last step.
    pub(crate) fn events(&self) -> &ContactEvents {
        &self.events.events
    }

    /// Writes what the next step needs from the last one into `out`,
    /// reusing its buffers: warm-start impulses, who touched whom (for
    /// begin and end events) and the stored contacts of sleeping islands;
    /// and the awake contacts, for queries until the next step. `locate`
    /// tells where a live body sits now.
    pub(crate) fn carry_into(
        &self,
        dynamic: &DynamicBodies,
        statics: &StaticBodies,
        locate: impl Fn(BodyId) -> Option<ColliderRef>,
        out: &mut ContactState,
    ) {
        out.cache.clone_from(&self.events.cache);
        out.touching.clone_from(&self.events.touching_prev);
        out.sensors.clone_from(&self.events.sensors_prev);
        out.asleep.clone_from(&self.sleeping.list.rows);
        out.asleep_infos.clone_from(&self.sleeping.list.infos);
        self.carry_awake(dynamic, statics, locate, out);
    }

    /// The awake contacts into `out`: a plain copy while no removal moved
    /// bodies since the step; after one, each contact points at
    /// where its bodies sit now (`locate`), and those of removed bodies
    /// are left out.
    fn carry_awake(
        &self,
        dynamic: &DynamicBodies,
        statics: &StaticBodies,
        locate: impl Fn(BodyId) -> Option<ColliderRef>,
        out: &mut ContactState,
    ) {
        if self.bodies_moved {
            let (rows, infos) = (&mut out.awake, &mut out.awake_infos);
            relocate(&self.solved, dynamic, statics, locate, rows, infos);
        } else {
            out.awake.clone_from(&self.solved.rows);
            out.awake_infos.clone_from(&self.solved.infos);
        }
        if self.reuse_forgotten {
            forget_all(&mut out.awake_infos);
        }
    }

    /// Before a step: the last step's contacts as the narrow phase reuses
    /// them, each pointing at where its bodies sit now, as a snapshot
    /// carries them (see [`carry_awake`](Self::carry_awake)), so a world
    /// restored from one reuses what this one does.
    pub(crate) fn relocate_last_contacts(
        &mut self,
        dynamic: &DynamicBodies,
        statics: &StaticBodies,
        locate: impl Fn(BodyId) -> Option<ColliderRef>,
    ) {
        if std::mem::take(&mut self.bodies_moved) {
            let (rows, infos) = (&mut self.last.rows, &mut self.last.infos);
            relocate(&self.solved, dynamic, statics, locate, rows, infos);
        } else {
            std::mem::swap(&mut self.solved, &mut self.last);
        }
        if std::mem::take(&mut self.reuse_forgotten) {
            forget_all(&mut self.last.infos);
        }
    }

    /// Game code changed what body `id` collides with (friction,
    /// restitution, friction mix, filter, sensor, one-way side): the next
    /// step finds its
    /// contacts afresh, not reusing the last step's.
    pub(crate) fn forget_reuse(&mut self, id: BodyId) {
        if self.reuse_forgotten {
            return;
        }
        for info in &mut self.solved.infos {
            if info.id_a == id || info.id_b == id {
                info.reusable = false;
            }
        }
    }

    /// Every contact is found afresh at the next step (the static bodies or
    /// the settings changed): marked there, and in a snapshot taken before
    /// it, so that adding a tile map's thousand boxes does not walk the
    /// contacts a thousand times.
    pub(crate) fn forget_all_reuse(&mut self) {
        self.reuse_forgotten = true;
    }

    /// Puts this contact stage in the state [`resume`](Self::resume) would
    /// make from `state`, reusing its buffers; with `statics_changed` the
    /// static tree is built again at the next step, else it is kept.
    pub(crate) fn restore(&mut self, state: &ContactState, statics_changed: bool) {
        if statics_changed {
            self.proxies.statics_changed();
        }
        self.solved.rows.clone_from(&state.awake);
        self.solved.infos.clone_from(&state.awake_infos);
        self.narrow.sensor_candidates.clear();
        self.sleeping.restore(&state.asleep, &state.asleep_infos);
        self.events.cache.clone_from(&state.cache);
        self.events.fresh = false;
        self.events.touching_prev.clone_from(&state.touching);
        self.events.sensors_prev.clone_from(&state.sensors);
        self.events.events.clear();
        self.events.events.step = 0;
        self.revision += 1;
        // The awake contacts are those of the snapshot's bodies.
        self.bodies_moved = false;
        self.reuse_forgotten = false;
    }

    /// A contact stage resuming from a carried state.
    pub(crate) fn resume(state: ContactState) -> Self {
        let mut world = Self::new();
        world.sleeping = SleepingContacts::resume(state.sleeping());
        world.solved = state.awake();
        world.events.cache = state.cache;
        world.events.touching_prev = state.touching;
        world.events.sensors_prev = state.sensors;
        world
    }
}

/// `solved`'s contacts into `rows` and `infos`, each pointing at where its
/// bodies sit now (`locate`), leaving out those of removed bodies.
fn relocate(
    solved: &ContactList,
    dynamic: &DynamicBodies,
    statics: &StaticBodies,
    locate: impl Fn(BodyId) -> Option<ColliderRef>,
    rows: &mut Vec<Constraint>,
    infos: &mut Vec<ContactInfo>,
) {
    rows.clear();
    infos.clear();
    for (c, info) in solved.iter() {
        // Body A of a row is `id_a`, and dynamic.
        let (Some(a), Some(b)) = (locate(info.id_a), locate(info.id_b)) else {
            continue;
        };
        let Some(a) = a.dynamic_index() else {
            continue;
        };
        let row = Constraint {
            a: a as u32,
            b,
            ..*c
        };
        if names_bodies(&row, info, dynamic, statics) {
            rows.push(row);
            infos.push(*info);
        }
    }
}

/// Marks every contact of `infos` to be found afresh.
fn forget_all(infos: &mut [ContactInfo]) {
    for info in infos {
        info.reusable = false;
    }
}
