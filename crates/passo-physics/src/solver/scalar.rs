//! The contact solver: sequential impulses in substeps, with split-impulse
//! position correction.
//!
//! Bodies do not rotate, so every point of a manifold has the same
//! Jacobian: one normal row and one friction row per contact are exactly
//! what solving each point would give. Where these functions run in a
//! tick is described in `step/mod.rs`. After the first substep, the warm
//! start adds each body's velocity change of the last substep as the
//! substep starts (see `motion::Start::Replay`).
//!
//! The passes run colour by colour, four or eight contacts wide (see
//! `colouring`), in an order that keeps each body's contacts in the list's
//! order; the functions here solve contacts one by one, with the same
//! arithmetic: for the contacts no colour took, and for groups whose blocks
//! would be mostly padding.
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
//! overlapping would fly apart; the push never becomes velocity. Its
//! impulse starts from nothing each substep, except in a deep pile (one
//! holding a contact that overlaps by more than `DEEP_OVERLAP`), where it
//! carries on from substep to substep and step to step (see
//! [`begin_substep`]).

use crate::columns::Columns;
use crate::contact::constraint::{Constraint, ContactInfo};
use crate::parallel::{for_chunks, for_chunks_max};
use glam::Vec2;

/// What the solver needs of the contact settings, for one step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SolverParams {
    /// The substep, seconds.
    pub h: f32,
    /// Apply the last substep's impulses first.
    pub warm_starting: bool,
    /// Gauss-Seidel passes with the push, per substep.
    pub iterations: u32,
    /// Velocity passes after positions moved, per substep.
    pub relax_iterations: u32,
    /// Fraction of the overlap beyond the slop removed per substep.
    pub position_correction: f32,
    /// Cap on the push-apart speed, metres per second.
    pub push_out_speed: f32,
    /// Allowed penetration, metres.
    pub slop: f32,
    /// Impacts slower than this do not bounce, metres per second.
    pub restitution_threshold: f32,
    /// Carry each contact's push from one substep (and step) to the next:
    /// set for the steps that solve a deep pile (see [`begin_substep`]).
    pub carry_push: bool,
}

impl SolverParams {
    /// The default contact settings at 60 Hz with 4 substeps (for tests).
    #[cfg(test)]
    pub(crate) fn for_tests() -> Self {
        Self {
            h: 1.0 / 240.0,
            warm_starting: true,
            iterations: 1,
            relax_iterations: 1,
            position_correction: 0.2,
            push_out_speed: 3.0,
            slop: 0.005,
            restitution_threshold: 1.0,
            carry_push: false,
        }
    }
}

/// A dynamic body's two velocities while the contact passes run, side by
/// side so that a pass reads and writes each body once: its velocity, and
/// its push velocity of this substep (split impulses). Sixteen bytes, one
/// aligned load; a pass that kept the two in separate arrays gathered and
/// scattered each body twice.
///
/// Once the positions have moved (the push spent), `push` holds the
/// body's displacement since the step began instead, until the next
/// substep loads the states: the relax stage's first pass measures the
/// separations from it, read with the velocity (its own walk over the
/// displacements took 5 % of a step of the pyramid of base 50).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C, align(16))]
pub(crate) struct BodyState {
    pub vel: Vec2,
    pub push: Vec2,
}

impl BodyState {
    /// A body moving at `vel`, with no push yet.
    #[inline(always)]
    pub(crate) fn moving(vel: Vec2) -> Self {
        Self {
            vel,
            push: Vec2::ZERO,
        }
    }

    /// The states of bodies moving at `vel`, with no push, and the rest
    /// state after them (for tests; see [`SolverBodies::state`]).
    #[cfg(test)]
    pub(crate) fn of(vel: &[Vec2]) -> Vec<Self> {
        let states = vel.iter().map(|&v| Self::moving(v));
        states.chain([Self::default()]).collect()
    }

    /// The velocities and pushes of `states`, without the rest state
    /// (for tests).
    #[cfg(test)]
    pub(crate) fn split(states: &[Self]) -> (Vec<Vec2>, Vec<Vec2>) {
        let (rest, bodies) = states.split_last().expect("the rest state");
        assert_eq!(*rest, Self::default(), "the rest state is never written");
        bodies.iter().map(|s| (s.vel, s.push)).unzip()
    }
}

/// The solver's view of the bodies during one step.
pub(crate) struct SolverBodies<'a> {
    /// Velocity and push of each dynamic body, and one more state after
    /// them: the rest state, zero and never written, which a lane that
    /// names no body (padding, or a static B) reads. The wide passes then
    /// read every lane's bodies without a branch.
    pub state: &'a mut [BodyState],
    /// Displacement of each body since the step began.
    pub delta: &'a [Vec2],
    /// Per body, whether it is in a deep pile this step (empty: none is).
    pub deep: &'a [bool],
}

/// What `get` reads of a contact's two bodies in `bodies` (per dynamic
/// body: a velocity, a state, a displacement); zero for a static B.
#[inline(always)]
fn of_pair<T>(bodies: &[T], c: &Constraint, get: impl Fn(&T) -> Vec2) -> (Vec2, Vec2) {
    let b = c.b.dynamic_index().map_or(Vec2::ZERO, |b| get(&bodies[b]));
    (get(&bodies[c.a as usize]), b)
}

/// Separation now: the step's separation plus the relative displacement
/// along the normal since the step began (exact for boxes, first order
/// for circles; bodies do not rotate).
#[inline(always)]
fn separation(delta: &[Vec2], c: &Constraint) -> f32 {
    let (da, db) = of_pair(delta, c, |d| *d);
    c.base_separation + (db - da).dot(c.normal)
}

/// Applies `impulse` to the velocity `field` picks of each body in
/// `bodies` (a velocity, or a state's velocity or push): minus to A, plus
/// to B, for the bodies the contact moves (a held body is not written, as
/// in the wide passes).
#[inline(always)]
fn apply_impulse<T>(
    bodies: &mut [T],
    field: fn(&mut T) -> &mut Vec2,
    c: &Constraint,
    impulse: Vec2,
) {
    let (a, b) = c.moved();
    if let Some(a) = a {
        *field(&mut bodies[a]) -= impulse * c.inv_mass_a;
    }
    if let Some(b) = b {
        *field(&mut bodies[b]) += impulse * c.inv_mass_b;
    }
}

/// The greater of `x` and `y` as a compare and a select: one vector
/// instruction (`maxps`) where `f32::max` needs four more to handle NaN. A
/// NaN `x` gives `y` (as `f32::max` does), but a NaN `y` gives NaN (where
/// `f32::max` gives `x`); of two zeros it gives `y` (which `f32::max` leaves
/// open).
#[inline(always)]
pub(crate) fn greater(x: f32, y: f32) -> f32 {
    if x > y { x } else { y }
}

/// The lesser of `x` and `y` (see [`greater`]; `minps`). A NaN `x` gives
/// `y`, a NaN `y` gives NaN.
#[inline(always)]
pub(crate) fn lesser(x: f32, y: f32) -> f32 {
    if x < y { x } else { y }
}

/// `x` clamped to `[lo, hi]` by [`greater`] then [`lesser`]. A NaN `x` gives
/// `lesser(lo, hi)`; unlike `x.max(lo).min(hi)`, a NaN bound is not
/// skipped. (The solver's bounds are never NaN: the normal impulse is
/// clamped at zero and the push speed is validated.)
#[inline(always)]
pub(crate) fn clamp(x: f32, lo: f32, hi: f32) -> f32 {
    lesser(greater(x, lo), hi)
}

/// Starts a substep: applies the impulses carried from the last substep
/// (or step) when warm starting.
///
/// The push out of overlap starts from nothing in each substep, except in
/// a deep pile (`carry_push`, and the bodies of [`DeepPiles`]): there each
/// substep's Gauss-Seidel passes go on from the pushes the last one found,
/// so the push spreads through the whole pile instead of a few contacts
/// deep. The pile then opens out as one: 10 000 circles spawned on one
/// spot are apart in about 5 s instead of over 15 s. Other piles never
/// carry it: there a push that outlives the overlap it was for lifts
/// bodies off and keeps the pile from coming to rest.
pub(crate) fn begin_substep(
    constraints: &mut [Constraint],
    bodies: &mut SolverBodies<'_>,
    params: &SolverParams,
) {
    let (warm, carry) = (params.warm_starting, params.carry_push);
    for c in constraints {
        // (`>= 0.0` applies a push of nothing: the same.)
        if carry && c.push_impulse > 0.0 && bodies.deep[c.a as usize] {
            apply_impulse(bodies.state, |s| &mut s.push, c, c.normal * c.push_impulse);
        } else {
            c.push_impulse = 0.0;
        }
        if warm {
            let tangent = c.normal.perp();
            let impulse = c.normal * c.normal_impulse + tangent * c.tangent_impulse;
            apply_impulse(bodies.state, |s| &mut s.vel, c, impulse);
        }
    }
}

/// One Gauss-Seidel pass over every contact: the normal row, then friction,
/// and
/// (with `push`) the split-impulse push out of overlap deeper than the slop.
/// Each contact reads its two bodies' velocities once, updates them in
/// registers and writes them back once.
pub(crate) fn solve(
    constraints: &mut [Constraint],
    bodies: &mut SolverBodies<'_>,
    params: &SolverParams,
    push: bool,
) {
    let inv_h = 1.0 / params.h;
    let push_rate = params.position_correction * inv_h;
    for c in constraints.iter_mut() {
        // `ib` is only read for a dynamic B. A body the contact does not
        // move (inverse mass zero) is read, never written, as in the wide
        // passes of `colouring`.
        let (ia, ib) = (c.a as usize, c.b.index());
        let b_static = c.is_static();
        let (moved_a, moved_b) = c.moved();
        let (mut va, mut vb) = of_pair(bodies.state, c, |s| s.vel);
        let tangent = c.normal.perp();

        // Non-penetration: v_n >= 0, or >= -s / h while still apart.
        let s = separation(bodies.delta, c);
        let bias = if s > 0.0 { s * inv_h } else { 0.0 };
        let dv = vb - va;
        let (vn, vt) = (dv.dot(c.normal), dv.dot(tangent));
        let new_n = ((c.normal_impulse - c.mass * bias) - c.mass * vn).max(0.0);
        let dn = new_n - c.normal_impulse;
        c.normal_impulse = new_n;
        c.max_normal_impulse = greater(c.max_normal_impulse, new_n);

        // Coulomb friction, |lambda_t| <= mu lambda_n, bounded by this
        // pass's normal impulse (as Box2D v3 orders them: friction first
        // would be bounded by the last pass's, none on a new contact). The
        // normal impulse changes the relative velocity along the normal
        // alone (the bodies do not rotate), so `vt` is read before it, and
        // the two impulses are applied together: a pass's chain of
        // dependent operations a third shorter (see BENCHMARKS.md).
        let max_friction = c.friction * new_n;
        // `greater` then `lesser`, as the wide passes (`f32::clamp` would
        // pass a NaN through, and panic on bounds the wrong way round).
        let new_t = clamp(
            c.tangent_impulse - c.mass * (vt - c.tangent_speed),
            -max_friction,
            max_friction,
        );
        let dt = new_t - c.tangent_impulse;
        c.tangent_impulse = new_t;
        let impulse = c.normal * dn + tangent * dt;
        va -= impulse * c.inv_mass_a;
        if !b_static {
            vb += impulse * c.inv_mass_b;
        }
        if let Some(a) = moved_a {
            bodies.state[a].vel = va;
        }
        if let Some(b) = moved_b {
            bodies.state[b].vel = vb;
        }

        // Push out of overlap deeper than the slop.
        if push {
            let target = lesser(
                (push_rate * (-s - params.slop)).max(0.0),
                params.push_out_speed,
            );
            let pa = bodies.state[ia].push;
            let pb = if b_static {
                Vec2::ZERO
            } else {
                bodies.state[ib].push
            };
            let pn = (pb - pa).dot(c.normal);
            let new_p = (c.push_impulse + c.mass * (target - pn)).max(0.0);
            let impulse = c.normal * (new_p - c.push_impulse);
            c.push_impulse = new_p;
            if let Some(a) = moved_a {
                bodies.state[a].push = pa - impulse * c.inv_mass_a;
            }
            if let Some(b) = moved_b {
                bodies.state[b].push = pb + impulse * c.inv_mass_b;
            }
        }
    }
}

/// After the substeps: contacts hit faster than the threshold bounce,
/// `u <- -e u_impact` (see [`Constraint::new`]). `vel` holds the dynamic
/// bodies' velocities.
pub(crate) fn restitution(
    constraints: &mut [Constraint],
    infos: &[ContactInfo],
    vel: &mut Columns,
    threshold: f32,
) {
    for (c, info) in constraints.iter_mut().zip(infos) {
        if info.restitution == 0.0 || info.impact_u > -threshold || c.max_normal_impulse == 0.0 {
            continue;
        }
        let va = vel.at(c.a as usize);
        let vb = c.b.dynamic_index().map_or(Vec2::ZERO, |b| vel.at(b));
        let vn = (vb - va).dot(c.normal);
        let target = -info.restitution * info.impact_u - info.half_an_h;
        let new_n = (c.normal_impulse + c.mass * (target - vn)).max(0.0);
        let dn = new_n - c.normal_impulse;
        c.normal_impulse = new_n;
        c.max_normal_impulse = c.max_normal_impulse.max(new_n);
        let impulse = c.normal * dn;
        let (a, b) = c.moved();
        if let Some(a) = a {
            vel.set(a, vel.at(a) - impulse * c.inv_mass_a);
        }
        if let Some(b) = b {
            vel.set(b, vel.at(b) + impulse * c.inv_mass_b);
        }
    }
}

/// The piles (bodies joined by contacts) that hold a contact overlapping
/// by more than a depth, found with a union-find over the contacts.
#[derive(Clone, Debug, Default)]
pub(crate) struct DeepPiles {
    parent: Vec<u32>,
    deep_root: Vec<bool>,
    /// Per dynamic body: whether it is in a deep pile (empty: none is).
    pub deep: Vec<bool>,
}

impl DeepPiles {
    /// Finds the piles of `constraints` (over `bodies` dynamic bodies)
    /// holding a contact overlapping by more than `depth` metres when the
    /// step begins; returns whether there is any. `O(contacts)` then, and
    /// one pass over the contacts otherwise (in chunks on the pool when
    /// `parallel`).
    pub(crate) fn find(
        &mut self,
        constraints: &[Constraint],
        bodies: usize,
        depth: f32,
        parallel: bool,
    ) -> bool {
        self.deep.clear();
        // (Should this ask `>`, only a pile whose every contact is deep,
        // one spawned on a single spot, goes unfound, for one step: then
        // some are shallower and the search below finds it. The unit test
        // asks for such a pile.)
        let deep = for_chunks_max(parallel, constraints, |rows| {
            u64::from(rows.iter().any(|c| c.base_separation < -depth))
        });
        if deep == 0 {
            return false;
        }
        self.parent.clear();
        self.parent.extend(0..bodies as u32);
        for c in constraints {
            if let Some(b) = c.b.dynamic_index() {
                let (ra, rb) = (self.root(c.a), self.root(b as u32));
                // The lower index becomes the root: the result depends on
                // the contacts alone, not on the order of the unions.
                let (lo, hi) = (ra.min(rb), ra.max(rb));
                self.parent[hi as usize] = lo;
            }
        }
        self.deep_root.clear();
        self.deep_root.resize(bodies, false);
        for c in constraints {
            if c.base_separation < -depth {
                let r = self.root(c.a);
                self.deep_root[r as usize] = true;
            }
        }
        for i in 0..bodies as u32 {
            let r = self.root(i);
            self.deep.push(self.deep_root[r as usize]);
        }
        true
    }

    fn root(&mut self, mut i: u32) -> u32 {
        while self.parent[i as usize] != i {
            let p = self.parent[i as usize];
            // Path halving.
            self.parent[i as usize] = self.parent[p as usize];
            i = p;
        }
        i
    }
}

/// Records each contact's separation at the end of the step, from the
/// bodies' displacements `delta` since it began (in chunks on the thread
/// pool when `parallel` and there are many).
pub(crate) fn store_separations(
    constraints: &[Constraint],
    infos: &mut [ContactInfo],
    delta: &[Vec2],
    parallel: bool,
) {
    for_chunks(parallel, (constraints, infos), |_, (constraints, infos)| {
        for (c, info) in constraints.iter().zip(infos) {
            info.separation = separation(delta, c) - info.lead;
        }
        0
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::collider::ColliderRef;

    /// A contact between dynamic bodies `a` and `b` (or `a` and a static
    /// body), overlapping by `depth`.
    fn contact(a: u32, b: Option<u32>, depth: f32) -> Constraint {
        Constraint {
            a,
            b: b.map_or(ColliderRef::fixed(0), ColliderRef::dynamic),
            normal: Vec2::Y,
            base_separation: -depth,
            inv_mass_a: 1.0,
            inv_mass_b: f32::from(u8::from(b.is_some())),
            mass: 0.5,
            friction: 0.6,
            normal_impulse: 0.0,
            tangent_impulse: 0.0,
            push_impulse: 0.0,
            max_normal_impulse: 0.0,
            tangent_speed: 0.0,
        }
    }

    /// Which of `bodies` bodies `find` puts in a deep pile (overlap beyond
    /// 0.1 m), or `None` if it finds none.
    fn deep(rows: &[Constraint], bodies: usize) -> Option<Vec<usize>> {
        let mut piles = DeepPiles::default();
        piles
            .find(rows, bodies, 0.1, false)
            .then(|| (0..bodies).filter(|&i| piles.deep[i]).collect())
    }

    #[test]
    fn a_pile_is_deep_when_any_of_its_contacts_is_deeper_than_the_depth() {
        // Piles {0, 1, 2} (a chain, joined in any order), {3, 4} and {5}
        // on the ground, and 6 alone.
        let chain = [
            contact(0, Some(1), 0.01),
            contact(2, Some(1), 0.01),
            contact(3, Some(4), 0.01),
            contact(5, None, 0.01),
        ];
        assert_eq!(deep(&chain, 7), None, "nothing deeper than 0.1 m");
        // Exactly at the depth is not deeper.
        let mut rows = chain.to_vec();
        rows[1].base_separation = -0.1;
        assert_eq!(deep(&rows, 7), None);
        for (row, pile) in [
            (0, vec![0, 1, 2]),
            (1, vec![0, 1, 2]),
            (2, vec![3, 4]),
            (3, vec![5]),
        ] {
            let mut rows = chain.to_vec();
            rows[row].base_separation = -0.2;
            assert_eq!(deep(&rows, 7), Some(pile.clone()), "row {row}");
            // The rows in the other order: the same piles.
            rows.reverse();
            assert_eq!(deep(&rows, 7), Some(pile), "row {row}, reversed");
        }
        // One pile deeper than the depth, another exactly as deep: only
        // the first.
        let mut rows = chain.to_vec();
        rows[2].base_separation = -0.1;
        rows[3].base_separation = -0.2;
        assert_eq!(deep(&rows, 7), Some(vec![5]));
        // Every contact deep (a pile spawned on one spot): all of them.
        let all: Vec<Constraint> = chain
            .iter()
            .map(|c| Constraint {
                base_separation: -0.5,
                ..*c
            })
            .collect();
        assert_eq!(deep(&all, 7), Some(vec![0, 1, 2, 3, 4, 5]));
    }
}
