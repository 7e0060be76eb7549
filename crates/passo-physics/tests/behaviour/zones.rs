//! Gravity per body and force zones against closed forms: a scaled fall,
//! Archimedes' depth for boxes and discs, wind and drag that never
//! overshoot; and zones saved, moved and removed with their bodies.

use crate::support::add_ground;
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, BodyId, ForceZone, Liquid, PhysicsError, Shape, Stage, Wind, World};

const DT: f32 = 1.0 / 60.0;
const G: f32 = 9.81;

#[test]
fn a_scaled_body_falls_with_its_share_of_gravity() {
    // Semi-implicit Euler from rest: y_n = y0 - s g dt^2 n (n + 1) / 2.
    for scale in [0.0f32, 0.5, 1.0, 2.0, -1.0] {
        let mut world = World::default();
        let body = world
            .add_body(BodyDef {
                gravity_scale: scale,
                drag_area: 0.0,
                ..BodyDef::point_mass(Vec2::new(0.0, 100.0))
            })
            .unwrap();
        for n in 1..=120u32 {
            world.step(DT);
            let y = world.body(body).unwrap().position.y;
            let n = n as f32;
            let exact = 100.0 - scale * G * DT * DT * n * (n + 1.0) / 2.0;
            assert!(
                (y - exact).abs() < 2e-3,
                "scale {scale}, step {n}: {y} against {exact}"
            );
        }
    }
    let mut world = World::default();
    let body = world.add_body(BodyDef::point_mass(Vec2::ZERO)).unwrap();
    assert!(!world.active_stages().contains(&Stage::BodyForces));
    world.set_gravity_scale(body, 0.0).unwrap();
    assert!(world.active_stages().contains(&Stage::BodyForces));
    assert_eq!(world.body(body).unwrap().gravity_scale, 0.0);
    assert!(world.set_gravity_scale(body, f32::NAN).is_err());
    assert!(world.set_gravity_scale(body, 1e4).is_err());
    let ground = add_ground(&mut world, 4.0);
    assert!(world.set_gravity_scale(ground, 0.0).is_err());
}

/// A pool `width` wide, its surface at y = 0, 3 m deep, on a floor.
fn pool(world: &mut World, width: f32, liquid: Liquid) -> BodyId {
    let def = BodyDef::new_static(Vec2::new(0.0, -1.5), Shape::rect(width, 3.0)).as_sensor();
    let water = world.add_body(def).unwrap();
    let floor = BodyDef::new_static(Vec2::new(0.0, -3.5), Shape::rect(width + 2.0, 1.0));
    world.add_body(floor).unwrap();
    world
        .add_force_zone(
            water,
            ForceZone {
                liquid: Some(liquid),
                ..Default::default()
            },
        )
        .unwrap();
    water
}

#[test]
fn a_box_floats_at_its_archimedes_depth_within_a_millimetre() {
    for density in [2.0f32, 8.0, 30.0] {
        for (w, h) in [(0.5f32, 0.5f32), (1.2, 0.4), (0.3, 0.9)] {
            for share in [0.2f32, 0.5, 0.85] {
                // The mass that floats with `share` of its height under.
                let mass = share * density * w * h;
                let mut world = World::default();
                pool(&mut world, 8.0, Liquid { density, drag: 6.0 });
                let body = world
                    .add_body(BodyDef {
                        mass,
                        ..BodyDef::new_dynamic(Vec2::new(0.3, 1.0), Shape::rect(w, h))
                    })
                    .unwrap();
                for _ in 0..1800 {
                    world.step(DT);
                }
                let bottom = world.body(body).unwrap().position.y - 0.5 * h;
                let depth = -bottom;
                let exact = mass / (density * w);
                assert!(
                    (depth - exact).abs() < 1e-3,
                    "{w}×{h} m of {mass} kg in {density} kg/m²: {depth} m deep against {exact}"
                );
            }
        }
    }
}

/// The area of a unit... disc of radius `r` below a line `d` above its
/// centre.
fn disc_below(r: f64, d: f64) -> f64 {
    let t = (d / r).clamp(-1.0, 1.0);
    r * r * (std::f64::consts::PI - (t.acos() - t * (1.0 - t * t).sqrt()))
}

#[test]
fn a_disc_floats_where_the_liquid_it_displaces_weighs_as_much_as_it() {
    for (radius, share) in [(0.3f32, 0.3f32), (0.5, 0.5), (0.25, 0.8)] {
        let density = 6.0f32;
        let area = std::f32::consts::PI * radius * radius;
        let mass = share * density * area;
        let mut world = World::default();
        pool(&mut world, 6.0, Liquid { density, drag: 6.0 });
        let body = world
            .add_body(BodyDef {
                mass,
                ..BodyDef::new_dynamic(Vec2::new(0.0, 1.0), Shape::circle(radius))
            })
            .unwrap();
        for _ in 0..1800 {
            world.step(DT);
        }
        let y = world.body(body).unwrap().position.y as f64;
        // The surface is -y above the centre: the submerged area times the
        // density holds the mass up.
        let held = density as f64 * disc_below(radius as f64, -y);
        assert!(
            (held - mass as f64).abs() < 2e-3 * mass as f64,
            "r {radius}, {share}: displaces {held} kg for {mass} kg (centre at {y})"
        );
    }
}

#[test]
fn a_body_denser_than_the_liquid_sinks_to_the_floor() {
    let mut world = World::default();
    pool(
        &mut world,
        6.0,
        Liquid {
            density: 4.0,
            drag: 1.0,
        },
    );
    let body = world
        .add_body(BodyDef {
            mass: 2.0,
            ..BodyDef::new_dynamic(Vec2::new(0.0, 0.5), Shape::rect(0.5, 0.5))
        })
        .unwrap();
    for _ in 0..600 {
        world.step(DT);
    }
    let y = world.body(body).unwrap().position.y;
    assert!((y - (-3.0 + 0.25)).abs() < 0.01, "on the floor: {y}");
}

#[test]
fn a_zone_s_own_gravity_acts_inside_it_only() {
    let mut world = World::default();
    let lift = BodyDef::new_static(Vec2::new(0.0, 2.0), Shape::rect(2.0, 4.0)).as_sensor();
    let lift = world.add_body(lift).unwrap();
    let up = ForceZone {
        gravity: Some(Vec2::new(0.0, 5.0)),
        ..Default::default()
    };
    world.add_force_zone(lift, up).unwrap();
    let body = world
        .add_body(BodyDef {
            drag_area: 0.0,
            ..BodyDef::new_dynamic(Vec2::new(0.0, 0.5), Shape::circle(0.1))
        })
        .unwrap();
    let mut last = world.body(body).unwrap();
    let mut left = false;
    for _ in 0..240 {
        world.step(DT);
        let b = world.body(body).unwrap();
        let accel = (b.velocity.y - last.velocity.y) / DT;
        // Inside or above it over the whole step.
        let (low, high) = (
            last.position.y.min(b.position.y),
            last.position.y.max(b.position.y),
        );
        let fully_in = high + 0.1 < 4.0 && low - 0.1 > 0.0;
        let out = low - 0.1 > 4.0;
        last = b;
        if fully_in {
            assert!((accel - 5.0).abs() < 1e-2, "inside: {accel}");
        }
        if out {
            left = true;
            assert!((accel + G).abs() < 1e-2, "above it: {accel}");
        }
    }
    assert!(left, "it rose out of the zone");
}

#[test]
fn wind_brings_a_body_to_its_speed_and_no_faster() {
    for speed in [2.0f32, 15.0, 60.0] {
        let mut world = World::new(passo_physics::WorldSettings {
            forces: passo_physics::ForceModels::none(),
            ..Default::default()
        })
        .unwrap();
        let tunnel = BodyDef::new_static(Vec2::ZERO, Shape::rect(1000.0, 10.0)).as_sensor();
        let tunnel = world.add_body(tunnel).unwrap();
        let wind = Wind {
            velocity: Vec2::new(speed, 0.0),
            density: 1.225,
        };
        world
            .add_force_zone(
                tunnel,
                ForceZone {
                    wind: Some(wind),
                    ..Default::default()
                },
            )
            .unwrap();
        let body = world
            .add_body(BodyDef {
                drag_area: 2.0,
                mass: 0.5,
                ..BodyDef::new_dynamic(Vec2::new(-400.0, 0.0), Shape::circle(0.2))
            })
            .unwrap();
        let mut last = 0.0f32;
        for _ in 0..1200 {
            world.step(DT);
            let v = world.body(body).unwrap().velocity.x;
            assert!(v <= speed * (1.0 + 1e-5), "{speed} m/s wind: {v}");
            assert!(v >= last - 1e-6, "it only speeds up");
            last = v;
        }
        assert!(last > 0.9 * speed, "{speed} m/s wind: reached {last}");
    }
}

#[test]
fn a_drag_zone_slows_a_body_without_turning_it_back() {
    for rate in [0.5f32, 5.0, 500.0] {
        let mut world = World::new(passo_physics::WorldSettings {
            forces: passo_physics::ForceModels::none(),
            ..Default::default()
        })
        .unwrap();
        let mud = world
            .add_body(BodyDef::new_static(Vec2::ZERO, Shape::rect(100.0, 10.0)).as_sensor())
            .unwrap();
        world
            .add_force_zone(
                mud,
                ForceZone {
                    drag: Some(rate),
                    ..Default::default()
                },
            )
            .unwrap();
        let body = world
            .add_body(
                BodyDef::new_dynamic(Vec2::ZERO, Shape::circle(0.2))
                    .with_velocity(Vec2::new(4.0, 0.0)),
            )
            .unwrap();
        let mut last = 4.0f32;
        for _ in 0..120 {
            world.step(DT);
            let v = world.body(body).unwrap().velocity.x;
            assert!((0.0..=last).contains(&v), "rate {rate}: {v} after {last}");
            last = v;
        }
        if rate >= 5.0 {
            assert!(last < 0.01, "rate {rate}: still at {last}");
        }
    }
}

#[test]
fn zones_are_saved_and_go_with_their_bodies() {
    let mut world = World::default();
    let water = pool(
        &mut world,
        4.0,
        Liquid {
            density: 5.0,
            drag: 1.0,
        },
    );
    let body = world
        .add_body(BodyDef::new_dynamic(
            Vec2::new(0.0, 0.5),
            Shape::rect(0.4, 0.4),
        ))
        .unwrap();
    for _ in 0..30 {
        world.step(DT);
    }
    let saved = world.snapshot();
    let mut copy = World::from_snapshot(saved.clone()).unwrap();
    assert_eq!(copy.snapshot(), saved, "the same state read back");
    assert_eq!(copy.force_zones().count(), 1);
    for _ in 0..60 {
        world.step(DT);
        copy.step(DT);
    }
    let bits = |w: &World| w.body(body).unwrap().position.to_array().map(f32::to_bits);
    assert_eq!(bits(&world), bits(&copy));
    world.remove_body(water).unwrap();
    assert_eq!(world.force_zones().count(), 0);
    world.step(DT);

    let solid = world
        .add_body(BodyDef::new_static(Vec2::ZERO, Shape::rect(1.0, 1.0)))
        .unwrap();
    let round = world
        .add_body(BodyDef::new_static(Vec2::ZERO, Shape::circle(1.0)).as_sensor())
        .unwrap();
    let zone = ForceZone {
        drag: Some(1.0),
        ..Default::default()
    };
    assert!(world.add_force_zone(solid, zone).is_err(), "not a sensor");
    assert!(world.add_force_zone(round, zone).is_err(), "not a box");
    let bad = ForceZone {
        liquid: Some(Liquid {
            density: 0.0,
            drag: 1.0,
        }),
        ..Default::default()
    };
    let sensor = world
        .add_body(BodyDef::new_static(Vec2::ZERO, Shape::rect(1.0, 1.0)).as_sensor())
        .unwrap();
    assert!(matches!(
        world.add_force_zone(sensor, bad),
        Err(PhysicsError::OutOfRange { .. })
    ));
    assert!(world.remove_force_zone(sensor).is_none());
}
