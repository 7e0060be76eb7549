//! An island woken at the end of a step (a body touching it) dropped its
//! stored contacts: until the next step found them again, `contacts_of`
//! showed none, the step reported every pair of the stack as no longer
//! touching (and the next step as touching again), and the impulses the
//! stack rested on were not there to warm start from.

use crate::support::add_ground;
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, BodyId, Shape, World};

/// A stack of five boxes on the ground; a ball thrown down at its top.
fn stack_and_ball(sleeping: bool) -> (World, Vec<BodyId>) {
    stack_and_thrown_ball(sleeping, Vec2::new(0.0, 5.6), Vec2::new(0.0, -3.0))
}

/// A stack of five boxes on the ground; a ball thrown from `at` at
/// `velocity`.
fn stack_and_thrown_ball(sleeping: bool, at: Vec2, velocity: Vec2) -> (World, Vec<BodyId>) {
    let mut world = World::default();
    let mut settings = *world.settings();
    settings.contacts.as_mut().unwrap().sleeping = sleeping;
    world.set_settings(settings).unwrap();
    add_ground(&mut world, 20.0);
    let boxes: Vec<_> = (0..5)
        .map(|i| {
            let def = BodyDef::new_dynamic(Vec2::new(0.0, 0.5 + i as f32), Shape::rect(1.0, 1.0));
            world.add_body(def).unwrap()
        })
        .collect();
    for _ in 0..180 {
        world.step(1.0 / 60.0);
    }
    let ball = BodyDef {
        velocity,
        ..BodyDef::new_dynamic(at, Shape::circle(0.1))
    };
    world.add_body(ball).unwrap();
    (world, boxes)
}

/// Steps `world` and a world restored from its snapshot taken now side by
/// side for `ticks` ticks, checking they stay the same bits.
fn steps_on_as_its_snapshot(world: &mut World, ticks: u32, what: &str) {
    let mut restored = World::from_snapshot(world.snapshot()).unwrap();
    for tick in 0..ticks {
        world.step(1.0 / 60.0);
        restored.step(1.0 / 60.0);
        assert_eq!(
            world.state_hash(),
            restored.state_hash(),
            "{what}, tick {tick}"
        );
    }
}

#[test]
fn a_stack_woken_by_a_ball_keeps_its_contacts_in_the_step_it_wakes() {
    let (mut world, boxes) = stack_and_ball(true);
    assert!(boxes.iter().all(|&b| world.is_asleep(b) == Some(true)));
    let mut woke = false;
    for _ in 0..60 {
        world.step(1.0 / 60.0);
        if world.is_asleep(boxes[0]) == Some(false) {
            woke = true;
            break;
        }
    }
    assert!(woke, "the ball woke the stack");
    let stack_pair = |a: BodyId, b: BodyId| boxes.contains(&a) && boxes.contains(&b);
    // Every box still touches the one below, and no pair of the stack
    // stopped touching.
    for k in 1..boxes.len() {
        let below = boxes[k - 1];
        assert!(
            world
                .contacts_of(boxes[k])
                .any(|c| (c.a == below || c.b == below) && c.touching),
            "box {k} touches the box below in the step it woke"
        );
    }
    let ended = world
        .events()
        .end
        .iter()
        .filter(|p| stack_pair(p.a, p.b))
        .count();
    assert_eq!(ended, 0, "no pair of the stack ended touching");
    // Nor does one begin in the next step: they never stopped.
    world.step(1.0 / 60.0);
    let events = world.events();
    let began = events.begin.iter().filter(|p| stack_pair(p.a, p.b)).count();
    let ended = events.end.iter().filter(|p| stack_pair(p.a, p.b)).count();
    assert_eq!(
        (began, ended),
        (0, 0),
        "the next step's events of the stack"
    );
}

#[test]
fn the_woken_stack_takes_the_blow_as_an_awake_one_does() {
    // The ball's blow, sideways at the top box, moves the woken stack
    // about as it moves one that never slept (warm started from the
    // impulses it slept with, which bound the friction that passes the
    // blow down). A blow from above moves neither: shock propagation
    // holds the stack on the ground.
    let speeds = |sleeping: bool| {
        let (at, velocity) = (Vec2::new(-0.65, 4.5), Vec2::new(6.0, 0.0));
        let (mut world, boxes) = stack_and_thrown_ball(sleeping, at, velocity);
        let mut fastest: f32 = 0.0;
        for _ in 0..40 {
            world.step(1.0 / 60.0);
            for &b in &boxes {
                fastest = fastest.max(world.body(b).unwrap().velocity.length());
            }
        }
        fastest
    };
    let (awake, woken) = (speeds(false), speeds(true));
    assert!(awake > 0.1, "the blow moves the stack: {awake}");
    assert!(
        (woken - awake).abs() < 0.5 * awake,
        "woken {woken} m/s against awake {awake} m/s"
    );
}

#[test]
fn a_stack_woken_at_the_start_of_a_step_is_solved_whole_in_it() {
    // A fast ball reaches the stack's top within the step: the island
    // wakes before the solver runs, and its boxes (which slept without
    // proxies) must bring their contacts with each other and with the
    // ground along. Then the stack takes the blow as one that never slept.
    let fast_ball = |sleeping: bool| {
        let (mut world, boxes) = stack_and_ball(sleeping);
        let ball = world.bodies().last().unwrap().id;
        world.set_velocity(ball, Vec2::new(0.0, -12.0));
        (world, boxes)
    };
    let (mut world, boxes) = fast_ball(true);
    let mut steps = 0;
    while world.is_asleep(boxes[0]) == Some(true) && steps < 60 {
        world.step(1.0 / 60.0);
        steps += 1;
    }
    assert!(steps < 60, "the ball woke the stack");
    let (mut awake, _) = fast_ball(false);
    for _ in 0..steps {
        awake.step(1.0 / 60.0);
    }
    for (k, &b) in boxes.iter().enumerate() {
        let touches_below = world.contacts_of(b).any(|c| {
            c.touching
                && (if k == 0 {
                    !boxes.contains(&c.b)
                } else {
                    c.b == boxes[k - 1]
                })
        });
        assert!(touches_below, "box {k} stands on what is below it");
        // Without its contacts a box fell freely: -g dt = -0.16 m/s.
        let (v, v_awake) = (
            world.body(b).unwrap().velocity.y,
            awake.body(b).unwrap().velocity.y,
        );
        assert!(
            (v - v_awake).abs() < 0.25 * v_awake.abs().max(0.1),
            "box {k}: {v} m/s woken, {v_awake} m/s never asleep"
        );
    }
}

#[test]
fn waking_every_body_keeps_the_stored_contacts_for_queries_until_the_next_step() {
    // `wake_all`, new settings, a force model or a static body's change
    // let every sleeping contact go at once: a sleeping player reported not
    // standing (and `contacts_of` nothing) until the next step, where
    // `wake(id)` keeps its island's. A snapshot taken in between restores
    // to a world that steps as this one does.
    type Poke = fn(&mut World);
    let pokes: [(&str, Poke); 4] = [
        ("wake_all", |w| w.wake_all()),
        ("set_settings", |w| w.set_settings(*w.settings()).unwrap()),
        ("a static body added", |w| {
            let far = BodyDef::new_static(Vec2::new(50.0, 5.0), Shape::rect(2.0, 0.5));
            w.add_body(far).unwrap();
        }),
        ("wake", |w| {
            let id = w
                .bodies()
                .find(|b| b.kind == passo_physics::BodyKind::Dynamic)
                .unwrap()
                .id;
            w.wake(id).unwrap();
        }),
    ];
    for (what, poke) in pokes {
        let (mut world, boxes) = stack_and_ball(true);
        // The ball, thrown at the stack, lands in about ten ticks.
        let bottom = boxes[0];
        assert_eq!(world.is_asleep(bottom), Some(true), "{what}");
        assert!(world.is_standing(bottom, 0.7), "{what}");
        let contacts = world.contacts().count();
        poke(&mut world);
        assert_eq!(
            world.is_asleep(bottom),
            Some(false),
            "{what}: awake at once"
        );
        assert!(world.is_standing(bottom, 0.7), "{what}: still standing");
        assert_eq!(world.contacts().count(), contacts, "{what}");
        assert!(world.contacts_of(bottom).count() >= 2, "{what}");
        steps_on_as_its_snapshot(&mut world, 30, what);
    }
}

#[test]
fn removing_a_body_keeps_its_island_mates_contacts_for_queries_until_the_next_step() {
    // `remove_body` wakes the removed body's island. Its other stored
    // contacts were let go at once: a crate whose top crate was removed
    // reported not standing for that tick. They stay until the next step,
    // as for `wake`; only the removed body's contacts go.
    for (what, removed) in [("the top box", 4), ("a middle box", 2)] {
        let (mut world, boxes) = stack_and_ball(true);
        if removed == 2 {
            // Without the ball the top box is the last dynamic body: the
            // removal moves it, with its stored contacts, into the
            // removed one's place.
            let ball = world.bodies().last().unwrap().id;
            world.remove_body(ball).unwrap();
        }
        assert!(boxes.iter().all(|&b| world.is_asleep(b) == Some(true)));
        let gone = boxes[removed];
        let pairs =
            |w: &World| -> Vec<(BodyId, BodyId)> { w.contacts().map(|c| (c.a, c.b)).collect() };
        let kept: Vec<_> = pairs(&world)
            .into_iter()
            .filter(|&(a, b)| a != gone && b != gone)
            .collect();
        assert_eq!(
            kept.len(),
            pairs(&world).len() - 2 + usize::from(removed == 4),
            "{what}"
        );
        world.remove_body(gone).unwrap();
        assert_eq!(pairs(&world), kept, "{what}: the other contacts stay");
        for (k, &b) in boxes.iter().enumerate().filter(|&(k, _)| k != removed) {
            assert_eq!(
                world.is_asleep(b),
                Some(false),
                "{what}: box {k} awake at once"
            );
            // The box that stood on the removed one stands on nothing.
            let stands = k != removed + 1;
            assert_eq!(world.is_standing(b, 0.7), stands, "{what}: box {k}");
        }
        steps_on_as_its_snapshot(&mut world, 90, what);
        // What stood on the removed box fell onto the one below it and
        // rests there: each box a metre above the next.
        let mut heights: Vec<f32> = boxes
            .iter()
            .filter(|&&b| b != gone)
            .map(|&b| world.body(b).unwrap().position.y)
            .collect();
        heights.sort_by(f32::total_cmp);
        for (k, y) in heights.iter().enumerate() {
            assert!(
                (y - (0.5 + k as f32)).abs() < 0.01,
                "{what}: box {k} at {y}"
            );
        }
    }
}
