//! A force model of your own: buoyancy and water drag below a water line.
//!
//! A wooden crate (density 600 kg/m³) dropped into water sinks, floats back
//! up and settles where buoyancy equals its weight: 60 % under water.
//!
//! Run: `cargo run -p passo-examples --example custom_force`

use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, ForceModel, World};
use std::sync::Arc;

/// Archimedes for a 1 m² box of height `height`, plus water drag.
struct Water {
    /// Height of the water surface, metres.
    surface: f32,
    /// Height of the floating box, metres (its area is 1 m² in 2D).
    height: f32,
}

impl ForceModel for Water {
    fn force(&self, position: Vec2, velocity: Vec2, _mass: f32) -> Vec2 {
        const RHO_WATER: f32 = 1000.0;
        const G: f32 = 9.81;
        let bottom = position.y - 0.5 * self.height;
        let submerged = (self.surface - bottom).clamp(0.0, self.height);
        let buoyancy = Vec2::new(0.0, RHO_WATER * G * submerged);
        // Linear water drag while in the water, proportional to depth.
        buoyancy - velocity * (4000.0 * submerged)
    }
}

fn main() {
    let mut world = World::default();
    world.add_force_model(Arc::new(Water {
        surface: 0.0,
        height: 1.0,
    }));
    let crate_id = world
        .add_body(BodyDef {
            position: Vec2::new(0.0, 2.0),
            mass: 600.0, // 1 m² of wood at 600 kg/m²
            ..Default::default()
        })
        .expect("valid body");
    for second in 0..=10 {
        let y = world.body(crate_id).expect("body exists").position.y;
        println!("t = {second:2} s: crate centre at y = {y:+.3} m");
        for _ in 0..60 {
            world.step(1.0 / 60.0);
        }
    }
    let y = world.body(crate_id).expect("body exists").position.y;
    println!("floats with {:.0} % under water", (0.5 - y) * 100.0);
}
