//! The contact solver: sequential impulses in substeps, with split-impulse
//! position correction.
//!
//! Bodies do not rotate, so every point of a manifold has the same
//! Jacobian: one normal row and one friction row per contact are exactly
//! what solving each point would give. Per step:
//!
//! ```text
//! prepare contacts (narrow phase, warm-start impulses)
//! for each substep h = dt / substeps:
//!     integrate velocities (forces)
//!     warm start: apply the last substep's impulses
//!     iterate: friction, normal (velocity), push (position)
//!     integrate positions with velocity + push; forget the push
//!     relax: more velocity iterations
//! restitution
//! ```
//!
//! The normal row is a hard constraint `v_n >= 0` with accumulated-impulse
//! clamping (`lambda >= 0`) and warm starting, so a resting contact's impulse
//! converges to exactly the weight it carries and nothing sinks. A contact
//! still apart (separation `s > 0`) lets the bodies close at most `s / h`:
//! a speculative contact, which stops fast bodies at the surface. Friction
//! is Coulomb's: `|lambda_t| <= mu lambda_n`.
//!
//! Overlap deeper than the slop is removed by split impulses: a separate
//! "push" velocity, solved like the normal row with target
//! `min(beta (-s - slop) / h, push_out_speed)`, moves the bodies apart and is
//! then discarded. Baumgarte stabilisation (a bias in the real velocity)
//! would turn every overlap into kinetic energy, so bodies created
//! overlapping would fly apart; the push never becomes velocity.

use crate::body::{DynamicBodies, StaticBodies};
use crate::manifold::Manifold;
use crate::{BodyId, ContactSettings};
use glam::Vec2;

/// Marks a constraint's body B as static; the low bits are its static index.
pub(crate) const STATIC_BODY: u32 = 1 << 31;

/// What the solver reads and writes of one contact between a dynamic body
/// A and a dynamic or static body B: kept small (56 bytes), so the passes
/// over every contact stay in cache.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Constraint {
    pub a: u32,
    pub b: u32,
    pub normal: Vec2,
    /// Separation when the step began.
    pub base_separation: f32,
    inv_mass_a: f32,
    inv_mass_b: f32,
    /// `1 / (1/m_a + 1/m_b)`, the same for the normal and the friction row.
    mass: f32,
    friction: f32,
    pub normal_impulse: f32,
    pub tangent_impulse: f32,
    /// Push (position) impulse of the current substep.
    push_impulse: f32,
    pub max_normal_impulse: f32,
}

/// The rest of a contact: who, where, and what restitution needs.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct ContactInfo {
    pub id_a: BodyId,
    pub id_b: BodyId,
    /// Separation after the last substep.
    pub separation: f32,
    pub points: [Vec2; 2],
    pub point_count: u8,
    restitution: f32,
    /// `u = v_n + a_n h / 2` at impact (negative when approaching).
    impact_u: f32,
    /// `a_n h / 2`.
    half_an_h: f32,
}

impl ContactInfo {
    /// The pair's order key (see `contact::key`).
    pub fn key(&self) -> (BodyId, BodyId) {
        crate::contact::key(self.id_a, self.id_b)
    }

    /// Touching: the solver pushed the bodies apart this step, or they overlap.
    pub fn is_touching(&self, c: &Constraint) -> bool {
        c.max_normal_impulse > 0.0 || self.separation < 0.0
    }
}

impl Constraint {
    /// The solver row and the rest of a new contact.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        m: &Manifold,
        a: u32,
        b: u32,
        id_a: BodyId,
        id_b: BodyId,
        dynamic: &DynamicBodies,
        statics: &StaticBodies,
        gravity: Vec2,
        h: f32,
    ) -> (Self, ContactInfo) {
        let ai = a as usize;
        let b_static = b & STATIC_BODY != 0;
        // A sleeping body holds like a static one: it is not solved this
        // step (an awake body touching it wakes its island for the next).
        let asleep = |i: usize| dynamic.sleep[i].is_asleep();
        let (a_holds, b_holds) = (asleep(ai), b_static || asleep(b as usize));
        let (inv_mass_b, friction_b, restitution_b, vel_b) = if b_static {
            let s = (b & !STATIC_BODY) as usize;
            (
                0.0,
                statics.friction[s],
                statics.meta[s].restitution,
                Vec2::ZERO,
            )
        } else {
            let bi = b as usize;
            (
                if b_holds { 0.0 } else { dynamic.inv_mass[bi] },
                dynamic.friction[bi],
                dynamic.meta[bi].restitution,
                dynamic.vel[bi],
            )
        };
        let inv_mass_a = if a_holds { 0.0 } else { dynamic.inv_mass[ai] };
        let k = inv_mass_a + inv_mass_b;
        // Restitution reflects the normal velocity at the moment of impact,
        // in the form the integrator conserves. With a relative normal
        // acceleration `a_n` (gravity; only a static B does not fall with A),
        // semi-implicit Euler over substeps `h` conserves exactly
        // `Q = 1/2 u^2 - a_n s` with `u = v_n + a_n h / 2`. A contact still
        // apart closes the gap `s`, so at impact `u^2 = u0^2 - 2 a_n s`; the
        // bounce sets `u <- -e u`. An elastic ball then keeps `Q`, and so its
        // height, bounce after bounce, wherever in a step the impact falls.
        let vn = (vel_b - dynamic.vel[ai]).dot(m.normal);
        // Relative normal acceleration: gravity moves only the bodies that
        // are free to fall (a static or sleeping body holds).
        let falls = |holds: bool| if holds { Vec2::ZERO } else { gravity };
        let a_n = (falls(b_holds) - falls(a_holds)).dot(m.normal);
        let half_an_h = 0.5 * a_n * h;
        let u0 = vn + half_an_h;
        let mut impact_u = u0;
        if m.separation > 0.0 && (u0 < 0.0 || a_n < 0.0) {
            let u2 = u0 * u0 - 2.0 * a_n * m.separation;
            if u2 > 0.0 {
                impact_u = -u2.sqrt();
            }
        }
        let row = Self {
            a,
            b,
            normal: m.normal,
            base_separation: m.separation,
            inv_mass_a,
            inv_mass_b,
            mass: if k > 0.0 { 1.0 / k } else { 0.0 },
            friction: (dynamic.friction[ai] * friction_b).sqrt(),
            normal_impulse: 0.0,
            tangent_impulse: 0.0,
            push_impulse: 0.0,
            max_normal_impulse: 0.0,
        };
        let info = ContactInfo {
            id_a,
            id_b,
            separation: m.separation,
            points: m.points,
            point_count: m.point_count,
            restitution: dynamic.meta[ai].restitution.max(restitution_b),
            impact_u,
            half_an_h,
        };
        (row, info)
    }

    pub fn is_static(&self) -> bool {
        self.b & STATIC_BODY != 0
    }

    /// Whether every number is finite and every mass term >= 0 (for
    /// snapshots).
    pub fn is_valid(&self) -> bool {
        let numbers = [
            self.base_separation,
            self.inv_mass_a,
            self.inv_mass_b,
            self.mass,
            self.friction,
            self.normal_impulse,
            self.tangent_impulse,
            self.push_impulse,
            self.max_normal_impulse,
        ];
        self.normal.is_finite()
            && numbers.iter().all(|x| x.is_finite())
            && self.inv_mass_a >= 0.0
            && self.inv_mass_b >= 0.0
            && self.mass >= 0.0
    }
}

/// The solver's view of the bodies during one step.
pub(crate) struct SolverBodies<'a> {
    pub vel: &'a mut [Vec2],
    /// Push velocities of this substep (split impulses).
    pub push: &'a mut [Vec2],
    /// Displacement of each body since the step began.
    pub delta: &'a [Vec2],
}

impl SolverBodies<'_> {
    #[inline(always)]
    fn velocity(&self, c: &Constraint) -> (Vec2, Vec2) {
        let va = self.vel[c.a as usize];
        let vb = if c.is_static() {
            Vec2::ZERO
        } else {
            self.vel[c.b as usize]
        };
        (va, vb)
    }

    #[inline(always)]
    fn apply(&mut self, c: &Constraint, impulse: Vec2) {
        self.vel[c.a as usize] -= impulse * c.inv_mass_a;
        if !c.is_static() {
            self.vel[c.b as usize] += impulse * c.inv_mass_b;
        }
    }

    /// Separation now: the step's separation plus the relative displacement
    /// along the normal since the step began (exact for boxes, first order
    /// for circles; bodies do not rotate).
    #[inline(always)]
    fn separation(&self, c: &Constraint) -> f32 {
        let da = self.delta[c.a as usize];
        let db = if c.is_static() {
            Vec2::ZERO
        } else {
            self.delta[c.b as usize]
        };
        c.base_separation + (db - da).dot(c.normal)
    }
}

/// Starts a substep: applies the impulses carried from the last substep
/// (or step) when warm starting, and clears the push impulses.
pub(crate) fn begin_substep(
    constraints: &mut [Constraint],
    bodies: &mut SolverBodies<'_>,
    warm: bool,
) {
    for c in constraints {
        c.push_impulse = 0.0;
        if warm {
            let tangent = c.normal.perp();
            bodies.apply(c, c.normal * c.normal_impulse + tangent * c.tangent_impulse);
        }
    }
}

/// One Gauss-Seidel pass over every contact: friction, the normal row, and
/// (with `push`) the split-impulse push out of overlap deeper than the slop.
/// Each contact reads its two bodies' velocities once, updates them in
/// registers and writes them back once.
pub(crate) fn solve(
    constraints: &mut [Constraint],
    bodies: &mut SolverBodies<'_>,
    settings: &ContactSettings,
    h: f32,
    push: bool,
) {
    let inv_h = 1.0 / h;
    let push_rate = settings.position_correction * inv_h;
    for c in constraints.iter_mut() {
        let (ia, ib) = (c.a as usize, c.b as usize);
        let b_static = c.is_static();
        let (mut va, mut vb) = bodies.velocity(c);
        let tangent = c.normal.perp();

        // Coulomb friction: |lambda_t| <= mu lambda_n.
        let vt = (vb - va).dot(tangent);
        let max_friction = c.friction * c.normal_impulse;
        let new_t = (c.tangent_impulse - c.mass * vt).clamp(-max_friction, max_friction);
        let impulse = tangent * (new_t - c.tangent_impulse);
        c.tangent_impulse = new_t;
        va -= impulse * c.inv_mass_a;
        if !b_static {
            vb += impulse * c.inv_mass_b;
        }

        // Non-penetration: v_n >= 0, or >= -s / h while still apart.
        let s = bodies.separation(c);
        let bias = if s > 0.0 { s * inv_h } else { 0.0 };
        let vn = (vb - va).dot(c.normal);
        let new_n = (c.normal_impulse - c.mass * (vn + bias)).max(0.0);
        let impulse = c.normal * (new_n - c.normal_impulse);
        c.normal_impulse = new_n;
        c.max_normal_impulse = c.max_normal_impulse.max(new_n);
        va -= impulse * c.inv_mass_a;
        bodies.vel[ia] = va;
        if !b_static {
            vb += impulse * c.inv_mass_b;
            bodies.vel[ib] = vb;
        }

        // Push out of overlap deeper than the slop.
        if push {
            let target = (push_rate * (-s - settings.slop)).clamp(0.0, settings.push_out_speed);
            let pa = bodies.push[ia];
            let pb = if b_static {
                Vec2::ZERO
            } else {
                bodies.push[ib]
            };
            let pn = (pb - pa).dot(c.normal);
            let new_p = (c.push_impulse + c.mass * (target - pn)).max(0.0);
            let impulse = c.normal * (new_p - c.push_impulse);
            c.push_impulse = new_p;
            bodies.push[ia] = pa - impulse * c.inv_mass_a;
            if !b_static {
                bodies.push[ib] = pb + impulse * c.inv_mass_b;
            }
        }
    }
}

/// After the substeps: contacts hit faster than the threshold bounce,
/// `u <- -e u_impact` (see [`Constraint::new`]).
pub(crate) fn restitution(
    constraints: &mut [Constraint],
    infos: &[ContactInfo],
    bodies: &mut SolverBodies<'_>,
    threshold: f32,
) {
    for (c, info) in constraints.iter_mut().zip(infos) {
        if info.restitution == 0.0 || info.impact_u > -threshold || c.max_normal_impulse == 0.0 {
            continue;
        }
        let (va, vb) = bodies.velocity(c);
        let vn = (vb - va).dot(c.normal);
        let target = -info.restitution * info.impact_u - info.half_an_h;
        let new_n = (c.normal_impulse + c.mass * (target - vn)).max(0.0);
        let dn = new_n - c.normal_impulse;
        c.normal_impulse = new_n;
        c.max_normal_impulse = c.max_normal_impulse.max(new_n);
        bodies.apply(c, c.normal * dn);
    }
}

/// Records each contact's separation at the end of the step.
pub(crate) fn store_separations(
    constraints: &[Constraint],
    infos: &mut [ContactInfo],
    bodies: &SolverBodies<'_>,
) {
    for (c, info) in constraints.iter().zip(infos) {
        info.separation = bodies.separation(c);
    }
}
