//! The demo's rewind ring allocates nothing once full: each tick's state
//! goes into the buffers of the oldest one (a counting global allocator
//! checks it).

use passo::demo::{Entry, Input, load};
use passo_tests::{ALLOCATIONS, COUNTING, Counting};
use std::sync::atomic::Ordering;
use std::time::Duration;

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn a_full_rewind_ring_keeps_each_new_tick_without_allocating() {
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
    let bytes = sim.scene.rewind_bytes();
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
