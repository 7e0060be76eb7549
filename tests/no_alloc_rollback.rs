//! Rollback allocates nothing once warm: saving every tick into a ring of
//! reused snapshots, restoring seven ticks back and simulating again makes
//! no heap allocation (a counting global allocator checks it).

use passo_physics::WorldSnapshot;
use passo_physics::glam::Vec2;
use passo_scene::Scene;
use passo_tests::{ALLOCATIONS, COUNTING, Counting};
use std::path::PathBuf;
use std::sync::atomic::Ordering;

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn saving_and_restoring_every_tick_allocates_nothing_after_warm_up() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/rain.ron");
    let mut world = Scene::load(&path).unwrap().build().unwrap().world;
    world.set_parallel(false);
    let ids: Vec<_> = world.bodies().map(|b| b.id).collect();
    let mut ring: Vec<WorldSnapshot> = (0..8).map(|_| WorldSnapshot::default()).collect();
    let mut run = |world: &mut passo_physics::World, ticks: std::ops::Range<usize>| {
        for tick in ticks {
            world.snapshot_into(&mut ring[tick % 8]);
            if tick % 30 == 0 {
                world.apply_impulse(ids[(tick * 37) % ids.len()], Vec2::new(0.0, 2.0));
            }
            world.step(1.0 / 60.0);
            if tick >= 8 {
                // Roll back seven ticks and simulate them again.
                world.restore_from(&ring[(tick - 7) % 8]).unwrap();
                for _ in 0..8 {
                    world.step(1.0 / 60.0);
                }
            }
        }
    };
    // Warm up as the stepping test does (the rain falls, piles and falls
    // asleep), then with rollbacks: buffers and snapshots grow to their
    // working size.
    for _ in 0..600 {
        world.step(1.0 / 60.0);
    }
    run(&mut world, 0..300);
    COUNTING.store(true, Ordering::Relaxed);
    run(&mut world, 300..420);
    COUNTING.store(false, Ordering::Relaxed);
    assert_eq!(
        ALLOCATIONS.load(Ordering::Relaxed),
        0,
        "allocations while rolling back"
    );
}
