#![doc = include_str!("../README.md")]
//! Helpers shared by the cross-crate tests.

/// The user guide's chapters (`docs/guide/src/`): their Rust snippets are
/// compiled and run as doc tests, so they cannot drift from the code.
/// Run one chapter's with `cargo test -p passo-tests --doc guide::loop_`.
#[cfg(doctest)]
pub mod guide {
    #[doc = include_str!("../docs/guide/src/introduction.md")]
    pub mod introduction {}
    #[doc = include_str!("../docs/guide/src/loop.md")]
    pub mod loop_ {}
    #[doc = include_str!("../docs/guide/src/bodies-and-forces.md")]
    pub mod bodies_and_forces {}
    #[doc = include_str!("../docs/guide/src/integrators.md")]
    pub mod integrators {}
    #[doc = include_str!("../docs/guide/src/collisions.md")]
    pub mod collisions {}
    #[doc = include_str!("../docs/guide/src/platforms-and-tiles.md")]
    pub mod platforms_and_tiles {}
    #[doc = include_str!("../docs/guide/src/tiled.md")]
    pub mod tiled {}
    #[doc = include_str!("../docs/guide/src/character-mover.md")]
    pub mod character_mover {}
    #[doc = include_str!("../docs/guide/src/joints-and-zones.md")]
    pub mod joints_and_zones {}
    #[doc = include_str!("../docs/guide/src/queries-and-events.md")]
    pub mod queries_and_events {}
    #[doc = include_str!("../docs/guide/src/determinism.md")]
    pub mod determinism {}
    #[doc = include_str!("../docs/guide/src/scenes-and-cli.md")]
    pub mod scenes_and_cli {}
    #[doc = include_str!("../docs/guide/src/scene-format.md")]
    pub mod scene_format {}
    #[doc = include_str!("../docs/guide/src/rendering-and-demo.md")]
    pub mod rendering_and_demo {}
    #[doc = include_str!("../docs/guide/src/performance.md")]
    pub mod performance {}
    #[doc = include_str!("../docs/guide/src/bad-input.md")]
    pub mod bad_input {}
    #[doc = include_str!("../crates/passo-physics/README.md")]
    pub mod physics_readme {}
    #[doc = include_str!("../crates/passo-loop/README.md")]
    pub mod loop_readme {}
    #[doc = include_str!("../crates/passo-render/README.md")]
    pub mod render_readme {}
    #[doc = include_str!("../crates/passo-scene/README.md")]
    pub mod scene_readme {}
}

use std::time::Duration;

// The physics-only helpers live beside the physics' behaviour tests.
#[path = "../crates/passo-physics/tests/behaviour/support.rs"]
mod support;
pub use support::*;

/// The frame time of a display refreshing at `hz`, to the nanosecond.
pub fn frame_time(hz: u64) -> Duration {
    Duration::from_nanos(1_000_000_000 / hz)
}

use passo_physics::World;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// A global allocator that counts allocations while [`COUNTING`] is on:
/// a test binary installs it with
/// `#[global_allocator] static GLOBAL: Counting = Counting;`.
pub struct Counting;

pub static COUNTING: AtomicBool = AtomicBool::new(false);
pub static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// SAFETY: every method forwards to `System` with the caller's arguments
// unchanged, so `System`'s guarantees hold; counting touches only atomics.
#[allow(unsafe_code)]
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

/// Steps a built scene `ticks` ticks at 60 Hz, its platforms driven, and
/// calls `after(tick, world)` after each step.
pub fn run_scene(
    built: &mut passo_scene::BuiltScene,
    ticks: u64,
    mut after: impl FnMut(u64, &World),
) {
    for tick in 1..=ticks {
        built.step(1.0 / 60.0);
        debug_assert_eq!(built.tick, tick);
        after(tick, &built.world);
    }
}
