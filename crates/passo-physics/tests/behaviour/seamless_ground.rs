//! Seamless ground: bodies slide across the joints of flush static boxes as
//! they slide along one long box. A box sliding across the joint of two
//! boxes with the same top used to stop dead at the joint (a contact with
//! the second box's side, normal (1, 0)), and the same with the second box
//! 1 mm lower (a speculative contact with its side).

use crate::support::{
    add_box, add_ground, assert_falls_freely_along_a_wall, assert_slides_as_on_one_box,
    push_along_x,
};
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, BodyId, Shape, World};

const DT: f32 = 1.0 / 60.0;

/// A world whose ground is the given static boxes `(centre, size)`, with
/// one dynamic body of `shape` resting on top at `x`.
fn world_with(ground: &[(Vec2, Vec2)], shape: Shape, x: f32) -> (World, BodyId) {
    let mut world = World::default();
    for &(centre, size) in ground {
        world
            .add_body(BodyDef::new_static(centre, Shape::rect(size.x, size.y)))
            .unwrap();
    }
    let body = world
        .add_body(BodyDef {
            position: Vec2::new(x, shape.half_extents().y),
            shape: Some(shape),
            ..Default::default()
        })
        .unwrap();
    (world, body)
}

/// `n` unit boxes edge to edge, tops at y = 0, the first centred on x = 0.
fn tiles(n: usize) -> Vec<(Vec2, Vec2)> {
    (0..n)
        .map(|i| (Vec2::new(i as f32, -0.5), Vec2::ONE))
        .collect()
}

/// One box as long as `n` tiles.
fn long_box(n: usize) -> Vec<(Vec2, Vec2)> {
    vec![(
        Vec2::new(0.5 * (n as f32 - 1.0), -0.5),
        Vec2::new(n as f32, 1.0),
    )]
}

#[test]
fn a_box_crosses_the_joint_of_two_flush_boxes_without_stopping() {
    for drop in [0.0, 0.001] {
        let ground = [
            (Vec2::new(-5.0, -0.5), Vec2::new(10.0, 1.0)),
            (Vec2::new(5.0, -0.5 - drop), Vec2::new(10.0, 1.0)),
        ];
        let one = [(Vec2::new(0.0, -0.5), Vec2::new(20.0, 1.0))];
        let slide = |ground: &[(Vec2, Vec2)]| {
            let (mut world, body) = world_with(ground, Shape::rect(0.6, 1.0), -0.5);
            world.set_velocity(body, Vec2::new(3.25, 0.0));
            (0..60)
                .map(|_| {
                    world.step(DT);
                    world.body(body).unwrap()
                })
                .collect::<Vec<_>>()
        };
        let (joint, reference) = (slide(&ground), slide(&one));
        // Friction alone (mu 0.6, g 9.81) stops it after 3.25² / (2 mu g)
        // = 0.897 m: past the joint at x = 0.
        let end = joint.last().unwrap().position.x;
        assert!(
            end > 0.35,
            "drop {drop}: crossed the joint, stopped at {end}"
        );
        // Flush, it slides exactly as on one box. A millimetre lower, it
        // falls that millimetre past the joint, and while it falls nothing
        // rubs: never slower than on one box.
        for (tick, (j, r)) in joint.iter().zip(&reference).enumerate() {
            let lost = r.velocity.x - j.velocity.x;
            assert!(
                if drop == 0.0 {
                    lost.abs() < 1e-5
                } else {
                    lost < 1e-5
                },
                "drop {drop}, tick {tick}: {} m/s across the joint, {} on one box",
                j.velocity.x,
                r.velocity.x
            );
        }
    }
}

#[test]
fn a_box_and_a_circle_pushed_across_200_tiles_move_as_on_one_long_box() {
    let n = 204;
    // About 5.94 m/s for 2 040 ticks (34 s): 202 m, past 201 joints and
    // short of the end of the tiles (203.5 m).
    let ticks = 2_040;
    for shape in [Shape::rect(0.6, 1.0), Shape::circle(0.4)] {
        let (mut on_tiles, a) = world_with(&tiles(n), shape, 0.0);
        let (mut on_one, b) = world_with(&long_box(n), shape, 0.0);
        let tiled = push_along_x(&mut on_tiles, a, 6.0, ticks, DT);
        let reference = push_along_x(&mut on_one, b, 6.0, ticks, DT);
        let end = on_tiles.body(a).unwrap().position.x;
        assert!(end > 201.0, "{shape:?} crossed 200 joints: at {end}");
        assert_slides_as_on_one_box(&tiled, &reference, &format!("{shape:?} on the tiles"));
        // Friction is the only loss: 6 - mu g dt after each pushed step.
        let loss = 6.0 - reference[ticks / 2].x;
        assert!(
            (loss - 0.6 * 9.81 * DT).abs() < 1e-4,
            "friction loss {loss}"
        );
    }
}

#[test]
fn a_box_slides_down_a_wall_of_stacked_tiles_without_catching() {
    // A column of 50 unit tiles; a box pressed against its right side
    // slides down along it (no friction, so it falls freely).
    let mut world = World::default();
    for i in 0..50 {
        let def = BodyDef {
            friction: 0.0,
            ..BodyDef::new_static(Vec2::new(0.0, i as f32), Shape::rect(1.0, 1.0))
        };
        world.add_body(def).unwrap();
    }
    let body = world
        .add_body(BodyDef {
            position: Vec2::new(0.8, 45.0),
            shape: Some(Shape::rect(0.6, 0.6)),
            friction: 0.0,
            ..Default::default()
        })
        .unwrap();
    assert_falls_freely_along_a_wall(&mut world, body, DT, |b| {
        assert!(b.position.x > 0.79, "it stays against the wall");
    });
}

#[test]
fn a_box_slides_from_static_ground_onto_a_flush_kinematic_platform_and_off_again() {
    // Ground, a kinematic platform level with it (a lift at rest), ground.
    let slide = |with_platform: bool| {
        let mut world = World::default();
        let ground = |w: &mut World, x: f32, width: f32| {
            w.add_body(BodyDef::new_static(
                Vec2::new(x, -0.5),
                Shape::rect(width, 1.0),
            ))
            .unwrap();
        };
        if with_platform {
            ground(&mut world, -6.0, 10.0);
            world
                .add_body(BodyDef::new_kinematic(
                    Vec2::new(0.0, -0.5),
                    Shape::rect(2.0, 1.0),
                    Vec2::ZERO,
                ))
                .unwrap();
            ground(&mut world, 6.0, 10.0);
        } else {
            ground(&mut world, 0.0, 22.0);
        }
        let body = world
            .add_body(BodyDef::new_dynamic(
                Vec2::new(-4.0, 0.5),
                Shape::rect(0.6, 1.0),
            ))
            .unwrap();
        push_along_x(&mut world, body, 4.0, 150, DT)
    };
    let (with, without) = (slide(true), slide(false));
    for (tick, (a, b)) in with.iter().zip(&without).enumerate() {
        assert!(a.y.abs() < 1e-4, "tick {tick}: vertical speed {}", a.y);
        assert!(
            (a.x - b.x).abs() < 1e-5,
            "tick {tick}: {} against {}",
            a.x,
            b.x
        );
    }
}

#[test]
fn a_sensor_or_a_one_way_ledge_flush_on_the_ground_does_not_make_it_seamless() {
    // A sensor zone as wide as the ground box, lying on it, and a one-way
    // ledge beside it: neither covers the ground's faces, so a box resting
    // on the ground stays put (it used to be pushed out sideways).
    for kind in ["sensor", "one-way"] {
        let mut world = World::default();
        add_ground(&mut world, 4.0);
        let cover = BodyDef::new_static(Vec2::new(0.0, 0.5), Shape::rect(4.0, 1.0));
        let cover = if kind == "sensor" {
            cover.as_sensor()
        } else {
            cover.with_one_way(Vec2::Y)
        };
        world.add_body(cover).unwrap();
        let body = world
            .add_body(BodyDef::new_dynamic(
                Vec2::new(0.0, 0.5),
                Shape::rect(0.6, 1.0),
            ))
            .unwrap();
        for _ in 0..60 {
            world.step(DT);
        }
        let p = world.body(body).unwrap().position;
        assert!(p.x.abs() < 1e-3 && (p.y - 0.5).abs() < 0.006, "{kind}: {p}");
    }
}

/// A world with static ground and, on it, dynamic 1 m crates of 5 kg from
/// x = 0 to x = `n`: `n` of them side by side, or one crate `n` m long.
/// Returns it with the crates.
fn crates(n: usize, side_by_side: bool) -> (World, Vec<BodyId>) {
    let mut world = World::default();
    add_ground(&mut world, 4.0 * n as f32);
    let sizes = if side_by_side {
        vec![1.0; n]
    } else {
        vec![n as f32]
    };
    let mut x = 0.0;
    let ids = sizes
        .iter()
        .map(|&w| {
            let id = add_box(
                &mut world,
                Vec2::new(x + 0.5 * w, 0.5),
                Vec2::new(w, 1.0),
                5.0,
            );
            x += w;
            id
        })
        .collect();
    (world, ids)
}

/// A frictionless body of `shape` resting on the crates at `x`.
fn slider(world: &mut World, shape: Shape, x: f32) -> BodyId {
    let def = BodyDef {
        position: Vec2::new(x, 1.0 + shape.half_extents().y),
        shape: Some(shape),
        friction: 0.0,
        ..Default::default()
    };
    world.add_body(def).unwrap()
}

#[test]
fn a_box_and_a_circle_slide_across_flush_crates_as_across_one_long_crate() {
    // Contacts let a resting body sink into the crate under it by up to the
    // slop, so the next crate's side stood a few micrometres to millimetres
    // above its bottom: a frictionless box sliding at 3 m/s stopped dead at
    // the second seam, and a circle was thrown up at every seam (up to
    // 0.57 m/s), losing a third of its speed over five seams.
    for shape in [Shape::rect(0.4, 0.4), Shape::circle(0.2)] {
        let run = |side_by_side: bool| {
            let (mut world, _) = crates(12, side_by_side);
            let body = slider(&mut world, shape, 0.3);
            world.set_velocity(body, Vec2::new(3.0, 0.0));
            // 3 m/s for 3 s: 9 m, across eight seams.
            (0..180)
                .map(|_| {
                    world.step(DT);
                    world.body(body).unwrap()
                })
                .collect::<Vec<_>>()
        };
        let (seamed, reference) = (run(true), run(false));
        let end = seamed.last().unwrap().position.x;
        assert!(end > 9.0, "{shape:?}: crossed the seams, at {end}");
        for (tick, (s, r)) in seamed.iter().zip(&reference).enumerate() {
            // (Leaving a crate, the body may close on the corner it leaves
            // at that corner's gap per substep, a speculative contact: 1 mm/s
            // for a tick at most.)
            assert!(
                s.velocity.y.abs() < 2e-3 && (s.position.y - r.position.y).abs() < 1e-4,
                "{shape:?}, tick {tick}: at {} moving {}, on one crate at {} moving {}",
                s.position,
                s.velocity,
                r.position,
                r.velocity
            );
            // (Leaving each crate, gravity presses it on the crate's corner
            // for a substep or two: 1e-4 m/s forward at most.)
            assert!(
                (s.velocity.x - r.velocity.x).abs() < 1e-3,
                "{shape:?}, tick {tick}: {} m/s over the seams, {} on one crate",
                s.velocity.x,
                r.velocity.x
            );
        }
    }
}

#[test]
fn a_step_higher_than_the_slop_still_stops_a_box_and_a_body_leaving_a_crate_falls() {
    // A crate 2 cm taller than the one the box slides on: a wall (the box
    // pushes it along). (A circle meets that corner's normal and may hop
    // onto it, as a ball hits a kerb.)
    let mut world = World::default();
    add_ground(&mut world, 20.0);
    add_box(&mut world, Vec2::new(0.5, 0.5), Vec2::ONE, 5.0);
    let wall = add_box(&mut world, Vec2::new(1.5, 0.51), Vec2::new(1.0, 1.02), 5.0);
    let body = slider(&mut world, Shape::rect(0.4, 0.4), 0.3);
    world.set_velocity(body, Vec2::new(3.0, 0.0));
    for _ in 0..60 {
        world.step(DT);
        let (b, w) = (world.body(body).unwrap(), world.body(wall).unwrap());
        assert!(
            b.position.x + 0.2 < w.position.x - 0.5 + 0.005 && b.position.y < 1.2 + 0.005,
            "the box climbed a 2 cm step: at {}, the taller crate at {}",
            b.position,
            w.position
        );
    }

    for shape in [Shape::rect(0.4, 0.4), Shape::circle(0.2)] {
        // Off the end of a lone crate: it falls in the first step it starts
        // wholly past the crate, not held up by the crate's top beyond its
        // edge (the crate closes on it along y only: gravity).
        let (mut world, _) = crates(1, true);
        let body = slider(&mut world, shape, 0.5);
        world.set_velocity(body, Vec2::new(3.0, 0.0));
        let mut airborne = 0;
        for _ in 0..30 {
            let past = world.body(body).unwrap().position.x - shape.half_extents().x > 1.0;
            world.step(DT);
            let b = world.body(body).unwrap();
            if past {
                airborne += 1;
                assert!(
                    b.velocity.y < -0.1,
                    "{shape:?} held up past the edge: {b:?}"
                );
            }
        }
        assert!(airborne > 5, "{shape:?} left the crate");
    }
}

#[test]
fn a_box_falling_past_a_crate_it_overlaps_by_less_than_the_slop_slides_down_its_side() {
    // A 0.4 m box dropped so that it overlaps a 1 m crate's top by 3 mm
    // sideways, and one that overlaps it by 2 cm: the first lands on the
    // ground beside the crate, the second on the crate's edge.
    for (overlap, on_crate) in [(0.003, false), (0.02, true)] {
        let mut world = World::default();
        add_ground(&mut world, 20.0);
        add_box(&mut world, Vec2::new(0.5, 0.5), Vec2::ONE, 5.0);
        let def = BodyDef {
            position: Vec2::new(-0.2 + overlap, 3.0),
            shape: Some(Shape::rect(0.4, 0.4)),
            friction: 0.0,
            ..Default::default()
        };
        let body = world.add_body(def).unwrap();
        for _ in 0..120 {
            world.step(DT);
        }
        let y = world.body(body).unwrap().position.y;
        let want = if on_crate { 1.2 } else { 0.2 };
        assert!(
            (y - want).abs() < 0.01,
            "overlap {overlap}: rests at y = {y}"
        );
    }
}

#[test]
fn a_box_and_a_circle_slide_from_a_one_way_run_onto_solid_ground_level_with_it() {
    // A one-way platform does not cover a solid neighbour's face, and the
    // body, pulled down by gravity as it slid, took the solid run's side at
    // the joint: it stopped dead there.
    for shape in [Shape::rect(0.6, 1.0), Shape::circle(0.4)] {
        let mut world = World::default();
        let one_way = BodyDef::new_static(Vec2::new(-5.0, -0.5), Shape::rect(10.0, 1.0));
        world.add_body(one_way.with_one_way(Vec2::Y)).unwrap();
        let solid = BodyDef::new_static(Vec2::new(5.0, -0.5), Shape::rect(10.0, 1.0));
        world.add_body(solid).unwrap();
        let def = BodyDef {
            position: Vec2::new(-3.0, shape.half_extents().y),
            shape: Some(shape),
            friction: 0.0,
            ..Default::default()
        };
        let body = world.add_body(def).unwrap();
        world.set_velocity(body, Vec2::new(3.0, 0.0));
        for _ in 0..120 {
            world.step(DT);
            let b = world.body(body).unwrap();
            assert!(
                (b.velocity - Vec2::new(3.0, 0.0)).length() < 1e-3,
                "{shape:?} at {}: {}",
                b.position,
                b.velocity
            );
        }
        assert!(world.body(body).unwrap().position.x > 2.9);
    }
}

#[test]
fn a_crate_resting_above_a_covered_face_is_not_shoved_sideways() {
    // A face counts as covered when a static or kinematic box lies flush on
    // it or across it. A crate resting above such a face (on a thin coat
    // flush on the ground, or on a ledge a lift rises through) was given a
    // sideways contact as deep as its own width and pushed 0.95 m along
    // the ground, or 5 cm in one step, at rest before and after.
    for (hz, coat) in [
        (60.0f32, 0.011f32),
        (30.0, 0.011),
        (30.0, 0.015),
        (30.0, 0.02),
    ] {
        let mut world = World::default();
        let ground = BodyDef::new_static(Vec2::new(0.0, -0.5), Shape::rect(2.0, 1.0));
        world.add_body(ground).unwrap();
        let strip = BodyDef::new_static(Vec2::new(0.0, coat / 2.0), Shape::rect(2.0, coat));
        world.add_body(strip.with_friction(0.02)).unwrap();
        let at = Vec2::new(0.3, coat + 0.25);
        let crate_ = world
            .add_body(BodyDef::new_dynamic(at, Shape::rect(0.5, 0.5)))
            .unwrap();
        for _ in 0..120 {
            world.step(1.0 / hz);
        }
        let x = world.body(crate_).unwrap().position.x;
        assert!(
            (x - 0.3).abs() < 1e-4,
            "{hz} Hz, {coat} m coat: the crate went to x = {x}"
        );
    }
    for speed in [0.5f32, 3.0] {
        let mut world = World::default();
        let ledge = BodyDef::new_static(Vec2::new(0.0, -0.5), Shape::rect(1.0, 1.0));
        world.add_body(ledge).unwrap();
        let crate_ = world
            .add_body(BodyDef::new_dynamic(
                Vec2::new(0.0, 0.25),
                Shape::rect(0.5, 0.5),
            ))
            .unwrap();
        let lift = BodyDef::new_kinematic(
            Vec2::new(0.0, -3.0),
            Shape::rect(3.0, 0.2),
            Vec2::new(0.0, speed),
        );
        world.add_body(lift).unwrap();
        for step in 0..(4.0 / speed * 60.0) as usize {
            world.step(DT);
            let x = world.body(crate_).unwrap().position.x;
            assert!(
                x.abs() < 1e-4,
                "lift at {speed} m/s, step {step}: the crate went to x = {x}"
            );
        }
    }
}
