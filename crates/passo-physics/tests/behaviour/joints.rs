//! Joints against closed forms: a pendulum's period (the complete elliptic
//! integral), a spring's damped oscillation, a motor's constant force; and
//! the promises: a rope never stretches, a weld holds, a joint breaks once,
//! joints sleep, wake, save and go with their bodies.

use crate::support::{add_ground, weightless_world};
use passo_physics::glam::Vec2;
use passo_physics::{
    BodyDef, BodyId, JointDef, JointKind, JointMotor, PhysicsError, Shape, World, WorldSettings,
};

const DT: f32 = 1.0 / 60.0;
const G: f32 = 9.81;

/// The complete elliptic integral of the first kind, K(k), by the
/// arithmetic-geometric mean.
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    for _ in 0..40 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

/// The exact period of a pendulum of `length` released at rest from
/// `amplitude` radians.
fn pendulum_period(length: f64, amplitude: f64) -> f64 {
    4.0 * (length / G as f64).sqrt() * elliptic_k((amplitude / 2.0).sin())
}

/// A point mass on a rod of `length` from the origin, released at rest
/// `amplitude` radians from straight down.
fn pendulum(length: f32, amplitude: f32) -> (World, BodyId) {
    let mut world = World::default();
    let start = length * Vec2::new(amplitude.sin(), -amplitude.cos());
    let bob = world.add_body(BodyDef::point_mass(start)).unwrap();
    world
        .add_joint(JointDef::distance(bob, None, length))
        .unwrap();
    (world, bob)
}

/// Times at which the bob crosses x = 0 moving right, interpolated within
/// the step.
fn crossings(
    world: &mut World,
    bob: BodyId,
    steps: usize,
    mut each: impl FnMut(&World),
) -> Vec<f64> {
    let mut times = Vec::new();
    let mut x = world.body(bob).unwrap().position.x;
    for n in 0..steps {
        world.step(DT);
        each(world);
        let next = world.body(bob).unwrap().position.x;
        if x < 0.0 && next >= 0.0 {
            let f = (-x / (next - x)) as f64;
            times.push((n as f64 + f) * DT as f64);
        }
        x = next;
    }
    times
}

#[test]
fn a_pendulum_on_a_rod_keeps_the_exact_period_and_its_length() {
    for length in [0.5f32, 1.0, 4.0] {
        for degrees in [5.0f32, 30.0, 90.0, 150.0] {
            let amplitude = degrees.to_radians();
            let (mut world, bob) = pendulum(length, amplitude);
            let mut worst = 0.0f32;
            let times = crossings(&mut world, bob, 1200, |w| {
                let r = w.body(bob).unwrap().position.length();
                worst = worst.max((r - length).abs());
            });
            assert!(times.len() >= 3, "{length} m, {degrees}°: it swings");
            let measured = (times[times.len() - 1] - times[0]) / (times.len() - 1) as f64;
            let exact = pendulum_period(length as f64, amplitude as f64);
            let error = (measured - exact).abs() / exact;
            // First order in the substep: 1 % at 150° on a 0.5 m rod.
            assert!(
                error < 0.02,
                "{length} m, {degrees}°: period {measured:.4} s against {exact:.4} s"
            );
            assert!(
                worst < passo_physics::ContactSettings::default().slop,
                "{length} m, {degrees}°: the rod stretched {worst} m"
            );
        }
    }
}

#[test]
fn a_pendulum_swings_back_to_its_height() {
    // No energy added by the drift correction: after ten swings the bob
    // still reaches within 5 % of its starting height and never above it.
    let (mut world, bob) = pendulum(1.0, 60f32.to_radians());
    let start = world.body(bob).unwrap().position.y;
    let mut highest_late = f32::MIN;
    for n in 0..1200 {
        world.step(DT);
        let y = world.body(bob).unwrap().position.y;
        assert!(
            y <= start + 1e-4,
            "step {n}: above its start, {y} > {start}"
        );
        if n > 1000 {
            highest_late = highest_late.max(y);
        }
    }
    let drop = start - highest_late;
    assert!(drop < 0.05 * 0.5, "lost {drop} m of 0.5 m swing height");
}

#[test]
fn a_body_on_a_spring_joint_follows_the_damped_oscillator() {
    // x'' = -w^2 x - 2 z w x'; released at rest 0.5 m from rest length.
    for (hertz, zeta) in [(1.0f32, 0.0f32), (2.0, 0.1), (0.5, 0.5), (1.0, 1.0)] {
        let mut world = weightless_world();
        let body = world
            .add_body(BodyDef {
                position: Vec2::new(1.5, 0.0),
                mass: 2.0,
                ..Default::default()
            })
            .unwrap();
        let def = JointDef::spring(
            body,
            None,
            1.0,
            passo_physics::JointSpring::new(hertz, zeta),
        );
        world.add_joint(def).unwrap();
        let w = std::f64::consts::TAU * hertz as f64;
        let z = zeta as f64;
        let exact = |t: f64| -> f64 {
            let x0 = 0.5;
            if z < 1.0 {
                let wd = w * (1.0 - z * z).sqrt();
                x0 * (-z * w * t).exp() * ((wd * t).cos() + z * w / wd * (wd * t).sin())
            } else {
                x0 * (-w * t).exp() * (1.0 + w * t)
            }
        };
        let mut worst = 0.0f64;
        for n in 1..=240 {
            world.step(DT);
            let x = world.body(body).unwrap().position.x as f64 - 1.0;
            worst = worst.max((x - exact(n as f64 * DT as f64)).abs());
        }
        // An implicit spring stepped at 240 Hz: a few percent of the
        // amplitude over two seconds.
        assert!(
            worst < 0.05 * 0.5,
            "{hertz} Hz, zeta {zeta}: off by {worst} m"
        );
    }
}

#[test]
fn a_rope_never_stretches_past_its_length_by_more_than_the_slop() {
    let slop = passo_physics::ContactSettings::default().slop;
    for mass in [0.1f32, 1.0, 30.0, 1000.0] {
        for slack in [0.0f32, 0.5, 1.9] {
            for angle in [0.0f32, 0.8, 1.5] {
                let mut world = World::default();
                let top = Vec2::new(0.0, 10.0);
                let anchor = world
                    .add_body(BodyDef::new_static(top, Shape::circle(0.1)))
                    .unwrap();
                let body = world
                    .add_body(BodyDef {
                        position: top + (2.0 - slack) * Vec2::new(angle.sin(), -angle.cos()),
                        mass,
                        shape: Some(Shape::rect(0.4, 0.4)),
                        ..Default::default()
                    })
                    .unwrap();
                world
                    .add_joint(JointDef::rope(anchor, Some(body), 2.0))
                    .unwrap();
                let mut longest = 0.0f32;
                for _ in 0..600 {
                    world.step(DT);
                    let p = world.body(body).unwrap().position;
                    longest = longest.max((p - top).length());
                }
                assert!(
                    longest <= 2.0 + slop,
                    "{mass} kg, {slack} m of slack at {angle} rad: the rope reached {longest} m"
                );
            }
        }
    }
}

#[test]
fn a_rope_lets_its_ends_come_closer() {
    let mut world = weightless_world();
    let a = world.add_body(BodyDef::point_mass(Vec2::ZERO)).unwrap();
    let b = world
        .add_body(BodyDef::point_mass(Vec2::new(1.0, 0.0)))
        .unwrap();
    world.add_joint(JointDef::rope(a, Some(b), 2.0)).unwrap();
    world.set_velocity(b, Vec2::new(-0.5, 0.0));
    for _ in 0..60 {
        world.step(DT);
    }
    let gap = world.body(b).unwrap().position.x - world.body(a).unwrap().position.x;
    assert!(
        (gap - 0.5).abs() < 1e-4,
        "slack rope: free flight, gap {gap}"
    );
}

#[test]
fn a_motorised_slider_reaches_its_speed_with_at_most_its_force() {
    for (mass, force, speed) in [
        (1.0f32, 5.0f32, 2.0f32),
        (10.0, 20.0, -1.0),
        (0.5, 100.0, 3.0),
    ] {
        let mut world = World::default();
        let rail = world
            .add_body(BodyDef::new_static(Vec2::ZERO, Shape::rect(0.2, 0.2)))
            .unwrap();
        let car = world
            .add_body(BodyDef {
                position: Vec2::new(0.0, 0.0),
                mass,
                ..Default::default()
            })
            .unwrap();
        let def = JointDef::prismatic(rail, Some(car), Vec2::X).motor(speed, force);
        let joint = world.add_joint(def).unwrap();
        // Constant force F until the speed is reached: v = F t / m.
        let mut last = 0.0f32;
        for n in 1..=300 {
            world.step(DT);
            let body = world.body(car).unwrap();
            let v = body.velocity.x;
            let t = n as f32 * DT;
            let free = (force / mass * t).min(speed.abs()) * speed.signum();
            assert!(
                (v - free).abs() < 1e-3 * speed.abs().max(1.0),
                "{mass} kg, step {n}: {v} against {free}"
            );
            let accel = (v - last).abs() / DT;
            assert!(
                accel <= force / mass * (1.0 + 1e-4) + 1e-3,
                "step {n}: {accel} m/s²"
            );
            assert!(
                body.position.y.abs() < 1e-3,
                "the car stays on its rail: {}",
                body.position.y
            );
            last = v;
        }
        assert!(
            world.joint(joint).unwrap().force > 0.0,
            "it holds the car's weight"
        );
    }
}

#[test]
fn a_slider_stops_at_its_limits() {
    let mut world = weightless_world();
    let rail = world
        .add_body(BodyDef::new_static(Vec2::ZERO, Shape::circle(0.1)))
        .unwrap();
    let car = world
        .add_body(BodyDef::point_mass(Vec2::new(0.0, 0.0)))
        .unwrap();
    let def = JointDef::prismatic(rail, Some(car), Vec2::new(1.0, 1.0)).limits(-1.0, 2.0);
    world.add_joint(def).unwrap();
    world.set_velocity(car, Vec2::new(8.0, 0.0));
    for _ in 0..120 {
        world.step(DT);
        let p = world.body(car).unwrap().position;
        let along = p.dot(Vec2::new(1.0, 1.0).normalize());
        assert!(along <= 2.0 + 0.006, "past the upper limit: {along}");
        // The soft correction lets the first substep drift a little
        // while it takes the 5.7 m/s across the axis out.
        assert!((p.x - p.y).abs() < 5e-3, "off the axis: {p}");
    }
    let p = world.body(car).unwrap().position;
    assert!((p.x - p.y).abs() < 1e-4, "back on the axis: {p}");
}

#[test]
fn a_weld_moves_two_bodies_as_one() {
    let mut world = World::default();
    let a = world
        .add_body(BodyDef {
            position: Vec2::new(0.0, 5.0),
            mass: 1.0,
            ..Default::default()
        })
        .unwrap();
    let b = world
        .add_body(BodyDef {
            position: Vec2::new(1.0, 5.0),
            mass: 3.0,
            ..Default::default()
        })
        .unwrap();
    world
        .add_joint(JointDef::weld(a, Some(b), Vec2::new(1.0, 0.0)))
        .unwrap();
    for _ in 0..60 {
        world.apply_force(a, Vec2::new(8.0, 0.0));
        world.step(DT);
    }
    let (pa, pb) = (world.body(a).unwrap(), world.body(b).unwrap());
    assert!(
        ((pb.position - pa.position) - Vec2::X).length() < 1e-3,
        "offset kept"
    );
    // 8 N on 4 kg for 1 s: 2 m/s, and gravity's free fall.
    let v = pa.velocity;
    assert!((v.x - 2.0).abs() < 1e-2, "as one body of 4 kg: {v}");
    assert!((v.y + G).abs() < 1e-2, "falling freely: {v}");
}

#[test]
fn a_target_joint_pulls_to_its_point_with_at_most_its_force() {
    let mut world = weightless_world();
    let body = world
        .add_body(BodyDef {
            position: Vec2::ZERO,
            mass: 2.0,
            ..Default::default()
        })
        .unwrap();
    let weak = world
        .add_joint(JointDef::target(body, Vec2::new(3.0, 4.0)).max_force(10.0))
        .unwrap();
    let mut last = Vec2::ZERO;
    for _ in 0..600 {
        world.step(DT);
        let v = world.body(body).unwrap().velocity;
        let accel = (v - last).length() / DT;
        assert!(
            accel <= 10.0 / 2.0 * 1.001 + 1e-3,
            "at most 10 N on 2 kg: {accel}"
        );
        last = v;
    }
    world.remove_joint(weak).unwrap();
    let joint = world
        .add_joint(JointDef::target(body, Vec2::new(3.0, 4.0)).max_force(1000.0))
        .unwrap();
    for _ in 0..600 {
        world.step(DT);
    }
    let p = world.body(body).unwrap().position;
    assert!(
        (p - Vec2::new(3.0, 4.0)).length() < 1e-2,
        "at the target: {p}"
    );
    world.set_joint_target(joint, Vec2::new(-1.0, 0.0)).unwrap();
    for _ in 0..600 {
        world.step(DT);
    }
    let p = world.body(body).unwrap().position;
    assert!(
        (p - Vec2::new(-1.0, 0.0)).length() < 1e-2,
        "at the new target: {p}"
    );
}

#[test]
fn a_joint_breaks_above_its_force_once_and_says_so() {
    for (mass, breaks) in [(1.0f32, false), (3.0, true)] {
        let mut world = World::default();
        let hook = world
            .add_body(BodyDef::new_static(Vec2::new(0.0, 5.0), Shape::circle(0.1)))
            .unwrap();
        let body = world
            .add_body(BodyDef {
                position: Vec2::new(0.0, 4.0),
                mass,
                ..Default::default()
            })
            .unwrap();
        // 20 N holds 1 kg (9.81 N), not 3 kg (29.4 N).
        let id = world
            .add_joint(JointDef::distance(hook, Some(body), 1.0).break_force(20.0))
            .unwrap();
        let mut events = 0;
        for _ in 0..120 {
            world.step(DT);
            for broken in world.broken_joints() {
                assert_eq!(broken.id, id);
                assert!(broken.force > 20.0);
                events += 1;
            }
        }
        assert_eq!(events, usize::from(breaks), "{mass} kg");
        assert_eq!(world.joint(id).is_none(), breaks);
        let y = world.body(body).unwrap().position.y;
        assert_eq!(y < 0.0, breaks, "{mass} kg: at {y}");
    }
}

#[test]
fn a_removed_body_takes_its_joints_with_it() {
    let mut world = World::default();
    let a = world.add_body(BodyDef::point_mass(Vec2::ZERO)).unwrap();
    let b = world.add_body(BodyDef::point_mass(Vec2::X)).unwrap();
    let c = world.add_body(BodyDef::point_mass(Vec2::Y)).unwrap();
    let ab = world
        .add_joint(JointDef::distance(a, Some(b), 1.0))
        .unwrap();
    let bc = world.add_joint(JointDef::rope(b, Some(c), 2.0)).unwrap();
    let ca = world
        .add_joint(JointDef::distance(c, Some(a), 1.0))
        .unwrap();
    assert_eq!(world.joints_of(b), vec![ab, bc]);
    world.remove_body(b).unwrap();
    assert!(world.joint(ab).is_none() && world.joint(bc).is_none());
    assert!(world.joint(ca).is_some());
    assert_eq!(world.joint_len(), 1);
    assert_eq!(world.remove_joint(ab), None, "a stale id");
    assert_eq!(
        world.set_joint_target(ab, Vec2::ZERO),
        Err(PhysicsError::StaleJoint(ab))
    );
    world.step(DT);
}

#[test]
fn bad_joints_are_refused_with_a_reason() {
    let mut world = World::default();
    let ground = world
        .add_body(BodyDef::new_static(Vec2::ZERO, Shape::rect(1.0, 1.0)))
        .unwrap();
    let wall = world
        .add_body(BodyDef::new_static(Vec2::X, Shape::rect(1.0, 1.0)))
        .unwrap();
    let body = world.add_body(BodyDef::point_mass(Vec2::Y)).unwrap();
    let stale = world.add_body(BodyDef::point_mass(Vec2::Y)).unwrap();
    world.remove_body(stale);
    let bad = [
        JointDef::distance(body, Some(body), 1.0),
        JointDef::distance(ground, Some(wall), 1.0),
        JointDef::distance(body, None, f32::NAN),
        JointDef::distance(body, None, 1.0).anchors(Vec2::new(f32::INFINITY, 0.0), Vec2::ZERO),
        JointDef::distance(body, None, 1.0).limits(2.0, 1.0),
        JointDef::distance(body, None, 1.0).break_force(0.0),
        JointDef::prismatic(body, None, Vec2::ZERO),
        JointDef::prismatic(body, None, Vec2::X).limits(1.0, -1.0),
        JointDef::prismatic(body, None, Vec2::X).motor(1.0, -5.0),
        JointDef::spring(body, None, 1.0, passo_physics::JointSpring::new(-1.0, 0.0)),
        JointDef::target(body, Vec2::new(1e9, 0.0)),
        JointDef::target(body, Vec2::ZERO).max_force(0.0),
        JointDef::distance(stale, None, 1.0),
    ];
    for def in bad {
        assert!(world.add_joint(def).is_err(), "{def:?} refused");
    }
    assert_eq!(world.joint_len(), 0);
    let mut off = World::new(WorldSettings {
        contacts: None,
        ..Default::default()
    })
    .unwrap();
    let lone = off.add_body(BodyDef::point_mass(Vec2::Y)).unwrap();
    assert!(matches!(
        off.add_joint(JointDef::distance(lone, None, 1.0)),
        Err(PhysicsError::InvalidJoint(_))
    ));
    // And contacts cannot be turned off under a joint.
    world
        .add_joint(JointDef::distance(body, None, 1.0))
        .unwrap();
    let settings = WorldSettings {
        contacts: None,
        ..*world.settings()
    };
    assert!(world.set_settings(settings).is_err());
}

#[test]
fn a_chain_of_crates_sleeps_and_wakes_as_one() {
    let mut world = World::default();
    let top = Vec2::new(0.0, 10.0);
    let hook = world
        .add_body(BodyDef::new_static(top, Shape::circle(0.1)))
        .unwrap();
    let mut last = hook;
    let mut links = Vec::new();
    for k in 1..=5 {
        let body = world
            .add_body(BodyDef {
                position: top - Vec2::new(0.0, k as f32),
                shape: Some(Shape::rect(0.5, 0.5)),
                ..Default::default()
            })
            .unwrap();
        world
            .add_joint(JointDef::distance(last, Some(body), 1.0))
            .unwrap();
        links.push(body);
        last = body;
    }
    for _ in 0..300 {
        world.step(DT);
    }
    assert!(
        links.iter().all(|&b| world.is_asleep(b) == Some(true)),
        "the still chain sleeps"
    );
    world.apply_impulse(links[4], Vec2::new(1.0, 0.0));
    assert!(
        links.iter().all(|&b| world.is_asleep(b) == Some(false)),
        "a push at the bottom wakes every link"
    );
    world.step(DT);
    assert!(
        world.body(links[0]).unwrap().velocity.x != 0.0,
        "and the top link moves with it"
    );
}

#[test]
fn a_restored_snapshot_swings_on_with_the_same_bits() {
    let (mut world, bob) = pendulum(1.5, 1.0);
    let other = world
        .add_body(BodyDef::point_mass(Vec2::new(3.0, 0.0)))
        .unwrap();
    world
        .add_joint(JointDef::spring(
            bob,
            Some(other),
            2.0,
            passo_physics::JointSpring::new(3.0, 0.2),
        ))
        .unwrap();
    for _ in 0..37 {
        world.step(DT);
    }
    let snapshot = world.snapshot();
    let mut copy = World::from_snapshot(snapshot.clone()).unwrap();
    assert_eq!(copy.joint_len(), 2);
    for _ in 0..100 {
        world.step(DT);
        copy.step(DT);
    }
    let bits = |w: &World, id| {
        let b = w.body(id).unwrap();
        [b.position, b.velocity].map(|v| v.to_array().map(f32::to_bits))
    };
    assert_eq!(bits(&world, bob), bits(&copy, bob));
    assert_eq!(bits(&world, other), bits(&copy, other));
}

#[test]
fn joints_to_kinematic_bodies_carry_what_hangs_from_them() {
    let mut world = World::default();
    let platform = world
        .add_body(BodyDef::new_kinematic(
            Vec2::new(0.0, 5.0),
            Shape::rect(2.0, 0.2),
            Vec2::ZERO,
        ))
        .unwrap();
    let crate_ = world
        .add_body(BodyDef {
            position: Vec2::new(0.0, 3.0),
            shape: Some(Shape::rect(0.5, 0.5)),
            ..Default::default()
        })
        .unwrap();
    world
        .add_joint(JointDef::distance(platform, Some(crate_), 2.0))
        .unwrap();
    for _ in 0..300 {
        world.step(DT);
    }
    world.set_velocity(platform, Vec2::new(1.0, 0.0));
    for _ in 0..120 {
        world.step(DT);
    }
    // It swings behind the platform; over 10 s it keeps up with it.
    let from = world.body(crate_).unwrap().position.x;
    for _ in 0..600 {
        world.step(DT);
        let (p, c) = (world.body(platform).unwrap(), world.body(crate_).unwrap());
        let rod = (c.position - p.position).length();
        assert!((rod - 2.0).abs() < 1e-2, "on its rod: {rod}");
    }
    let (p, c) = (world.body(platform).unwrap(), world.body(crate_).unwrap());
    let moved = p.position.x;
    assert!(
        (moved - 12.0).abs() < 0.05,
        "the platform moved 12 m: {moved}"
    );
    // 10 m, give or take its swing (1 m/s at 2.2 rad/s: 0.45 m each way).
    let travel = c.position.x - from;
    assert!((travel - 10.0).abs() < 1.0, "the crate kept up: {travel} m");
}

#[test]
fn a_joint_kind_reads_back_as_given() {
    let mut world = World::default();
    let body = world.add_body(BodyDef::point_mass(Vec2::Y)).unwrap();
    let id = world
        .add_joint(JointDef::prismatic(body, None, Vec2::new(0.0, 2.0)).motor(1.0, 2.0))
        .unwrap();
    let joint = world.joint(id).unwrap();
    assert_eq!(
        joint.def.kind,
        JointKind::Prismatic {
            axis: Vec2::Y,
            limits: None,
            motor: Some(JointMotor {
                speed: 1.0,
                max_force: 2.0
            })
        }
    );
    world.set_joint_motor(id, None).unwrap();
    assert!(matches!(
        world.joint(id).unwrap().def.kind,
        JointKind::Prismatic { motor: None, .. }
    ));
}

#[test]
fn joined_bodies_pass_through_each_other_unless_the_joint_says_they_collide() {
    for collide in [false, true] {
        let mut world = World::default();
        let frame = world
            .add_body(BodyDef::new_static(
                Vec2::new(0.0, 4.0),
                Shape::rect(0.6, 0.2),
            ))
            .unwrap();
        let door = world
            .add_body(BodyDef::new_dynamic(
                Vec2::new(0.0, 1.0),
                Shape::rect(0.5, 2.0),
            ))
            .unwrap();
        let slider = JointDef::prismatic(frame, Some(door), Vec2::Y)
            .limits(-3.0, -0.5)
            .motor(1.0, 1000.0);
        let slider = if collide { slider.colliding() } else { slider };
        world.add_joint(slider).unwrap();
        for _ in 0..240 {
            world.step(DT);
        }
        let y = world.body(door).unwrap().position.y;
        if collide {
            // Its top (y + 1) stops at the frame's bottom (3.9).
            assert!((y - 2.9).abs() < 0.01, "caught on its frame: {y}");
        } else {
            assert!(
                (y - 3.5).abs() < 0.01,
                "through its frame to the limit: {y}"
            );
        }
    }
}

#[test]
fn a_body_put_back_from_overflow_leaves_its_joint_finite() {
    // Two balls on the ground joined by a rod; a force so large on one
    // that its velocity overflows. The step puts the ball back (each
    // substep counts a reset), the rod's force reads finite, and the pair
    // settles as before.
    for force in [1e30, 1e34, 1e36, f32::MAX] {
        let mut world = World::default();
        add_ground(&mut world, 20.0);
        let ball = |world: &mut World, x: f32| {
            let def = BodyDef::new_dynamic(Vec2::new(x, 0.25), Shape::circle(0.25));
            world.add_body(def).unwrap()
        };
        let (a, b) = (ball(&mut world, 0.0), ball(&mut world, 1.0));
        let rod = world
            .add_joint(JointDef::distance(a, Some(b), 1.0))
            .unwrap();
        for _ in 0..10 {
            world.step(DT);
        }
        world.apply_force(a, Vec2::new(force, 0.0));
        world.step(DT);
        assert!(world.stats().non_finite_resets > 0, "{force} N");
        let f = world.joint(rod).unwrap().force;
        assert!(f.is_finite(), "{force} N: the rod's force {f}");
        for _ in 0..60 {
            world.step(DT);
        }
        let (pa, pb) = (
            world.body(a).unwrap().position,
            world.body(b).unwrap().position,
        );
        assert!(
            ((pb - pa).length() - 1.0).abs() < 0.01,
            "{force} N: {pa} {pb}"
        );
        assert!(world.joint(rod).unwrap().force.is_finite());
    }
}
