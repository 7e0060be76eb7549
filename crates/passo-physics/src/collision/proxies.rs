//! Candidate pairs: each shaped dynamic body's bounding box (its proxy),
//! swept along how far it can move this step, is paired with the proxies
//! of the grid ([`BroadPhase`]) it overlaps; grown by that distance in
//! every direction, with the static bodies of the static tree and the
//! sleeping bodies it overlaps.

use crate::body::collider::ColliderRef;
use crate::body::store::{BodyMeta, DynamicBodies, StaticBodies};
use crate::collision::broad_phase::BroadPhase;
use crate::constants::{LINEAR_SLOP, SPECULATIVE_DISTANCE, SPECULATIVE_REACH};
use crate::geometry::manifold::Faces;
use crate::geometry::static_tree::StaticTree;
use crate::parallel::for_chunks;
use crate::switches::TestSwitches;
use crate::{Aabb, Shape};
use glam::Vec2;

/// The step searches a tree of the static bodies near its awake proxies
/// when they are fewer than one in this many of the whole level...
const NARROWED_TREE: usize = 8;
/// ...and the level has at least this many static bodies.
const NARROWED_LEVEL: usize = 256;

/// No proxy (or no body) here.
pub(crate) const NO_PROXY: u32 = u32::MAX;

/// Most kinematic boxes within reach of one whose covered faces are
/// worked out: a box of a moving tile map has eight neighbours at most, and
/// one with more than 64 lies in a pile (bodies generated on one spot),
/// where looking at every other box made a step `O(k²)`.
const MAX_KINEMATIC_NEIGHBOURS: usize = 64;

/// Most static bodies one proxy is paired with in a step: the first this
/// many the static tree finds (a fixed order). A box 12 m wide lying on
/// 0.1 m static tiles meets about 120; a body among static bodies piled on
/// one spot met every one of them, so 5 000 dynamic bodies on 5 000 static
/// ones made 25 million contacts (45 s and 9.6 GB for one step).
const MAX_STATIC_NEIGHBOURS: usize = 128;

/// How much a settled scene's boxes are grown, all round, for the pairs
/// kept while each box stays inside its grown one (see
/// [`Proxies::find_pairs`]): an eighth of each box's smaller side. A pile
/// that jitters by micrometres stays inside for good, and the grown boxes
/// meet few more boxes than the boxes do.
const ENLARGED_FRACTION: f32 = 0.125;

/// How far a body's speculative contacts reach (its *margin*): half the
/// speculative distance, plus the body's possible travel this step with
/// continuous collision, up to its reach ([`SPECULATIVE_REACH`] of its
/// smallest half extent; a kinematic body's whole travel). Its proxy is
/// swept along that travel in the direction it moves (see
/// [`swept`](Self::swept)).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct ProxyMargin {
    /// Speed gravity can add this step, m/s.
    pub fall: f32,
    pub dt: f32,
    pub continuous: bool,
}

impl ProxyMargin {
    /// The margin of a body of `shape` moving at `velocity`, metres.
    pub(crate) fn of(&self, velocity: Vec2, shape: &Shape) -> f32 {
        Self::within(self.travel(velocity), reach(shape))
    }

    /// The margin of a body that may travel `travel` this step, as far as
    /// its contacts `reach`.
    #[inline(always)]
    fn within(travel: f32, reach: f32) -> f32 {
        Self::STATIC + travel.min(reach)
    }

    /// How far a body moving at `velocity` can travel this step, metres
    /// (zero without continuous collision).
    fn travel(&self, velocity: Vec2) -> f32 {
        if self.continuous {
            (velocity.length() + self.fall) * self.dt
        } else {
            0.0
        }
    }

    /// Whether every body's margin is the same with `other` (without
    /// continuous collision the step and gravity do not matter).
    pub(crate) fn grows_like(&self, other: &Self) -> bool {
        self.continuous == other.continuous && (!self.continuous || self == other)
    }

    /// The proxy box of dynamic body `i` and its margin; `None` if it has
    /// no shape. A kinematic body is never swept by continuous collision
    /// (it goes where it is told), so its proxy covers its whole travel: a
    /// fast wall meets the resting bodies in its way. A level has few of
    /// them.
    #[inline(always)]
    fn proxy(&self, dynamic: &DynamicBodies, i: usize) -> Option<Proxy> {
        let meta = &dynamic.meta[i];
        let shape = meta.shape?;
        let velocity = dynamic.vel.at(i);
        // The travel once, for the margin and both boxes.
        let travel = self.travel(velocity);
        let reach = if meta.kinematic {
            f32::INFINITY
        } else {
            reach(&shape)
        };
        let margin = Self::within(travel, reach);
        let aabb = Aabb::from_centre(dynamic.pos.at(i), shape.half_extents());
        Some(Proxy {
            swept: self.swept(aabb, velocity, travel, reach),
            around: aabb.grown(margin),
            margin,
        })
    }

    /// Whether a body of `shape` moving at `velocity` may travel farther
    /// this step than its speculative contacts reach (see [`reach`]).
    #[inline(always)]
    pub(crate) fn beyond_reach(&self, velocity: Vec2, shape: &Shape) -> bool {
        self.travel(velocity) > reach(shape)
    }

    /// `aabb` grown by half the speculative distance all round, by what
    /// gravity can add this step in any direction, and along the body's
    /// travel at `velocity` this step (`travel` long, from
    /// [`travel`](Self::travel)): where the body may be during the
    /// step, if it goes on or stops. (Grown by its travel in every
    /// direction, two bodies falling side by side were a pair; the narrow
    /// phase then found nothing to close, see `narrow_phase`.) A body that
    /// may travel farther than `reach` is grown by `reach` in every
    /// direction instead: so fast, or over so long a step, that contacts
    /// may turn it far from where it was heading.
    #[inline(always)]
    fn swept(&self, aabb: Aabb, velocity: Vec2, travel: f32, reach: f32) -> Aabb {
        let grown = aabb.grown(Self::STATIC);
        if !self.continuous {
            return grown;
        }
        if travel > reach {
            return grown.grown(reach);
        }
        let travel = velocity * self.dt;
        let fall = Vec2::splat(self.fall * self.dt);
        Aabb {
            min: grown.min + travel.min(Vec2::ZERO) - fall,
            max: grown.max + travel.max(Vec2::ZERO) + fall,
        }
    }

    /// The margin a static body adds to a pair.
    pub(crate) const STATIC: f32 = 0.5 * SPECULATIVE_DISTANCE;

    /// How far a proxy of margin `margin` lets its body's contacts reach
    /// beyond a static body's: its travel this step, no farther than its
    /// reach (see [`within`](Self::within)).
    #[inline(always)]
    pub(crate) fn reached(margin: f32) -> f32 {
        margin - Self::STATIC
    }
}

/// A body's boxes and margin this step (see [`ProxyMargin`]).
#[derive(Clone, Copy, Debug)]
struct Proxy {
    swept: Aabb,
    around: Aabb,
    margin: f32,
}

/// How far the speculative contacts of a body of `shape` reach along its
/// travel, metres.
pub(crate) fn reach(shape: &Shape) -> f32 {
    SPECULATIVE_REACH * shape.half_extents().min_element()
}

/// The proxies of one step and the pairs found among them, with the static
/// tree they are queried against. Kept between steps so it allocates
/// nothing once warm.
#[derive(Clone, Debug, Default)]
pub(crate) struct Proxies {
    grid: BroadPhase,
    tree: StaticTree,
    /// Static index per tree item.
    tree_items: Vec<u32>,
    /// Per static body: the faces other static boxes cover (seamless
    /// ground; see [`Faces`]).
    pub(crate) static_faces: Vec<Faces>,
    /// This step, by dynamic index: the faces of each kinematic box that
    /// static or other kinematic boxes cover; sorted.
    kinematic_faces: Vec<(u32, Faces)>,
    /// This step, by static index: the faces of static boxes that a
    /// kinematic box covers; sorted.
    faces_by_kinematic: Vec<(u32, Faces)>,
    tree_dirty: bool,
    /// This step: the static bodies near the awake proxies (by static
    /// index), their boxes, and a tree of them (see `find_pairs`).
    near_items: Vec<u32>,
    near_boxes: Vec<Aabb>,
    near_tree: StaticTree,
    /// This step: the kinematic boxes, and scratch space for the faces
    /// their neighbours cover.
    kinematic_tree: StaticTree,
    neighbours: Vec<Aabb>,
    spans: Vec<(f32, f32)>,
    /// Proxy -> dynamic index.
    pub body: Vec<u32>,
    /// Proxy -> its body's slot (`BodyId` index), which orders pairs.
    pub slot: Vec<u32>,
    /// Proxy boxes in the grid: swept along each body's travel (see
    /// [`ProxyMargin::swept`]), a kinematic body's grown further by the
    /// farthest any other body's contacts reach (see
    /// [`widen_kinematic`](Self::widen_kinematic)).
    pub boxes: Vec<Aabb>,
    /// Per proxy: its body's box grown by its margin in every direction,
    /// which the static bodies are looked for in: a body turned by a
    /// contact during the step still meets a wall beside it.
    pub around: Vec<Aabb>,
    /// Per proxy: its body's travel margin this step.
    pub margins: Vec<f32>,
    /// Per proxy: whether its body sleeps (empty when none does).
    pub asleep: Vec<bool>,
    /// Per dynamic body: its proxy this step, or [`NO_PROXY`].
    pub of_body: Vec<u32>,
    /// How far proxies are grown this step.
    pub margin: ProxyMargin,
    /// Pairs of proxies, lower proxy first: the grid's (the first
    /// `grid_pairs`), then those with sleeping bodies.
    pub pairs: Vec<(u32, u32)>,
    /// How many of `pairs` the last grid search found.
    grid_pairs: usize,
    /// The boxes and the boxes grown all round of the last search, when
    /// it had none asleep and no kinematic proxy (otherwise empty); see
    /// [`find_pairs`](Self::find_pairs).
    searched_boxes: Vec<Aabb>,
    searched_around: Vec<Aabb>,
    /// Whether `boxes` and `around` are those of the last search (set by
    /// it, cleared when a step begins).
    boxes_searched: bool,
    /// Pairs of a proxy and a static body (by static index).
    pub static_pairs: Vec<(u32, u32)>,
    /// Proxies of the last pair search that met more than
    /// [`MAX_STATIC_NEIGHBOURS`] static bodies.
    static_crowded: usize,
    /// Static pairs found by each parallel task, concatenated in order.
    #[cfg(feature = "parallel")]
    task_pairs: Vec<Vec<(u32, u32)>>,
    /// The boxes of a settled scene grown all round (see
    /// [`ENLARGED_FRACTION`]), with every pair of them in
    /// `enlarged_pairs`; empty when the last search was not of a settled
    /// scene (see [`find_pairs`](Self::find_pairs)).
    enlarged: Vec<Aabb>,
    enlarged_pairs: Vec<(u32, u32)>,
    /// The grid's pairs of the last step, to tell a settled scene (one
    /// whose searches find the same pairs) and unchanged pairs.
    earlier_pairs: Vec<(u32, u32)>,
    /// The static pairs of the last step.
    earlier_static_pairs: Vec<(u32, u32)>,
    /// [`order_free_sum`] of the grid's pairs of the last search.
    pairs_sum: u64,
    /// Whether this step's pairs, the grid's and the static ones, are the
    /// last step's, in the same order and with the same static bodies:
    /// the narrow phase's keys of them are then the last step's too.
    pub pairs_same: bool,
    /// Whether the static tree was built again this step (other static
    /// bodies, or the same ones at other indices).
    tree_rebuilt: bool,
    /// Searches whose pairs were reused from the last one (see
    /// `StepCounters`).
    pub(crate) grid_pairs_reused: u64,
    /// Searches whose pairs were those of the grown boxes that the boxes
    /// overlap.
    pub(crate) grown_pairs_reused: u64,
    /// Searches whose pairs with static bodies were reused.
    pub(crate) static_pairs_reused: u64,
    /// The shortcuts turned off (`search_always`).
    pub(crate) switches: TestSwitches,
}

impl Proxies {
    pub(crate) fn new() -> Self {
        Self {
            tree_dirty: true,
            ..Self::default()
        }
    }

    /// Static bodies changed: rebuild the tree at the next step.
    pub(crate) fn statics_changed(&mut self) {
        self.tree_dirty = true;
    }

    /// Starts a step: rebuilds the static tree if static bodies changed and
    /// forgets the last step's proxies.
    pub(crate) fn begin(
        &mut self,
        dynamic: &DynamicBodies,
        statics: &StaticBodies,
        margin: ProxyMargin,
    ) {
        let bodies = dynamic.len();
        // The last search's boxes are kept to compare with this step's
        // (the lists trade places: nothing is copied).
        if self.boxes_searched {
            std::mem::swap(&mut self.boxes, &mut self.searched_boxes);
            std::mem::swap(&mut self.around, &mut self.searched_around);
        } else {
            self.searched_boxes.clear();
            self.searched_around.clear();
        }
        self.boxes_searched = false;
        self.tree_rebuilt = self.tree_dirty;
        if self.tree_dirty {
            self.rebuild_tree(statics);
            // Other static bodies: other pairs with them.
            self.searched_around.clear();
        }
        self.find_faces_covered_by_kinematic(dynamic, statics);
        self.body.clear();
        self.slot.clear();
        self.boxes.clear();
        self.around.clear();
        self.margins.clear();
        self.asleep.clear();
        self.margin = margin;
        self.of_body.clear();
        self.of_body.resize(bodies, NO_PROXY);
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
        self.find_covered_faces(statics);
        self.tree_dirty = false;
    }

    /// Which faces of each static box other static boxes cover, together
    /// (see [`Faces::covered_by_all`]), found with the static tree:
    /// `O(n log n)` for `n` static bodies, once per change.
    fn find_covered_faces(&mut self, statics: &StaticBodies) {
        let aabb = |i: usize| match statics.meta[i].shape {
            Some(Shape::Box { half_extents }) => {
                Some(Aabb::from_centre(statics.pos[i], half_extents))
            }
            _ => None,
        };
        self.static_faces.clear();
        self.static_faces.resize(statics.len(), Faces::default());
        let (mut neighbours, mut spans) = (Vec::new(), Vec::new());
        for i in 0..statics.len() {
            let Some(a) = aabb(i) else { continue };
            neighbours.clear();
            let items = &self.tree_items;
            self.tree.query(&a.grown(2.0 * LINEAR_SLOP), |item| {
                let j = items[item as usize] as usize;
                let covers = j != i && can_cover(&statics.meta[j], &statics.meta[i]);
                if let (true, Some(b)) = (covers, aabb(j)) {
                    neighbours.push(b);
                }
            });
            let faces = Faces::covered_by_all(&a, &neighbours, LINEAR_SLOP, &mut spans);
            self.static_faces[i] = Faces(faces);
        }
    }

    /// Which faces kinematic boxes and static boxes cover of each other
    /// where they lie flush (a platform level with the ground), at the
    /// positions the step starts from: `O(k log n + k²)` for `k` kinematic
    /// bodies (a level has a few), nothing without them.
    fn find_faces_covered_by_kinematic(&mut self, dynamic: &DynamicBodies, statics: &StaticBodies) {
        self.kinematic_faces.clear();
        self.faces_by_kinematic.clear();
        let box_of = |i: u32| match dynamic.meta[i as usize].shape {
            Some(Shape::Box { half_extents }) => {
                Some(Aabb::from_centre(dynamic.pos.at(i as usize), half_extents))
            }
            _ => None,
        };
        if dynamic.kinematic.is_empty() {
            return;
        }
        // The kinematic boxes in a tree of their own, rebuilt each step
        // (they move): `O(k log k)` for `k` of them.
        let boxes = dynamic.kinematic.iter().map(|&k| {
            box_of(k).unwrap_or(Aabb::from_centre(dynamic.pos.at(k as usize), Vec2::ZERO))
        });
        self.kinematic_tree.rebuild(boxes);
        let (mut neighbours, mut spans) = (
            std::mem::take(&mut self.neighbours),
            std::mem::take(&mut self.spans),
        );
        for &k in &dynamic.kinematic {
            let Some(a) = box_of(k) else { continue };
            neighbours.clear();
            let (items, by_kinematic) = (&self.tree_items, &mut self.faces_by_kinematic);
            let meta_k = &dynamic.meta[k as usize];
            let near = a.grown(2.0 * LINEAR_SLOP);
            self.tree.query(&near, |item| {
                let s = items[item as usize];
                let meta_s = &statics.meta[s as usize];
                if let Some(Shape::Box { half_extents }) = meta_s.shape {
                    let b = Aabb::from_centre(statics.pos[s as usize], half_extents);
                    if can_cover(meta_s, meta_k) {
                        neighbours.push(b);
                    }
                    let covered = Faces::covered_by(&b, &a, LINEAR_SLOP);
                    if covered != 0 && can_cover(meta_k, meta_s) {
                        by_kinematic.push((s, Faces(covered)));
                    }
                }
            });
            let kinematic = &dynamic.kinematic;
            let mut met = 0;
            self.kinematic_tree.query_while(&near, |item| {
                let other = kinematic[item as usize];
                let covers = other != k && can_cover(&dynamic.meta[other as usize], meta_k);
                if let (true, Some(b)) = (covers, box_of(other)) {
                    neighbours.push(b);
                }
                met += 1;
                met <= MAX_KINEMATIC_NEIGHBOURS
            });
            if met > MAX_KINEMATIC_NEIGHBOURS {
                // A pile, not a level: none of its faces is covered.
                continue;
            }
            // Neighbours cover a face together, as for static boxes (a
            // moving tile map's boxes meet as a static map's do).
            let faces = Faces::covered_by_all(&a, &neighbours, LINEAR_SLOP, &mut spans);
            if faces != 0 {
                self.kinematic_faces.push((k, Faces(faces)));
            }
        }
        self.neighbours = neighbours;
        self.spans = spans;
        self.kinematic_faces.sort_unstable_by_key(|f| f.0);
        self.faces_by_kinematic.sort_unstable_by_key(|f| f.0);
    }

    /// The covered faces of an immovable collider this step: a static box
    /// (by its neighbours, static or kinematic) or a kinematic box.
    pub(crate) fn covered_faces(&self, body: ColliderRef) -> Faces {
        let lookup = |list: &[(u32, Faces)], i: usize| {
            let at = list.partition_point(|f| (f.0 as usize) < i);
            let mut faces = 0;
            for f in &list[at..] {
                if f.0 as usize != i {
                    break;
                }
                faces |= f.1.0;
            }
            faces
        };
        match body.dynamic_index() {
            Some(i) => Faces(lookup(&self.kinematic_faces, i)),
            None => {
                let s = body.index();
                Faces(self.static_faces[s].0 | lookup(&self.faces_by_kinematic, s))
            }
        }
    }

    /// Calls `f` with the index of each static body whose box overlaps
    /// `aabb`.
    pub(crate) fn statics_in(&self, aabb: &Aabb, mut f: impl FnMut(u32)) {
        let items = &self.tree_items;
        self.tree.query(aabb, |item| f(items[item as usize]));
    }

    /// Adds a proxy for dynamic body `i` (which has a shape); `track_sleep`
    /// records whether it sleeps.
    #[inline(always)]
    pub(crate) fn add(&mut self, dynamic: &DynamicBodies, i: usize, track_sleep: bool) -> u32 {
        let proxy = self
            .margin
            .proxy(dynamic, i)
            .expect("a proxy's body has a shape");
        let p = self.boxes.len() as u32;
        self.of_body[i] = p;
        self.body.push(i as u32);
        self.slot.push(dynamic.meta[i].id.index);
        self.boxes.push(proxy.swept);
        self.around.push(proxy.around);
        self.margins.push(proxy.margin);
        if track_sleep {
            self.asleep.push(dynamic.sleep[i].is_asleep());
        }
        p
    }

    /// Adds a proxy for every dynamic body, proxy `i` for body `i`, in
    /// chunks on the thread pool when `parallel` and the bodies are many
    /// (the same proxies as [`add`](Self::add) in order). Returns `false`,
    /// having added none, if some body has no shape.
    pub(crate) fn add_all(&mut self, dynamic: &DynamicBodies, parallel: bool) -> bool {
        debug_assert!(self.boxes.is_empty(), "no proxy yet this step");
        let n = dynamic.len();
        self.body.resize(n, 0);
        self.slot.resize(n, 0);
        let empty = Aabb::from_centre(Vec2::ZERO, Vec2::ZERO);
        self.boxes.resize(n, empty);
        self.around.resize(n, empty);
        self.margins.resize(n, 0.0);
        let margin = self.margin;
        let parts = (
            (&mut self.body[..], &mut self.slot[..]),
            (&mut self.boxes[..], &mut self.around[..]),
            &mut self.margins[..],
            &mut self.of_body[..],
        );
        let shapeless = for_chunks(
            parallel,
            parts,
            |offset, ((body, slot), (boxes, around), margins, of_body)| {
                let mut shapeless = 0;
                for k in 0..body.len() {
                    let i = offset + k;
                    let Some(proxy) = margin.proxy(dynamic, i) else {
                        shapeless += 1;
                        continue;
                    };
                    (body[k], slot[k], of_body[k]) = (i as u32, dynamic.meta[i].id.index, i as u32);
                    (boxes[k], around[k], margins[k]) = (proxy.swept, proxy.around, proxy.margin);
                }
                shapeless
            },
        );
        if shapeless > 0 {
            self.body.clear();
            self.slot.clear();
            self.boxes.clear();
            self.around.clear();
            self.margins.clear();
            self.of_body.fill(NO_PROXY);
            return false;
        }
        true
    }

    /// The proxy of dynamic body `i`, made now if it has none.
    pub(crate) fn proxy_or_add(&mut self, dynamic: &DynamicBodies, i: usize) -> u32 {
        match self.of_body[i] {
            NO_PROXY => self.add(dynamic, i, true),
            p => p,
        }
    }

    /// Whether proxy `p`'s body sleeps.
    pub(crate) fn is_asleep(&self, p: usize) -> bool {
        marked_asleep(&self.asleep, p)
    }

    /// Crowded grid cells (see `CROWDED_CELL`) and proxies crowded by
    /// static bodies (see [`MAX_STATIC_NEIGHBOURS`]) in the last pair
    /// search.
    pub(crate) fn crowded(&self) -> usize {
        self.grid.crowded + self.static_crowded
    }

    /// Grows each kinematic body's proxy in the grid by the farthest any
    /// other proxy's contacts reach (its margin beyond half the speculative
    /// distance), and exempts its pairs from a crowded cell's bound: every
    /// body that could reach the kinematic one in any direction is then a
    /// pair with it, however a contact turns it during the step, as with a
    /// static body. A level has few kinematic bodies.
    pub(crate) fn widen_kinematic(&mut self, dynamic: &DynamicBodies) {
        self.grid.uncapped.clear();
        self.grid.immovable.clear();
        if dynamic.kinematic.is_empty() {
            return;
        }
        self.grid.uncapped.resize(self.boxes.len(), false);
        self.grid.immovable.resize(self.boxes.len(), false);
        let reach = self
            .margins
            .iter()
            .zip(&self.body)
            .filter(|&(_, &i)| !dynamic.meta[i as usize].kinematic)
            .map(|(&m, _)| ProxyMargin::reached(m))
            .fold(0.0f32, f32::max);
        for &k in &dynamic.kinematic {
            let p = self.of_body[k as usize];
            if p != NO_PROXY {
                self.boxes[p as usize] = self.boxes[p as usize].grown(reach);
                self.grid.uncapped[p as usize] = true;
                self.grid.immovable[p as usize] = !dynamic.meta[k as usize].sensor;
            }
        }
    }

    /// Finds the pairs among the proxies (except pairs of two sleeping
    /// ones) and the static bodies each awake proxy overlaps.
    ///
    /// The grid's pairs depend on the boxes alone when no proxy sleeps and
    /// none is kinematic, and the pairs with static bodies on the boxes
    /// grown all round and the static bodies: when every box is the last
    /// search's, bit for bit (a pile at rest whose bodies did not move),
    /// its pairs are kept instead of searched for again.
    ///
    /// A settled scene, whose search found the same pairs as the search
    /// before (in any order) and crowded no cell (a pile still jittering by
    /// micrometres), is searched once more with each box grown (see
    /// [`ENLARGED_FRACTION`]). While each box stays inside its grown one,
    /// every pair of boxes that overlap is a pair of grown boxes, and the
    /// grid's pairs are those of the grown boxes' pairs whose boxes
    /// overlap: the pairs a search would find, in another order (the
    /// narrow phase sorts them), for a fraction of a search's time. Should
    /// the boxes crowd a
    /// cell that the grown ones did not, they are all the pairs that
    /// overlap, where a search would have capped them; no more than the
    /// grown boxes' pairs, which their search bounds.
    pub(crate) fn find_pairs(&mut self, parallel: bool) {
        let plain = self.asleep.is_empty()
            && self.grid.uncapped.is_empty()
            && self.grid.immovable.is_empty();
        let may_reuse = plain && !self.switches.search_always;
        let unchanged = may_reuse
            && !self.searched_boxes.is_empty()
            && same_bits(&self.boxes, &self.searched_boxes);
        let statics_unchanged = may_reuse
            && !self.searched_around.is_empty()
            && same_bits(&self.around, &self.searched_around);
        let within = may_reuse
            && !unchanged
            && !self.enlarged.is_empty()
            && all_within(&self.boxes, &self.enlarged);
        let grid_same = if unchanged {
            self.pairs.truncate(self.grid_pairs);
            true
        } else {
            // The last step's pairs, to compare with this one's.
            std::mem::swap(&mut self.pairs, &mut self.earlier_pairs);
            self.earlier_pairs.truncate(self.grid_pairs);
            self.pairs.clear();
            if within {
                let boxes = &self.boxes;
                self.pairs.extend(
                    self.enlarged_pairs
                        .iter()
                        .filter(|&&(a, b)| boxes[a as usize].overlaps(&boxes[b as usize])),
                );
                self.grid.crowded = 0;
            } else {
                self.grid
                    .find_pairs(&self.boxes, &self.asleep, parallel, &mut self.pairs);
                self.enlarged.clear();
            }
            let same = self.pairs == self.earlier_pairs;
            if !within {
                // Settled: the same pairs as the last search's, perhaps in
                // another order (a corner on a cell's edge moves between
                // cells as the boxes jitter), told by their number and a
                // sum that does not depend on the order.
                let sum = order_free_sum(&self.pairs);
                let settled =
                    same || (self.pairs.len() == self.earlier_pairs.len() && sum == self.pairs_sum);
                self.pairs_sum = sum;
                if may_reuse && self.grid.crowded == 0 && settled {
                    self.enlarge(parallel);
                }
            }
            same
        };
        self.grid_pairs_reused += u64::from(unchanged);
        self.grown_pairs_reused += u64::from(within);
        self.static_pairs_reused += u64::from(statics_unchanged);
        self.grid_pairs = self.pairs.len();
        // Kept to compare only when the search was a plain one.
        self.boxes_searched = plain;
        let statics_same = statics_unchanged || {
            std::mem::swap(&mut self.static_pairs, &mut self.earlier_static_pairs);
            self.find_static_pairs(parallel);
            self.static_pairs == self.earlier_static_pairs
        };
        self.pairs_same = plain && grid_same && statics_same && !self.tree_rebuilt;
    }

    /// Pairs each awake proxy with the static bodies its box grown all
    /// round overlaps, in the static tree or in a tree of the static bodies
    /// near the proxies.
    fn find_static_pairs(&mut self, parallel: bool) {
        self.static_pairs.clear();
        self.static_crowded = 0;
        // The static bodies near the awake proxies, when they are few of a
        // large level (a rain in one room of a 1000 × 1000 tile map): each
        // proxy then searches a small tree of them, not the whole level.
        // A level of a few static bodies is searched as it is.
        if self.tree.len() < NARROWED_LEVEL {
            return self.pair_with_statics(false, parallel);
        }
        let mut region: Option<Aabb> = None;
        for (p, aabb) in self.around.iter().enumerate() {
            if !self.is_asleep(p) {
                region = Some(region.map_or(*aabb, |r| r.union(aabb)));
            }
        }
        let Some(region) = region else { return };
        // Only when the proxies fill a small part of the level: otherwise
        // looking for the statics near them would visit most of the tree
        // every step for nothing.
        let area = |b: &Aabb| b.size().x * b.size().y;
        let small = self
            .tree
            .bounds()
            .is_some_and(|level| area(&region) * NARROWED_TREE as f32 <= area(&level));
        self.near_items.clear();
        self.near_boxes.clear();
        if small {
            let (near, boxes, items) =
                (&mut self.near_items, &mut self.near_boxes, &self.tree_items);
            let tree = &self.tree;
            tree.query(&region, |item| {
                near.push(items[item as usize]);
                boxes.push(tree.item_box(item));
            });
        }
        let narrowed = small && self.near_items.len() * NARROWED_TREE < self.tree.len();
        if narrowed {
            self.near_tree.rebuild(self.near_boxes.iter().copied());
        }
        self.pair_with_statics(narrowed, parallel);
    }

    /// Grows each box (see [`ENLARGED_FRACTION`]) into `enlarged` and
    /// finds their pairs, kept if the search crowded no cell (otherwise
    /// `enlarged` is left empty). The grid's counts stay the last search's.
    fn enlarge(&mut self, parallel: bool) {
        let crowded = self.grid.crowded;
        let large_tests = self.grid.large_tests;
        self.enlarged.clear();
        self.enlarged.extend(self.boxes.iter().map(|b| {
            let size = b.max - b.min;
            b.grown(ENLARGED_FRACTION * size.x.min(size.y))
        }));
        self.enlarged_pairs.clear();
        self.grid
            .find_pairs(&self.enlarged, &[], parallel, &mut self.enlarged_pairs);
        if self.grid.crowded > 0 {
            self.enlarged.clear();
        }
        self.grid.crowded = crowded;
        self.grid.large_tests = large_tests;
    }

    /// Pairs each awake proxy with the static bodies its box grown all
    /// round overlaps (`around`), in
    /// the tree of the nearby ones (`narrowed`) or the whole level's; with
    /// `parallel` (and the feature), in runs of proxies on rayon's pool,
    /// giving the same pairs in the same order.
    fn pair_with_statics(&mut self, narrowed: bool, parallel: bool) {
        let (tree, items) = if narrowed {
            (&self.near_tree, &self.near_items)
        } else {
            (&self.tree, &self.tree_items)
        };
        let (boxes, asleep) = (&self.around, &self.asleep);
        let crowded = std::sync::atomic::AtomicUsize::new(0);
        let search = |range: std::ops::Range<usize>, pairs: &mut Vec<(u32, u32)>| {
            for p in range {
                if marked_asleep(asleep, p) {
                    continue;
                }
                let mut met = 0;
                tree.query_while(&boxes[p], |item| {
                    if met == MAX_STATIC_NEIGHBOURS {
                        crowded.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        return false;
                    }
                    met += 1;
                    pairs.push((p as u32, items[item as usize]));
                    true
                });
            }
        };
        #[cfg(feature = "parallel")]
        if crate::parallel::goes_parallel(parallel, boxes.len()) {
            let chunk = crate::constants::PARALLEL_CHUNK;
            let (tasks, pairs) = (&mut self.task_pairs, &mut self.static_pairs);
            crate::collision::broad_phase::in_tasks(tasks, boxes.len(), chunk, search, pairs);
            self.static_crowded = crowded.into_inner();
            return;
        }
        let _ = parallel;
        search(0..boxes.len(), &mut self.static_pairs);
        self.static_crowded = crowded.into_inner();
    }
}

/// A sum over `pairs` that does not depend on their order: a pair's two
/// proxies mixed into 64 bits, added up. Two lists of the same pairs in
/// other orders give the same sum; other pairs almost never do (and when
/// they do, a settled scene is only searched once more, for nothing).
fn order_free_sum(pairs: &[(u32, u32)]) -> u64 {
    pairs.iter().fold(0u64, |sum, &(a, b)| {
        let x = (u64::from(a) << 32 | u64::from(b)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        sum.wrapping_add(x ^ (x >> 29))
    })
}

/// Whether each of `boxes` lies inside the one of `enlarged` at its index
/// (a box with a NaN does not), one for each.
fn all_within(boxes: &[Aabb], enlarged: &[Aabb]) -> bool {
    boxes.len() == enlarged.len()
        && boxes.iter().zip(enlarged).all(|(b, e)| {
            (b.min.x >= e.min.x)
                & (b.min.y >= e.min.y)
                & (b.max.x <= e.max.x)
                & (b.max.y <= e.max.y)
        })
}

/// Whether two lists of boxes are the same, bit for bit (`0.0` and
/// `-0.0` differ, a NaN is itself).
fn same_bits(a: &[Aabb], b: &[Aabb]) -> bool {
    let bits = |x: &Aabb| [x.min.x, x.min.y, x.max.x, x.max.y].map(f32::to_bits);
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| bits(x) == bits(y))
}

/// Whether proxy `p` is marked asleep in `asleep` (empty when no proxy
/// sleeps).
#[inline(always)]
fn marked_asleep(asleep: &[bool], p: usize) -> bool {
    asleep.get(p) == Some(&true)
}

/// Whether `coverer` can make the faces of `covered` seamless: a solid
/// body (not a sensor, not a one-way platform) with the same filter, as
/// the tiles of one level are. A sensor zone or a decoration on another
/// layer lying flush on the ground must not turn the ground's face away.
fn can_cover(coverer: &BodyMeta, covered: &BodyMeta) -> bool {
    !coverer.sensor && coverer.one_way.is_none() && coverer.filter == covered.filter
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::World;

    fn proxies_of(world: &mut World) -> &mut Proxies {
        world.contacts.as_mut().expect("contacts").proxies_mut()
    }

    #[test]
    fn grid_pairs_kept_at_rest_are_those_a_search_finds() {
        // The pile comes to rest, and its boxes stop changing.
        let (mut world, boxes) = crate::testing::pile();
        world.step(1.0 / 60.0);
        let mut searched = world.clone();
        searched.set_test_switches(crate::TestSwitches {
            search_always: true,
            ..Default::default()
        });
        let kept = |w: &mut World| {
            let c = w.counters();
            (c.grid_pairs_reused, c.static_pairs_reused)
        };
        // Knocked at tick 200: the boxes move, and are searched again.
        let mut before_knock = (0, 0);
        crate::testing::step_side_by_side(
            (&mut world, &mut searched),
            &boxes,
            (240, 200),
            |w| w.set_velocity(boxes[0], Vec2::new(2.0, 0.0)),
            |tick, world, searched| {
                // (The grown boxes' pairs come in their own order.)
                let pairs = |w: &mut World| {
                    let p = proxies_of(w);
                    let mut grid = p.pairs.clone();
                    grid.sort_unstable();
                    (grid, p.static_pairs.clone())
                };
                assert_eq!(pairs(world), pairs(searched), "tick {tick}: the same pairs");
                match tick {
                    199 => before_knock = kept(world),
                    200 => assert_eq!(kept(world), before_knock, "searched when knocked"),
                    _ => {}
                }
            },
        );
        assert_eq!(kept(&mut searched), (0, 0));
        let (grid, statics) = before_knock;
        assert!(grid >= 10, "grid pairs kept {grid} times before the knock");
        assert!(
            statics >= 10,
            "static pairs kept {statics} times before the knock"
        );
    }

    #[test]
    fn the_order_free_sum_tells_the_same_pairs_in_another_order() {
        let pairs: Vec<(u32, u32)> = (0..100).map(|i| (i, i + 1 + i % 3)).collect();
        let mut shuffled = pairs.clone();
        shuffled.reverse();
        shuffled.swap(3, 70);
        assert_eq!(order_free_sum(&pairs), order_free_sum(&shuffled));
        let mut other = pairs.clone();
        other[40] = (40, 45);
        assert_ne!(order_free_sum(&pairs), order_free_sum(&other));
        // (1, 2) and (2, 1) are not the same pair to it: a pair is always
        // written lower proxy first.
        assert_ne!(order_free_sum(&[(1, 2)]), order_free_sum(&[(2, 1)]));
    }

    #[test]
    fn pairs_kept_through_grown_boxes_are_those_a_search_finds() {
        // A pyramid of base 12, sleeping off and shock propagation off: it
        // settles, its boxes jittering inside their grown boxes (whose pairs are kept), and
        // then stops; a box knocked out of its grown box is searched
        // again, and the pile settles again.
        let (mut world, boxes) = crate::testing::pyramid(12);
        // Without shock propagation, so that the pile jitters a while.
        let mut settings = *world.settings();
        settings.contacts.as_mut().unwrap().shock_propagation = false;
        world.set_settings(settings).unwrap();
        world.step(1.0 / 60.0);
        let mut searched = world.clone();
        searched.set_test_switches(crate::TestSwitches {
            search_always: true,
            ..Default::default()
        });
        let mut before_knock = 0;
        crate::testing::step_side_by_side(
            (&mut world, &mut searched),
            &boxes,
            (200, 60),
            |w| w.set_velocity(boxes[0], Vec2::new(0.0, 30.0)),
            |tick, world, searched| {
                let grid_pairs = |w: &mut World| {
                    let mut pairs = proxies_of(w).pairs.clone();
                    pairs.sort_unstable();
                    pairs
                };
                assert_eq!(grid_pairs(world), grid_pairs(searched), "tick {tick}");
                let kept = world.counters().grown_pairs_reused;
                match tick {
                    59 => before_knock = kept,
                    60 => assert_eq!(kept, before_knock, "searched when knocked"),
                    _ => {}
                }
            },
        );
        assert_eq!(searched.counters().grown_pairs_reused, 0);
        assert!(
            before_knock >= 10,
            "grown boxes' pairs kept {before_knock} times before the knock"
        );
        let after = world.counters().grown_pairs_reused - before_knock;
        assert!(after >= 5, "kept {after} times after the knock");
    }

    #[test]
    fn a_proxy_grows_along_its_travel_and_by_the_fall_all_round() {
        let margin = ProxyMargin {
            fall: 9.81 / 60.0,
            dt: 1.0 / 60.0,
            continuous: true,
        };
        let unit = Aabb::from_centre(Vec2::ZERO, Vec2::splat(0.5));
        let round = 0.5 * SPECULATIVE_DISTANCE + margin.fall * margin.dt;
        // 6 m/s to the right and 3 m/s down: 0.1 m right, 0.05 m down.
        let swept_at = |m: &ProxyMargin, velocity: Vec2, reach: f32| {
            m.swept(unit, velocity, m.travel(velocity), reach)
        };
        let swept = swept_at(&margin, Vec2::new(6.0, -3.0), 10.0);
        let close = |a: Vec2, b: Vec2| (a - b).abs().max_element() < 1e-6;
        assert!(close(swept.min, Vec2::new(-0.5 - round, -0.55 - round)));
        assert!(close(swept.max, Vec2::new(0.6 + round, 0.5 + round)));
        // Beyond the reach: the reach in every direction.
        let capped = swept_at(&margin, Vec2::new(600.0, 0.0), 2.0);
        let reach = 0.5 * SPECULATIVE_DISTANCE + 2.0;
        assert!(close(capped.max, Vec2::splat(0.5 + reach)));
        assert!(close(capped.min, Vec2::splat(-0.5 - reach)));
        // Without continuous collision: the speculative distance alone.
        let off = ProxyMargin {
            continuous: false,
            ..margin
        };
        let still = swept_at(&off, Vec2::new(600.0, 0.0), 2.0);
        assert_eq!(still, unit.grown(0.5 * SPECULATIVE_DISTANCE));
    }
}
