//! Graph colouring of the contacts, and the passes over them colour by
//! colour.
//!
//! Two contacts that move no body in common can be solved at the same
//! time. Each step the contacts are coloured so that no two contacts of a
//! colour move the same body. Bodies the contacts only read (static,
//! kinematic and sleeping bodies: inverse mass zero) do not count, so a
//! whole floor of boxes resting on the ground can share one colour.
//!
//! The colours are dealt in the contact list's order, and each contact
//! takes the colour right after the last colour its bodies already have:
//! every body's contacts are then solved in the list's order, as the
//! sequential Gauss-Seidel solver would solve them, and while no chain of
//! contacts is longer than [`COLOURS`] the passes give exactly its bits. A
//! longer chain wraps round to the first free colour. (Taking the first
//! free colour instead, as greedy colouring does, interleaves a stack's
//! contacts so that support climbs it two contacts per pass: a rain of
//! 10 000 circles sank three times deeper and was still moving after ten
//! seconds.) The colours depend on the contacts alone.
//!
//! Each colour's contacts are laid out in blocks of [`LANES`] and solved
//! lane by lane (see `lanes`). A contact whose two bodies already have
//! every one of the [`COLOURS`] between them is left over, and solved one by
//! one after the colours by the scalar solver (`scalar`), which has the
//! same arithmetic and, like the blocks, never writes a body the contact
//! does not move. So is a whole group whose blocks would be mostly padding
//! (a stack: one contact a colour), where one by one is faster.

use crate::contact::constraint::Constraint;
use crate::solver::lanes::{Block, Bodies, LANES, NONE, Rates, measure, solve_block, warm_start};
use crate::solver::scalar::{self, SolverBodies, SolverParams};
use crate::switches::TestSwitches;
use std::ops::Range;

/// Colours at most: one bit each in a body's `u128` mask.
pub(crate) const COLOURS: usize = 128;

/// The step's contacts in colours of blocks, and those left over.
#[derive(Clone, Debug, Default)]
pub(crate) struct Colouring {
    /// Every colour's blocks, colour after colour.
    blocks: Vec<Block>,
    /// Each colour's blocks in `blocks`.
    colours: Vec<Range<usize>>,
    /// Contacts no colour could take, solved one by one after the colours.
    overflow: Vec<Constraint>,
    /// The row of each overflow contact.
    overflow_rows: Vec<u32>,
    /// Per dynamic body: the colours of the contacts that move it.
    masks: Vec<u128>,
    /// Per picked row: its colour ([`OVERFLOW`]: none).
    colour_of: Vec<u8>,
    /// Per picked row of the last build: the bodies it moves (see
    /// [`moved_key`]). The colours depend on these alone, so a build whose
    /// rows move the same bodies in the same order (a pile at rest keeps
    /// its contacts step after step) takes the last build's colours.
    last_moved: Vec<u64>,
    /// Contacts per colour in the last build.
    counts: Vec<usize>,
    /// Rows the last colouring left over (colour [`OVERFLOW`]).
    left_over: usize,
    /// Builds that took the last build's colours (see `StepCounters`).
    pub(crate) reused: u64,
    /// Whether the last build kept the colours of the build before it, so
    /// that every row kept its [`Slot`].
    pub(crate) kept: bool,
    /// The shortcuts turned off (`blocks_always`).
    pub(crate) switches: TestSwitches,
}

/// Lanes per contact above which the contacts are solved one by one
/// instead: 2, blocks (counted eight lanes wide whatever [`LANES`] is)
/// less than half full: a stack of boxes (one contact a colour) steps
/// faster one by one than in blocks of padding.
pub(crate) const MAX_PADDING: usize = 2;

/// Clears the masks of the bodies contact `c` moves (each build leaves
/// every mask zero).
fn unmask(masks: &mut [u128], c: &Constraint) {
    let (a, b) = c.moved();
    for body in [a, b].into_iter().flatten() {
        masks[body] = 0;
    }
}

/// The bodies row `c` moves ([`Constraint::moved`]), in one word: A's
/// index and B's, each `u32::MAX` when the row does not move it (a static,
/// kinematic or sleeping body).
fn moved_key(c: &Constraint) -> u64 {
    let (a, b) = c.moved();
    let index = |i: Option<usize>| i.map_or(u64::from(u32::MAX), |i| i as u64);
    // (The halves share no bit: `^` would give the same key as `|`.)
    index(a) << 32 | index(b)
}

/// The colour of a constraint whose bodies' earlier constraints have the
/// colours `used` (a mask): the one after the last of them, as the
/// sequential order would solve it; wrapping round to the first free
/// colour past the last; none when every colour is taken.
pub(crate) fn colour_after(used: u128) -> Option<usize> {
    if used == u128::MAX {
        return None;
    }
    let after = (u128::BITS - used.leading_zeros()) as usize;
    Some(if after < COLOURS {
        after
    } else {
        (!used).trailing_zeros() as usize
    })
}

/// The colour of a row left over, solved one by one.
const OVERFLOW: u8 = u8::MAX;
const _: () = assert!(COLOURS <= OVERFLOW as usize);

impl Colouring {
    /// Colours the rows `picked` (indices into `rows`, in order) over
    /// `bodies` dynamic bodies, and lays them out in blocks. `deep` marks
    /// the bodies whose contacts carry their push (empty: none does).
    /// `O(picked)` once the body masks have grown to `bodies`.
    pub(crate) fn build(
        &mut self,
        rows: &[Constraint],
        picked: impl Iterator<Item = usize> + Clone,
        bodies: usize,
        deep: &[bool],
    ) {
        // The masks are all zero between builds: grown here, and the
        // entries a build sets are cleared at its end. (`<=` would resize
        // to the same length: no change.)
        if self.masks.len() < bodies {
            self.masks.resize(bodies, 0);
        }
        self.overflow.clear();
        self.overflow_rows.clear();
        // The masks are set only when the colours are worked out anew.
        let coloured_now = !self.same_bodies(rows, picked.clone());
        self.kept = !coloured_now;
        if coloured_now {
            self.colour(rows, picked.clone());
        } else {
            self.reused += 1;
            // (A pile coloured whole has none to look for: a shortcut, the
            // loop would find none.)
            if self.left_over > 0 {
                for (i, &colour) in picked.clone().zip(&self.colour_of) {
                    if colour == OVERFLOW {
                        self.overflow.push(rows[i]);
                        self.overflow_rows.push(i as u32);
                    }
                }
            }
        }
        // (Empty until a build has worked colours out: no rows yet.)
        let mut counts = [0usize; COLOURS];
        counts[..self.counts.len()].copy_from_slice(&self.counts);

        // Each colour's blocks, then the rows dealt into their lanes in order.
        self.colours.clear();
        let mut next = [0usize; COLOURS];
        let mut start = 0;
        for (colour, &count) in counts.iter().enumerate() {
            if count == 0 {
                continue;
            }
            next[colour] = start * LANES;
            let end = start + count.div_ceil(LANES);
            self.colours.push(start..end);
            start = end;
        }
        // Colours taken from the last build give its layout: its blocks
        // are kept, not filled with padding again and then written. Their
        // padding lanes name no body and have zero masses, so the passes
        // left their numbers zero (up to sign), and every lane a row
        // takes is written whole below. (A shortcut: taken colours give
        // as many blocks, and blocks laid out anew get the same lanes.)
        let same_layout = !coloured_now && self.blocks.len() == start;
        if !same_layout {
            self.blocks.clear();
        }
        // Judged at a fixed width, so that the choice (and the bits, once a
        // chain wraps round) is the same with four lanes or eight.
        let coloured = self.colour_of.len() - self.overflow.len();
        let lanes: usize = counts.iter().map(|&n| n.div_ceil(8) * 8).sum();
        let coloured = if self.switches.blocks_always {
            lanes
        } else {
            coloured
        };
        if lanes > MAX_PADDING * coloured {
            // Mostly padding (a stack: one contact a colour): one by one
            // in the list's order is faster, and gives the same bits while
            // no chain wraps round the colours.
            self.blocks.clear();
            self.colours.clear();
            self.overflow.clear();
            self.overflow_rows.clear();
            for i in picked {
                if coloured_now {
                    unmask(&mut self.masks, &rows[i]);
                }
                self.overflow.push(rows[i]);
                self.overflow_rows.push(i as u32);
            }
            return;
        }
        if !same_layout {
            self.blocks.resize(start, Block::PADDING);
        }
        for (i, &colour) in picked.zip(&self.colour_of) {
            let c = &rows[i];
            if coloured_now {
                unmask(&mut self.masks, c);
            }
            if colour == OVERFLOW {
                continue;
            }
            let slot = &mut next[colour as usize];
            let carry = deep.get(c.a as usize).copied().unwrap_or(false);
            self.blocks[*slot / LANES].set(*slot % LANES, i, c, carry);
            *slot += 1;
        }
    }

    /// Whether the rows `picked` move the same bodies, in the same order,
    /// as the last build's (which then gave their colours).
    fn same_bodies(&self, rows: &[Constraint], picked: impl Iterator<Item = usize>) -> bool {
        let mut last = self.last_moved.iter();
        picked
            .map(|i| moved_key(&rows[i]))
            .all(|key| last.next() == Some(&key))
            && last.next().is_none()
    }

    /// Works out the colours of the rows `picked` (and their counts), and
    /// notes the bodies each moves; the contacts left over go to the
    /// overflow. Leaves the masks of the bodies set, for the layout to
    /// clear.
    fn colour(&mut self, rows: &[Constraint], picked: impl Iterator<Item = usize>) {
        self.colour_of.clear();
        self.last_moved.clear();
        self.counts.clear();
        self.counts.resize(COLOURS, 0);
        self.left_over = 0;
        for i in picked {
            let c = &rows[i];
            self.last_moved.push(moved_key(c));
            let (a, b) = c.moved();
            let used = a.map_or(0, |a| self.masks[a]) | b.map_or(0, |b| self.masks[b]);
            let Some(colour) = colour_after(used) else {
                self.left_over += 1;
                self.colour_of.push(OVERFLOW);
                self.overflow.push(*c);
                self.overflow_rows.push(i as u32);
                continue;
            };
            for body in [a, b].into_iter().flatten() {
                self.masks[body] |= 1 << colour;
            }
            self.colour_of.push(colour as u8);
            self.counts[colour] += 1;
        }
    }

    /// Notes in `slot_of` (indexed by row) where each of this colouring's
    /// rows keeps its impulses while the passes run; `group` names this
    /// colouring among the regions' (see [`Slot`]).
    pub(crate) fn note_slots(&self, group: u8, slot_of: &mut [Slot]) {
        for (b, block) in self.blocks.iter().enumerate() {
            for (l, &row) in block.row.iter().enumerate() {
                if row != NONE {
                    slot_of[row as usize] = Slot::Lane {
                        group,
                        block: b as u32,
                        lane: l as u8,
                    };
                }
            }
        }
        for (k, &row) in self.overflow_rows.iter().enumerate() {
            slot_of[row as usize] = Slot::Overflow {
                group,
                index: k as u32,
            };
        }
    }

    /// The normal, push and greatest normal impulses of the row at `slot`
    /// (one of this colouring's).
    pub(crate) fn impulses_mut(&mut self, slot: Slot) -> [&mut f32; 3] {
        match slot {
            Slot::Lane { block, lane, .. } => {
                let (k, l) = (&mut self.blocks[block as usize], lane as usize);
                [
                    &mut k.normal_impulse[l],
                    &mut k.push_impulse[l],
                    &mut k.max_normal_impulse[l],
                ]
            }
            Slot::Overflow { index, .. } => {
                let c = &mut self.overflow[index as usize];
                [
                    &mut c.normal_impulse,
                    &mut c.push_impulse,
                    &mut c.max_normal_impulse,
                ]
            }
            Slot::None => unreachable!("a row no colouring holds"),
        }
    }

    /// Holds no contact.
    pub(crate) fn clear(&mut self) {
        // An empty colouring's rows (none) keep their slots; whether the
        // rows it held moved elsewhere, the colouring that took them tells.
        self.kept = true;
        self.blocks.clear();
        self.colours.clear();
        self.overflow.clear();
        self.overflow_rows.clear();
    }

    /// Writes the impulses back to the rows they were built from.
    pub(crate) fn store(&self, rows: &mut [Constraint]) {
        self.store_from(rows, 0);
    }

    /// [`store`](Self::store) into `rows`, the rows from index `first` on,
    /// which hold every row this colouring was built from.
    pub(crate) fn store_from(&self, rows: &mut [Constraint], first: usize) {
        for block in &self.blocks {
            for (l, &row) in block.row.iter().enumerate() {
                if row != NONE {
                    block.store(l, &mut rows[row as usize - first]);
                }
            }
        }
        for (c, &row) in self.overflow.iter().zip(&self.overflow_rows) {
            rows[row as usize - first] = *c;
        }
    }

    /// Sets each contact's normal impulse to its row's index, in its lane
    /// or in the overflow (to check that `store` puts every one back).
    #[cfg(test)]
    pub(crate) fn mark_rows(&mut self) {
        for k in &mut self.blocks {
            for l in 0..LANES {
                k.normal_impulse[l] = k.row[l] as f32;
            }
        }
        for (c, &row) in self.overflow.iter_mut().zip(&self.overflow_rows) {
            c.normal_impulse = row as f32;
        }
    }

    /// Contacts left over, solved one by one (for tests).
    #[cfg(test)]
    pub(crate) fn left_over(&self) -> usize {
        self.overflow.len()
    }

    /// Colours in use.
    #[cfg(test)]
    pub(crate) fn colour_count(&self) -> usize {
        self.colours.len()
    }

    /// Runs `pass` over every block, colour after colour.
    pub(crate) fn blocks(&mut self, view: &mut Bodies<'_>, pass: &Pass) {
        for range in &self.colours {
            for k in &mut self.blocks[range.clone()] {
                pass.run(k, view);
            }
        }
    }

    /// Runs `pass` over the contacts left over, one by one.
    pub(crate) fn overflow(&mut self, bodies: &mut SolverBodies<'_>, pass: &Pass) {
        if self.overflow.is_empty() {
            return;
        }
        match *pass {
            Pass::Begin(ref params, _) => scalar::begin_substep(&mut self.overflow, bodies, params),
            // The scalar solver measures as it goes.
            #[cfg(test)]
            Pass::Measure => {}
            Pass::Solve(ref params, _, push) => {
                scalar::solve(&mut self.overflow, bodies, params, push)
            }
            Pass::Fresh(ref params, _) => {
                for c in &mut self.overflow {
                    c.push_impulse = 0.0;
                }
                scalar::solve(&mut self.overflow, bodies, params, true)
            }
            Pass::Relax(ref params, _) => scalar::solve(&mut self.overflow, bodies, params, false),
        }
    }

    /// Runs `pass` over the blocks, then over the contacts left over.
    pub(crate) fn run(&mut self, bodies: &mut SolverBodies<'_>, pass: &Pass) {
        self.blocks(&mut Bodies::new(bodies), pass);
        self.overflow(bodies, pass);
    }

    /// The dynamic bodies the blocks write (`written`) or read (for
    /// checks: a debug assertion that no step can fail, so no test sees
    /// it emptied).
    #[cfg(debug_assertions)]
    pub(crate) fn bodies_in_blocks(&self, written: bool) -> impl Iterator<Item = u32> + '_ {
        self.blocks
            .iter()
            .flat_map(move |k| match written {
                true => k.write_a.iter().chain(&k.write_b),
                false => k.a.iter().chain(&k.b),
            })
            .copied()
            .filter(|&i| i != NONE)
    }
}

/// Where a row keeps its impulses while a substep's passes run: a lane of
/// a block, or the contacts left over, of one of the regions' colourings
/// (`group`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) enum Slot {
    /// No colouring holds the row.
    #[default]
    None,
    Lane {
        group: u8,
        block: u32,
        lane: u8,
    },
    Overflow {
        group: u8,
        index: u32,
    },
}

impl Slot {
    /// The colouring that holds the row.
    pub(crate) fn group(self) -> usize {
        match self {
            Slot::Lane { group, .. } | Slot::Overflow { group, .. } => group as usize,
            Slot::None => unreachable!("a row no colouring holds"),
        }
    }
}

/// What a pass over the contacts does.
pub(crate) enum Pass {
    /// Start a substep: warm start (unless the parameters turn it off, as
    /// after a replayed warm start), carry the push in deep piles or clear
    /// it (see [`scalar::begin_substep`]), and with `true` measure the
    /// separations.
    /// The step measures only when the bodies moved since the last
    /// measure: a substep after a relax stage (which measured at the same
    /// positions) does not, nor does the first (blocks are built with the
    /// step's separations).
    Begin(SolverParams, bool),
    /// Measure the separations after the bodies moved (for tests; the
    /// step measures in [`Pass::Begin`] and [`Pass::Relax`]).
    #[cfg(test)]
    Measure,
    /// One Gauss-Seidel pass, with the push or without (see
    /// [`scalar::solve`]).
    Solve(SolverParams, Rates, bool),
    /// The first pass with the push of a substep whose warm start was
    /// replayed (see `motion::Start::Replay`) and whose push no deep pile
    /// carries: each contact's push starts from zero, as the warm start
    /// pass, which this one makes needless, would have left it.
    Fresh(SolverParams, Rates),
    /// The first pass after the bodies moved: measure each block's
    /// separations, then a pass without the push, block by block (one walk
    /// over the blocks instead of two; the same bits, since solving does
    /// not move the bodies). The states' push slots must hold the bodies'
    /// displacements, as the position stage leaves them (see
    /// `BodyState`): the blocks measure from those.
    Relax(SolverParams, Rates),
}

impl Pass {
    pub(crate) fn solve(params: &SolverParams, push: bool) -> Self {
        Self::Solve(*params, Rates::new(params), push)
    }

    pub(crate) fn fresh(params: &SolverParams) -> Self {
        Self::Fresh(*params, Rates::new(params))
    }

    pub(crate) fn relax(params: &SolverParams) -> Self {
        Self::Relax(*params, Rates::new(params))
    }

    #[inline(always)]
    fn run(&self, k: &mut Block, view: &mut Bodies<'_>) {
        match *self {
            Pass::Begin(ref params, measures) => {
                warm_start(k, view, params.warm_starting, params.carry_push);
                if measures {
                    measure(k, view);
                }
            }
            #[cfg(test)]
            Pass::Measure => measure(k, view),
            Pass::Solve(_, ref rates, true) => solve_block::<true, false, false>(k, view, rates),
            Pass::Solve(_, ref rates, false) => solve_block::<false, false, false>(k, view, rates),
            Pass::Fresh(_, ref rates) => solve_block::<true, true, false>(k, view, rates),
            Pass::Relax(_, ref rates) => solve_block::<false, false, true>(k, view, rates),
        }
    }
}

#[cfg(test)]
mod tests;
