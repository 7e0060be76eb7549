//! Soft constraints: Box2D v3's `b2Softness`, and the weighting of a
//! joint's own spring (see `solve`).

use crate::joint::JointSpring;

/// A soft constraint's coefficients for a substep `h` (Box2D v3's
/// `b2Softness`, with its bias rate and mass scale multiplied out): the
/// impulse is `-m * (mass_scale * cdot + bias * C) - impulse_scale *
/// accumulated`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Soft {
    pub bias: f32,
    pub mass_scale: f32,
    pub impulse_scale: f32,
}

impl Soft {
    /// Rigid, with no correction of drift.
    pub(crate) const RIGID: Self = Self {
        bias: 0.0,
        mass_scale: 1.0,
        impulse_scale: 0.0,
    };

    /// Closes a gap `C` in one substep, no more: a limit not yet reached.
    pub(crate) fn speculative(h: f32) -> Self {
        Self {
            bias: 1.0 / h,
            ..Self::RIGID
        }
    }

    /// The impulse for relative speed `cdot`, error `c`, effective mass
    /// `m` and accumulated impulse `accumulated`.
    #[inline(always)]
    pub(crate) fn impulse<T>(self, m: f32, cdot: T, c: T, accumulated: T) -> T
    where
        T: std::ops::Mul<f32, Output = T> + std::ops::Add<Output = T> + std::ops::Sub<Output = T>,
    {
        (cdot * (-m * self.mass_scale) + c * (-m * self.bias)) - accumulated * self.impulse_scale
    }

    /// A spring of `hertz` and `damping_ratio` over a substep `h`, as
    /// Box2D v3's `b2MakeSoft`: the spring force taken at the end of the
    /// substep (implicit Euler), stable at any stiffness; rigid when
    /// `hertz` is 0.
    pub(crate) fn new(hertz: f32, damping_ratio: f32, h: f32) -> Self {
        Self::weighted(hertz, damping_ratio, h, 1.0)
    }

    /// A spring whose force is taken a fraction `beta` of the way from
    /// the start of the substep to its end (the damping always at the
    /// end): 1 is [`new`](Self::new). With the positions then moved by
    /// the new velocity, a linear spring's step has determinant
    /// `1 / (1 + beta (h w)^2)`: its amplitude shrinks by that much a
    /// substep with no damping asked for. The step is stable when
    /// `(h w)^2 (1 - 2 beta) <= 4`.
    pub(crate) fn weighted(hertz: f32, damping_ratio: f32, h: f32, beta: f32) -> Self {
        if hertz == 0.0 {
            return Self::RIGID;
        }
        let omega = std::f32::consts::TAU * hertz;
        let hw = h * omega;
        let a2 = hw * (2.0 * damping_ratio + beta * hw);
        let a3 = 1.0 / (1.0 + a2);
        Self {
            bias: hw * omega * a3,
            mass_scale: a2 * a3,
            impulse_scale: a3,
        }
    }

    /// A joint's own spring, solved once a substep (the solve passes):
    /// explicit (`beta` 0, no numerical damping: the amplitude of an
    /// undamped spring neither grows nor shrinks) while the spring is soft
    /// for the substep, moving toward the midpoint (`beta` 1/2, stable at
    /// any stiffness) as it stiffens: `beta = max(0, 1/2 - 1/(h w)^2)`,
    /// which keeps the step stable with a margin of two.
    pub(crate) fn of(spring: JointSpring, h: f32) -> Self {
        let hw = h * std::f32::consts::TAU * spring.hertz;
        let beta = if hw * hw > 2.0 {
            0.5 - 1.0 / (hw * hw)
        } else {
            0.0
        };
        Self::weighted(spring.hertz, spring.damping_ratio, h, beta)
    }
}
