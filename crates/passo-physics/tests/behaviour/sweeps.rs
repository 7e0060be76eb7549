//! Where a swept body stops: a slop short of the first thing on its path,
//! seen from where that thing ends the step, exactly.

use crate::support::weightless_world;
use passo_physics::constants::{LINEAR_SLOP, SPECULATIVE_REACH};
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, BodyId, Shape, World};

const DT: f32 = 1.0 / 60.0;
const RADIUS: f32 = 0.1;

/// A thin wall (2 cm) whose face toward -x is at `face`, static or moving
/// along x at `speed`.
fn wall(world: &mut World, face: f32, speed: Option<f32>) -> BodyId {
    let centre = Vec2::new(face + 0.01, 0.0);
    let def = match speed {
        None => BodyDef::new_static(centre, Shape::rect(0.02, 4.0)),
        Some(v) => BodyDef::new_kinematic(centre, Shape::rect(0.02, 4.0), Vec2::new(v, 0.0)),
    };
    world.add_body(def).unwrap()
}

/// A ball of radius `RADIUS` at the origin going along +x at `speed`.
fn ball(world: &mut World, speed: f32) -> BodyId {
    let def = BodyDef::new_dynamic(Vec2::ZERO, Shape::circle(RADIUS))
        .with_velocity(Vec2::new(speed, 0.0));
    world.add_body(def).unwrap()
}

#[test]
fn a_swept_body_stops_a_slop_short_of_the_nearest_wall_on_its_path() {
    // Three thin static walls across the path, added in every order: the
    // ball, far beyond its reach in one step, stops at the nearest, its
    // velocity kept (the contact it meets next step stops it).
    let faces = [3.0, 5.0, 8.0];
    let orders = [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ];
    for speed in [300.0, 700.0, 1_000.0] {
        assert!(speed * DT > 3.0 + SPECULATIVE_REACH * RADIUS);
        for order in orders {
            let mut world = weightless_world();
            for k in order {
                wall(&mut world, faces[k], None);
            }
            let b = ball(&mut world, speed);
            world.step(DT);
            let body = world.body(b).unwrap();
            let expected = 3.0 - RADIUS - LINEAR_SLOP;
            let case = format!("{speed} m/s, walls added in order {order:?}");
            assert!(
                (body.position.x - expected).abs() < 1e-4,
                "{case}: at {}",
                body.position
            );
            assert_eq!(body.velocity, Vec2::new(speed, 0.0), "{case}");
            assert_eq!(world.stats().swept_stops, 1, "{case}");
        }
    }
}

#[test]
fn a_swept_body_stops_a_slop_short_of_where_a_moving_wall_ends_the_step() {
    // A kinematic wall coming towards the ball, or going away slower: the
    // ball meets it on the way and ends the step carried with it, a slop
    // short of its face where the wall ends the step (on the way, so the
    // slop is along the relative travel).
    for speed in [300.0, 900.0] {
        for wall_speed in [-240.0, -60.0, -5.0, 5.0, 60.0] {
            let mut world = weightless_world();
            let w = wall(&mut world, 3.0, Some(wall_speed));
            let b = ball(&mut world, speed);
            world.step(DT);
            let face = world.body(w).unwrap().position.x - 0.01;
            assert!((face - (3.0 + wall_speed * DT)).abs() < 1e-4);
            let x = world.body(b).unwrap().position.x;
            // A wall this fast reaches the ball with its own contacts, which
            // stop the ball touching it; slower ones, by a sweep.
            let swept = wall_speed > -200.0;
            assert_eq!(world.stats().swept_stops, u64::from(swept));
            let expected = face - RADIUS - if swept { LINEAR_SLOP } else { 0.0 };
            assert!(
                (x - expected).abs() < 1e-4,
                "{speed} m/s at a wall moving {wall_speed} m/s: at {x}, not {expected}"
            );
        }
    }
}

#[test]
fn each_stop_is_counted_once() {
    // A bullet at a free plank (stopped in the second pass, against dynamic
    // bodies), and a fast body at a wall (the first pass): one stop each.
    let mut world = weightless_world();
    let plank = BodyDef::new_dynamic(Vec2::new(5.0, 0.0), Shape::rect(0.02, 2.0));
    world.add_body(plank).unwrap();
    let bullet = BodyDef {
        bullet: true,
        ..BodyDef::new_dynamic(Vec2::ZERO, Shape::circle(RADIUS))
            .with_velocity(Vec2::new(600.0, 0.0))
    };
    let shot = world.add_body(bullet).unwrap();
    world.step(DT);
    assert_eq!(world.stats().swept_stops, 1);
    let x = world.body(shot).unwrap().position.x;
    assert!(
        (x - (4.99 - RADIUS - LINEAR_SLOP)).abs() < 1e-4,
        "the bullet at {x}"
    );
    let mut world = weightless_world();
    wall(&mut world, 5.0, None);
    ball(&mut world, 600.0);
    ball(&mut world, 600.0);
    world.step(DT);
    assert_eq!(world.stats().swept_stops, 2);
}
