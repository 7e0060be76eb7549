//! Sleeping: resting islands stop costing solver work, keep their contacts,
//! and wake when something reaches them or game code changes them.

use crate::support::{add_box, add_ground, add_static_box, assert_finite};
use passo_physics::constants::{SLEEP_SPEED, TIME_TO_SLEEP};
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, BodyId, ContactSettings, JointDef, Shape, World, WorldSettings};

const DT: f32 = 1.0 / 60.0;

fn run(world: &mut World, seconds: f32) {
    for _ in 0..(seconds / DT).round() as usize {
        world.step(DT);
        assert_finite(world);
    }
}

/// A ground and a stack of `n` unit boxes at `x`.
fn stack(world: &mut World, x: f32, n: usize) -> Vec<BodyId> {
    (0..n)
        .map(|i| add_box(world, Vec2::new(x, 0.5 + i as f32), Vec2::ONE, 1.0))
        .collect()
}

fn ground(world: &mut World) -> BodyId {
    add_static_box(world, Vec2::new(-20.0, -1.0), Vec2::new(20.0, 0.0))
}

fn asleep(world: &World, ids: &[BodyId]) -> Vec<bool> {
    ids.iter().map(|&id| world.is_asleep(id).unwrap()).collect()
}

#[test]
fn a_resting_stack_falls_asleep_and_keeps_its_contacts() {
    let mut w = World::new(WorldSettings::default()).unwrap();
    ground(&mut w);
    let boxes = stack(&mut w, 0.0, 5);
    // Not before it has rested for TIME_TO_SLEEP.
    run(&mut w, 0.9 * TIME_TO_SLEEP);
    assert_eq!(w.sleeping_len(), 0);
    run(&mut w, 2.0);
    assert_eq!(asleep(&w, &boxes), vec![true; 5]);
    assert_eq!(w.sleeping_len(), 5);
    assert_eq!(
        w.solved_contacts(),
        0,
        "no contact of a sleeping island is solved"
    );
    // The contacts are still there, touching, and the top box still stands.
    let touching = w.contacts().filter(|c| c.touching).count();
    assert_eq!(touching, 5, "ground-box and four box-box contacts");
    assert!(w.is_standing(boxes[4], 0.8));
    assert!(w.body(boxes[2]).unwrap().asleep);
    // Asleep, nothing moves by a single bit, and no event fires.
    let before = w.state_hash();
    for _ in 0..120 {
        w.step(DT);
        assert!(w.events().begin.is_empty() && w.events().end.is_empty());
    }
    assert_eq!(w.state_hash(), before);
    for &id in &boxes {
        assert_eq!(w.body(id).unwrap().velocity, Vec2::ZERO);
    }
}

#[test]
fn a_falling_or_sliding_body_does_not_sleep() {
    let mut w = World::new(WorldSettings::default()).unwrap();
    ground(&mut w);
    // Sliding at 3 m/s on ice (no friction) for 3 s: never slower than SLEEP_SPEED.
    let slider = w
        .add_body(BodyDef {
            position: Vec2::new(-15.0, 0.5),
            velocity: Vec2::new(3.0, 0.0),
            shape: Some(Shape::rect(1.0, 1.0)),
            friction: 0.0,
            ..Default::default()
        })
        .unwrap();
    // A ball bouncing elastically: slow at the top of each bounce, never for long.
    let ball = w
        .add_body(BodyDef {
            position: Vec2::new(10.0, 3.0),
            shape: Some(Shape::circle(0.25)),
            restitution: 1.0,
            ..Default::default()
        })
        .unwrap();
    for _ in 0..180 {
        w.step(DT);
        assert!(!w.is_asleep(slider).unwrap());
        assert!(!w.is_asleep(ball).unwrap());
    }
    assert!(w.body(slider).unwrap().velocity.x > 2.9);
}

#[test]
fn bodies_pushed_out_of_an_overlap_are_not_resting() {
    // Overlapping boxes have zero velocity while the push separates them:
    // they must not fall asleep still overlapping.
    let mut w = World::new(WorldSettings::default()).unwrap();
    ground(&mut w);
    for i in 0..6 {
        add_box(&mut w, Vec2::new(i as f32 * 0.6, 0.5), Vec2::ONE, 1.0);
    }
    run(&mut w, 3.0);
    assert_eq!(w.sleeping_len(), 6, "they settle and sleep");
    let pen = crate::support::max_penetration(&w);
    assert!(
        pen <= 2.0 * passo_physics::constants::LINEAR_SLOP,
        "asleep at {pen} m overlap"
    );
}

#[test]
fn neighbours_within_the_slop_fall_asleep_together_and_stay_asleep() {
    // Two boxes side by side, 2 mm apart: not touching, but closer than the
    // slop, where an awake body wakes a sleeping one. The second lands
    // later, so it rests for less time. Were they islands of their own, the
    // first would fall asleep, be woken by the second, and the two would
    // take turns for ever.
    let mut w = World::new(WorldSettings::default()).unwrap();
    ground(&mut w);
    let first = add_box(&mut w, Vec2::new(0.0, 0.5), Vec2::ONE, 1.0);
    let second = add_box(&mut w, Vec2::new(1.002, 0.8), Vec2::ONE, 1.0);
    let ids = [first, second];
    let mut asleep_at = None;
    for tick in 0..240 {
        w.step(DT);
        let now = asleep(&w, &ids);
        if asleep_at.is_none() && now != [false, false] {
            assert_eq!(now, [true, true], "tick {tick}: one island, asleep as one");
            asleep_at = Some(tick);
        }
        if asleep_at.is_some() {
            assert_eq!(now, [true, true], "tick {tick}: woken again");
        }
    }
    let gap = w.body(second).unwrap().position.x - w.body(first).unwrap().position.x - 1.0;
    assert!(
        gap > 0.0 && gap < passo_physics::constants::LINEAR_SLOP,
        "{gap} m apart"
    );
    let tick = asleep_at.expect("they fall asleep");
    // The second lands after about 0.25 s and rests for TIME_TO_SLEEP.
    assert!(
        (tick as f32) * DT < 0.3 + TIME_TO_SLEEP + 0.5,
        "asleep only at tick {tick}"
    );
}

#[test]
fn an_awake_body_wakes_the_island_it_reaches_and_only_that_one() {
    let mut w = World::new(WorldSettings::default()).unwrap();
    ground(&mut w);
    let left = stack(&mut w, -5.0, 4);
    let right = stack(&mut w, 5.0, 4);
    run(&mut w, 2.0);
    assert_eq!(w.sleeping_len(), 8);
    // A heavy ball dropped on the left stack wakes it, not the right one.
    let ball = w
        .add_body(BodyDef {
            position: Vec2::new(-5.0, 8.0),
            shape: Some(Shape::circle(0.4)),
            mass: 5.0,
            ..Default::default()
        })
        .unwrap();
    let mut woke = false;
    for _ in 0..120 {
        w.step(DT);
        woke |= asleep(&w, &left).iter().all(|&s| !s);
        assert_eq!(asleep(&w, &right), vec![true; 4], "the far stack sleeps on");
    }
    assert!(woke, "the stack the ball fell on woke up");
    assert!(
        w.body(ball).unwrap().position.y > 4.0,
        "the ball rests on the stack"
    );
}

#[test]
fn changing_a_sleeping_body_wakes_its_island() {
    let mut w = World::new(WorldSettings::default()).unwrap();
    ground(&mut w);
    let boxes = stack(&mut w, 0.0, 3);
    run(&mut w, 2.0);
    assert_eq!(asleep(&w, &boxes), vec![true; 3]);
    // An impulse on the bottom box wakes the whole stack at once.
    w.apply_impulse(boxes[0], Vec2::new(0.5, 0.0));
    assert_eq!(asleep(&w, &boxes), vec![false; 3]);
    run(&mut w, 3.0);
    assert_eq!(
        asleep(&w, &boxes),
        vec![true; 3],
        "asleep again once at rest"
    );

    // Every other kind of change wakes it too.
    type Change = fn(&mut World, BodyId);
    let changes: [(&str, Change); 7] = [
        ("force", |w, id| w.apply_force(id, Vec2::X)),
        ("velocity", |w, id| w.set_velocity(id, Vec2::ZERO)),
        ("position", |w, id| {
            let p = w.body(id).unwrap().position;
            w.set_position(id, p)
        }),
        ("friction", |w, id| w.set_friction(id, 0.5)),
        ("restitution", |w, id| w.set_restitution(id, 0.1).unwrap()),
        ("drag area", |w, id| w.set_drag_area(id, 0.2).unwrap()),
        ("wake", |w, id| w.wake(id).unwrap()),
    ];
    for (what, change) in changes {
        run(&mut w, 2.0);
        assert_eq!(asleep(&w, &boxes), vec![true; 3], "before {what}");
        change(&mut w, boxes[1]);
        assert_eq!(
            asleep(&w, &boxes),
            vec![false; 3],
            "{what} wakes the island"
        );
    }
}

#[test]
fn removing_a_support_or_changing_the_world_wakes_what_rested_on_it() {
    let mut w = World::new(WorldSettings::default()).unwrap();
    let floor = ground(&mut w);
    let boxes = stack(&mut w, 0.0, 3);
    run(&mut w, 2.0);
    assert_eq!(w.sleeping_len(), 3);
    // Remove the bottom box: the two above wake and fall onto the ground.
    let top_before = w.body(boxes[2]).unwrap().position.y;
    w.remove_body(boxes[0]).unwrap();
    assert_eq!(asleep(&w, &boxes[1..]), vec![false; 2]);
    run(&mut w, 2.0);
    let drop = top_before - w.body(boxes[2]).unwrap().position.y;
    assert!(
        (drop - 1.0).abs() < 0.02,
        "the stack fell one box: {drop} m"
    );

    // New settings (a gravity slider) wake every body.
    assert_eq!(w.sleeping_len(), 2);
    let mut settings = *w.settings();
    settings.forces.gravity = Some(Vec2::new(3.0, -9.81));
    w.set_settings(settings).unwrap();
    assert_eq!(w.sleeping_len(), 0);
    // Removing the ground (a static body) wakes everything too.
    run(&mut w, 3.0);
    settings.forces.gravity = Some(Vec2::new(0.0, -9.81));
    w.set_settings(settings).unwrap();
    run(&mut w, 3.0);
    assert!(w.sleeping_len() > 0);
    w.remove_body(floor).unwrap();
    assert_eq!(w.sleeping_len(), 0);
    run(&mut w, 1.0);
    assert!(
        w.body(boxes[1]).unwrap().position.y < -1.0,
        "falls once the floor is gone"
    );
}

#[test]
fn with_sleeping_off_no_body_ever_sleeps() {
    let mut w = World::new(WorldSettings {
        contacts: Some(ContactSettings {
            sleeping: false,
            ..Default::default()
        }),
        ..Default::default()
    })
    .unwrap();
    ground(&mut w);
    stack(&mut w, 0.0, 4);
    run(&mut w, 3.0);
    assert_eq!(w.sleeping_len(), 0);
    assert_eq!(w.solved_contacts(), w.contacts().count());
}

#[test]
fn a_slow_drift_below_the_sleep_speed_counts_as_rest() {
    // No gravity, no contact with anything but a far ground: a box gliding
    // at half the sleep speed falls asleep after TIME_TO_SLEEP and stops.
    let mut w = World::new(WorldSettings {
        forces: passo_physics::ForceModels::none(),
        min_speed: 0.0,
        ..Default::default()
    })
    .unwrap();
    ground(&mut w);
    let id = w
        .add_body(BodyDef {
            position: Vec2::new(0.0, 5.0),
            velocity: Vec2::new(0.5 * SLEEP_SPEED, 0.0),
            shape: Some(Shape::rect(1.0, 1.0)),
            ..Default::default()
        })
        .unwrap();
    let steps_to_sleep = (TIME_TO_SLEEP / DT).ceil() as usize;
    for _ in 0..steps_to_sleep - 1 {
        w.step(DT);
    }
    assert!(!w.is_asleep(id).unwrap());
    w.step(DT);
    assert!(w.is_asleep(id).unwrap());
    assert_eq!(w.body(id).unwrap().velocity, Vec2::ZERO);
}

/// A ground with a stack of four boxes at x = 0 and one of two at x = 3,
/// after `seconds`.
fn two_stacks(seconds: f32) -> World {
    let mut w = World::new(WorldSettings::default()).unwrap();
    ground(&mut w);
    stack(&mut w, 0.0, 4);
    stack(&mut w, 3.0, 2);
    run(&mut w, seconds);
    w
}

/// A 4 kg ball of radius 0.3 m at `position`.
fn heavy_ball(position: Vec2) -> BodyDef {
    BodyDef {
        position,
        shape: Some(Shape::circle(0.3)),
        mass: 4.0,
        ..Default::default()
    }
}

#[test]
fn rollback_through_a_sleeping_world_gives_the_same_bits() {
    let w = two_stacks(1.5);
    assert!(w.sleeping_len() > 0);
    let snapshot = w.snapshot();
    let ball = heavy_ball(Vec2::new(0.2, 7.0));
    let mut straight = w.clone();
    straight.add_body(ball).unwrap();
    run(&mut straight, 2.0);
    let mut restored = World::from_snapshot(snapshot).unwrap();
    restored.add_body(ball).unwrap();
    run(&mut restored, 2.0);
    assert_eq!(restored.state_hash(), straight.state_hash());
    assert_eq!(restored.sleeping_len(), straight.sleeping_len());
}

#[test]
fn removing_a_body_keeps_the_sleeping_ones_reachable() {
    // Enough sleeping boxes for the sleep tree (more than 64), and a body
    // stored first that keeps moving: removing it moves the last box (asleep
    // on top of the last stack) into its place in storage.
    let mut w = World::new(WorldSettings::default()).unwrap();
    let faller = w
        .add_body(BodyDef {
            position: Vec2::new(100.0, 0.0),
            shape: Some(Shape::circle(0.1)),
            ..Default::default()
        })
        .unwrap();
    add_static_box(&mut w, Vec2::new(-30.0, -1.0), Vec2::new(30.0, 0.0));
    let stacks: Vec<Vec<BodyId>> = (0..10).map(|s| stack(&mut w, s as f32 * 2.0, 8)).collect();
    run(&mut w, 2.0);
    assert_eq!(w.sleeping_len(), 80);
    w.remove_body(faller).unwrap();
    assert_eq!(w.sleeping_len(), 80, "removing an awake body wakes no one");
    // A ball dropped on the box that moved in storage lands on it.
    let top = *stacks[9].last().unwrap();
    let top_y = w.body(top).unwrap().position.y;
    let ball = w
        .add_body(BodyDef {
            position: Vec2::new(18.0, top_y + 3.0),
            shape: Some(Shape::circle(0.3)),
            ..Default::default()
        })
        .unwrap();
    run(&mut w, 2.0);
    let rest = w.body(ball).unwrap().position.y;
    assert!(
        (rest - (top_y + 0.5 + 0.3)).abs() < 0.02,
        "the ball rests on the top box: {rest} vs {}",
        top_y + 0.8
    );
    assert_eq!(
        asleep(&w, &stacks[0]),
        vec![true; 8],
        "a stack nothing reached sleeps on"
    );
}

#[test]
fn a_body_inside_a_sensor_stays_awake_and_inside() {
    let mut w = World::new(WorldSettings::default()).unwrap();
    ground(&mut w);
    let zone = w
        .add_body(BodyDef {
            sensor: true,
            ..BodyDef::new_static(Vec2::new(0.0, 1.0), Shape::rect(3.0, 2.0))
        })
        .unwrap();
    let inside = add_box(&mut w, Vec2::new(0.0, 0.5), Vec2::ONE, 1.0);
    let outside = add_box(&mut w, Vec2::new(6.0, 0.5), Vec2::ONE, 1.0);
    run(&mut w, 3.0);
    assert!(w.is_asleep(outside).unwrap());
    assert!(!w.is_asleep(inside).unwrap(), "a sensor keeps seeing it");
    assert_eq!(w.sensor_overlaps().len(), 1);
    assert_eq!(w.sensor_overlaps()[0].sensor, zone);
    for _ in 0..60 {
        w.step(DT);
        assert!(w.events().sensor_end.is_empty());
    }
}

#[test]
fn a_woken_island_reports_awake_at_once_and_a_snapshot_taken_then_resumes_bit_for_bit() {
    // Two stacks of three boxes, each its own island, asleep.
    let mut world = World::default();
    add_ground(&mut world, 20.0);
    let stack = |world: &mut World, x: f32| -> Vec<_> {
        (0..3)
            .map(|i| {
                world
                    .add_body(BodyDef::new_dynamic(
                        Vec2::new(x, 0.5 + i as f32),
                        Shape::rect(1.0, 1.0),
                    ))
                    .unwrap()
            })
            .collect()
    };
    let (left, right) = (stack(&mut world, -3.0), stack(&mut world, 3.0));
    for _ in 0..120 {
        world.step(1.0 / 60.0);
    }
    assert_eq!(world.sleeping_len(), 6);
    // Waking the top of the left stack wakes its island, at once.
    world.wake(left[2]).unwrap();
    for &id in &left {
        assert_eq!(world.is_asleep(id), Some(false));
        assert!(!world.body(id).unwrap().asleep);
    }
    for &id in &right {
        assert_eq!(world.is_asleep(id), Some(true));
    }
    assert_eq!(world.sleeping_len(), 3);
    // A snapshot taken now resumes to the same bits as the world.
    let mut copy = World::from_snapshot(world.snapshot()).unwrap();
    for _ in 0..60 {
        world.step(1.0 / 60.0);
        copy.step(1.0 / 60.0);
    }
    assert_eq!(world.state_hash(), copy.state_hash());
}

#[test]
fn a_world_woken_whole_keeps_no_mark_that_wakes_an_island_later() {
    // Game code wakes a sleeping stack and, in the same tick, changes the
    // settings (which wakes every body). The stack sleeps again under the
    // same island id; a stale mark from the first wake woke it again at
    // the next wake anywhere, in the live world only: a world restored
    // from a save in between stepped differently.
    let mut world = World::default();
    add_static_box(&mut world, Vec2::new(-20.0, -1.0), Vec2::new(20.0, 0.0));
    let boxes = stack(&mut world, -5.0, 3);
    let ball = BodyDef::new_dynamic(Vec2::new(5.0, 0.3), Shape::circle(0.3));
    let ball = world.add_body(ball).unwrap();
    let settle = |w: &mut World| {
        for _ in 0..2000 {
            if w.is_asleep(boxes[0]) == Some(true) && w.is_asleep(ball) == Some(true) {
                return;
            }
            w.step(DT);
        }
        panic!("the stack and the ball fall asleep");
    };
    settle(&mut world);
    world.apply_impulse(boxes[2], Vec2::new(0.01, 0.0));
    world.set_settings(*world.settings()).unwrap();
    settle(&mut world);
    let mut restored = World::from_snapshot(world.snapshot()).unwrap();
    for w in [&mut world, &mut restored] {
        w.apply_impulse(ball, Vec2::new(0.0, 0.5));
        w.step(DT);
    }
    assert_eq!(
        world.is_asleep(boxes[0]),
        Some(true),
        "the ball woke only itself"
    );
    assert_eq!(restored.is_asleep(boxes[0]), Some(true));
    for k in 0..60 {
        for w in [&mut world, &mut restored] {
            if k == 10 {
                w.set_velocity(boxes[2], Vec2::new(0.0, 2.0));
            }
            w.step(DT);
        }
        assert_eq!(world.state_hash(), restored.state_hash(), "step {k}");
    }
}

#[test]
fn the_sleep_tree_is_built_when_an_island_sleeps_half_of_it_wakes_or_the_step_changes() {
    // Three stacks of four asleep: the tree of sleeping bodies is built
    // once they sleep, then kept while nothing changes.
    let mut w = World::new(WorldSettings::default()).unwrap();
    ground(&mut w);
    let stacks: Vec<_> = [-6.0, 0.0, 6.0].map(|x| stack(&mut w, x, 4)).into();
    run(&mut w, 3.0);
    assert_eq!(w.sleeping_len(), 12);
    let builds = |w: &World| w.counters().sleep_tree_builds;
    let first = builds(&w);
    assert!(
        (1..=3).contains(&first),
        "{first} builds: one a stack at most"
    );
    run(&mut w, 1.0);
    assert_eq!(builds(&w), first, "nothing changed: kept");
    // One stack woken: a third of the tree leaves it, which keeps the
    // rest; one build when that stack sleeps again.
    w.wake(stacks[0][0]).unwrap();
    w.step(DT);
    assert_eq!(builds(&w), first, "a third woke: kept");
    run(&mut w, 3.0);
    assert_eq!(w.sleeping_len(), 12);
    assert_eq!(builds(&w), first + 1, "the stack slept again");
    // Two stacks woken: more than half the tree leaves, built at once.
    w.wake(stacks[0][0]).unwrap();
    w.wake(stacks[2][0]).unwrap();
    w.step(DT);
    assert_eq!(builds(&w), first + 2, "two thirds woke: built");
    run(&mut w, 3.0);
    assert_eq!(w.sleeping_len(), 12);
    let slept = builds(&w);
    assert!(slept > first + 2, "the stacks slept again");
    // Another step length grows the boxes by another margin (continuous
    // collision reaches as far as a body falls in a step): built again.
    w.step(2.0 * DT);
    assert_eq!(builds(&w), slept + 1, "a longer step");
    w.step(DT);
    assert_eq!(builds(&w), slept + 2, "back to the usual step");
    w.step(DT);
    assert_eq!(builds(&w), slept + 2, "the same step: kept");
    assert_eq!(w.sleeping_len(), 12, "none of it woke a body");
}

#[test]
fn restoring_a_sleeping_world_in_place_steps_as_one_made_from_the_snapshot() {
    // A world asleep, saved; then a ball wakes a stack, a new stack is
    // built, and the world moves on until all of it sleeps. Restored in
    // place, it steps as a world made from the snapshot when another ball
    // wakes that stack: the stored contacts, islands and sleep tree are
    // the snapshot's, none of the world that moved on.
    let mut w = two_stacks(2.0);
    assert_eq!(w.sleeping_len(), 6);
    let saved = w.snapshot();
    w.add_body(heavy_ball(Vec2::new(0.2, 7.0))).unwrap();
    stack(&mut w, 10.0, 5);
    run(&mut w, 3.0);
    assert_eq!(w.sleeping_len(), 12, "the new stack and the ball slept too");
    w.restore_from(&saved).unwrap();
    let mut made = World::from_snapshot(saved).unwrap();
    for world in [&mut w, &mut made] {
        world.add_body(heavy_ball(Vec2::new(-0.1, 6.0))).unwrap();
    }
    for tick in 0..180 {
        w.step(DT);
        made.step(DT);
        assert_eq!(w.state_hash(), made.state_hash(), "tick {tick}");
        assert_eq!(w.sleeping_len(), made.sleeping_len(), "tick {tick}");
    }
}

#[test]
fn waking_the_only_sleeping_island_hands_its_contacts_back_once() {
    // One stack asleep, woken by game code: after the next step its
    // contacts are listed once each, as before it slept, none twice.
    let mut w = World::new(WorldSettings::default()).unwrap();
    ground(&mut w);
    let ids = stack(&mut w, 0.0, 3);
    run(&mut w, 2.0);
    assert_eq!(w.sleeping_len(), 3);
    let pairs = |w: &World| {
        let mut pairs: Vec<_> = w.contacts().map(|c| (c.a, c.b)).collect();
        pairs.sort();
        pairs
    };
    let asleep = pairs(&w);
    assert!(!asleep.is_empty());
    w.wake(ids[0]).unwrap();
    for _ in 0..3 {
        w.step(DT);
        assert_eq!(w.sleeping_len(), 0);
        assert_eq!(pairs(&w), asleep);
    }
}

#[test]
fn the_stages_listed_after_a_wake_hold_no_sleeper() {
    // The only sleeping island woken by game code (a ball falls far
    // away): its bodies are awake at once, so the next step holds no
    // sleeping body, and the stages listed before it say so.
    let mut w = World::new(WorldSettings::default()).unwrap();
    ground(&mut w);
    let ids = stack(&mut w, 0.0, 3);
    run(&mut w, 2.0);
    // A ball falling far away: the contact step runs.
    let ball = BodyDef {
        position: Vec2::new(15.0, 30.0),
        shape: Some(Shape::circle(0.3)),
        ..Default::default()
    };
    w.add_body(ball).unwrap();
    w.step(DT);
    let hold = passo_physics::ContactStage::HoldSleepers;
    assert!(w.contact_stages().contains(&hold));
    w.wake(ids[2]).unwrap();
    assert!(!w.contact_stages().contains(&hold));
    w.step(DT);
    assert!(!w.contact_stages().contains(&hold));
}

#[test]
fn an_awake_body_close_to_a_sleeping_one_but_not_touching_leaves_it_asleep() {
    // A box kept awake by a sensor rests a centimetre from a sleeping
    // one: close enough for a speculative contact between them, not
    // touching. Only a touching contact wakes a sleeper.
    let mut w = World::new(WorldSettings::default()).unwrap();
    ground(&mut w);
    w.add_body(BodyDef {
        sensor: true,
        ..BodyDef::new_static(Vec2::new(1.51, 1.0), Shape::rect(0.5, 2.0))
    })
    .unwrap();
    let sleeper = add_box(&mut w, Vec2::new(0.0, 0.5), Vec2::ONE, 1.0);
    run(&mut w, 2.0);
    assert!(w.is_asleep(sleeper).unwrap());
    let awake = add_box(&mut w, Vec2::new(1.01, 0.5), Vec2::ONE, 1.0);
    for _ in 0..120 {
        w.step(DT);
        assert!(w.is_asleep(sleeper).unwrap());
        assert!(!w.is_asleep(awake).unwrap());
    }
    let near = w
        .contacts_of(awake)
        .any(|c| c.b == sleeper || c.a == sleeper);
    assert!(near, "a speculative contact between them");
}

#[test]
fn waking_every_body_wakes_a_chain_asleep_with_no_contact_stored() {
    // Three bodies without shapes hanging still from a rod chain: an
    // island with no contact to store. Game code waking every body wakes
    // them too.
    let mut w = World::new(WorldSettings::default()).unwrap();
    ground(&mut w);
    let mut ids: Vec<BodyId> = Vec::new();
    for k in 1..=3 {
        let position = Vec2::new(0.0, 10.0 - k as f32);
        let id = w
            .add_body(BodyDef {
                position,
                ..Default::default()
            })
            .unwrap();
        let rod = match ids.last() {
            None => JointDef::distance(id, None, 1.0).anchors(Vec2::ZERO, Vec2::new(0.0, 10.0)),
            Some(&above) => JointDef::distance(above, Some(id), 1.0),
        };
        w.add_joint(rod).unwrap();
        ids.push(id);
    }
    run(&mut w, 2.0);
    assert_eq!(asleep(&w, &ids), [true; 3]);
    assert!(w.contacts().next().is_none());
    w.wake_all();
    assert_eq!(asleep(&w, &ids), [false; 3]);
    w.step(DT);
    assert_eq!(asleep(&w, &ids), [false; 3]);
}
