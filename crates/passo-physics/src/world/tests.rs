//! Tests of `world`.

use super::*;
use crate::Shape;
use crate::body::census::BodyCensus;

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
    // Ground from y = -1.5 to -0.5, and a 1 kg box resting on it.
    let ground_at = Vec2::new(0.0, -1.0);
    let ground = world
        .add_body(BodyDef::new_static(ground_at, Shape::rect(10.0, 1.0)))
        .unwrap();
    let crate_at = Vec2::new(0.0, 0.0);
    let boxed = world
        .add_body(BodyDef::new_dynamic(crate_at, Shape::rect(1.0, 1.0)))
        .unwrap();
    assert!(world.active_stages().contains(&crate::Stage::Contacts));

    // The `try_` forms ignore a static body: they succeed and change
    // nothing. A value they refuse is still refused, with its reason.
    let push = Vec2::new(1e3, 1e3);
    assert_eq!(world.try_apply_force(ground, push), Ok(()));
    assert_eq!(world.try_apply_impulse(ground, push), Ok(()));
    assert_eq!(world.try_set_velocity(ground, Vec2::new(5.0, 5.0)), Ok(()));
    let nan = Vec2::new(f32::NAN, 0.0);
    assert_eq!(
        world.try_apply_force(ground, nan),
        Err(PhysicsError::NonFinite { what: "force" })
    );
    assert_eq!(
        world.try_apply_impulse(ground, nan),
        Err(PhysicsError::NonFinite { what: "impulse" })
    );
    assert_eq!(
        world.try_set_velocity(ground, nan),
        Err(PhysicsError::NonFinite { what: "velocity" })
    );
    assert_eq!(world.stats().rejected_inputs, 0, "try_ calls count nothing");
    // The per-tick forms count only what their `try_` form refuses.
    world.apply_force(ground, push);
    world.apply_impulse(ground, push);
    world.set_velocity(ground, push);
    assert_eq!(world.stats().rejected_inputs, 0, "ignoring is not refusing");
    world.apply_force(ground, nan);
    assert_eq!(world.stats().rejected_inputs, 1);

    for n in 0..300 {
        world.apply_force(ground, push);
        world.apply_impulse(ground, push);
        world.set_velocity(ground, push);
        world.step(1.0 / 60.0);
        if n < 30 {
            // Awake, the box is solved against the ground every step.
            let contacts: Vec<_> = world.contacts_of(ground).collect();
            assert_eq!(contacts.len(), 1, "step {n}");
            assert_eq!(contacts[0].b, boxed, "step {n}");
        }
    }
    assert_eq!(world.stats().rejected_inputs, 1);
    let g = world.body(ground).unwrap();
    assert_eq!(
        g.position.to_array().map(f32::to_bits),
        ground_at.to_array().map(f32::to_bits)
    );
    assert_eq!(g.velocity, Vec2::ZERO);
    assert_eq!(g.mass, f32::INFINITY);
    // The box rests on the ground, still, and in the end asleep.
    let b = world.body(boxed).unwrap();
    assert!((b.position - crate_at).length() < 0.01, "{}", b.position);
    assert_eq!(b.velocity, Vec2::ZERO);
    assert_eq!(world.standing_on(boxed, 0.8), Some(ground));
    assert_eq!(world.is_asleep(boxed), Some(true));
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

#[test]
fn a_minimum_speed_above_the_maximum_is_refused_wherever_it_comes_from() {
    // The snap tests the speed before the clamp: with a minimum of 10 and a
    // maximum of 5, a body at 7 m/s would stop dead and one at 12 drop to 5.
    let settings = WorldSettings {
        min_speed: 10.0,
        max_speed: 5.0,
        ..WorldSettings::default()
    };
    let err = World::new(settings).unwrap_err().to_string();
    assert!(err.contains("WorldSettings::min_speed"), "{err}");
    let mut world = World::new(WorldSettings {
        max_speed: 5.0,
        ..WorldSettings::default()
    })
    .unwrap();
    let body = |min: Option<f32>, max: Option<f32>| BodyDef {
        min_speed: min,
        max_speed: max,
        ..BodyDef::point_mass(Vec2::ZERO)
    };
    // Its own minimum against the world's maximum, or against its own.
    for def in [body(Some(10.0), None), body(Some(10.0), Some(8.0))] {
        let err = world.add_body(def).unwrap_err().to_string();
        assert!(err.contains("minimum speed") && err.contains("10"), "{err}");
    }
    assert!(world.is_empty());
    let fast = world.add_body(body(Some(10.0), Some(20.0))).unwrap();
    // Kinematic bodies have no speed limits.
    let kinematic = BodyDef {
        kind: BodyKind::Kinematic,
        ..body(Some(10.0), None)
    };
    assert!(world.add_body(kinematic).is_ok());
    // A world maximum below a body's own minimum is refused, and changes
    // nothing.
    let before = *world.settings();
    let slower = WorldSettings {
        max_speed: 4.0,
        min_speed: 12.0,
        ..before
    };
    assert!(world.set_settings(slower).is_err());
    let lower_min = WorldSettings {
        min_speed: 0.5,
        ..before
    };
    world.set_settings(lower_min).unwrap();
    assert_eq!(world.body(fast).unwrap().max_speed, Some(20.0));
    // A body with its own minimum of 3 m/s and the world's maximum: a world
    // maximum of 2 would leave it no speed to move at.
    world.add_body(body(Some(3.0), None)).unwrap();
    let conflict = WorldSettings {
        max_speed: 2.0,
        ..lower_min
    };
    let err = world.set_settings(conflict).unwrap_err().to_string();
    assert!(err.contains("minimum speed") && err.contains('3'), "{err}");
    assert_eq!(world.settings().max_speed, 5.0);
}

/// Random adds, removals and edits of every sort of body, the census
/// checked against a recount after each one (not only after a step, where
/// the world checks it in debug builds).
#[test]
fn the_census_agrees_with_a_recount_after_every_edit() {
    let mut next = crate::testing::uniform(7);
    let mut world = World::default();
    let mut ids = Vec::new();
    let mut sorts_seen = BodyCensus::default();
    for round in 0..600 {
        let r = next();
        if ids.is_empty() || r < 0.45 {
            let kind = match (next() * 3.0) as u32 {
                0 => BodyKind::Static,
                1 => BodyKind::Kinematic,
                _ => BodyKind::Dynamic,
            };
            let def = BodyDef {
                kind,
                position: Vec2::new(next() * 50.0, next() * 50.0),
                shape: (next() < 0.7).then(|| Shape::circle(0.5)),
                restitution: if next() < 0.3 { 0.5 } else { 0.0 },
                max_speed: (next() < 0.2).then_some(30.0),
                ..Default::default()
            };
            ids.push(world.add_body(def).unwrap());
        } else if r < 0.7 {
            let id = ids.swap_remove((next() * ids.len() as f32) as usize % ids.len());
            world.remove_body(id).unwrap();
        } else if r < 0.8 {
            let id = ids[(next() * ids.len() as f32) as usize % ids.len()];
            let restitution = if next() < 0.5 { 0.0 } else { 0.7 };
            world.set_restitution(id, restitution).unwrap();
        } else if r < 0.9 {
            let id = ids[(next() * ids.len() as f32) as usize % ids.len()];
            let seconds = if next() < 0.5 { 0.0 } else { 0.05 };
            world.try_drop_through(id, seconds).unwrap();
        } else {
            world.step(1.0 / 60.0);
        }
        let recount = BodyCensus::recount(&world.dynamic, &world.statics);
        assert_eq!(world.census, recount, "round {round}");
        sorts_seen.add(recount);
    }
    // The sweep reached every count.
    let c = sorts_seen;
    let counts = [
        c.shaped_dynamic,
        c.shaped_static,
        c.bouncy,
        c.dropping,
        c.speed_overrides,
    ];
    assert!(counts.iter().all(|&n| n > 0), "{c:?}");
}
