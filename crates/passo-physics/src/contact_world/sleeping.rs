//! Sleeping: bodies at rest stop costing contact work.
//!
//! A pile that has settled is solved again every step for nothing: the
//! minimum-speed snap already holds its velocities at exactly zero, and the
//! solver only confirms that the weights are carried. So the contact stage
//! groups dynamic bodies into islands (bodies joined by touching contacts,
//! or by contacts within the slop, where one would wake the other) and
//! puts an island to sleep when every body in it has been slower than
//! [`SLEEP_SPEED`](crate::constants::SLEEP_SPEED) for
//! [`TIME_TO_SLEEP`](crate::constants::TIME_TO_SLEEP). A sleeping body keeps its
//! position, has zero velocity and is not integrated. Its contacts with
//! other sleeping bodies and with static ones are stored as they were when
//! it fell asleep (so `contacts`, `is_standing` and events still see them)
//! and cost nothing: the broad phase skips pairs of sleeping bodies, and
//! sleeping bodies are not queried against static ones.
//!
//! An awake body reaching a sleeping one meets it as if it were static for
//! that step; if they touch, the sleeping island wakes, all of it, for the
//! next step. Game code changing a body (force, impulse, velocity,
//! position, material, removal) wakes its island at once; changing the
//! world's settings, its force models or a static body wakes every body.
//! Bodies inside a sensor stay awake. Every decision depends only on the
//! state, in a fixed order, so sleeping is as deterministic as the rest of
//! the step.

use crate::Aabb;
use crate::body::store::DynamicBodies;
use crate::collision::proxies::{NO_PROXY, ProxyMargin};
use crate::contact::constraint::{Constraint, ContactInfo, ContactList, Merge};
use crate::contact_world::island::Islands;
use crate::geometry::static_tree::StaticTree;
use glam::Vec2;
use std::collections::HashSet;

/// Islands woken by game code between two steps that fit without an
/// allocation once a world has slept.
const PENDING_ROOM: usize = 64;

/// The sleeping side of the contact stage: the stored contacts of sleeping
/// islands, the tree that finds sleeping bodies an awake one reaches, and
/// the island bookkeeping. Kept between steps.
#[derive(Clone, Debug, Default)]
pub(crate) struct SleepingContacts {
    /// Contacts between sleeping bodies (or a sleeping and a static one),
    /// kept as they were when their island fell asleep; sorted by pair.
    pub list: ContactList,
    /// Room for merging contacts, kept between steps.
    scratch: ContactList,
    /// Sleeping bodies, in a tree rebuilt when one falls asleep (see
    /// `update_tree`); items are `tree_bodies` entries.
    tree: StaticTree,
    /// Dynamic index per sleep-tree item (`NO_PROXY` once removed).
    tree_bodies: Vec<u32>,
    /// Per dynamic body: whether it is in the sleep tree.
    tree_member: Vec<bool>,
    /// Sleeping bodies one proxy reaches (scratch).
    hits: Vec<u32>,
    /// Entries of the tree whose bodies woke (and left) since it was built.
    left: usize,
    /// Builds of the tree (see `StepCounters::sleep_tree_builds`).
    pub(crate) tree_builds: u64,
    /// The margins the tree's boxes were grown by (they follow gravity, the
    /// step and continuous collision: a change rebuilds the tree).
    built_margin: ProxyMargin,
    /// Island bookkeeping.
    islands: Islands,
    /// Islands game code woke since the last step (by their id): they wake
    /// all together when the next step begins (or a removal or a snapshot
    /// needs them awake), so waking one island costs one lookup, not a
    /// pass over every body. Looked up, never iterated.
    pending: HashSet<u32>,
    /// Game code woke every body since the last step: the stored contacts
    /// and the sleep tree go when the next step begins (or a removal or a
    /// snapshot needs them gone), as a woken island's do; until then
    /// queries still see the contacts.
    all_pending: bool,
}

impl SleepingContacts {
    /// Sleeping contacts resumed from a snapshot.
    pub(crate) fn resume(list: ContactList) -> Self {
        Self {
            list,
            ..Self::default()
        }
    }

    /// Back to the state [`resume`](Self::resume) makes from these stored
    /// contacts, reusing the buffers (the sleep tree empties, and is built
    /// again when the next steps need it).
    pub(crate) fn restore(&mut self, rows: &[Constraint], infos: &[ContactInfo]) {
        self.list.rows.clear();
        self.list.rows.extend_from_slice(rows);
        self.list.infos.clear();
        self.list.infos.extend_from_slice(infos);
        self.scratch.clear();
        self.tree.rebuild([]);
        self.tree_bodies.clear();
        self.tree_member.clear();
        self.hits.clear();
        self.left = 0;
        self.islands.clear();
        self.pending.clear();
        self.all_pending = false;
    }

    /// Whether any body sleeps, leaving out the islands game code woke
    /// since the last step (their bodies are awake at once, and wake for
    /// good when the next step begins): what the next step will find, so
    /// that `World::contact_stages` lists what it runs. Stored contacts
    /// are those of sleeping bodies.
    pub(crate) fn any(&self, dynamic: &DynamicBodies) -> bool {
        let sleeps = |island: u32| !self.is_pending(island);
        dynamic.sleep.iter().any(|s| s.island().is_some_and(sleeps))
    }

    /// Whether dynamic body `i` sleeps in the tree (it then needs no proxy
    /// unless an awake one reaches it). Once the step's `begin` has run,
    /// every sleeping shaped body is in it: asked of those alone, `true`
    /// would answer the same.
    pub(crate) fn in_tree(&self, i: usize) -> bool {
        self.tree_member[i]
    }

    /// Starts a step: sizes the per-body flags, and (with sleeping bodies)
    /// rebuilds the tree when enough changed.
    pub(crate) fn begin(
        &mut self,
        dynamic: &DynamicBodies,
        any_asleep: bool,
        margin: &ProxyMargin,
    ) {
        self.tree_member.resize(dynamic.len(), false);
        if any_asleep {
            self.update_tree(dynamic, margin);
        } else if !self.tree_bodies.is_empty() {
            // Nobody sleeps: every member woke. Forget them now, or one
            // falling asleep elsewhere later would be looked for at its old
            // box.
            self.tree.rebuild([]);
            self.tree_bodies.clear();
            self.tree_member.fill(false);
            self.left = 0;
        }
    }

    /// Rebuilds the sleep tree over every sleeping shaped body when one is
    /// missing from it (it fell asleep since the last build), half of its
    /// entries woke, or the margin its boxes are grown by changed (with
    /// gravity, the step or continuous collision). Members that woke leave
    /// at once (their entries are skipped). So the tree holds exactly the
    /// sleeping bodies, at the places they sleep, grown by today's margin:
    /// what it finds depends on the bodies and settings alone, never on
    /// when it was built, and a world restored from a snapshot (which
    /// builds it afresh) steps as the original does. Islands fall asleep
    /// seldom, so the `O(n log n)` builds are rare.
    fn update_tree(&mut self, dynamic: &DynamicBodies, margin: &ProxyMargin) {
        let mut missing = 0;
        for (i, s) in dynamic.sleep.iter().enumerate() {
            let shaped = dynamic.meta[i].shape.is_some();
            missing += usize::from(shaped && s.is_asleep() && !self.tree_member[i]);
            // A member that woke leaves at once (its entry is skipped until
            // the next build): should it fall asleep again elsewhere, it is
            // missing, never found at its old box.
            if self.tree_member[i] && !s.is_asleep() {
                self.tree_member[i] = false;
                self.left += 1;
            }
        }
        if missing == 0 && 2 * self.left <= self.tree.len() && margin.grows_like(&self.built_margin)
        {
            return;
        }
        self.built_margin = *margin;
        self.tree_builds += 1;
        self.tree_member.fill(false);
        self.tree_bodies.clear();
        self.left = 0;
        // Room for every body: later rebuilds allocate nothing.
        let n = dynamic.len();
        self.tree_bodies.reserve(n);
        self.tree.reserve(n);
        self.hits.reserve(n);
        for (i, s) in dynamic.sleep.iter().enumerate() {
            if s.is_asleep() && dynamic.meta[i].shape.is_some() {
                self.tree_bodies.push(i as u32);
                self.tree_member[i] = true;
            }
        }
        let boxes = self.tree_bodies.iter().map(|&i| {
            let shape = dynamic.meta[i as usize].shape.expect("shaped");
            Aabb::from_centre(dynamic.pos.at(i as usize), shape.half_extents())
                .grown(margin.of(Vec2::ZERO, &shape))
        });
        self.tree.rebuild(boxes);
    }

    /// The sleeping bodies of the tree whose boxes overlap `aabb`.
    pub(crate) fn reached(&mut self, aabb: &Aabb, dynamic: &DynamicBodies) -> &[u32] {
        self.hits.clear();
        let (hits, bodies) = (&mut self.hits, &self.tree_bodies);
        let member = &self.tree_member;
        self.tree.query(aabb, |item| {
            let body = bodies[item as usize];
            let b = body as usize;
            if body != NO_PROXY && member[b] && dynamic.sleep[b].is_asleep() {
                hits.push(body);
            }
        });
        &self.hits
    }

    /// After a step (sleeping on): rest times, waking islands an awake body
    /// touched (for the next step: during this one they held like static
    /// bodies), and putting islands that rested long enough to sleep, with
    /// their contacts moved from `solved` to the stored list. `moved` is
    /// each body's displacement over the step; `slop` is the contact
    /// settings' allowed overlap.
    pub(crate) fn after_step(
        &mut self,
        solved: &mut ContactList,
        dynamic: &mut DynamicBodies,
        links: &[(u32, u32)],
        moved: &[Vec2],
        dt: f32,
        slop: f32,
    ) {
        self.islands.rest(dynamic, moved, dt);
        let mut woke = false;
        // A joint between an awake body and a sleeping one wakes the
        // sleeper's island (they share one once both are awake).
        for &(a, b) in links {
            let (a, b) = (a as usize, b as usize);
            if dynamic.sleep[a].is_asleep() != dynamic.sleep[b].is_asleep() {
                let sleeper = if dynamic.sleep[a].is_asleep() { a } else { b };
                self.islands.wake_body(dynamic, sleeper);
                woke = true;
            }
        }
        for (c, info) in solved.iter() {
            if c.is_static() || !info.is_touching(c) {
                continue;
            }
            for body in [c.a as usize, c.b.index()] {
                if dynamic.sleep[body].is_asleep() {
                    self.islands.wake_body(dynamic, body);
                    woke = true;
                }
            }
        }
        if woke {
            // The woken islands' stored contacts join the solved ones, so
            // the step's record keeps their impulses for warm starting and
            // sees them still touching (dropped, the next step began them
            // afresh: a woken stack sagged and popped up, and every pair
            // ended and began touching again).
            self.wake_marked_islands(dynamic);
            let mut merge = Merge::new(solved, &mut self.scratch);
            self.list.retain(
                |c| !has_awake_body(dynamic, c),
                |c, info| merge.push(c, info),
            );
            merge.finish();
        }
        if self
            .islands
            .fall_asleep(dynamic, &solved.rows, &solved.infos, links, slop, dt)
        {
            self.store(solved, dynamic);
        }
    }

    /// Moves the solved contacts whose bodies all sleep now into the stored
    /// list, keeping both lists in key order.
    fn store(&mut self, solved: &mut ContactList, dynamic: &DynamicBodies) {
        // Room for the islands game code may wake between two steps, so a
        // few wakes allocate nothing once a world has slept.
        self.pending.reserve(PENDING_ROOM);
        let mut merge = Merge::new(&mut self.list, &mut self.scratch);
        solved.retain(
            |c| has_awake_body(dynamic, c),
            |c, info| merge.push(c, info),
        );
        merge.finish();
    }

    /// Forgets the stored contacts of bodies that woke: the next step finds
    /// them afresh.
    pub(crate) fn drop_awake(&mut self, dynamic: &DynamicBodies) {
        self.list.retain(|c| !has_awake_body(dynamic, c), |_, _| {});
    }

    /// Marks the island of dynamic body `i` to be woken (the body itself
    /// wakes at once); [`wake_marked`](Self::wake_marked) wakes the rest.
    pub(crate) fn mark(&mut self, dynamic: &mut DynamicBodies, i: usize) {
        self.islands.wake_body(dynamic, i);
    }

    /// Wakes the marked islands, keeping their stored contacts for now
    /// (see [`drop_awake`](Self::drop_awake)).
    pub(crate) fn wake_marked_islands(&mut self, dynamic: &mut DynamicBodies) {
        self.islands.wake_marked(dynamic);
    }

    /// Wakes the marked islands and forgets their stored contacts.
    pub(crate) fn wake_marked(&mut self, dynamic: &mut DynamicBodies) {
        self.wake_marked_islands(dynamic);
        self.drop_awake(dynamic);
    }

    /// Wakes dynamic body `i` now and its island at the next
    /// [`flush`](Self::flush) (the body's island mates report awake from
    /// now on, see [`is_pending`](Self::is_pending)).
    pub(crate) fn wake_body(&mut self, dynamic: &mut DynamicBodies, i: usize) {
        if let Some(island) = dynamic.sleep[i].island() {
            self.pending.insert(island);
        }
        self.islands.wake_body(dynamic, i);
    }

    /// Whether game code woke `island` since the last step.
    pub(crate) fn is_pending(&self, island: u32) -> bool {
        self.all_pending || self.pending.contains(&island)
    }

    /// Whether any island waits to wake. (A shortcut: flushing with none
    /// waiting changes nothing but the contacts' revision.)
    pub(crate) fn has_pending(&self) -> bool {
        self.all_pending || !self.pending.is_empty()
    }

    /// Wakes the islands game code woke since the last step: one pass
    /// over the bodies and the stored contacts for all of them (or, after
    /// [`wake_all_later`](Self::wake_all_later), lets every stored contact
    /// go).
    pub(crate) fn flush(&mut self, dynamic: &mut DynamicBodies) {
        if std::mem::take(&mut self.all_pending) {
            self.pending.clear();
            self.forget_stored();
        } else if !self.pending.is_empty() {
            self.pending.clear();
            self.wake_marked(dynamic);
        }
    }

    /// Wakes every body now. Nothing happens when every body is already
    /// awake with no rest time and nothing is stored: the step calls this
    /// while sleeping is off and while the stage is idle. (A safety net:
    /// the settings change that turns sleeping off, and the removals that
    /// leave no collider, have woken every body already.)
    pub(crate) fn wake_all(&mut self, dynamic: &mut DynamicBodies) {
        if self.wake_every_body(dynamic) {
            self.all_pending = false;
            self.forget_stored();
        }
    }

    /// Wakes every body, for game code: the bodies report awake at once,
    /// and their stored contacts stay listed for queries until the next
    /// [`flush`](Self::flush), as a woken island's do (they vanished at
    /// once: a sleeping player reported not standing until the next step).
    pub(crate) fn wake_all_later(&mut self, dynamic: &mut DynamicBodies) {
        if self.wake_every_body(dynamic) {
            self.all_pending = true;
        }
    }

    /// Every body awake and no island marked or pending; false (and
    /// nothing done) when every body was awake with no rest time already
    /// and nothing is stored.
    fn wake_every_body(&mut self, dynamic: &mut DynamicBodies) -> bool {
        self.pending.clear();
        self.islands.forget_marks();
        // (With every body awake and fresh, entries left in the tree are
        // of bodies that woke, which every search skips: `!=` here would
        // keep them a while, finding nothing more.)
        if self.list.is_empty() && self.tree.len() == 0 && dynamic.all_fresh() {
            return false;
        }
        dynamic.wake_all();
        true
    }

    /// Lets go of every stored contact and empties the sleep tree.
    fn forget_stored(&mut self) {
        self.list.clear();
        self.tree.rebuild([]);
        self.tree_bodies.clear();
        self.tree_member.fill(false);
        self.left = 0;
    }

    /// Dynamic body `to` was removed and `from` (the last one) now sits at
    /// its index. The removed body's stored contacts go; its island mates'
    /// stay listed for queries until the next [`flush`](Self::flush) wakes
    /// them, as for any island game code wakes.
    pub(crate) fn body_moved(&mut self, from: u32, to: u32) {
        let names_removed = |c: &Constraint| c.a == to || c.b.dynamic_index() == Some(to as usize);
        self.list.retain(|c| !names_removed(c), |_, _| {});
        for body in &mut self.tree_bodies {
            if *body == to {
                *body = NO_PROXY; // removed
            } else if *body == from {
                *body = to;
            }
        }
        self.tree_member.resize(from as usize + 1, false);
        self.tree_member.swap_remove(to as usize);
        for c in &mut self.list.rows {
            if c.a == from {
                c.a = to;
            }
            if c.b.dynamic_index() == Some(from as usize) {
                c.b = c.b.with_index(to);
            }
        }
    }
}

/// Whether a contact has an awake dynamic body (so the solver works on it).
pub(crate) fn has_awake_body(dynamic: &DynamicBodies, c: &Constraint) -> bool {
    !dynamic.sleep[c.a as usize].is_asleep()
        || c.b
            .dynamic_index()
            .is_some_and(|b| !dynamic.sleep[b].is_asleep())
}
