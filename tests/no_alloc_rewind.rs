//! The demo's rewind ring allocates nothing once full, at its tick limit or
//! its byte budget: each tick's state goes into the buffers of the oldest
//! one (a counting global allocator checks it).

use passo::demo::{Entry, Input, Sim, load};
use passo_tests::{ALLOCATIONS, COUNTING, Counting};
use std::sync::Mutex;
use std::sync::atomic::Ordering;
use std::time::Duration;

#[global_allocator]
static GLOBAL: Counting = Counting;

/// The allocator counts every thread: one test at a time.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

/// Saves 100 more ticks under the counting allocator: no allocation, as
/// many ticks kept, no buffer grown.
fn saving_allocates_nothing(sim: &mut Sim) {
    let (kept, bytes) = (sim.scene.rewindable(), sim.scene.rewind_bytes());
    COUNTING.store(true, Ordering::SeqCst);
    ALLOCATIONS.store(0, Ordering::SeqCst);
    for _ in 0..100 {
        sim.scene.save_for_rewind();
    }
    COUNTING.store(false, Ordering::SeqCst);
    assert_eq!(ALLOCATIONS.load(Ordering::SeqCst), 0);
    assert_eq!(sim.scene.rewindable(), kept, "the oldest made room");
    assert_eq!(sim.scene.rewind_bytes(), bytes, "no buffer grew");
}

#[test]
fn a_full_rewind_ring_keeps_each_new_tick_without_allocating() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let mut sim = load(&Entry::File("playground".into())).unwrap();
    let frame = Duration::from_nanos(16_666_667);
    let walk = Input {
        right: true,
        ..Input::default()
    };
    // Twice round the ring (600 ticks for a scene this small): every
    // buffer has held a state.
    for _ in 0..1_300 {
        sim.scene.set_input(walk);
        sim.frame(frame);
    }
    let kept = sim.scene.rewindable();
    assert_eq!(kept, 600);
    saving_allocates_nothing(&mut sim);
}

#[test]
fn a_ring_held_to_its_byte_budget_keeps_each_new_tick_without_allocating() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    // The rain's 2 000 circles, settled: about 90 ticks fit the budget.
    // Once every buffer of the ring has held a state this size, a new
    // tick goes into the oldest one's buffers.
    let mut sim = load(&Entry::File("rain".into())).unwrap();
    let frame = Duration::from_nanos(16_666_667);
    for _ in 0..600 {
        sim.frame(frame);
    }
    let kept = sim.scene.rewindable();
    assert!(kept < 600, "the budget holds the ring: {kept} ticks");
    for _ in 0..2 * kept {
        sim.scene.save_for_rewind();
    }
    saving_allocates_nothing(&mut sim);
}
