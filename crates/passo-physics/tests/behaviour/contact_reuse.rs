//! Contact reuse: a step keeps the last step's contact of two bodies that
//! moved less than `ContactSettings::reuse_distance` relative to each other
//! since its manifold was computed, moving only its separation. These tests
//! hold it to what finding every contact afresh gives, to the bound it
//! claims, and to rollback's bits.

use crate::support::add_ground;
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, BodyId, Shape, World};

const DT: f32 = 1.0 / 60.0;

/// `world` with contact reuse within `distance` (0: off).
fn reusing(mut world: World, distance: f32) -> World {
    let mut settings = *world.settings();
    settings.contacts.as_mut().unwrap().reuse_distance = distance;
    world.set_settings(settings).unwrap();
    world
}

/// A pyramid of boxes of base `base` on the ground, awake throughout.
fn pyramid(base: usize) -> World {
    let mut world = World::default();
    let mut settings = *world.settings();
    settings.contacts.as_mut().unwrap().sleeping = false;
    world.set_settings(settings).unwrap();
    add_ground(&mut world, base as f32 * 2.0 + 10.0);
    for row in 0..base {
        for i in 0..base - row {
            let x = i as f32 - (base - row - 1) as f32 * 0.5;
            let def = BodyDef::new_dynamic(Vec2::new(x, 0.5 + row as f32), Shape::rect(1.0, 1.0));
            world.add_body(def).unwrap();
        }
    }
    world
}

#[test]
fn the_default_reuses_within_the_slop_and_zero_turns_it_off() {
    let settings = World::default().settings().contacts.unwrap();
    assert_eq!(settings.reuse_distance, settings.slop);
    for bad in [-0.001, f32::NAN, f32::INFINITY] {
        let mut world = World::default();
        let mut s = *world.settings();
        s.contacts.as_mut().unwrap().reuse_distance = bad;
        let error = world.set_settings(s).expect_err("refused");
        assert!(
            error
                .to_string()
                .contains("ContactSettings::reuse_distance"),
            "{bad}: {error}"
        );
    }
}

#[test]
fn a_pile_stands_as_it_does_with_every_contact_found_afresh() {
    // A pyramid of 55 boxes over five seconds: the boxes end where they end
    // without reuse to a fraction of the reuse distance, overlap no deeper,
    // and touch the same pairs.
    let (mut fresh, mut reused) = (reusing(pyramid(10), 0.0), pyramid(10));
    let (mut deepest_fresh, mut deepest_reused) = (0.0f32, 0.0f32);
    for _ in 0..300 {
        fresh.step(DT);
        reused.step(DT);
        deepest_fresh = deepest_fresh.max(fresh.max_penetration());
        deepest_reused = deepest_reused.max(reused.max_penetration());
    }
    for (a, b) in fresh.bodies().zip(reused.bodies()) {
        let apart = (a.position - b.position).length();
        assert!(
            apart < 1e-3,
            "body {:?} {apart} m from where it ends afresh",
            a.id
        );
    }
    assert!(
        deepest_reused <= deepest_fresh + 1e-4,
        "deepest overlap {deepest_reused} m reused, {deepest_fresh} m afresh"
    );
    let pairs = |w: &World| {
        let mut p: Vec<(BodyId, BodyId)> = w
            .contacts()
            .filter(|c| c.touching)
            .map(|c| (c.a, c.b))
            .collect();
        p.sort();
        p
    };
    assert_eq!(pairs(&fresh), pairs(&reused));
}

/// How far a box pushed slowly off the end of a ledge travelled beyond
/// the ledge's edge when it started to fall.
fn travel_beyond_the_edge_when_it_falls(reuse_distance: f32) -> f32 {
    // A frictionless ledge ending at x = 0 and a 1 m box on it, moving
    // right at 0.12 m/s: 2 mm a step, under the reuse distance, so a kept
    // contact would hold it up for ever if the motion since its manifold
    // was not counted from where the manifold was computed.
    let mut world = reusing(World::default(), reuse_distance);
    let ledge = BodyDef {
        friction: 0.0,
        ..BodyDef::new_static(Vec2::new(-5.0, -0.5), Shape::rect(10.0, 1.0))
    };
    world.add_body(ledge).unwrap();
    let crate_def = BodyDef {
        friction: 0.0,
        velocity: Vec2::new(0.12, 0.0),
        ..BodyDef::new_dynamic(Vec2::new(-0.56, 0.5), Shape::rect(1.0, 1.0))
    };
    let id = world.add_body(crate_def).unwrap();
    for _ in 0..1200 {
        world.step(DT);
        let body = world.body(id).unwrap();
        if body.position.y < 0.49 {
            // The box's left side against the edge at x = 0.
            return body.position.x - 0.5;
        }
    }
    panic!("the box never fell off the ledge");
}

#[test]
fn a_box_leaving_a_ledge_falls_within_the_reuse_distance_of_where_it_falls_afresh() {
    let fresh = travel_beyond_the_edge_when_it_falls(0.0);
    let reused = travel_beyond_the_edge_when_it_falls(0.005);
    assert!(
        fresh.abs() < 0.02,
        "afresh it falls as it leaves: {fresh} m"
    );
    // At most the reuse distance later, and a step's travel (2 mm).
    assert!(
        (reused - fresh).abs() <= 0.005 + 0.002 + 1e-4,
        "reused {reused} m against {fresh} m afresh"
    );
}

#[test]
fn a_friction_change_acts_in_the_next_step() {
    // A box at rest on the ground, pushed sideways by less than static
    // friction holds (0.5 × 9.81 N against 3 N); with its friction set to
    // zero it slides from the next step on: its kept contact does not keep
    // the old friction.
    let mut world = World::default();
    add_ground(&mut world, 20.0);
    let id = world
        .add_body(BodyDef::new_dynamic(
            Vec2::new(0.0, 0.5),
            Shape::rect(1.0, 1.0),
        ))
        .unwrap();
    for _ in 0..30 {
        world.apply_force(id, Vec2::new(3.0, 0.0));
        world.step(DT);
    }
    assert!(world.body(id).unwrap().velocity.x.abs() < 1e-4, "held");
    world.set_friction(id, 0.0);
    world.apply_force(id, Vec2::new(3.0, 0.0));
    world.step(DT);
    let v = world.body(id).unwrap().velocity.x;
    // 3 N on 1 kg for one step, no friction: 0.05 m/s.
    assert!((v - 3.0 * DT).abs() < 1e-3, "slides at once: {v} m/s");
}

#[test]
fn a_snapshot_steps_on_with_the_contacts_it_reuses() {
    // Rollback's bits: a world restored from a snapshot reuses what the
    // world it was taken from reuses, after a plain step, after a removal
    // moved bodies' indices, and after a friction change.
    type Poke = fn(&mut World, &[BodyId]);
    let pokes: [(&str, Poke); 3] = [
        ("nothing", |_, _| {}),
        ("a removal", |w, ids| {
            w.remove_body(ids[3]).unwrap();
        }),
        ("a friction change", |w, ids| w.set_friction(ids[7], 0.1)),
    ];
    for (what, poke) in pokes {
        let mut world = pyramid(8);
        for _ in 0..60 {
            world.step(DT);
        }
        let ids: Vec<BodyId> = world.bodies().map(|b| b.id).collect();
        poke(&mut world, &ids);
        let mut restored = World::from_snapshot(world.snapshot()).unwrap();
        for tick in 0..120 {
            world.step(DT);
            restored.step(DT);
            assert_eq!(
                world.state_hash(),
                restored.state_hash(),
                "{what}, tick {tick}"
            );
        }
    }
}

#[test]
fn a_pyramid_at_rest_takes_the_last_steps_colours_and_a_new_box_colours_anew() {
    // At rest the pyramid keeps its contacts, so each step takes the last
    // step's colours; a box dropped on it brings new contacts.
    let mut world = pyramid(10);
    for _ in 0..120 {
        world.step(DT);
    }
    let reused = |w: &World| w.counters().colourings_reused;
    let before = reused(&world);
    for _ in 0..30 {
        world.step(DT);
    }
    assert_eq!(reused(&world) - before, 30, "every step at rest");
    let def = BodyDef::new_dynamic(Vec2::new(0.0, 10.6), Shape::rect(1.0, 1.0));
    world.add_body(def).unwrap();
    let before = reused(&world);
    for _ in 0..30 {
        world.step(DT);
    }
    let landing = reused(&world) - before;
    assert!(
        (1..30).contains(&landing),
        "{landing} of 30 while the box lands"
    );
}

#[test]
fn a_body_moved_into_the_place_of_one_removed_gets_the_contacts_there() {
    // Pooling: a crate on a crate is removed and, in the same tick, a
    // crate of the same size from far away is moved to exactly where it
    // was, at its velocity. The pairs of the step are the same as the
    // last step's (the spare, floating far off, was in none), between
    // other bodies: the contacts name the new crate.
    for far in [3.0f32, 7.0, 12.0] {
        let mut world = World::default();
        let mut settings = *world.settings();
        settings.contacts.as_mut().unwrap().sleeping = false;
        world.set_settings(settings).unwrap();
        add_ground(&mut world, 40.0);
        let crate_at = |world: &mut World, at: Vec2| {
            let def = BodyDef::new_dynamic(at, Shape::rect(1.0, 1.0));
            world.add_body(def).unwrap()
        };
        let below = crate_at(&mut world, Vec2::new(0.0, 0.5));
        let top = crate_at(&mut world, Vec2::new(0.0, 1.5));
        // Floating, out of every pair (gravity off for it).
        let spare = crate_at(&mut world, Vec2::new(far, 5.0));
        world.set_gravity_scale(spare, 0.0).unwrap();
        for _ in 0..60 {
            world.step(DT);
        }
        let was = world.body(top).unwrap();
        world.remove_body(top).unwrap();
        world.set_position(spare, was.position);
        world.set_velocity(spare, was.velocity);
        world.step(DT);
        let on_top: Vec<_> = world.contacts_of(spare).collect();
        assert!(
            on_top.iter().any(|c| c.a == below || c.b == below),
            "{far}: {on_top:?}"
        );
        for c in world.contacts_of(below) {
            assert!(
                c.a != top && c.b != top,
                "{far}: a contact of the removed crate"
            );
        }
        // It stays where the removed crate was.
        let p = world.body(spare).unwrap().position;
        assert!((p - was.position).length() < 1e-3, "{far}: {p}");
    }
}
