//! Tests of `narrow_phase`.

use crate::testing::pile;
use crate::{TestSwitches, World};
use glam::Vec2;

/// Runs a step of `world` and returns whether its narrow phase sorted
/// the pairs, checking that the pairs it went through are this step's
/// keys sorted.
fn step(world: &mut World) -> bool {
    let before = world.counters().pair_sorts;
    world.step(1.0 / 60.0);
    let narrow = world.contacts.as_ref().expect("contacts").narrow();
    let mut sorted = narrow.last_keys.clone();
    sorted.sort_by_key(|k| k.0);
    assert_eq!(narrow.keyed, sorted, "the pairs in key order");
    world.counters().pair_sorts > before
}

#[test]
fn a_pile_at_rest_keeps_its_sorted_pairs_until_they_change() {
    let (mut world, boxes) = pile();
    assert!(step(&mut world), "the first step sorts");
    let sorts = (0..60).filter(|_| step(&mut world)).count();
    assert_eq!(sorts, 0, "the pile keeps its pairs");
    // A box lifted off the top and set down beside the pile: other
    // pairs, sorted again.
    world.set_position(boxes[0], Vec2::new(6.0, 0.5));
    assert!(step(&mut world), "new pairs are sorted");
    assert!(!step(&mut world), "and kept while they last");
}

/// The pile stepped beside a copy changed by `change`, with a box
/// dropped on both halfway (found anew, then kept again): the same
/// contacts, impulses and bits every tick. Returns both worlds.
fn beside_a_dropped_box(change: impl FnOnce(&mut World)) -> (World, World) {
    let (mut world, boxes) = pile();
    world.step(1.0 / 60.0);
    let mut other = world.clone();
    change(&mut other);
    crate::testing::step_side_by_side(
        (&mut world, &mut other),
        &boxes,
        (90, 45),
        |w| w.set_position(boxes[0], Vec2::new(0.0, 4.0)),
        |tick, world, other| {
            // (The impulses the next step starts from are cached
            // from these.)
            let (a, b) = (world.contacts.as_ref(), other.contacts.as_ref());
            let (a, b) = (&a.unwrap().solved, &b.unwrap().solved);
            assert_eq!(a, b, "tick {tick}: the same contacts and impulses");
        },
    );
    (world, other)
}

#[test]
fn impulses_kept_in_place_are_those_the_warm_start_gives() {
    let (world, _) = beside_a_dropped_box(|warmed| {
        warmed.set_test_switches(TestSwitches {
            warm_start_always: true,
            ..Default::default()
        });
    });
    assert!(world.counters().contacts_reused_in_place > 60);
}

#[test]
fn contacts_kept_in_place_are_those_the_walk_keeps() {
    let (mut world, mut walked) = beside_a_dropped_box(|walked| {
        walked.set_test_switches(TestSwitches {
            walk_always: true,
            ..Default::default()
        })
    });
    let kept = |w: &mut World| w.counters().contacts_reused_in_place;
    assert_eq!(kept(&mut walked), 0);
    assert!(
        kept(&mut world) > 60,
        "kept in place {} times",
        kept(&mut world)
    );
    assert!(kept(&mut world) < 89, "the drop was found anew");
}

#[test]
fn contacts_found_after_a_keep_that_stopped_halfway_are_those_the_walk_finds() {
    // The pile at rest; then the body of the last contact (in key
    // order) is moved beyond the reuse distance, so the keep in place
    // checks and keeps the contacts before its, and stops there.
    let (mut world, boxes) = pile();
    for _ in 0..60 {
        world.step(1.0 / 60.0);
    }
    let mut walked = world.clone();
    walked.set_test_switches(TestSwitches {
        walk_always: true,
        ..Default::default()
    });
    let last = world
        .contacts
        .as_ref()
        .unwrap()
        .solved
        .infos
        .last()
        .unwrap();
    let moved = if boxes.contains(&last.id_b) {
        last.id_b
    } else {
        last.id_a
    };
    let kept_before = world.counters().contacts_reused_in_place;
    crate::testing::step_side_by_side(
        (&mut world, &mut walked),
        &boxes,
        (30, 0),
        |w| {
            let p = w.body(moved).unwrap().position;
            w.set_position(moved, p + Vec2::new(0.02, 0.0));
        },
        |tick, world, walked| {
            let (a, b) = (world.contacts.as_ref(), walked.contacts.as_ref());
            let (a, b) = (&a.unwrap().solved, &b.unwrap().solved);
            assert_eq!(a, b, "tick {tick}: the same contacts and impulses");
            if tick == 0 {
                assert_eq!(
                    world.counters().contacts_reused_in_place,
                    kept_before,
                    "not kept"
                );
            }
        },
    );
}

/// Bodies on one spot are pushed apart along a direction of their
/// pair's own: unit length, different for different pairs, and spread
/// evenly around the circle.
#[test]
fn pairs_on_one_spot_spread_evenly_in_directions_of_their_own() {
    use crate::BodyId;
    let mut dirs = Vec::new();
    for a in 0..40u32 {
        for b in a + 1..a + 26 {
            let id = |index, generation| BodyId { index, generation };
            let d = super::spread_direction(id(a, 0), id(b, 3));
            assert!((d.length() - 1.0).abs() < 1e-6, "{a}, {b}: {d}");
            dirs.push(d);
        }
    }
    let n = dirs.len();
    let mut bits: Vec<_> = dirs
        .iter()
        .map(|d| (d.x.to_bits(), d.y.to_bits()))
        .collect();
    bits.sort_unstable();
    bits.dedup();
    assert_eq!(bits.len(), n, "a direction of each pair's own");
    // Each sixteenth of the circle holds about a sixteenth of them
    // (uniform: none below 0.6 or above 1.45 of its share; directions
    // drawn from a square, not a disc, crowd the diagonals 1.6 times).
    let mut bins = [0usize; 16];
    for d in &dirs {
        let turn = (d.y.atan2(d.x) / std::f32::consts::TAU + 1.0) % 1.0;
        bins[(turn * 16.0) as usize % 16] += 1;
    }
    let share = n as f32 / 16.0;
    for count in bins {
        let ratio = count as f32 / share;
        assert!((0.6..1.45).contains(&ratio), "{bins:?} of {n}");
    }
}
