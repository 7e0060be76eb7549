//! # passo-physics
//!
//! The core of Passo: rigid bodies (that do not rotate) with mass, position,
//! velocity and an accumulated force; force models (gravity, quadratic and
//! linear drag, friction, force fields, springs, central gravity, your own);
//! integrators (semi-implicit Euler by default, explicit Euler, velocity
//! Verlet, RK4) and speed limits. Depends on `glam`, `libm` (the same
//! maths on every platform) and `std` only, so it runs on a server with no
//! GPU; `serde` support is behind the `serde`
//! feature.
//!
//! Drive [`World::step`] from a fixed-timestep loop (the `passo-loop` crate)
//! so the simulation does not depend on the frame rate.
//!
//! ```
//! use passo_physics::{BodyDef, ForceModels, QuadraticDrag, World, WorldSettings, glam::Vec2};
//!
//! let settings = WorldSettings {
//!     forces: ForceModels { quadratic_drag: Some(QuadraticDrag::default()), ..Default::default() },
//!     ..Default::default()
//! };
//! let mut world = World::new(settings).unwrap();
//! let id = world.add_body(BodyDef { mass: 2.0, drag_area: 0.5, ..Default::default() }).unwrap();
//! for _ in 0..600 {
//!     world.step(1.0 / 60.0);
//! }
//! // Terminal speed v_t = sqrt(2 m g / (rho Cd A)) = 8.0 m/s. The first-order
//! // step settles where s (s + g dt) = v_t^2: g dt / 2 = 0.08 m/s below it.
//! let vt = (2.0f32 * 2.0 * 9.81 / (1.225 * 0.5)).sqrt();
//! let s = -world.body(id).unwrap().velocity.y;
//! assert!((s * (s + 9.81 / 60.0) - vt * vt).abs() < 1e-3);
//! ```
#![warn(missing_docs, unreachable_pub)]
#![forbid(unsafe_code)]
// Tests may call the platform's transcendental functions for their closed
// forms; the physics may not (see `clippy.toml`).
#![cfg_attr(test, allow(clippy::disallowed_methods))]

// The modules are folders that are layers, in the order data flows
// through them: a folder imports only the root's modules and the folders
// declared above it, and inside a folder each file imports only the files
// declared above it (checked by `tests/module_graph.rs`).

// The root: ids, tuning constants, errors, split vectors, the thread pool.
mod id;

pub mod constants;

mod error;

mod columns;
mod parallel;
mod switches;

mod geometry;
mod body;
mod forces;
mod contact;
mod collision;
mod solver;
mod joint;
mod contact_world;
mod world;
mod step;
mod query;

pub use body::def::{Body, BodyDef, BodyKind};
pub use body::filter::CollisionFilter;
pub use body::material::FrictionMix;
pub use body::tile_map::{
    ASCII_LEGEND, MAX_TILE_CELLS, Slope, TileChain, TileKind, TileMap, TileRect,
};
pub use contact::hooks::{ContactHooks, PairInfo, PreSolve};
pub use contact::{Contact, ContactEvents, ContactPair, ContactSettings, SensorPair};
pub use contact_world::StepCounters;
pub use error::PhysicsError;
pub use forces::integrator::Integrator;
pub use forces::models::{
    CentralGravity, ForceForm, ForceModel, ForceModels, LinearDrag, QuadraticDrag, Spring,
    SurfaceFriction,
};
pub use forces::zones::{ForceZone, Liquid, Wind};
pub use geometry::aabb::Aabb;
#[doc(hidden)]
pub use geometry::manifold::{Manifold, collide};
pub use geometry::shape::{ConvexPolygon, MAX_POLYGON_VERTICES, Shape};
pub use glam;
pub use id::{BodyId, JointId};
pub use joint::{BrokenJoint, JointDef, JointKind, JointMotor, JointSpring};
pub use query::diagnostics::StateHasher;
pub use query::mover::{CharacterMover, MoveOutcome};
pub use query::{QueryFilter, RayHit, ShapeHit};
pub use step::Stage;
pub use step::contacts::ContactStage;
#[doc(hidden)]
pub use switches::TestSwitches;
pub use world::chains::{ChainDef, MAX_CHAIN_POINTS};
pub use world::joints::Joint;
pub use world::settings::WorldSettings;
pub use world::snapshot::WorldSnapshot;
pub use world::{StepStats, World};

/// How many contacts the wide solver solves side by side in this build:
/// eight where the compiler may use AVX (`-C target-cpu=native` on a CPU
/// that has it), four elsewhere (SSE2, NEON, wasm's `simd128`, or plain
/// scalar code). The width changes the speed, never the bits.
pub const SOLVER_LANES: usize = solver::lanes::LANES;

/// Helpers shared by the unit tests.
#[cfg(test)]
mod testing {
    use crate::{BodyDef, BodyId, Shape, World};
    use glam::Vec2;

    /// Numbers in `[0, 1)`, the same for the same seed (xorshift; a seed
    /// of zero gives zeros).
    pub(crate) fn uniform(mut seed: u64) -> impl FnMut() -> f32 {
        move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 40) as f32 / (1u64 << 24) as f32
        }
    }

    /// Unit boxes centred at `centres` (in that order) on a ground `width`
    /// wide, sleeping off, and the boxes' ids.
    fn boxes_on_ground(width: f32, centres: impl Iterator<Item = Vec2>) -> (World, Vec<BodyId>) {
        let mut world = World::default();
        let ground = BodyDef::new_static(Vec2::new(0.0, -0.5), Shape::rect(width, 1.0));
        world.add_body(ground).unwrap();
        let boxes = centres
            .map(|position| {
                let def = BodyDef {
                    position,
                    shape: Some(Shape::rect(1.0, 1.0)),
                    ..Default::default()
                };
                world.add_body(def).unwrap()
            })
            .collect();
        let mut settings = *world.settings();
        settings.contacts.as_mut().unwrap().sleeping = false;
        world.set_settings(settings).unwrap();
        (world, boxes)
    }

    /// Rows of boxes on the ground, `count` boxes centred in row `row`.
    fn rows(rows: &[(usize, usize)]) -> impl Iterator<Item = Vec2> + '_ {
        rows.iter().flat_map(|&(row, count)| {
            (0..count)
                .rev()
                .map(move |i| Vec2::new(i as f32 - (count - 1) as f32 * 0.5, 0.5 + row as f32))
        })
    }

    /// Two rows of boxes on the ground, sleeping off, and the boxes' ids.
    /// The upper row lies across the joints of the lower; each row is
    /// added right to left, the upper first, so that storage order is not
    /// key order.
    pub(crate) fn pile() -> (World, Vec<BodyId>) {
        boxes_on_ground(20.0, rows(&[(1, 3), (0, 4)]))
    }

    /// A pyramid of boxes, `base` wide, sleeping off, and the boxes' ids.
    pub(crate) fn pyramid(base: usize) -> (World, Vec<BodyId>) {
        let rows: Vec<_> = (0..base).map(|row| (row, base - row)).collect();
        boxes_on_ground(2.0 * base as f32 + 10.0, self::rows(&rows))
    }

    /// Steps `a` and `b` side by side, `ticks` ticks at 60 Hz: `poke`
    /// changes both before tick `at`, and after each tick `check` compares
    /// them and bodies `ids` must have the same position and velocity in
    /// both, bit for bit.
    pub(crate) fn step_side_by_side(
        (a, b): (&mut World, &mut World),
        ids: &[BodyId],
        (ticks, at): (usize, usize),
        poke: impl Fn(&mut World),
        mut check: impl FnMut(usize, &mut World, &mut World),
    ) {
        for tick in 0..ticks {
            if tick == at {
                poke(a);
                poke(b);
            }
            a.step(1.0 / 60.0);
            b.step(1.0 / 60.0);
            check(tick, a, b);
            for &id in ids {
                let bits = |w: &World| {
                    let body = w.body(id).expect("the body");
                    [body.position, body.velocity].map(|v| v.to_array().map(f32::to_bits))
                };
                assert_eq!(bits(a), bits(b), "tick {tick}, {id:?}: the same bits");
            }
        }
    }
}
