//! Sloped ground: segments and chains against circles, boxes and
//! capsules. Contacts against their closed forms, smooth chain joints,
//! one-sided chains, rays, resting on slopes, snapshots and bad chains.

use crate::support::max_penetration;
use passo_physics::glam::Vec2;
use passo_physics::{
    BodyDef, ChainDef, ContactSettings, FrictionMix, QueryFilter, Shape, World, WorldSettings,
    collide,
};

const DT: f32 = 1.0 / 60.0;

/// The moving shapes, and how far each reaches along `-n` from its centre
/// (its support: core half extents along `n`, plus its radius).
fn movers() -> Vec<(&'static str, Shape)> {
    vec![
        ("circle", Shape::circle(0.3)),
        ("box", Shape::rect(0.8, 0.6)),
        ("upright capsule", Shape::capsule(0.4, 1.0)),
        ("lying capsule", Shape::capsule(1.0, 0.4)),
    ]
}

fn support(shape: &Shape, n: Vec2) -> f32 {
    let (k, r) = match *shape {
        Shape::Circle { radius } => (Vec2::ZERO, radius),
        Shape::Box { half_extents } => (half_extents, 0.0),
        Shape::Capsule {
            half_segment,
            radius,
        } => (half_segment, radius),
        _ => unreachable!(),
    };
    k.x * n.x.abs() + k.y * n.y.abs() + r
}

#[test]
fn contacts_with_a_segment_match_the_closed_form_for_every_shape() {
    // A segment 6 m long through the origin at each angle, a shape with
    // its lowest point `gap` from the segment's line above each of several
    // points along it: the normal is the segment's, the separation the
    // gap (negative: overlap, down to the centre on the line), and every
    // point midway between the surfaces, on the segment's stretch.
    for degrees in [0.0f32, 15.0, 30.0, 45.0, 60.0, -30.0, -45.0] {
        let u = Vec2::from_angle(degrees.to_radians());
        let n = u.perp();
        for chain in [false, true] {
            let line = if chain {
                Shape::ChainSegment {
                    half: 3.0 * u,
                    before: None,
                    after: None,
                }
            } else {
                Shape::segment(-3.0 * u, 3.0 * u)
            };
            for (name, shape) in movers() {
                let reach = support(&shape, n);
                for along in [-1.5f32, -0.4, 0.0, 0.7, 1.6] {
                    // Down to the centre just in front of the line.
                    for gap in [0.2f32, 0.01, 0.0, -0.02, -0.1, 1e-4 - reach] {
                        let centre = u * along + n * (reach + gap);
                        let case = format!(
                            "{name} at {degrees}°, {along} along, gap {gap}, chain {chain}"
                        );
                        let m = collide(&line, Vec2::ZERO, &shape, centre, 1.0)
                            .unwrap_or_else(|| panic!("{case}: no contact"));
                        assert!((m.normal - n).length() < 1e-5, "{case}: {m:?}");
                        assert!((m.separation - gap).abs() < 1e-5, "{case}: {m:?}");
                        for p in m.points() {
                            let height = p.dot(n);
                            assert!((height - 0.5 * gap).abs() < 1e-5, "{case}: {m:?}");
                            assert!(p.dot(u).abs() <= 3.0 + 1e-5, "{case}: {m:?}");
                        }
                        // Seen from the shape: the same contact reversed.
                        let back = collide(&shape, centre, &line, Vec2::ZERO, 1.0).unwrap();
                        assert_eq!(back.normal, -m.normal, "{case}");
                        assert_eq!(back.separation, m.separation, "{case}");
                    }
                }
                // Centred on the segment's middle: out along a normal (the
                // open side's for a chain), as deep as the shape reaches.
                let m = collide(&line, Vec2::ZERO, &shape, Vec2::ZERO, 1.0).unwrap();
                let case = format!("{name} on the middle at {degrees}°, chain {chain}");
                assert!(
                    (m.normal - n).length() < 1e-5 || (!chain && (m.normal + n).length() < 1e-5),
                    "{case}: {m:?}"
                );
                assert!((m.separation + reach).abs() < 1e-5, "{case}: {m:?}");
            }
        }
    }
}

#[test]
fn a_flat_shape_face_on_a_flat_segment_has_two_points_and_a_circle_one() {
    let floor = Shape::segment(Vec2::new(-2.0, 0.0), Vec2::new(2.0, 0.0));
    let m = collide(
        &floor,
        Vec2::ZERO,
        &Shape::rect(1.0, 0.5),
        Vec2::new(1.8, 0.26),
        1.0,
    )
    .unwrap();
    // The box's bottom from 1.3 to 2.3, cut at the segment's end, 2.
    assert_eq!(m.point_count, 2, "{m:?}");
    assert!(
        (m.points[0] - Vec2::new(1.3, 0.005)).length() < 1e-5,
        "{m:?}"
    );
    assert!(
        (m.points[1] - Vec2::new(2.0, 0.005)).length() < 1e-5,
        "{m:?}"
    );
    let m = collide(
        &floor,
        Vec2::ZERO,
        &Shape::circle(0.5),
        Vec2::new(0.3, 0.51),
        1.0,
    )
    .unwrap();
    assert_eq!(m.point_count, 1);
    // A plain segment is solid from below too; a chain segment is not.
    let m = collide(
        &floor,
        Vec2::ZERO,
        &Shape::circle(0.5),
        Vec2::new(0.3, -0.51),
        1.0,
    )
    .unwrap();
    assert_eq!(m.normal, -Vec2::Y);
    let chain = Shape::ChainSegment {
        half: Vec2::new(2.0, 0.0),
        before: None,
        after: None,
    };
    assert!(
        collide(
            &chain,
            Vec2::ZERO,
            &Shape::circle(0.5),
            Vec2::new(0.3, -0.4),
            1.0
        )
        .is_none()
    );
}

/// A world without friction or restitution between bodies and ground.
fn slippery() -> World {
    World::new(WorldSettings {
        contacts: Some(ContactSettings::default()),
        ..WorldSettings::default()
    })
    .unwrap()
}

fn slippery_chain(world: &mut World, points: Vec<Vec2>) {
    let chain = ChainDef {
        friction: 0.0,
        ..ChainDef::new(points)
    };
    world.add_chain(&chain).unwrap();
}

#[test]
fn bodies_slide_along_a_chain_of_many_segments_without_catching_on_a_joint() {
    // 80 segments of 0.25 m, flat; each shape slides at 5 m/s with no
    // friction for 3 s: a joint it caught on would slow it or throw it up.
    for (name, shape) in movers() {
        for offset in [0.0f32, 0.03, 0.11] {
            let mut world = slippery();
            let points: Vec<Vec2> = (0..=80)
                .map(|i| Vec2::new(-10.0 + 0.25 * i as f32 + offset, 0.0))
                .collect();
            slippery_chain(&mut world, points);
            let reach = support(&shape, Vec2::Y);
            let body = BodyDef {
                friction: 0.0,
                friction_mix: FrictionMix::Min,
                velocity: Vec2::new(5.0, 0.0),
                ..BodyDef::new_dynamic(Vec2::new(-8.0, reach), shape)
            };
            let id = world.add_body(body).unwrap();
            for tick in 0..180 {
                world.step(DT);
                let b = world.body(id).unwrap();
                let case = format!("{name} +{offset}, tick {tick}: {b:?}");
                assert!((b.velocity.x - 5.0).abs() < 1e-3, "{case}");
                // (Settling into the slop takes 0.16 m/s at first.)
                assert!(b.velocity.y.abs() < 0.2, "{case}");
                assert!((b.position.y - reach).abs() < 0.006, "{case}");
            }
        }
    }
}

#[test]
fn a_ball_rolls_down_a_slope_onto_the_flat_without_a_bump() {
    // 30° down onto flat ground, no friction: on the flat its height
    // stays and it never jumps up.
    let mut world = slippery();
    let top = 3.0 * 30f32.to_radians().tan();
    slippery_chain(
        &mut world,
        vec![
            Vec2::new(-6.0, top),
            Vec2::new(-3.0, top),
            Vec2::new(0.0, 0.0),
            Vec2::new(20.0, 0.0),
        ],
    );
    let ball = BodyDef {
        friction: 0.0,
        friction_mix: FrictionMix::Min,
        ..BodyDef::new_dynamic(Vec2::new(-4.0, top + 0.25), Shape::circle(0.25))
            .with_velocity(Vec2::new(2.0, 0.0))
    };
    let id = world.add_body(ball).unwrap();
    let mut on_flat = false;
    for tick in 0..240 {
        world.step(DT);
        let b = world.body(id).unwrap();
        if b.position.x > 0.5 {
            on_flat = true;
            assert!(b.velocity.y.abs() < 0.05, "tick {tick}: {b:?}");
            assert!((b.position.y - 0.25).abs() < 0.006, "tick {tick}: {b:?}");
        }
        assert!(max_penetration(&world) < 0.006, "tick {tick}");
    }
    assert!(on_flat);
}

#[test]
fn a_chain_is_solid_from_above_and_open_from_below() {
    let mut world = World::default();
    world
        .add_chain(&ChainDef::new(vec![
            Vec2::new(-5.0, 2.0),
            Vec2::new(5.0, 2.0),
        ]))
        .unwrap();
    // Thrown up from below, through it, to land on it.
    let ball = world
        .add_body(
            BodyDef::new_dynamic(Vec2::new(0.0, 0.5), Shape::circle(0.25))
                .with_velocity(Vec2::new(0.0, 9.0)),
        )
        .unwrap();
    let mut highest = 0.0f32;
    for _ in 0..180 {
        world.step(DT);
        highest = highest.max(world.body(ball).unwrap().position.y);
    }
    assert!(highest > 3.0, "went through: {highest}");
    let y = world.body(ball).unwrap().position.y;
    assert!((y - 2.25).abs() < 0.006, "landed on it: {y}");
}

#[test]
fn a_crate_rests_on_a_slope_its_friction_holds_and_slides_down_a_steeper_one() {
    // mu = 0.6 holds on 20° (tan 20° = 0.36), not on 40° (0.84).
    for (degrees, holds) in [(20.0f32, true), (40.0, false)] {
        let mut world = World::default();
        let u = Vec2::from_angle(degrees.to_radians());
        world
            .add_chain(&ChainDef::new(vec![-6.0 * u, 6.0 * u]))
            .unwrap();
        let half = 0.25;
        let start = u.perp() * (half * (u.x.abs() + u.y.abs()) + 0.001);
        let id = world
            .add_body(BodyDef::new_dynamic(start, Shape::rect(0.5, 0.5)))
            .unwrap();
        for _ in 0..120 {
            world.step(DT);
        }
        let moved = (world.body(id).unwrap().position - start).length();
        if holds {
            assert!(moved < 0.01, "{degrees}°: moved {moved}");
        } else {
            assert!(moved > 1.0, "{degrees}°: moved {moved}");
        }
        assert!(max_penetration(&world) < 0.006, "{degrees}°");
    }
}

#[test]
fn rays_and_casts_meet_segments_where_the_closed_form_says() {
    let mut world = World::default();
    let u = Vec2::from_angle(30f32.to_radians());
    let slope = world
        .add_chain(&ChainDef::new(vec![-4.0 * u, 4.0 * u]))
        .unwrap()[0];
    let wall = world
        .add_body(BodyDef::new_static(
            Vec2::new(6.0, 0.0),
            Shape::segment(Vec2::new(0.0, -2.0), Vec2::new(0.0, 2.0)),
        ))
        .unwrap();
    // Straight down onto the slope at x: its height is x tan 30°.
    for x in [-2.0f32, 0.0, 1.5] {
        let hit = world.ray_cast(Vec2::new(x, 5.0), -Vec2::Y, 10.0).unwrap();
        assert_eq!(hit.body, slope);
        let expected = 5.0 - x * 30f32.to_radians().tan();
        assert!((hit.distance - expected).abs() < 1e-5, "{x}: {hit:?}");
        assert!((hit.normal - u.perp()).length() < 1e-6, "{hit:?}");
        // From below, the chain is open.
        let below = world.ray_cast(Vec2::new(x, -5.0), Vec2::Y, 20.0);
        assert_ne!(below.map(|h| h.body), Some(slope));
    }
    // A plain segment is solid from both sides.
    for (from, dir) in [
        (Vec2::new(4.0, 0.5), Vec2::X),
        (Vec2::new(8.0, 0.5), -Vec2::X),
    ] {
        let hit = world.ray_cast(from, dir, 10.0).unwrap();
        assert_eq!(hit.body, wall);
        assert!(
            (hit.distance - 2.0).abs() < 1e-5 && hit.normal == -dir,
            "{hit:?}"
        );
    }
    // A box cast down lands with its corner on the slope.
    let shape = Shape::rect(0.4, 0.4);
    let hit = world
        .cast_shape(
            &shape,
            Vec2::new(0.0, 3.0),
            Vec2::new(0.0, -6.0),
            &QueryFilter::default(),
        )
        .unwrap();
    let at = Vec2::new(0.0, 3.0) + Vec2::new(0.0, -6.0) * hit.fraction;
    // The box's lower-right corner touches the line y = x tan 30°.
    let corner = at + Vec2::new(0.2, -0.2);
    assert!(
        (corner.y - corner.x * 30f32.to_radians().tan()).abs() < 1e-5,
        "{at}"
    );
}

#[test]
fn chains_survive_a_snapshot_and_step_on_to_the_same_bits() {
    let mut world = World::default();
    world
        .add_chain(&ChainDef::new(vec![
            Vec2::new(-5.0, 3.0),
            Vec2::new(0.0, 0.0),
            Vec2::new(5.0, 1.0),
        ]))
        .unwrap();
    for i in 0..5 {
        world
            .add_body(BodyDef::new_dynamic(
                Vec2::new(-3.0 + 1.3 * i as f32, 4.0),
                Shape::capsule(0.3, 0.7),
            ))
            .unwrap();
    }
    for _ in 0..30 {
        world.step(DT);
    }
    let mut restored = World::from_snapshot(world.snapshot()).unwrap();
    for _ in 0..90 {
        world.step(DT);
        restored.step(DT);
    }
    assert_eq!(world.state_hash(), restored.state_hash());
}

#[test]
fn bad_chains_are_refused_and_add_nothing() {
    let mut world = World::default();
    let cases = [
        ChainDef::new(vec![Vec2::ZERO]),
        ChainDef::new(vec![Vec2::ZERO, Vec2::X]).closed(),
        ChainDef::new(vec![Vec2::ZERO, Vec2::X, Vec2::X]),
        ChainDef::new(vec![Vec2::ZERO, Vec2::new(f32::NAN, 0.0)]),
        ChainDef::new(vec![Vec2::ZERO, Vec2::new(3e7, 0.0)]),
        ChainDef {
            kind: passo_physics::BodyKind::Dynamic,
            ..ChainDef::new(vec![Vec2::ZERO, Vec2::X])
        },
        ChainDef {
            friction: -1.0,
            ..ChainDef::new(vec![Vec2::ZERO, Vec2::X])
        },
    ];
    for chain in cases {
        let error = world.add_chain(&chain).unwrap_err();
        assert!(!error.to_string().is_empty());
        assert_eq!(world.len(), 0, "{chain:?}");
    }
    // A segment on a dynamic body is refused with the field named.
    let error = world
        .add_body(BodyDef::new_dynamic(
            Vec2::ZERO,
            Shape::segment(Vec2::ZERO, Vec2::X),
        ))
        .unwrap_err();
    assert!(error.to_string().contains("BodyDef::shape"), "{error}");
}

#[test]
fn contacts_with_a_polygon_match_the_closed_form_for_every_shape() {
    // A wedge: flat bottom 4 m wide, a slope up at `degrees` to a
    // vertical back 2 m tall... kept convex: the slope face from (-2, 0)
    // to (2, h). Each shape over the slope face, `gap` from it.
    for degrees in [15.0f32, 26.5, 40.0] {
        let h = 4.0 * degrees.to_radians().tan();
        let wedge = Shape::polygon(&[Vec2::new(-2.0, 0.0), Vec2::new(2.0, 0.0), Vec2::new(2.0, h)])
            .unwrap();
        let u = Vec2::new(4.0, h).normalize();
        let n = u.perp();
        for (name, shape) in movers() {
            let reach = support(&shape, n);
            for along in [1.0f32, 2.0, 3.0] {
                for gap in [0.3f32, 0.02, 0.0, -0.03] {
                    let on_face = Vec2::new(-2.0, 0.0) + u * along;
                    let centre = on_face + n * (reach + gap);
                    let case = format!("{name} at {degrees}°, {along} along, gap {gap}");
                    let m = collide(&wedge, Vec2::ZERO, &shape, centre, 1.0).unwrap();
                    assert!((m.normal - n).length() < 1e-5, "{case}: {m:?}");
                    assert!((m.separation - gap).abs() < 1e-5, "{case}: {m:?}");
                    for p in m.points() {
                        assert!(
                            ((*p - Vec2::new(-2.0, 0.0)).dot(n) - 0.5 * gap).abs() < 1e-5,
                            "{case}: {m:?}"
                        );
                    }
                }
            }
            // Inside it, and on its middle: out by a face, defined.
            for inside in [Vec2::new(1.5, 0.2), Vec2::new(0.7, 0.5 * h / 2.0)] {
                let m = collide(&wedge, Vec2::ZERO, &shape, inside, 1.0).unwrap();
                assert!(
                    (m.normal.length() - 1.0).abs() < 1e-5 && m.separation < 0.0,
                    "{name}: {m:?}"
                );
                let out = inside - m.normal * m.separation;
                let touching = collide(&wedge, Vec2::ZERO, &shape, out, 1.0).unwrap();
                assert!(
                    touching.separation.abs() < 1e-4,
                    "{name} from {inside}: {touching:?}"
                );
            }
        }
    }
}

#[test]
fn bodies_rest_on_a_polygon_and_rays_meet_it_and_a_bad_one_is_refused() {
    let mut world = World::default();
    // A ramp of 20° (friction holds) as a static polygon.
    let h = 4.0 * 20f32.to_radians().tan();
    let ramp = world
        .add_body(BodyDef::new_static(
            Vec2::ZERO,
            Shape::polygon(&[Vec2::new(-2.0, 0.0), Vec2::new(2.0, 0.0), Vec2::new(2.0, h)])
                .unwrap(),
        ))
        .unwrap();
    let n = Vec2::new(4.0, h).normalize().perp();
    let start = Vec2::new(0.0, 0.5 * h) + n * (0.25 + 0.001);
    let ball = world.add_body(BodyDef::new_dynamic(start, Shape::rect(0.5, 0.5)));
    assert!(ball.is_ok());
    for _ in 0..120 {
        world.step(DT);
    }
    assert!(max_penetration(&world) < 0.006);
    // A ray straight down meets the slope at its height.
    let hit = world
        .ray_cast(Vec2::new(-1.0, 5.0), -Vec2::Y, 10.0)
        .unwrap();
    assert_eq!(hit.body, ramp);
    assert!((hit.distance - (5.0 - 0.25 * h)).abs() < 1e-5, "{hit:?}");
    assert!((hit.normal - n).length() < 1e-5);
    // Not convex, too few points, repeated, or on a dynamic body: refused.
    let star = [
        Vec2::ZERO,
        Vec2::new(2.0, 0.0),
        Vec2::new(1.0, 0.2),
        Vec2::new(1.0, 2.0),
    ];
    assert!(Shape::polygon(&star).is_err());
    assert!(Shape::polygon(&[Vec2::ZERO, Vec2::X]).is_err());
    assert!(Shape::polygon(&[Vec2::ZERO, Vec2::X, Vec2::X, Vec2::Y]).is_err());
    assert!(Shape::polygon(&[Vec2::ZERO, Vec2::X, Vec2::new(2.0, 0.0)]).is_err());
    assert!(Shape::polygon(&[Vec2::ZERO; 9]).is_err());
    let square = Shape::polygon(&[Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y]).unwrap();
    let error = world
        .add_body(BodyDef::new_dynamic(Vec2::ZERO, square))
        .unwrap_err();
    assert!(error.to_string().contains("BodyDef::shape"), "{error}");
}

#[test]
fn fast_bodies_never_pass_through_thin_sloped_ground() {
    // A chain, a plain segment and a polygon's edge, each met by circles
    // and capsules at up to 300 m/s (5 m a tick, 20 times their size),
    // at several angles: each stops on the near side.
    for speed in [30.0f32, 100.0, 300.0] {
        for degrees in [-60.0f32, -30.0, -90.0] {
            for ground in 0..3 {
                let mut world = World::default();
                match ground {
                    0 => {
                        world
                            .add_chain(&ChainDef::new(vec![
                                Vec2::new(-50.0, 0.0),
                                Vec2::new(50.0, 2.0),
                            ]))
                            .unwrap();
                    }
                    1 => {
                        world
                            .add_body(BodyDef::new_static(
                                Vec2::ZERO,
                                Shape::segment(Vec2::new(-50.0, -1.0), Vec2::new(50.0, 1.0)),
                            ))
                            .unwrap();
                    }
                    _ => {
                        world
                            .add_body(BodyDef::new_static(
                                Vec2::ZERO,
                                Shape::polygon(&[
                                    Vec2::new(-50.0, -3.0),
                                    Vec2::new(50.0, -3.0),
                                    Vec2::new(50.0, 1.0),
                                    Vec2::new(-50.0, -1.0),
                                ])
                                .unwrap(),
                            ))
                            .unwrap();
                    }
                }
                for shape in [Shape::circle(0.1), Shape::capsule(0.2, 0.5)] {
                    let velocity = Vec2::from_angle(degrees.to_radians()) * speed;
                    let id = world
                        .add_body(
                            BodyDef::new_dynamic(Vec2::new(0.0, 12.0), shape)
                                .with_velocity(velocity),
                        )
                        .unwrap();
                    for tick in 0..60 {
                        world.step(DT);
                        let p = world.body(id).unwrap().position;
                        // Above the ground's line, y = x / 50, while over
                        // it (it may slide off an end).
                        if p.x.abs() < 49.0 {
                            assert!(
                                p.y > p.x / 50.0 - 0.01,
                                "{speed} m/s at {degrees}°, ground {ground}, {shape:?}, tick {tick}: {p}"
                            );
                        }
                    }
                    world.remove_body(id).unwrap();
                }
            }
        }
    }
}

#[test]
fn a_capsule_at_rest_on_a_chain_sleeps_and_a_sensor_polygon_sees_it_come() {
    let mut world = World::default();
    world
        .add_chain(&ChainDef::new(vec![
            Vec2::new(-10.0, 0.0),
            Vec2::new(0.0, 0.0),
            Vec2::new(10.0, 1.0),
        ]))
        .unwrap();
    let sensor = world
        .add_body(BodyDef {
            sensor: true,
            // Above where it comes to rest: bodies inside a sensor stay
            // awake.
            ..BodyDef::new_static(
                Vec2::new(-3.0, 2.25),
                Shape::polygon(&[
                    Vec2::new(-1.0, -0.75),
                    Vec2::new(1.0, -0.75),
                    Vec2::new(0.0, 0.75),
                ])
                .unwrap(),
            )
        })
        .unwrap();
    let pill = world
        .add_body(BodyDef::new_dynamic(
            Vec2::new(-3.0, 4.0),
            Shape::capsule(0.3, 0.8),
        ))
        .unwrap();
    let mut entered = 0;
    for _ in 0..600 {
        world.step(DT);
        entered += world
            .events()
            .sensor_begin
            .iter()
            .filter(|e| e.sensor == sensor && e.visitor == pill)
            .count();
    }
    assert_eq!(entered, 1, "the sensor saw it come once");
    assert_eq!(world.is_asleep(pill), Some(true));
    let y = world.body(pill).unwrap().position.y;
    assert!((y - 0.4).abs() < 0.006, "{y}");
}
