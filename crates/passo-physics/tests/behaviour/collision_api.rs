//! What a game reads from collisions: events, sensors, filters, queries.

use crate::support::{add_box, add_circle, add_static_box, weightless_world};
use passo_physics::glam::Vec2;
use passo_physics::{Aabb, BodyDef, CollisionFilter, ContactPair, SensorPair, Shape, Stage, World};

const DT: f32 = 1.0 / 60.0;

#[test]
fn a_falling_ball_reports_begin_on_landing_and_end_when_thrown_up() {
    let mut w = World::default();
    let ground = add_static_box(&mut w, Vec2::new(-5.0, -1.0), Vec2::new(5.0, 0.0));
    let ball = add_circle(&mut w, Vec2::new(0.0, 1.5), 0.5, 1.0);
    let mut began = None;
    for n in 0..120 {
        w.step(DT);
        if !w.events().begin.is_empty() {
            assert_eq!(w.events().begin, [ContactPair { a: ground, b: ball }]);
            began.get_or_insert(n);
        }
    }
    // Falling 1 m takes 0.45 s: 27 steps.
    let began = began.expect("the ball landed");
    assert!((25..=29).contains(&began), "began at step {began}");
    assert!(w.is_standing(ball, 0.8));
    assert_eq!(w.standing_on(ball, 0.8), Some(ground));
    let contact = w.contacts_of(ball).next().unwrap();
    assert_eq!(contact.a, ball);
    assert_eq!(contact.normal, -Vec2::Y, "from the ball down to the ground");
    assert!(contact.touching);
    // Weight over a substep: m g h.
    let substeps = w.settings().contacts.unwrap().substeps as f32;
    let h = DT / substeps;
    assert!((contact.normal_impulse - 9.81 * h).abs() < 1e-4);

    w.apply_impulse(ball, Vec2::new(0.0, 8.0));
    w.step(DT);
    assert_eq!(w.events().end, [ContactPair { a: ground, b: ball }]);
    w.step(DT);
    assert!(w.events().end.is_empty(), "an end is reported once");
    assert!(!w.is_standing(ball, 0.8));
}

#[test]
fn standing_needs_a_support_within_the_slope_cone() {
    let mut w = World::default();
    add_static_box(&mut w, Vec2::new(-5.0, -1.0), Vec2::new(5.0, 0.0));
    // A box resting against a wall on its right: touching, but not standing on it.
    add_static_box(&mut w, Vec2::new(0.5, 0.0), Vec2::new(1.0, 5.0));
    let b = add_box(&mut w, Vec2::new(0.0, 2.0), Vec2::ONE, 1.0);
    w.apply_force(b, Vec2::new(200.0, 0.0));
    w.step(DT);
    assert!(
        !w.is_standing(b, 0.8),
        "in the air, pressed against the wall"
    );
    assert!(w.contacts_of(b).any(|c| c.touching && c.normal == Vec2::X));
}

#[test]
fn removing_a_body_ends_its_contacts() {
    let mut w = World::default();
    let ground = add_static_box(&mut w, Vec2::new(-5.0, -1.0), Vec2::new(5.0, 0.0));
    let b = add_box(&mut w, Vec2::new(0.0, 0.5), Vec2::ONE, 1.0);
    w.step(DT);
    assert_eq!(w.events().begin.len(), 1);
    w.remove_body(b).unwrap();
    w.step(DT);
    assert_eq!(w.events().end, [ContactPair { a: ground, b }]);
}

#[test]
fn filters_let_layers_pass_through_each_other() {
    let mut w = World::default();
    let ground = add_static_box(&mut w, Vec2::new(-5.0, -1.0), Vec2::new(5.0, 0.0));
    let ghost = w
        .add_body(BodyDef {
            position: Vec2::new(0.0, 0.5),
            shape: Some(Shape::circle(0.5)),
            filter: CollisionFilter {
                layers: 2,
                mask: !1,
            },
            ..Default::default()
        })
        .unwrap();
    let ball = add_circle(&mut w, Vec2::new(3.0, 0.5), 0.5, 1.0);
    for _ in 0..60 {
        w.step(DT);
    }
    assert!(
        w.body(ghost).unwrap().position.y < -1.0,
        "the ghost fell through the ground"
    );
    assert!((w.body(ball).unwrap().position.y - 0.5).abs() < 0.01);
    assert!(w.contacts().all(|c| c.a != ghost && c.b != ghost));
    let _ = ground;
}

#[test]
fn sensors_report_visitors_and_never_push() {
    let mut w = weightless_world();
    let zone = w
        .add_body(BodyDef {
            sensor: true,
            ..BodyDef::new_static(Vec2::new(5.0, 0.0), Shape::rect(2.0, 2.0))
        })
        .unwrap();
    let ball = w
        .add_body(BodyDef {
            velocity: Vec2::new(6.0, 0.0),
            shape: Some(Shape::circle(0.25)),
            ..Default::default()
        })
        .unwrap();
    let (mut entered, mut left) = (None, None);
    for n in 0..120 {
        w.step(DT);
        let pair = SensorPair {
            sensor: zone,
            visitor: ball,
        };
        if w.events().sensor_begin.contains(&pair) {
            entered = Some(n);
            assert_eq!(w.sensor_overlaps(), [pair]);
        }
        if w.events().sensor_end.contains(&pair) {
            left = Some(n);
        }
    }
    // Enters when x > 5 - 1 - 0.25 = 3.75 (0.625 s), leaves when x > 6.25 (1.04 s).
    assert_eq!(entered, Some(37));
    assert_eq!(left, Some(62));
    assert_eq!(
        w.body(ball).unwrap().velocity,
        Vec2::new(6.0, 0.0),
        "never pushed"
    );
}

/// Steps `w` until `ticks` have passed and returns, for the pair, the
/// steps it began and ended in, and whether it was in the sensor's
/// overlaps after a step that began it.
fn sensor_events(w: &mut World, pair: SensorPair, ticks: u32) -> (Vec<u32>, Vec<u32>, bool) {
    let (mut began, mut ended, mut listed) = (Vec::new(), Vec::new(), false);
    for n in 0..ticks {
        w.step(DT);
        if w.events().sensor_begin.contains(&pair) {
            began.push(n);
            listed |= w.sensor_overlaps().contains(&pair);
        }
        if w.events().sensor_end.contains(&pair) {
            ended.push(n);
        }
    }
    (began, ended, listed)
}

#[test]
fn a_body_crossing_a_sensor_within_one_step_begins_and_ends_in_that_step() {
    // A 0.2 m gate and a 0.05 m ball from fifty starting points: at 20 m/s
    // (0.33 m a step) the ball is inside at the end of some steps and not
    // others; at 59 and 400 m/s it crosses the gate within one step. Every
    // time, one begin and one end.
    for speed in [20.0, 59.0, 400.0] {
        for k in 0..50 {
            let mut w = weightless_world();
            let gate = w
                .add_body(
                    BodyDef::new_static(Vec2::new(5.0, 0.0), Shape::rect(0.2, 2.0)).as_sensor(),
                )
                .unwrap();
            let start = Vec2::new(k as f32 * 0.0137, 0.3);
            let ball = w
                .add_body(BodyDef {
                    velocity: Vec2::new(speed, 0.0),
                    ..BodyDef::new_dynamic(start, Shape::circle(0.05))
                })
                .unwrap();
            let pair = SensorPair {
                sensor: gate,
                visitor: ball,
            };
            let (began, ended, listed) = sensor_events(&mut w, pair, 40);
            assert_eq!(began.len(), 1, "{speed} m/s from {start}: begins {began:?}");
            assert_eq!(ended.len(), 1, "{speed} m/s from {start}: ends {ended:?}");
            assert!(began[0] <= ended[0]);
            if began[0] == ended[0] {
                assert!(!listed, "crossed within the step: not inside after it");
            }
            assert_eq!(w.body(ball).unwrap().velocity.x, speed, "never pushed");
        }
    }
}

#[test]
fn a_fast_sensor_sweeping_over_a_body_sees_it_and_one_passing_by_does_not() {
    // A kinematic sensor 0.1 m wide sweeping at 120 m/s (2 m a step) over
    // a ball at rest, and a ball 0.1 m beside its path.
    let mut w = weightless_world();
    let sensor = w
        .add_body(
            BodyDef::new_kinematic(
                Vec2::new(-3.5, 0.0),
                Shape::rect(0.1, 1.0),
                Vec2::new(120.0, 0.0),
            )
            .as_sensor(),
        )
        .unwrap();
    let inside = w
        .add_body(BodyDef::new_dynamic(
            Vec2::new(1.0, 0.0),
            Shape::circle(0.1),
        ))
        .unwrap();
    let beside = w
        .add_body(BodyDef::new_dynamic(
            Vec2::new(3.0, 0.65),
            Shape::circle(0.1),
        ))
        .unwrap();
    let crossing = SensorPair {
        sensor,
        visitor: inside,
    };
    let passing = SensorPair {
        sensor,
        visitor: beside,
    };
    let mut events = Vec::new();
    for n in 0..6 {
        w.step(DT);
        let e = w.events();
        for (pair, name) in [(crossing, "crossing"), (passing, "passing")] {
            if e.sensor_begin.contains(&pair) {
                events.push((n, name, "begin"));
            }
            if e.sensor_end.contains(&pair) {
                events.push((n, name, "end"));
            }
        }
    }
    // From x = -3.5 the sensor ends its steps at -1.5, 0.5 and 2.5: it
    // passes over the ball (0.9 to 1.1) within the third step. The other
    // ball's bottom (0.55) stays 0.05 m above the sensor's top.
    assert_eq!(events, [(2, "crossing", "begin"), (2, "crossing", "end")]);
}

#[test]
fn a_body_leaving_a_sensor_fast_only_ends() {
    let mut w = weightless_world();
    let zone = w
        .add_body(BodyDef::new_static(Vec2::ZERO, Shape::rect(1.0, 1.0)).as_sensor())
        .unwrap();
    let ball = w
        .add_body(BodyDef::new_dynamic(Vec2::ZERO, Shape::circle(0.1)))
        .unwrap();
    let pair = SensorPair {
        sensor: zone,
        visitor: ball,
    };
    w.step(DT);
    assert_eq!(w.events().sensor_begin, [pair]);
    w.set_velocity(ball, Vec2::new(300.0, 0.0));
    let (began, ended, _) = sensor_events(&mut w, pair, 5);
    assert_eq!((began, ended), (vec![], vec![0]));
}

#[test]
fn point_box_and_ray_queries() {
    let mut w = weightless_world();
    let wall = add_static_box(&mut w, Vec2::new(4.0, -2.0), Vec2::new(5.0, 2.0));
    let ball = add_circle(&mut w, Vec2::new(2.0, 0.0), 0.5, 1.0);
    let other = add_circle(&mut w, Vec2::new(-3.0, 0.0), 1.0, 1.0);
    w.add_body(BodyDef::point_mass(Vec2::new(2.0, 0.0)))
        .unwrap(); // no shape: never found

    assert_eq!(w.query_point(Vec2::new(2.2, 0.1)), [ball]);
    assert_eq!(w.query_point(Vec2::new(4.5, 1.9)), [wall]);
    assert!(w.query_point(Vec2::new(0.0, 0.0)).is_empty());
    let around = Aabb {
        min: Vec2::new(1.0, -1.0),
        max: Vec2::new(4.2, 1.0),
    };
    assert_eq!(w.query_aabb(around), [wall, ball]);

    let hit = w.ray_cast(Vec2::ZERO, Vec2::X, 100.0).unwrap();
    assert_eq!(hit.body, ball);
    assert!((hit.distance - 1.5).abs() < 1e-6);
    assert_eq!(hit.normal, -Vec2::X);
    let hit = w
        .ray_cast(Vec2::new(0.0, 1.0), Vec2::new(2.0, 0.0), 100.0)
        .unwrap();
    assert_eq!((hit.body, hit.distance, hit.normal), (wall, 4.0, -Vec2::X));
    assert_eq!(w.ray_cast(Vec2::ZERO, -Vec2::X, 100.0).unwrap().body, other);
    assert!(w.ray_cast(Vec2::ZERO, -Vec2::X, 1.5).is_none());
    assert!(w.ray_cast(Vec2::ZERO, Vec2::ZERO, 10.0).is_none());
    assert!(
        w.ray_cast(Vec2::new(f32::NAN, 0.0), Vec2::X, 10.0)
            .is_none()
    );
    // Any length but zero: a subnormal direction (its length rounds to
    // zero) or one whose length overflows still points somewhere.
    for direction in [Vec2::new(1e-45, 0.0), Vec2::new(f32::MAX, 0.0)] {
        let hit = w.ray_cast(Vec2::ZERO, direction, 100.0).unwrap();
        assert_eq!((hit.body, hit.distance), (ball, 1.5), "{direction}");
    }
    let diagonal = w.ray_cast(Vec2::ZERO, Vec2::splat(f32::MAX), 100.0);
    assert_eq!(diagonal, w.ray_cast(Vec2::ZERO, Vec2::ONE, 100.0));
    assert!(
        w.ray_cast(Vec2::ZERO, Vec2::new(f32::INFINITY, 0.0), 10.0)
            .is_none()
    );
}

#[test]
fn the_contact_stage_runs_only_with_colliders() {
    let mut w = World::default();
    let a = w.add_body(BodyDef::point_mass(Vec2::ZERO)).unwrap();
    w.add_body(BodyDef::point_mass(Vec2::ZERO)).unwrap();
    assert!(!w.active_stages().contains(&Stage::Contacts));
    w.step(DT);
    assert!(w.contacts().next().is_none());
    // One shaped body alone has nothing to touch.
    let b = add_circle(&mut w, Vec2::new(5.0, 0.0), 1.0, 1.0);
    assert!(!w.active_stages().contains(&Stage::Contacts));
    add_static_box(&mut w, Vec2::new(-5.0, -10.0), Vec2::new(5.0, -9.0));
    assert!(w.active_stages().contains(&Stage::Contacts));
    w.remove_body(b).unwrap();
    assert!(!w.active_stages().contains(&Stage::Contacts));
    let _ = a;
}

#[test]
fn the_same_scene_twice_gives_the_same_bits() {
    let run = || {
        let mut w = World::default();
        add_static_box(&mut w, Vec2::new(-10.0, -1.0), Vec2::new(10.0, 0.0));
        for i in 0..200 {
            let p = Vec2::new((i % 20) as f32 * 0.9 - 9.0, 1.0 + (i / 20) as f32 * 0.9);
            if i % 3 == 0 {
                add_box(&mut w, p, Vec2::splat(0.8), 1.0);
            } else {
                add_circle(&mut w, p, 0.4, 1.0);
            }
        }
        for _ in 0..300 {
            w.step(DT);
        }
        w.state_hash()
    };
    assert_eq!(run(), run());
}

#[test]
fn an_ice_tile_with_the_min_rule_slides_at_its_own_friction() {
    use passo_physics::FrictionMix;
    // A box launched at 3 m/s stops after v² / (2 mu g): 0.76 m at
    // sqrt(0.05 * 0.6) = 0.173, 9.17 m at min(0.05, 0.6) = 0.05.
    let slide = |mix: FrictionMix| {
        let mut w = World::default();
        w.add_body(
            BodyDef::new_static(Vec2::new(0.0, -0.5), Shape::rect(40.0, 1.0))
                .with_friction_mix(0.05, mix),
        )
        .unwrap();
        let b = w
            .add_body(
                BodyDef::new_dynamic(Vec2::new(-15.0, 0.5), Shape::rect(1.0, 1.0))
                    .with_velocity(Vec2::new(3.0, 0.0)),
            )
            .unwrap();
        for _ in 0..900 {
            w.step(1.0 / 60.0);
        }
        w.body(b).unwrap().position.x + 15.0
    };
    let mean = slide(FrictionMix::GeometricMean);
    let ice = slide(FrictionMix::Min);
    let g = 9.81;
    let stop = |mu: f32| 9.0 / (2.0 * mu * g);
    assert!((mean - stop((0.05f32 * 0.6).sqrt())).abs() < 0.06, "{mean}");
    assert!((ice - stop(0.05)).abs() < 0.06, "{ice}");
}

#[test]
fn per_tick_setters_count_what_they_refuse_and_change_nothing() {
    let mut w = World::default();
    let a = w.add_body(BodyDef::point_mass(Vec2::ZERO)).unwrap();
    let gone = w.add_body(BodyDef::point_mass(Vec2::ONE)).unwrap();
    w.remove_body(gone);
    w.set_velocity(a, Vec2::new(f32::NAN, 0.0));
    w.apply_force(a, Vec2::new(f32::INFINITY, 0.0));
    w.set_friction(a, -1.0);
    w.apply_impulse(gone, Vec2::X);
    assert_eq!(w.stats().rejected_inputs, 4);
    assert_eq!(w.body(a).unwrap().velocity, Vec2::ZERO);
    assert_eq!(w.body(a).unwrap().friction, 0.6);
    // The try_ forms say why.
    assert_eq!(
        w.try_apply_impulse(gone, Vec2::X),
        Err(passo_physics::PhysicsError::StaleBody(gone))
    );
    w.set_velocity(a, Vec2::X);
    assert_eq!(w.body(a).unwrap().velocity, Vec2::X);
    assert_eq!(w.stats().rejected_inputs, 4);
}

#[test]
fn positions_beyond_the_usable_extent_and_giant_shapes_are_refused() {
    // Beyond 2e9 m the grid's cells saturated and every body fell into one
    // cell; at 1e30 m bodies 1 m apart were one point.
    let mut w = World::default();
    for p in [
        Vec2::new(3e9, 0.0),
        Vec2::new(0.0, -1e30),
        Vec2::new(1.0e7 + 1e3, 0.0),
    ] {
        let err = w.add_body(BodyDef::point_mass(p)).unwrap_err().to_string();
        assert!(err.contains("MAX_COORDINATE"), "{err}");
    }
    let a = w
        .add_body(BodyDef::point_mass(Vec2::new(1.0e7, -1.0e7)))
        .unwrap();
    assert!(w.try_set_position(a, Vec2::new(2e7, 0.0)).is_err());
    assert!(
        w.add_body(BodyDef::new_static(Vec2::ZERO, Shape::circle(2e6)))
            .unwrap_err()
            .to_string()
            .contains("MAX_SHAPE_SIZE")
    );
    // The largest shape at the edge of the extent, among small bodies,
    // steps without overflowing a cell index.
    w.add_body(BodyDef::new_dynamic(
        Vec2::new(1.0e7, 0.0),
        Shape::rect(2.0e6, 2.0e6),
    ))
    .unwrap();
    for i in 0..20 {
        w.add_body(BodyDef::new_dynamic(
            Vec2::new(i as f32, 0.0),
            Shape::circle(0.2),
        ))
        .unwrap();
    }
    w.step(1.0 / 60.0);
    assert!(w.bodies().all(|b| b.position.is_finite()));
}

#[test]
fn a_fast_body_crossing_the_path_of_a_moving_sensor_is_seen() {
    // A 0.5 m kinematic sensor at 60 m/s along x and a 0.05 m ball at
    // 300 m/s along y: relative to the sensor the ball passes through its
    // middle within one step, where neither ends near the other. It used
    // to be seen only against a static sensor.
    let mut w = weightless_world();
    let sensor = w
        .add_body(
            BodyDef::new_kinematic(
                Vec2::new(-0.5, 0.0),
                Shape::rect(0.5, 0.5),
                Vec2::new(60.0, 0.0),
            )
            .as_sensor(),
        )
        .unwrap();
    let ball = w
        .add_body(BodyDef {
            velocity: Vec2::new(0.0, 300.0),
            ..BodyDef::new_dynamic(Vec2::new(0.0, -2.5), Shape::circle(0.05))
        })
        .unwrap();
    let pair = SensorPair {
        sensor,
        visitor: ball,
    };
    let (began, ended, listed) = sensor_events(&mut w, pair, 3);
    assert_eq!((began, ended, listed), (vec![0], vec![0], false));
}

#[test]
fn a_contact_between_two_moving_bodies_names_the_lower_id_first() {
    // The same two boxes, added in both orders: the contact's `a` is the
    // lower id and its normal points from `a` to `b`, whatever the order.
    for lower_on_top in [false, true] {
        let mut world = World::default();
        world
            .add_body(BodyDef::new_static(
                Vec2::new(0.0, -0.5),
                Shape::rect(10.0, 1.0),
            ))
            .unwrap();
        let bottom_def = BodyDef::new_dynamic(Vec2::new(0.0, 0.5), Shape::rect(1.0, 1.0));
        let top_def = BodyDef::new_dynamic(Vec2::new(0.0, 1.5), Shape::rect(1.0, 1.0));
        let (bottom, top) = if lower_on_top {
            let top = world.add_body(top_def).unwrap();
            (world.add_body(bottom_def).unwrap(), top)
        } else {
            let bottom = world.add_body(bottom_def).unwrap();
            (bottom, world.add_body(top_def).unwrap())
        };
        world.step(1.0 / 60.0);
        let c = world
            .contacts()
            .find(|c| [c.a, c.b] == [bottom, top] || [c.a, c.b] == [top, bottom])
            .expect("the boxes touch");
        assert!(c.a.index() < c.b.index(), "{c:?}");
        let up = if c.a == bottom { 1.0 } else { -1.0 };
        assert_eq!(c.normal, Vec2::new(0.0, up), "{c:?}");
    }
}
