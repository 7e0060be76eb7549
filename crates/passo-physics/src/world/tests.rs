//! Tests of `world`.

use super::*;
use crate::Shape;

fn ball(x: f32) -> BodyDef {
    BodyDef::point_mass(Vec2::new(x, 0.0))
}

#[test]
fn removed_ids_never_reach_the_body_that_reuses_the_slot() {
    let mut world = World::default();
    let a = world.add_body(ball(1.0)).unwrap();
    let b = world.add_body(ball(2.0)).unwrap();
    let removed = world.remove_body(a).unwrap();
    assert_eq!(removed.position.x, 1.0);
    let c = world.add_body(ball(3.0)).unwrap();
    assert_eq!(c.index(), a.index(), "the slot is reused");
    assert_ne!(c, a);
    assert_eq!(world.body(a), None);
    assert!(world.remove_body(a).is_none());
    assert_eq!(
        world.try_set_velocity(a, Vec2::ONE),
        Err(PhysicsError::StaleBody(a))
    );
    assert_eq!(world.body(b).unwrap().position.x, 2.0);
    assert_eq!(world.body(c).unwrap().position.x, 3.0);
    assert_eq!(world.len(), 2);
}

#[test]
fn swap_remove_keeps_every_other_id_pointing_at_its_body() {
    let mut world = World::default();
    let ids: Vec<_> = (0..10)
        .map(|i| world.add_body(ball(i as f32)).unwrap())
        .collect();
    for &id in ids.iter().step_by(3) {
        world.remove_body(id).unwrap();
    }
    for (i, &id) in ids.iter().enumerate() {
        match world.body(id) {
            Some(b) => assert_eq!(b.position.x, i as f32),
            None => assert_eq!(i % 3, 0),
        }
    }
    let order: Vec<_> = world.bodies().map(|b| b.position.x).collect();
    assert_eq!(
        order,
        [1.0, 2.0, 4.0, 5.0, 7.0, 8.0],
        "bodies() is in id order"
    );
}

#[test]
fn static_bodies_never_move_and_ignore_forces() {
    let mut world = World::default();
    let ground = world
        .add_body(BodyDef::new_static(
            Vec2::new(0.0, -1.0),
            Shape::rect(10.0, 1.0),
        ))
        .unwrap();
    world.apply_force(ground, Vec2::new(1e6, 1e6));
    world.apply_impulse(ground, Vec2::new(1e6, 1e6));
    world.set_velocity(ground, Vec2::new(5.0, 5.0));
    for _ in 0..100 {
        world.step(1.0 / 60.0);
    }
    let b = world.body(ground).unwrap();
    assert_eq!(b.position, Vec2::new(0.0, -1.0));
    assert_eq!(b.velocity, Vec2::ZERO);
    assert_eq!(b.mass, f32::INFINITY);
    assert_eq!(world.kinetic_energy(), 0.0);
}

#[test]
fn bad_body_definitions_are_rejected_with_the_field_named() {
    let mut world = World::default();
    let cases = [
        (
            BodyDef {
                mass: 0.0,
                ..ball(0.0)
            },
            "BodyDef::mass must be > 0, got 0",
        ),
        (
            BodyDef {
                mass: -2.0,
                ..ball(0.0)
            },
            "BodyDef::mass must be > 0, got -2",
        ),
        (
            BodyDef {
                mass: f32::NAN,
                ..ball(0.0)
            },
            "BodyDef::mass must be finite (got NaN or infinity)",
        ),
        (
            BodyDef {
                position: Vec2::new(f32::INFINITY, 0.0),
                ..ball(0.0)
            },
            "BodyDef::position must be finite (got NaN or infinity)",
        ),
        (
            BodyDef {
                velocity: Vec2::new(0.0, f32::NAN),
                ..ball(0.0)
            },
            "BodyDef::velocity must be finite (got NaN or infinity)",
        ),
        (
            BodyDef {
                restitution: 1.5,
                ..ball(0.0)
            },
            "BodyDef::restitution must be in [0, 1], got 1.5",
        ),
        (
            BodyDef {
                shape: Some(Shape::circle(0.0)),
                ..ball(0.0)
            },
            "Shape::Circle::radius must be > 0, got 0",
        ),
        (
            BodyDef {
                max_speed: Some(-1.0),
                ..ball(0.0)
            },
            "BodyDef::max_speed must be > 0, got -1",
        ),
    ];
    for (def, message) in cases {
        let err = world.add_body(def).unwrap_err();
        assert_eq!(err.to_string(), message);
    }
    assert!(world.is_empty(), "nothing was added");
    // A static body needs no mass.
    let ground = BodyDef {
        mass: 0.0,
        ..BodyDef::new_static(Vec2::ZERO, Shape::circle(1.0))
    };
    assert!(world.add_body(ground).is_ok());
}
