//! The report's cases (each with a closed-form solution) and methods.

use passo_physics::glam::Vec2;
use passo_physics::{
    BodyDef, BodyId, CentralGravity, ContactSettings, ForceForm, ForceModels, Integrator, JointDef,
    JointSpring, LinearDrag, QuadraticDrag, Spring, SurfaceFriction, World, WorldSettings,
};

/// A problem with a closed-form solution.
#[derive(Clone, Copy, Debug)]
pub struct Case {
    /// Short name, used in the CSV.
    pub name: &'static str,
    /// What it is, for the Markdown report.
    pub title: &'static str,
    /// Simulated time at which the error is measured, seconds.
    pub end_time: f64,
    /// The force models.
    pub forces: ForceModels,
    /// The body (mass, drag area, friction, start state).
    pub body: BodyDef,
    /// The exact position at a time, metres (f64 throughout).
    pub exact: fn(f64) -> [f64; 2],
    /// Whether energy is conserved (the drift column is filled).
    pub conservative: bool,
    /// Whether drag or friction act (plain forms differ from stable ones).
    pub dissipative: bool,
    /// Whether the solution is smooth, so integrators show their orders.
    pub smooth: bool,
    /// What to know when reading the case's numbers.
    pub note: &'static str,
    /// A joint holding the body, made for a body and the offset of its
    /// copy (see [`world`]); `None` for a free body.
    pub joint: Option<fn(BodyId, Vec2) -> JointDef>,
}

impl Case {
    /// Size of the solution at the end time (at least 1 m), for relative errors.
    pub fn scale(&self) -> f64 {
        let [x, y] = (self.exact)(self.end_time);
        x.hypot(y).max(1.0)
    }
}

/// Standard gravity, m/s².
const G: f64 = 9.81;
/// Air density, kg/m³.
const RHO: f64 = 1.225;
/// Projectile launch velocity, m/s.
const LAUNCH: [f64; 2] = [10.0, 10.0];
/// Linear drag rate b/m, 1/s, and start speed, m/s.
const LINEAR_RATE: f64 = 8.0;
const LINEAR_V0: f64 = 10.0;
/// Falling body: mass, kg, and drag area, m².
const FALL_MASS: f64 = 2.0;
const FALL_CDA: f64 = 0.5;
/// Coasting body: mass, kg, drag area, m², start speed, m/s.
const COAST_MASS: f64 = 1.0;
const COAST_CDA: f64 = 0.5;
const COAST_V0: f64 = 20.0;
/// Friction slide: mu and start speed, m/s.
const SLIDE_MU: f64 = 0.5;
const SLIDE_V0: f64 = 10.0;
/// Spring: angular frequency, rad/s (unit mass).
const SPRING_W: f64 = 12.0;

fn v2(x: f64, y: f64) -> Vec2 {
    Vec2::new(x as f32, y as f32)
}

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    let none = ForceModels::none();
    let body = |position: Vec2, velocity: Vec2| BodyDef {
        position,
        velocity,
        ..Default::default()
    };
    let gravity = Some(v2(0.0, -G));
    vec![
        Case {
            name: "projectile",
            title: "projectile under gravity, v0 = (10, 10) m/s, 2 s",
            end_time: 2.0,
            forces: ForceModels { gravity, ..none },
            body: body(Vec2::ZERO, v2(LAUNCH[0], LAUNCH[1])),
            // p = v0 t + 1/2 g t^2
            exact: |t| [LAUNCH[0] * t, LAUNCH[1] * t - 0.5 * G * t * t],
            conservative: true,
            dissipative: false,
            smooth: true,
            note: "Constant acceleration: both Euler methods miss the parabola by exactly 1/2 g dt t \
                   (first order); Verlet and RK4 are exact, so their errors are f32 rounding alone.",
            joint: None,
        },
        Case {
            name: "linear_drag",
            title: "linear drag coast, b/m = 8 /s, v0 = 10 m/s, 0.5 s",
            end_time: 0.5,
            forces: ForceModels {
                linear_drag: Some(LinearDrag {
                    coefficient: LINEAR_RATE as f32,
                }),
                ..none
            },
            body: body(Vec2::ZERO, v2(LINEAR_V0, 0.0)),
            // x = v0 m / b (1 - exp(-b t / m)), m = 1
            exact: |t| {
                [
                    LINEAR_V0 / LINEAR_RATE * (1.0 - (-LINEAR_RATE * t).exp()),
                    0.0,
                ]
            },
            conservative: false,
            dissipative: true,
            smooth: true,
            note: "The stable forms are exact for drag alone, but the Euler step that moves the \
                   body is first order; the plain explicit forms go unstable once b dt / m > 2.",
            joint: None,
        },
        Case {
            name: "quadratic_drag_fall",
            title: "fall from rest through air, m = 2 kg, Cd A = 0.5 m² (v_t = 8.0 m/s), 3 s",
            end_time: 3.0,
            forces: ForceModels {
                gravity,
                quadratic_drag: Some(QuadraticDrag {
                    density: RHO as f32,
                }),
                ..none
            },
            body: BodyDef {
                mass: FALL_MASS as f32,
                drag_area: FALL_CDA as f32,
                ..body(Vec2::ZERO, Vec2::ZERO)
            },
            // y = -(v_t^2 / g) ln cosh(g t / v_t), v_t = sqrt(2 m g / (rho Cd A))
            exact: |t| {
                let vt = (2.0 * FALL_MASS * G / (RHO * FALL_CDA)).sqrt();
                [0.0, -(vt * vt / G) * (G * t / vt).cosh().ln()]
            },
            conservative: false,
            dissipative: true,
            smooth: true,
            note: "Gravity and drag together: the stable split is first order; Verlet and RK4 \
                   evaluate drag at every stage and reach the rounding floor quickly.",
            joint: None,
        },
        Case {
            name: "drag_coast",
            title: "coast under quadratic drag, k/m = 0.306 /m, v0 = 20 m/s, 3 s",
            end_time: 3.0,
            forces: ForceModels {
                quadratic_drag: Some(QuadraticDrag {
                    density: RHO as f32,
                }),
                ..none
            },
            body: BodyDef {
                mass: COAST_MASS as f32,
                drag_area: COAST_CDA as f32,
                ..body(Vec2::ZERO, v2(COAST_V0, 0.0))
            },
            // x = (m / k) ln(1 + k v0 t / m), k = rho Cd A / 2
            exact: |t| {
                let k = 0.5 * RHO * COAST_CDA;
                [
                    (COAST_MASS / k) * (1.0 + k * COAST_V0 * t / COAST_MASS).ln(),
                    0.0,
                ]
            },
            conservative: false,
            dissipative: true,
            smooth: true,
            note: "Drag alone: the stable velocity update is exact, so the stable Euler error is \
                   the first-order position update only.",
            joint: None,
        },
        Case {
            name: "friction_slide",
            title: "top-down friction slide, mu = 0.5, v0 = 10 m/s, to rest (3 s)",
            end_time: 3.0,
            forces: ForceModels {
                surface_friction: Some(SurfaceFriction { gravity: G as f32 }),
                ..none
            },
            body: BodyDef {
                friction: SLIDE_MU as f32,
                ..body(Vec2::ZERO, v2(SLIDE_V0, 0.0))
            },
            // Stops after v0^2 / (2 mu g).
            exact: |_| [SLIDE_V0 * SLIDE_V0 / (2.0 * SLIDE_MU * G), 0.0],
            conservative: false,
            dissipative: true,
            smooth: false,
            note: "Not smooth (the body stops): no method shows its order; the stable forms stop \
                   the body within one step of the closed-form distance and never reverse it. \
                   Verlet and RK4 apply friction exactly for half a step before their stages and \
                   half after, so the slide itself is exact and only rounding and the last step \
                   remain.",
            joint: None,
        },
        Case {
            name: "spring",
            title: "undamped spring, w = 12 rad/s, x0 = 1 m, w t = 100 rad (8.3 s)",
            // About 16 periods: long enough that even RK4's error stays above
            // f32 rounding at the coarser steps.
            end_time: 100.0 / SPRING_W,
            forces: ForceModels {
                spring: Some(Spring {
                    anchor: Vec2::ZERO,
                    stiffness: (SPRING_W * SPRING_W) as f32,
                }),
                ..none
            },
            body: body(v2(1.0, 0.0), Vec2::ZERO),
            // x = cos(w t)
            exact: |t| [(SPRING_W * t).cos(), 0.0],
            conservative: true,
            dissipative: false,
            smooth: true,
            note: "Explicit Euler multiplies the energy by 1 + w² dt² per step and blows up at the \
                   coarse steps; the others' error is mostly phase error. RK4 reaches the f32 \
                   rounding floor from dt = 1/240.",
            joint: None,
        },
        Case {
            name: "kepler",
            title: "Kepler orbit, GM = 1, e = 0.6, one period (2 pi s)",
            end_time: 2.0 * std::f64::consts::PI,
            forces: ForceModels {
                central_gravity: Some(CentralGravity {
                    centre: Vec2::ZERO,
                    gm: 1.0,
                }),
                ..none
            },
            // q0 = (0.4, 0), p0 = (0, 2): energy -1/2, e = 0.6, period 2 pi.
            body: body(v2(0.4, 0.0), v2(0.0, 2.0)),
            exact: kepler,
            conservative: true,
            dissipative: false,
            smooth: true,
            note: "The error is measured at the simulated time (a whole number of steps) against \
                   Kepler's equation solved in f64. Over one whole period the symmetric orbit \
                   cancels the first-order error of semi-implicit Euler, which converges at \
                   second order here.",
            joint: None,
        },
        pendulum_case(
            "pendulum_small",
            "pendulum on a 1 m rod, released at 10 degrees, 5 s",
            PENDULUM_SMALL,
            |t| pendulum(PENDULUM_SMALL, t),
        ),
        pendulum_case(
            "pendulum_large",
            "pendulum on a 1 m rod, released at 150 degrees, 5 s",
            PENDULUM_LARGE,
            |t| pendulum(PENDULUM_LARGE, t),
        ),
        Case {
            name: "spring_joint",
            title: "body on a spring joint, 2 Hz, damping ratio 0.1, released 0.5 m out, 3 s",
            end_time: 3.0,
            forces: none,
            body: body(v2(SPRING_REST + 0.5, 0.0), Vec2::ZERO),
            exact: |t| [SPRING_REST + damped(t), 0.0],
            conservative: false,
            dissipative: false,
            smooth: true,
            note: "The joint's spring is solved in the contact step's substeps (four a step) \
                   whatever the integrator, so the methods differ little: explicit (no \
                   numerical damping) while the spring is soft for the substep.",
            joint: Some(|id, offset| {
                let spring = JointSpring::new(SPRING_HERTZ as f32, SPRING_ZETA as f32);
                JointDef::spring(id, None, SPRING_REST as f32, spring).anchors(Vec2::ZERO, offset)
            }),
        },
    ]
}

/// Pendulum release angles, radians.
const PENDULUM_SMALL: f64 = 10.0 * std::f64::consts::PI / 180.0;
const PENDULUM_LARGE: f64 = 150.0 * std::f64::consts::PI / 180.0;

/// A point mass on a rigid rod of 1 m from the origin, released at rest
/// `amplitude` radians from straight down.
fn pendulum_case(
    name: &'static str,
    title: &'static str,
    amplitude: f64,
    exact: fn(f64) -> [f64; 2],
) -> Case {
    Case {
        name,
        title,
        end_time: 5.0,
        forces: ForceModels {
            gravity: Some(v2(0.0, -G)),
            ..ForceModels::none()
        },
        body: BodyDef {
            position: v2(amplitude.sin(), -amplitude.cos()),
            ..Default::default()
        },
        exact,
        conservative: true,
        dissipative: false,
        smooth: true,
        note: "Against the exact motion, theta = 2 asin(k sn(K - w t | k^2)) with k = \
               sin(theta0 / 2) (the period is 4 K sqrt(L / g), K the complete elliptic \
               integral). The rod is solved in the contact step's substeps whatever the \
               integrator, so the methods differ only in how gravity enters each substep.",
        joint: Some(|id, offset| JointDef::distance(id, None, 1.0).anchors(Vec2::ZERO, offset)),
    }
}

/// The pendulum's position at `t`: the angle from Jacobi's sn (see
/// `pendulum_case`).
fn pendulum(amplitude: f64, t: f64) -> [f64; 2] {
    let k = (amplitude / 2.0).sin();
    let m = k * k;
    let w = G.sqrt();
    let theta = 2.0 * (k * jacobi_sn(complete_k(m) - w * t, m)).asin();
    [theta.sin(), -theta.cos()]
}

/// The complete elliptic integral of the first kind K(m), by the
/// arithmetic-geometric mean.
fn complete_k(m: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - m).sqrt());
    for _ in 0..40 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

/// Jacobi's sn(u | m), by the descending Landen transformation.
fn jacobi_sn(u: f64, m: f64) -> f64 {
    let (mut a, mut c) = ([0.0f64; 24], [0.0f64; 24]);
    a[0] = 1.0;
    c[0] = m.sqrt();
    let mut b = (1.0 - m).sqrt();
    let mut n = 0;
    while n < 23 && c[n].abs() > 1e-16 {
        a[n + 1] = 0.5 * (a[n] + b);
        c[n + 1] = 0.5 * (a[n] - b);
        b = (a[n] * b).sqrt();
        n += 1;
    }
    let mut phi = 2f64.powi(n as i32) * a[n] * u;
    for k in (1..=n).rev() {
        phi = 0.5 * (phi + (c[k] / a[k] * phi.sin()).asin());
    }
    phi.sin()
}

/// Spring joint: rest length, m, frequency, Hz, and damping ratio (unit
/// mass).
const SPRING_REST: f64 = 1.0;
const SPRING_HERTZ: f64 = 2.0;
const SPRING_ZETA: f64 = 0.1;

/// The spring joint's stretch at `t`, released at rest 0.5 m out:
/// underdamped, x = x0 e^(-z w t) (cos(wd t) + z w / wd sin(wd t)).
fn damped(t: f64) -> f64 {
    let w = std::f64::consts::TAU * SPRING_HERTZ;
    let wd = w * (1.0 - SPRING_ZETA * SPRING_ZETA).sqrt();
    let decay = (-SPRING_ZETA * w * t).exp();
    0.5 * decay * ((wd * t).cos() + SPRING_ZETA * w / wd * (wd * t).sin())
}

/// The Kepler orbit with GM = 1, a = 1, e = 0.6 from perihelion (0.4, 0)
/// at t = 0: solve Kepler's equation `E - e sin E = t` (mean motion 1) by
/// Newton's method, then `x = cos E - e`, `y = sqrt(1 - e^2) sin E`.
fn kepler(t: f64) -> [f64; 2] {
    let e = 0.6f64;
    let m = t.rem_euclid(2.0 * std::f64::consts::PI);
    let mut big_e = if e > 0.8 { std::f64::consts::PI } else { m };
    for _ in 0..50 {
        let step = (big_e - e * big_e.sin() - m) / (1.0 - e * big_e.cos());
        big_e -= step;
        if step.abs() < 1e-15 {
            break;
        }
    }
    [big_e.cos() - e, (1.0 - e * e).sqrt() * big_e.sin()]
}

/// An integrator with a form of drag and friction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Method {
    /// Name in the CSV.
    pub name: &'static str,
    /// The integrator.
    pub integrator: Integrator,
    /// Stable or plain drag and friction.
    pub form: ForceForm,
}

/// Every method; the `_plain` ones only matter where drag or friction act.
pub const METHODS: [Method; 6] = [
    Method {
        name: "explicit_euler",
        integrator: Integrator::ExplicitEuler,
        form: ForceForm::Stable,
    },
    Method {
        name: "explicit_euler_plain",
        integrator: Integrator::ExplicitEuler,
        form: ForceForm::Explicit,
    },
    Method {
        name: "semi_implicit_euler",
        integrator: Integrator::SemiImplicitEuler,
        form: ForceForm::Stable,
    },
    Method {
        name: "semi_implicit_euler_plain",
        integrator: Integrator::SemiImplicitEuler,
        form: ForceForm::Explicit,
    },
    Method {
        name: "velocity_verlet",
        integrator: Integrator::VelocityVerlet,
        form: ForceForm::Stable,
    },
    Method {
        name: "rk4",
        integrator: Integrator::Rk4,
        form: ForceForm::Stable,
    },
];

/// The methods that differ on a case.
pub fn methods_for(case: &Case) -> Vec<Method> {
    METHODS
        .iter()
        .copied()
        .filter(|m| case.dissipative || m.form == ForceForm::Stable)
        .collect()
}

/// The theoretical order of a method on a smooth case (the stable Euler
/// forms are first order, like the Euler step they follow).
pub fn theoretical_order(method: &Method) -> f64 {
    match method.integrator {
        Integrator::ExplicitEuler | Integrator::SemiImplicitEuler => 1.0,
        Integrator::VelocityVerlet => 2.0,
        Integrator::Rk4 => 4.0,
    }
}

/// A world for the case with `count` copies of its body (spread a
/// millimetre apart, so they are distinct but follow the same physics).
pub fn world(case: &Case, method: &Method, count: usize, min_speed: f32) -> World {
    let mut world = World::new(WorldSettings {
        forces: case.forces,
        integrator: method.integrator,
        force_form: method.form,
        min_speed,
        max_speed: f32::INFINITY,
        interpolation: false,
        // Joints are solved in the contact step.
        contacts: case.joint.map(|_| ContactSettings::default()),
    })
    .expect("report settings are valid");
    for i in 0..count {
        let mut def = case.body;
        let offset = Vec2::new(0.0, i as f32 * 1e-3);
        def.position += offset;
        let id = world.add_body(def).expect("report bodies are valid");
        if let Some(joint) = case.joint {
            world
                .add_joint(joint(id, offset))
                .expect("report joints are valid");
        }
    }
    world
}
