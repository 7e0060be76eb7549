//! On the thread pool, a narrow phase that found sensor overlaps but no
//! contact at all dropped the sensor candidates, so no body was reported
//! entering a sensor. Here 5 000 circles float apart (no gravity), each
//! inside a static sensor box of its own: 5 000 candidate pairs, enough for
//! the narrow phase to go to the pool, and not one contact.

use crate::support::weightless_world;
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, SensorPair, Shape};

/// Every body that entered a sensor on the first step, with and without
/// the pool.
fn entered(parallel: bool) -> (usize, Vec<SensorPair>) {
    let mut world = weightless_world();
    world.set_parallel(parallel);
    for i in 0..5_000 {
        let at = Vec2::new((i % 100) as f32, (i / 100) as f32);
        world
            .add_body(BodyDef::new_static(at, Shape::rect(0.6, 0.6)).as_sensor())
            .unwrap();
        world
            .add_body(BodyDef::new_dynamic(at, Shape::circle(0.1)))
            .unwrap();
    }
    world.step(1.0 / 60.0);
    (
        world.contacts().count(),
        world.events().sensor_begin.clone(),
    )
}

#[test]
fn sensor_overlaps_are_reported_on_the_pool_when_nothing_touches() {
    let (contacts, on_pool) = entered(true);
    assert_eq!(contacts, 0, "nothing solid touches");
    assert_eq!(on_pool.len(), 5_000, "every circle is inside its sensor");
    assert_eq!(on_pool, entered(false).1, "the same pairs on one thread");
}
