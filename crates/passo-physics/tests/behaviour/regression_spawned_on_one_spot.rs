//! Bodies spawned on one spot made a pair of every two of them: 10 000
//! circles took over 2 s per step and 14 GB. Now a crowded grid cell
//! bounds each body's pairs (`CROWDED_CELL`), and bodies on exactly the
//! same spot are pushed apart each pair its own way, so the pile spreads
//! in every direction instead of along one line. While some contact
//! overlaps by more than `DEEP_OVERLAP`, the push out of overlap carries on
//! from substep to substep, so it spreads through the whole pile: 10 000
//! circles were still overlapping by 19 cm after 10 s, and are now apart
//! in about 5 s (`passo bench extreme`).

use crate::support::{max_penetration, weightless_world};
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, Shape};

#[test]
fn a_pile_spawned_on_one_spot_spreads_out_calmly_with_bounded_contacts() {
    let n = 2_000;
    let mut world = weightless_world();
    for _ in 0..n {
        world
            .add_body(BodyDef::new_dynamic(Vec2::ZERO, Shape::circle(0.1)))
            .unwrap();
    }
    let (mut fastest, mut most) = (0.0f32, 0);
    for _ in 0..240 {
        world.step(1.0 / 60.0);
        // At most 64 pairs per body in each grid cell its box covers, four
        // at most for a box no larger than twice the mean (these are all
        // the same); none from the static tree: there is no static body.
        most = most.max(world.contacts().count());
        for b in world.bodies() {
            fastest = fastest.max(b.velocity.length());
        }
    }
    assert!(
        world.stats().crowded_steps > 0,
        "the first steps were crowded"
    );
    // Linear: a quarter of the 2 million pairs of every two bodies at
    // most (133 142 at the busiest step when measured).
    assert!(most <= 4 * 64 * n, "{most} contacts");
    let overlap = max_penetration(&world);
    assert!(overlap <= 0.01, "apart within 4 s: {overlap} m left");
    // Split impulses push without turning overlap into speed.
    assert!(
        fastest < 1.0,
        "calm: the fastest body moved at {fastest} m/s"
    );
    // Spread in two dimensions: not a line.
    let (mut xs, mut ys) = (0.0f32, 0.0f32);
    for b in world.bodies() {
        xs = xs.max(b.position.x.abs());
        ys = ys.max(b.position.y.abs());
    }
    assert!(xs > 1.0 && ys > 1.0, "spread {xs} by {ys} m");
    // Spread out, no step is crowded any more.
    let crowded = world.stats().crowded_steps;
    for _ in 0..10 {
        world.step(1.0 / 60.0);
    }
    assert_eq!(world.stats().crowded_steps, crowded);
}

#[test]
fn bodies_spawned_on_static_bodies_piled_on_one_spot_have_bounded_contacts() {
    // 1 000 static circles and 1 000 dynamic ones on one spot: each
    // dynamic body met every static one, a million contacts (5 000 of each
    // took 45 s and 9.6 GB for one step). Now each proxy meets at most
    // `MAX_STATIC_NEIGHBOURS` (128) static bodies, and the step counts as
    // crowded.
    let n = 1_000;
    let mut world = weightless_world();
    for _ in 0..n {
        world
            .add_body(BodyDef::new_static(Vec2::ZERO, Shape::circle(0.5)))
            .unwrap();
        world
            .add_body(BodyDef::new_dynamic(Vec2::ZERO, Shape::circle(0.5)))
            .unwrap();
    }
    world.step(1.0 / 60.0);
    let with_static = |c: &passo_physics::Contact| {
        [c.a, c.b].iter().any(|&id| {
            world
                .body(id)
                .is_some_and(|b| b.kind == passo_physics::BodyKind::Static)
        })
    };
    let static_contacts = world.contacts().filter(with_static).count();
    assert!(
        static_contacts <= 128 * n,
        "{static_contacts} contacts with static bodies"
    );
    assert!(
        static_contacts >= 64 * n,
        "each still meets many: {static_contacts}"
    );
    assert_eq!(world.stats().crowded_steps, 1);
    for b in world.bodies() {
        assert!(b.position.is_finite() && b.velocity.is_finite());
    }
}
