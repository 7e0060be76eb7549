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
use std::alloc::{GlobalAlloc, Layout, System};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// Counts allocations while `COUNTING` is on.
struct Counting;

static COUNTING: AtomicBool = AtomicBool::new(false);
static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// SAFETY: every method forwards to `System` with the caller's arguments
// unchanged, so `System`'s guarantees hold; counting touches only atomics.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if COUNTING.load(Ordering::Relaxed) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        // SAFETY: forwarded as is (see the impl).
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: forwarded as is (see the impl).
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if COUNTING.load(Ordering::Relaxed) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        // SAFETY: forwarded as is (see the impl).
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

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
