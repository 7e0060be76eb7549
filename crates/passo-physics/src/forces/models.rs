//! Force models: what pushes bodies, each opt-in per world.
//!
//! Every model is a formula of the body's state. The world evaluates only
//! the models that are switched on (see [`World::active_stages`](crate::World::active_stages)).
//!
//! | model | force on a body of mass `m` |
//! |---|---|
//! | gravity | `m g` |
//! | quadratic drag | `-1/2 rho |v_rel|^2 (Cd A) v_rel_hat`, `v_rel = v - air_velocity` |
//! | linear drag | `-b v_rel` |
//! | surface friction | `-mu |N| v_hat`, `|N| = m g_surface` (top-down games) |
//! | force field | a constant force `F` on every dynamic body |
//! | spring | `-k (p - anchor)` |
//! | central gravity | `-G M m r_hat / r^2`, `r = p - centre` |
//! | custom | any [`ForceModel`] |
//!
//! Drag and friction dissipate energy and are stiff: their plain explicit
//! forms overshoot (reverse the velocity, or blow up) when `dt` is large.
//! With [`ForceForm::Stable`] (the default) the Euler integrators apply them
//! as exact velocity factors instead, derived next to [`Dissipation::apply_stable`].

use crate::PhysicsError;
use crate::body::store::BodyParams;
use crate::constants::{AIR_DENSITY, DEFAULT_GRAVITY, DEFAULT_SURFACE_GRAVITY};
use crate::error::{finite, finite_vec, non_negative};
use glam::Vec2;
use std::sync::Arc;

/// The force models of a world. Every model is off (`None`) by default except
/// gravity; switch on only what the scene needs.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct ForceModels {
    /// Gravitational acceleration, metres per second²; weight is `m g`.
    /// Default `Some((0, -9.81))`.
    pub gravity: Option<Vec2>,
    /// Quadratic (aerodynamic) drag. Default `None`.
    pub quadratic_drag: Option<QuadraticDrag>,
    /// Linear (viscous) drag. Default `None`.
    pub linear_drag: Option<LinearDrag>,
    /// Velocity of the air (wind), metres per second. Both drag models act
    /// on the velocity relative to it, so wind pushes a body through drag.
    /// Default `(0, 0)`.
    pub air_velocity: Vec2,
    /// Kinetic friction against the ground plane of a top-down game.
    /// Default `None`.
    pub surface_friction: Option<SurfaceFriction>,
    /// A constant force on every dynamic body, newtons (a push of wind on a
    /// glider, a conveyor). Default `None`.
    pub force_field: Option<Vec2>,
    /// A spring pulling every dynamic body to an anchor. Default `None`.
    pub spring: Option<Spring>,
    /// Newtonian attraction to a fixed centre (orbits). Default `None`.
    pub central_gravity: Option<CentralGravity>,
}

impl Default for ForceModels {
    fn default() -> Self {
        Self {
            gravity: Some(DEFAULT_GRAVITY),
            quadratic_drag: None,
            linear_drag: None,
            air_velocity: Vec2::ZERO,
            surface_friction: None,
            force_field: None,
            spring: None,
            central_gravity: None,
        }
    }
}

impl ForceModels {
    /// No force model at all (bodies coast).
    pub fn none() -> Self {
        Self {
            gravity: None,
            ..Self::default()
        }
    }

    /// Checks every parameter, naming the first one that is wrong.
    pub fn validate(&self) -> Result<(), PhysicsError> {
        if let Some(g) = self.gravity {
            finite_vec("ForceModels::gravity", g)?;
        }
        if let Some(d) = &self.quadratic_drag {
            non_negative("QuadraticDrag::density", d.density)?;
        }
        if let Some(d) = &self.linear_drag {
            non_negative("LinearDrag::coefficient", d.coefficient)?;
        }
        finite_vec("ForceModels::air_velocity", self.air_velocity)?;
        if let Some(f) = &self.surface_friction {
            non_negative("SurfaceFriction::gravity", f.gravity)?;
        }
        if let Some(f) = self.force_field {
            finite_vec("ForceModels::force_field", f)?;
        }
        if let Some(s) = &self.spring {
            finite_vec("Spring::anchor", s.anchor)?;
            non_negative("Spring::stiffness", s.stiffness)?;
        }
        if let Some(c) = &self.central_gravity {
            finite_vec("CentralGravity::centre", c.centre)?;
            finite("CentralGravity::gm", c.gm)?;
        }
        Ok(())
    }
}

/// Quadratic drag `-1/2 rho |v_rel|^2 (Cd A) v_rel_hat`; `Cd A` is per body
/// ([`BodyDef::drag_area`](crate::BodyDef::drag_area)).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct QuadraticDrag {
    /// Fluid density `rho`, kilograms per cubic metre, >= 0. Default 1.225 (air).
    pub density: f32,
}

impl Default for QuadraticDrag {
    fn default() -> Self {
        Self {
            density: AIR_DENSITY,
        }
    }
}

/// Linear (viscous) drag `-b v_rel`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct LinearDrag {
    /// `b`, kilograms per second (newtons per metre per second), >= 0. Default 0.
    pub coefficient: f32,
}

/// Top-down kinetic friction `-mu |N| v_hat` with `|N| = m g_surface`; `mu`
/// is per body ([`BodyDef::friction`](crate::BodyDef::friction)).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct SurfaceFriction {
    /// `g_surface`, metres per second², >= 0. Default 9.81.
    pub gravity: f32,
}

impl Default for SurfaceFriction {
    fn default() -> Self {
        Self {
            gravity: DEFAULT_SURFACE_GRAVITY,
        }
    }
}

/// A linear spring from every dynamic body to `anchor`: `F = -k (p - anchor)`,
/// potential energy `1/2 k |p - anchor|^2`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct Spring {
    /// Rest point, metres. Default `(0, 0)`.
    pub anchor: Vec2,
    /// Stiffness `k`, newtons per metre, >= 0. Default 0.
    pub stiffness: f32,
}

/// Newtonian attraction to a fixed centre: acceleration `-GM r_hat / r^2`,
/// potential energy `-GM m / r`. At `r = 0` the force is zero (no NaN).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct CentralGravity {
    /// Centre of attraction, metres. Default `(0, 0)`.
    pub centre: Vec2,
    /// Gravitational parameter `G M`, cubic metres per second². Default 0.
    pub gm: f32,
}

/// A force of the game's own, evaluated like the built-in models (at every
/// stage of a multi-stage integrator).
///
/// ```
/// use passo_physics::{ForceModel, glam::Vec2};
///
/// /// Buoyancy below the water line y = 0.
/// struct Buoyancy;
/// impl ForceModel for Buoyancy {
///     fn force(&self, position: Vec2, _velocity: Vec2, mass: f32) -> Vec2 {
///         if position.y < 0.0 { Vec2::new(0.0, 12.0 * mass) } else { Vec2::ZERO }
///     }
/// }
/// ```
pub trait ForceModel: Send + Sync {
    /// The force, newtons, on a body of `mass` kilograms at `position`
    /// moving at `velocity`. Called for dynamic bodies only, so `mass` is
    /// finite and > 0 (a kinematic body goes where game code steers it,
    /// whatever the forces). A non-finite result is dropped by the step (see
    /// [`StepStats::non_finite_resets`](crate::StepStats::non_finite_resets)).
    fn force(&self, position: Vec2, velocity: Vec2, mass: f32) -> Vec2;

    /// Potential energy, joules, if the force is conservative (default 0).
    fn potential_energy(&self, _position: Vec2, _mass: f32) -> f64 {
        0.0
    }
}

/// How the Euler integrators apply drag and friction.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ForceForm {
    /// Exact velocity factors, unconditionally stable: friction never
    /// reverses a velocity, drag never overshoots. The default.
    #[default]
    Stable,
    /// The plain explicit forces, `a dt` added to the velocity. Kept so the
    /// accuracy report can compare. Unstable once the step is long for the
    /// damping: quadratic drag when `k |v| dt / m > 2` (`k = rho Cd A / 2`),
    /// linear drag when `b dt / m > 2`; and plain friction reverses any
    /// velocity slower than its deceleration times `dt` (`mu g dt`).
    Explicit,
}

/// The conservative and game-applied part of the acceleration: everything
/// but drag and friction. Constants are hoisted out of the body loop.
#[derive(Clone, Copy)]
pub(crate) struct Drive<'a> {
    gravity: Vec2,
    field: Vec2,
    spring: Option<Spring>,
    central: Option<CentralGravity>,
    custom: &'a [Arc<dyn ForceModel>],
}

impl<'a> Drive<'a> {
    pub(crate) fn new(models: &ForceModels, custom: &'a [Arc<dyn ForceModel>]) -> Self {
        Self {
            gravity: models.gravity.unwrap_or(Vec2::ZERO),
            field: models.force_field.unwrap_or(Vec2::ZERO),
            spring: models.spring,
            central: models.central_gravity,
            custom,
        }
    }

    /// Acceleration, metres per second², from gravity, the force field, the
    /// game's forces, springs, central gravity and custom models.
    #[inline(always)]
    pub(crate) fn accel(&self, p: Vec2, v: Vec2, b: &BodyParams) -> Vec2 {
        let mut a = self.gravity + (b.force + self.field) * b.inv_mass;
        if let Some(s) = &self.spring {
            a -= (p - s.anchor) * (s.stiffness * b.inv_mass);
        }
        if let Some(c) = &self.central {
            a += central_accel(c, p);
        }
        // A kinematic body (inverse mass zero) keeps its own velocity
        // whatever the forces: its infinite mass would make a model's force
        // `inf * 0 = NaN` and count a false reset every step.
        if !self.custom.is_empty() && b.inv_mass > 0.0 {
            let mass = 1.0 / b.inv_mass;
            for model in self.custom {
                a += model.force(p, v, mass) * b.inv_mass;
            }
        }
        a
    }
}

/// `-GM r_hat / r^2`, zero at the centre.
#[inline]
fn central_accel(c: &CentralGravity, p: Vec2) -> Vec2 {
    let r = p - c.centre;
    let r2 = r.length_squared();
    if r2 > 0.0 {
        r * (-c.gm / (r2 * r2.sqrt()))
    } else {
        Vec2::ZERO
    }
}

/// Drag and friction: the dissipative part of the acceleration.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Dissipation {
    /// `1/2 rho`, or `None` without quadratic drag.
    half_rho: Option<f32>,
    /// `b`, or `None` without linear drag.
    linear: Option<f32>,
    air: Vec2,
    /// `g_surface`, or `None` without surface friction.
    surface_g: Option<f32>,
    /// Whether game code may have applied friction this step.
    game_friction: bool,
}

impl Dissipation {
    pub(crate) fn new(models: &ForceModels, game_friction: bool) -> Self {
        Self {
            half_rho: models.quadratic_drag.map(|d| 0.5 * d.density),
            linear: models.linear_drag.map(|d| d.coefficient),
            air: models.air_velocity,
            surface_g: models.surface_friction.map(|f| f.gravity),
            game_friction,
        }
    }

    /// Whether any drag or friction acts at all.
    pub(crate) fn is_active(&self) -> bool {
        self.half_rho.is_some()
            || self.linear.is_some()
            || self.surface_g.is_some()
            || self.game_friction
    }

    /// Friction deceleration, metres per second²: `(mu m g_s + F_game) / m`.
    #[inline(always)]
    fn friction_decel(&self, b: &BodyParams) -> f32 {
        let surface = self.surface_g.map_or(0.0, |g| b.friction * g);
        surface + b.friction_force * b.inv_mass
    }

    /// The plain explicit acceleration of drag and friction at velocity `v`.
    #[inline(always)]
    pub(crate) fn accel(&self, v: Vec2, b: &BodyParams) -> Vec2 {
        let mut a = self.drag_accel(v, b);
        let decel = self.friction_decel(b);
        if decel > 0.0 {
            a -= v.normalize_or_zero() * decel;
        }
        a
    }

    /// The plain explicit acceleration of drag alone (no friction) at
    /// velocity `v`.
    #[inline(always)]
    pub(crate) fn drag_accel(&self, v: Vec2, b: &BodyParams) -> Vec2 {
        let mut a = Vec2::ZERO;
        let rel = v - self.air;
        if let Some(half_rho) = self.half_rho {
            a -= rel * (half_rho * b.drag_area * rel.length() * b.inv_mass);
        }
        if let Some(damping) = self.linear {
            a -= rel * (damping * b.inv_mass);
        }
        a
    }

    /// Friction alone over `dt` in its exact form (see
    /// [`apply_stable`](Self::apply_stable)): the speed falls by the
    /// friction deceleration times `dt`, to zero and never past it.
    /// Unchanged bits without friction.
    #[inline(always)]
    pub(crate) fn apply_friction(&self, v: Vec2, b: &BodyParams, dt: f32) -> Vec2 {
        self.apply_friction_for(v, b, dt).0
    }

    /// [`apply_friction`](Self::apply_friction), and how much of `dt` was
    /// left when the body stopped (zero if it did not, or has no friction).
    #[inline(always)]
    pub(crate) fn apply_friction_for(&self, mut v: Vec2, b: &BodyParams, dt: f32) -> (Vec2, f32) {
        let decel = self.friction_decel(b);
        let mut left = 0.0;
        if decel > 0.0 {
            let speed = v.length();
            if speed > 0.0 {
                v *= (speed - decel * dt).max(0.0) / speed;
            }
            left = (dt - speed / decel).max(0.0);
        }
        (v, left)
    }

    /// Applies drag and friction over `dt` as exact velocity factors, one
    /// model after the other (operator splitting, first order overall, like
    /// the Euler step it follows).
    ///
    /// - Quadratic drag alone, `dv/dt = -c |v| v` with `c = rho Cd A / (2 m)`,
    ///   keeps the direction of `v` and its speed obeys `s' = -c s^2`, whose
    ///   solution is `s(t) = s0 / (1 + c s0 t)`. So
    ///   `v <- v / (1 + c |v| dt)`: exact for drag alone, never reverses,
    ///   stable for any `dt` (the Pade form Box2D uses for damping).
    /// - Linear drag alone, `dv/dt = -(b/m) v`: `v <- v exp(-b dt / m)`, exact.
    /// - Kinetic friction alone decelerates at the constant rate
    ///   `d = mu g_s + F_game / m` along `-v_hat`: `s <- max(s - d dt, 0)`,
    ///   exact, and it stops the body instead of reversing it.
    ///
    /// Drag acts on the velocity relative to the air, friction on the
    /// velocity relative to the ground.
    #[inline(always)]
    pub(crate) fn apply_stable(&self, mut v: Vec2, b: &BodyParams, dt: f32) -> Vec2 {
        if let Some(half_rho) = self.half_rho {
            v = stable_quadratic_drag(v, self.air, half_rho * b.drag_area * b.inv_mass, dt);
        }
        if let Some(damping) = self.linear {
            v = self.air + (v - self.air) * libm::expf(-damping * b.inv_mass * dt);
        }
        self.apply_friction(v, b, dt)
    }
}

/// Quadratic drag over `dt` in its exact form, `v <- air + rel / (1 + c
/// |rel| dt)` with `rel = v - air` and `c = rho Cd A / (2 m)` (see
/// [`Dissipation::apply_stable`]). Every path that applies stable drag
/// calls this, so they give the same bits.
#[inline(always)]
pub(crate) fn stable_quadratic_drag(v: Vec2, air: Vec2, c: f32, dt: f32) -> Vec2 {
    let rel = v - air;
    air + rel / (1.0 + c * rel.length() * dt)
}

/// Potential energy, joules, of a body of `mass` at `p` under the
/// conservative models (gravity and the force field relative to the origin,
/// the spring, central gravity, custom models).
pub(crate) fn potential_energy(
    models: &ForceModels,
    custom: &[Arc<dyn ForceModel>],
    p: Vec2,
    mass: f32,
) -> f64 {
    let m = f64::from(mass);
    let mut e = 0.0;
    let px = f64::from(p.x);
    let py = f64::from(p.y);
    if let Some(g) = models.gravity {
        e -= m * (f64::from(g.x) * px + f64::from(g.y) * py);
    }
    if let Some(f) = models.force_field {
        e -= f64::from(f.x) * px + f64::from(f.y) * py;
    }
    if let Some(s) = &models.spring {
        e += 0.5 * f64::from(s.stiffness) * f64::from((p - s.anchor).length_squared());
    }
    if let Some(c) = &models.central_gravity {
        let r = f64::from((p - c.centre).length());
        if r > 0.0 {
            e -= f64::from(c.gm) * m / r;
        }
    }
    for model in custom {
        e += model.potential_energy(p, mass);
    }
    e
}
