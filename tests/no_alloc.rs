//! A world in steady state allocates nothing: after warming up, stepping a
//! rain scene (broad phase, narrow phase, solver, events, bodies falling
//! asleep and waking) makes no heap allocation at all. A counting global
//! allocator checks it.
//!
//! The world runs its stages on the calling thread here
//! (`set_parallel(false)`). With parallel stages on, Passo's own buffers
//! still stay put, but rayon's scheduler allocates now and then (its job
//! queues grow in blocks), so the strict count is made without it.

use passo_physics::glam::Vec2;
use passo_scene::Scene;
use std::path::PathBuf;
use std::sync::atomic::Ordering;

#[global_allocator]
static GLOBAL: Counting = Counting;

use passo_tests::{ALLOCATIONS, COUNTING, Counting};

#[test]
fn stepping_a_rain_scene_allocates_nothing_after_warm_up() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/rain.ron");
    let mut world = Scene::load(&path).unwrap().build().unwrap().world;
    world.set_parallel(false);
    // Warm up: the rain falls, piles and falls asleep; buffers grow to
    // their working size.
    for _ in 0..600 {
        world.step(1.0 / 60.0);
    }
    let ids: Vec<_> = world.bodies().map(|b| b.id).collect();
    let (mut most_solved, mut most_asleep) = (0, 0);
    COUNTING.store(true, Ordering::Relaxed);
    for tick in 0..300 {
        // Every half second a kick wakes an island somewhere in the pile:
        // islands wake, move, settle and fall asleep again while counting.
        if tick % 30 == 0 {
            let id = ids[(tick * 37) % ids.len()];
            world.apply_impulse(id, Vec2::new(0.0, 2.0));
        }
        world.step(1.0 / 60.0);
        most_solved = most_solved.max(world.solved_contacts());
        most_asleep = most_asleep.max(world.sleeping_len());
    }
    COUNTING.store(false, Ordering::Relaxed);
    assert!(world.contacts().count() > 2000, "the pile is in contact");
    assert!(
        most_asleep > 1000 && most_solved > 50,
        "bodies slept ({most_asleep}) and woke to be solved ({most_solved}) while counting"
    );
    assert_eq!(
        ALLOCATIONS.load(Ordering::Relaxed),
        0,
        "allocations while stepping"
    );
    small_awake_worlds_allocate_nothing();
}

/// Small awake worlds too: 33 and 428 candidate pairs a step, which the
/// narrow phase sorts by insertion and by radix. (The standard library's
/// stable sort, used below 512 pairs for a while, allocated a buffer every
/// step of the second.) In this test function, not a test of its own: the
/// count is global, and tests run side by side.
fn small_awake_worlds_allocate_nothing() {
    use passo_physics::{BodyDef, Shape, World};
    let mut worlds = Vec::new();
    for (rows, columns) in [(3, 4), (8, 15)] {
        let mut world = World::default();
        world
            .add_body(BodyDef::new_static(
                Vec2::new(0.0, -0.5),
                Shape::rect(40.0, 1.0),
            ))
            .unwrap();
        for k in 0..rows * columns {
            let (i, j) = (k % columns, k / columns);
            let def = BodyDef::new_dynamic(
                Vec2::new(i as f32 * 0.2 - 2.5, 0.1 + j as f32 * 0.2),
                Shape::circle(0.1),
            );
            world.add_body(def).unwrap();
        }
        let mut settings = *world.settings();
        settings.contacts.as_mut().unwrap().sleeping = false;
        world.set_settings(settings).unwrap();
        world.set_parallel(false);
        for _ in 0..120 {
            world.step(1.0 / 60.0);
        }
        worlds.push(world);
    }
    ALLOCATIONS.store(0, Ordering::Relaxed);
    COUNTING.store(true, Ordering::Relaxed);
    for world in &mut worlds {
        for _ in 0..120 {
            world.step(1.0 / 60.0);
        }
    }
    COUNTING.store(false, Ordering::Relaxed);
    assert!(worlds[0].contacts().count() >= 12 && worlds[1].contacts().count() >= 200);
    assert_eq!(
        ALLOCATIONS.load(Ordering::Relaxed),
        0,
        "allocations while stepping small worlds"
    );
}
