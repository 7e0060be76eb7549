//! The wide contact passes: a colour's contacts laid out [`LANES`] (four or
//! eight) at a time as a structure of arrays (a [`Block`]). A pass gathers
//! the bodies of a block's lanes, solves the lanes side by side with the
//! scalar solver's arithmetic (plain loops over arrays, which the compiler
//! turns into vector instructions), and scatters back the bodies the lanes
//! move. A colour's last block is padded with lanes that name no body and
//! whose masses are zero. Which contacts share a block is `colouring`'s
//! business: the lanes of a block never move the same body.

use crate::contact::constraint::Constraint;
use crate::solver::scalar::{BodyState, SolverBodies, SolverParams, clamp, greater, lesser};
use glam::{Mat4, Vec2, Vec4};

/// Contacts solved side by side in a [`Block`]: the `f32`s of one vector
/// register, eight with AVX, four with SSE (the default x86-64 target,
/// where eight spill registers). The lanes of a block
/// are independent, so the width changes the speed, never the bits.
#[cfg(target_feature = "avx")]
pub(crate) const LANES: usize = 8;
/// Contacts solved side by side in a [`Block`] (see the AVX version).
#[cfg(not(target_feature = "avx"))]
pub(crate) const LANES: usize = 4;
// The passes gather the lanes' bodies four at a time.
const _: () = assert!(LANES.is_multiple_of(4));

/// A lane that names no body (padding), or a static body B.
pub(crate) const NONE: u32 = u32::MAX;

/// [`LANES`] contacts of one colour, as a structure of arrays. What the
/// solver reads and writes of [`Constraint`], lane by lane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Block {
    /// The contact's index in the list of rows ([`NONE`]: padding).
    pub(crate) row: [u32; LANES],
    /// Body A's dynamic index ([`NONE`]: padding).
    pub(crate) a: [u32; LANES],
    /// Body B's dynamic index ([`NONE`]: static, or padding).
    pub(crate) b: [u32; LANES],
    /// Body A's dynamic index if the lane moves it (else [`NONE`]).
    pub(crate) write_a: [u32; LANES],
    /// Body B's dynamic index if the lane moves it (else [`NONE`]).
    pub(crate) write_b: [u32; LANES],
    pub(crate) nx: [f32; LANES],
    pub(crate) ny: [f32; LANES],
    pub(crate) base_separation: [f32; LANES],
    /// Separation now: measured when the bodies last moved.
    pub(crate) separation: [f32; LANES],
    pub(crate) inv_mass_a: [f32; LANES],
    pub(crate) inv_mass_b: [f32; LANES],
    pub(crate) mass: [f32; LANES],
    pub(crate) friction: [f32; LANES],
    pub(crate) normal_impulse: [f32; LANES],
    pub(crate) tangent_impulse: [f32; LANES],
    pub(crate) push_impulse: [f32; LANES],
    pub(crate) max_normal_impulse: [f32; LANES],
    pub(crate) tangent_speed: [f32; LANES],
    /// Whether the lane's push carries on between substeps (a deep pile).
    pub(crate) carry: [bool; LANES],
}

impl Block {
    pub(crate) const PADDING: Self = Self {
        row: [NONE; LANES],
        a: [NONE; LANES],
        b: [NONE; LANES],
        write_a: [NONE; LANES],
        write_b: [NONE; LANES],
        nx: [0.0; LANES],
        ny: [0.0; LANES],
        base_separation: [0.0; LANES],
        separation: [0.0; LANES],
        inv_mass_a: [0.0; LANES],
        inv_mass_b: [0.0; LANES],
        mass: [0.0; LANES],
        friction: [0.0; LANES],
        normal_impulse: [0.0; LANES],
        tangent_impulse: [0.0; LANES],
        push_impulse: [0.0; LANES],
        max_normal_impulse: [0.0; LANES],
        tangent_speed: [0.0; LANES],
        carry: [false; LANES],
    };

    pub(crate) fn set(&mut self, l: usize, row: usize, c: &Constraint, carry: bool) {
        self.row[l] = row as u32;
        self.a[l] = c.a;
        self.b[l] = c.b.dynamic_index().map_or(NONE, |b| b as u32);
        let (write_a, write_b) = c.moved();
        self.write_a[l] = write_a.map_or(NONE, |a| a as u32);
        self.write_b[l] = write_b.map_or(NONE, |b| b as u32);
        self.nx[l] = c.normal.x;
        self.ny[l] = c.normal.y;
        self.base_separation[l] = c.base_separation;
        self.separation[l] = c.base_separation;
        self.inv_mass_a[l] = c.inv_mass_a;
        self.inv_mass_b[l] = c.inv_mass_b;
        self.mass[l] = c.mass;
        self.friction[l] = c.friction;
        self.normal_impulse[l] = c.normal_impulse;
        self.tangent_impulse[l] = c.tangent_impulse;
        self.push_impulse[l] = c.push_impulse;
        self.max_normal_impulse[l] = c.max_normal_impulse;
        self.tangent_speed[l] = c.tangent_speed;
        self.carry[l] = carry;
    }

    /// Writes lane `l`'s impulses back to its row.
    pub(crate) fn store(&self, l: usize, c: &mut Constraint) {
        c.normal_impulse = self.normal_impulse[l];
        c.tangent_impulse = self.tangent_impulse[l];
        c.push_impulse = self.push_impulse[l];
        c.max_normal_impulse = self.max_normal_impulse[l];
    }
}

/// The solver's rates of one substep.
pub(crate) struct Rates {
    inv_h: f32,
    push_rate: f32,
    slop: f32,
    push_out_speed: f32,
}

impl Rates {
    pub(crate) fn new(params: &SolverParams) -> Self {
        let inv_h = 1.0 / params.h;
        Self {
            inv_h,
            push_rate: params.position_correction * inv_h,
            slop: params.slop,
            push_out_speed: params.push_out_speed,
        }
    }
}

/// How blocks reach the bodies, borrowed from the solver's view of them:
/// velocity and push (a [`BodyState`]) and displacement by dynamic index.
/// An index out of range ([`NONE`]) reads as zero (the rest state of
/// [`SolverBodies::state`]) and writes nothing.
pub(crate) struct Bodies<'a> {
    state: &'a mut [BodyState],
    delta: &'a [Vec2],
}

impl<'a> Bodies<'a> {
    pub(crate) fn new(bodies: &'a mut SolverBodies<'_>) -> Self {
        debug_assert!(
            !bodies.state.is_empty(),
            "the rest state follows the bodies"
        );
        Self {
            state: &mut *bodies.state,
            delta: bodies.delta,
        }
    }

    /// Body `i`'s state, if `i` names a body (never the rest state: no
    /// lane names it, so `len` here instead of `len - 1` would change
    /// nothing but the guard).
    #[inline(always)]
    fn body(&mut self, i: u32) -> Option<&mut BodyState> {
        let bodies = self.state.len() - 1;
        self.state[..bodies].get_mut(i as usize)
    }
}

impl Bodies<'_> {
    /// Velocity and push of body `i`.
    #[inline(always)]
    fn state(&self, i: u32) -> BodyState {
        // Past the bodies: the rest state. The index is clamped, not
        // tested (the bounds check that remains is never taken).
        self.state[(i as usize).min(self.state.len() - 1)]
    }

    /// Sets velocity and push of body `i`.
    #[inline(always)]
    fn set_state(&mut self, i: u32, s: BodyState) {
        if let Some(slot) = self.body(i) {
            *slot = s;
        }
    }

    /// Sets the velocity of body `i` (its push unchanged).
    #[inline(always)]
    fn set_vel(&mut self, i: u32, v: Vec2) {
        if let Some(slot) = self.body(i) {
            slot.vel = v;
        }
    }

    /// Displacement of body `i` since the step began (only read).
    #[inline(always)]
    fn delta(&self, i: u32) -> Vec2 {
        self.delta.get(i as usize).copied().unwrap_or(Vec2::ZERO)
    }
}

/// Velocities (or pushes, or displacements) of a block's lanes: A's and
/// B's, by axis.
#[derive(Default)]
struct Lanes {
    ax: [f32; LANES],
    ay: [f32; LANES],
    bx: [f32; LANES],
    by: [f32; LANES],
}

impl Lanes {
    /// Sets lane `l` to `a` and `b`.
    #[inline(always)]
    fn set(&mut self, l: usize, a: Vec2, b: Vec2) {
        (self.ax[l], self.ay[l]) = (a.x, a.y);
        (self.bx[l], self.by[l]) = (b.x, b.y);
    }

    #[inline(always)]
    fn a(&self, l: usize) -> Vec2 {
        Vec2::new(self.ax[l], self.ay[l])
    }

    #[inline(always)]
    fn b(&self, l: usize) -> Vec2 {
        Vec2::new(self.bx[l], self.by[l])
    }

    /// Applies impulse `(ix, iy)` of lane `l`: minus to A, plus to B.
    #[inline(always)]
    fn apply(&mut self, k: &Block, l: usize, ix: f32, iy: f32) {
        self.ax[l] -= ix * k.inv_mass_a[l];
        self.ay[l] -= iy * k.inv_mass_a[l];
        self.bx[l] += ix * k.inv_mass_b[l];
        self.by[l] += iy * k.inv_mass_b[l];
    }
}

/// The velocities and pushes of a block's lanes' bodies: each body read
/// once, four at a time.
#[inline(always)]
fn gather(k: &Block, bodies: &Bodies<'_>) -> (Lanes, Lanes) {
    let (mut v, mut p) = (Lanes::default(), Lanes::default());
    for g in (0..LANES).step_by(4) {
        let lanes = g..g + 4;
        let [vx, vy, px, py] = columns(|l| bodies.state(k.a[g + l]));
        v.ax[lanes.clone()].copy_from_slice(&vx);
        v.ay[lanes.clone()].copy_from_slice(&vy);
        p.ax[lanes.clone()].copy_from_slice(&px);
        p.ay[lanes.clone()].copy_from_slice(&py);
        let [vx, vy, px, py] = columns(|l| bodies.state(k.b[g + l]));
        v.bx[lanes.clone()].copy_from_slice(&vx);
        v.by[lanes.clone()].copy_from_slice(&vy);
        p.bx[lanes.clone()].copy_from_slice(&px);
        p.by[lanes].copy_from_slice(&py);
    }
    (v, p)
}

/// Four bodies' states (`state` of lanes 0 to 3) turned into columns:
/// the four velocities' x, their y, the four pushes' x, their y. Each
/// state is one row of a 4×4 matrix, so the turn is a transpose, a few
/// shuffles on a vector unit, where reading each number into its own lane
/// took a load and a shuffle apiece. The numbers are only moved, never
/// changed.
#[inline(always)]
fn columns(state: impl Fn(usize) -> BodyState) -> [[f32; 4]; 4] {
    let row = |l| {
        let s = state(l);
        Vec4::new(s.vel.x, s.vel.y, s.push.x, s.push.y)
    };
    let m = Mat4::from_cols(row(0), row(1), row(2), row(3)).transpose();
    [m.x_axis, m.y_axis, m.z_axis, m.w_axis].map(|c| c.to_array())
}

/// Writes back the velocities of the bodies the lanes move.
#[inline(always)]
fn scatter_vel(k: &Block, bodies: &mut Bodies<'_>, v: &Lanes) {
    for l in 0..LANES {
        bodies.set_vel(k.write_a[l], v.a(l));
        bodies.set_vel(k.write_b[l], v.b(l));
    }
}

/// Writes back the velocities and pushes of the bodies the lanes move:
/// each body written once.
#[inline(always)]
fn scatter(k: &Block, bodies: &mut Bodies<'_>, v: &Lanes, p: &Lanes) {
    for l in 0..LANES {
        let (a, b) = (k.write_a[l], k.write_b[l]);
        bodies.set_state(
            a,
            BodyState {
                vel: v.a(l),
                push: p.a(l),
            },
        );
        bodies.set_state(
            b,
            BodyState {
                vel: v.b(l),
                push: p.b(l),
            },
        );
    }
}

/// Warm start and push carry of one block (see
/// [`scalar::begin_substep`](crate::solver::scalar::begin_substep)).
pub(crate) fn warm_start(k: &mut Block, bodies: &mut Bodies<'_>, warm: bool, carry: bool) {
    let carries = carry && k.carry.iter().any(|&c| c);
    if !carries {
        k.push_impulse = [0.0; LANES];
        if !warm {
            return;
        }
    }
    let (mut v, mut p) = gather(k, bodies);
    if carries {
        for l in 0..LANES {
            let q = k.push_impulse[l];
            // (A push is never negative: `>=` would apply a zero one.)
            if k.carry[l] && q > 0.0 {
                p.apply(k, l, k.nx[l] * q, k.ny[l] * q);
            } else {
                k.push_impulse[l] = 0.0;
            }
        }
    }
    if warm {
        for l in 0..LANES {
            let (n, t) = (k.normal_impulse[l], k.tangent_impulse[l]);
            // normal * n + perp(normal) * t
            let ix = k.nx[l] * n + -k.ny[l] * t;
            let iy = k.ny[l] * n + k.nx[l] * t;
            v.apply(k, l, ix, iy);
        }
    }
    if carries {
        scatter(k, bodies, &v, &p);
    } else {
        scatter_vel(k, bodies, &v);
    }
}

/// Separation now of each lane: the step's separation plus the relative
/// displacement along the normal since the step began (see
/// `scalar::separation`). The bodies move only between the passes,
/// so the passes of a substep share it.
#[inline(always)]
pub(crate) fn measure(k: &mut Block, bodies: &Bodies<'_>) {
    let mut d = Lanes::default();
    for l in 0..LANES {
        d.set(l, bodies.delta(k.a[l]), bodies.delta(k.b[l]));
    }
    separations(k, &d);
}

/// Each lane's separation now, from the lanes' bodies' displacements `d`
/// (see [`measure`]).
#[inline(always)]
fn separations(k: &mut Block, d: &Lanes) {
    for l in 0..LANES {
        let (nx, ny) = (k.nx[l], k.ny[l]);
        k.separation[l] =
            k.base_separation[l] + ((d.bx[l] - d.ax[l]) * nx + (d.by[l] - d.ay[l]) * ny);
    }
}

/// One Gauss-Seidel pass over a block's lanes (see
/// [`scalar::solve`](crate::solver::scalar::solve)):
/// the same rows in the same arithmetic, lane by lane. With `FRESH` each
/// lane's push impulse starts from zero (the first pass of a substep whose
/// warm start pass did not run to clear it). With `MEASURE` (a pass
/// without the push, right after the positions moved) each lane's
/// separation is measured first, from the displacements the states' push
/// slots then hold.
///
/// The push of a block [at rest](at_rest) is left out: it would change
/// nothing.
#[inline(always)]
pub(crate) fn solve_block<const PUSH: bool, const FRESH: bool, const MEASURE: bool>(
    k: &mut Block,
    bodies: &mut Bodies<'_>,
    r: &Rates,
) {
    let (mut v, mut p) = gather(k, bodies);
    if MEASURE {
        // After the positions moved the push slots hold the displacements
        // (see `BodyState`): [`measure`]'s numbers, read with the
        // velocities.
        debug_assert!(!PUSH);
        separations(k, &p);
    }
    // Push out of overlap deeper than the slop: each lane's target speed.
    let target: [f32; LANES] = std::array::from_fn(|l| {
        let s = k.separation[l];
        lesser((r.push_rate * (-s - r.slop)).max(0.0), r.push_out_speed)
    });
    let push = PUSH && !at_rest::<FRESH>(k, &p, &target);
    #[cfg(test)]
    if PUSH && !push {
        RESTING.with(|n| n.set(n.get() + 1));
    }
    for l in 0..LANES {
        let (nx, ny) = (k.nx[l], k.ny[l]);
        let (tx, ty) = (-ny, nx);
        let mass = k.mass[l];

        // Non-penetration: v_n >= 0, or >= -s / h while still apart.
        // (At `s` zero, `>=` would give a bias of zero too.)
        let s = k.separation[l];
        let bias = if s > 0.0 { s * r.inv_h } else { 0.0 };
        let (dvx, dvy) = (v.bx[l] - v.ax[l], v.by[l] - v.ay[l]);
        let (vn, vt) = (dvx * nx + dvy * ny, dvx * tx + dvy * ty);
        let n = k.normal_impulse[l];
        let new_n = ((n - mass * bias) - mass * vn).max(0.0);
        let dn = new_n - n;
        k.normal_impulse[l] = new_n;
        k.max_normal_impulse[l] = greater(k.max_normal_impulse[l], new_n);

        // Coulomb friction, |lambda_t| <= mu lambda_n, bounded by this
        // pass's normal impulse; `vt` read before the normal impulse,
        // which leaves it as it is, and both applied together (see
        // `scalar::solve`).
        let max_friction = k.friction[l] * new_n;
        let t = k.tangent_impulse[l];
        let new_t = clamp(
            t - mass * (vt - k.tangent_speed[l]),
            -max_friction,
            max_friction,
        );
        let dt = new_t - t;
        k.tangent_impulse[l] = new_t;
        v.apply(k, l, nx * dn + tx * dt, ny * dn + ty * dt);
    }
    // The push works on the push velocities alone: solved after the
    // velocities of every lane, it gives the same bits as lane by lane.
    if push {
        for (l, &target) in target.iter().enumerate() {
            let (nx, ny) = (k.nx[l], k.ny[l]);
            let pn = (p.bx[l] - p.ax[l]) * nx + (p.by[l] - p.ay[l]) * ny;
            let q = if FRESH { 0.0 } else { k.push_impulse[l] };
            let new_q = (q + k.mass[l] * (target - pn)).max(0.0);
            let dq = new_q - q;
            k.push_impulse[l] = new_q;
            p.apply(k, l, nx * dq, ny * dq);
        }
        scatter(k, bodies, &v, &p);
    } else {
        // (No pass runs with `FRESH` and without `PUSH`, and a block at
        // rest has no push impulse left: `||` would clear zeros.)
        if PUSH && FRESH {
            k.push_impulse = [0.0; LANES];
        }
        scatter_vel(k, bodies, &v);
    }
}

/// Whether a pass's push would leave a block as it is: every lane's
/// target push speed is `+0` (no overlap deeper than the slop), and so is
/// every lane's push impulse (or it starts from zero, `FRESH`) and each
/// push velocity of the lanes' bodies. Then each lane's new push impulse
/// works out to `+0` exactly (`+0 - ±0` is `+0`, and so is `+0 + ±0`),
/// and each push velocity stays `+0` (the normals and inverse masses are
/// finite: validated masses, unit normals): the push part of the pass is
/// the identity, bit for bit, and is left out. In a pile at rest no contact
/// is deeper than the slop and no body is pushed, so every block is; the
/// push pass then costs what a pass without it does (see BENCHMARKS.md).
#[inline(always)]
fn at_rest<const FRESH: bool>(k: &Block, p: &Lanes, target: &[f32; LANES]) -> bool {
    let mut bits = 0;
    for (l, target) in target.iter().enumerate() {
        let q = if FRESH {
            0
        } else {
            k.push_impulse[l].to_bits()
        };
        bits |= target.to_bits() | q;
        bits |= p.ax[l].to_bits() | p.ay[l].to_bits() | p.bx[l].to_bits() | p.by[l].to_bits();
    }
    bits == 0
}

#[cfg(test)]
thread_local! {
    /// Blocks whose push was left out as [`at_rest`], on this thread (for
    /// tests).
    pub(crate) static RESTING: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_block_is_at_rest_only_when_every_push_number_is_plus_zero() {
        let (k, still, zero) = (Block::PADDING, Lanes::default(), [0.0; LANES]);
        assert!(at_rest::<false>(&k, &still, &zero));
        // A target push speed equal to the push impulse left: not at rest
        // (their bits must not cancel), unless the pass starts afresh.
        let (mut pushed, mut target) = (k, zero);
        pushed.push_impulse[1] = 0.25;
        target[1] = 0.25;
        assert!(!at_rest::<false>(&pushed, &still, &target));
        assert!(!at_rest::<true>(&k, &still, &target));
        assert!(at_rest::<true>(&pushed, &still, &zero));
        assert!(!at_rest::<false>(&pushed, &still, &zero));
        // Two of a lane's push velocities equal (or one -0): not at rest.
        for (i, j) in [(0, 1), (1, 2), (2, 3), (0, 3)] {
            let mut p = Lanes::default();
            let parts = [&mut p.ax, &mut p.ay, &mut p.bx, &mut p.by];
            for (n, part) in parts.into_iter().enumerate() {
                if n == i || n == j {
                    part[2] = 0.5;
                }
            }
            assert!(!at_rest::<false>(&k, &p, &zero), "parts {i} and {j}");
        }
        let mut minus = Lanes::default();
        minus.by[0] = -0.0;
        assert!(!at_rest::<false>(&k, &minus, &zero));
    }
}
