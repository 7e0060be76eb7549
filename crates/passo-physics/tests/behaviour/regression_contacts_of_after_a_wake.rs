//! `contacts_of` could index past the contact lists (a panic) or return
//! other bodies' contacts when called after a wake in the same tick: its
//! per-body index was kept while waking dropped stored contacts. It also
//! returned a removed body's contacts for the body that reused its slot.

use crate::support::{add_ground, contacts_seen_from as scan};
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, Shape, World};

#[test]
fn contacts_of_after_waking_a_sleeping_pile_matches_the_contact_list() {
    let mut world = World::default();
    add_ground(&mut world, 20.0);
    let boxes: Vec<_> = (0..12)
        .map(|i| {
            let p = Vec2::new((i % 4) as f32 * 1.01 - 1.5, 0.5 + (i / 4) as f32);
            world
                .add_body(BodyDef::new_dynamic(p, Shape::rect(1.0, 1.0)))
                .unwrap()
        })
        .collect();
    for _ in 0..120 {
        world.step(1.0 / 60.0);
    }
    assert!(world.sleeping_len() > 0, "the pile sleeps");
    // Build the index, wake the pile (its stored contacts are dropped),
    // and ask again in the same tick.
    assert_eq!(
        world.contacts_of(boxes[0]).collect::<Vec<_>>(),
        scan(&world, boxes[0])
    );
    world.apply_impulse(boxes[5], Vec2::new(0.0, 1.0));
    for &b in &boxes {
        assert_eq!(world.contacts_of(b).collect::<Vec<_>>(), scan(&world, b));
    }
    world.wake_all();
    for &b in &boxes {
        assert_eq!(world.contacts_of(b).collect::<Vec<_>>(), scan(&world, b));
    }
}

#[test]
fn a_body_reusing_a_removed_bodys_slot_has_none_of_its_contacts() {
    let mut world = World::default();
    add_ground(&mut world, 20.0);
    let a = world
        .add_body(BodyDef::new_dynamic(
            Vec2::new(0.0, 0.5),
            Shape::rect(1.0, 1.0),
        ))
        .unwrap();
    world.step(1.0 / 60.0);
    assert!(world.contacts_of(a).count() > 0);
    world.remove_body(a).unwrap();
    let c = world
        .add_body(BodyDef::new_dynamic(
            Vec2::new(5.0, 5.0),
            Shape::circle(0.2),
        ))
        .unwrap();
    assert_eq!(c.index(), a.index(), "the slot is reused");
    assert_eq!(world.contacts_of(c).count(), 0);
    assert!(!world.is_standing(c, 0.8));
}

#[test]
fn contacts_of_after_restoring_a_snapshot_from_before_the_first_step() {
    // Box A in the air, box B on the ground. A snapshot from before the
    // first step (the first save of a rollback session) has no contacts;
    // restoring it and stepping a different timeline gave the same step
    // count and contact revision as the abandoned one, so `contacts_of`
    // kept that timeline's index: empty lists, `is_standing` false, and a
    // game reading them desynchronised from a run that never rolled back.
    let mut world = World::default();
    add_ground(&mut world, 20.0);
    let a = world
        .add_body(BodyDef::new_dynamic(
            Vec2::new(-3.0, 3.0),
            Shape::rect(1.0, 1.0),
        ))
        .unwrap();
    let b = world
        .add_body(BodyDef::new_dynamic(
            Vec2::new(3.0, 0.5),
            Shape::rect(1.0, 1.0),
        ))
        .unwrap();
    let saved = world.snapshot();
    let mut straight = world.clone();
    world.step(1.0 / 60.0);
    assert_eq!(world.contacts_of(a).count(), 0, "A is in the air");
    world.restore_from(&saved).unwrap();
    for w in [&mut world, &mut straight] {
        w.set_position(a, Vec2::new(-3.0, 0.5));
        w.step(1.0 / 60.0);
    }
    for id in [a, b] {
        assert_eq!(world.contacts_of(id).collect::<Vec<_>>(), scan(&world, id));
        assert_eq!(world.contacts_of(id).count(), 1, "{id:?} on the ground");
        assert!(world.is_standing(id, 0.8));
        assert_eq!(
            world.contacts_of(id).collect::<Vec<_>>(),
            straight.contacts_of(id).collect::<Vec<_>>()
        );
    }
}
