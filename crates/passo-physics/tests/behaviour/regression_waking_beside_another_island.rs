//! Waking a sleeping island panicked (an index out of bounds in the narrow
//! phase) when one of its stored contacts was a speculative one with a body
//! of another sleeping island: that body had no proxy, and the contact was
//! looked up with none.

use crate::support::add_ground;
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, Shape, World};

#[test]
fn a_ball_landing_on_a_sleeping_box_beside_another_wakes_it_without_a_panic() {
    let mut world = World::default();
    add_ground(&mut world, 40.0);
    // A row of boxes 1 cm apart: each its own island (they never touch),
    // joined to its neighbours by speculative contacts.
    let boxes: Vec<_> = (0..40)
        .map(|i| {
            let def = BodyDef {
                position: Vec2::new(i as f32 * 1.01 - 20.0, 0.5),
                shape: Some(Shape::rect(1.0, 1.0)),
                ..Default::default()
            };
            world.add_body(def).unwrap()
        })
        .collect();
    for _ in 0..120 {
        world.step(1.0 / 60.0);
    }
    assert!(
        boxes.iter().all(|&b| world.is_asleep(b) == Some(true)),
        "the row fell asleep"
    );
    // More quiet steps: the sleeping boxes move into the sleep tree.
    for _ in 0..10 {
        world.step(1.0 / 60.0);
    }
    let ball = world
        .add_body(BodyDef {
            position: Vec2::new(boxes.len() as f32 / 2.0 * 1.01 - 20.0, 3.0),
            shape: Some(Shape::circle(0.25)),
            ..Default::default()
        })
        .unwrap();
    for _ in 0..120 {
        world.step(1.0 / 60.0);
    }
    let hit = boxes[boxes.len() / 2];
    assert!(
        world.body(ball).unwrap().position.y > 1.0,
        "the ball rests on the box"
    );
    assert!(world.contacts_of(hit).any(|c| c.b == ball && c.touching));
    for b in world.bodies() {
        assert!(b.position.is_finite() && b.velocity.is_finite());
    }
}
