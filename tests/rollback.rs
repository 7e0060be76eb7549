//! Rollback: saving every tick into reused snapshots and restoring from
//! them gives the bits a straight run gives.

use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, Shape, World, WorldSnapshot};
use passo_scene::Scene;
use std::path::PathBuf;

const DT: f32 = 1.0 / 60.0;

/// The rain scene with a kinematic platform and a pushed ball: contacts,
/// sleeping, kinematic bodies.
fn busy() -> (World, passo_physics::BodyId) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/rain.ron");
    let mut world = Scene::load(&path).unwrap().build().unwrap().world;
    world
        .add_body(BodyDef::new_kinematic(
            Vec2::new(-3.0, 6.0),
            Shape::rect(3.0, 0.3),
            Vec2::new(1.0, 0.0),
        ))
        .unwrap();
    let ball = world
        .add_body(BodyDef::new_dynamic(
            Vec2::new(0.0, 12.0),
            Shape::circle(0.3),
        ))
        .unwrap();
    (world, ball)
}

/// The game input of a tick: a push now and then.
fn input(world: &mut World, ball: passo_physics::BodyId, tick: u32) {
    if tick.is_multiple_of(17) {
        world.apply_impulse(ball, Vec2::new((tick % 5) as f32 - 2.0, 1.0));
    }
}

#[test]
fn restore_from_steps_on_as_from_snapshot_does() {
    let (mut world, ball) = busy();
    for tick in 0..45 {
        input(&mut world, ball, tick);
        world.step(DT);
    }
    let mut saved = WorldSnapshot::default();
    world.snapshot_into(&mut saved);
    let mut fresh = World::from_snapshot(saved.clone()).unwrap();
    // Run on, then roll back into the same world.
    for _ in 0..30 {
        world.step(DT);
    }
    world.restore_from(&saved).unwrap();
    for tick in 45..120 {
        input(&mut world, ball, tick);
        input(&mut fresh, ball, tick);
        world.step(DT);
        fresh.step(DT);
        assert_eq!(world.state_hash(), fresh.state_hash(), "tick {tick}");
    }
}

#[test]
fn rolling_back_seven_ticks_every_tick_gives_the_straight_run() {
    let (mut straight, ball) = busy();
    let (mut rolled, _) = busy();
    // A ring of 8 snapshots, saved every tick as GGRS does.
    let mut ring: Vec<WorldSnapshot> = (0..8).map(|_| WorldSnapshot::default()).collect();
    for tick in 0..200u32 {
        input(&mut straight, ball, tick);
        straight.step(DT);

        rolled.snapshot_into(&mut ring[tick as usize % 8]);
        input(&mut rolled, ball, tick);
        rolled.step(DT);
        if tick >= 7 {
            // A late input arrived: go back 7 ticks and simulate again.
            let from = tick - 7;
            rolled.restore_from(&ring[from as usize % 8]).unwrap();
            for t in from..=tick {
                if t > from {
                    rolled.snapshot_into(&mut ring[t as usize % 8]);
                }
                input(&mut rolled, ball, t);
                rolled.step(DT);
            }
        }
        assert_eq!(rolled.state_hash(), straight.state_hash(), "tick {tick}");
    }
}

#[test]
fn a_snapshot_of_another_world_is_never_taken_for_this_ones_statics() {
    let (mut a, _) = busy();
    let mut b = a.clone();
    // The clone moves a static body: the same count of static edits as a
    // change in `a` would make, but other statics.
    let wall = b
        .bodies()
        .find(|x| x.kind == passo_physics::BodyKind::Static)
        .unwrap()
        .id;
    b.set_position(wall, Vec2::new(0.0, -3.0));
    a.set_position(wall, Vec2::new(0.0, -2.0));
    let mut saved = WorldSnapshot::default();
    b.snapshot_into(&mut saved);
    a.restore_from(&saved).unwrap();
    assert_eq!(a.body(wall).unwrap().position, Vec2::new(0.0, -3.0));
}

#[test]
fn a_snapshot_taken_after_a_removal_is_valid_and_queries_the_same() {
    // Two boxes on three static slabs; a slab and a box are removed
    // between a step and the save, so stored contacts name bodies that are
    // gone or moved.
    let mut world = World::default();
    let slabs: Vec<_> = (0..3)
        .map(|i| {
            let x = i as f32 * 2.0 - 2.0;
            world
                .add_body(BodyDef::new_static(
                    Vec2::new(x, -0.5),
                    Shape::rect(2.0, 1.0),
                ))
                .unwrap()
        })
        .collect();
    let boxes: Vec<_> = [-2.0f32, 0.0, 2.0]
        .into_iter()
        .map(|x| {
            world
                .add_body(BodyDef::new_dynamic(
                    Vec2::new(x, 0.5),
                    Shape::rect(1.0, 1.0),
                ))
                .unwrap()
        })
        .collect();
    for _ in 0..10 {
        world.step(1.0 / 60.0);
    }
    world.remove_body(slabs[0]).unwrap();
    world.remove_body(boxes[0]).unwrap();
    // Through a file: checked as any snapshot from outside.
    let copy = World::from_snapshot(world.snapshot()).expect("a valid snapshot");
    for &b in &boxes[1..] {
        let ours: Vec<_> = world.contacts_of(b).collect();
        assert_eq!(copy.contacts_of(b).collect::<Vec<_>>(), ours);
        assert!(ours.iter().any(|c| c.touching), "{b:?} rests on a slab");
    }
    assert_eq!(copy.contacts_of(boxes[0]).count(), 0);
}

#[test]
fn a_static_bodys_material_changed_after_a_save_is_rolled_back() {
    // Changing a static body's friction, restitution, filter, sensor or
    // one-way side did not count as an edit of the statics: restore_from
    // kept the changed body, and snapshot_into a reused buffer kept the old
    // one. A slider on a floor that turns icy after the save ended 2.6 m
    // from where the saved state takes it.
    type Edit = fn(&mut World, passo_physics::BodyId);
    let edits: [(&str, Edit); 6] = [
        ("friction", |w, id| w.try_set_friction(id, 0.0).unwrap()),
        ("drag area", |w, id| w.set_drag_area(id, 3.0).unwrap()),
        ("restitution", |w, id| w.set_restitution(id, 0.9).unwrap()),
        ("sensor", |w, id| w.set_sensor(id, true).unwrap()),
        ("one-way", |w, id| {
            w.set_one_way(id, Some(Vec2::NEG_Y)).unwrap()
        }),
        ("filter", |w, id| {
            let filter = passo_physics::CollisionFilter { layers: 2, mask: 2 };
            w.set_filter(id, filter).unwrap()
        }),
    ];
    for (what, edit) in edits {
        let mut world = World::default();
        let floor = world
            .add_body(BodyDef::new_static(
                Vec2::new(0.0, -0.5),
                Shape::rect(40.0, 1.0),
            ))
            .unwrap();
        let slider = world
            .add_body(
                BodyDef::new_dynamic(Vec2::new(0.0, 0.25), Shape::rect(0.5, 0.5))
                    .with_velocity(Vec2::new(6.0, 0.0)),
            )
            .unwrap();
        let mut saved = WorldSnapshot::default();
        world.snapshot_into(&mut saved);
        let straight = {
            let mut w = World::from_snapshot(saved.clone()).unwrap();
            (0..60).for_each(|_| w.step(DT));
            w.state_hash()
        };
        edit(&mut world, floor);
        (0..30).for_each(|_| world.step(DT));
        // The buffer, saved into again, holds the changed floor.
        let mut again = saved.clone();
        world.snapshot_into(&mut again);
        assert_eq!(again, world.snapshot(), "{what}: the reused buffer");
        // Rolled back, the world steps as the saved state does.
        world.restore_from(&saved).unwrap();
        (0..60).for_each(|_| world.step(DT));
        assert_eq!(world.state_hash(), straight, "{what}: rolled back");
        let _ = slider;
    }
}
