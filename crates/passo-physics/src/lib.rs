//! # passo-physics
//!
//! The core of Passo: rigid bodies (that do not rotate) with mass, position,
//! velocity and an accumulated force; force models (gravity, quadratic and
//! linear drag, friction, force fields, springs, central gravity, your own);
//! integrators (semi-implicit Euler by default, explicit Euler, velocity
//! Verlet, RK4) and speed limits. Depends on `glam` and `std` only, so it
//! runs on a server with no GPU; `serde` support is behind the `serde`
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
#![warn(missing_docs)]
#![forbid(unsafe_code)]

// Modules in the order data flows through them; each imports only from
// those above it (checked by `tests/module_graph.rs`).
mod aabb;
mod bodies;
mod body;
mod body_edit;
mod broad_phase;
mod collider;
pub mod constants;
mod constraint;
mod contact;
mod contact_state;
mod contact_world;
mod diagnostics;
mod error;
mod events;
mod filter;
mod forces;
mod integrator;
mod island;
mod kernel;
mod manifold;
mod narrow_phase;
mod parallel;
mod proxies;
mod query;
mod settings;
mod shape;
mod sleeping;
mod snapshot;
mod solver;
mod static_tree;
mod step;
mod world;

pub use aabb::Aabb;
pub use body::{Body, BodyDef, BodyId, BodyKind};
pub use contact::{Contact, ContactEvents, ContactPair, ContactSettings, SensorPair};
pub use error::PhysicsError;
pub use filter::CollisionFilter;
pub use forces::{
    CentralGravity, ForceForm, ForceModel, ForceModels, LinearDrag, QuadraticDrag, Spring,
    SurfaceFriction,
};
pub use glam;
pub use integrator::Integrator;
#[doc(hidden)]
pub use manifold::{Manifold, collide};
pub use query::RayHit;
pub use settings::WorldSettings;
pub use shape::Shape;
pub use snapshot::WorldSnapshot;
pub use step::{ContactStage, Stage};
pub use world::{StepStats, World};
