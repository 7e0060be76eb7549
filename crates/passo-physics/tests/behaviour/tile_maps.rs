//! Tile maps: levels drawn on a grid become as few boxes as they need,
//! with no ghost collisions at the joints between them, per-cell material
//! and one-way cells.

use crate::support::{assert_falls_freely_along_a_wall, assert_slides_as_on_one_box, push_along_x};
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, BodyId, BodyKind, Shape, TileKind, TileMap, World};

const DT: f32 = 1.0 / 60.0;

/// A ground `width` cells long whose top row (y = 0) alternates plain and
/// slippery-but-frictionless-to-the-body runs, over rows cut into runs of
/// other lengths and kinds, with holes: the merged boxes meet at joints
/// of every sort along the surface.
fn patchwork_ground(width: u32) -> TileMap {
    let mut map = TileMap::new(width, 3, Vec2::ONE, Vec2::new(-0.5, -3.0)).unwrap();
    let solid = map.add_kind(TileKind::SOLID).unwrap();
    let ice = map.add_kind(TileKind::ICE).unwrap();
    let bouncy = map.add_kind(TileKind::BOUNCY).unwrap();
    for x in 0..width {
        // Top row: runs of 7 cells, alternating kinds.
        map.set(x, 2, Some(if (x / 7) % 2 == 0 { solid } else { ice }))
            .unwrap();
        // Middle row: runs of 5, with a hole every 11 cells.
        let middle = if x % 11 == 3 {
            None
        } else {
            Some(if (x / 5) % 2 == 0 { ice } else { solid })
        };
        map.set(x, 1, middle).unwrap();
        // Bottom row: runs of 3.
        map.set(x, 0, Some(if (x / 3) % 2 == 0 { bouncy } else { solid }))
            .unwrap();
    }
    map
}

/// The body, with no friction of its own (so every kind of cell is the
/// same to it), resting at `x` on top of the map (y = 0).
fn body_on(world: &mut World, shape: Shape, x: f32) -> BodyId {
    let def = BodyDef {
        friction: 0.0,
        ..BodyDef::new_dynamic(Vec2::new(x, shape.half_extents().y), shape)
    };
    world.add_body(def).unwrap()
}

#[test]
fn a_box_and_a_circle_slide_across_200_cells_as_on_one_box() {
    let map = patchwork_ground(210);
    let rects = map.rects();
    // The surface row alone is 30 runs; the map is far fewer boxes than
    // its 612 solid cells less its holes.
    assert!(rects.len() < 210, "{} boxes", rects.len());
    let ticks = 2_040;
    for shape in [Shape::rect(0.6, 1.0), Shape::circle(0.4)] {
        let mut tiled = World::default();
        tiled.add_tile_map(&map, BodyKind::Static).unwrap();
        let a = body_on(&mut tiled, shape, 0.0);
        let mut one = World::default();
        one.add_body(BodyDef::new_static(
            Vec2::new(104.5, -1.5),
            Shape::rect(210.0, 3.0),
        ))
        .unwrap();
        let b = body_on(&mut one, shape, 0.0);
        let on_tiles = push_along_x(&mut tiled, a, 6.0, ticks, DT);
        let reference = push_along_x(&mut one, b, 6.0, ticks, DT);
        let end = tiled.body(a).unwrap().position.x;
        assert!(end > 200.0, "{shape:?} crossed the map: at {end}");
        assert_slides_as_on_one_box(&on_tiles, &reference, &format!("{shape:?} on the map"));
    }
}

#[test]
fn a_box_slides_down_a_wall_of_cells_of_many_kinds_without_catching() {
    // A wall 40 cells tall whose kinds change every 3 cells, beside a
    // column that changes every 4: merged boxes of many heights.
    let mut map = TileMap::new(2, 40, Vec2::ONE, Vec2::new(-2.0, 0.0)).unwrap();
    let kinds = [TileKind::SOLID, TileKind::ICE, TileKind::BOUNCY];
    let ids: Vec<u8> = kinds.iter().map(|k| map.add_kind(*k).unwrap()).collect();
    for y in 0..40 {
        map.set(0, y, Some(ids[(y / 4) as usize % 3])).unwrap();
        map.set(1, y, Some(ids[(y / 3) as usize % 3])).unwrap();
    }
    let mut world = World::default();
    world.add_tile_map(&map, BodyKind::Static).unwrap();
    let body = world
        .add_body(BodyDef {
            friction: 0.0,
            ..BodyDef::new_dynamic(Vec2::new(0.3, 38.0), Shape::rect(0.6, 0.6))
        })
        .unwrap();
    assert_falls_freely_along_a_wall(&mut world, body, DT, |b| {
        assert!(
            b.velocity.x.abs() < 1e-4,
            "no sideways kick: {}",
            b.velocity.x
        );
    });
}

#[test]
fn ice_cells_let_a_box_slide_as_far_as_coulomb_friction_says() {
    // A box (mu 0.6) at 3 m/s on ice (mu 0.02): the contact's friction is
    // the geometric mean, sqrt(0.012), so it stops after v² / (2 mu g).
    let map = TileMap::from_ascii("~~~~~~~~~~~~~~~~~~~~", Vec2::ONE, Vec2::new(0.0, -1.0)).unwrap();
    let mut world = World::default();
    world.add_tile_map(&map, BodyKind::Static).unwrap();
    let body = world
        .add_body(BodyDef::new_dynamic(
            Vec2::new(2.0, 0.25),
            Shape::rect(0.5, 0.5),
        ))
        .unwrap();
    for _ in 0..10 {
        world.step(DT);
    }
    world.set_velocity(body, Vec2::new(3.0, 0.0));
    let start = world.body(body).unwrap().position.x;
    for _ in 0..600 {
        world.step(DT);
    }
    let mu = (0.6f32 * 0.02).sqrt();
    let expected = 9.0 / (2.0 * mu * 9.81);
    let slid = world.body(body).unwrap().position.x - start;
    assert!(
        (slid - expected).abs() < 0.05 * expected,
        "slid {slid} m, Coulomb says {expected}"
    );
}

#[test]
fn a_ball_bounces_on_bouncy_cells_and_stops_on_solid_ones() {
    let map = TileMap::from_ascii("^^^^^#####", Vec2::ONE, Vec2::new(0.0, -1.0)).unwrap();
    let mut world = World::default();
    world.add_tile_map(&map, BodyKind::Static).unwrap();
    let drop = |world: &mut World, x: f32| {
        world
            .add_body(BodyDef::new_dynamic(
                Vec2::new(x, 2.25),
                Shape::circle(0.25),
            ))
            .unwrap()
    };
    let (bouncy, solid) = (drop(&mut world, 2.5), drop(&mut world, 7.5));
    let mut highest_after_bounce = [f32::MIN; 2];
    let mut fell = [false; 2];
    for _ in 0..120 {
        world.step(DT);
        for (k, id) in [bouncy, solid].into_iter().enumerate() {
            let b = world.body(id).unwrap();
            fell[k] |= b.velocity.y > 0.5;
            if fell[k] {
                highest_after_bounce[k] = highest_after_bounce[k].max(b.position.y);
            }
        }
    }
    // Restitution 0.9 of a 2 m drop: back up to about 0.81 × 2 m.
    assert!(fell[0], "the ball bounced on the bouncy cells");
    assert!(
        highest_after_bounce[0] - 0.25 > 0.7 * 2.0,
        "{}",
        highest_after_bounce[0]
    );
    assert!(!fell[1], "no bounce on solid cells");
}

#[test]
fn one_way_cells_are_landed_on_from_above_and_jumped_through_from_below() {
    let map = TileMap::from_ascii(
        "
        ..----..
        ........
        ........
        ########",
        Vec2::ONE,
        Vec2::ZERO,
    )
    .unwrap();
    let mut world = World::default();
    world.add_tile_map(&map, BodyKind::Static).unwrap();
    // A ball jumping from the floor through the ledge (top at y = 4),
    // and one dropped on it from above.
    let jumper = world
        .add_body(
            BodyDef::new_dynamic(Vec2::new(3.5, 1.25), Shape::circle(0.25))
                .with_velocity(Vec2::new(0.0, 10.0)),
        )
        .unwrap();
    let dropped = world
        .add_body(BodyDef::new_dynamic(
            Vec2::new(4.5, 6.0),
            Shape::circle(0.25),
        ))
        .unwrap();
    let mut highest = 0.0f32;
    for _ in 0..180 {
        world.step(DT);
        highest = highest.max(world.body(jumper).unwrap().position.y);
    }
    assert!(
        highest > 4.5,
        "the jumper went up through the ledge: {highest}"
    );
    let y = |id| world.body(id).unwrap().position.y;
    assert!(
        (y(jumper) - 4.25).abs() < 0.01,
        "and landed on it: {}",
        y(jumper)
    );
    assert!(
        (y(dropped) - 4.25).abs() < 0.01,
        "the dropped ball rests on it: {}",
        y(dropped)
    );
}

#[test]
fn a_kinematic_map_carries_its_rider() {
    let map = TileMap::from_ascii("####", Vec2::ONE, Vec2::new(-2.0, -1.0)).unwrap();
    let mut world = World::default();
    let ids = world.add_tile_map(&map, BodyKind::Kinematic).unwrap();
    assert_eq!(ids.len(), 1, "one run, one box");
    let rider = world
        .add_body(BodyDef::new_dynamic(
            Vec2::new(0.0, 0.25),
            Shape::rect(0.5, 0.5),
        ))
        .unwrap();
    for _ in 0..30 {
        world.step(DT);
    }
    for &id in &ids {
        world.set_velocity(id, Vec2::new(0.0, 1.0));
    }
    let start = world.body(rider).unwrap().position.y;
    for _ in 0..60 {
        world.step(DT);
    }
    let rose = world.body(rider).unwrap().position.y - start;
    assert!(
        (rose - 1.0).abs() < 0.01,
        "the rider rose {rose} m with the map"
    );
}

#[test]
fn a_dynamic_map_is_refused() {
    let map = TileMap::from_ascii("#", Vec2::ONE, Vec2::ZERO).unwrap();
    let err = World::default()
        .add_tile_map(&map, BodyKind::Dynamic)
        .unwrap_err();
    assert!(err.to_string().contains("Static or Kinematic"), "{err}");
}
