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

use crate::contact::constraint::Constraint;
use crate::parallel::{for_chunks, goes_parallel, halfway, join};
use crate::solver::colouring::{Colouring, Pass, Slot};
use crate::solver::lanes::Bodies;
use crate::solver::motion::{Home, Homes};
use crate::solver::scalar::{BodyState, SolverBodies};
use crate::switches::TestSwitches;
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
    /// The step does not split whatever its size (it has joints, whose
    /// passes read every body's state in the solver's array).
    pub(crate) no_split: bool,
}

impl ContactRegions {
    /// Turns the colourings' shortcuts off, or on again. (They change the
    /// work, never the bits: left undone, no result shows it.)
    pub(crate) fn set_switches(&mut self, switches: TestSwitches) {
        for group in &mut self.groups {
            group.switches = switches;
        }
    }

    /// Builds that took the last build's colours, over the groups.
    pub(crate) fn colourings_reused(&self) -> u64 {
        self.groups.iter().map(|g| g.reused).sum()
    }

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
        self.split = bodies >= SPLIT_BODIES && !self.no_split;
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
            // (Any cut gives the same picks: only the halves' sizes.)
            let (head, tail) = rows.split_at(rows.len() / 2);
            let (picked, picked_tail) = (&mut self.picked, &mut self.picked_tail);
            let held = join(
                true,
                || assign_regions(head, 0, region, use_of, picked),
                || assign_regions(tail, head.len(), region, use_of, picked_tail),
            );
            for (g, t) in picked.iter_mut().zip(&*picked_tail) {
                g.extend_from_slice(t);
            }
            held.0 || held.1
        } else {
            assign_regions(rows, 0, region, use_of, &mut self.picked)
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
        // (No cut is the last row of group 0 or 2: `r` would do as well
        // as `r + 1`.)
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
        solve_region_blocks(first, second, bodies, &mut far, pass, parallel);
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

    /// Whether every row kept its [`Slot`] since the build before the last
    /// (each colouring kept its colours).
    pub(crate) fn slots_kept(&self) -> bool {
        self.groups.iter().all(|g| g.kept)
    }

    /// Notes in `slot_of` (one per row) where each row keeps its impulses
    /// while the passes run.
    pub(crate) fn note_slots(&self, slot_of: &mut [Slot]) {
        for (g, group) in self.groups.iter().enumerate() {
            group.note_slots(g as u8, slot_of);
        }
    }

    /// While the step splits: where each body's state lives during the
    /// passes.
    pub(crate) fn homes(&self) -> Option<&Homes> {
        self.split.then_some(&self.homes)
    }

    /// The colourings, whose rows' impulses a [`Slot`] names, and while
    /// the step splits each body's home and the far array.
    pub(crate) fn parts_mut(
        &mut self,
    ) -> (&mut [Colouring; 3], Option<(&Homes, &mut [BodyState])>) {
        let far = self.split.then_some((&self.homes, &mut self.far[..]));
        (&mut self.groups, far)
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
fn assign_regions(
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
        // (Set wrongly, it only makes the build start again with `holds`,
        // which picks the same.)
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
fn solve_region_blocks(
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
mod tests;
