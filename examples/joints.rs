//! Joints, a conveyor and water from code, with no window: a rope bridge
//! of twelve planks that a 60 kg crate is dropped on, a 1 kg lamp on a
//! rope that snaps above 20 N as it swings down (at the bottom of its
//! swing the rope would pull 3 m g, 29 N), and a belt that tips a parcel
//! into a pool where it floats. It prints what happened.
//!
//! ```text
//! cargo run --release -p passo-examples --example joints
//! ```

use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, ForceZone, JointDef, Liquid, Shape, World};

fn main() -> Result<(), passo_physics::PhysicsError> {
    let mut world = World::default();

    // Two banks, and a bridge of planks between them on short rods from
    // each plank's corner to the next one's.
    let bank = |x: f32| BodyDef::new_static(Vec2::new(x, -1.0), Shape::rect(4.0, 2.0));
    let left = world.add_body(bank(-8.0))?;
    let right = world.add_body(bank(8.0))?;
    let mut last = (left, Vec2::new(2.0, 1.0));
    let mut planks = Vec::new();
    for i in 0..12 {
        let at = Vec2::new(-5.5 + i as f32, -0.1);
        let plank = world.add_body(BodyDef {
            mass: 4.0,
            ..BodyDef::new_dynamic(at, Shape::rect(0.9, 0.2))
        })?;
        // A little slack: 0.12 m rods across gaps of 0.1 m.
        let rod =
            JointDef::distance(last.0, Some(plank), 0.12).anchors(last.1, Vec2::new(-0.45, 0.1));
        world.add_joint(rod)?;
        last = (plank, Vec2::new(0.45, 0.1));
        planks.push(plank);
    }
    world.add_joint(
        JointDef::distance(last.0, Some(right), 0.12).anchors(last.1, Vec2::new(-2.0, 1.0)),
    )?;

    // A crate of 60 kg dropped on the middle of the bridge.
    let crate_ = world.add_body(BodyDef {
        mass: 60.0,
        ..BodyDef::new_dynamic(Vec2::new(0.0, 2.0), Shape::rect(0.8, 0.8))
    })?;

    // A lamp of 1 kg held out level on a 2 m rope from a hook, which snaps
    // above 20 N.
    let hook = world.add_body(BodyDef::new_static(
        Vec2::new(12.0, 6.0),
        Shape::circle(0.1),
    ))?;
    let lamp = world.add_body(BodyDef::new_dynamic(
        Vec2::new(14.0, 6.0),
        Shape::circle(0.2),
    ))?;
    let rope = world.add_joint(JointDef::rope(hook, Some(lamp), 2.0).break_force(20.0))?;

    // A pool of water 6 m wide, its surface at y = -3, and a belt that
    // carries parcels over its edge.
    let water = BodyDef::new_static(Vec2::new(0.0, -4.5), Shape::rect(6.0, 3.0)).as_sensor();
    let water = world.add_body(water)?;
    let liquid = Liquid {
        density: 4.0,
        drag: 3.0,
    };
    world.add_force_zone(
        water,
        ForceZone {
            liquid: Some(liquid),
            ..Default::default()
        },
    )?;
    world.add_body(BodyDef::new_static(
        Vec2::new(0.0, -6.5),
        Shape::rect(8.0, 1.0),
    ))?;
    world.add_body(BodyDef {
        conveyor: Some(Vec2::new(1.5, 0.0)),
        ..BodyDef::new_static(Vec2::new(-4.5, -2.75), Shape::rect(3.0, 0.5))
    })?;
    let parcel = world.add_body(BodyDef {
        mass: 0.5,
        ..BodyDef::new_dynamic(Vec2::new(-5.5, -2.25), Shape::rect(0.5, 0.5))
    })?;

    let dt = 1.0 / 60.0;
    let mut broke_at = None;
    for tick in 0..600 {
        world.step(dt);
        if world.broken_joints().iter().any(|b| b.id == rope) {
            broke_at = Some(tick as f32 * dt);
        }
    }
    let lowest = planks
        .iter()
        .map(|&p| world.body(p).map_or(0.0, |b| b.position.y))
        .fold(f32::INFINITY, f32::min);
    let resting = world.body(crate_).map_or(Vec2::ZERO, |b| b.position);
    println!("the bridge sags to {lowest:.3} m under the crate, which rests at {resting:.2}");
    match broke_at {
        Some(t) => println!(
            "the lamp's rope broke at {t:.2} s, {} joints left",
            world.joint_len()
        ),
        None => println!("the lamp's rope held"),
    }
    let p = world.body(parcel).map_or(Vec2::ZERO, |b| b.position);
    // 0.5 kg over 0.25 m² in 4 kg/m²: half its height under the surface.
    println!(
        "the parcel floats at y = {:.3} m (its centre at the surface, -3, floats it half under)",
        p.y
    );
    Ok(())
}
