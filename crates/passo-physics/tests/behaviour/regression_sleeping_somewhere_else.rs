//! A body that slept, woke while no other body slept, slid elsewhere and
//! fell asleep again stayed in the sleep tree at its old box: awake bodies
//! looked for it there, so one could pass through it. And which sleeping
//! bodies were in the tree depended on when the tree was last built, so a
//! world restored from a snapshot (which builds it afresh) could step
//! differently from the original: GGRS's sync test of the netplay example
//! caught that (`tests/netplay.rs`); the second test here keeps a simpler
//! scene honest at every tick.

use crate::support::add_ground;
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, BodyId, Shape, World};

const DT: f32 = 1.0 / 60.0;

fn ground_and_crate() -> (World, BodyId) {
    let mut world = World::default();
    add_ground(&mut world, 60.0);
    let crate_ = world
        .add_body(
            BodyDef::new_dynamic(Vec2::new(0.0, 0.5), Shape::rect(1.0, 1.0)).with_friction(0.5),
        )
        .unwrap();
    (world, crate_)
}

fn step_until_asleep(world: &mut World, id: BodyId) {
    for _ in 0..600 {
        world.step(DT);
        if world.is_asleep(id) == Some(true) {
            return;
        }
    }
    panic!("{id:?} never fell asleep");
}

#[test]
fn a_body_that_sleeps_again_elsewhere_is_found_where_it_sleeps() {
    let (mut world, crate_) = ground_and_crate();
    step_until_asleep(&mut world, crate_);
    // A few more steps: it is in the sleep tree.
    for _ in 0..5 {
        world.step(DT);
    }
    // Pushed 5 m to the right; nothing else sleeps while it slides.
    world.set_velocity(crate_, Vec2::new(5.0, 0.0));
    step_until_asleep(&mut world, crate_);
    for _ in 0..5 {
        world.step(DT);
    }
    let rest = world.body(crate_).unwrap().position;
    assert!(
        rest.x > 1.5,
        "the crate slid away from where it first slept: {rest}"
    );
    // A ball rolls at it from the left along the ground.
    let ball = world
        .add_body(
            BodyDef::new_dynamic(Vec2::new(rest.x - 3.0, 0.25), Shape::circle(0.25))
                .with_velocity(Vec2::new(6.0, 0.0)),
        )
        .unwrap();
    for _ in 0..120 {
        world.step(DT);
    }
    let ball_x = world.body(ball).unwrap().position.x;
    assert!(
        ball_x < rest.x - 0.5 + 0.25 + 0.01,
        "the ball stops at the crate's left face ({}), not inside or past it: {ball_x}",
        rest.x - 0.5
    );
}

#[test]
fn a_world_restored_at_any_tick_steps_as_the_original() {
    // Crates that fall asleep, wake, slide and fall asleep again, pushed by
    // a ball now and then.
    let (mut world, _) = ground_and_crate();
    for i in 1..8 {
        world
            .add_body(BodyDef::new_dynamic(
                Vec2::new(i as f32 * 1.5, 0.5),
                Shape::rect(1.0, 1.0),
            ))
            .unwrap();
    }
    let ball = world
        .add_body(BodyDef::new_dynamic(Vec2::new(-5.0, 0.25), Shape::circle(0.25)).with_mass(20.0))
        .unwrap();
    for tick in 0..900u32 {
        if tick % 150 == 60 {
            let x = world.body(ball).unwrap().position.x;
            let push = if x < 4.0 { 8.0 } else { -8.0 };
            world.set_velocity(ball, Vec2::new(push, 0.0));
        }
        let mut copy = World::from_snapshot(world.snapshot()).unwrap();
        world.step(DT);
        copy.step(DT);
        assert_eq!(
            copy.state_hash(),
            world.state_hash(),
            "a copy restored at tick {tick} stepped differently"
        );
    }
}
