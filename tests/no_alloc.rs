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
}
