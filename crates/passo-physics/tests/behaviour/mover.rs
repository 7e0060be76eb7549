//! The character mover: move and slide with a skin, steps, snapping down,
//! ground, wall and ceiling reports, riding platforms, one-way platforms,
//! pushing dynamic bodies, and never ending a move inside geometry.

use passo_physics::constants::LINEAR_SLOP;
use passo_physics::glam::Vec2;
use passo_physics::{
    BodyDef, BodyId, BodyKind, CharacterMover, MoveOutcome, Shape, TileKind, TileMap, World,
    collide,
};
use proptest::prelude::*;

const DT: f32 = 1.0 / 60.0;
const HALF: Vec2 = Vec2::new(0.2, 0.4);

fn level(text: &str) -> World {
    let mut world = World::default();
    let map = TileMap::from_ascii(text, Vec2::splat(0.5), Vec2::ZERO).unwrap();
    world.add_tile_map(&map, BodyKind::Static).unwrap();
    world
}

/// A character standing (a skin above the ground) with its centre at `x`
/// on ground whose top is at `ground`.
fn character(world: &mut World, x: f32, ground: f32) -> BodyId {
    let skin = CharacterMover::default().skin;
    character_at(world, Vec2::new(x, ground + HALF.y + skin))
}

/// Moves at `velocity` (m/s) for `ticks` ticks; returns the last outcome.
fn walk(world: &mut World, id: BodyId, velocity: Vec2, ticks: usize) -> MoveOutcome {
    let mover = CharacterMover::default();
    let mut last = MoveOutcome::default();
    for _ in 0..ticks {
        last = world.move_character(id, velocity * DT, &mover, DT).unwrap();
        world.step(DT);
    }
    last
}

/// One tick of standing still: the character moves by nothing (riding,
/// pushed or pushed out, as the mover decides), then the world steps.
fn stand(world: &mut World, id: BodyId) {
    let mover = CharacterMover::default();
    world.move_character(id, Vec2::ZERO, &mover, DT).unwrap();
    world.step(DT);
}

fn at(world: &World, id: BodyId) -> Vec2 {
    world.body(id).unwrap().position
}

#[test]
fn it_walks_on_flat_ground_exactly_as_far_as_asked() {
    let mut world = level("################");
    let id = character(&mut world, 1.0, 0.5);
    let start = at(&world, id);
    let out = walk(&mut world, id, Vec2::new(3.0, -5.0), 60);
    let moved = at(&world, id) - start;
    assert!((moved.x - 3.0).abs() < 1e-3, "moved {moved}");
    assert!(
        moved.y.abs() < 1e-4,
        "stayed a skin above the ground: {moved}"
    );
    assert!(out.on_ground && out.ground.is_some() && out.wall.is_none());
}

#[test]
fn a_wall_stops_it_a_skin_short_and_is_reported() {
    let mut world = level(
        "
        .......#
        .......#
        ########",
    );
    let id = character(&mut world, 1.0, 0.5);
    let out = walk(&mut world, id, Vec2::new(4.0, -5.0), 90);
    let skin = CharacterMover::default().skin;
    let x = at(&world, id).x;
    // The wall's face is at x = 3.5.
    assert!((x - (3.5 - HALF.x - skin)).abs() < 1e-3, "at {x}");
    assert!(out.wall.is_some(), "{out:?}");
}

#[test]
fn it_climbs_a_step_up_to_max_step_and_no_higher() {
    // Steps of 0.25 m, of 0.295 m (just under `max_step`, 0.3 m), of
    // 0.305 m (within a skin over it, climbed too) and of 0.32 m (more than
    // a skin over it), and one of 0.5 m.
    for (height, climbs) in [
        (0.25, true),
        (0.295, true),
        (0.305, true),
        (0.32, false),
        (0.5, false),
    ] {
        let mut world = level("################");
        let step =
            BodyDef::new_static(Vec2::new(5.0, 0.5 + height / 2.0), Shape::rect(4.0, height));
        world.add_body(step).unwrap();
        let id = character(&mut world, 1.0, 0.5);
        let out = walk(&mut world, id, Vec2::new(3.0, -5.0), 60);
        let p = at(&world, id);
        if climbs {
            let top = 0.5 + height + HALF.y + CharacterMover::default().skin;
            assert!(
                (p.y - top).abs() < 2e-3 && p.x > 3.5,
                "{height} m step: at {p}"
            );
        } else {
            assert!(p.x < 3.0 - HALF.x, "{height} m step stops it: at {p}");
            assert!(out.wall.is_some());
        }
    }
}

#[test]
fn it_follows_a_small_drop_and_leaves_the_ground_over_a_big_one() {
    // (0.295 m: just inside `snap_down`, 0.3 m, with the skin the feet
    // keep above the ground on top of it.)
    for (drop, follows) in [(0.25, true), (0.295, true), (0.75, false)] {
        let mut world = World::default();
        let high = BodyDef::new_static(Vec2::new(2.0, -0.5), Shape::rect(4.0, 1.0));
        let low = BodyDef::new_static(Vec2::new(8.0, -0.5 - drop), Shape::rect(8.0, 1.0));
        world.add_body(high).unwrap();
        world.add_body(low).unwrap();
        let id = character(&mut world, 3.0, 0.0);
        // Walking with no fall in the translation: only snapping keeps it
        // on the ground.
        let mover = CharacterMover::default();
        let mut left_ground = false;
        for _ in 0..30 {
            let out = world
                .move_character(id, Vec2::new(3.0, 0.0) * DT, &mover, DT)
                .unwrap();
            world.step(DT);
            left_ground |= !out.on_ground;
        }
        let y = at(&world, id).y;
        if follows {
            assert!(!left_ground, "{drop} m: it stayed on the ground");
            assert!((y - (-drop + HALF.y + mover.skin)).abs() < 2e-3, "at {y}");
        } else {
            assert!(left_ground, "{drop} m: it walked off into the air");
        }
    }
}

#[test]
fn a_ceiling_stops_a_jump_and_is_reported() {
    let mut world = level(
        "
        ########
        ........
        ........
        ########",
    );
    // Ground top at 0.5, ceiling underside at 1.5.
    let id = character(&mut world, 1.0, 0.5);
    let out = walk(&mut world, id, Vec2::new(0.0, 6.0), 30);
    let top = at(&world, id).y + HALF.y;
    assert!(
        (top - (1.5 - CharacterMover::default().skin)).abs() < 1e-3,
        "head at {top}"
    );
    assert!(out.ceiling.is_some());
}

#[test]
fn it_rides_a_moving_platform() {
    let mut world = World::default();
    let platform = world
        .add_body(BodyDef::new_kinematic(
            Vec2::new(0.0, -0.25),
            Shape::rect(3.0, 0.5),
            Vec2::new(2.0, 0.0),
        ))
        .unwrap();
    let id = character(&mut world, 0.0, 0.0);
    let start = at(&world, id);
    let out = walk(&mut world, id, Vec2::new(0.0, -5.0), 60);
    let moved = at(&world, id) - start;
    assert!((moved.x - 2.0).abs() < 0.02, "carried {moved}");
    assert!(moved.y.abs() < 1e-3);
    assert_eq!(out.ground, Some(platform));
}

#[test]
fn it_rides_a_lift_down_without_leaving_it() {
    // A lift going down at 1.5 m/s (2.5 cm a tick, more than the skin).
    let mut world = World::default();
    let lift = world
        .add_body(BodyDef::new_kinematic(
            Vec2::new(0.0, -0.25),
            Shape::rect(3.0, 0.5),
            Vec2::new(0.0, -1.5),
        ))
        .unwrap();
    let id = character(&mut world, 0.0, 0.0);
    let mover = CharacterMover::default();
    for tick in 0..60 {
        let out = world
            .move_character(id, Vec2::new(0.0, -5.0) * DT, &mover, DT)
            .unwrap();
        assert!(
            out.on_ground && out.ground == Some(lift),
            "tick {tick}: {out:?}"
        );
        world.step(DT);
    }
    let gap = at(&world, id).y - HALF.y - (world.body(lift).unwrap().position.y + 0.25);
    assert!(
        (gap - mover.skin).abs() < 1e-3,
        "a skin above the lift: {gap}"
    );
}

#[test]
fn one_way_platforms_are_jumped_through_landed_on_and_dropped_through() {
    let mut world = level(
        "
        ........
        ..----..
        ........
        ........
        ########",
    );
    // Ground top 0.5; the ledge from x 1 to 3, top at 2.0.
    let id = character(&mut world, 2.0, 0.5);
    // Jump up through it, then fall back onto it.
    walk(&mut world, id, Vec2::new(0.0, 8.0), 20);
    assert!(at(&world, id).y - HALF.y > 2.0, "went up through the ledge");
    let out = walk(&mut world, id, Vec2::new(0.0, -5.0), 40);
    let feet = at(&world, id).y - HALF.y;
    assert!(
        (feet - (2.0 + CharacterMover::default().skin)).abs() < 1e-3,
        "on the ledge: {feet}"
    );
    assert!(out.on_ground);
    // Drop through it.
    world.drop_through(id, 0.3);
    walk(&mut world, id, Vec2::new(0.0, -5.0), 40);
    let feet = at(&world, id).y - HALF.y;
    assert!(
        (feet - (0.5 + CharacterMover::default().skin)).abs() < 1e-3,
        "back on the ground: {feet}"
    );
}

#[test]
fn it_pushes_a_crate_as_hard_as_push_mass_says() {
    let push = |push_mass: f32| {
        let mut world = level("####################");
        let crate_ = world
            .add_body(BodyDef::new_dynamic(
                Vec2::new(3.0, 0.75),
                Shape::rect(0.5, 0.5),
            ))
            .unwrap();
        let id = character(&mut world, 1.0, 0.5);
        let mover = CharacterMover {
            push_mass,
            ..CharacterMover::default()
        };
        for _ in 0..120 {
            world
                .move_character(id, Vec2::new(2.0, -5.0) * DT, &mover, DT)
                .unwrap();
            world.step(DT);
        }
        (at(&world, crate_).x, at(&world, id).x)
    };
    let (crate_x, player_x) = push(20.0);
    assert!(crate_x > 4.0, "pushed the crate to {crate_x}");
    // Never faster than the character walks (2 m/s for 2 s from x = 3).
    assert!(crate_x < 3.0 + 2.0 * 2.0 + 0.1, "crate at {crate_x}");
    assert!(
        player_x < crate_x - 0.45,
        "never inside it: {player_x} vs {crate_x}"
    );
    let (crate_x, _) = push(0.0);
    assert!(
        (crate_x - 3.0).abs() < 0.05,
        "push_mass 0 leaves it: {crate_x}"
    );
}

#[test]
fn bad_calls_are_refused() {
    let mut world = level("####");
    let dynamic = world
        .add_body(BodyDef::new_dynamic(
            Vec2::new(1.0, 2.0),
            Shape::circle(0.2),
        ))
        .unwrap();
    let id = character(&mut world, 1.0, 0.5);
    let mover = CharacterMover::default();
    assert!(world.move_character(dynamic, Vec2::X, &mover, DT).is_err());
    assert!(
        world
            .move_character(id, Vec2::new(f32::NAN, 0.0), &mover, DT)
            .is_err()
    );
    assert!(world.move_character(id, Vec2::X, &mover, 0.0).is_err());
    let bad = CharacterMover { skin: 0.0, ..mover };
    assert!(world.move_character(id, Vec2::X, &bad, DT).is_err());
}

/// The deepest overlap of the character with a solid (not one-way) static
/// body.
fn deepest_in_walls(world: &World, id: BodyId) -> f32 {
    let me = world.body(id).unwrap();
    let shape = me.shape.unwrap();
    world
        .bodies()
        .filter(|b| b.kind == BodyKind::Static && b.one_way.is_none())
        .filter_map(|b| collide(&shape, me.position, &b.shape?, b.position, 0.0))
        .map(|m| -m.separation)
        .fold(0.0, f32::max)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn it_never_ends_a_move_inside_a_solid_cell(
        cells in prop::collection::vec(0u8..10, 16 * 12),
        inputs in prop::collection::vec((-6.0f32..6.0, -12.0f32..12.0, 0u8..8), 90),
    ) {
        // A random level of 16 × 12 cells of 0.5 m in a closed room, with
        // a clear spot at the start.
        let mut map = TileMap::new(16, 12, Vec2::splat(0.5), Vec2::ZERO).unwrap();
        let kinds = [TileKind::SOLID, TileKind::ICE, TileKind::ONE_WAY];
        let kinds: Vec<u8> = kinds.iter().map(|k| map.add_kind(*k).unwrap()).collect();
        for y in 0..12u32 {
            for x in 0..16u32 {
                let edge = x == 0 || y == 0 || x == 15 || y == 11;
                let clear = (2..4).contains(&x) && (1..4).contains(&y);
                let cell = cells[(y * 16 + x) as usize];
                let kind = if edge { Some(kinds[0]) } else if clear { None } else {
                    match cell { 0 => Some(kinds[0]), 1 => Some(kinds[1]), 2 => Some(kinds[2]), _ => None }
                };
                map.set(x, y, kind).unwrap();
            }
        }
        let mut world = World::default();
        world.add_tile_map(&map, BodyKind::Static).unwrap();
        let id = character(&mut world, 1.5, 0.5);
        let mover = CharacterMover::default();
        for (vx, vy, drop) in inputs {
            if drop == 0 {
                world.drop_through(id, 0.2);
            }
            world.move_character(id, Vec2::new(vx, vy) * DT, &mover, DT).unwrap();
            world.step(DT);
            let deepest = deepest_in_walls(&world, id);
            prop_assert!(deepest <= LINEAR_SLOP, "{} m inside a solid cell at {}", deepest, at(&world, id));
        }
    }
}

/// A game's tick: game gravity on the character's own velocity, reset on
/// the ground, platforms steered first (see `move_character`).
fn play(
    world: &mut World,
    id: BodyId,
    velocity: &mut Vec2,
    steer: impl Fn(&mut World),
) -> MoveOutcome {
    steer(world);
    velocity.y -= 9.81 * DT;
    let out = world
        .move_character(id, *velocity * DT, &CharacterMover::default(), DT)
        .unwrap();
    if out.on_ground {
        velocity.y = 0.0;
    }
    world.step(DT);
    out
}

/// A lift of `boxes` flush kinematic boxes (3 m wide in all), top at 0,
/// moving at `velocity`; steered by `steer_lift`.
fn lift(world: &mut World, boxes: usize, one_way: bool) -> Vec<BodyId> {
    let w = 3.0 / boxes as f32;
    (0..boxes)
        .map(|k| {
            let x = -1.5 + w * (k as f32 + 0.5);
            let mut def =
                BodyDef::new_kinematic(Vec2::new(x, -0.25), Shape::rect(w, 0.5), Vec2::ZERO);
            if one_way {
                def = def.with_one_way(Vec2::Y);
            }
            world.add_body(def).unwrap()
        })
        .collect()
}

fn steer_lift(world: &mut World, boxes: &[BodyId], velocity: Vec2) {
    for &b in boxes {
        let p = world.body(b).unwrap().position;
        world.set_kinematic_target(b, p + velocity * DT, DT);
    }
}

#[test]
fn it_lands_on_a_moving_lift_and_stays_on_it() {
    // Falling onto a lift going down at 1.5 m/s, one box or two: it used
    // to see the lift a step behind, land a skin above where it was, and
    // bounce on it (on the ground 6 ticks of 120). Falling onto a one-way
    // lift going up, it used to fall through it (29 of 40 drop heights).
    for (boxes, one_way, v) in [
        (1, false, -1.5),
        (2, false, -1.5),
        (1, true, 1.0),
        (1, true, 3.0),
    ] {
        for drop in [0.3f32, 0.77, 1.3] {
            let mut world = World::default();
            let lift = lift(&mut world, boxes, one_way);
            let id = world
                .add_body(BodyDef::new_kinematic(
                    Vec2::new(0.0, drop + HALF.y),
                    Shape::rect(2.0 * HALF.x, 2.0 * HALF.y),
                    Vec2::ZERO,
                ))
                .unwrap();
            let mut velocity = Vec2::ZERO;
            let mut landed = None;
            for tick in 0..120 {
                let out = play(&mut world, id, &mut velocity, |w| {
                    steer_lift(w, &lift, Vec2::new(0.0, v));
                });
                let top = world.body(lift[0]).unwrap().position.y + 0.25;
                let gap = at(&world, id).y - HALF.y - top;
                let what = format!(
                    "{boxes} box(es), one-way {one_way}, {v} m/s, drop {drop}, tick {tick}"
                );
                if let Some(first) = landed {
                    assert!(
                        out.on_ground && lift.contains(&out.ground.unwrap()),
                        "{what}: {out:?}"
                    );
                    assert!((-1e-4..=0.011).contains(&gap), "{what}: gap {gap}");
                    let _: usize = first;
                } else if out.on_ground {
                    landed = Some(tick);
                }
                assert!(gap > -0.01, "{what}: {gap} below the lift's top");
            }
            assert!(
                landed.is_some_and(|t| t < 80),
                "{boxes} {one_way} {v} {drop}: {landed:?}"
            );
        }
    }
}

#[test]
fn a_one_way_ledge_holds_when_a_tick_falls_exactly_onto_it() {
    // With game gravity 36 m/s² at 60 Hz the first tick's fall, g dt², is
    // exactly the skin: the move ended touching the ledge, and the next
    // cast (from touching, fraction 0) was ignored, so it fell through.
    let mut world = World::default();
    let ledge = BodyDef::new_static(Vec2::new(0.0, 1.75), Shape::rect(4.0, 0.5));
    world.add_body(ledge.with_one_way(Vec2::Y)).unwrap();
    let id = character(&mut world, 0.0, 2.0);
    let mut velocity = Vec2::ZERO;
    for tick in 0..60 {
        velocity.y -= 36.0 * DT;
        let out = world
            .move_character(id, velocity * DT, &CharacterMover::default(), DT)
            .unwrap();
        assert!(out.on_ground, "tick {tick}: {out:?}");
        velocity.y = 0.0;
        world.step(DT);
    }
    let feet = at(&world, id).y - HALF.y;
    assert!((2.0 - 1e-4..=2.011).contains(&feet), "on the ledge: {feet}");
}

#[test]
fn a_slow_walk_climbs_a_step_and_a_crate_is_pushed_not_climbed() {
    // A 0.25 m step at 0.3 m/s: the walk's few millimetres a tick never
    // carried it over the edge, and it stood at the step for good.
    let mut world = level("################");
    let step = BodyDef::new_static(Vec2::new(4.0, 0.625), Shape::rect(4.0, 0.25));
    world.add_body(step).unwrap();
    let id = character(&mut world, 1.0, 0.5);
    let mut velocity = Vec2::new(0.3, 0.0);
    for _ in 0..600 {
        play(&mut world, id, &mut velocity, |_| {});
    }
    let p = at(&world, id);
    assert!(
        p.x > 2.2 && (p.y - HALF.y - 0.75).abs() < 0.011,
        "on the step: {p}"
    );
    // A crate as high as a step is a body to push: it used to be climbed.
    let mut world = level("################");
    let crate_ = world
        .add_body(BodyDef::new_dynamic(
            Vec2::new(2.0, 0.5 + 0.125),
            Shape::rect(0.5, 0.25),
        ))
        .unwrap();
    let id = character(&mut world, 1.0, 0.5);
    let mut velocity = Vec2::new(3.0, 0.0);
    for tick in 0..40 {
        let out = play(&mut world, id, &mut velocity, |_| {});
        assert_eq!(out.stepped, 0.0, "tick {tick}");
        assert_ne!(out.ground, Some(crate_), "tick {tick}");
    }
    assert!(world.body(crate_).unwrap().position.x > 2.5, "pushed along");
}

#[test]
fn walking_off_a_crate_does_not_launch_it() {
    // Snapping down off the crate's edge moved the character in a straight
    // line through the crate's corner; caught between it and the floor,
    // the crate flew up 10 m.
    for mass in [5.0, 100.0] {
        let mut world = level("################");
        let crate_ = world
            .add_body(
                BodyDef::new_dynamic(Vec2::new(2.0, 0.5 + 0.125), Shape::rect(0.5, 0.25))
                    .with_mass(mass),
            )
            .unwrap();
        let id = character(&mut world, 2.0, 0.75);
        for _ in 0..30 {
            world.step(DT);
        }
        let mut velocity = Vec2::new(3.0, 0.0);
        let mut fastest: f32 = 0.0;
        for _ in 0..60 {
            play(&mut world, id, &mut velocity, |_| {});
            fastest = fastest.max(world.body(crate_).unwrap().velocity.length());
        }
        assert!(fastest < 1.0, "{mass} kg: the crate reached {fastest} m/s");
        let feet = at(&world, id).y - HALF.y;
        assert!((0.5..=0.511).contains(&feet), "down on the floor: {feet}");
    }
}

#[test]
fn a_fast_kinematic_wall_pushes_it_instead_of_passing_through() {
    // A wall 0.2 m thick and 1 m tall sweeping along the ground at 30, 60
    // and 120 m/s (0.5 to 2 m a tick) into a character 0.4 m wide, from
    // several starting places: the character always ends in front of it,
    // a skin from its face, never behind it or inside it. At 60 and 120
    // m/s the wall used to pass through.
    let mover = CharacterMover::default();
    for speed in [30.0f32, 60.0, 120.0] {
        for k in 0..8 {
            let mut world = level("##########################");
            let player = character(&mut world, 6.0, 0.5);
            let start = Vec2::new(6.0 - 2.5 - k as f32 * 0.13, 1.05);
            let wall = world
                .add_body(BodyDef::new_kinematic(
                    start,
                    Shape::rect(0.2, 1.0),
                    Vec2::new(speed, 0.0),
                ))
                .unwrap();
            for _ in 0..3 {
                // Each tick: the platforms are steered first (the wall
                // keeps its velocity), then the character moves.
                stand(&mut world, player);
                let (p, w) = (at(&world, player).x, at(&world, wall).x);
                let case = format!("{speed} m/s from {start}: wall at {w}, character at {p}");
                assert!(
                    p - HALF.x >= w + 0.1 - 1e-4,
                    "{case}: behind or inside the wall"
                );
                if w + 0.1 >= 6.0 - HALF.x - mover.skin {
                    // The wall reached where the character stood: carried
                    // in front of its face, a skin away.
                    assert!(
                        p - HALF.x - (w + 0.1) <= mover.skin + 1e-3,
                        "{case}: left behind"
                    );
                }
            }
        }
    }
}

#[test]
fn a_fast_wall_meeting_a_character_riding_towards_it_pushes_it_back() {
    // The character rides a platform at 3 or 6 m/s towards a wall coming
    // at 20 or 30 m/s (0.4 to 0.6 m a tick closer, more than its 0.4 m
    // width): the wall always ends in front of it, never passed.
    for (ride, wall_speed) in [(3.0f32, 30.0f32), (6.0, 20.0)] {
        for k in 0..8 {
            let mut world = World::default();
            let platform = BodyDef::new_kinematic(
                Vec2::new(0.0, -0.1),
                Shape::rect(40.0, 0.2),
                Vec2::new(ride, 0.0),
            );
            world.add_body(platform).unwrap();
            let player = character(&mut world, 0.0, 0.0);
            let start = 3.0 + k as f32 * 0.13;
            let wall = world
                .add_body(BodyDef::new_kinematic(
                    Vec2::new(start, 0.55),
                    Shape::rect(0.2, 1.0),
                    Vec2::new(-wall_speed, 0.0),
                ))
                .unwrap();
            for tick in 0..12 {
                stand(&mut world, player);
                let (p, w) = (at(&world, player).x, at(&world, wall).x);
                assert!(
                    p + HALF.x <= w - 0.1 + 1e-3,
                    "riding at {ride} m/s, wall at {wall_speed} m/s from {start}, tick {tick}: \
                     character at {p}, wall at {w}"
                );
            }
        }
    }
}

#[test]
fn a_low_lipped_platform_sliding_into_it_scoops_it_up() {
    // A platform 3 cm high sliding along the floor at 3 m/s into the
    // standing character lifts it onto its top (the push out's shortest
    // way), rather than shoving it along the floor.
    let mover = CharacterMover::default();
    let mut world = level("##########################");
    let player = character(&mut world, 6.0, 0.5);
    let lip = world
        .add_body(BodyDef::new_kinematic(
            Vec2::new(4.0, 0.515),
            Shape::rect(2.0, 0.03),
            Vec2::new(3.0, 0.0),
        ))
        .unwrap();
    for _ in 0..30 {
        stand(&mut world, player);
    }
    let (p, l) = (at(&world, player), at(&world, lip));
    assert!((p.y - (0.53 + HALF.y + mover.skin)).abs() < 2e-3, "{p}");
    assert!(p.x - HALF.x < l.x + 1.0, "over the platform: {p} and {l}");
}

#[test]
fn a_fast_block_at_head_height_never_ends_inside_the_character() {
    // A block 2 m wide whose bottom is 0.3 m below the character's head,
    // sweeping at 20 m/s: too high to scoop it up, so it pushes the
    // character along; it used to pass through it for want of a way out
    // (the ground is under the character).
    let body = Shape::rect(2.0 * HALF.x, 2.0 * HALF.y);
    let block = Shape::rect(2.0, 1.0);
    for k in 0..8 {
        let mut world = level("##########################");
        let player = character(&mut world, 6.0, 0.5);
        let head = at(&world, player).y + HALF.y;
        let start = Vec2::new(10.0 + k as f32 * 0.13, head - 0.3 + 0.5);
        let wall = world
            .add_body(BodyDef::new_kinematic(start, block, Vec2::new(-20.0, 0.0)))
            .unwrap();
        for tick in 0..12 {
            stand(&mut world, player);
            let m = collide(&body, at(&world, player), &block, at(&world, wall), 0.0);
            let depth = m.map_or(0.0, |m| -m.separation);
            assert!(
                depth <= LINEAR_SLOP,
                "from {start}, tick {tick}: {depth} m inside"
            );
        }
    }
}

#[test]
fn a_lift_coming_down_onto_it_crushes_it_and_says_so() {
    // A lift comes down at 1 or 8 m/s onto a character standing on the
    // floor: a thin one (0.3 m) to 0.15 m above the floor, a thick one
    // (0.6 m) all the way down. There is no room. It used to sink through
    // the character's head (by up to 0.46 m, on the ground, no ceiling
    // reported), then throw it on top of the lift.
    let ground = 0.5;
    for (thickness, lowest, speed) in [(0.3, 0.15, 1.0f32), (0.3, 0.15, 8.0), (0.6, 0.0, 3.0)] {
        let mut world = level("..........\n##########");
        let player = character(&mut world, 2.5, ground);
        let shape = Shape::rect(2.0, thickness);
        let lift = BodyDef::new_kinematic(Vec2::new(2.5, 3.5), shape, Vec2::ZERO);
        let lift = world.add_body(lift).unwrap();
        let mover = CharacterMover::default();
        let skin = mover.skin;
        let bottom_stop = ground + lowest;
        let mut crushed_at = None;
        for tick in 1..=240usize {
            let y = (3.5 - speed * tick as f32 * DT).max(bottom_stop + thickness / 2.0);
            world.set_kinematic_target(lift, Vec2::new(2.5, y), DT);
            let out = world
                .move_character(player, Vec2::ZERO, &mover, DT)
                .unwrap();
            world.step(DT);
            let p = at(&world, player);
            let head = p.y + HALF.y;
            let lift_bottom = at(&world, lift).y - thickness / 2.0;
            let case = format!("{thickness} m at {speed} m/s, tick {tick}");
            if out.crushed.is_some() {
                assert_eq!(out.crushed, Some(lift), "{case}");
                crushed_at.get_or_insert(tick);
            } else {
                // Until crushed, never overlapped by more than the skin.
                assert!(
                    lift_bottom >= head - skin - 1e-4,
                    "{case}: {lift_bottom} in {head}"
                );
            }
            // Never thrown on top of the lift: it stays on the floor.
            let standing = ground + HALF.y + skin;
            assert!((p.y - standing).abs() < 0.02, "{case}: {p}");
        }
        let tick = crushed_at.expect("it is crushed");
        // The lift's bottom reaches the head (0.81 m) at this tick.
        let start_bottom = 3.5 - thickness / 2.0;
        let meets = ((start_bottom - (ground + 2.0 * HALF.y + skin)) / speed / DT).ceil() as usize;
        assert!(
            tick.abs_diff(meets) <= 2,
            "{thickness} m at {speed} m/s: tick {tick}, not {meets}"
        );
    }
}

#[test]
fn a_kinematic_wall_pressing_it_against_a_wall_crushes_it_and_says_so() {
    // A kinematic wall (0.2 m thick, 0.6 or 1.2 m tall) slides along the
    // floor at 1, 3 or 8 m/s and presses the character against a static
    // wall: there is no room. The character must never end inside either
    // wall by more than the skin until it is crushed, nor be thrown on top
    // of the kinematic wall or through the static one; once crushed,
    // `crushed` names the kinematic wall, from about the tick the gap closes.
    let cases = [(1.2f32, 1.0f32), (1.2, 3.0), (0.6, 8.0), (1.2, 8.0)];
    // On the floor, and in the air (mid-jump: the mover is given no
    // motion, so it hangs 0.2 m up).
    for ((height, speed), lift) in cases.into_iter().flat_map(|c| [(c, 0.0f32), (c, 0.2)]) {
        let ground = 0.5;
        let mut world = level("..........#\n..........#\n..........#\n###########");
        // The static wall's face is at x = 5.
        let mover = CharacterMover::default();
        let skin = mover.skin;
        let player = character(&mut world, 5.0 - HALF.x - skin, ground + lift);
        let centre_y = ground + height / 2.0;
        let shape = Shape::rect(0.2, height);
        let pusher = BodyDef::new_kinematic(Vec2::new(2.0, centre_y), shape, Vec2::ZERO);
        let pusher = world.add_body(pusher).unwrap();
        // It stops with its face 0.1 m past the static wall's face less the
        // character's width: a 0.1 m squeeze.
        let stop = 5.0 - 2.0 * HALF.x + 0.1 - 0.1;
        let mut crushed_at = None;
        for tick in 1..=240usize {
            let x = (2.0 + speed * tick as f32 * DT).min(stop);
            world.set_kinematic_target(pusher, Vec2::new(x, centre_y), DT);
            let out = world
                .move_character(player, Vec2::ZERO, &mover, DT)
                .unwrap();
            world.step(DT);
            let p = at(&world, player);
            let face = at(&world, pusher).x + 0.1;
            let case =
                format!("{height} m at {speed} m/s, {lift} m up, tick {tick}: {p}, face {face}");
            assert!(p.x + HALF.x <= 5.0 + 1e-4, "{case}: into the static wall");
            let height_kept = (p.y - (ground + lift + HALF.y + skin)).abs() < 0.02;
            assert!(height_kept, "{case}: thrown up or down");
            if out.crushed.is_some() {
                assert_eq!(out.crushed, Some(pusher), "{case}");
                crushed_at.get_or_insert(tick);
            } else {
                assert!(
                    p.x - HALF.x >= face - skin - 1e-4,
                    "{case}: inside the pusher"
                );
            }
        }
        let case = format!("{height} m at {speed} m/s, {lift} m up");
        let tick = crushed_at.unwrap_or_else(|| panic!("{case}: not crushed"));
        // The gap (one skin) closes at this tick.
        let gap_closes = ((5.0 - 2.0 * HALF.x - skin - 2.1) / speed / DT).ceil() as usize;
        assert!(
            tick.abs_diff(gap_closes) <= 2,
            "{case}: tick {tick}, not {gap_closes}"
        );
    }
}

#[test]
fn a_lift_carrying_it_into_a_ceiling_crushes_it_and_says_so() {
    // A character rides a lift (0.2 m thick) going up at 1 or 4 m/s
    // towards a ceiling whose underside is at y = 3; the lift stops 0.1 m
    // short of leaving the character room. It must never be pushed into the
    // ceiling, and `crushed` names the lift from about the tick the gap
    // closes.
    for speed in [1.0f32, 4.0] {
        let mut world = level("######\n......\n......\n......\n......\n......\n......");
        let mover = CharacterMover::default();
        let skin = mover.skin;
        let ceiling = 3.0;
        let start = 0.5;
        let lift_shape = Shape::rect(2.0, 0.2);
        let lift = BodyDef::new_kinematic(Vec2::new(1.5, start - 0.1), lift_shape, Vec2::ZERO);
        let lift = world.add_body(lift).unwrap();
        let player = character(&mut world, 1.5, start);
        let top_stop = ceiling - 2.0 * HALF.y + 0.1;
        let mut crushed_at = None;
        for tick in 1..=240usize {
            let top = (start + speed * tick as f32 * DT).min(top_stop);
            world.set_kinematic_target(lift, Vec2::new(1.5, top - 0.1), DT);
            let out = world
                .move_character(player, Vec2::ZERO, &mover, DT)
                .unwrap();
            world.step(DT);
            let p = at(&world, player);
            let case = format!("{speed} m/s, tick {tick}: {p}");
            assert!(p.y + HALF.y <= ceiling + 1e-4, "{case}: into the ceiling");
            if out.crushed.is_some() {
                assert_eq!(out.crushed, Some(lift), "{case}");
                crushed_at.get_or_insert(tick);
            }
        }
        let tick = crushed_at.unwrap_or_else(|| panic!("{speed} m/s: not crushed"));
        let gap_closes = ((ceiling - 2.0 * HALF.y - skin - start) / speed / DT).ceil() as usize;
        assert!(
            tick.abs_diff(gap_closes) <= 2,
            "{speed} m/s: tick {tick}, not {gap_closes}"
        );
    }
}

/// Walks at `walk` m/s into a crate of `mass` kg from `offset` metres
/// behind the usual start (a fraction of one tick's walk) for 2.5 s with
/// `push_mass`. Returns the crate's fastest speed, its mean speed from the
/// first push on, how far it moved, and the deepest the character went
/// into it.
fn push_run(mass: f32, walk: f32, offset: f32, push_mass: f32) -> (f32, f32, f32, f32) {
    let mut world = level("##################################################");
    let start = Vec2::new(3.0, 0.75);
    let crate_ = world
        .add_body(BodyDef::new_dynamic(start, Shape::rect(0.5, 0.5)).with_mass(mass))
        .unwrap();
    let id = character(&mut world, 1.0 + offset, 0.5);
    let mover = CharacterMover {
        push_mass,
        ..CharacterMover::default()
    };
    let (mut fastest, mut first, mut deepest) = (0.0f32, None, 0.0f32);
    let ticks = 150;
    for tick in 0..ticks {
        world
            .move_character(id, Vec2::new(walk, -5.0) * DT, &mover, DT)
            .unwrap();
        world.step(DT);
        let v = world.body(crate_).unwrap().velocity.x;
        fastest = fastest.max(v);
        if first.is_none() && v > 0.0 {
            first = Some((tick, at(&world, crate_).x));
        }
        let gap = at(&world, crate_).x - 0.25 - (at(&world, id).x + HALF.x);
        deepest = deepest.max(-gap);
    }
    let end = at(&world, crate_).x;
    let mean = first.map_or(0.0, |(tick, x)| {
        (end - x) / ((ticks - 1 - tick) as f32 * DT)
    });
    (fastest, mean, end - start.x, deepest)
}

#[test]
fn a_pushed_crate_never_moves_faster_than_the_character_walks() {
    // A move ending within a skin of a crate let the contacts push it at
    // the walking speed, and the next move's push added the walking speed
    // again: a 4 kg crate left at 8.9 m/s from a 4.5 m/s walk. Swept over
    // start offsets within one tick's walk, crates lighter and heavier
    // than push_mass (20 kg), and walking speeds.
    for (mass, walk) in [(0.5, 3.0), (2.0, 3.0), (4.0, 4.5), (4.0, 9.0), (40.0, 4.5)] {
        for k in 0..75 {
            let offset = walk * DT * k as f32 / 75.0;
            let (fastest, mean, _, deepest) = push_run(mass, walk, offset, 20.0);
            let case = format!("{mass} kg at {walk} m/s from +{offset:.4} m");
            assert!(fastest <= walk * 1.001, "{case}: {fastest} m/s");
            // Pushed along at about the walking speed: friction (0.6 g)
            // takes 0.1 m/s a tick off between pushes.
            assert!(mean >= 0.9 * walk, "{case}: {mean} m/s on average");
            assert!(deepest <= LINEAR_SLOP, "{case}: {deepest} m inside it");
        }
    }
}

#[test]
fn push_mass_zero_never_moves_a_crate() {
    // The character's kinematic body pushed through ordinary contacts:
    // crates moved up to 1.5 m with push_mass 0.
    for (mass, walk) in [(0.5, 3.0), (4.0, 4.5), (4.0, 9.0)] {
        for k in 0..75 {
            let offset = walk * DT * k as f32 / 75.0;
            let (fastest, _, moved, deepest) = push_run(mass, walk, offset, 0.0);
            let case = format!("{mass} kg at {walk} m/s from +{offset:.4} m");
            assert!(
                moved.abs() < 1e-4 && fastest < 1e-3,
                "{case}: moved {moved} m"
            );
            assert!(deepest <= 0.0, "{case}: {deepest} m inside it");
        }
    }
}

#[test]
fn a_crate_dropped_on_its_head_rests_there_standing_and_walking() {
    // The character's contacts stop what comes at it (only a push ahead
    // of it is left to the mover).
    let mut world = level("##################################################");
    let id = character(&mut world, 2.0, 0.5);
    let head = at(&world, id).y + HALF.y;
    let crate_ = world
        .add_body(BodyDef::new_dynamic(
            Vec2::new(2.0, head + 1.0),
            Shape::rect(0.8, 0.3),
        ))
        .unwrap();
    for (speed, ticks) in [(0.0, 60), (1.0, 60)] {
        walk(&mut world, id, Vec2::new(speed, -5.0), ticks);
        let (c, p) = (at(&world, crate_), at(&world, id));
        let gap = c.y - 0.15 - (p.y + HALF.y);
        assert!(
            gap.abs() <= LINEAR_SLOP,
            "{speed} m/s: {gap} m above the head"
        );
        // Carried along by friction (it slides v² / 2 mu g, 8.5 cm at
        // the default 0.6, while it catches up).
        assert!(
            (c.x - p.x).abs() < 0.1,
            "{speed} m/s: crate {c}, character {p}"
        );
    }
}

#[test]
fn it_lands_and_rests_exactly_a_skin_above_the_ground() {
    // `on_ground` came up to 1.5 cm above the floor at the full fall
    // speed, and the game's gravity crept the feet down to 1.8 mm. Swept
    // over drop heights within one tick's fall and walking speeds.
    let skin = CharacterMover::default().skin;
    for k in 0..40 {
        for speed in [0.0, 3.0] {
            let mut world = level("##################################################");
            let drop = 0.5 + 0.2 * k as f32 / 40.0;
            let id = character(&mut world, 2.0, 0.5 + drop);
            let mut velocity = Vec2::new(speed, 0.0);
            let mut landed = None;
            for tick in 0..150 {
                let out = play(&mut world, id, &mut velocity, |_| {});
                let gap = at(&world, id).y - HALF.y - 0.5;
                let case = format!("dropped {drop} m at {speed} m/s, tick {tick}");
                if out.on_ground {
                    assert!(
                        (gap - skin).abs() < 1e-4,
                        "{case}: on the ground {gap} m above it"
                    );
                    landed.get_or_insert(tick);
                } else {
                    assert!(landed.is_none(), "{case}: left the ground at {gap} m");
                }
            }
            assert!(
                landed.is_some_and(|t| t < 30),
                "dropped {drop} m: landed at {landed:?}"
            );
        }
    }
}

#[test]
fn a_capsule_character_walks_over_tile_seams_without_a_bump_and_climbs_a_step() {
    // 0.4 × 0.8 m, round ends of radius 0.2 m, on a floor of 0.5 m cells.
    let skin = CharacterMover::default().skin;
    for k in 0..10 {
        let mut world = level(
            "..................................##\n\
             ####################################",
        );
        let x0 = 1.0 + 0.05 * k as f32;
        let start = Vec2::new(x0, 0.5 + 0.4 + skin);
        let player = world
            .add_body(BodyDef::new_kinematic(
                start,
                Shape::capsule(0.4, 0.8),
                Vec2::ZERO,
            ))
            .unwrap();
        let mut velocity = Vec2::new(4.5, 0.0);
        let mut stepped = 0.0f32;
        for tick in 0..240 {
            let out = play(&mut world, player, &mut velocity, |_| {});
            stepped = stepped.max(out.stepped);
            let p = at(&world, player);
            if p.x < 16.5 {
                // On the flat: level, and exactly as far as asked.
                assert!((p.y - start.y).abs() < 1e-4, "from {x0}, tick {tick}: {p}");
                let expected = x0 + 4.5 * DT * (tick + 1) as f32;
                assert!((p.x - expected).abs() < 1e-3, "from {x0}, tick {tick}: {p}");
                assert!(
                    out.on_ground && out.wall.is_none(),
                    "from {x0}, tick {tick}"
                );
            }
        }
        // The step 0.5 m high (two cells) at x = 17 is a wall; a 0.25 m
        // one is climbed (next world).
        assert_eq!(stepped, 0.0);
        let p = at(&world, player);
        assert!(
            (p.x - (17.0 - 0.2 - skin)).abs() < 2.0 * skin,
            "from {x0}: {p}"
        );
    }
    let mut world = level("################################");
    world
        .add_body(BodyDef::new_static(
            Vec2::new(12.0, 0.625),
            Shape::rect(8.0, 0.25),
        ))
        .unwrap();
    let player = world
        .add_body(BodyDef::new_kinematic(
            Vec2::new(5.0, 0.9 + skin),
            Shape::capsule(0.4, 0.8),
            Vec2::ZERO,
        ))
        .unwrap();
    let mut velocity = Vec2::new(3.0, 0.0);
    for _ in 0..90 {
        play(&mut world, player, &mut velocity, |_| {});
    }
    let p = at(&world, player);
    assert!(
        p.x > 9.0 && (p.y - (0.75 + 0.4 + skin)).abs() < 1e-3,
        "on the step: {p}"
    );
    // At a crawl (0.3 m/s, 5 mm a tick), the climb still carries its round
    // bottom's lowest point over the step's edge: it stays up, going on.
    let mut world = level("################################");
    let step = BodyDef::new_static(Vec2::new(12.0, 0.625), Shape::rect(8.0, 0.25));
    world.add_body(step).unwrap();
    let start = Vec2::new(7.5, 0.9 + skin);
    let def = BodyDef::new_kinematic(start, Shape::capsule(0.4, 0.8), Vec2::ZERO);
    let player = world.add_body(def).unwrap();
    let mut velocity = Vec2::new(0.3, 0.0);
    let mut up = None;
    for tick in 0..120 {
        let out = play(&mut world, player, &mut velocity, |_| {});
        if out.stepped > 0.0 {
            up.get_or_insert(tick);
        }
        if up.is_some() {
            let p = at(&world, player);
            assert!((p.y - (0.75 + 0.4 + skin)).abs() < 1e-3, "tick {tick}: {p}");
        }
    }
    assert!(up.is_some(), "it climbed");
}

/// A level of sloped ground (a chain, solid below), with a character of
/// `shape` standing a skin above its ground at `x`, whose height there is
/// `height(x)`.
fn on_chain(points: Vec<Vec2>, shape: Shape, x: f32, height: f32) -> (World, BodyId) {
    let mut world = World::default();
    world
        .add_chain(&passo_physics::ChainDef::new(points))
        .unwrap();
    let skin = CharacterMover::default().skin;
    let half = shape.half_extents().y;
    let id = world
        .add_body(BodyDef::new_kinematic(
            Vec2::new(x, height + half + skin),
            shape,
            Vec2::ZERO,
        ))
        .unwrap();
    (world, id)
}

/// A hill: flat to x = 0, up at `degrees` for 3 m across, flat on top for
/// 3 m, down at the same slope, then flat.
fn hill(degrees: f32) -> (Vec<Vec2>, impl Fn(f32) -> f32) {
    let rise = 3.0 * degrees.to_radians().tan();
    let points = vec![
        Vec2::new(-20.0, 0.0),
        Vec2::new(0.0, 0.0),
        Vec2::new(3.0, rise),
        Vec2::new(6.0, rise),
        Vec2::new(9.0, 0.0),
        Vec2::new(30.0, 0.0),
    ];
    let height = move |x: f32| match x {
        x if x <= 0.0 || x >= 9.0 => 0.0,
        x if x < 3.0 => x / 3.0 * rise,
        x if x <= 6.0 => rise,
        x => (9.0 - x) / 3.0 * rise,
    };
    (points, height)
}

/// The characters to try on slopes: a box and an upright capsule, each
/// 0.4 × 0.8 m.
fn walkers() -> Vec<(&'static str, Shape)> {
    vec![
        ("box", Shape::rect(0.4, 0.8)),
        ("capsule", Shape::capsule(0.4, 0.8)),
    ]
}

#[test]
fn it_walks_over_a_hill_at_its_walking_speed_always_on_the_ground() {
    // Up and down 30° and 45° slopes, over their joints with the flat, at
    // 4.5 and 9 m/s: each tick it covers `speed × dt` across (or along the
    // ground, with `constant_speed`) within 1 %, and never leaves the
    // ground.
    for degrees in [30.0f32, 45.0] {
        for (name, shape) in walkers() {
            for speed in [4.5f32, 9.0] {
                for constant_speed in [false, true] {
                    let (points, _) = hill(degrees);
                    let (mut world, id) = on_chain(points, shape, -2.0, 0.0);
                    let mover = CharacterMover {
                        constant_speed,
                        ..CharacterMover::default()
                    };
                    let case = format!(
                        "{name} at {speed} m/s over {degrees}°, constant speed {constant_speed}"
                    );
                    let mut velocity = Vec2::new(speed, 0.0);
                    let mut before = at(&world, id);
                    while before.x < 12.0 {
                        velocity.y -= 9.81 * DT;
                        let out = world.move_character(id, velocity * DT, &mover, DT).unwrap();
                        if out.on_ground {
                            velocity.y = 0.0;
                        }
                        world.step(DT);
                        let now = at(&world, id);
                        let step = now - before;
                        assert!(out.on_ground, "{case}: off the ground at {now}");
                        assert!(out.wall.is_none(), "{case}: a wall at {now}");
                        let covered = if constant_speed {
                            step.length()
                        } else {
                            step.x
                        };
                        // Over a joint a tick is partly on each side: the
                        // ground it covers is then shorter, never longer.
                        let on_one_slope = [0.0f32, 3.0, 6.0, 9.0]
                            .iter()
                            .all(|j| (before.x - j).abs() > 0.4 && (now.x - j).abs() > 0.4);
                        if on_one_slope || !constant_speed {
                            assert!(
                                (covered - speed * DT).abs() <= 0.01 * speed * DT,
                                "{case}: {covered} at {now}"
                            );
                        }
                        before = now;
                    }
                }
            }
        }
    }
}

#[test]
fn its_feet_follow_the_ground_over_every_joint_without_a_bump() {
    // Walking over the hill, a capsule's lowest point stays a skin above
    // the ground (measured straight down from its centre to its round end
    // on the slope): no bump at the foot or the crest of either slope.
    let skin = CharacterMover::default().skin;
    for degrees in [20.0f32, 30.0, 45.0] {
        let (points, height) = hill(degrees);
        let (mut world, id) = on_chain(points, Shape::capsule(0.4, 0.8), -1.0, 0.0);
        let mut velocity = Vec2::new(3.0, 0.0);
        for tick in 0..240 {
            play(&mut world, id, &mut velocity, |_| {});
            let p = at(&world, id);
            // The nearest ground to the lower round end's centre is the
            // radius plus the skin away (up to the skin measured straight
            // down on a slope).
            let end = p - Vec2::new(0.0, 0.2);
            let nearest = (0..=600)
                .map(|i| {
                    let x = p.x - 3.0 + 0.01 * i as f32;
                    (Vec2::new(x, height(x)) - end).length()
                })
                .fold(f32::INFINITY, f32::min);
            let gap = nearest - 0.2;
            assert!(
                gap > -1e-3 && gap < skin + 2e-3,
                "{degrees}°, tick {tick}: {gap} at {p}"
            );
        }
    }
}

#[test]
fn it_stands_still_on_a_walkable_slope_and_slides_down_a_steeper_one() {
    for (name, shape) in walkers() {
        // 30°: under 1 mm in 10 s with the game's gravity every tick.
        let (points, height) = hill(30.0);
        // A box's corner rests on the slope, 0.2 m higher beside its
        // middle: start it that much higher.
        let (mut world, id) = on_chain(points, shape, 1.5, height(1.7));
        // Let it settle onto the slope first.
        let mut velocity = Vec2::ZERO;
        for _ in 0..10 {
            play(&mut world, id, &mut velocity, |_| {});
        }
        let start = at(&world, id);
        for tick in 0..600 {
            let out = play(&mut world, id, &mut velocity, |_| {});
            assert!(
                out.on_ground,
                "{name}, tick {tick}: {out:?} at {}",
                at(&world, id)
            );
        }
        let drift = (at(&world, id) - start).length();
        assert!(drift < 1e-3, "{name}: drifted {drift} m, from {start}");
        assert!(height(start.x) > 0.5, "{name}: on the slope at {start}");
        // Without stop_on_slope the game's gravity slides it down.
        let mover = CharacterMover {
            stop_on_slope: false,
            ..CharacterMover::default()
        };
        let mut velocity = Vec2::ZERO;
        for _ in 0..120 {
            velocity.y -= 9.81 * DT;
            let out = world.move_character(id, velocity * DT, &mover, DT).unwrap();
            if out.on_ground {
                velocity.y = 0.0;
            }
            world.step(DT);
        }
        assert!(
            at(&world, id).x < start.x - 0.1,
            "{name}: slid to {}",
            at(&world, id)
        );
        // 60° is steeper than max_slope (45°): a wall to walk into, and
        // it slides down it.
        let (points, _) = hill(60.0);
        let (mut world, id) = on_chain(points, shape, -1.0, 0.0);
        let mut velocity = Vec2::new(3.0, 0.0);
        let mut walled = false;
        for _ in 0..60 {
            let out = play(&mut world, id, &mut velocity, |_| {});
            walled |= out.on_wall;
        }
        assert!(walled, "{name}: the 60° slope is a wall");
        assert!(
            at(&world, id).y < 0.6,
            "{name}: did not walk up it: {}",
            at(&world, id)
        );
        let rise = 3.0 * 60f32.to_radians().tan();
        let (mut world, id) = on_chain(hill(60.0).0, shape, 1.5, 1.5 / 3.0 * rise + 0.3);
        let mut velocity = Vec2::ZERO;
        for _ in 0..120 {
            play(&mut world, id, &mut velocity, |_| {});
        }
        assert!(
            at(&world, id).x < 0.5,
            "{name}: slid down to {}",
            at(&world, id)
        );
    }
}

#[test]
fn it_reports_the_ground_normal_and_a_moving_platform_s_velocity() {
    // A kinematic ramp at 30°, moving right at 2 m/s.
    let mut world = World::default();
    let u = Vec2::from_angle(30f32.to_radians());
    let ramp = world
        .add_body(BodyDef::new_kinematic(
            Vec2::ZERO,
            Shape::segment(-4.0 * u, 4.0 * u),
            Vec2::new(2.0, 0.0),
        ))
        .unwrap();
    let skin = CharacterMover::default().skin;
    let id = world
        .add_body(BodyDef::new_kinematic(
            Vec2::new(0.0, 0.4 + 0.2 * 30f32.to_radians().tan() + skin),
            Shape::rect(0.4, 0.8),
            Vec2::ZERO,
        ))
        .unwrap();
    let mut velocity = Vec2::ZERO;
    let mut out = MoveOutcome::default();
    for _ in 0..30 {
        out = play(&mut world, id, &mut velocity, |_| {});
    }
    assert!(out.on_ground);
    assert_eq!(out.ground, Some(ramp));
    assert!((out.ground_normal - u.perp()).length() < 1e-5, "{out:?}");
    assert_eq!(out.ground_velocity, Vec2::new(2.0, 0.0));
    // It rode the ramp: half a second at 2 m/s.
    assert!((at(&world, id).x - 1.0).abs() < 0.02, "{}", at(&world, id));
}

#[test]
fn it_walks_over_slope_tiles_as_over_a_chain() {
    // 0.5 m cells: up a 2:1 slope and a 45° one, along the top, down a
    // 45° slope and a 2:1 one, back on the flat (each 45° slope is one
    // cell: side by side in a row, `//` is a saw). At 4.5 m/s every tick
    // covers 7.5 cm across within 1 % and none leaves the ground.
    let mut world = level(
        "
        ......./##\\.............................
        .....rR####Ff............................
        ##############################################",
    );
    for (name, shape) in walkers() {
        let skin = CharacterMover::default().skin;
        let start = Vec2::new(1.0, 0.5 + shape.half_extents().y + skin);
        let id = world
            .add_body(BodyDef::new_kinematic(start, shape, Vec2::ZERO))
            .unwrap();
        let mut velocity = Vec2::new(4.5, 0.0);
        let mut before = at(&world, id);
        let mut highest = before.y;
        while before.x < 20.0 {
            let out = play(&mut world, id, &mut velocity, |_| {});
            let now = at(&world, id);
            assert!(
                out.on_ground && out.wall.is_none(),
                "{name} at {now}: {out:?}"
            );
            assert!(
                ((now.x - before.x) - 4.5 * DT).abs() < 0.01 * 4.5 * DT,
                "{name} at {now}"
            );
            highest = highest.max(now.y);
            before = now;
        }
        // Over the top of the hill, 1 m up, and down again.
        assert!(
            (highest - (start.y + 1.0)).abs() < 0.02,
            "{name}: {highest}"
        );
        assert!((before.y - start.y).abs() < 1e-3, "{name}: {before}");
        world.remove_body(id).unwrap();
    }
}

/// A world with a static box from `min` to `max`, and a character (the
/// box of `HALF`) with its centre at `centre`.
fn beside_a_box(min: Vec2, max: Vec2, centre: Vec2) -> (World, BodyId) {
    let mut world = World::default();
    let size = max - min;
    let def = BodyDef::new_static((min + max) / 2.0, Shape::rect(size.x, size.y));
    world.add_body(def).unwrap();
    let id = character_at(&mut world, centre);
    (world, id)
}

/// A character (the box of `HALF`) with its centre at `centre`.
fn character_at(world: &mut World, centre: Vec2) -> BodyId {
    let def = BodyDef::new_kinematic(centre, Shape::rect(2.0 * HALF.x, 2.0 * HALF.y), Vec2::ZERO);
    world.add_body(def).unwrap()
}

/// One move of `by`, where the character ends.
fn move_once(world: &mut World, id: BodyId, by: Vec2) -> Vec2 {
    let out = world
        .move_character(id, by, &CharacterMover::default(), DT)
        .unwrap();
    out.position
}

#[test]
fn a_wall_it_touches_holds_it_and_walls_it_is_caught_between_let_it_out() {
    // A wall whose face is at x = 1. Touching it (no skin), a move into
    // it goes nowhere, and one away goes all the way.
    let touching = Vec2::new(1.0 - HALF.x, 5.0);
    let (mut world, id) = beside_a_box(Vec2::new(1.0, 0.0), Vec2::new(2.0, 10.0), touching);
    assert_eq!(move_once(&mut world, id, Vec2::new(0.1, 0.0)), touching);
    assert_eq!(move_once(&mut world, id, Vec2::ZERO), touching);
    let away = move_once(&mut world, id, Vec2::new(-0.1, 0.0));
    assert!(
        (away - (touching - Vec2::new(0.1, 0.0))).length() < 1e-6,
        "{away}"
    );
    // Caught between two walls closer than it is wide (the push out cannot
    // free it, and moves it a little to one side): it still moves out
    // along the slot.
    let mut world = World::default();
    for x in [-0.68, 0.68] {
        let def = BodyDef::new_static(Vec2::new(x, 0.0), Shape::rect(1.0, 4.0));
        world.add_body(def).unwrap();
    }
    let id = character_at(&mut world, Vec2::ZERO);
    let up = move_once(&mut world, id, Vec2::new(0.0, 3.0));
    assert!((up.y - 3.0).abs() < 1e-4 && up.x.abs() < 0.05, "{up}");
}

#[test]
fn at_a_slant_it_stops_a_skin_from_a_wall_measured_along_its_normal() {
    // In the air, moving up and right at 45 degrees, or at a shallower
    // angle, into a wall whose face is at x = 1, 0.3 m away: the side ends
    // exactly a skin from the face, and the rest of the move slides it up.
    let skin = CharacterMover::default().skin;
    for by in [
        Vec2::new(0.5, 0.5),
        Vec2::new(0.5, 0.1),
        Vec2::new(0.5, 1.0),
    ] {
        let start = Vec2::new(1.0 - HALF.x - 0.3, 5.0);
        let (mut world, id) = beside_a_box(Vec2::new(1.0, 0.0), Vec2::new(2.0, 10.0), start);
        let end = move_once(&mut world, id, by);
        let gap = 1.0 - (end.x + HALF.x);
        assert!((gap - skin).abs() < 1e-5, "{by}: {gap} m from the wall");
        assert!(
            (end.y - (start.y + by.y)).abs() < 1e-4,
            "{by}: slid up to {end}"
        );
    }
}

#[test]
fn a_one_way_platform_lets_it_through_from_below_and_from_the_side_wherever_it_is() {
    // A one-way platform (solid side up), 0.2 m thick, near the origin or
    // far from it: a character whose head is 0.15 m into it from below
    // stays there (it is not pushed up on top), one whose feet are deeper
    // in it than a landing falls on through, and one walking into its end
    // at the platform's height walks through.
    for (x, y) in [(0.0, 0.0), (0.0, 80.0), (-300.0, 150.0)] {
        let mut world = World::default();
        let platform =
            BodyDef::new_static(Vec2::new(x, y), Shape::rect(2.0, 0.2)).with_one_way(Vec2::Y);
        world.add_body(platform).unwrap();
        let under = Vec2::new(x, y - 0.1 - HALF.y + 0.15);
        let id = character_at(&mut world, under);
        assert_eq!(move_once(&mut world, id, Vec2::ZERO), under, "at {x}, {y}");
        // Its feet 0.1 m into it from above (deeper than a landing goes):
        // falling on, it goes on through.
        let sunk = Vec2::new(x, y + 0.1 + HALF.y - 0.1);
        world.set_position(id, sunk);
        let fell = move_once(&mut world, id, Vec2::new(0.0, -0.05));
        assert!(
            (fell - (sunk - Vec2::new(0.0, 0.05))).length() < 1e-4,
            "at {x}, {y}: {fell}"
        );
        // Walking through its end, 4 cm a tick.
        let mut at = Vec2::new(x - 1.0 - HALF.x - 0.05, y);
        world.set_position(id, at);
        for _ in 0..80 {
            at = move_once(&mut world, id, Vec2::new(0.04, 0.0));
            world.set_position(id, at);
        }
        assert!(
            (at.x - (x - 1.0 - HALF.x - 0.05 + 3.2)).abs() < 1e-3,
            "at {x}, {y}: {at}"
        );
    }
}

#[test]
fn a_moving_crate_is_met_where_it_is_and_a_kinematic_body_where_it_will_be() {
    // A crate sliding at the character at 3 m/s (weightless, so nothing
    // slows it), 1 m ahead: the move stops a skin short of where the crate
    // is now. A kinematic block moving the same way is met where it will
    // be after the step.
    let skin = CharacterMover::default().skin;
    for kinematic in [false, true] {
        let mut world = World::default();
        let mut settings = *world.settings();
        settings.forces.gravity = None;
        world.set_settings(settings).unwrap();
        let (kind, v) = (
            if kinematic {
                BodyKind::Kinematic
            } else {
                BodyKind::Dynamic
            },
            -3.0,
        );
        let def = BodyDef {
            kind,
            position: Vec2::new(1.5, 0.0),
            shape: Some(Shape::rect(1.0, 1.0)),
            velocity: Vec2::new(v, 0.0),
            ..Default::default()
        };
        world.add_body(def).unwrap();
        let id = character_at(&mut world, Vec2::ZERO);
        let end = move_once(&mut world, id, Vec2::new(0.9, 0.0));
        let face = 1.0 + if kinematic { v * DT } else { 0.0 };
        let expected = face - HALF.x - skin;
        assert!(
            (end.x - expected).abs() < 1e-5,
            "kinematic {kinematic}: at {end}, not {expected}"
        );
    }
}

#[test]
fn a_one_way_platform_coming_down_passes_through_the_character() {
    // A one-way platform (solid side up) moving down at 2 m/s through a
    // character standing on the floor, or held in the air (on a ladder,
    // say): it is neither pushed down nor crushed, and stays put.
    for standing in [true, false] {
        let mut world = level("##########################");
        let ground = if standing { 0.5 } else { 1.5 };
        let player = character(&mut world, 6.0, ground);
        let start = at(&world, player);
        let def = BodyDef::new_kinematic(
            Vec2::new(6.0, ground + 1.5),
            Shape::rect(2.0, 0.2),
            Vec2::new(0.0, -2.0),
        )
        .with_one_way(Vec2::Y);
        let platform = world.add_body(def).unwrap();
        let mover = CharacterMover::default();
        // 40 ticks: the platform ends inside it (before it could stand on it).
        for tick in 0..40 {
            let out = world
                .move_character(player, Vec2::ZERO, &mover, DT)
                .unwrap();
            assert_eq!(out.crushed, None, "tick {tick}");
            world.step(DT);
            let now = at(&world, player);
            assert!(
                (now - start).length() < 1e-4,
                "standing {standing}, tick {tick}: {now}"
            );
        }
        let top = at(&world, platform).y + 0.1;
        let inside = start.y - HALF.y..start.y + HALF.y;
        assert!(
            inside.contains(&top),
            "the platform went in: its top at {top}"
        );
    }
}

#[test]
fn only_a_kinematic_body_pressing_in_deeper_than_the_skin_crushes_it() {
    // A character standing on the floor. A still kinematic block touching
    // its head, or in it by half the skin, does not crush it; one in it by
    // twice the skin does. A static ceiling or a crate in its head never
    // crushes it (the push out deals with those).
    let skin = CharacterMover::default().skin;
    let mover = CharacterMover::default();
    for (kind, depth, crushes) in [
        (BodyKind::Kinematic, 0.0, false),
        (BodyKind::Kinematic, 0.5 * skin, false),
        (BodyKind::Kinematic, 2.0 * skin, true),
        (BodyKind::Static, 0.05, false),
        (BodyKind::Dynamic, 0.05, false),
    ] {
        let mut world = level("##########################");
        let player = character(&mut world, 6.0, 0.5);
        let head = at(&world, player).y + HALF.y;
        let def = BodyDef {
            kind,
            position: Vec2::new(6.0, head + 0.25 - depth),
            shape: Some(Shape::rect(1.0, 0.5)),
            ..Default::default()
        };
        let block = world.add_body(def).unwrap();
        let out = world
            .move_character(player, Vec2::ZERO, &mover, DT)
            .unwrap();
        let expected = crushes.then_some(block);
        assert_eq!(out.crushed, expected, "{kind:?} {depth} m in");
    }
}

#[test]
fn a_kinematic_bar_in_its_legs_crushes_it_on_the_ground_but_not_in_the_air() {
    // A still kinematic bar 0.1 m thick across the character's legs, its
    // underside 0.1 m above the feet: on the floor the character has no
    // way out (the bar is not low enough to step onto), so it is crushed;
    // held 0.5 m above the floor, or 3 cm above it, it is not (it is
    // pushed out instead). A bar 3 cm or 0.3 m thick (as high as a step)
    // whose underside is 5 mm under the feet is stepped onto, not
    // crushing.
    let mover = CharacterMover::default();
    for (lift, underside, thick, crushes) in [
        (0.0, 0.1, 0.1, true),
        (0.03, 0.1, 0.1, false),
        (0.5, 0.1, 0.1, false),
        (0.0, -0.005, 0.03, false),
        (0.0, -0.005, 0.3, false),
    ] {
        let mut world = level("##########################");
        let player = character(&mut world, 6.0, 0.5 + lift);
        let feet = at(&world, player).y - HALF.y;
        let def = BodyDef::new_kinematic(
            Vec2::new(6.0, feet + underside + thick / 2.0),
            Shape::rect(1.0, thick),
            Vec2::ZERO,
        );
        let bar = world.add_body(def).unwrap();
        let out = world
            .move_character(player, Vec2::ZERO, &mover, DT)
            .unwrap();
        let case = format!("{lift} m up, underside {underside} m above the feet");
        assert_eq!(out.crushed, crushes.then_some(bar), "{case}");
    }
}

#[test]
fn a_kinematic_wall_pressing_in_with_room_behind_pushes_rather_than_crushes() {
    // In the air, a still kinematic wall 5 cm into the character's side,
    // and behind the character a static wall 1 m away, or a crate 2 cm
    // away (it gives way): there is room, so the character is not
    // crushed. With the wall behind, it is pushed out by the overlap and a
    // skin.
    let mover = CharacterMover::default();
    for (behind, kind) in [(1.0, BodyKind::Static), (0.02, BodyKind::Dynamic)] {
        let mut world = World::default();
        let mut settings = *world.settings();
        settings.forces.gravity = None;
        world.set_settings(settings).unwrap();
        let def = BodyDef {
            kind,
            position: Vec2::new(-HALF.x - behind - 0.5, 0.0),
            shape: Some(Shape::rect(1.0, 1.0)),
            ..Default::default()
        };
        world.add_body(def).unwrap();
        let player = character_at(&mut world, Vec2::ZERO);
        let def = BodyDef::new_kinematic(
            Vec2::new(HALF.x + 0.5 - 0.05, 0.0),
            Shape::rect(1.0, 4.0),
            Vec2::ZERO,
        );
        world.add_body(def).unwrap();
        let out = world
            .move_character(player, Vec2::ZERO, &mover, DT)
            .unwrap();
        assert_eq!(out.crushed, None, "{kind:?} {behind} m behind");
        if kind == BodyKind::Static {
            assert!((out.position.x + 0.05 + mover.skin).abs() < 1e-5, "{out:?}");
        }
    }
}

#[test]
fn of_two_bodies_crushing_it_the_first_added_is_named() {
    // Two still kinematic lids side by side, each 5 cm into the head of a
    // character standing on the floor, added left first or right first:
    // the one added first (the lower id) is named. Also when a body added
    // before them is removed, which moves the second lid's storage ahead
    // of the first's.
    let mover = CharacterMover::default();
    for (left_first, shuffled) in [(true, false), (false, false), (true, true), (false, true)] {
        let mut world = level("##########################");
        let player = character(&mut world, 6.0, 0.5);
        let head = at(&world, player).y + HALF.y;
        let spacer = world
            .add_body(BodyDef::new_dynamic(
                Vec2::new(20.0, 3.0),
                Shape::circle(0.1),
            ))
            .unwrap();
        let lid = |world: &mut World, x: f32| {
            let def = BodyDef::new_kinematic(
                Vec2::new(x, head + 0.25 - 0.05),
                Shape::rect(0.5, 0.5),
                Vec2::ZERO,
            );
            world.add_body(def).unwrap()
        };
        let xs = if left_first { [5.8, 6.2] } else { [6.2, 5.8] };
        let first = lid(&mut world, xs[0]);
        lid(&mut world, xs[1]);
        if shuffled {
            world.remove_body(spacer).unwrap();
        }
        let out = world
            .move_character(player, Vec2::ZERO, &mover, DT)
            .unwrap();
        let case = format!("left first: {left_first}, shuffled: {shuffled}");
        assert_eq!(out.crushed, Some(first), "{case}");
    }
}

#[test]
fn a_thin_low_post_sweeping_fast_pushes_the_character_ahead_of_it() {
    // A kinematic post 5 cm wide and lower than a step (0.29 m) slides
    // along the floor into a standing character at 24 to 36 m/s, ending
    // past its middle or beyond it: the push out alone would put the
    // character behind the post (the shortest way out, backwards), or
    // leave it there. It is swept ahead of the post instead, a skin in
    // front of it.
    let skin = CharacterMover::default().skin;
    for speed in [24.0, 30.0, 36.0] {
        let mut world = level("##########################");
        let player = character(&mut world, 6.0, 0.5);
        let start = Vec2::new(6.0 - HALF.x - 0.025 - 0.05, 0.5 + 0.145);
        let def = BodyDef::new_kinematic(start, Shape::rect(0.05, 0.29), Vec2::new(speed, 0.0));
        let post = world.add_body(def).unwrap();
        stand(&mut world, player);
        let (p, q) = (at(&world, player), at(&world, post));
        let gap = (p.x - HALF.x) - (q.x + 0.025);
        assert!(
            (gap - skin).abs() < 1e-3,
            "{speed} m/s: {gap} m in front of the post"
        );
    }
}

#[test]
fn a_block_higher_than_a_step_sliding_under_it_pushes_it_rather_than_lifting_it() {
    // A kinematic block 2 m wide and 0.35 m high (above `max_step`) slides
    // along the floor at 30 m/s and ends under most of a standing
    // character: the push out's shortest way is up, on top, but the block
    // is too high to be climbed, so it sweeps the character ahead of it,
    // a skin in front, still on the floor.
    let skin = CharacterMover::default().skin;
    for height in [0.35, 0.38] {
        let mut world = level("##########################");
        let player = character(&mut world, 6.0, 0.5);
        let y = at(&world, player).y;
        let start = Vec2::new(6.0 - HALF.x - 0.05 - 1.0, 0.5 + height / 2.0);
        let def = BodyDef::new_kinematic(start, Shape::rect(2.0, height), Vec2::new(30.0, 0.0));
        let block = world.add_body(def).unwrap();
        stand(&mut world, player);
        let (p, q) = (at(&world, player), at(&world, block));
        let gap = (p.x - HALF.x) - (q.x + 1.0);
        assert!(
            (gap - skin).abs() < 1e-3,
            "{height} m: {gap} m in front of it"
        );
        assert!((p.y - y).abs() < 1e-4, "{height} m: lifted to {p}");
    }
}

#[test]
fn without_stop_on_slope_a_fall_on_a_slope_slides_along_it() {
    // Standing on a 30° slope with `stop_on_slope` off, a move straight
    // down by 0.1 m becomes its part along the slope: 0.05 m down it.
    let mover = CharacterMover {
        stop_on_slope: false,
        ..CharacterMover::default()
    };
    for (name, shape) in walkers() {
        let (points, height) = hill(30.0);
        let (mut world, id) = on_chain(points, shape, 1.5, height(1.7));
        let mut velocity = Vec2::ZERO;
        for _ in 0..10 {
            play(&mut world, id, &mut velocity, |_| {});
        }
        let out = world
            .move_character(id, Vec2::new(0.0, -0.1), &mover, DT)
            .unwrap();
        let (s, c) = 30f32.to_radians().sin_cos();
        let expected = Vec2::new(-c, -s) * 0.1 * s;
        let moved = out.translation;
        assert!(
            (moved - expected).length() < 1e-3,
            "{name}: moved {moved}, not {expected}"
        );
        assert!(out.on_ground, "{name}");
    }
}

#[test]
fn the_push_out_takes_the_deepest_overlap_first() {
    // A character sunk 0.3 m into the floor, its side also 5 cm into a
    // block buried in the floor (top 0.1 m under the surface). Out of the
    // floor first, straight up, it clears the block too and stays where
    // it is across; out of the block first it would be shoved sideways.
    // Both orders of adding the two bodies.
    let skin = CharacterMover::default().skin;
    for floor_first in [true, false] {
        let mut world = World::default();
        let floor = BodyDef::new_static(Vec2::new(0.0, -0.5), Shape::rect(20.0, 1.0));
        let block = BodyDef::new_static(Vec2::new(1.5, -0.3), Shape::rect(1.0, 0.4));
        let defs = if floor_first {
            [floor, block]
        } else {
            [block, floor]
        };
        for def in defs {
            world.add_body(def).unwrap();
        }
        let start = Vec2::new(1.0 - HALF.x + 0.05, -0.3 + HALF.y);
        let id = character_at(&mut world, start);
        let end = move_once(&mut world, id, Vec2::ZERO);
        let expected = Vec2::new(start.x, HALF.y + skin);
        assert!(
            (end - expected).length() < 1e-4,
            "floor first: {floor_first}: at {end}"
        );
    }
}

#[test]
fn of_two_bodies_sweeping_in_the_first_met_pushes() {
    // Two kinematic posts (5 cm wide, as tall as the character) sweep in
    // from the left in one step: one 5 cm away at 12 m/s (0.2 m a step),
    // one 0.3 m away at 24 m/s (0.4 m a step). The near one meets the
    // character first (a quarter of its way, against three quarters of
    // the far one's) and pushes it to a skin in front of where it ends,
    // clear of both. Both orders of adding them.
    let skin = CharacterMover::default().skin;
    for near_first in [true, false] {
        let mut world = level("##########################");
        let player = character(&mut world, 6.0, 0.5);
        let y = at(&world, player).y;
        let post = |world: &mut World, gap: f32, speed: f32| {
            let x = 6.0 - HALF.x - gap - 0.025;
            let def = BodyDef::new_kinematic(
                Vec2::new(x, y),
                Shape::rect(0.05, 0.8),
                Vec2::new(speed, 0.0),
            );
            world.add_body(def).unwrap();
        };
        let posts = [(0.05, 12.0), (0.3, 24.0)];
        let order = if near_first { [0, 1] } else { [1, 0] };
        for k in order {
            post(&mut world, posts[k].0, posts[k].1);
        }
        let mover = CharacterMover::default();
        let out = world
            .move_character(player, Vec2::ZERO, &mover, DT)
            .unwrap();
        // The near post's right face ends at 6 - 0.2 - 0.05 + 0.2.
        let expected = 5.95 + skin + HALF.x;
        assert_eq!(out.crushed, None, "near first: {near_first}");
        assert!(
            (out.position.x - expected).abs() < 1e-4,
            "near first: {near_first}: {out:?}"
        );
    }
}

#[test]
fn each_crate_met_in_a_move_is_pushed_once_and_none_with_push_mass_zero() {
    // Weightless, moving up and right into a corner between a crate on
    // the right and a crate above: the move slides up along the first and
    // meets the second, and pushes each once. With `push_mass` 0 it pushes
    // neither.
    for push_mass in [20.0, 0.0] {
        let mut world = World::default();
        let mut settings = *world.settings();
        settings.forces.gravity = None;
        world.set_settings(settings).unwrap();
        let crate_at = |world: &mut World, at: Vec2| {
            let def = BodyDef::new_dynamic(at, Shape::rect(0.5, 0.5));
            world.add_body(def).unwrap()
        };
        let right = crate_at(&mut world, Vec2::new(HALF.x + 0.05 + 0.25, 0.0));
        let above = crate_at(&mut world, Vec2::new(-0.3, HALF.y + 0.1 + 0.25));
        let id = character_at(&mut world, Vec2::ZERO);
        let mover = CharacterMover {
            push_mass,
            ..CharacterMover::default()
        };
        let out = world
            .move_character(id, Vec2::new(0.2, 0.3), &mover, DT)
            .unwrap();
        assert_eq!(out.wall, Some(right));
        assert_eq!(out.ceiling, Some(above));
        let expected = if push_mass > 0.0 { 2 } else { 0 };
        assert_eq!(out.pushed, expected, "push_mass {push_mass}");
    }
}

#[test]
fn with_max_step_zero_it_climbs_no_step_at_all() {
    // A ledge 2 cm high: with `max_step` 0 a walk stops at it; with the
    // default it steps up.
    for (max_step, climbs) in [(0.0, false), (0.3, true)] {
        let mut world = World::default();
        let floor = BodyDef::new_static(Vec2::new(0.0, -0.5), Shape::rect(20.0, 1.0));
        let ledge = BodyDef::new_static(Vec2::new(5.0, 0.01), Shape::rect(4.0, 0.02));
        world.add_body(floor).unwrap();
        world.add_body(ledge).unwrap();
        let id = character(&mut world, 2.0, 0.0);
        let mover = CharacterMover {
            max_step,
            ..CharacterMover::default()
        };
        for _ in 0..60 {
            world
                .move_character(id, Vec2::new(3.0, -1.0) * DT, &mover, DT)
                .unwrap();
            world.step(DT);
        }
        let x = at(&world, id).x;
        assert_eq!(x > 3.5, climbs, "max_step {max_step}: at {x}");
    }
}

#[test]
fn it_climbs_onto_a_ledge_too_narrow_to_step_forward_on() {
    // A step 0.2 m high and 15 mm deep in front of a tall wall: a climb
    // moves forward at least two skins (2 cm), so the wall stops the
    // forward part of every climb; it still ends on the step's top,
    // against the wall.
    let mut world = level("################");
    let step = BodyDef::new_static(Vec2::new(3.0075, 0.6), Shape::rect(0.015, 0.2));
    let wall = BodyDef::new_static(Vec2::new(3.515, 2.0), Shape::rect(1.0, 4.0));
    world.add_body(step).unwrap();
    world.add_body(wall).unwrap();
    let id = character(&mut world, 1.0, 0.5);
    walk(&mut world, id, Vec2::new(3.0, -5.0), 60);
    let p = at(&world, id);
    let skin = CharacterMover::default().skin;
    assert!(
        (p.y - (0.7 + HALF.y + skin)).abs() < 2e-3,
        "on the ledge: {p}"
    );
    // Its side clear of the wall, and no more than two skins from it.
    let gap = 3.015 - (p.x + HALF.x);
    assert!(
        (0.0..2.0 * skin).contains(&gap),
        "against the wall: {gap} m from it"
    );
}

#[test]
fn in_a_tunnel_barely_taller_than_it_its_feet_are_lifted_only_as_far_as_the_ceiling_lets() {
    // A tunnel 4 mm taller than the character, which stands in it with
    // 2 mm above and below (less than the skin it keeps from the ground):
    // lifting its feet a skin above the floor would put its head in the
    // ceiling, so it goes no higher than the ceiling lets it.
    let mut world = World::default();
    let floor = BodyDef::new_static(Vec2::new(0.0, -0.5), Shape::rect(20.0, 1.0));
    let ceiling = BodyDef::new_static(
        Vec2::new(0.0, 2.0 * HALF.y + 0.004 + 0.5),
        Shape::rect(20.0, 1.0),
    );
    world.add_body(floor).unwrap();
    world.add_body(ceiling).unwrap();
    let start = Vec2::new(0.0, HALF.y + 0.002);
    let id = character_at(&mut world, start);
    let end = move_once(&mut world, id, Vec2::ZERO);
    let head = end.y + HALF.y;
    assert!(
        head <= 2.0 * HALF.y + 0.004,
        "its head at {head}, in the ceiling"
    );
    assert!(end.y >= start.y, "it sank to {end}");
}

#[test]
fn walking_off_a_drop_away_from_a_crate_leaning_on_it_follows_the_drop() {
    // A crate resting against the character's back, 3 mm into it (as the
    // contacts leave a crate pushed against it), and a drop of 0.2 m ahead:
    // the move off the edge, away from the crate, follows the drop down.
    // The straight line it snaps along starts inside the crate but leaves
    // it; it cuts through no crate.
    let skin = CharacterMover::default().skin;
    let mut world = World::default();
    let high = BodyDef::new_static(Vec2::new(-5.0, -0.5), Shape::rect(10.0, 1.0));
    let low = BodyDef::new_static(Vec2::new(5.0, -0.7), Shape::rect(10.0, 1.0));
    world.add_body(high).unwrap();
    world.add_body(low).unwrap();
    let start = Vec2::new(-0.25, HALF.y + skin);
    let id = character_at(&mut world, start);
    let crate_at = Vec2::new(start.x - HALF.x - 0.25 + 0.003, 0.25);
    let def = BodyDef::new_dynamic(crate_at, Shape::rect(0.5, 0.5));
    world.add_body(def).unwrap();
    let mover = CharacterMover::default();
    let out = world
        .move_character(id, Vec2::new(0.5, 0.0), &mover, DT)
        .unwrap();
    assert!(out.on_ground, "{out:?}");
    assert!(
        (out.position.y - (-0.2 + HALF.y + skin)).abs() < 1e-4,
        "{out:?}"
    );
}

#[test]
fn walking_off_a_drop_to_land_touching_a_crate_follows_the_drop() {
    // A character 0.5 m wide walks 0.5 m off a ledge and drops 0.25 m:
    // where the drop ends, its side exactly touches a crate standing on
    // the ground below. The straight line it snaps along ends touching the
    // crate and never goes into it, so it follows the drop. (Exact
    // numbers: the touch is exact, at the line's very end.)
    let skin = CharacterMover::default().skin;
    let mut world = World::default();
    let ledge = BodyDef::new_static(Vec2::new(-5.0, -0.5), Shape::rect(10.0, 1.0));
    let floor = BodyDef::new_static(Vec2::new(5.0, -0.75), Shape::rect(10.0, 1.0));
    world.add_body(ledge).unwrap();
    world.add_body(floor).unwrap();
    // Its top below the feet on the ledge: the walk does not meet it.
    let crate_ = BodyDef::new_dynamic(Vec2::new(0.875, -0.15), Shape::rect(0.5, 0.2));
    world.add_body(crate_).unwrap();
    let start = Vec2::new(-0.125, 0.5 + skin);
    let def = BodyDef::new_kinematic(start, Shape::rect(0.5, 1.0), Vec2::ZERO);
    let id = world.add_body(def).unwrap();
    let mover = CharacterMover::default();
    let out = world
        .move_character(id, Vec2::new(0.5, 0.0), &mover, DT)
        .unwrap();
    assert_eq!(out.position.x, 0.375, "{out:?}");
    assert!(out.on_ground, "{out:?}");
    assert!(
        (out.position.y - (-0.25 + skin + 0.5)).abs() < 1e-5,
        "{out:?}"
    );
}

#[test]
fn a_fast_walk_climbs_a_step_with_a_wall_behind_it_when_the_top_is_a_skin_deep() {
    // A step 0.2 m high with a tall wall `depth` behind its face; the
    // character stands a skin short of the face and walks 0.1 m in one
    // move, farther than the step's top is deep. The climb's forward move
    // runs into the wall, yet it climbs if the top is deeper than the
    // skin, and ends on it a skin short of the wall. A top shallower than
    // the skin is no step: the wall stops it below.
    let skin = CharacterMover::default().skin;
    for depth in [0.005, 0.008, 0.012, 0.015, 0.03, 0.06] {
        let mut world = World::default();
        let floor = BodyDef::new_static(Vec2::new(0.0, -0.5), Shape::rect(20.0, 1.0));
        let step = BodyDef::new_static(Vec2::new(1.0 + depth / 2.0, 0.1), Shape::rect(depth, 0.2));
        let wall = BodyDef::new_static(Vec2::new(1.5 + depth, 2.0), Shape::rect(1.0, 4.0));
        for def in [floor, step, wall] {
            world.add_body(def).unwrap();
        }
        let start = Vec2::new(1.0 - skin - HALF.x, HALF.y + skin);
        let id = character_at(&mut world, start);
        let end = move_once(&mut world, id, Vec2::new(0.1, 0.0));
        if depth > skin {
            let on_top = Vec2::new(1.0 + depth - skin - HALF.x, 0.2 + HALF.y + skin);
            assert!((end - on_top).length() < 1e-4, "depth {depth}: at {end}");
        } else {
            assert!((end - start).length() < 1e-4, "depth {depth}: at {end}");
        }
    }
}
