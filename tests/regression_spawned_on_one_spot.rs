//! Bodies spawned on one spot made a pair of every two of them: 10 000
//! circles took over 2 s per step and 14 GB. Now a crowded grid cell
//! bounds each body's pairs (`CROWDED_CELL`), and bodies on exactly the
//! same spot are pushed apart each pair its own way, so the pile spreads
//! in every direction instead of along one line. While some contact
//! overlaps by more than `DEEP_OVERLAP`, the push out of overlap carries on
//! from substep to substep, so it spreads through the whole pile: 10 000
//! circles were still overlapping by 19 cm after 10 s, and are now apart
//! in about 5 s (`passo bench extreme`).

use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, Shape};
use passo_tests::{max_penetration, weightless_world};

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
}
