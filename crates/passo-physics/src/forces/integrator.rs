//! Integrators: how one step of length `dt` turns accelerations into new
//! velocities and positions.
//!
//! Each integrator computes the new velocity and, for the multi-stage ones,
//! a position correction `c`, so the world can run contacts and speed clamps
//! on the velocity before it moves bodies with `p <- p + v dt + c`. For
//! semi-implicit Euler `c = 0`: it is the plain `v += a dt; p += v dt`.

use crate::body::store::BodyParams;
use crate::body::store::flush_subnormal;
use crate::forces::models::{Dissipation, Drive, ForceForm};
use glam::Vec2;

/// The time-stepping method of a world.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Integrator {
    /// `p += v dt; v += a dt` (position first, with the old velocity).
    /// First order; adds energy to oscillators (`(1 + w^2 dt^2)` per step on
    /// a spring). Kept for comparison.
    ExplicitEuler,
    /// Semi-implicit (symplectic) Euler: `v += a dt; p += v dt`, velocity
    /// first. First order, one force evaluation, and its energy error on
    /// conservative systems stays bounded. The default, as in most game
    /// engines.
    #[default]
    SemiImplicitEuler,
    /// Velocity Verlet: `p += v dt + a0 dt^2 / 2; v += (a0 + a1) dt / 2`.
    /// Second order, two force evaluations. For velocity-dependent forces
    /// `a1` is evaluated at the predicted velocity `v + a0 dt`, which keeps
    /// the method second order. Dry friction is split off (see
    /// [`Rk4`](Self::Rk4)).
    VelocityVerlet,
    /// Classical fourth-order Runge-Kutta on `(p, v)`, every force model
    /// evaluated at each of the four stages. Fourth order, four evaluations.
    ///
    /// Dry friction (surface and game-applied) is not a smooth force: it
    /// flips with the velocity's direction, and evaluated in the stages its
    /// flips cancel, so a body slower than about `mu g dt` kept coasting for
    /// ever. Verlet and RK4 apply it in its exact form for half a step
    /// before their stages and half after (Strang splitting): a sliding
    /// body stops exactly and never reverses. The splitting is second
    /// order: while dry friction acts, RK4 converges at second order (a
    /// spring with `mu = 0.2` friction: slopes 1.7-2.0 from dt = 1/8 to
    /// 1/64), and fourth order again where none acts.
    Rk4,
}

impl Integrator {
    /// Every integrator, cheapest first.
    pub const ALL: [Self; 4] = [
        Self::ExplicitEuler,
        Self::SemiImplicitEuler,
        Self::VelocityVerlet,
        Self::Rk4,
    ];

    /// A short lowercase name: `explicit_euler`, `semi_implicit_euler`,
    /// `velocity_verlet`, `rk4`.
    pub fn name(self) -> &'static str {
        match self {
            Self::ExplicitEuler => "explicit_euler",
            Self::SemiImplicitEuler => "semi_implicit_euler",
            Self::VelocityVerlet => "velocity_verlet",
            Self::Rk4 => "rk4",
        }
    }

    /// Whether drag and friction can be applied in their stable form. Only
    /// the Euler methods split them off; Verlet and RK4 evaluate every other
    /// force as written, which is what makes them higher order, and split
    /// off dry friction alone (see [`Rk4`](Self::Rk4)).
    pub(crate) fn splits_dissipation(self) -> bool {
        matches!(self, Self::ExplicitEuler | Self::SemiImplicitEuler)
    }
}

/// The forces a step evaluates, with the constants hoisted out of the loop.
#[derive(Clone, Copy)]
pub(crate) struct Forces<'a> {
    pub drive: Drive<'a>,
    pub dissipation: Dissipation,
    /// Apply dissipation as exact factors after the Euler update.
    pub stable: bool,
}

impl<'a> Forces<'a> {
    pub(crate) fn new(
        drive: Drive<'a>,
        dissipation: Dissipation,
        form: ForceForm,
        integrator: Integrator,
    ) -> Self {
        Self {
            drive,
            stable: form == ForceForm::Stable && integrator.splits_dissipation(),
            dissipation,
        }
    }

    /// Total acceleration with every force in its plain form.
    #[inline(always)]
    fn accel(&self, p: Vec2, v: Vec2, b: &BodyParams) -> Vec2 {
        self.accel_with(p, v, b, Dissipation::accel)
    }

    /// Total acceleration but dry friction, every force in its plain form
    /// (the stages of Verlet and RK4).
    #[inline(always)]
    fn smooth_accel(&self, p: Vec2, v: Vec2, b: &BodyParams) -> Vec2 {
        self.accel_with(p, v, b, Dissipation::drag_accel)
    }

    /// The drive's acceleration plus `dissipation`'s, when there is any.
    #[inline(always)]
    fn accel_with(
        &self,
        p: Vec2,
        v: Vec2,
        b: &BodyParams,
        dissipation: fn(&Dissipation, Vec2, &BodyParams) -> Vec2,
    ) -> Vec2 {
        let a = self.drive.accel(p, v, b);
        if self.dissipation.is_active() {
            a + dissipation(&self.dissipation, v, b)
        } else {
            a
        }
    }

    /// `v + a dt` for the Euler methods, with dissipation stable or plain.
    #[inline(always)]
    fn euler_velocity(&self, p: Vec2, v: Vec2, b: &BodyParams, dt: f32) -> Vec2 {
        if self.stable {
            let v1 = v + self.drive.accel(p, v, b) * dt;
            if self.dissipation.is_active() {
                self.dissipation.apply_stable(v1, b, dt)
            } else {
                v1
            }
        } else {
            v + self.accel(p, v, b) * dt
        }
    }
}

/// One body's step: the new velocity and the position correction `c` such
/// that the new position is `p + v_new dt + c`.
#[inline(always)]
pub(crate) fn integrate_body(
    integrator: Integrator,
    forces: &Forces<'_>,
    p: Vec2,
    v: Vec2,
    b: &BodyParams,
    dt: f32,
) -> (Vec2, Vec2) {
    match integrator {
        Integrator::SemiImplicitEuler => (forces.euler_velocity(p, v, b, dt), Vec2::ZERO),
        Integrator::ExplicitEuler => {
            // p1 = p + v0 dt = p + v1 dt + (v0 - v1) dt
            let v1 = forces.euler_velocity(p, v, b, dt);
            (v1, (v - v1) * dt)
        }
        Integrator::VelocityVerlet => {
            let (v, left) = forces.dissipation.apply_friction_for(v, b, 0.5 * dt);
            let a0 = forces.smooth_accel(p, v, b);
            let dp = v * dt + a0 * (0.5 * dt * dt);
            let a1 = forces.smooth_accel(p + dp, v + a0 * dt, b);
            let v1 = v + (a0 + a1) * (0.5 * dt);
            held(forces, b, (v, v1), dp, 0.5 * dt + left, dt)
        }
        Integrator::Rk4 => {
            let h = 0.5 * dt;
            let (v, left) = forces.dissipation.apply_friction_for(v, b, h);
            let a1 = forces.smooth_accel(p, v, b);
            let v2 = v + a1 * h;
            let a2 = forces.smooth_accel(p + v * h, v2, b);
            let v3 = v + a2 * h;
            let a3 = forces.smooth_accel(p + v2 * h, v3, b);
            let v4 = v + a3 * dt;
            let a4 = forces.smooth_accel(p + v3 * dt, v4, b);
            let sixth = dt / 6.0;
            let dp = (v + (v2 + v3) * 2.0 + v4) * sixth;
            let v1 = v + (a1 + (a2 + a3) * 2.0 + a4) * sixth;
            held(forces, b, (v, v1), dp, h + left, dt)
        }
    }
}

/// The end of a Verlet or RK4 step of `dt` whose stages (from velocity
/// `v`, after the first half step of friction) reached `v1` and moved the
/// body by `dp`: the second half of friction, over `rest` (half the step,
/// and whatever of the first half the body spent stopped), and the
/// position correction. A body that was stopped and is stopped again was
/// held by friction all along: it does not move (the stages' `dp` came from
/// forces friction held back; a body pushed gently on the ground crept).
#[inline(always)]
fn held(
    forces: &Forces<'_>,
    b: &BodyParams,
    (v, v1): (Vec2, Vec2),
    dp: Vec2,
    rest: f32,
    dt: f32,
) -> (Vec2, Vec2) {
    let v1 = forces.dissipation.apply_friction(v1, b, rest);
    if v == Vec2::ZERO && v1 == Vec2::ZERO {
        return (v1, Vec2::ZERO);
    }
    (v1, dp - v1 * dt)
}

/// One body's new velocity and position correction over `h`. A non-finite
/// result (a broken custom force, an overflow) drops the body's motion for
/// this step and counts a reset.
#[inline(always)]
pub(crate) fn integrate_velocity(
    integrator: Integrator,
    forces: &Forces<'_>,
    p: Vec2,
    v: Vec2,
    params: &BodyParams,
    h: f32,
    resets: &mut u64,
) -> (Vec2, Vec2) {
    let (v, c) = integrate_body(integrator, forces, p, v, params, h);
    guard_finite(v, c, resets)
}

/// Drops a step that produced a non-finite velocity or correction, or a
/// speed whose square overflows `f32` (over 1.8e19 m/s): the body stays
/// where it was with zero velocity, and the reset is counted. Subnormal
/// velocity components are flushed to zero.
#[inline(always)]
fn guard_finite(v: Vec2, c: Vec2, resets: &mut u64) -> (Vec2, Vec2) {
    if v.length_squared().is_finite() && c.is_finite() {
        (flush_subnormal(v), c)
    } else {
        *resets += 1;
        (Vec2::ZERO, Vec2::ZERO)
    }
}
