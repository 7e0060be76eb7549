//! Speculative contacts: a pair becomes a contact before its bodies touch
//! only if they can close the gap within the step. Between two dynamic
//! bodies each body's box in the broad phase is swept along its travel,
//! and the narrow phase keeps a contact as far as the two move towards
//! each other along the pair's normal (each at its own speed, since either
//! may be stopped during the step). A static or kinematic body is met in
//! every direction as far as the other body's travel reaches.

use crate::support::{add_ground, max_penetration, weightless_world};
use passo_physics::constants::{LINEAR_SLOP, SPECULATIVE_DISTANCE};
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, BodyId, Shape, World};

const DT: f32 = 1.0 / 60.0;

fn circle(world: &mut World, at: Vec2, velocity: Vec2) -> BodyId {
    let def = BodyDef::new_dynamic(at, Shape::circle(0.2)).with_velocity(velocity);
    world.add_body(def).unwrap()
}

fn contacts_between(world: &World, a: BodyId, b: BodyId) -> usize {
    world
        .contacts_of(a)
        .filter(|c| c.a == b || c.b == b)
        .count()
}

#[test]
fn bodies_falling_side_by_side_make_no_contact_and_one_above_another_do() {
    let mut world = World::default();
    let fall = Vec2::new(0.0, -10.0);
    // Gaps of 15 cm, far more than the speculative distance (2 cm) and
    // less than a step's fall (17 cm).
    let left = circle(&mut world, Vec2::new(0.0, 50.0), fall);
    let right = circle(&mut world, Vec2::new(0.55, 50.0), fall);
    let below = circle(&mut world, Vec2::new(0.0, 49.45), fall);
    world.step(DT);
    // Side by side nothing closes the gap: no contact.
    assert_eq!(contacts_between(&world, left, right), 0);
    // One above another the lower one may be stopped within the step, and
    // the upper one then closes the gap at its own speed: a contact.
    assert_eq!(contacts_between(&world, left, below), 1);
    // Neither contact acted: the three still fall together, 15 cm apart.
    let x = |id| world.body(id).unwrap().position;
    assert_eq!(x(left).y, x(right).y);
    assert!((x(left).y - x(below).y - 0.55).abs() < 1e-4);
}

#[test]
fn a_column_falling_together_lands_on_the_ground_without_sinking_in() {
    // Ten circles falling at 12 m/s, 15 cm apart: the lowest stops on the
    // ground in the middle of a step, and every one above it closes its gap
    // within a step at its own speed. Each contact above was made
    // speculatively while the column still fell together.
    let mut world = World::default();
    add_ground(&mut world, 20.0);
    let fall = Vec2::new(0.0, -12.0);
    for i in 0..10 {
        circle(&mut world, Vec2::new(0.0, 1.0 + 0.55 * i as f32), fall);
    }
    let mut deepest = 0.0f32;
    for _ in 0..120 {
        world.step(DT);
        deepest = deepest.max(max_penetration(&world));
    }
    assert!(
        deepest < SPECULATIVE_DISTANCE,
        "sank {} mm into each other",
        deepest * 1e3
    );
    // At rest at the end, within the slop of touching.
    let last = max_penetration(&world);
    assert!(last <= 2.0 * LINEAR_SLOP, "{} mm", last * 1e3);
}

#[test]
fn a_body_keeps_its_speculative_contacts_with_walls_whichever_way_it_moves() {
    // A ball flying level at 20 m/s, 5 cm above the ground and 5 cm below
    // a kinematic ceiling: it moves along both, yet something it glances
    // off on its way could turn it into either within the step. A static
    // or kinematic body is met in every direction as far as the ball's
    // travel reaches, so both are contacts (a thin wall is never passed).
    // The same with the ceiling at rest long enough to fall asleep.
    for settle in [0, 60] {
        let mut world = World::default();
        let ground = add_ground(&mut world, 100.0);
        let ceiling = world
            .add_body(BodyDef::new_kinematic(
                Vec2::new(0.0, 0.75),
                Shape::rect(10.0, 0.5),
                Vec2::ZERO,
            ))
            .unwrap();
        for _ in 0..settle {
            world.step(DT);
        }
        assert_eq!(world.is_asleep(ceiling), Some(settle > 0));
        let ball = circle(&mut world, Vec2::new(0.0, 0.25), Vec2::new(20.0, 0.0));
        world.step(DT);
        assert_eq!(contacts_between(&world, ball, ground), 1, "{settle}");
        assert_eq!(contacts_between(&world, ball, ceiling), 1, "{settle}");
        // Neither acted: the ball flew on.
        assert!(world.body(ball).unwrap().position.x > 0.3);
    }
}

#[test]
fn a_body_keeps_its_speculative_contact_with_a_sleeping_body_it_flies_past() {
    // A crate asleep on the ground, and a ball flying level at 20 m/s
    // 5 cm above its top: it does not close on the crate, but something
    // it glances off could turn it into it within the step, and the crate,
    // held still while it sleeps, is met as a wall is. One contact, which
    // neither wakes the crate nor stops the ball.
    let mut world = World::default();
    add_ground(&mut world, 100.0);
    let def = BodyDef::new_dynamic(Vec2::new(1.0, 0.25), Shape::rect(4.0, 0.5));
    let crate_ = world.add_body(def).unwrap();
    for _ in 0..120 {
        world.step(DT);
    }
    assert_eq!(world.is_asleep(crate_), Some(true));
    let ball = circle(&mut world, Vec2::new(0.0, 0.75), Vec2::new(20.0, 0.0));
    world.step(DT);
    assert_eq!(contacts_between(&world, ball, crate_), 1);
    assert_eq!(world.is_asleep(crate_), Some(true));
    assert!(world.body(ball).unwrap().position.x > 0.3);
}

#[test]
fn a_fast_body_keeps_its_speculative_contact_with_an_awake_crate_it_flies_past() {
    // As with a sleeping crate: a ball at 60 m/s travels farther in a step
    // (1 m) than its contacts reach (4 radii), so a glance could turn it
    // anywhere; it keeps the contact with an awake crate 5 cm below its
    // path.
    let mut world = World::default();
    add_ground(&mut world, 100.0);
    let def = BodyDef::new_dynamic(Vec2::new(1.0, 0.25), Shape::rect(4.0, 0.5));
    let crate_ = world.add_body(def).unwrap();
    world.step(DT);
    assert_eq!(world.is_asleep(crate_), Some(false));
    let ball = circle(&mut world, Vec2::new(0.0, 0.75), Vec2::new(60.0, 0.0));
    world.step(DT);
    assert_eq!(contacts_between(&world, ball, crate_), 1);
    assert!(world.body(ball).unwrap().position.x > 0.9);
}

#[test]
fn at_20_hz_a_box_falling_onto_a_crate_is_met_before_it_gets_in() {
    // A long step (20 Hz): gravity adds 0.5 m/s over it, and the box
    // falls that much farther than its speed at the start says. Dropped
    // from 1 to 80 cm onto a crate (two awake dynamic bodies), the contact
    // is made the step before they meet, at every height.
    const STEP: f32 = 0.05;
    for i in 0..80 {
        let drop = 0.01 + 0.01 * i as f32;
        let mut world = World::default();
        add_ground(&mut world, 20.0);
        let below = BodyDef::new_dynamic(Vec2::new(0.0, 0.25), Shape::rect(1.0, 0.5));
        world.add_body(below).unwrap();
        let def = BodyDef::new_dynamic(Vec2::new(0.0, 0.75 + drop), Shape::rect(0.5, 0.5));
        world.add_body(def).unwrap();
        for tick in 0..20 {
            world.step(STEP);
            let deepest = max_penetration(&world);
            assert!(
                deepest <= 2.0 * LINEAR_SLOP,
                "from {drop} m, tick {tick}: {} mm in",
                deepest * 1e3
            );
        }
    }
}

#[test]
fn a_pair_whose_bodies_do_not_approach_along_its_normal_is_no_contact() {
    let weightless = || weightless_world();
    // B passes A along the tangent of their 10 cm gap at 10 m/s: the
    // broad phase pairs them (B's box is swept towards A's), but neither
    // closes the gap along the normal.
    let d = 0.5 / std::f32::consts::SQRT_2;
    let mut world = weightless();
    let a = circle(&mut world, Vec2::ZERO, Vec2::ZERO);
    let b = circle(&mut world, Vec2::new(d, -d), Vec2::new(7.07, 7.07));
    world.step(DT);
    assert_eq!(contacts_between(&world, a, b), 0);
    // B (the higher id, so the pair's B) comes straight at A over the same
    // gap: a contact, which stops B at A's surface.
    let mut world = weightless();
    let a = circle(&mut world, Vec2::ZERO, Vec2::ZERO);
    let b = circle(&mut world, Vec2::new(0.5, 0.0), Vec2::new(-10.0, 0.0));
    world.step(DT);
    assert_eq!(contacts_between(&world, a, b), 1);
    assert!(max_penetration(&world) <= LINEAR_SLOP);
}

#[test]
fn a_body_let_go_at_rest_beside_a_ledge_a_hair_above_its_top_falls_past_it() {
    // A ledge whose top is at y = 0 and right face at x = 0, static or
    // kinematic (standing still), and a box or a circle let go at rest
    // beside it, `gap.x` to its right and `gap.y` above its top: beyond
    // the corner. Gravity alone moves it, straight down past the ledge's
    // side: the contact is the side's plane. Seen without gravity's pull
    // over the step (on it, or on the kinematic ledge too), no gap would
    // close and the top's plane, a hair below, would hold it in the air.
    for kinematic in [false, true] {
        for shape in [Shape::rect(0.5, 0.5), Shape::circle(0.25)] {
            for gap in [
                Vec2::new(0.0005, 0.0005),
                Vec2::new(0.001, 0.001),
                Vec2::new(0.003, 0.0005),
                Vec2::new(0.0005, 0.002),
            ] {
                let mut world = World::default();
                add_ground(&mut world, 20.0);
                let centre = Vec2::new(-1.0, 4.0);
                let ledge = if kinematic {
                    BodyDef::new_kinematic(centre, Shape::rect(2.0, 8.0), Vec2::ZERO)
                } else {
                    BodyDef::new_static(centre, Shape::rect(2.0, 8.0))
                };
                world.add_body(ledge).unwrap();
                let half = shape.half_extents();
                // Circles beyond the corner diagonally, by the same gaps.
                let at = Vec2::new(0.0, 8.0) + half + gap;
                let body = world.add_body(BodyDef::new_dynamic(at, shape)).unwrap();
                for _ in 0..30 {
                    world.step(DT);
                }
                // Half a second of free fall is 1.23 m.
                let fell = at.y - world.body(body).unwrap().position.y;
                assert!(
                    fell > 1.2,
                    "kinematic {kinematic}, {shape:?}, gap {gap}: fell {fell} m"
                );
            }
        }
    }
}
