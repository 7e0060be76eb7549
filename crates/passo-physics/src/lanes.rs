//! The wide contact passes: a colour's contacts laid out [`LANES`] (four or
//! eight) at a time as a structure of arrays (a [`Block`]). A pass gathers
//! the bodies of a block's lanes, solves the lanes side by side with the
//! scalar solver's arithmetic (plain loops over arrays, which the compiler
//! turns into vector instructions), and scatters back the bodies the lanes
//! move. A colour's last block is padded with lanes that name no body and
//! whose masses are zero. Which contacts share a block is `colouring`'s
//! business: the lanes of a block never move the same body.

use crate::constraint::Constraint;
use crate::solver::{SolverBodies, SolverParams};
use glam::Vec2;

/// Contacts solved side by side in a [`Block`]: the `f32`s of one vector
/// register, eight with AVX, four with SSE (the default x86-64 target;
/// eight there spill registers and ran 5 % slower). The lanes of a block
/// are independent, so the width changes the speed, never the bits.
#[cfg(target_feature = "avx")]
pub(crate) const LANES: usize = 8;
/// Contacts solved side by side in a [`Block`] (see the AVX version).
#[cfg(not(target_feature = "avx"))]
pub(crate) const LANES: usize = 4;

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

/// Which per-body array a block reads or writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Field {
    Vel,
    Push,
    /// The displacement since the step began: only read.
    Delta,
}

/// How blocks reach the bodies: velocities, pushes and displacements by
/// dynamic index. An index out of range ([`NONE`]) reads as zero and
/// writes nothing: one bounds check serves as the padding check.
pub(crate) trait View {
    /// `field` of body `i`.
    fn get(&self, field: Field, i: u32) -> Vec2;
    /// Sets `field` of body `i` (`Delta` is never written).
    fn set(&mut self, field: Field, i: u32, v: Vec2);
}

/// The bodies' arrays, borrowed from the solver's view of them.
pub(crate) struct Bodies<'a> {
    vel: &'a mut [Vec2],
    push: &'a mut [Vec2],
    delta: &'a [Vec2],
}

impl<'a> Bodies<'a> {
    pub(crate) fn new(bodies: &'a mut SolverBodies<'_>) -> Self {
        Self {
            vel: &mut *bodies.vel,
            push: &mut *bodies.push,
            delta: bodies.delta,
        }
    }
}

impl View for Bodies<'_> {
    #[inline(always)]
    fn get(&self, field: Field, i: u32) -> Vec2 {
        let array: &[Vec2] = match field {
            Field::Vel => self.vel,
            Field::Push => self.push,
            Field::Delta => self.delta,
        };
        array.get(i as usize).copied().unwrap_or(Vec2::ZERO)
    }

    #[inline(always)]
    fn set(&mut self, field: Field, i: u32, v: Vec2) {
        let array = match field {
            Field::Vel => &mut *self.vel,
            Field::Push => &mut *self.push,
            Field::Delta => return,
        };
        if let Some(slot) = array.get_mut(i as usize) {
            *slot = v;
        }
    }
}

/// Velocities (and pushes) of a block's lanes: A's and B's, by axis.
#[derive(Default)]
struct Lanes {
    ax: [f32; LANES],
    ay: [f32; LANES],
    bx: [f32; LANES],
    by: [f32; LANES],
}

impl Lanes {
    #[inline(always)]
    fn gather(k: &Block, get: impl Fn(u32) -> Vec2) -> Self {
        let mut s = Self::default();
        for l in 0..LANES {
            let (a, b) = (get(k.a[l]), get(k.b[l]));
            (s.ax[l], s.ay[l]) = (a.x, a.y);
            (s.bx[l], s.by[l]) = (b.x, b.y);
        }
        s
    }

    /// Writes back the bodies the lanes move.
    #[inline(always)]
    fn scatter(&self, k: &Block, mut set: impl FnMut(u32, Vec2)) {
        for l in 0..LANES {
            set(k.write_a[l], Vec2::new(self.ax[l], self.ay[l]));
            set(k.write_b[l], Vec2::new(self.bx[l], self.by[l]));
        }
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

/// Warm start and push carry of one block (see
/// [`solver::begin_substep`](crate::solver::begin_substep)).
pub(crate) fn warm_start<V: View>(k: &mut Block, bodies: &mut V, warm: bool, carry: bool) {
    let carries = carry && k.carry.iter().any(|&c| c);
    if carries {
        let mut p = Lanes::gather(k, |i| bodies.get(Field::Push, i));
        for l in 0..LANES {
            let q = k.push_impulse[l];
            if k.carry[l] && q > 0.0 {
                p.apply(k, l, k.nx[l] * q, k.ny[l] * q);
            } else {
                k.push_impulse[l] = 0.0;
            }
        }
        p.scatter(k, |i, v| bodies.set(Field::Push, i, v));
    } else {
        k.push_impulse = [0.0; LANES];
    }
    if warm {
        let mut v = Lanes::gather(k, |i| bodies.get(Field::Vel, i));
        for l in 0..LANES {
            let (n, t) = (k.normal_impulse[l], k.tangent_impulse[l]);
            // normal * n + perp(normal) * t
            let ix = k.nx[l] * n + -k.ny[l] * t;
            let iy = k.ny[l] * n + k.nx[l] * t;
            v.apply(k, l, ix, iy);
        }
        v.scatter(k, |i, v| bodies.set(Field::Vel, i, v));
    }
}

/// Separation now of each lane: the step's separation plus the relative
/// displacement along the normal since the step began (see
/// `SolverBodies::separation`). The bodies move only between the passes,
/// so the passes of a substep share it.
pub(crate) fn measure<V: View>(k: &mut Block, bodies: &mut V) {
    let d = Lanes::gather(k, |i| bodies.get(Field::Delta, i));
    for l in 0..LANES {
        let (nx, ny) = (k.nx[l], k.ny[l]);
        k.separation[l] =
            k.base_separation[l] + ((d.bx[l] - d.ax[l]) * nx + (d.by[l] - d.ay[l]) * ny);
    }
}

/// One Gauss-Seidel pass over a block's lanes (see
/// [`solver::solve`](crate::solver::solve)):
/// the same rows in the same arithmetic, lane by lane.
#[inline(always)]
pub(crate) fn solve_block<const PUSH: bool, V: View>(k: &mut Block, bodies: &mut V, r: &Rates) {
    let mut v = Lanes::gather(k, |i| bodies.get(Field::Vel, i));
    let mut p = if PUSH {
        Lanes::gather(k, |i| bodies.get(Field::Push, i))
    } else {
        Lanes::default()
    };
    for l in 0..LANES {
        let (nx, ny) = (k.nx[l], k.ny[l]);
        let (tx, ty) = (-ny, nx);
        let mass = k.mass[l];

        // Coulomb friction: |lambda_t| <= mu lambda_n.
        let vt = (v.bx[l] - v.ax[l]) * tx + (v.by[l] - v.ay[l]) * ty;
        let max_friction = k.friction[l] * k.normal_impulse[l];
        let t = k.tangent_impulse[l];
        let new_t = (t - mass * vt).max(-max_friction).min(max_friction);
        let dt = new_t - t;
        k.tangent_impulse[l] = new_t;
        v.apply(k, l, tx * dt, ty * dt);

        // Non-penetration: v_n >= 0, or >= -s / h while still apart.
        let s = k.separation[l];
        let bias = if s > 0.0 { s * r.inv_h } else { 0.0 };
        let vn = (v.bx[l] - v.ax[l]) * nx + (v.by[l] - v.ay[l]) * ny;
        let n = k.normal_impulse[l];
        let new_n = (n - mass * (vn + bias)).max(0.0);
        let dn = new_n - n;
        k.normal_impulse[l] = new_n;
        k.max_normal_impulse[l] = k.max_normal_impulse[l].max(new_n);
        v.apply(k, l, nx * dn, ny * dn);

        // Push out of overlap deeper than the slop.
        if PUSH {
            let target = (r.push_rate * (-s - r.slop)).max(0.0).min(r.push_out_speed);
            let pn = (p.bx[l] - p.ax[l]) * nx + (p.by[l] - p.ay[l]) * ny;
            let q = k.push_impulse[l];
            let new_q = (q + mass * (target - pn)).max(0.0);
            let dq = new_q - q;
            k.push_impulse[l] = new_q;
            p.apply(k, l, nx * dq, ny * dq);
        }
    }
    v.scatter(k, |i, x| bodies.set(Field::Vel, i, x));
    if PUSH {
        p.scatter(k, |i, x| bodies.set(Field::Push, i, x));
    }
}
