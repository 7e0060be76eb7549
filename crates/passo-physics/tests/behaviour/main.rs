//! The physics' behaviour, tested through the public API of
//! `passo-physics` alone: closed forms, hard cases, contacts, platforms,
//! queries, the mover, sleeping, and one module per regression (named after
//! its symptom). One test binary, one module per subject.
//!
//! Run them with `cargo test -p passo-physics --test behaviour`. The
//! workspace's `tests/` holds the tests that need more than the physics
//! (scenes, the loop, rendering, netplay).

// Closed forms call the platform's transcendental functions: the tests may
// (see `clippy.toml`).
#![allow(clippy::disallowed_methods)]

mod support;

mod analytic;
mod api_fuzz;
mod collision_api;
mod contact_reuse;
mod hard_cases;
mod hooks;
mod joints;
mod kinematic;
mod mover;
mod one_way;
mod queries;
mod regression_contacts_of_after_a_wake;
mod regression_fast_bodies;
mod regression_parallel_sensors;
mod regression_sleeping_somewhere_else;
mod regression_spawned_on_one_spot;
mod regression_subnormal_velocity;
mod regression_waking_beside_another_island;
mod regression_woken_stack_keeps_its_contacts;
mod seamless_ground;
mod sleeping;
mod slopes;
mod speculative;
mod sweeps;
mod tile_maps;
mod zones;
