//! A body falling at terminal speed through air kept its decaying
//! horizontal speed as a subnormal float (5e-44 m/s) forever, and arithmetic
//! on subnormals made every step about eight times slower. Velocity
//! components below the smallest normal float are now flushed to zero, on
//! the fast path and the general path alike.

use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, ForceModel, ForceModels, QuadraticDrag, World, WorldSettings};
use std::sync::Arc;

struct Nothing;
impl ForceModel for Nothing {
    fn force(&self, _: Vec2, _: Vec2, _: f32) -> Vec2 {
        Vec2::ZERO
    }
}

#[test]
fn decaying_velocity_components_never_become_subnormal() {
    for general in [false, true] {
        let mut world = World::new(WorldSettings {
            forces: ForceModels {
                quadratic_drag: Some(QuadraticDrag::default()),
                ..Default::default()
            },
            ..Default::default()
        })
        .unwrap();
        if general {
            world.add_force_model(Arc::new(Nothing));
        }
        let id = world
            .add_body(BodyDef {
                velocity: Vec2::new(3.0, 1.0),
                ..Default::default()
            })
            .unwrap();
        let mut saw_tiny = false;
        for _ in 0..8000 {
            world.step(1.0 / 60.0);
            let v = world.body(id).unwrap().velocity;
            assert!(!v.x.is_subnormal() && !v.y.is_subnormal(), "{v:?}");
            saw_tiny |= v.x != 0.0 && v.x.abs() < 1e-30;
        }
        assert!(
            saw_tiny,
            "the horizontal speed did decay through tiny values"
        );
        assert_eq!(world.body(id).unwrap().velocity.x, 0.0);
    }
}
