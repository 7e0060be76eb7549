//! Queries a game makes every frame: rays, points, boxes and swept shapes
//! with a filter, the contacts of one body, and events read once per frame.

use crate::support::contacts_seen_from;
use passo_physics::glam::Vec2;
use passo_physics::{Aabb, BodyDef, BodyId, CollisionFilter, QueryFilter, Shape, World};

const DT: f32 = 1.0 / 60.0;

fn ground(world: &mut World) -> BodyId {
    world
        .add_body(BodyDef::new_static(
            Vec2::new(0.0, -0.5),
            Shape::rect(40.0, 1.0),
        ))
        .unwrap()
}

fn circle(world: &mut World, position: Vec2, radius: f32) -> BodyId {
    world
        .add_body(BodyDef {
            position,
            shape: Some(Shape::circle(radius)),
            ..Default::default()
        })
        .unwrap()
}

#[test]
fn a_ray_from_inside_the_player_excluding_it_finds_the_ground_past_a_sensor() {
    let mut world = World::default();
    let floor = ground(&mut world);
    let player = world
        .add_body(BodyDef {
            position: Vec2::new(0.0, 2.0),
            shape: Some(Shape::rect(0.8, 1.6)),
            ..Default::default()
        })
        .unwrap();
    let coin = world
        .add_body(BodyDef {
            sensor: true,
            ..BodyDef::new_static(Vec2::new(0.0, 0.6), Shape::circle(0.3))
        })
        .unwrap();
    let down = -Vec2::Y;
    // Unfiltered: the ray starts inside the player.
    assert_eq!(
        world
            .ray_cast(Vec2::new(0.0, 2.0), down, 10.0)
            .unwrap()
            .body,
        player
    );
    let all_but_player = QueryFilter::default().excluding(player);
    let hit = world
        .ray_cast_with(Vec2::new(0.0, 2.0), down, 10.0, &all_but_player)
        .unwrap();
    assert_eq!(hit.body, coin, "the sensor is in the way");
    let solid = QueryFilter::solid().excluding(player);
    let hit = world
        .ray_cast_with(Vec2::new(0.0, 2.0), down, 10.0, &solid)
        .unwrap();
    assert_eq!(hit.body, floor);
    assert!((hit.distance - 2.0).abs() < 1e-6);
    assert_eq!(hit.normal, Vec2::Y);
    // Layers: the ground on layer 2 is not seen by a mask of layer 1.
    world
        .set_filter(
            floor,
            CollisionFilter {
                layers: 2,
                mask: u32::MAX,
            },
        )
        .unwrap();
    assert!(
        world
            .ray_cast_with(Vec2::new(0.0, 2.0), down, 10.0, &solid.with_mask(1))
            .is_none()
    );
    assert_eq!(
        world.query_point_with(Vec2::new(0.0, 0.6), &QueryFilter::solid()),
        Vec::<BodyId>::new()
    );
    assert_eq!(world.query_point(Vec2::new(0.0, 0.6)), [coin]);
}

/// A reference ray test, by brute force over every body: the distance at
/// which the ray enters a circle or a box.
fn reference_ray(world: &World, origin: Vec2, dir: Vec2, max: f32) -> Option<(f32, BodyId)> {
    let mut best: Option<(f32, BodyId)> = None;
    for b in world.bodies() {
        let t = match b.shape.unwrap() {
            Shape::Circle { radius } => {
                let m = origin - b.position;
                let (bq, c) = (m.dot(dir), m.length_squared() - radius * radius);
                if c <= 0.0 {
                    Some(0.0)
                } else if bq > 0.0 || bq * bq - c < 0.0 {
                    None
                } else {
                    Some(-bq - (bq * bq - c).sqrt())
                }
            }
            Shape::Box { half_extents } => {
                let (lo, hi) = (b.position - half_extents, b.position + half_extents);
                let (mut t0, mut t1) = (0.0f32, f32::INFINITY);
                for axis in 0..2 {
                    if dir[axis] == 0.0 {
                        if origin[axis] < lo[axis] || origin[axis] > hi[axis] {
                            t0 = f32::INFINITY;
                        }
                        continue;
                    }
                    let (a, c) = (
                        (lo[axis] - origin[axis]) / dir[axis],
                        (hi[axis] - origin[axis]) / dir[axis],
                    );
                    t0 = t0.max(a.min(c));
                    t1 = t1.min(a.max(c));
                }
                (t0 <= t1).then_some(t0)
            }
            Shape::Capsule {
                half_segment,
                radius,
            } => {
                // Sphere tracing: step by the distance to the capsule (the
                // distance to its segment less its radius) until on it.
                let distance = |t: f32| {
                    let local = origin + dir * t - b.position;
                    (local - local.clamp(-half_segment, half_segment)).length() - radius
                };
                let mut t = 0.0f32;
                let mut hit = None;
                while t <= max + 1.0 {
                    let d = distance(t);
                    if d <= 1e-6 {
                        hit = Some(t);
                        break;
                    }
                    t += d;
                }
                hit
            }
            // A ray crossing the segment: where it meets its line.
            Shape::Segment { half } | Shape::ChainSegment { half, .. } => {
                let (a, ab) = (b.position - half, 2.0 * half);
                let denom = dir.perp_dot(ab);
                let t = (a - origin).perp_dot(ab) / denom;
                let s = (a - origin).perp_dot(dir) / denom;
                (denom != 0.0 && t >= 0.0 && (0.0..=1.0).contains(&s)).then_some(t)
            }
            // Not in these worlds.
            Shape::Polygon(_) => None,
        };
        if let Some(t) = t.filter(|&t| t <= max)
            && best.is_none_or(|(bt, id)| (t, b.id) < (bt, id))
        {
            best = Some((t, b.id));
        }
    }
    best
}

#[test]
fn rays_find_what_brute_force_finds_as_the_world_moves_and_changes() {
    let mut world = World::default();
    ground(&mut world);
    let mut seed = 7u32;
    let mut next = move || {
        seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (seed >> 8) as f32 / (1u32 << 24) as f32
    };
    let mut ids = Vec::new();
    for _ in 0..300 {
        let p = Vec2::new(next() * 36.0 - 18.0, next() * 20.0 + 1.0);
        let def = BodyDef {
            position: p,
            shape: Some(match (next() * 3.0) as u32 {
                0 => Shape::circle(0.1 + next() * 0.4),
                1 => Shape::rect(0.2 + next(), 0.2 + next()),
                _ => Shape::capsule(0.2 + next(), 0.2 + next()),
            }),
            ..Default::default()
        };
        ids.push(world.add_body(def).unwrap());
    }
    for round in 0..6 {
        for _ in 0..40 {
            let origin = Vec2::new(next() * 40.0 - 20.0, next() * 22.0);
            let dir = Vec2::from_angle(next() * std::f32::consts::TAU);
            let got = world
                .ray_cast(origin, dir, 15.0)
                .map(|h| (h.distance, h.body));
            let want = reference_ray(&world, origin, dir, 15.0);
            match (got, want) {
                (Some((t, a)), Some((u, b))) => {
                    // Two f32 formulas of the same distance, up to 15 m.
                    assert!((t - u).abs() < 1e-3, "round {round}: {t} against {u}");
                    assert!(
                        a == b || (t - u).abs() < 1e-3,
                        "round {round}: {a:?} against {b:?}"
                    );
                }
                (None, None) => {}
                other => panic!("round {round}: {other:?}"),
            }
        }
        // Change the world between rounds: step, move one by hand, remove
        // one, add one.
        world.step(DT);
        world.set_position(ids[round], Vec2::new(0.0, 30.0 + round as f32));
        world.remove_body(ids[100 + round]).unwrap();
        circle(&mut world, Vec2::new(round as f32, 12.0), 0.3);
        assert_eq!(
            world
                .ray_cast(Vec2::new(0.0, 40.0), -Vec2::Y, 100.0)
                .unwrap()
                .body,
            ids[round],
            "the body just moved to the top is found there"
        );
    }
}

#[test]
fn points_and_boxes_come_back_in_id_order_from_both_trees() {
    let mut world = World::default();
    let floor = ground(&mut world);
    let a = circle(&mut world, Vec2::new(1.0, 1.0), 0.5);
    let b = circle(&mut world, Vec2::new(1.4, 1.0), 0.5);
    assert_eq!(world.query_point(Vec2::new(1.2, 1.0)), [a, b]);
    let area = Aabb::from_centre(Vec2::new(1.0, 0.2), Vec2::new(0.5, 0.3));
    assert_eq!(world.query_aabb(area), [floor, a, b]);
    assert_eq!(
        world.query_aabb_with(area, &QueryFilter::default().excluding(a)),
        [floor, b]
    );
}

#[test]
fn shape_casts_stop_at_the_closed_form_time_of_impact() {
    let mut world = World::default();
    let floor = ground(&mut world);
    let ball = circle(&mut world, Vec2::new(5.0, 3.0), 0.5);
    let filter = QueryFilter::default();
    // A circle of 0.25 dropped from (5, 6) meets the ball (radius 0.5) when
    // the centres are 0.75 apart: at y = 3.75, fraction (6 - 3.75) / 6.
    let hit = world
        .cast_shape(
            &Shape::circle(0.25),
            Vec2::new(5.0, 6.0),
            Vec2::new(0.0, -6.0),
            &filter,
        )
        .unwrap();
    assert_eq!(hit.body, ball);
    assert!((hit.fraction * 6.0 - 2.25).abs() < 1e-5);
    assert!((hit.normal - Vec2::Y).length() < 1e-6);
    assert!((hit.point - Vec2::new(5.0, 3.5)).length() < 1e-5);
    // Excluding the ball, it falls to the ground: its bottom at y = 0.
    let hit = world
        .cast_shape(
            &Shape::circle(0.25),
            Vec2::new(5.0, 6.0),
            Vec2::new(0.0, -6.0),
            &filter.excluding(ball),
        )
        .unwrap();
    assert_eq!(hit.body, floor);
    assert!((hit.fraction * 6.0 - 5.75).abs() < 1e-5);
    // A box slid sideways into the ball: box half width 0.3, so its right
    // face meets the circle's leftmost point (4.5, 3) at x = 4.2.
    let hit = world
        .cast_shape(
            &Shape::rect(0.6, 0.6),
            Vec2::new(0.0, 3.0),
            Vec2::new(8.0, 0.0),
            &filter,
        )
        .unwrap();
    assert_eq!(hit.body, ball);
    assert!((hit.fraction * 8.0 - 4.2).abs() < 1e-5);
    assert!((hit.normal + Vec2::X).length() < 1e-6);
    // A box grazing the floor's top (touching, not overlapping) is no hit.
    assert!(
        world
            .cast_shape(
                &Shape::rect(1.0, 1.0),
                Vec2::new(-10.0, 0.5),
                Vec2::new(5.0, 0.0),
                &filter
            )
            .is_none()
    );
    // Bad input gives no hit rather than a panic.
    let nan = Vec2::new(f32::NAN, 0.0);
    assert!(
        world
            .cast_shape(&Shape::circle(0.2), nan, Vec2::X, &filter)
            .is_none()
    );
    assert!(
        world
            .cast_shape(&Shape::circle(0.0), Vec2::ZERO, Vec2::X, &filter)
            .is_none()
    );
}

#[test]
fn contacts_of_a_body_are_the_contacts_naming_it() {
    let mut world = World::default();
    ground(&mut world);
    let mut ids = Vec::new();
    for i in 0..200 {
        ids.push(circle(
            &mut world,
            Vec2::new((i % 20) as f32 * 0.45 - 4.5, 0.3 + (i / 20) as f32 * 0.45),
            0.2,
        ));
    }
    for round in 0..4 {
        for _ in 0..30 {
            world.step(DT);
        }
        for &id in ids.iter().step_by(7) {
            let want = contacts_seen_from(&world, id);
            let got: Vec<_> = world.contacts_of(id).collect();
            assert_eq!(got, want, "round {round}, {id:?}");
        }
        world.remove_body(ids[round * 3]).unwrap();
        assert_eq!(
            world.contacts_of(ids[round * 3]).count(),
            0,
            "a removed body has none"
        );
    }
}

#[test]
fn a_game_reading_events_once_per_frame_sees_each_step_once() {
    let mut world = World::default();
    ground(&mut world);
    // Touching the ground from the start: the contact begins in step 1.
    let ball = circle(&mut world, Vec2::new(0.0, 0.5), 0.5);
    let mut handled = 0u64;
    let mut begins = 0;
    // Frames with 0, 1 and 2 ticks, as a fixed-timestep loop gives them.
    for ticks in [1, 0, 0, 2, 0, 1, 0] {
        for _ in 0..ticks {
            world.step(DT);
        }
        let events = world.events();
        if events.step != handled {
            handled = events.step;
            begins += events
                .begin
                .iter()
                .filter(|p| p.a == ball || p.b == ball)
                .count();
        }
    }
    assert_eq!(handled, 4, "the last step handled");
    assert_eq!(begins, 1, "the landing began once, read once");
}

#[test]
fn a_ray_from_afar_hits_a_small_circle_exactly_with_a_unit_normal() {
    // A ray's quadratic, written as b^2 - c, subtracted two numbers of the
    // distance squared: from 100 m a 5 cm circle's hit was 2 cm off with a
    // normal 1.17 long, and from 300 m the hit was the centre with a zero
    // normal. Hand-solved: the line y = h meets the circle at
    // x = -sqrt(r^2 - h^2), whose normal is (x, h) / r.
    let r = 0.05;
    let mut world = World::default();
    world
        .add_body(BodyDef::new_static(Vec2::ZERO, Shape::circle(r)))
        .unwrap();
    for distance in [1.0f32, 100.0, 300.0, 10_000.0] {
        for h in [0.0f32, 0.01, -0.03, 0.049] {
            let hit = world
                .ray_cast(Vec2::new(-distance, h), Vec2::X, 2.0 * distance)
                .unwrap_or_else(|| panic!("{distance} m, {h}: no hit"));
            let x = -(r * r - h * h).sqrt();
            let want = Vec2::new(x, h) / r;
            let case = format!("{distance} m, line y = {h}: {hit:?}");
            // The distance as exact as the origin's f32 allows.
            let tolerance = 1e-6 + distance * f32::EPSILON;
            assert!((hit.distance - (distance + x)).abs() <= tolerance, "{case}");
            assert!((hit.normal.length() - 1.0).abs() < 1e-5, "{case}");
            assert!((hit.normal - want).length() < 1e-4, "{case}");
        }
    }
    // From the edge of the world (a ray from farther gives no hit: see
    // `queries_from_beyond_the_worlds_limits_give_no_hit`), and heading
    // away (no hit).
    let edge = passo_physics::constants::MAX_COORDINATE;
    let hit = world
        .ray_cast(Vec2::new(0.0, -edge), Vec2::Y, f32::INFINITY)
        .unwrap();
    assert_eq!((hit.distance, hit.normal), (edge - r, -Vec2::Y));
    assert!(
        world
            .ray_cast(Vec2::new(-5.0, 0.0), -Vec2::X, 100.0)
            .is_none()
    );
}

/// A ray or a cast starting (or, for a cast, ending) where no body may be
/// gives no hit: a ray from (3.4e38, 3.4e38) toward a body once reported a
/// hit at an infinite distance and point.
#[test]
fn queries_from_beyond_the_worlds_limits_give_no_hit() {
    use passo_physics::constants::MAX_COORDINATE;
    let mut world = World::default();
    // A wall covering the whole diagonal the rays cross.
    let wall = BodyDef::new_static(Vec2::ZERO, Shape::rect(1.0e6, 1.0e6));
    world.add_body(wall).unwrap();
    let toward = Vec2::new(-1.0, -1.0);
    for far in [3.4e38f32, 1.0e20, MAX_COORDINATE * 1.01] {
        let origin = Vec2::splat(far);
        assert_eq!(world.ray_cast(origin, toward, f32::INFINITY), None, "{far}");
        let filter = QueryFilter::default();
        let circle = Shape::circle(0.5);
        assert!(
            world
                .cast_shape(&circle, origin, -origin, &filter)
                .is_none(),
            "{far}"
        );
        // From inside the limits to beyond them.
        assert!(
            world
                .cast_shape(&circle, Vec2::ZERO, origin, &filter)
                .is_none(),
            "{far}"
        );
    }
    // At the limit itself, the same ray hits the wall at a finite point.
    let origin = Vec2::splat(MAX_COORDINATE);
    let hit = world
        .ray_cast(origin, toward, f32::INFINITY)
        .expect("a hit");
    assert!(hit.distance.is_finite() && hit.point.is_finite(), "{hit:?}");
    assert!((hit.point - Vec2::splat(5.0e5)).length() < 1.0, "{hit:?}");
}
