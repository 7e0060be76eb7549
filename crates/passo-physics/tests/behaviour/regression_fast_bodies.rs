//! Fast bodies made pairs grow with speed: continuous collision grew each
//! body's proxy by its whole travel, so 5 000 circles at 100–500 m/s in a
//! box took 55 ms per tick and 1.9 GB, and a rain stepped at 1 Hz took 1 s
//! per tick and 520 MB. Now speculative contacts reach at most
//! `SPECULATIVE_REACH` of a body's smallest half extent, and a body that
//! moves farther is swept along its path and stopped at its first impact:
//! against static and kinematic bodies, and as a bullet against every body.
//! Nothing tunnels, and pairs stay bounded.

use crate::support::{Rng, max_penetration, weightless_world};
use passo_physics::constants::{LINEAR_SLOP, SPECULATIVE_REACH};
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, BodyKind, Shape, World};

fn wall(world: &mut World, centre: Vec2, size: Vec2) {
    world
        .add_body(BodyDef::new_static(centre, Shape::rect(size.x, size.y)))
        .unwrap();
}

#[test]
fn fast_circles_in_a_closed_box_stay_inside_with_bounded_contacts() {
    let n = 1_000;
    let mut world = weightless_world();
    // A 20 m × 10 m box with walls 1 m thick.
    wall(&mut world, Vec2::new(0.0, -5.5), Vec2::new(22.0, 1.0));
    wall(&mut world, Vec2::new(0.0, 5.5), Vec2::new(22.0, 1.0));
    wall(&mut world, Vec2::new(-10.5, 0.0), Vec2::new(1.0, 10.0));
    wall(&mut world, Vec2::new(10.5, 0.0), Vec2::new(1.0, 10.0));
    let mut rng = Rng::new(7);
    for _ in 0..n {
        let p = Vec2::new(rng.range(-9.5, 9.5), rng.range(-4.5, 4.5));
        let angle = rng.range(0.0, std::f32::consts::TAU);
        let speed = rng.range(100.0, 500.0);
        let def = BodyDef::new_dynamic(p, Shape::circle(0.1))
            .with_velocity(Vec2::new(angle.cos(), angle.sin()) * speed);
        world.add_body(def).unwrap();
    }
    let mut most = 0;
    for _ in 0..120 {
        world.step(1.0 / 60.0);
        most = most.max(world.contacts().count());
        for b in world.bodies().filter(|b| b.kind == BodyKind::Dynamic) {
            let p = b.position;
            // Inside the walls' middle lines: a centre beyond one would be
            // pushed out on the far side.
            assert!(
                p.x.abs() < 10.5 && p.y.abs() < 5.5,
                "{:?} left the box: {p}",
                b.id
            );
        }
    }
    // A body travelling 1.7–8.3 m per step once made a contact with
    // everything along its path. Its reach is now 0.4 m: at 5 bodies per
    // m², about 16 others lie within two reaches and a diameter (π 1.02²
    // × 5), so about 8 contacts per body, whatever the speed.
    assert!(most <= 12 * n, "{most} contacts for {n} bodies");
    assert!(world.stats().swept_stops > 0, "walls stopped swept bodies");
}

#[test]
fn a_rain_at_one_hertz_keeps_bounded_contacts_and_stays_above_the_floor() {
    let mut world = World::default();
    wall(&mut world, Vec2::new(0.0, -0.5), Vec2::new(40.0, 1.0));
    let n = 400;
    for k in 0..n {
        let p = Vec2::new((k % 40) as f32 * 0.25 - 5.0, 2.0 + (k / 40) as f32 * 0.25);
        world
            .add_body(BodyDef::new_dynamic(p, Shape::circle(0.1)))
            .unwrap();
    }
    let mut lowest = f32::MAX;
    for _ in 0..30 {
        world.step(1.0);
        // Each circle meets at most those within two reaches (0.8 m) and a
        // diameter. One-second steps squeeze the pile: its busiest step has
        // at most 50 contacts per circle.
        // (Until the broad phase's corner grid, crowded grid buckets capped
        // that step at 13 805.) Linear in the bodies, where a fast body once
        // met everything along its path.
        assert!(world.contacts().count() <= 50 * n);
        for b in world.bodies().filter(|b| b.kind == BodyKind::Dynamic) {
            assert!(b.position.is_finite());
            lowest = lowest.min(b.position.y);
        }
    }
    // A step of a second is coarse: four substeps of 0.25 s cannot hold a
    // pile ten deep, which sinks into the floor (up to 25 cm here), but
    // nothing falls through it.
    assert!(lowest > -0.5, "a centre sank to {lowest}");
}

/// A circle of radius 0.05 m fired at `speed` along x at a wall 2 cm thick
/// at x = 5 m; returns the largest x it reached.
fn fire_at_thin_wall(speed: f32, hz: f32, kinematic_wall_speed: f32) -> f32 {
    let mut world = weightless_world();
    let wall_def = if kinematic_wall_speed == 0.0 {
        BodyDef::new_static(Vec2::new(5.01, 0.0), Shape::rect(0.02, 4.0))
    } else {
        BodyDef::new_kinematic(
            Vec2::new(5.01, 0.0),
            Shape::rect(0.02, 4.0),
            Vec2::new(kinematic_wall_speed, 0.0),
        )
    };
    let wall = world.add_body(wall_def).unwrap();
    let bullet = world
        .add_body(
            BodyDef::new_dynamic(Vec2::new(-20.0, 0.3), Shape::circle(0.05))
                .with_velocity(Vec2::new(speed, 0.0)),
        )
        .unwrap();
    let mut furthest = f32::MIN;
    for _ in 0..(hz as usize) {
        world.step(1.0 / hz);
        let wall_x = world.body(wall).unwrap().position.x - 0.01;
        let x = world.body(bullet).unwrap().position.x;
        furthest = furthest.max(x - wall_x);
    }
    furthest
}

#[test]
fn a_fast_body_never_passes_a_thin_static_wall_at_any_speed() {
    for speed in [50.0, 400.0, 5_000.0] {
        for hz in [10.0, 30.0, 60.0] {
            let past = fire_at_thin_wall(speed, hz, 0.0);
            assert!(
                past < -0.05 + LINEAR_SLOP,
                "{speed} m/s at {hz} Hz: centre {past} m from the wall"
            );
        }
    }
}

#[test]
fn a_fast_body_meets_a_kinematic_wall_coming_the_other_way() {
    for wall_speed in [-30.0, -200.0] {
        let past = fire_at_thin_wall(300.0, 60.0, wall_speed);
        assert!(
            past < -0.05 + LINEAR_SLOP,
            "wall at {wall_speed} m/s: centre {past} m past the wall's face"
        );
    }
}

/// Fires a circle at 400 m/s at a free dynamic plank 2 cm thick; returns
/// whether it ended on the far side.
fn passes_a_dynamic_plank(bullet: bool) -> bool {
    let mut world = weightless_world();
    let plank = world
        .add_body(BodyDef::new_dynamic(
            Vec2::new(5.0, 0.0),
            Shape::rect(0.02, 2.0),
        ))
        .unwrap();
    let def = BodyDef {
        bullet,
        ..BodyDef::new_dynamic(Vec2::new(-20.0, 0.3), Shape::circle(0.05))
            .with_velocity(Vec2::new(400.0, 0.0))
    };
    let shot = world.add_body(def).unwrap();
    for _ in 0..60 {
        world.step(1.0 / 60.0);
    }
    let x = |id| world.body(id).unwrap().position.x;
    x(shot) > x(plank)
}

#[test]
fn a_bullet_never_passes_a_thin_dynamic_body() {
    assert!(
        !passes_a_dynamic_plank(true),
        "the bullet stopped at the plank"
    );
    // An ordinary fast body is swept against static and kinematic bodies
    // only (as in Box2D): beyond its reach, it may pass a thin dynamic one.
    assert!(passes_a_dynamic_plank(false));
}

#[test]
fn a_bullet_hits_a_fast_body_crossing_its_path() {
    let mut world = weightless_world();
    // A fast box crossing the line of fire, timed to be on it when the
    // bullet passes, and a bullet: both move far beyond their reach.
    let crossing = world
        .add_body(
            BodyDef::new_dynamic(Vec2::new(5.0, -6.0), Shape::rect(0.5, 0.5))
                .with_velocity(Vec2::new(0.0, 120.0)),
        )
        .unwrap();
    let def = BodyDef {
        bullet: true,
        ..BodyDef::new_dynamic(Vec2::new(-5.0, 0.0), Shape::circle(0.05))
            .with_velocity(Vec2::new(200.0, 0.0))
    };
    let shot = world.add_body(def).unwrap();
    for _ in 0..4 {
        world.step(1.0 / 60.0);
    }
    let (a, b) = (world.body(shot).unwrap(), world.body(crossing).unwrap());
    assert!(a.position.x < b.position.x, "the bullet stayed on its side");
    assert!(world.stats().swept_stops > 0);
    assert!(max_penetration(&world) <= 2.0 * LINEAR_SLOP);
}

#[test]
fn a_fast_box_slides_across_flush_tiles_without_catching() {
    let mut world = World::default();
    // 200 tiles of 1 m, flush.
    for k in 0..200 {
        wall(&mut world, Vec2::new(k as f32 + 0.5, -0.5), Vec2::ONE);
    }
    let def = BodyDef {
        friction: 0.0,
        ..BodyDef::new_dynamic(Vec2::new(1.0, 0.1), Shape::rect(0.2, 0.2))
    };
    let body = world.add_body(def).unwrap();
    // Settle, then slide at 60 m/s: 1 m per step, beyond the box's reach
    // (SPECULATIVE_REACH × 0.1 m), so it is swept against the tiles every
    // step and none of their inner faces may stop it.
    for _ in 0..30 {
        world.step(1.0 / 60.0);
    }
    const { assert!(60.0 / 60.0 > SPECULATIVE_REACH * 0.1) };
    world.set_velocity(body, Vec2::new(60.0, 0.0));
    for _ in 0..150 {
        world.step(1.0 / 60.0);
        let b = world.body(body).unwrap();
        if b.position.x > 195.0 {
            break;
        }
        assert!(b.velocity.y.abs() < 1e-4, "vy {}", b.velocity.y);
        assert!((b.velocity.x - 60.0).abs() < 1e-3, "vx {}", b.velocity.x);
    }
    assert!(world.body(body).unwrap().position.x > 150.0);
    assert_eq!(world.stats().swept_stops, 0, "no tile stopped the box");
}

#[test]
fn a_fast_body_lands_on_a_one_way_platform_from_above_and_passes_from_below() {
    let mut world = weightless_world();
    let platform = BodyDef {
        one_way: Some(Vec2::Y),
        ..BodyDef::new_static(Vec2::ZERO, Shape::rect(4.0, 0.1))
    };
    world.add_body(platform).unwrap();
    let falling = world
        .add_body(
            BodyDef::new_dynamic(Vec2::new(-1.0, 10.0), Shape::circle(0.1))
                .with_velocity(Vec2::new(0.0, -200.0)),
        )
        .unwrap();
    let rising = world
        .add_body(
            BodyDef::new_dynamic(Vec2::new(1.0, -10.0), Shape::circle(0.1))
                .with_velocity(Vec2::new(0.0, 200.0)),
        )
        .unwrap();
    for _ in 0..30 {
        world.step(1.0 / 60.0);
    }
    let y = |id| world.body(id).unwrap().position.y;
    assert!(
        (y(falling) - 0.15).abs() < 2.0 * LINEAR_SLOP,
        "landed at {}",
        y(falling)
    );
    assert!(y(rising) > 10.0, "passed through to {}", y(rising));
    assert_eq!(world.body(rising).unwrap().velocity, Vec2::new(0.0, 200.0));
}

#[test]
fn a_fast_kinematic_wall_pushes_a_resting_ball_instead_of_passing_it() {
    // A wall 10 cm thick at 50 m/s moves 0.83 m a step, far beyond its
    // own reach (4 × 5 cm): it is never swept, so its proxy covers its
    // whole travel and it meets the ball in its way.
    let mut world = weightless_world();
    let wall = world
        .add_body(BodyDef::new_kinematic(
            Vec2::new(-5.0, 0.0),
            Shape::rect(0.1, 2.0),
            Vec2::new(50.0, 0.0),
        ))
        .unwrap();
    let ball = world
        .add_body(BodyDef::new_dynamic(Vec2::ZERO, Shape::circle(0.1)))
        .unwrap();
    for _ in 0..12 {
        world.step(1.0 / 60.0);
        let (w, b) = (world.body(wall).unwrap(), world.body(ball).unwrap());
        assert!(
            b.position.x > w.position.x,
            "the ball stays ahead of the wall: {} vs {}",
            b.position.x,
            w.position.x
        );
    }
    assert!(world.body(ball).unwrap().velocity.x >= 50.0 - 1e-3);
}

#[test]
fn a_bullet_is_not_carried_through_a_wall_by_the_body_it_hits() {
    // A crate moving fast at a wall stops at the wall; a bullet behind it
    // meets the crate before the crate meets the wall. It must end where
    // the crate ended, not where the crate would have gone.
    let mut world = weightless_world();
    wall(&mut world, Vec2::new(10.0, 0.0), Vec2::new(1.0, 4.0));
    let crate_ = world
        .add_body(
            BodyDef::new_dynamic(Vec2::new(0.0, 0.0), Shape::rect(0.4, 0.4))
                .with_velocity(Vec2::new(540.0, 0.0)),
        )
        .unwrap();
    let bullet = world
        .add_body(BodyDef {
            bullet: true,
            ..BodyDef::new_dynamic(Vec2::new(-3.0, 0.0), Shape::circle(0.05))
                .with_velocity(Vec2::new(800.0, 0.0))
        })
        .unwrap();
    for _ in 0..3 {
        world.step(1.0 / 60.0);
        let x = |id| world.body(id).unwrap().position.x;
        assert!(
            x(crate_) < 9.5 - 0.2 + LINEAR_SLOP,
            "crate at {}",
            x(crate_)
        );
        assert!(
            x(bullet) < x(crate_),
            "bullet at {}, crate at {}",
            x(bullet),
            x(crate_)
        );
    }
}

#[test]
fn a_fast_body_that_ends_inside_a_sensor_beyond_its_reach_is_reported() {
    let mut world = weightless_world();
    let zone = world
        .add_body(BodyDef {
            sensor: true,
            ..BodyDef::new_static(Vec2::new(6.0, 0.0), Shape::rect(1.0, 1.0))
        })
        .unwrap();
    // 330 m/s: 5.5 m a step, ending inside the zone after one step.
    let ball = world
        .add_body(
            BodyDef::new_dynamic(Vec2::new(0.5, 0.0), Shape::circle(0.05))
                .with_velocity(Vec2::new(330.0, 0.0)),
        )
        .unwrap();
    world.step(1.0 / 60.0);
    let x = world.body(ball).unwrap().position.x;
    assert!((x - 6.0).abs() < 0.5, "inside the zone: {x}");
    let inside: Vec<_> = world.sensor_overlaps().to_vec();
    assert_eq!(inside.len(), 1, "{inside:?}");
    assert_eq!((inside[0].sensor, inside[0].visitor), (zone, ball));
}
