//! Every integrator and force model against its closed-form solution.

use passo_physics::glam::Vec2;
use passo_physics::{
    BodyDef, BodyId, ForceForm, ForceModels, Integrator, LinearDrag, QuadraticDrag, Shape, Spring,
    SurfaceFriction, World, WorldSettings,
};

const G: f32 = 9.81;

/// A world with the given forces and integrator, no speed limits, and one
/// body made from `def`.
fn single(forces: ForceModels, integrator: Integrator, def: BodyDef) -> (World, BodyId) {
    let mut world = World::new(WorldSettings {
        forces,
        integrator,
        min_speed: 0.0,
        max_speed: f32::INFINITY,
        ..Default::default()
    })
    .unwrap();
    let id = world.add_body(def).unwrap();
    (world, id)
}

fn run(world: &mut World, dt: f32, steps: usize) {
    for _ in 0..steps {
        world.step(dt);
    }
}

fn assert_close(what: &str, got: f32, want: f32, tol: f32) {
    assert!(
        (got - want).abs() <= tol,
        "{what}: got {got}, want {want} (tolerance {tol})"
    );
}

#[test]
fn projectile_matches_each_integrators_exact_discrete_solution() {
    let p0 = Vec2::new(1.0, 2.0);
    let v0 = Vec2::new(3.0, 15.0);
    let g = Vec2::new(0.0, -G);
    let dt = 1.0 / 60.0;
    let n = 120;
    let t = dt * n as f32;
    let parabola = p0 + v0 * t + 0.5 * g * t * t;
    // Semi-implicit Euler uses the end-of-step velocity: it leads the
    // parabola by 1/2 g dt t. Explicit Euler uses the start-of-step velocity:
    // it lags by the same amount. Verlet and RK4 are exact for constant
    // acceleration.
    let cases = [
        (Integrator::SemiImplicitEuler, parabola + 0.5 * g * dt * t),
        (Integrator::ExplicitEuler, parabola - 0.5 * g * dt * t),
        (Integrator::VelocityVerlet, parabola),
        (Integrator::Rk4, parabola),
    ];
    for (integrator, want) in cases {
        let def = BodyDef {
            position: p0,
            velocity: v0,
            ..Default::default()
        };
        let (mut world, id) = single(ForceModels::default(), integrator, def);
        run(&mut world, dt, n);
        let body = world.body(id).unwrap();
        let name = integrator.name();
        assert_close(&format!("{name} x"), body.position.x, want.x, 2e-5);
        assert_close(&format!("{name} y"), body.position.y, want.y, 2e-5);
        assert_close(&format!("{name} vy"), body.velocity.y, v0.y + g.y * t, 2e-5);
        assert_eq!(body.velocity.x, v0.x, "{name}: nothing acts along x");
    }
}

#[test]
fn quadratic_drag_fall_from_rest_follows_tanh() {
    // m = 2 kg, Cd A = 0.5 m², air: v_t = sqrt(2 m g / (rho Cd A)).
    let (m, cda, rho) = (2.0f32, 0.5f32, 1.225f32);
    let vt = (2.0 * m * G / (rho * cda)).sqrt();
    let forces = ForceModels {
        quadratic_drag: Some(QuadraticDrag { density: rho }),
        ..Default::default()
    };
    let t = 3.0f32;
    let want_v = -vt * (G * t / vt).tanh();
    let want_y = -(vt * vt / G) * (G * t / vt).cosh().ln();
    let mut last_error = f32::INFINITY;
    for steps_per_second in [60usize, 240, 960] {
        let dt = 1.0 / steps_per_second as f32;
        let def = BodyDef {
            mass: m,
            drag_area: cda,
            ..Default::default()
        };
        let (mut world, id) = single(forces, Integrator::SemiImplicitEuler, def);
        run(&mut world, dt, 3 * steps_per_second);
        let body = world.body(id).unwrap();
        // First order: the velocity error is bounded by a few g dt.
        let error = (body.velocity.y - want_v).abs();
        assert!(
            error < 0.6 * G * dt,
            "dt {dt}: v {} vs {want_v}",
            body.velocity.y
        );
        assert!(
            (body.position.y - want_y).abs() < 2.0 * G * dt,
            "dt {dt}: y {} vs {want_y}",
            body.position.y
        );
        // Error shrinks with dt (about linearly).
        assert!(
            error < last_error / 3.0,
            "dt {dt}: error {error} after {last_error}"
        );
        last_error = error;
    }
}

#[test]
fn drag_only_coast_is_exact_with_the_stable_form_at_any_dt() {
    // Quadratic drag alone: v(t) = v0 / (1 + k v0 t / m), k = 1/2 rho Cd A.
    let (m, cda, rho, v0) = (1.5f32, 0.4f32, 1.225f32, 30.0f32);
    let k = 0.5 * rho * cda;
    let forces = ForceModels {
        gravity: None,
        quadratic_drag: Some(QuadraticDrag { density: rho }),
        ..Default::default()
    };
    for dt in [1.0 / 60.0, 0.25, 1.0] {
        let def = BodyDef {
            mass: m,
            drag_area: cda,
            velocity: Vec2::new(v0 * 0.6, v0 * 0.8),
            ..Default::default()
        };
        let (mut world, id) = single(forces, Integrator::SemiImplicitEuler, def);
        let steps = (4.0 / dt) as usize;
        run(&mut world, dt, steps);
        let t = dt * steps as f32;
        let want = v0 / (1.0 + k * v0 * t / m);
        let v = world.body(id).unwrap().velocity;
        assert_close(&format!("speed at dt {dt}"), v.length(), want, want * 1e-5);
        // Direction never changes under drag alone.
        assert_close("direction", v.y / v.x, 0.8 / 0.6, 1e-5);
    }
}

#[test]
fn linear_drag_decays_exponentially() {
    let (m, b, v0) = (2.0f32, 3.0f32, 12.0f32);
    let forces = ForceModels {
        gravity: None,
        linear_drag: Some(LinearDrag { coefficient: b }),
        ..Default::default()
    };
    let dt = 0.1;
    let def = BodyDef {
        mass: m,
        velocity: Vec2::new(v0, 0.0),
        ..Default::default()
    };
    let (mut world, id) = single(forces, Integrator::SemiImplicitEuler, def);
    for n in 1..=20 {
        world.step(dt);
        let want = v0 * (-b * dt * n as f32 / m).exp();
        let got = world.body(id).unwrap().velocity.x;
        assert_close(&format!("step {n}"), got, want, want * 1e-5);
    }
}

#[test]
fn rk4_is_fourth_order_with_velocity_dependent_forces() {
    // Plain linear drag, b/m = 1 per second: v = v0 exp(-t). Error ratio
    // between dt and dt/2 must be about 2^4.
    let forces = ForceModels {
        gravity: None,
        linear_drag: Some(LinearDrag { coefficient: 1.0 }),
        ..Default::default()
    };
    let error = |dt: f32| {
        let def = BodyDef {
            velocity: Vec2::new(10.0, 0.0),
            ..Default::default()
        };
        let (mut world, id) = single(forces, Integrator::Rk4, def);
        run(&mut world, dt, (2.0 / dt) as usize);
        (world.body(id).unwrap().velocity.x - 10.0 * (-2.0f32).exp()).abs()
    };
    let order = (error(0.5) / error(0.25)).log2();
    assert!((3.5..=4.6).contains(&order), "observed order {order}");
}

#[test]
fn friction_slide_stops_without_reversing_at_the_closed_form_distance() {
    let (mu, v0) = (0.4f32, 9.0f32);
    let forces = ForceModels {
        gravity: None,
        surface_friction: Some(SurfaceFriction { gravity: G }),
        ..Default::default()
    };
    let want = v0 * v0 / (2.0 * mu * G);
    // Every integrator: Verlet and RK4 evaluated friction in their stages,
    // where its flips at zero speed cancelled, and a body slower than about
    // `mu g dt` coasted on for ever; they now split it off.
    for (dt, integrator) in [1.0 / 60.0, 1.0 / 240.0, 0.5]
        .into_iter()
        .flat_map(|dt| Integrator::ALL.map(|i| (dt, i)))
    {
        let def = BodyDef {
            friction: mu,
            velocity: Vec2::new(v0, 0.0),
            ..Default::default()
        };
        let (mut world, id) = single(forces, integrator, def);
        let mut last_v = v0;
        for _ in 0..(10.0 / dt) as usize {
            world.step(dt);
            let v = world.body(id).unwrap().velocity;
            assert!(
                v.x >= 0.0 && v.x <= last_v,
                "{integrator:?}, dt {dt}: speed went {last_v} -> {}",
                v.x
            );
            assert_eq!(v.y, 0.0);
            last_v = v.x;
        }
        let body = world.body(id).unwrap();
        assert_eq!(
            body.velocity,
            Vec2::ZERO,
            "{integrator:?}, dt {dt}: stops exactly"
        );
        let step_travel = v0 * dt;
        assert!(
            (body.position.x - want).abs() <= step_travel,
            "{integrator:?}, dt {dt}: stopped at {} vs {want}",
            body.position.x
        );
    }
}

#[test]
fn friction_holds_a_gently_pushed_body_and_slows_a_hard_pushed_one() {
    // mu g = 3.92 m/s². Pushed at 1.5 m/s² a body at rest stays put under
    // every integrator: under Verlet and RK4 the stages' displacement, from
    // a push friction held back, crept it 0.125 m in 10 s at zero speed.
    // Pushed at 6 m/s² it accelerates at 6 - 3.92.
    let (mu, g) = (0.4f32, G);
    let forces = ForceModels {
        gravity: None,
        surface_friction: Some(SurfaceFriction { gravity: g }),
        ..Default::default()
    };
    for integrator in Integrator::ALL {
        for (push, want) in [(1.5f32, 0.0f32), (6.0, 6.0 - mu * g)] {
            let def = BodyDef {
                friction: mu,
                ..Default::default()
            };
            let (mut world, id) = single(forces, integrator, def);
            let dt = 1.0 / 60.0;
            for _ in 0..600 {
                world.apply_force(id, Vec2::new(push, 0.0));
                world.step(dt);
            }
            let b = world.body(id).unwrap();
            if want == 0.0 {
                assert_eq!(
                    (b.position, b.velocity),
                    (Vec2::ZERO, Vec2::ZERO),
                    "{integrator:?}"
                );
            } else {
                let v = want * 10.0;
                assert!(
                    (b.velocity.x - v).abs() < 1e-3 * v,
                    "{integrator:?}: {} against {v}",
                    b.velocity.x
                );
            }
        }
    }
}

#[test]
fn game_applied_friction_stops_and_never_reverses() {
    // The seed's call: friction with mu and a normal force, every step.
    let forces = ForceModels::none();
    let def = BodyDef {
        mass: 2.0,
        velocity: Vec2::new(-1.0, 1.0),
        ..Default::default()
    };
    let (mut world, id) = single(forces, Integrator::SemiImplicitEuler, def);
    // mu |N| / m dt = 0.5 * 40 / 2 * 0.1 = 1 m/s per step > |v| = 1.41 after one step.
    for _ in 0..3 {
        world.apply_friction(id, 0.5, 40.0);
        world.step(0.1);
    }
    assert_eq!(world.body(id).unwrap().velocity, Vec2::ZERO);
}

/// Energy of a unit mass on a spring of stiffness k: 1/2 v^2 + 1/2 k x^2.
fn spring_energy(world: &World) -> f64 {
    world.total_energy()
}

fn spring_world(integrator: Integrator, k: f32) -> World {
    let forces = ForceModels {
        gravity: None,
        spring: Some(Spring {
            anchor: Vec2::ZERO,
            stiffness: k,
        }),
        ..Default::default()
    };
    let def = BodyDef {
        position: Vec2::new(1.0, 0.0),
        ..Default::default()
    };
    single(forces, integrator, def).0
}

#[test]
fn spring_energy_is_bounded_for_semi_implicit_euler_over_a_million_steps() {
    let k = (2.0 * std::f32::consts::PI).powi(2); // w = 2 pi: period 1 s
    let dt = 1.0 / 60.0;
    let mut world = spring_world(Integrator::SemiImplicitEuler, k);
    let e0 = spring_energy(&world);
    let mut early = 0.0f64;
    let mut late = 0.0f64;
    let steps = 1_000_000;
    for n in 0..steps {
        world.step(dt);
        let drift = (spring_energy(&world) - e0).abs() / e0;
        if n < 10_000 {
            early = early.max(drift);
        } else if n >= steps - 10_000 {
            late = late.max(drift);
        }
    }
    // Symplectic Euler conserves a modified energy: the true energy
    // oscillates by about w dt / 2 = 0.05 and does not grow.
    let w_dt = f64::from(k.sqrt() * dt);
    assert!(early < w_dt, "early drift {early}");
    assert!(late < w_dt, "late drift {late}");
    assert!(
        late < early * 1.1 + 1e-3,
        "drift grew from {early} to {late}"
    );
}

#[test]
fn spring_energy_grows_by_one_plus_w2dt2_per_step_for_explicit_euler() {
    let k = 4.0f32; // w = 2 rad/s
    let dt = 0.01f32;
    let mut world = spring_world(Integrator::ExplicitEuler, k);
    let factor = 1.0 + f64::from(k * dt * dt);
    let mut e = spring_energy(&world);
    for _ in 0..1000 {
        world.step(dt);
        let next = spring_energy(&world);
        assert!(
            ((next / e) - factor).abs() < 1e-5,
            "ratio {} vs {factor}",
            next / e
        );
        e = next;
    }
}

#[test]
fn stable_drag_never_overshoots_where_the_plain_form_blows_up() {
    // k |v| dt / m = 50: the plain explicit update multiplies the speed by
    // (1 - 50) and reverses it every step.
    let forces = ForceModels {
        gravity: None,
        quadratic_drag: Some(QuadraticDrag { density: 2.0 }),
        ..Default::default()
    };
    let def = BodyDef {
        velocity: Vec2::new(50.0, 0.0),
        drag_area: 1.0,
        ..Default::default()
    };
    let (mut stable, s) = single(forces, Integrator::SemiImplicitEuler, def);
    let mut plain = World::new(WorldSettings {
        force_form: ForceForm::Explicit,
        ..*stable.settings()
    })
    .unwrap();
    let p = plain.add_body(def).unwrap();
    stable.step(1.0);
    plain.step(1.0);
    let vs = stable.body(s).unwrap().velocity.x;
    let vp = plain.body(p).unwrap().velocity.x;
    assert_close("stable", vs, 50.0 / 51.0, 1e-5);
    assert_close("plain", vp, 50.0 - 2500.0, 1e-2);
}

#[test]
fn min_speed_snaps_to_exactly_zero_and_max_speed_clamps_exactly() {
    let mut world = World::new(WorldSettings {
        forces: ForceModels::none(),
        min_speed: 0.5,
        max_speed: 20.0,
        ..Default::default()
    })
    .unwrap();
    let slow = world
        .add_body(BodyDef {
            velocity: Vec2::new(0.3, -0.3),
            ..Default::default()
        })
        .unwrap();
    let fast = world
        .add_body(BodyDef {
            velocity: Vec2::new(300.0, 400.0),
            ..Default::default()
        })
        .unwrap();
    let own = world
        .add_body(BodyDef {
            velocity: Vec2::new(0.0, 9.0),
            max_speed: Some(3.0),
            ..Default::default()
        })
        .unwrap();
    let start = world.body(slow).unwrap().position;
    world.step(0.1);
    let b = world.body(slow).unwrap();
    assert_eq!(b.velocity, Vec2::ZERO);
    assert_eq!(b.position, start, "a snapped body does not move");
    let v = world.body(fast).unwrap().velocity;
    assert_eq!(v, Vec2::new(12.0, 16.0));
    assert_eq!(world.body(own).unwrap().velocity, Vec2::new(0.0, 3.0));
}

#[test]
fn a_speed_limit_acts_on_a_body_in_the_contact_step_as_without_the_replayed_warm_start() {
    // The contact step's substeps after the first start from each body's
    // velocity change of the last substep (the replayed warm start); a
    // change a speed limit makes is not a contact's and must not be
    // replayed. A body thrown up past a large minimum speed hovers where it
    // is snapped, as it does with the replay off (no relax pass), and one
    // falling at the maximum speed falls at it, as does one thrown far
    // faster; the ground far below makes the step a contact step.
    let world = |relax_iterations: u32| {
        let mut settings = WorldSettings {
            min_speed: 0.05,
            max_speed: 4.0,
            ..Default::default()
        };
        if let Some(contacts) = &mut settings.contacts {
            contacts.relax_iterations = relax_iterations;
        }
        let mut world = World::new(settings).unwrap();
        crate::support::add_ground(&mut world, 10.0);
        let shape = passo_physics::Shape::circle(0.1);
        // Snapped in the second substep of tick 6 (gravity takes 9.81 / 240
        // m/s a substep), so that the replay would act within the step.
        let up =
            BodyDef::new_dynamic(Vec2::new(0.0, 50.0), shape).with_velocity(Vec2::new(0.0, 1.09));
        let down = BodyDef::new_dynamic(Vec2::new(3.0, 60.0), shape).with_velocity(-Vec2::Y);
        // Clamped from far above twice the maximum, where the change a
        // limit makes is rounded at the size of the speed before it.
        let thrown = BodyDef::new_dynamic(Vec2::new(-3.0, 50.0), shape)
            .with_velocity(Vec2::new(300.0, 400.0));
        let ids = [up, down, thrown].map(|def| world.add_body(def).unwrap());
        (world, ids)
    };
    let (mut replayed, ids) = world(1);
    let (mut plain, _) = world(0);
    for tick in 0..120 {
        replayed.step(1.0 / 60.0);
        plain.step(1.0 / 60.0);
        for id in ids {
            let (a, b) = (replayed.body(id).unwrap(), plain.body(id).unwrap());
            assert_eq!(a.position, b.position, "tick {tick}");
            assert_eq!(a.velocity, b.velocity, "tick {tick}");
        }
    }
    let up = replayed.body(ids[0]).unwrap();
    assert_eq!(
        up.velocity,
        Vec2::ZERO,
        "snapped at the top, and held there"
    );
    assert!(up.position.y > 50.0);
    let down = replayed.body(ids[1]).unwrap();
    assert_eq!(down.velocity.length(), 4.0, "falling at the maximum speed");
}

#[test]
fn a_speed_limit_moves_a_body_along_its_velocity_with_every_integrator() {
    // The multi-stage integrators move a body by its new velocity plus a
    // correction worked out before the limits; a limit that changed the
    // velocity left the correction in: a body pushed by 10^4 N and clamped
    // to 10 m/s went 2.61 m backwards in one step with explicit Euler (1.22
    // m with Verlet and RK4), and a body snapped to rest under gravity
    // climbed g dt^2 a step instead of hanging. With or without contacts
    // (a ground far away makes the step a contact step).
    for contacts in [false, true] {
        for integrator in Integrator::ALL {
            let mut world = World::new(WorldSettings {
                forces: ForceModels::none(),
                integrator,
                max_speed: 10.0,
                ..Default::default()
            })
            .unwrap();
            let shape = passo_physics::Shape::circle(0.1);
            if contacts {
                crate::support::add_ground(&mut world, 10.0);
            }
            let pushed = world
                .add_body(BodyDef::new_dynamic(Vec2::new(0.0, 50.0), shape))
                .unwrap();
            let dt = 1.0 / 60.0;
            for step in 1..=10 {
                world.apply_force(pushed, Vec2::new(1e4, 0.0));
                world.step(dt);
                let b = world.body(pushed).unwrap();
                let case = format!("{integrator:?}, contacts {contacts}, step {step}");
                assert_eq!(b.velocity, Vec2::new(10.0, 0.0), "{case}");
                // Never behind where it was, never faster than the limit.
                let most = step as f32 * 10.0 * dt;
                assert!(
                    b.position.x > 0.0 && b.position.x <= most * (1.0 + 1e-5),
                    "{case}: {}",
                    b.position
                );
            }
        }
    }
    for integrator in Integrator::ALL {
        let mut world = World::new(WorldSettings {
            integrator,
            min_speed: 0.5,
            ..Default::default()
        })
        .unwrap();
        let hanging = world
            .add_body(BodyDef::point_mass(Vec2::new(0.0, 5.0)))
            .unwrap();
        for _ in 0..10 {
            world.step(1.0 / 60.0);
        }
        let b = world.body(hanging).unwrap();
        assert_eq!(b.velocity, Vec2::ZERO, "{integrator:?}");
        assert_eq!(b.position, Vec2::new(0.0, 5.0), "{integrator:?}: it hangs");
    }
}

/// Two balls meeting head on in empty space leave with the velocities of
/// the one-dimensional collision law, for every mass ratio and
/// restitution swept: `v_a' = (m_a v_a + m_b v_b - m_b e (v_a - v_b)) / M`
/// and `v_b' = (m_a v_a + m_b v_b + m_a e (v_a - v_b)) / M`. Momentum is
/// kept exactly; a closing speed under the restitution threshold (1 m/s)
/// gives no bounce, as `e = 0` would.
#[test]
fn balls_meeting_head_on_leave_as_the_collision_law_says() {
    let no_forces = WorldSettings {
        forces: ForceModels::none(),
        ..Default::default()
    };
    for (ma, mb) in [(1.0f32, 1.0f32), (1.0, 3.0), (5.0, 1.0)] {
        for e in [1.0f32, 0.5, 0.0] {
            for (va, vb) in [(4.0f32, 0.0f32), (3.0, -2.0), (0.6, 0.0)] {
                let mut world = World::new(no_forces).unwrap();
                let ball = |world: &mut World, x: f32, v: f32, m: f32| {
                    let def = BodyDef {
                        position: Vec2::new(x, 0.0),
                        velocity: Vec2::new(v, 0.0),
                        shape: Some(Shape::circle(0.25)),
                        mass: m,
                        restitution: e,
                        ..Default::default()
                    };
                    world.add_body(def).unwrap()
                };
                let a = ball(&mut world, -1.0, va, ma);
                let b = ball(&mut world, 0.0, vb, mb);
                for _ in 0..60 {
                    world.step(1.0 / 60.0);
                }
                let v = |id| world.body(id).unwrap().velocity.x;
                let e = if va - vb < 1.0 { 0.0 } else { e };
                let m = ma + mb;
                let want_a = (ma * va + mb * vb - mb * e * (va - vb)) / m;
                let want_b = (ma * va + mb * vb + ma * e * (va - vb)) / m;
                let case = format!("{ma}:{mb} kg, e {e}, {va} and {vb} m/s");
                assert!(
                    (v(a) - want_a).abs() < 0.02 * va.abs().max(1.0),
                    "{case}: a {}, want {want_a}",
                    v(a)
                );
                assert!(
                    (v(b) - want_b).abs() < 0.02 * va.abs().max(1.0),
                    "{case}: b {}, want {want_b}",
                    v(b)
                );
                let p = ma * v(a) + mb * v(b);
                assert!(
                    (p - (ma * va + mb * vb)).abs() < 1e-4 * m,
                    "{case}: momentum {p}"
                );
            }
        }
    }
}
