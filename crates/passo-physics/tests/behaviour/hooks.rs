//! Contact hooks: a conveyor carries at its belt speed, a filter and a
//! disabled contact let bodies through, friction and restitution change
//! where a hook says, and hooks keep the bits the same.

use crate::support::add_ground;
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, BodyId, ContactHooks, PairInfo, PreSolve, Shape, World};
use std::sync::Arc;

const DT: f32 = 1.0 / 60.0;

/// Bodies with user data 1 are belts moving at `speed` along x.
struct Belts {
    speed: f32,
}

impl ContactHooks for Belts {
    fn pre_solve(&self, contact: &mut PreSolve) {
        for end in [contact.a, contact.b] {
            if end.user_data == 1 {
                contact.conveyor(end.id, Vec2::new(self.speed, 0.0));
            }
        }
    }
}

#[test]
fn a_conveyor_moves_a_crate_at_its_belt_speed_within_one_percent() {
    for speed in [-3.0f32, 0.5, 2.0, 6.0] {
        for (mass, friction) in [(1.0f32, 0.6f32), (50.0, 0.3), (0.2, 1.0)] {
            for shape in [Shape::rect(0.6, 0.4), Shape::circle(0.3)] {
                let mut world = World::default();
                let belt = BodyDef::new_static(Vec2::new(0.0, -0.5), Shape::rect(400.0, 1.0));
                world.add_body(belt.with_user_data(1)).unwrap();
                let h = shape.half_extents().y;
                let def = BodyDef {
                    mass,
                    friction,
                    ..BodyDef::new_dynamic(Vec2::new(0.0, h), shape)
                };
                let body = world.add_body(def).unwrap();
                world.set_contact_hooks(Some(Arc::new(Belts { speed })));
                for _ in 0..180 {
                    world.step(DT);
                }
                let v = world.body(body).unwrap().velocity;
                assert!(
                    (v.x - speed).abs() <= 0.01 * speed.abs(),
                    "{speed} m/s belt, {mass} kg, mu {friction}, {shape:?}: {v}"
                );
                assert!(v.y.abs() < 1e-3, "it stays on the belt: {v}");
            }
        }
    }
}

#[test]
fn a_conveyor_body_carries_what_lies_on_it_without_a_hook() {
    for speed in [-4.0f32, 1.0, 3.0] {
        let mut world = World::default();
        let belt = BodyDef {
            conveyor: Some(Vec2::new(speed, 0.0)),
            ..BodyDef::new_static(Vec2::new(0.0, -0.5), Shape::rect(400.0, 1.0))
        };
        let belt = world.add_body(belt).unwrap();
        let parcel = world
            .add_body(BodyDef::new_dynamic(
                Vec2::new(0.0, 0.2),
                Shape::rect(0.6, 0.4),
            ))
            .unwrap();
        for _ in 0..180 {
            world.step(DT);
        }
        let v = world.body(parcel).unwrap().velocity.x;
        assert!(
            (v - speed).abs() <= 0.01 * speed.abs(),
            "{speed} m/s belt: {v}"
        );
        // Stopped, the belt lets the parcel slide to rest.
        world.set_conveyor(belt, None).unwrap();
        for _ in 0..180 {
            world.step(DT);
        }
        let v = world.body(parcel).unwrap().velocity.x;
        assert!(v.abs() < 1e-3, "a stopped belt: {v}");
    }
}

/// Bodies whose user data is odd pass through each other; a body with
/// user data 10 has ice under it (friction 0); one with 20 bounces fully.
struct Rules;

impl ContactHooks for Rules {
    fn filter_pair(&self, a: &PairInfo, b: &PairInfo) -> bool {
        !(a.user_data % 2 == 1 && b.user_data % 2 == 1)
    }

    fn pre_solve(&self, contact: &mut PreSolve) {
        let data = [contact.a.user_data, contact.b.user_data];
        if data.contains(&10) {
            contact.friction = 0.0;
        }
        if data.contains(&20) {
            contact.restitution = 1.0;
        }
        if data.contains(&30) {
            contact.enabled = false;
        }
    }
}

fn ball(world: &mut World, at: Vec2, user_data: u64) -> BodyId {
    let def = BodyDef::new_dynamic(at, Shape::circle(0.25)).with_user_data(user_data);
    world.add_body(def).unwrap()
}

#[test]
fn a_filtered_pair_and_a_disabled_contact_pass_through() {
    let mut world = World::default();
    let ground = BodyDef::new_static(Vec2::new(0.0, -0.5), Shape::rect(40.0, 1.0));
    world.add_body(ground.with_user_data(1)).unwrap();
    let ghost = ball(&mut world, Vec2::new(-2.0, 1.0), 3);
    let solid = ball(&mut world, Vec2::new(0.0, 1.0), 2);
    let phantom = ball(&mut world, Vec2::new(2.0, 1.0), 30);
    world.set_contact_hooks(Some(Arc::new(Rules)));
    for _ in 0..60 {
        world.step(DT);
    }
    let y = |id| world.body(id).unwrap().position.y;
    assert!(
        y(ghost) < -2.0,
        "odd on odd: it falls through, at {}",
        y(ghost)
    );
    assert!(
        y(phantom) < -2.0,
        "disabled: it falls through, at {}",
        y(phantom)
    );
    assert!(
        (y(solid) - 0.25).abs() < 0.01,
        "even: it rests, at {}",
        y(solid)
    );
    assert!(
        world
            .contacts()
            .all(|c| c.a != ghost && c.b != ghost && c.a != phantom && c.b != phantom)
    );
    world.set_contact_hooks(None);
    assert!(!world.has_contact_hooks());
}

#[test]
fn a_filter_hides_a_body_from_a_sensor() {
    let mut world = World::default();
    let sensor = BodyDef::new_static(Vec2::ZERO, Shape::rect(4.0, 4.0)).as_sensor();
    let sensor = world.add_body(sensor.with_user_data(1)).unwrap();
    let seen = ball(&mut world, Vec2::new(-1.0, 0.0), 2);
    let unseen = ball(&mut world, Vec2::new(1.0, 0.0), 5);
    world.set_contact_hooks(Some(Arc::new(Rules)));
    world.step(DT);
    let visitors: Vec<_> = (world.sensor_overlaps().iter())
        .filter(|p| p.sensor == sensor)
        .map(|p| p.visitor)
        .collect();
    assert!(visitors.contains(&seen));
    assert!(!visitors.contains(&unseen));
}

#[test]
fn a_hook_sets_friction_and_restitution() {
    let mut world = World::default();
    add_ground(&mut world, 100.0);
    let on_ice = ball(&mut world, Vec2::new(0.0, 0.25), 10);
    let on_rock = ball(&mut world, Vec2::new(-40.0, 0.25), 0);
    let bouncer = ball(&mut world, Vec2::new(-20.0, 3.25), 20);
    world.set_velocity(on_ice, Vec2::new(3.0, 0.0));
    world.set_velocity(on_rock, Vec2::new(3.0, 0.0));
    world.set_contact_hooks(Some(Arc::new(Rules)));
    let mut highest_late = 0.0f32;
    for n in 0..240 {
        world.step(DT);
        if n > 120 {
            highest_late = highest_late.max(world.body(bouncer).unwrap().position.y);
        }
    }
    let v = |id| world.body(id).unwrap().velocity.x;
    assert!((v(on_ice) - 3.0).abs() < 1e-3, "no friction: {}", v(on_ice));
    assert!(v(on_rock) < 0.1, "friction stops it: {}", v(on_rock));
    // An elastic ball dropped from 3 m keeps bouncing to about 3 m.
    assert!(
        highest_late > 3.25 - 0.1,
        "it bounces back up: {highest_late}"
    );
}

#[test]
fn hooks_keep_the_same_bits_on_any_thread_count_and_after_a_restore() {
    let build = || {
        let mut world = World::default();
        let belt = BodyDef::new_static(Vec2::new(0.0, -0.5), Shape::rect(400.0, 1.0));
        world.add_body(belt.with_user_data(1)).unwrap();
        for i in 0..300 {
            let at = Vec2::new((i % 30) as f32 * 0.7 - 10.0, 0.5 + (i / 30) as f32 * 0.7);
            world
                .add_body(BodyDef::new_dynamic(at, Shape::rect(0.5, 0.5)).with_user_data(i % 3))
                .unwrap();
        }
        world.set_contact_hooks(Some(Arc::new(Belts { speed: 1.5 })));
        world
    };
    let (mut one, mut two) = (build(), build());
    one.set_parallel(false);
    two.set_parallel(true);
    for _ in 0..90 {
        one.step(DT);
        two.step(DT);
    }
    assert_eq!(one.state_hash(), two.state_hash());
    let mut restored = World::from_snapshot(one.snapshot()).unwrap();
    assert!(!restored.has_contact_hooks(), "hooks are code: not saved");
    restored.set_contact_hooks(Some(Arc::new(Belts { speed: 1.5 })));
    for _ in 0..60 {
        one.step(DT);
        restored.step(DT);
    }
    assert_eq!(one.state_hash(), restored.state_hash());
}
