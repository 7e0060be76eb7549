//! Kinematic bodies: moved by their velocity alone, they carry, lift and
//! push dynamic bodies and are not moved by anything.

use crate::support::{add_ground, max_penetration};
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, BodyId, BodyKind, ContactStage, Shape, Stage, World, WorldSettings};

const DT: f32 = 1.0 / 60.0;

fn platform(world: &mut World, position: Vec2, velocity: Vec2) -> BodyId {
    world
        .add_body(BodyDef::new_kinematic(
            position,
            Shape::rect(4.0, 0.5),
            velocity,
        ))
        .unwrap()
}

/// A 1 m box resting on the platform's top (the platform is 0.5 m thick).
fn rider(world: &mut World, on: Vec2, velocity: Vec2) -> BodyId {
    world
        .add_body(BodyDef {
            position: on + Vec2::new(0.0, 0.25 + 0.5),
            velocity,
            shape: Some(Shape::rect(1.0, 1.0)),
            ..Default::default()
        })
        .unwrap()
}

fn pos(world: &World, id: BodyId) -> Vec2 {
    world.body(id).unwrap().position
}

#[test]
fn a_kinematic_body_moves_by_its_velocity_alone() {
    for shaped in [false, true] {
        let mut world = World::default();
        let def = BodyDef {
            kind: BodyKind::Kinematic,
            velocity: Vec2::new(2.0, -1.0),
            shape: shaped.then_some(Shape::circle(0.5)),
            ..Default::default()
        };
        let k = world.add_body(def).unwrap();
        // Something to collide with, so the contact stage runs too.
        world
            .add_body(BodyDef::new_static(
                Vec2::new(0.0, -3.0),
                Shape::rect(50.0, 1.0),
            ))
            .unwrap();
        world.apply_force(k, Vec2::new(1e4, 1e4));
        world.apply_impulse(k, Vec2::new(1e4, 1e4));
        for _ in 0..120 {
            world.step(DT);
        }
        let b = world.body(k).unwrap();
        assert_eq!(b.kind, BodyKind::Kinematic);
        assert_eq!(
            b.velocity,
            Vec2::new(2.0, -1.0),
            "no gravity, force or impulse"
        );
        // 2 s at (2, -1) m/s; it passes through the static ground.
        assert!(
            (b.position - Vec2::new(4.0, -2.0)).length() < 1e-4,
            "{shaped}: {}",
            b.position
        );
        assert_eq!(b.mass, f32::INFINITY);
        assert!(world.active_stages().contains(&Stage::Kinematic));
        if shaped {
            assert!(
                world
                    .contact_stages()
                    .contains(&ContactStage::HoldKinematic)
            );
        }
    }
}

#[test]
fn set_kinematic_target_reaches_the_target_in_one_step() {
    let mut world = World::default();
    let k = platform(&mut world, Vec2::ZERO, Vec2::ZERO);
    for target in [Vec2::new(0.5, 0.25), Vec2::new(-1.0, 3.0)] {
        world.set_kinematic_target(k, target, DT);
        world.step(DT);
        assert!((pos(&world, k) - target).length() < 1e-5);
    }
    assert!(world.try_set_kinematic_target(k, Vec2::NAN, DT).is_err());
    assert!(world.try_set_kinematic_target(k, Vec2::ONE, 0.0).is_err());
    // A dynamic body is not moved by it.
    let d = world.add_body(BodyDef::point_mass(Vec2::ZERO)).unwrap();
    world.set_kinematic_target(d, Vec2::new(9.0, 9.0), DT);
    assert_eq!(world.body(d).unwrap().velocity, Vec2::ZERO);
}

#[test]
fn a_rider_is_carried_sideways_by_friction_with_under_a_centimetre_of_slip() {
    let mut world = World::default();
    let v = Vec2::new(2.0, 0.0);
    let k = platform(&mut world, Vec2::ZERO, v);
    let r = rider(&mut world, Vec2::ZERO, v);
    let start = pos(&world, r) - pos(&world, k);
    for _ in 0..300 {
        world.step(DT);
    }
    let slip = (pos(&world, r) - pos(&world, k) - start).length();
    assert!(slip < 0.01, "slip over 5 s: {slip} m");
    assert!((world.body(r).unwrap().velocity - v).length() < 1e-3);
    assert!(world.is_standing(r, 0.8));
    assert_eq!(world.standing_on(r, 0.8), Some(k));
}

#[test]
fn a_rider_at_rest_is_brought_up_to_the_platforms_speed_by_friction() {
    // mu g = 0.6 * 9.81 = 5.886 m/s²: 2 m/s is reached in 0.34 s.
    let mut world = World::default();
    let k = platform(&mut world, Vec2::ZERO, Vec2::new(2.0, 0.0));
    let r = rider(&mut world, Vec2::ZERO, Vec2::ZERO);
    for _ in 0..15 {
        world.step(DT);
    }
    let vx = world.body(r).unwrap().velocity.x;
    assert!((vx - 5.886 * 0.25).abs() < 0.05, "after 0.25 s: {vx} m/s");
    for _ in 0..45 {
        world.step(DT);
    }
    assert!((world.body(r).unwrap().velocity.x - 2.0).abs() < 1e-3);
    let _ = k;
}

#[test]
fn a_platform_moving_up_lifts_its_rider_and_one_moving_down_keeps_it() {
    for vy in [2.0, -3.0] {
        let mut world = World::default();
        let v = Vec2::new(0.0, vy);
        let k = platform(&mut world, Vec2::ZERO, v);
        let r = rider(&mut world, Vec2::ZERO, v);
        let mut worst_gap = 0.0f32;
        let mut worst_sink = 0.0f32;
        for _ in 0..300 {
            world.step(DT);
            // Rider bottom minus platform top.
            let gap = (pos(&world, r).y - 0.5) - (pos(&world, k).y + 0.25);
            worst_gap = worst_gap.max(gap);
            worst_sink = worst_sink.max(-gap);
        }
        assert!(worst_gap < 0.01, "{vy} m/s: lifted off by {worst_gap} m");
        assert!(worst_sink < 0.0075, "{vy} m/s: sank {worst_sink} m");
        assert!((world.body(r).unwrap().velocity.y - vy).abs() < 1e-3);
    }
}

#[test]
fn a_platform_that_reverses_from_up_to_down_lands_its_rider_again_without_a_bounce() {
    // The rider leaves the platform when it turns from 2 m/s up to 3 m/s
    // down (it falls at g, slower at first than the platform sinks), and
    // lands on it about 0.8 s later; with restitution 0 it stays there.
    let mut world = World::default();
    let k = platform(&mut world, Vec2::ZERO, Vec2::new(0.0, 2.0));
    let r = rider(&mut world, Vec2::ZERO, Vec2::new(0.0, 2.0));
    for _ in 0..60 {
        world.step(DT);
    }
    world.set_velocity(k, Vec2::new(0.0, -3.0));
    for _ in 0..120 {
        world.step(DT);
    }
    let gap = (pos(&world, r).y - 0.5) - (pos(&world, k).y + 0.25);
    assert!(gap.abs() < 0.01, "back on the platform: gap {gap}");
    assert!((world.body(r).unwrap().velocity.y + 3.0).abs() < 1e-3);
    assert!(max_penetration(&world) < 0.0075);
}

#[test]
fn a_platform_moving_sideways_pushes_a_box_in_its_way() {
    let mut world = World::default();
    add_ground(&mut world, 40.0);
    let wall = world
        .add_body(BodyDef::new_kinematic(
            Vec2::new(-3.0, 1.0),
            Shape::rect(0.5, 2.0),
            Vec2::new(1.5, 0.0),
        ))
        .unwrap();
    let b = world
        .add_body(BodyDef {
            position: Vec2::new(0.0, 0.5),
            shape: Some(Shape::rect(1.0, 1.0)),
            ..Default::default()
        })
        .unwrap();
    for _ in 0..240 {
        world.step(DT);
    }
    // The wall's right face reached 4 s * 1.5 m/s - 3 + 0.25 = 3.25 m; the
    // box is pushed ahead of it.
    let face = pos(&world, wall).x + 0.25;
    let box_left = pos(&world, b).x - 0.5;
    assert!(
        (box_left - face).abs() < 0.01,
        "box at {box_left}, wall at {face}"
    );
    assert!((world.body(b).unwrap().velocity.x - 1.5).abs() < 0.01);
    assert_eq!(world.body(wall).unwrap().velocity, Vec2::new(1.5, 0.0));
}

#[test]
fn kinematic_bodies_meet_neither_static_nor_kinematic_ones() {
    let mut world = World::default();
    let a = platform(&mut world, Vec2::new(-3.0, 0.0), Vec2::new(1.0, 0.0));
    let b = platform(&mut world, Vec2::new(3.0, 0.0), Vec2::new(-1.0, 0.0));
    world
        .add_body(BodyDef::new_static(Vec2::ZERO, Shape::rect(1.0, 5.0)))
        .unwrap();
    // A dynamic body far away, so the contact stage runs.
    world
        .add_body(BodyDef {
            position: Vec2::new(100.0, 0.0),
            shape: Some(Shape::circle(0.5)),
            ..Default::default()
        })
        .unwrap();
    // They pass through each other and through the wall, with no contact
    // at any tick (they overlap from 1 s to 5 s).
    for tick in 0..360 {
        world.step(DT);
        let touching = |id| world.contacts().any(|c| c.a == id || c.b == id);
        assert!(!touching(a) && !touching(b), "tick {tick}");
    }
    assert!((pos(&world, a).x - 3.0).abs() < 1e-3);
    assert!((pos(&world, b).x + 3.0).abs() < 1e-3);
}

#[test]
fn a_kinematic_sensor_sees_a_kinematic_body_pass() {
    let mut world = World::default();
    let sensor = world
        .add_body(
            BodyDef::new_kinematic(Vec2::new(-3.0, 0.0), Shape::rect(1.0, 1.0), Vec2::X)
                .as_sensor(),
        )
        .unwrap();
    let k = platform(&mut world, Vec2::new(3.0, 0.0), Vec2::new(-1.0, 0.0));
    // A dynamic body far away, so the contact stage runs.
    let far = BodyDef::new_dynamic(Vec2::new(100.0, 0.0), Shape::circle(0.5));
    world.add_body(far).unwrap();
    let mut seen = 0;
    for _ in 0..360 {
        world.step(DT);
        seen += usize::from(
            world
                .sensor_overlaps()
                .iter()
                .any(|p| (p.sensor, p.visitor) == (sensor, k)),
        );
    }
    // Their 1 m and 4 m boxes overlap while 2.5 m or less apart, closing
    // at 2 m/s: 2.5 s, 150 ticks.
    assert!((148..=152).contains(&seen), "{seen} ticks");
}

#[test]
fn a_kinematic_body_is_interpolated() {
    let mut world = World::new(WorldSettings {
        interpolation: true,
        ..Default::default()
    })
    .unwrap();
    let k = platform(&mut world, Vec2::ZERO, Vec2::new(6.0, 0.0));
    world.step(0.5);
    assert_eq!(
        world.interpolated_position(k, 0.5),
        Some(Vec2::new(1.5, 0.0))
    );
}

#[test]
fn riders_of_a_moving_platform_stay_awake_and_of_a_stopped_one_sleep() {
    let mut world = World::default();
    let k = platform(&mut world, Vec2::ZERO, Vec2::new(0.5, 0.0));
    let r = rider(&mut world, Vec2::ZERO, Vec2::new(0.5, 0.0));
    for _ in 0..180 {
        world.step(DT);
    }
    assert_eq!(world.is_asleep(r), Some(false), "moving: awake");
    world.set_velocity(k, Vec2::ZERO);
    for _ in 0..180 {
        world.step(DT);
    }
    assert_eq!(world.is_asleep(r), Some(true), "stopped: asleep");
    assert_eq!(world.is_asleep(k), Some(true));
    // Starting it again wakes the rider, which is carried along.
    world.set_velocity(k, Vec2::new(0.5, 0.0));
    let before = pos(&world, r);
    for _ in 0..60 {
        world.step(DT);
    }
    assert_eq!(world.is_asleep(r), Some(false));
    assert!(pos(&world, r).x - before.x > 0.4, "carried again");
}

#[test]
fn a_snapshot_with_a_kinematic_body_resumes_bit_for_bit() {
    let mut world = World::default();
    let k = platform(&mut world, Vec2::ZERO, Vec2::new(1.0, 0.5));
    rider(&mut world, Vec2::ZERO, Vec2::ZERO);
    for _ in 0..30 {
        world.step(DT);
    }
    let mut copy = World::from_snapshot(world.snapshot()).unwrap();
    for _ in 0..90 {
        world.step(DT);
        copy.step(DT);
    }
    assert_eq!(world.state_hash(), copy.state_hash());
    assert_eq!(copy.body(k).unwrap().kind, BodyKind::Kinematic);
    // Energy and momentum leave out the body of infinite mass.
    assert!(world.kinetic_energy().is_finite());
    assert!(world.momentum().iter().all(|p| p.is_finite()));
}

/// Drives the platform along `path(t)` with `set_kinematic_target`, as a
/// game drives a lift, for `ticks` ticks; returns the rider's offset from
/// the platform after each tick.
fn ride(path: impl Fn(f32) -> Vec2, ticks: usize) -> (World, BodyId, Vec<Vec2>) {
    let mut world = World::default();
    let k = platform(&mut world, path(0.0), Vec2::ZERO);
    // The rider starts with the platform's velocity.
    let v0 = (path(DT) - path(0.0)) / DT;
    let r = rider(&mut world, path(0.0), v0);
    world.set_velocity(k, v0);
    let offsets = (1..=ticks)
        .map(|tick| {
            world.set_kinematic_target(k, path(tick as f32 * DT), DT);
            world.step(DT);
            pos(&world, r) - pos(&world, k)
        })
        .collect();
    (world, r, offsets)
}

#[test]
fn a_lift_going_up_and_down_at_3_m_s_keeps_its_rider_without_bouncing_or_sinking() {
    // y = A sin(w t): top speed A w = 3 m/s, top acceleration A w² = 7.5
    // m/s², less than free fall, so the rider is never left behind.
    let w = 2.5;
    let a = 3.0 / w;
    let (world, r, offsets) = ride(|t| Vec2::new(0.0, a * (w * t).sin()), 600);
    let rest = 0.25 + 0.5;
    for (tick, o) in offsets.iter().enumerate() {
        let gap = o.y - rest;
        assert!(gap < 0.01, "tick {tick}: lifted off by {gap} m");
        assert!(gap > -0.0075, "tick {tick}: sank {} m", -gap);
        assert!(o.x.abs() < 0.01, "tick {tick}: slid {} m", o.x);
    }
    assert!(world.is_standing(r, 0.8));
}

/// The rider's lag behind a platform driven along `path`, as Coulomb
/// friction gives it when the platform's velocity changes once a tick
/// (`set_kinematic_target`): in each of `substeps` substeps of `h` the
/// rider's velocity moves towards the platform's by at most `mu g h` (the
/// friction impulse the weight's impulse allows), and the rider then moves
/// at its new velocity. Returns the rider's offset from where it started on
/// the platform after each tick (negative: behind). As `substeps`
/// grows this tends to the exact lag of a block dragged by a belt whose
/// speed jumps once a tick.
fn coulomb_lag(path: impl Fn(f64) -> f64, ticks: usize, substeps: usize, mu_g: f64) -> Vec<f64> {
    let dt = f64::from(DT);
    let h = dt / substeps as f64;
    let mut v = (path(dt) - path(0.0)) / dt;
    let mut x = path(0.0);
    (0..ticks)
        .map(|tick| {
            let t = tick as f64 * dt;
            let platform = (path(t + dt) - path(t)) / dt;
            for _ in 0..substeps {
                v += (platform - v).clamp(-mu_g * h, mu_g * h);
                x += v * h;
            }
            x - path(t + dt)
        })
        .collect()
}

#[test]
fn a_platform_swinging_sideways_carries_its_rider_with_coulomb_s_lag() {
    // x = A sin(w t): top speed 2 m/s, top acceleration 4 m/s², less than
    // mu g = 5.9 m/s², so friction holds the rider. But the platform's
    // velocity changes once per tick (up to 0.067 m/s), and friction takes
    // most of a tick to pass a change on: the rider lags while the platform
    // speeds up and gives the lag back as it slows, with no drift.
    let w = 2.0;
    let a = 2.0 / w;
    let (world, r, offsets) = ride(|t| Vec2::new(a * (w * t).sin(), 0.0), 400);
    let start = offsets[0];
    let lag: Vec<f32> = offsets.iter().map(|o| o.x - start.x).collect();
    for (tick, o) in offsets.iter().enumerate() {
        assert!((o.y - 0.75).abs() < 0.0075, "tick {tick}: {o}");
    }
    // The lag Coulomb friction gives over the world's substeps, within a
    // hundredth of a millimetre at every tick (0.8 µm at most with the
    // default settings); and never more than the exact (continuous) lag,
    // 17.8 mm.
    let substeps = world.settings().contacts.unwrap().substeps as usize;
    let path = |t: f64| f64::from(a) * (f64::from(w) * t).sin();
    // mu = sqrt(mu_rider mu_platform), the default mix; g from the world.
    let friction = |id| f64::from(world.body(id).unwrap().friction);
    let platform = world
        .bodies()
        .find(|b| b.kind == BodyKind::Kinematic)
        .unwrap();
    let mu = (friction(r) * friction(platform.id)).sqrt();
    let mu_g = mu * f64::from(world.settings().forces.gravity.unwrap().length());
    let expected = coulomb_lag(path, 400, substeps, mu_g);
    let exact = coulomb_lag(path, 400, 1000, mu_g);
    let most = |lags: &[f64]| lags.iter().fold(0.0f64, |m, &l| m.max(l.abs()));
    for (tick, (&got, &want)) in lag.iter().zip(&expected).enumerate() {
        let diff = (f64::from(got) - want).abs();
        assert!(diff < 1e-5, "tick {tick}: lags {got} m, Coulomb {want} m");
    }
    assert!(
        most(&expected) <= most(&exact),
        "{} {}",
        most(&expected),
        most(&exact)
    );
    assert!((0.0175..0.018).contains(&most(&exact)), "{}", most(&exact));
    // Each swing takes pi s (188.5 ticks); near its end the lag is gone.
    for swing in [1.0f32, 2.0] {
        let end = (swing * std::f32::consts::PI / DT) as usize;
        let least = lag[end - 15..end + 5]
            .iter()
            .fold(f32::INFINITY, |m, &l| m.min(l.abs()));
        assert!(least < 0.001, "swing {swing}: {least} m left");
    }
}

#[test]
fn refused_velocities_leave_the_body_as_it_was() {
    let mut world = World::default();
    let k = platform(&mut world, Vec2::ZERO, Vec2::new(1.0, 0.0));
    // Faster than the world's maximum speed (1000 m/s): refused.
    assert!(world.try_set_velocity(k, Vec2::new(3e38, 0.0)).is_err());
    assert!(world.try_set_velocity(k, Vec2::new(2000.0, 0.0)).is_err());
    assert!(
        world
            .try_set_kinematic_target(k, Vec2::new(1e6, 0.0), DT)
            .is_err()
    );
    assert_eq!(world.body(k).unwrap().velocity, Vec2::new(1.0, 0.0));
    // Forces that sum past f32::MAX are refused, not stored as infinity.
    let d = world.add_body(BodyDef::point_mass(Vec2::ZERO)).unwrap();
    world.apply_force(d, Vec2::new(3e38, 0.0));
    world.apply_force(d, Vec2::new(3e38, 0.0));
    assert_eq!(world.stats().rejected_inputs, 1);
    assert!(world.body(d).unwrap().force.is_finite());
    world.step(DT);
    assert!(World::from_snapshot(world.snapshot()).is_ok());
}

#[test]
fn a_platform_held_still_by_its_path_sleeps_with_its_rider() {
    let mut world = World::default();
    let k = platform(&mut world, Vec2::ZERO, Vec2::ZERO);
    let r = rider(&mut world, Vec2::ZERO, Vec2::ZERO);
    for _ in 0..120 {
        // A path at one of its ends: the target is where the platform is.
        world.set_kinematic_target(k, Vec2::ZERO, DT);
        world.step(DT);
    }
    assert_eq!(world.is_asleep(k), Some(true));
    assert_eq!(world.is_asleep(r), Some(true));
    // The path moving on wakes them.
    world.set_kinematic_target(k, Vec2::new(0.1, 0.0), DT);
    assert_eq!(world.is_asleep(r), Some(false));
}

/// A stack of `crates` 1 m crates resting on static ground is pressed
/// `depth` into it by a kinematic press (in one step, from 2 cm above the
/// top), held there for `held` steps, then the press leaves at `leave` m/s
/// the way it came. Returns the crates' largest speed away from the ground
/// once the press leaves, and where each ends, 2 s later, along that way.
fn crushed_then_released(
    sideways: bool,
    crates: usize,
    depth: f32,
    held: u32,
    leave: f32,
) -> (f32, Vec<f32>) {
    // The ground's outward direction: up, or (sideways) +x from a wall,
    // with gravity towards it.
    let out = if sideways { Vec2::X } else { Vec2::Y };
    // A `w` by `h` box along the ground (turned a quarter for a wall).
    let rect = |w: f32, h: f32| {
        if sideways {
            Shape::rect(h, w)
        } else {
            Shape::rect(w, h)
        }
    };
    let mut w = World::default();
    if sideways {
        // Gravity towards the wall: the same scene turned a quarter.
        let mut settings = *w.settings();
        settings.forces.gravity = Some(-out * 9.81);
        w.set_settings(settings).unwrap();
    }
    w.add_body(BodyDef::new_static(-out * 0.5, rect(20.0, 1.0)))
        .unwrap();
    let stack: Vec<BodyId> = (0..crates)
        .map(|k| {
            w.add_body(BodyDef {
                position: out * (0.5 + k as f32),
                shape: Some(Shape::rect(1.0, 1.0)),
                ..Default::default()
            })
            .unwrap()
        })
        .collect();
    let top = crates as f32;
    let press = w
        .add_body(BodyDef::new_kinematic(
            out * (top + 0.02 + 0.25),
            rect(2.0, 0.5),
            Vec2::ZERO,
        ))
        .unwrap();
    w.set_velocity(press, -out * (0.02 + depth) / DT);
    w.step(DT);
    w.set_velocity(press, Vec2::ZERO);
    for _ in 0..held {
        w.step(DT);
    }
    // The press is `depth` into the stack. Nothing stops a kinematic
    // body, and shock propagation holds the crates on the ground, so the
    // press ends inside the top crate rather than the crates inside the
    // ground: either way the crates are crushed.
    let press_bottom = pos(&w, press).dot(out) - 0.25;
    assert!(
        (press_bottom - (top - depth)).abs() < 0.02,
        "pressed {depth} m in"
    );
    let top_crate = pos(&w, stack[crates - 1]).dot(out);
    assert!(
        (top - 0.5 - depth - 0.02..=top - 0.5 + 0.02).contains(&top_crate),
        "the top crate at {top_crate}"
    );
    w.set_velocity(press, out * leave);
    let mut fastest = 0.0f32;
    for _ in 0..120 {
        w.step(DT);
        for &c in &stack {
            fastest = fastest.max(w.body(c).unwrap().velocity.dot(out));
        }
        if pos(&w, press).dot(out) > top + 3.0 {
            w.set_velocity(press, Vec2::ZERO);
        }
    }
    (
        fastest,
        stack.iter().map(|&c| pos(&w, c).dot(out)).collect(),
    )
}

#[test]
fn a_crate_crushed_by_a_press_stays_put_when_the_press_leaves() {
    // One crate, or a stack of two or three, pressed 0.1 or 0.26 m into
    // the ground (down, or sideways into a wall), held, then left at 5 m/s:
    // the crates used to leave with the press at its speed, carried by the
    // impulses the crush had piled up. Now the ground pushes them out and
    // they stay: held, no crate goes faster than 0.04 m/s; released the
    // step after the crush, a stack hops (two crates 0.6 m/s, three
    // 1.45 m/s) and settles.
    for sideways in [false, true] {
        for crates in 1..=3 {
            for (depth, held) in [(0.1, 4), (0.26, 4), (0.1, 0)] {
                let (fastest, end) = crushed_then_released(sideways, crates, depth, held, 5.0);
                let case = format!("sideways {sideways}, {crates} crates, {depth} m, held {held}");
                assert!(fastest < 2.0, "{case}: left at {fastest} m/s");
                for (k, at) in end.iter().enumerate() {
                    let rest = 0.5 + k as f32;
                    assert!((at - rest).abs() < 0.02, "{case}: crate {k} ended at {at}");
                }
            }
        }
    }
}

#[test]
fn crates_riding_a_lift_keep_riding_it() {
    // A stack on a lift is pressed by the lift but against nothing: its
    // contacts keep their impulses, and the stack rides up with the lift.
    let mut w = World::default();
    let lift = platform(&mut w, Vec2::ZERO, Vec2::ZERO);
    let first = rider(&mut w, Vec2::ZERO, Vec2::ZERO);
    let second = rider(&mut w, Vec2::new(0.0, 1.0), Vec2::ZERO);
    for tick in 0..180 {
        let v = if (30..90).contains(&tick) { 2.0 } else { 0.0 };
        w.set_velocity(lift, Vec2::new(0.0, v));
        w.step(DT);
        // Riding once the lift is up to speed, and resting on it again
        // after the hop its stop gives them (2 m/s: 0.2 m up and down).
        if (40..90).contains(&tick) || tick >= 170 {
            let top = pos(&w, lift).y + 0.25;
            let gaps = [
                pos(&w, first).y - (top + 0.5),
                pos(&w, second).y - (top + 1.5),
            ];
            assert!(gaps.iter().all(|g| g.abs() < 0.02), "tick {tick}: {gaps:?}");
        }
    }
    assert!((pos(&w, lift).y - 2.0).abs() < 1e-4);
}

/// Drives `press` down by `depth` in one step (through what it meets),
/// then holds it still for `held` steps.
fn press_down(w: &mut World, press: BodyId, depth: f32, held: u32) {
    w.set_velocity(press, Vec2::new(0.0, -depth / DT));
    w.step(DT);
    w.set_velocity(press, Vec2::ZERO);
    for _ in 0..held {
        w.step(DT);
    }
}

/// Steps `ticks` times; the fastest any of `bodies` rose, m/s.
fn fastest_rise(w: &mut World, bodies: &[BodyId], ticks: u32) -> f32 {
    let mut fastest = 0.0f32;
    for _ in 0..ticks {
        w.step(DT);
        for &b in bodies {
            fastest = fastest.max(w.body(b).unwrap().velocity.y);
        }
    }
    fastest
}

/// A world with ground under y = 0 and a 1 m crate resting on it.
fn crate_on_ground() -> (World, BodyId) {
    let mut w = World::default();
    add_ground(&mut w, 20.0);
    let def = BodyDef::new_dynamic(Vec2::new(0.0, 0.5), Shape::rect(1.0, 1.0));
    let crate_ = w.add_body(def).unwrap();
    (w, crate_)
}

#[test]
fn kinematic_jaws_gripping_a_crate_lift_it_and_a_held_press_keeps_its_contacts() {
    // Two jaws close 1 cm into the sides of a crate on the ground, then
    // carry it: friction holds the crate between them (it would drop if
    // the impulses the grip piles up were let go of).
    let (mut w, crate_) = crate_on_ground();
    let jaw = |w: &mut World, side: f32| {
        let def = BodyDef::new_kinematic(
            Vec2::new(side * 0.75, 0.6),
            Shape::rect(0.5, 0.8),
            Vec2::new(-side * 0.01 / DT, 0.0),
        );
        w.add_body(def).unwrap()
    };
    let jaws = [jaw(&mut w, -1.0), jaw(&mut w, 1.0)];
    w.step(DT);
    // Up for half a second, up and sideways for half a second, then
    // sideways (a claw machine): the crate keeps to the jaws all along.
    for (velocity, ticks) in [
        (Vec2::new(0.0, 2.0), 30),
        (Vec2::new(2.0, 2.0), 30),
        (Vec2::X * 2.0, 30),
    ] {
        for &j in &jaws {
            w.set_velocity(j, velocity);
        }
        for _ in 0..ticks {
            w.step(DT);
            let held = pos(&w, jaws[0]) + Vec2::new(0.75, -0.1);
            let off = pos(&w, crate_) - held;
            assert!(off.length() < 0.1, "the crate slipped {off} from the jaws");
        }
    }

    // A press that drives a crate 0.1 m into the ground and holds still:
    // its contact keeps touching, with an impulse, and ends no contact.
    let (mut w, crate_) = crate_on_ground();
    let press = w
        .add_body(BodyDef::new_kinematic(
            Vec2::new(0.0, 1.27),
            Shape::rect(2.0, 0.5),
            Vec2::new(0.0, -0.12 / DT),
        ))
        .unwrap();
    w.step(DT);
    w.set_velocity(press, Vec2::ZERO);
    for _ in 0..10 {
        w.step(DT);
        assert!(w.events().end.is_empty(), "{:?}", w.events().end);
        let pressing = w
            .contacts_of(crate_)
            .find(|c| c.a == press || c.b == press)
            .expect("the press's contact");
        assert!(pressing.touching);
    }
}

#[test]
fn a_crushed_pyramid_of_crates_stays_put_when_the_press_leaves() {
    // Three rows of crates (3, 2, 1) pressed 0.26 m by a press as wide as
    // the pyramid, held, then left at 5 m/s: the press's push spreads
    // through both branches of the pile to the ground, and every crate
    // starts cold (before, the bottom corners kept their impulses and the
    // pile left at 4.9 m/s).
    let mut w = World::default();
    add_ground(&mut w, 20.0);
    let mut crates = Vec::new();
    for (row, count) in [3, 2, 1].into_iter().enumerate() {
        for k in 0..count {
            let x = (k as f32 - (count - 1) as f32 / 2.0) * 1.02;
            let def = BodyDef::new_dynamic(Vec2::new(x, 0.5 + row as f32), Shape::rect(1.0, 1.0));
            crates.push(w.add_body(def).unwrap());
        }
    }
    for _ in 0..60 {
        w.step(DT);
    }
    let press = w
        .add_body(BodyDef::new_kinematic(
            Vec2::new(0.0, 3.27),
            Shape::rect(4.0, 0.5),
            Vec2::ZERO,
        ))
        .unwrap();
    press_down(&mut w, press, 0.28, 4);
    w.set_velocity(press, Vec2::new(0.0, 5.0));
    let fastest = fastest_rise(&mut w, &crates, 60);
    assert!(fastest < 0.5, "a crate left at {fastest} m/s");
}

#[test]
fn a_press_removed_while_it_crushes_leaves_the_crates_in_place() {
    // Two crates pressed 0.1 m into the ground, then the press is removed
    // rather than moved off: the crates used to leave at 3.8 m/s. Shock
    // propagation now holds a vertical stack by itself; the row pressed
    // into a wall (the next test) needs the removal's release.
    let mut w = World::default();
    add_ground(&mut w, 20.0);
    let crates: Vec<BodyId> = (0..2)
        .map(|k| {
            let def = BodyDef::new_dynamic(Vec2::new(0.0, 0.5 + k as f32), Shape::rect(1.0, 1.0));
            w.add_body(def).unwrap()
        })
        .collect();
    let press = w
        .add_body(BodyDef::new_kinematic(
            Vec2::new(0.0, 2.27),
            Shape::rect(2.0, 0.5),
            Vec2::ZERO,
        ))
        .unwrap();
    press_down(&mut w, press, 0.12, 0);
    let pressed = w.contacts_of(crates[1]).count();
    w.remove_body(press).unwrap();
    // The last step's contacts are still reported as they were.
    assert_eq!(w.contacts_of(crates[1]).count(), pressed);
    let fastest = fastest_rise(&mut w, &crates, 60);
    assert!(fastest < 2.0, "a crate left at {fastest} m/s");
    for (k, &c) in crates.iter().enumerate() {
        let y = pos(&w, c).y;
        assert!((y - (0.5 + k as f32)).abs() < 0.02, "crate {k} at {y}");
    }
}

#[test]
fn a_press_removed_while_it_crushes_a_row_into_a_wall_leaves_the_row_in_place() {
    // One to three crates in a row on the ground, pushed 0.12 or 0.28 m
    // into a wall by a kinematic press in one step and held there, then the
    // press is removed; with gravity (across the row) or without. Contacts
    // off the vertical get no help from shock propagation, so without
    // `released_by_removal` the piled-up impulses sent a row of two or
    // three off at 3.5-18 m/s.
    for gravity in [true, false] {
        for crates in 1..=3 {
            for depth in [0.12, 0.28] {
                for held in [1, 4] {
                    let case =
                        format!("gravity {gravity}, {crates} crates, {depth} m, held {held}");
                    let mut w = World::default();
                    if !gravity {
                        let mut settings = *w.settings();
                        settings.forces.gravity = None;
                        w.set_settings(settings).unwrap();
                    }
                    add_ground(&mut w, 20.0);
                    let wall = BodyDef::new_static(Vec2::new(-0.5, 2.0), Shape::rect(1.0, 4.0));
                    w.add_body(wall).unwrap();
                    let row: Vec<BodyId> = (0..crates)
                        .map(|k| {
                            let at = Vec2::new(0.5 + k as f32, 0.5);
                            w.add_body(BodyDef::new_dynamic(at, Shape::rect(1.0, 1.0)))
                                .unwrap()
                        })
                        .collect();
                    let press = w
                        .add_body(BodyDef::new_kinematic(
                            Vec2::new(crates as f32 + 0.27, 0.6),
                            Shape::rect(0.5, 0.8),
                            Vec2::new(-(0.02 + depth) / DT, 0.0),
                        ))
                        .unwrap();
                    w.step(DT);
                    w.set_velocity(press, Vec2::ZERO);
                    for _ in 0..held {
                        w.step(DT);
                    }
                    w.remove_body(press).unwrap();
                    let mut fastest = 0.0f32;
                    for _ in 0..60 {
                        w.step(DT);
                        for &c in &row {
                            fastest = fastest.max(w.body(c).unwrap().velocity.x.abs());
                        }
                    }
                    assert!(fastest < 0.1, "{case}: a crate left at {fastest} m/s");
                    for (k, &c) in row.iter().enumerate() {
                        let x = pos(&w, c).x;
                        assert!(
                            (x - (0.5 + k as f32)).abs() < 0.02,
                            "{case}: crate {k} at {x}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn a_press_shearing_off_sideways_does_not_launch_what_it_crushed() {
    // Pressed 0.26 m into the ground, held, then the press slides off
    // sideways at 5 m/s: the crate used to leave at 9-25 m/s when the press
    // cleared its top.
    let (mut w, crate_) = crate_on_ground();
    let press = w
        .add_body(BodyDef::new_kinematic(
            Vec2::new(0.0, 1.27),
            Shape::rect(2.0, 0.5),
            Vec2::ZERO,
        ))
        .unwrap();
    press_down(&mut w, press, 0.28, 4);
    w.set_velocity(press, Vec2::new(5.0, 0.0));
    let fastest = fastest_rise(&mut w, &[crate_], 120);
    assert!(fastest < 2.0, "the crate left at {fastest} m/s");
    assert!(
        (pos(&w, crate_).y - 0.5).abs() < 0.02,
        "ended at {}",
        pos(&w, crate_)
    );
}
