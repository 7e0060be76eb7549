//! The contacts of a large step in two regions solved side by side, then
//! the contacts between them.
//!
//! A world of at least [`SPLIT_BODIES`] dynamic bodies (kinematic and
//! sleeping ones count) splits them in two: in storage order, at the
//! halfway index, when few contacts cross it (bodies stored roughly in the
//! order of their places), else at the middle of their extent along its
//! wider axis (positions at the start of the step; see
//! [`ContactRegions::split_bodies`]). Each contact goes to the region
//! of the bodies it moves, or between the regions when it moves a body of
//! each; each group is coloured on its own (see `colouring`). A pass solves
//! the two regions' blocks, on two threads with the `parallel` feature,
//! then one by one the contacts of each region no block took, then the
//! contacts between the regions.
//!
//! The regions move disjoint sets of bodies and read only their own bodies
//! and bodies no contact moves (static, kinematic, sleeping: a contact that
//! reads a body another contact moves is put between the regions), so the
//! order in which they run does not matter: the bits are the same on one
//! thread or several. Whether a step splits depends on the world alone,
//! never on threads or features, so the bits are also the same with
//! `World::set_parallel` on or off, and in builds with the feature or
//! without.
//!
//! While the passes run, the second region's bodies keep their states in
//! an array of their own (see [`Homes`]), and each region's passes work on
//! one array, with no shared access and no `unsafe`. In one array the two
//! regions' bodies lie in runs between each other's wherever the storage
//! order does not follow the split (a rain added row by row and split at
//! the middle of its width: runs of a hundred), and the two threads slowed
//! each other by a third through it, although no cache line held bodies of
//! both (most likely the prefetchers, fetching ahead into the other
//! region's runs; see BENCHMARKS.md). The stages around the passes read
//! and write each run of bodies in the array where it lives.

use crate::colouring::{Colouring, Pass};
use crate::constraint::Constraint;
use crate::lanes::Bodies;
use crate::motion::{Home, Homes};
use crate::parallel::{for_chunks, goes_parallel, halfway, join};
use crate::solver::{BodyState, SolverBodies};
use glam::Vec2;

/// Dynamic bodies from which a step splits into regions: 4 096 (as the
/// other stages go parallel, see `PARALLEL_MIN_ITEMS`), where a region's
/// pass is long enough (tens of microseconds) that handing it to another
/// thread pays. A count of bodies, not of contacts, so that a world splits
/// or not for good: bodies far away, or contacts coming and going, do not
/// change how a smaller world's contacts are solved.
pub(crate) const SPLIT_BODIES: usize = crate::constants::PARALLEL_MIN_ITEMS;

/// A step splits in storage order when at most one contact in 32 moves a
/// body of each half (see [`ContactRegions::split_bodies`]): those
/// contacts are solved on one thread after the regions', 3 % of the
/// passes at most. (A rain of 10 000 circles added row by row: about 1 %
/// across the halves; a pyramid of base 100: about 2 %.)
const MAX_CROSSING: usize = 32;

/// The step's contacts by region, in colours.
#[derive(Clone, Debug, Default)]
pub(crate) struct ContactRegions {
    /// Region 0, region 1, and the contacts between them; all in the first
    /// when the step does not split.
    groups: [Colouring; 3],
    split: bool,
    /// Per dynamic body: its region.
    region: Vec<u8>,
    /// Each group's contacts, by index in the rows.
    picked: [Vec<u32>; 3],
    /// The same for the second half of the rows, when the halves are
    /// picked side by side.
    picked_tail: [Vec<u32>; 3],
    /// Per dynamic body: 1 if a contact moves it, 2 if one only reads it
    /// (empty when no row holds a body).
    use_of: Vec<u8>,
    /// While the step splits: where each body's state lives during the
    /// passes.
    homes: Homes,
    /// The states of the bodies whose home is [`Home::Far`] or
    /// [`Home::Both`], by dynamic index like the solver's (written by the
    /// solver's load, see `Motion::load`), then the rest state.
    far: Vec<BodyState>,
    /// The bodies at home in `far` that contacts between the regions
    /// move: copied to the solver's array for those contacts and back.
    far_between: Vec<u32>,
}

impl ContactRegions {
    /// Splits (or not) and colours `rows`, over the dynamic bodies at
    /// positions `pos`; `deep` as for [`Colouring::build`]. `holds`: some
    /// row holds a dynamic body (asleep or kinematic: inverse mass zero in
    /// the row), which the step knows from its bodies; should a row hold
    /// one all the same, sorting the rows notices and the build starts
    /// again as if `holds` were set. With `parallel`
    /// (and the feature) the rows are sorted into regions in two halves
    /// side by side, and the two regions are coloured side by side.
    pub(crate) fn build(
        &mut self,
        rows: &[Constraint],
        pos: &[Vec2],
        deep: &[bool],
        holds: bool,
        parallel: bool,
    ) {
        let bodies = pos.len();
        self.split = bodies >= SPLIT_BODIES;
        if !self.split {
            self.groups[0].build(rows, 0..rows.len(), bodies, deep);
            self.groups[1].clear();
            self.groups[2].clear();
            return;
        }
        self.split_bodies(pos, rows, parallel);
        // Per body: whether some contact moves it (1) and whether some
        // contact only reads it (2). Held bodies are held in all their
        // contacts (a step holds a body or not), but a body both moved and
        // read would be read by one region while the other moves it: its
        // contacts go between the regions, solved on one thread. When no
        // row holds a body, every body a row names it moves: no pass.
        self.use_of.clear();
        if holds {
            self.use_of.resize(bodies, 0);
            for c in rows {
                let (a, b) = c.moved();
                self.use_of[c.a as usize] |= if a.is_some() { 1 } else { 2 };
                if let Some(bi) = c.b.dynamic_index() {
                    self.use_of[bi] |= if b.is_some() { 1 } else { 2 };
                }
            }
        }
        let (region, use_of) = (&self.region[..], &self.use_of[..]);
        let held = if goes_parallel(parallel, rows.len()) {
            let (head, tail) = rows.split_at(rows.len() / 2);
            let (picked, picked_tail) = (&mut self.picked, &mut self.picked_tail);
            let held = join(
                true,
                || pick(head, 0, region, use_of, picked),
                || pick(tail, head.len(), region, use_of, picked_tail),
            );
            for (g, t) in picked.iter_mut().zip(&*picked_tail) {
                g.extend_from_slice(t);
            }
            held.0 || held.1
        } else {
            pick(rows, 0, region, use_of, &mut self.picked)
        };
        if held && !holds {
            // A row holds a body the step did not say was held: without
            // `use_of` such a body could be read by one region from the
            // array of states it does not live in.
            self.build(rows, pos, deep, true, parallel);
            return;
        }
        self.find_homes(rows);
        let [first, second, between] = &mut self.groups;
        let colour = |colouring: &mut Colouring, picked: &[u32]| {
            colouring.build(rows, picked.iter().map(|&i| i as usize), bodies, deep);
        };
        let [in_first, in_second, in_between] = &self.picked;
        join(
            parallel,
            || colour(first, in_first),
            || colour(second, in_second),
        );
        colour(between, in_between);
        // What lets the regions run side by side, each on its own array of
        // states (see `Homes`): a region's blocks move only its bodies, and
        // read only those and bodies no contact moves (held, in both
        // arrays).
        #[cfg(debug_assertions)]
        for r in 0..2 {
            let own = |i: u32| self.region[i as usize] == r as u8;
            assert!(self.groups[r].bodies_in_blocks(true).all(own));
            let only_read = |i: u32| self.use_of[i as usize] == 2;
            assert!(
                self.groups[r]
                    .bodies_in_blocks(false)
                    .all(|i| own(i) || only_read(i))
            );
        }
    }

    /// Each body's region. In storage order, the first half and the second
    /// (see [`halfway`]), when at most one contact in [`MAX_CROSSING`]
    /// moves a body of each: bodies stored roughly in the order of their
    /// places (a level built row by row, waves spawned one after another)
    /// cut in two along a line. Each region's bodies are then one run, and
    /// they are the bodies the same worker moves in the stages around the
    /// passes (see `parallel::for_chunks`), so neither worker reads states
    /// the other just wrote. Otherwise (bodies stored in no order of their
    /// places) by place: 0 below the middle of the bodies' extent along
    /// its wider axis, 1 from it on. One pass; a median would balance
    /// uneven piles better, at the price of a selection every step.
    fn split_bodies(&mut self, pos: &[Vec2], rows: &[Constraint], parallel: bool) {
        let half = halfway(pos.len());
        let crosses = |c: &Constraint| match c.moved() {
            (Some(a), Some(b)) => (a < half) != (b < half),
            _ => false,
        };
        let crossing = for_chunks(parallel, rows, |_, rows| {
            rows.iter().filter(|c| crosses(c)).count() as u64
        });
        self.region.clear();
        if crossing as usize * MAX_CROSSING <= rows.len() {
            self.region
                .extend((0..pos.len()).map(|i| u8::from(i >= half)));
            return;
        }
        let (lo, hi) = pos.iter().fold((Vec2::MAX, Vec2::MIN), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        });
        let axis = usize::from(hi.y - lo.y > hi.x - lo.x);
        let middle = 0.5 * lo[axis] + 0.5 * hi[axis];
        self.region
            .extend(pos.iter().map(|p| u8::from(p[axis] >= middle)));
    }

    /// Each body's home (see [`Home`]) and the far bodies that contacts
    /// between the regions move; sizes the far array.
    fn find_homes(&mut self, rows: &[Constraint]) {
        let (region, use_of) = (&self.region, &self.use_of);
        let home = |i: usize| match (use_of.get(i) == Some(&2), region[i]) {
            (true, _) => Home::Both,
            (false, 0) => Home::Near,
            (false, _) => Home::Far,
        };
        let bodies = region.len();
        self.homes.set((0..bodies).map(home));
        // Only the far bodies' entries (written at each load) and the rest
        // state after the bodies are ever read.
        self.far.resize(bodies + 1, BodyState::default());
        self.far[bodies] = BodyState::default();
        self.far_between.clear();
        for &r in &self.picked[2] {
            let (a, b) = rows[r as usize].moved();
            for i in [a, b].into_iter().flatten() {
                if home(i) == Home::Far {
                    self.far_between.push(i as u32);
                }
            }
        }
        self.far_between.sort_unstable();
        self.far_between.dedup();
    }

    /// While the step splits: each body's home and the far array (the
    /// states of the bodies at home there), for the stages around the
    /// passes, which read and write each body's state where it lives.
    pub(crate) fn far_states(&mut self) -> Option<(&Homes, &mut [BodyState])> {
        self.split.then(|| (&self.homes, &mut self.far[..]))
    }

    /// Copies the states of the bodies at home in the far array in from
    /// the solver's `states`, as a load does (for tests).
    #[cfg(test)]
    pub(crate) fn load_far(&mut self, states: &[BodyState]) {
        let far = &mut self.far;
        self.homes.each(0, self.region.len(), |run, home| {
            if home != Home::Near {
                far[run.clone()].copy_from_slice(&states[run]);
            }
        });
    }

    /// Writes the impulses back to the rows.
    pub(crate) fn store(&self, rows: &mut [Constraint], parallel: bool) {
        // The rows are in the order of their lower body: after a split in
        // storage order every row of the second region follows the
        // others', and the two parts are written side by side.
        let end = |g: usize| self.picked[g].last().map_or(0, |&r| r as usize + 1);
        let cut = self.picked[1].first().map(|&r| r as usize);
        if let Some(cut) = cut.filter(|&cut| self.split && cut >= end(0).max(end(2))) {
            let [first, second, between] = &self.groups;
            let (head, tail) = rows.split_at_mut(cut);
            join(
                parallel,
                || {
                    first.store(head);
                    between.store(head);
                },
                || second.store_from(tail, cut),
            );
            return;
        }
        for g in &self.groups {
            g.store(rows);
        }
    }

    /// Runs `pass` over every contact: the regions' blocks (side by side
    /// when `parallel`), the regions' contacts left over, the contacts
    /// between the regions.
    pub(crate) fn run(&mut self, bodies: &mut SolverBodies<'_>, pass: &Pass, parallel: bool) {
        if !self.split {
            self.groups[0].run(bodies, pass);
            return;
        }
        let [first, second, between] = &mut self.groups;
        let mut far = SolverBodies {
            state: &mut self.far,
            delta: bodies.delta,
            deep: bodies.deep,
        };
        both(first, second, bodies, &mut far, pass, parallel);
        first.overflow(bodies, pass);
        second.overflow(&mut far, pass);
        // The contacts between the regions, on the solver's array: the far
        // bodies they move are copied there for them, and back.
        for &i in &self.far_between {
            bodies.state[i as usize] = self.far[i as usize];
        }
        between.run(bodies, pass);
        for &i in &self.far_between {
            self.far[i as usize] = bodies.state[i as usize];
        }
    }

    /// Copies the far bodies' states into the solver's array (for tests:
    /// the step reads each body where it lives).
    #[cfg(test)]
    pub(crate) fn gather(&self, states: &mut [BodyState]) {
        self.homes.each(0, self.region.len(), |run, home| {
            if home == Home::Far {
                states[run.clone()].copy_from_slice(&self.far[run]);
            }
        });
    }

    /// Whether this step split (for tests).
    #[cfg(test)]
    pub(crate) fn is_split(&self) -> bool {
        self.split
    }
}

/// Sorts `rows` (the first at index `first` of all the rows) into
/// `picked`, cleared first: each contact goes to the region of the bodies
/// it moves, or between the regions when it moves a body of each or names
/// a body (`use_of` 3) that one contact moves and another only reads
/// (`use_of` is empty when no row holds a body). Returns whether some row
/// holds a dynamic body (reads it without moving it).
fn pick(
    rows: &[Constraint],
    first: usize,
    region: &[u8],
    use_of: &[u8],
    picked: &mut [Vec<u32>; 3],
) -> bool {
    for g in picked.iter_mut() {
        g.clear();
    }
    let shared = |i: usize| use_of.get(i) == Some(&3);
    let mut held = false;
    for (i, c) in rows.iter().enumerate() {
        let moved = c.moved();
        held |= moved != (Some(c.a as usize), c.b.dynamic_index());
        let g = match moved {
            _ if shared(c.a as usize) || c.b.dynamic_index().is_some_and(shared) => 2,
            (Some(a), Some(b)) if region[a] != region[b] => 2,
            (Some(x), _) | (None, Some(x)) => region[x],
            (None, None) => 0,
        };
        picked[g as usize].push((first + i) as u32);
    }
    held
}

/// The blocks of the two regions, each on its own array of states: on two
/// threads when `parallel` (and the feature is on), else one after the
/// other; the same bits either way.
fn both(
    first: &mut Colouring,
    second: &mut Colouring,
    near: &mut SolverBodies<'_>,
    far: &mut SolverBodies<'_>,
    pass: &Pass,
    parallel: bool,
) {
    join(
        parallel,
        || first.blocks(&mut Bodies::new(near), pass),
        || second.blocks(&mut Bodies::new(far), pass),
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collider::ColliderRef;
    use crate::solver::SolverParams;
    use crate::testing::uniform;

    /// A `side` × `side` lattice of boxes, each touching its right and upper
    /// neighbours, the bottom row on the ground, with some velocity and
    /// overlap: a pile, in positions, velocities and contacts.
    fn lattice(side: u32) -> (Vec<Vec2>, Vec<Vec2>, Vec<Constraint>) {
        let index = |x: u32, y: u32| y * side + x;
        let (mut pos, mut vel, mut rows) = (Vec::new(), Vec::new(), Vec::new());
        for y in 0..side {
            for x in 0..side {
                pos.push(Vec2::new(x as f32, y as f32));
                vel.push(Vec2::new(((x * 7 + y * 3) % 5) as f32 - 2.0, -1.0));
            }
        }
        let contact = |a: u32, b: ColliderRef, normal: Vec2, depth: f32| Constraint {
            a,
            b,
            normal,
            base_separation: -depth,
            inv_mass_a: 1.0,
            inv_mass_b: if b.is_static() { 0.0 } else { 1.0 },
            mass: if b.is_static() { 1.0 } else { 0.5 },
            friction: 0.6,
            normal_impulse: 0.1,
            tangent_impulse: 0.01,
            push_impulse: 0.0,
            max_normal_impulse: 0.0,
        };
        for y in 0..side {
            for x in 0..side {
                let a = index(x, y);
                let depth = ((x + y) % 4) as f32 * 0.004;
                if y == 0 {
                    rows.push(contact(a, ColliderRef::fixed(0), Vec2::Y, depth));
                }
                if x + 1 < side {
                    rows.push(contact(
                        a,
                        ColliderRef::dynamic(index(x + 1, y)),
                        Vec2::X,
                        depth,
                    ));
                }
                if y + 1 < side {
                    rows.push(contact(
                        a,
                        ColliderRef::dynamic(index(x, y + 1)),
                        Vec2::Y,
                        depth,
                    ));
                }
            }
        }
        (pos, vel, rows)
    }

    /// A pile's positions, velocities and contacts, the bodies in a deep
    /// pile, and whether a contact holds a body.
    type Scene = (Vec<Vec2>, Vec<Vec2>, Vec<Constraint>, Vec<bool>, bool);

    /// Where `scrambled` stores body `i` of `bodies` (6 400 = 2^8 5^2,
    /// which 7 919, a prime, does not divide: one place each).
    fn scrambled_index(i: u32, bodies: usize) -> u32 {
        (u64::from(i) * 7919 % bodies as u64) as u32
    }

    /// The same scene with its bodies stored in no order of their places
    /// (see `scrambled_index`): its steps split by place, not in storage
    /// order.
    fn scrambled(scene: Scene) -> Scene {
        let (pos, vel, mut rows, deep, holds) = scene;
        let n = pos.len();
        let to = |i: usize| scrambled_index(i as u32, n) as usize;
        let moved = |from: &[Vec2]| {
            let mut out = vec![Vec2::ZERO; n];
            for (i, &v) in from.iter().enumerate() {
                out[to(i)] = v;
            }
            out
        };
        let (pos, vel) = (moved(&pos), moved(&vel));
        let mut kept_deep = vec![false; deep.len()];
        for (i, &d) in deep.iter().enumerate() {
            kept_deep[to(i)] = d;
        }
        for c in &mut rows {
            c.a = to(c.a as usize) as u32;
            if let Some(b) = c.b.dynamic_index() {
                c.b = ColliderRef::dynamic(to(b) as u32);
            }
        }
        (pos, vel, rows, kept_deep, holds)
    }

    /// How a test runs a substep's passes.
    #[derive(Clone, Copy, PartialEq)]
    enum Run {
        /// As the step does, on two threads if `true`.
        Step(bool),
        /// The regions' groups one after the other on one array of states
        /// (the order of `ContactRegions::run`, with no array of their
        /// own for the second region's bodies).
        OneArray,
    }

    /// Runs a substep's passes over `scene` (warm start, two passes with
    /// the push, one without) and returns the velocities, pushes and rows,
    /// and whether the step split.
    fn substep(scene: &Scene, run: Run) -> (Vec<Vec2>, Vec<Vec2>, Vec<Constraint>, bool) {
        let (pos, vel, rows, deep, holds) = scene;
        let mut rows = rows.clone();
        let parallel = run == Run::Step(true);
        let mut regions = ContactRegions::default();
        regions.build(&rows, pos, deep, *holds, parallel);
        let mut state = BodyState::of(vel);
        regions.load_far(&state);
        let delta = vec![Vec2::ZERO; pos.len()];
        let mut bodies = SolverBodies {
            state: &mut state,
            delta: &delta,
            deep,
        };
        let p = SolverParams {
            carry_push: !deep.is_empty(),
            ..SolverParams::for_tests()
        };
        let passes = [
            Pass::Begin(p, true),
            Pass::solve(&p, true),
            Pass::solve(&p, true),
        ];
        for pass in passes.iter().chain([&Pass::solve(&p, false)]) {
            match run {
                Run::Step(parallel) => regions.run(&mut bodies, pass, parallel),
                Run::OneArray => {
                    let [first, second, between] = &mut regions.groups;
                    first.blocks(&mut Bodies::new(&mut bodies), pass);
                    second.blocks(&mut Bodies::new(&mut bodies), pass);
                    first.overflow(&mut bodies, pass);
                    second.overflow(&mut bodies, pass);
                    between.run(&mut bodies, pass);
                }
            }
        }
        regions.store(&mut rows, run == Run::Step(true));
        if run != Run::OneArray {
            regions.gather(&mut state);
        }
        let (vel, push) = BodyState::split(&state);
        (vel, push, rows, regions.is_split())
    }

    /// The lattice of `side` × `side` with nothing held and no deep pile.
    fn plain(side: u32) -> Scene {
        let (pos, vel, rows) = lattice(side);
        (pos, vel, rows, Vec::new(), false)
    }

    /// The lattice of 80 × 80, stored scrambled (so split at x = 39.5),
    /// with in the second
    /// region a body that every contact naming it holds (read by that
    /// region's blocks from both arrays), a hub touching 140 bodies (more
    /// contacts than colours: the region's contacts left over, solved one
    /// by one on its array), a body held in the first region, a body held
    /// by one contact and moved by others (all of its contacts between the
    /// regions), every body in a deep pile (pushes carried), and the
    /// pushes of the last substep.
    fn held_hub_and_deep() -> Scene {
        let (pos, vel, mut rows) = lattice(80);
        let at = |x: u32, y: u32| y * 80 + x;
        let (held_far, held_near, mixed, hub) = (at(60, 30), at(10, 30), at(20, 50), at(70, 70));
        for c in &mut rows {
            if c.a == held_far || c.a == held_near {
                c.inv_mass_a = 0.0;
            }
            if [held_far, held_near]
                .map(Some)
                .contains(&c.b.dynamic_index().map(|b| b as u32))
            {
                c.inv_mass_b = 0.0;
            }
            if c.a == mixed && c.normal == Vec2::X {
                c.inv_mass_a = 0.0;
            }
            c.push_impulse = 0.02;
        }
        let template = rows[0];
        let spoke = |k: u32| Constraint {
            a: hub,
            b: ColliderRef::dynamic(at(40 + k % 35, k / 35 * 9 + 1)),
            normal: Vec2::new(0.6, 0.8),
            base_separation: -0.01,
            inv_mass_b: 1.0,
            mass: 0.5,
            ..template
        };
        rows.extend((0..140).map(spoke));
        let deep = vec![true; pos.len()];
        scrambled((pos, vel, rows, deep, true))
    }

    /// A pile of 80 × 80 bodies jittered off a lattice, with random
    /// velocities and contacts between random near neighbours (up to three
    /// columns and one row apart), some on one of two static bodies, three
    /// hubs of up to 250 contacts each, random normals, overlaps, masses and
    /// impulses, held bodies and held ends (never a hub's), and for even
    /// seeds a deep pile over about a third of the bodies.
    fn random_pile(seed: u64) -> Scene {
        let side = 80u32;
        let mut next = uniform(seed);
        let mut between = |lo: f32, hi: f32| lo + (hi - lo) * next();
        let mut pos = Vec::new();
        let mut vel = Vec::new();
        for y in 0..side {
            for x in 0..side {
                let jitter = Vec2::new(between(-0.3, 0.3), between(-0.3, 0.3));
                pos.push(Vec2::new(x as f32, y as f32) + jitter);
                vel.push(Vec2::new(between(-3.0, 3.0), between(-3.0, 3.0)));
            }
        }
        let mut ends = std::collections::BTreeSet::new();
        let mut near = |x: u32, y: u32, between: &mut dyn FnMut(f32, f32) -> f32| {
            for (dx, dy) in [(1, 0), (2, 0), (3, 0), (0, 1), (1, 1), (-1, 1)] {
                let (bx, by) = (x as i32 + dx, y as i32 + dy);
                let inside = (0..side as i32).contains(&bx) && (0..side as i32).contains(&by);
                if inside && between(0.0, 1.0) < 0.5 {
                    ends.insert((y * side + x, by as u32 * side + bx as u32));
                }
            }
        };
        for y in 0..side {
            for x in 0..side {
                near(x, y, &mut between);
            }
        }
        let mut hubs = Vec::new();
        for _ in 0..3 {
            let hub = (between(0.0, 1.0) * (side * side) as f32) as u32;
            hubs.push(hub);
            let (hx, hy) = (hub % side, hub / side);
            let spokes = between(100.0, 250.0) as u32;
            for _ in 0..spokes {
                let x = (hx as f32 + between(-12.0, 12.0)).clamp(0.0, side as f32 - 1.0) as u32;
                let y = (hy as f32 + between(-12.0, 12.0)).clamp(0.0, side as f32 - 1.0) as u32;
                let other = y * side + x;
                if other != hub {
                    ends.insert((hub.min(other), hub.max(other)));
                }
            }
        }
        let statics = (0..side * side).filter(|&i| i < side || between(0.0, 1.0) < 0.02);
        let statics: Vec<(u32, ColliderRef)> =
            statics.map(|a| (a, ColliderRef::fixed(a % 2))).collect();
        let dynamic = ends.into_iter().map(|(a, b)| (a, ColliderRef::dynamic(b)));
        // Each body's inverse mass; about one body in thirty held (as a
        // kinematic or sleeping body is: in every contact), never a hub.
        let inv_mass: Vec<f32> = (0..side * side)
            .map(|i| match between(0.0, 1.0) < 0.03 && !hubs.contains(&i) {
                true => 0.0,
                false => between(0.5, 2.0),
            })
            .collect();
        let mut rows = Vec::new();
        for (a, b) in dynamic.chain(statics) {
            let angle = between(0.0, std::f32::consts::TAU);
            // And about one end in a hundred held by this contact alone
            // (a body both moved and read: its contacts go between).
            let mut end = |i: u32| match between(0.0, 1.0) < 0.01 && !hubs.contains(&i) {
                true => 0.0,
                false => inv_mass[i as usize],
            };
            let inv_mass_a = end(a);
            let inv_mass_b = match b.dynamic_index() {
                Some(b) => end(b as u32),
                None => 0.0,
            };
            let k = inv_mass_a + inv_mass_b;
            rows.push(Constraint {
                a,
                b,
                normal: Vec2::new(angle.cos(), angle.sin()),
                base_separation: between(-0.03, 0.01),
                inv_mass_a,
                inv_mass_b,
                mass: if k > 0.0 { 1.0 / k } else { 0.0 },
                friction: between(0.0, 1.0),
                normal_impulse: between(0.0, 0.2),
                tangent_impulse: between(-0.02, 0.02),
                push_impulse: between(0.0, 0.03),
                max_normal_impulse: 0.0,
            });
        }
        let deep = match seed % 2 {
            0 => (0..pos.len()).map(|_| between(0.0, 1.0) < 0.3).collect(),
            _ => Vec::new(),
        };
        let holds = rows.iter().any(|c| {
            let (write_a, write_b) = c.moved();
            write_a.is_none() || (c.b.dynamic_index().is_some() && write_b.is_none())
        });
        (pos, vel, rows, deep, holds)
    }

    #[test]
    fn each_region_on_its_own_array_gives_the_bits_of_one_array() {
        // The last: the held bodies not announced (`holds` false), which
        // the build notices and handles as if they were.
        let mut unannounced = held_hub_and_deep();
        unannounced.4 = false;
        let scenes = [
            plain(80),
            scrambled(plain(80)),
            held_hub_and_deep(),
            unannounced,
        ];
        let reference = [&scenes[0], &scenes[1], &scenes[2], &scenes[2]];
        for (scene, reference) in scenes.iter().zip(reference) {
            let one = substep(reference, Run::OneArray);
            assert!(one.3, "the pile splits");
            let own = substep(scene, Run::Step(false));
            assert_eq!(own.0, one.0, "velocities");
            assert_eq!(own.1, one.1, "pushes");
            assert_eq!(own.2, one.2, "impulses");
        }
        // The second scene has what it says: contacts between the regions,
        // left over in the second region, and held bodies in both arrays.
        let (pos, _, rows, deep, holds) = held_hub_and_deep();
        let mut regions = ContactRegions::default();
        regions.build(&rows, &pos, &deep, holds, false);
        assert!(!regions.picked[2].is_empty());
        assert!(regions.groups[1].left_over() > 0);
        assert!(!regions.far_between.is_empty());
        let homes = (0..pos.len()).map(|i| regions.homes.of(i));
        let both: Vec<usize> = homes
            .enumerate()
            .filter(|&(_, h)| h == Home::Both)
            .map(|(i, _)| i)
            .collect();
        let mut held = [30 * 80 + 10, 30 * 80 + 60].map(|i| scrambled_index(i, 6400) as usize);
        held.sort();
        assert_eq!(both, held);
    }

    #[test]
    fn random_piles_on_their_regions_arrays_give_the_bits_of_one_array() {
        let (mut left_over, mut held_in_both) = (0, 0);
        for seed in 1..=12 {
            // Half of them stored scrambled: split by place.
            let scene = match seed > 6 {
                true => scrambled(random_pile(seed)),
                false => random_pile(seed),
            };
            assert!(scene.4, "seed {seed}: some body is held");
            let (pos, _, rows, deep, holds) = &scene;
            let mut regions = ContactRegions::default();
            regions.build(rows, pos, deep, *holds, false);
            assert!(!regions.far_between.is_empty(), "seed {seed}");
            let half = halfway(pos.len());
            let in_order = (0..pos.len()).all(|i| regions.region[i] == u8::from(i >= half));
            assert_eq!(in_order, seed <= 6, "seed {seed}: split in storage order");
            left_over += regions.groups[0].left_over() + regions.groups[1].left_over();
            let held_here = (0..pos.len()).filter(|&i| regions.homes.of(i) == Home::Both);
            let held_here = held_here.count();
            assert!(held_here > 50, "seed {seed}: {held_here} held bodies");
            held_in_both += held_here;
            let one = substep(&scene, Run::OneArray);
            assert!(one.3, "seed {seed}: the pile splits");
            // The held bodies announced, and not (the build notices them).
            let mut unannounced = scene.clone();
            unannounced.4 = false;
            for scene in [&scene, &unannounced] {
                let own = substep(scene, Run::Step(false));
                assert_eq!(own.0, one.0, "seed {seed}: velocities");
                assert_eq!(own.1, one.1, "seed {seed}: pushes");
                assert_eq!(own.2, one.2, "seed {seed}: impulses");
            }
        }
        // The piles have what the test is about.
        assert!(
            left_over > 0 && held_in_both > 0,
            "{left_over} {held_in_both}"
        );
    }

    #[test]
    fn a_large_pile_splits_in_halves_with_few_contacts_between() {
        // Stored row by row: split in storage order, the rows below y = 40
        // and those above, 80 contacts across.
        let (pos, vel, rows) = lattice(80);
        assert!(pos.len() >= SPLIT_BODIES);
        let mut regions = ContactRegions::default();
        regions.build(&rows, &pos, &[], false, true);
        assert!(regions.is_split());
        assert_eq!(halfway(pos.len()), 3200);
        let in_order = (0..pos.len()).map(|i| u8::from(i >= 3200));
        assert!(regions.region.iter().copied().eq(in_order));
        assert_eq!(regions.picked[2].len(), 80);
        // Stored scrambled: split by place, at x = 39.5, 80 contacts across.
        let (pos, _, rows, _, _) = scrambled((pos, vel, rows, Vec::new(), false));
        regions.build(&rows, &pos, &[], false, true);
        assert!(regions.is_split());
        let by_place = pos.iter().map(|p| u8::from(p.x >= 39.5));
        assert!(regions.region.iter().copied().eq(by_place));
        let count = |g: usize| regions.picked[g].len();
        assert_eq!(count(2), 80);
        assert_eq!(count(0) + count(1) + count(2), rows.len());
        // A small pile does not split.
        let (pos, _, rows) = lattice(20);
        regions.build(&rows, &pos, &[], false, true);
        assert!(!regions.is_split());
    }

    #[test]
    fn every_contact_comes_back_from_its_one_place_whether_split_or_not() {
        // Not split, split in storage order (the second region's rows
        // written side by side with the others'), split by place.
        let scenes = [plain(20), plain(80), scrambled(plain(80))];
        for (k, (pos, _, mut rows, _, _)) in scenes.into_iter().enumerate() {
            for parallel in [false, true] {
                let mut regions = ContactRegions::default();
                regions.build(&rows, &pos, &[], false, parallel);
                for g in &mut regions.groups {
                    g.mark_rows();
                }
                for r in &mut rows {
                    r.normal_impulse = -1.0;
                }
                regions.store(&mut rows, parallel);
                for (i, r) in rows.iter().enumerate() {
                    assert_eq!(r.normal_impulse, i as f32, "row {i} of scene {k}");
                }
            }
        }
    }

    #[test]
    fn a_body_both_moved_and_read_puts_its_contacts_between_the_regions() {
        // Body 0 is read by the first contact (held there) and moved by
        // the second: both go between the regions.
        let (pos, _, mut rows) = lattice(80);
        rows[0].inv_mass_a = 0.0;
        let mut regions = ContactRegions::default();
        regions.build(&rows, &pos, &[], true, true);
        let touching_0: Vec<u32> = (0..rows.len() as u32)
            .filter(|&i| {
                let c = &rows[i as usize];
                c.a == 0 || c.b.dynamic_index() == Some(0)
            })
            .collect();
        assert!(touching_0.len() >= 2);
        for i in touching_0 {
            assert!(regions.picked[2].contains(&i), "row {i}");
        }
    }

    #[cfg(feature = "parallel")]
    #[test]
    fn the_regions_give_the_same_bits_on_any_number_of_threads() {
        for scene in [
            plain(80),
            scrambled(plain(80)),
            held_hub_and_deep(),
            random_pile(1),
            random_pile(2),
            scrambled(random_pile(3)),
        ] {
            let one = substep(&scene, Run::Step(false));
            assert!(one.3, "the pile splits");
            for threads in [1, 2, 4] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                let many = pool.install(|| substep(&scene, Run::Step(true)));
                assert_eq!(many.0, one.0, "velocities, {threads} threads");
                assert_eq!(many.1, one.1, "pushes, {threads} threads");
                assert_eq!(many.2, one.2, "impulses, {threads} threads");
            }
        }
    }
}
