//! Rigid rods: their rows, solved one by one or side by side. Side by
//! side, they are coloured as the contacts are (see `solver::colouring`)
//! and laid out [`LANES`] to a block, each block's lanes solved with the
//! one-by-one arithmetic of [`RodRow`].
//!
//! Each rod takes the colour right after the last colour its bodies
//! already have, so every body's rods are solved in slot order, as one by
//! one: while no chain of rods is longer than [`COLOURS`] the blocks give
//! the same bits. A longer chain (a net of thousands) wraps round to the
//! first free colour; a rod whose bodies have every colour between them is
//! solved one by one after the blocks. So is every rod when the blocks
//! would be mostly padding (a rope: one rod a colour), where one by one is
//! faster.
//!
//! Two lanes of a block never move the same body. A lane may read a body
//! no rod moves (kinematic, asleep: inverse mass zero), whose velocity
//! no lane writes.

use crate::joint::soft::Soft;
use crate::solver::colouring::{COLOURS, MAX_PADDING, colour_after};
use crate::solver::lanes::LANES;
use crate::solver::scalar::BodyState;
use glam::Vec2;

/// Marks a rod's end that no state moves (a static body, the world).
pub(crate) const NONE: u32 = u32::MAX;

/// A rigid rod (a distance joint of one length and no spring), the most
/// common joint (chains, bridges, nets), in a row of its own: 40 bytes
/// against a general row's 120, so a pass over thousands streams a third
/// of the memory.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RodRow {
    /// Body A's and B's dynamic index, or [`NONE`].
    pub(crate) a: u32,
    pub(crate) b: u32,
    pub(crate) ma: f32,
    pub(crate) mb: f32,
    pub(crate) mass: f32,
    pub(crate) base: Vec2,
    pub(crate) length: f32,
    pub(crate) impulse: f32,
    pub(crate) slot: u32,
}

impl RodRow {
    /// Applies the rod's impulse of the last substep again.
    pub(crate) fn warm_start(&self, state: &mut [BodyState], delta: &[Vec2]) {
        let (va, vb) = self.velocities(state);
        let p = self.impulse * self.separation(delta).normalize_or_zero();
        self.write(state, va - self.ma * p, vb + self.mb * p);
    }

    /// One pass over the rod, with drift correction `rigid`.
    pub(crate) fn solve(&mut self, state: &mut [BodyState], delta: &[Vec2], rigid: Soft) {
        let (va, vb) = self.velocities(state);
        let d = self.separation(delta);
        let len = d.length();
        let axis = if len > 0.0 { d / len } else { Vec2::ZERO };
        let cdot = axis.dot(vb - va);
        let impulse = rigid.impulse(self.mass, cdot, len - self.length, self.impulse);
        self.impulse += impulse;
        let p = impulse * axis;
        self.write(state, va - self.ma * p, vb + self.mb * p);
    }

    #[inline(always)]
    fn velocities(&self, state: &[BodyState]) -> (Vec2, Vec2) {
        let v = |i: u32| {
            if i == NONE {
                Vec2::ZERO
            } else {
                state[i as usize].vel
            }
        };
        (v(self.a), v(self.b))
    }

    /// Anchor B minus anchor A now.
    #[inline(always)]
    fn separation(&self, delta: &[Vec2]) -> Vec2 {
        let d = |i: u32| {
            if i == NONE {
                Vec2::ZERO
            } else {
                delta[i as usize]
            }
        };
        self.base + (d(self.b) - d(self.a))
    }

    /// Writes the velocities of the bodies the rod moves.
    #[inline(always)]
    fn write(&self, state: &mut [BodyState], va: Vec2, vb: Vec2) {
        if self.a != NONE && self.ma > 0.0 {
            state[self.a as usize].vel = va;
        }
        if self.b != NONE && self.mb > 0.0 {
            state[self.b as usize].vel = vb;
        }
    }
}

/// [`LANES`] rods of one colour, as a structure of arrays. A padding lane
/// names no rod and no body, and its masses are zero.
#[derive(Clone, Copy, Debug)]
struct RodBlock {
    /// The rod's index in the step's rods ([`NONE`]: padding).
    rod: [u32; LANES],
    a: [u32; LANES],
    b: [u32; LANES],
    ma: [f32; LANES],
    mb: [f32; LANES],
    mass: [f32; LANES],
    base_x: [f32; LANES],
    base_y: [f32; LANES],
    length: [f32; LANES],
    impulse: [f32; LANES],
}

impl RodBlock {
    const PADDING: Self = Self {
        rod: [NONE; LANES],
        a: [NONE; LANES],
        b: [NONE; LANES],
        ma: [0.0; LANES],
        mb: [0.0; LANES],
        mass: [0.0; LANES],
        base_x: [0.0; LANES],
        base_y: [0.0; LANES],
        length: [0.0; LANES],
        impulse: [0.0; LANES],
    };

    fn set(&mut self, l: usize, index: usize, rod: &RodRow) {
        self.rod[l] = index as u32;
        self.a[l] = rod.a;
        self.b[l] = rod.b;
        self.ma[l] = rod.ma;
        self.mb[l] = rod.mb;
        self.mass[l] = rod.mass;
        self.base_x[l] = rod.base.x;
        self.base_y[l] = rod.base.y;
        self.length[l] = rod.length;
        self.impulse[l] = rod.impulse;
    }
}

/// A block's bodies: velocities of A and B and anchor B minus anchor A now,
/// lane by lane.
struct Gathered {
    vax: [f32; LANES],
    vay: [f32; LANES],
    vbx: [f32; LANES],
    vby: [f32; LANES],
    dx: [f32; LANES],
    dy: [f32; LANES],
}

#[inline(always)]
fn gather(k: &RodBlock, state: &[BodyState], delta: &[Vec2]) -> Gathered {
    let mut g = Gathered {
        vax: [0.0; LANES],
        vay: [0.0; LANES],
        vbx: [0.0; LANES],
        vby: [0.0; LANES],
        dx: [0.0; LANES],
        dy: [0.0; LANES],
    };
    let at = |i: u32| {
        if i == NONE {
            (Vec2::ZERO, Vec2::ZERO)
        } else {
            (state[i as usize].vel, delta[i as usize])
        }
    };
    for l in 0..LANES {
        let (va, da) = at(k.a[l]);
        let (vb, db) = at(k.b[l]);
        (g.vax[l], g.vay[l], g.vbx[l], g.vby[l]) = (va.x, va.y, vb.x, vb.y);
        // As [`RodRow::separation`]: base + (delta B - delta A).
        g.dx[l] = k.base_x[l] + (db.x - da.x);
        g.dy[l] = k.base_y[l] + (db.y - da.y);
    }
    g
}

/// Writes the velocities of the bodies the lanes move.
#[inline(always)]
fn scatter(k: &RodBlock, state: &mut [BodyState], g: &Gathered) {
    for l in 0..LANES {
        if k.a[l] != NONE && k.ma[l] > 0.0 {
            state[k.a[l] as usize].vel = Vec2::new(g.vax[l], g.vay[l]);
        }
        if k.b[l] != NONE && k.mb[l] > 0.0 {
            state[k.b[l] as usize].vel = Vec2::new(g.vbx[l], g.vby[l]);
        }
    }
}

/// Applies impulse `p` along each lane (on B; minus on A).
#[inline(always)]
fn push(k: &RodBlock, g: &mut Gathered, px: &[f32; LANES], py: &[f32; LANES]) {
    for l in 0..LANES {
        g.vax[l] -= k.ma[l] * px[l];
        g.vay[l] -= k.ma[l] * py[l];
        g.vbx[l] += k.mb[l] * px[l];
        g.vby[l] += k.mb[l] * py[l];
    }
}

/// [`RodRow::warm_start`], lane by lane.
fn warm_start_block(k: &RodBlock, state: &mut [BodyState], delta: &[Vec2]) {
    let mut g = gather(k, state, delta);
    let (mut px, mut py) = ([0.0; LANES], [0.0; LANES]);
    for l in 0..LANES {
        // As `Vec2::normalize_or_zero`.
        let len = (g.dx[l] * g.dx[l] + g.dy[l] * g.dy[l]).sqrt();
        let rcp = 1.0 / len;
        let (ax, ay) = if rcp.is_finite() && rcp > 0.0 {
            (g.dx[l] * rcp, g.dy[l] * rcp)
        } else {
            (0.0, 0.0)
        };
        (px[l], py[l]) = (k.impulse[l] * ax, k.impulse[l] * ay);
    }
    push(k, &mut g, &px, &py);
    scatter(k, state, &g);
}

/// [`RodRow::solve`], lane by lane.
fn solve_block(k: &mut RodBlock, state: &mut [BodyState], delta: &[Vec2], rigid: Soft) {
    let mut g = gather(k, state, delta);
    let (mut px, mut py) = ([0.0; LANES], [0.0; LANES]);
    for l in 0..LANES {
        let len = (g.dx[l] * g.dx[l] + g.dy[l] * g.dy[l]).sqrt();
        let (ax, ay) = if len > 0.0 {
            (g.dx[l] / len, g.dy[l] / len)
        } else {
            (0.0, 0.0)
        };
        let cdot = ax * (g.vbx[l] - g.vax[l]) + ay * (g.vby[l] - g.vay[l]);
        let c = len - k.length[l];
        let impulse = rigid.impulse(k.mass[l], cdot, c, k.impulse[l]);
        k.impulse[l] += impulse;
        (px[l], py[l]) = (impulse * ax, impulse * ay);
    }
    push(k, &mut g, &px, &py);
    scatter(k, state, &g);
}

/// The step's rods in colours of blocks, and those solved one by one.
#[derive(Clone, Debug, Default)]
pub(crate) struct RodBlocks {
    /// Every colour's blocks, colour after colour.
    blocks: Vec<RodBlock>,
    /// The rods solved one by one after the blocks, by index, in order.
    one_by_one: Vec<u32>,
    /// Per dynamic body: the colours of the rods that move it (all zero
    /// between builds).
    masks: Vec<u128>,
    /// Per rod: its colour, or `None` (one by one).
    colour_of: Vec<Option<u8>>,
}

/// The dynamic bodies rod `r` moves.
fn moved(r: &RodRow) -> [Option<usize>; 2] {
    let one = |i: u32, m: f32| (i != NONE && m > 0.0).then_some(i as usize);
    [one(r.a, r.ma), one(r.b, r.mb)]
}

impl RodBlocks {
    /// Colours `rods` and lays them out in blocks. `blocks_always`: blocks
    /// however empty; `one_by_one`: no blocks at all (test switches).
    pub(crate) fn build(&mut self, rods: &[RodRow], blocks_always: bool, one_by_one: bool) {
        self.blocks.clear();
        self.one_by_one.clear();
        self.colour_of.clear();
        if one_by_one || rods.is_empty() {
            self.one_by_one.extend(0..rods.len() as u32);
            return;
        }
        let bodies = rods
            .iter()
            .flat_map(moved)
            .flatten()
            .max()
            .map_or(0, |i| i + 1);
        if self.masks.len() < bodies {
            self.masks.resize(bodies, 0);
        }
        let mut counts = [0usize; COLOURS];
        for r in rods {
            let [a, b] = moved(r);
            let used = a.map_or(0, |a| self.masks[a]) | b.map_or(0, |b| self.masks[b]);
            let colour = colour_after(used);
            if let Some(colour) = colour {
                for body in [a, b].into_iter().flatten() {
                    self.masks[body] |= 1 << colour;
                }
                counts[colour] += 1;
            }
            self.colour_of.push(colour.map(|c| c as u8));
        }
        for r in rods {
            for body in moved(r).into_iter().flatten() {
                self.masks[body] = 0;
            }
        }
        // Judged at eight lanes whatever `LANES` is, as the contacts are,
        // so that the choice (and the bits) is the same on every target.
        let coloured: usize = counts.iter().sum();
        let lanes: usize = counts.iter().map(|&n| n.div_ceil(8) * 8).sum();
        if lanes > MAX_PADDING * coloured && !blocks_always {
            self.one_by_one.extend(0..rods.len() as u32);
            return;
        }
        let mut next = [0usize; COLOURS];
        let mut start = 0;
        for (colour, &count) in counts.iter().enumerate() {
            next[colour] = start * LANES;
            start += count.div_ceil(LANES);
        }
        self.blocks.resize(start, RodBlock::PADDING);
        for (i, (r, colour)) in rods.iter().zip(&self.colour_of).enumerate() {
            match colour {
                Some(colour) => {
                    let slot = &mut next[*colour as usize];
                    self.blocks[*slot / LANES].set(*slot % LANES, i, r);
                    *slot += 1;
                }
                None => self.one_by_one.push(i as u32),
            }
        }
    }

    /// Applies each rod's impulse of the last substep again.
    pub(crate) fn warm_start(&self, rods: &[RodRow], state: &mut [BodyState], delta: &[Vec2]) {
        for k in &self.blocks {
            warm_start_block(k, state, delta);
        }
        for &i in &self.one_by_one {
            rods[i as usize].warm_start(state, delta);
        }
    }

    /// One pass over the rods, with drift correction `rigid`.
    pub(crate) fn solve(
        &mut self,
        rods: &mut [RodRow],
        state: &mut [BodyState],
        delta: &[Vec2],
        rigid: Soft,
    ) {
        for k in &mut self.blocks {
            solve_block(k, state, delta, rigid);
        }
        for &i in &self.one_by_one {
            rods[i as usize].solve(state, delta, rigid);
        }
    }

    /// Writes the blocks' impulses back to their rods.
    pub(crate) fn store(&self, rods: &mut [RodRow]) {
        for k in &self.blocks {
            for (&rod, &impulse) in k.rod.iter().zip(&k.impulse) {
                if rod != NONE {
                    rods[rod as usize].impulse = impulse;
                }
            }
        }
    }

    /// Rods solved in blocks.
    pub(crate) fn in_blocks(&self) -> usize {
        let lanes = self.blocks.iter().flat_map(|k| k.rod);
        lanes.filter(|&r| r != NONE).count()
    }
}

#[cfg(test)]
mod tests {
    use crate::testing::step_side_by_side;
    use crate::{BodyDef, BodyId, JointDef, TestSwitches, World};
    use glam::Vec2;

    /// A net of `n` × `n` bodies without shapes a metre apart, of masses
    /// from 0.5 to 4.5 kg, each tied by
    /// a rigid rod to its neighbours above and to the left, its top row
    /// hung from the world by rods; each row thrown sideways at `swing`
    /// m/s times its depth.
    fn net(n: usize, swing: f32) -> (World, Vec<BodyId>) {
        let mut world = World::default();
        let mut ids: Vec<BodyId> = Vec::new();
        for row in 0..n {
            for col in 0..n {
                let position = Vec2::new(col as f32, -(row as f32));
                let def = BodyDef {
                    position,
                    velocity: Vec2::new(swing * row as f32, 0.0),
                    mass: 0.5 + ((row + 2 * col) % 5) as f32,
                    ..Default::default()
                };
                let id = world.add_body(def).unwrap();
                let up = if row == 0 {
                    JointDef::distance(id, None, 1.0).anchors(Vec2::ZERO, position + Vec2::Y)
                } else {
                    JointDef::distance(ids[ids.len() - n], Some(id), 1.0)
                };
                world.add_joint(up).unwrap();
                if col > 0 {
                    world
                        .add_joint(JointDef::distance(ids[ids.len() - 1], Some(id), 1.0))
                        .unwrap();
                }
                ids.push(id);
            }
        }
        (world, ids)
    }

    fn one_by_one(world: &World) -> World {
        let mut world = world.clone();
        world.set_test_switches(TestSwitches {
            joints_one_by_one: true,
            ..Default::default()
        });
        world
    }

    #[test]
    fn rods_in_blocks_give_the_one_by_one_bits_while_no_chain_wraps() {
        // Nets whose longest chain of rods (about 2n) fits in the colours,
        // and the same net beside it solved one by one: the same bits
        // every tick. With four lanes or eight, as blocks or one by one.
        for n in [8, 20] {
            let (mut world, ids) = net(n, 0.3);
            let mut single = one_by_one(&world);
            step_side_by_side(
                (&mut world, &mut single),
                &ids,
                (60, 30),
                |_| {},
                |_, _, _| {},
            );
            assert_eq!(single.counters().rods_in_blocks, 0);
            let rods = 2 * n * n - n;
            assert_eq!(world.counters().rods_in_blocks, rods as u64, "{n} × {n}");
        }
    }

    #[test]
    fn a_rope_is_solved_one_by_one_unless_asked_and_the_bits_agree() {
        // A rope of rods: one rod a colour, blocks all padding.
        let (mut world, ids) = net(1, 0.0);
        let mut last = ids[0];
        let mut ids = ids;
        for k in 1..30 {
            let def = BodyDef {
                position: Vec2::new(k as f32, 0.0),
                ..Default::default()
            };
            let id = world.add_body(def).unwrap();
            world
                .add_joint(JointDef::distance(last, Some(id), 1.0))
                .unwrap();
            (last, ids) = (id, [ids, vec![id]].concat());
        }
        let mut blocks = world.clone();
        blocks.set_test_switches(TestSwitches {
            blocks_always: true,
            ..Default::default()
        });
        step_side_by_side(
            (&mut world, &mut blocks),
            &ids,
            (90, 0),
            |_| {},
            |_, _, _| {},
        );
        assert_eq!(world.counters().rods_in_blocks, 0, "one by one");
        assert_eq!(blocks.counters().rods_in_blocks, 30, "in blocks");
    }

    #[test]
    fn a_net_whose_chains_wrap_round_the_colours_holds_its_rods() {
        // A net of 70 × 70: chains of about 140 rods wrap round the 128
        // colours, and the order is no longer the one-by-one order. The
        // rods hold as well as one by one: a net 70 rods deep, heavy and
        // light bodies mixed, stretches (4.4 % at its worst after half a
        // second, as so deep a chain of Gauss-Seidel does), no more than
        // 2 % beyond the one-by-one net.
        let (mut world, ids) = net(70, 0.02);
        let mut single = one_by_one(&world);
        for _ in 0..30 {
            world.step(1.0 / 60.0);
            single.step(1.0 / 60.0);
        }
        let pos = |w: &World, i: usize| w.body(ids[i]).unwrap().position;
        let stretch = |w: &World| {
            let mut worst = 0.0f32;
            for i in 0..ids.len() {
                let (row, col) = (i / 70, i % 70);
                if row > 0 {
                    worst = worst.max((pos(w, i).distance(pos(w, i - 70)) - 1.0).abs());
                }
                if col > 0 {
                    worst = worst.max((pos(w, i).distance(pos(w, i - 1)) - 1.0).abs());
                }
            }
            worst
        };
        assert_eq!(world.counters().rods_in_blocks as usize, 2 * 70 * 70 - 70);
        assert_ne!(pos(&world, ids.len() - 1), pos(&single, ids.len() - 1));
        let (wide, single) = (stretch(&world), stretch(&single));
        assert!(
            wide < 0.06 && wide <= single * 1.02,
            "{wide} against {single}"
        );
    }
}
