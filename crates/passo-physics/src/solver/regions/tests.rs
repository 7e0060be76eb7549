//! Tests of `regions`.

use super::*;
use crate::body::collider::ColliderRef;
use crate::solver::scalar::SolverParams;
use crate::testing::uniform;

/// A `side` × `side` lattice of boxes, each touching its right and upper
/// neighbours, the bottom row on the ground, with some velocity and
/// overlap: a pile, in positions, velocities and contacts.
fn lattice(side: u32) -> (Vec<Vec2>, Vec<Vec2>, Vec<Constraint>) {
    let index = |x: u32, y: u32| y * side + x;
    let (mut pos, mut vel, mut rows) = (Vec::new(), Vec::new(), Vec::new());
    for y in 0..side {
        for x in 0..side {
            pos.push(Vec2::new(x as f32, y as f32));
            vel.push(Vec2::new(((x * 7 + y * 3) % 5) as f32 - 2.0, -1.0));
        }
    }
    let contact = |a: u32, b: ColliderRef, normal: Vec2, depth: f32| Constraint {
        a,
        b,
        normal,
        base_separation: -depth,
        inv_mass_a: 1.0,
        inv_mass_b: if b.is_static() { 0.0 } else { 1.0 },
        mass: if b.is_static() { 1.0 } else { 0.5 },
        friction: 0.6,
        normal_impulse: 0.1,
        tangent_impulse: 0.01,
        push_impulse: 0.0,
        max_normal_impulse: 0.0,
        tangent_speed: 0.0,
    };
    for y in 0..side {
        for x in 0..side {
            let a = index(x, y);
            let depth = ((x + y) % 4) as f32 * 0.004;
            if y == 0 {
                rows.push(contact(a, ColliderRef::fixed(0), Vec2::Y, depth));
            }
            if x + 1 < side {
                rows.push(contact(
                    a,
                    ColliderRef::dynamic(index(x + 1, y)),
                    Vec2::X,
                    depth,
                ));
            }
            if y + 1 < side {
                rows.push(contact(
                    a,
                    ColliderRef::dynamic(index(x, y + 1)),
                    Vec2::Y,
                    depth,
                ));
            }
        }
    }
    (pos, vel, rows)
}

/// A pile's positions, velocities and contacts, the bodies in a deep
/// pile, and whether a contact holds a body.
type Scene = (Vec<Vec2>, Vec<Vec2>, Vec<Constraint>, Vec<bool>, bool);

/// Where `scrambled` stores body `i` of `bodies` (6 400 = 2^8 5^2,
/// which 7 919, a prime, does not divide: one place each).
fn scrambled_index(i: u32, bodies: usize) -> u32 {
    (u64::from(i) * 7919 % bodies as u64) as u32
}

/// The same scene with its bodies stored in no order of their places
/// (see `scrambled_index`): its steps split by place, not in storage
/// order.
fn scrambled(scene: Scene) -> Scene {
    let (pos, vel, mut rows, deep, holds) = scene;
    let n = pos.len();
    let to = |i: usize| scrambled_index(i as u32, n) as usize;
    let moved = |from: &[Vec2]| {
        let mut out = vec![Vec2::ZERO; n];
        for (i, &v) in from.iter().enumerate() {
            out[to(i)] = v;
        }
        out
    };
    let (pos, vel) = (moved(&pos), moved(&vel));
    let mut kept_deep = vec![false; deep.len()];
    for (i, &d) in deep.iter().enumerate() {
        kept_deep[to(i)] = d;
    }
    for c in &mut rows {
        c.a = to(c.a as usize) as u32;
        if let Some(b) = c.b.dynamic_index() {
            c.b = ColliderRef::dynamic(to(b) as u32);
        }
    }
    (pos, vel, rows, kept_deep, holds)
}

/// How a test runs a substep's passes.
#[derive(Clone, Copy, PartialEq)]
enum Run {
    /// As the step does, on two threads if `true`.
    Step(bool),
    /// The regions' groups one after the other on one array of states
    /// (the order of `ContactRegions::run`, with no array of their
    /// own for the second region's bodies).
    OneArray,
}

/// Runs a substep's passes over `scene` (warm start, two passes with
/// the push, one without) and returns the velocities, pushes and rows,
/// and whether the step split.
fn substep(scene: &Scene, run: Run) -> (Vec<Vec2>, Vec<Vec2>, Vec<Constraint>, bool) {
    let (pos, vel, rows, deep, holds) = scene;
    let mut rows = rows.clone();
    let parallel = run == Run::Step(true);
    let mut regions = ContactRegions::default();
    regions.build(&rows, pos, deep, *holds, parallel);
    let mut state = BodyState::of(vel);
    regions.load_far(&state);
    let delta = vec![Vec2::ZERO; pos.len()];
    let mut bodies = SolverBodies {
        state: &mut state,
        delta: &delta,
        deep,
    };
    let p = SolverParams {
        carry_push: !deep.is_empty(),
        ..SolverParams::for_tests()
    };
    let passes = [
        Pass::Begin(p, true),
        Pass::solve(&p, true),
        Pass::solve(&p, true),
    ];
    for pass in passes.iter().chain([&Pass::solve(&p, false)]) {
        match run {
            Run::Step(parallel) => regions.run(&mut bodies, pass, parallel),
            Run::OneArray => {
                let [first, second, between] = &mut regions.groups;
                first.blocks(&mut Bodies::new(&mut bodies), pass);
                second.blocks(&mut Bodies::new(&mut bodies), pass);
                first.overflow(&mut bodies, pass);
                second.overflow(&mut bodies, pass);
                between.run(&mut bodies, pass);
            }
        }
    }
    regions.store(&mut rows, run == Run::Step(true));
    if run != Run::OneArray {
        regions.gather(&mut state);
    }
    let (vel, push) = BodyState::split(&state);
    (vel, push, rows, regions.is_split())
}

/// The lattice of `side` × `side` with nothing held and no deep pile.
fn plain(side: u32) -> Scene {
    let (pos, vel, rows) = lattice(side);
    (pos, vel, rows, Vec::new(), false)
}

/// The lattice of 80 × 80, stored scrambled (so split at x = 39.5),
/// with in the second
/// region a body that every contact naming it holds (read by that
/// region's blocks from both arrays), a hub touching 140 bodies (more
/// contacts than colours: the region's contacts left over, solved one
/// by one on its array), a body held in the first region, a body held
/// by one contact and moved by others (all of its contacts between the
/// regions), every body in a deep pile (pushes carried), and the
/// pushes of the last substep.
fn held_hub_and_deep() -> Scene {
    let (pos, vel, mut rows) = lattice(80);
    let at = |x: u32, y: u32| y * 80 + x;
    let (held_far, held_near, mixed, hub) = (at(60, 30), at(10, 30), at(20, 50), at(70, 70));
    for c in &mut rows {
        if c.a == held_far || c.a == held_near {
            c.inv_mass_a = 0.0;
        }
        if [held_far, held_near]
            .map(Some)
            .contains(&c.b.dynamic_index().map(|b| b as u32))
        {
            c.inv_mass_b = 0.0;
        }
        if c.a == mixed && c.normal == Vec2::X {
            c.inv_mass_a = 0.0;
        }
        c.push_impulse = 0.02;
    }
    let template = rows[0];
    let spoke = |k: u32| Constraint {
        a: hub,
        b: ColliderRef::dynamic(at(40 + k % 35, k / 35 * 9 + 1)),
        normal: Vec2::new(0.6, 0.8),
        base_separation: -0.01,
        inv_mass_b: 1.0,
        mass: 0.5,
        ..template
    };
    rows.extend((0..140).map(spoke));
    let deep = vec![true; pos.len()];
    scrambled((pos, vel, rows, deep, true))
}

/// A pile of 80 × 80 bodies jittered off a lattice, with random
/// velocities and contacts between random near neighbours (up to three
/// columns and one row apart), some on one of two static bodies, three
/// hubs of up to 250 contacts each, random normals, overlaps, masses and
/// impulses, held bodies and held ends (never a hub's), and for even
/// seeds a deep pile over about a third of the bodies.
fn random_pile(seed: u64) -> Scene {
    let side = 80u32;
    let mut next = uniform(seed);
    let mut between = |lo: f32, hi: f32| lo + (hi - lo) * next();
    let mut pos = Vec::new();
    let mut vel = Vec::new();
    for y in 0..side {
        for x in 0..side {
            let jitter = Vec2::new(between(-0.3, 0.3), between(-0.3, 0.3));
            pos.push(Vec2::new(x as f32, y as f32) + jitter);
            vel.push(Vec2::new(between(-3.0, 3.0), between(-3.0, 3.0)));
        }
    }
    let mut ends = std::collections::BTreeSet::new();
    let mut near = |x: u32, y: u32, between: &mut dyn FnMut(f32, f32) -> f32| {
        for (dx, dy) in [(1, 0), (2, 0), (3, 0), (0, 1), (1, 1), (-1, 1)] {
            let (bx, by) = (x as i32 + dx, y as i32 + dy);
            let inside = (0..side as i32).contains(&bx) && (0..side as i32).contains(&by);
            if inside && between(0.0, 1.0) < 0.5 {
                ends.insert((y * side + x, by as u32 * side + bx as u32));
            }
        }
    };
    for y in 0..side {
        for x in 0..side {
            near(x, y, &mut between);
        }
    }
    let mut hubs = Vec::new();
    for _ in 0..3 {
        let hub = (between(0.0, 1.0) * (side * side) as f32) as u32;
        hubs.push(hub);
        let (hx, hy) = (hub % side, hub / side);
        let spokes = between(100.0, 250.0) as u32;
        for _ in 0..spokes {
            let x = (hx as f32 + between(-12.0, 12.0)).clamp(0.0, side as f32 - 1.0) as u32;
            let y = (hy as f32 + between(-12.0, 12.0)).clamp(0.0, side as f32 - 1.0) as u32;
            let other = y * side + x;
            if other != hub {
                ends.insert((hub.min(other), hub.max(other)));
            }
        }
    }
    let statics = (0..side * side).filter(|&i| i < side || between(0.0, 1.0) < 0.02);
    let statics: Vec<(u32, ColliderRef)> =
        statics.map(|a| (a, ColliderRef::fixed(a % 2))).collect();
    let dynamic = ends.into_iter().map(|(a, b)| (a, ColliderRef::dynamic(b)));
    // Each body's inverse mass; about one body in thirty held (as a
    // kinematic or sleeping body is: in every contact), never a hub.
    let inv_mass: Vec<f32> = (0..side * side)
        .map(|i| match between(0.0, 1.0) < 0.03 && !hubs.contains(&i) {
            true => 0.0,
            false => between(0.5, 2.0),
        })
        .collect();
    let mut rows = Vec::new();
    for (a, b) in dynamic.chain(statics) {
        let angle = between(0.0, std::f32::consts::TAU);
        // And about one end in a hundred held by this contact alone
        // (a body both moved and read: its contacts go between).
        let mut end = |i: u32| match between(0.0, 1.0) < 0.01 && !hubs.contains(&i) {
            true => 0.0,
            false => inv_mass[i as usize],
        };
        let inv_mass_a = end(a);
        let inv_mass_b = match b.dynamic_index() {
            Some(b) => end(b as u32),
            None => 0.0,
        };
        let k = inv_mass_a + inv_mass_b;
        rows.push(Constraint {
            a,
            b,
            normal: Vec2::new(angle.cos(), angle.sin()),
            base_separation: between(-0.03, 0.01),
            inv_mass_a,
            inv_mass_b,
            mass: if k > 0.0 { 1.0 / k } else { 0.0 },
            friction: between(0.0, 1.0),
            normal_impulse: between(0.0, 0.2),
            tangent_impulse: between(-0.02, 0.02),
            push_impulse: between(0.0, 0.03),
            max_normal_impulse: 0.0,
            tangent_speed: 0.0,
        });
    }
    let deep = match seed % 2 {
        0 => (0..pos.len()).map(|_| between(0.0, 1.0) < 0.3).collect(),
        _ => Vec::new(),
    };
    let holds = rows.iter().any(|c| {
        let (write_a, write_b) = c.moved();
        write_a.is_none() || (c.b.dynamic_index().is_some() && write_b.is_none())
    });
    (pos, vel, rows, deep, holds)
}

#[test]
fn each_region_on_its_own_array_gives_the_bits_of_one_array() {
    // The last: the held bodies not announced (`holds` false), which
    // the build notices and handles as if they were.
    let mut unannounced = held_hub_and_deep();
    unannounced.4 = false;
    let scenes = [
        plain(80),
        scrambled(plain(80)),
        held_hub_and_deep(),
        unannounced,
    ];
    let reference = [&scenes[0], &scenes[1], &scenes[2], &scenes[2]];
    for (scene, reference) in scenes.iter().zip(reference) {
        let one = substep(reference, Run::OneArray);
        assert!(one.3, "the pile splits");
        let own = substep(scene, Run::Step(false));
        assert_eq!(own.0, one.0, "velocities");
        assert_eq!(own.1, one.1, "pushes");
        assert_eq!(own.2, one.2, "impulses");
    }
    // The second scene has what it says: contacts between the regions,
    // left over in the second region, and held bodies in both arrays.
    let (pos, _, rows, deep, holds) = held_hub_and_deep();
    let mut regions = ContactRegions::default();
    regions.build(&rows, &pos, &deep, holds, false);
    assert!(!regions.picked[2].is_empty());
    assert!(regions.groups[1].left_over() > 0);
    assert!(!regions.far_between.is_empty());
    let homes = (0..pos.len()).map(|i| regions.homes.of(i));
    let both: Vec<usize> = homes
        .enumerate()
        .filter(|&(_, h)| h == Home::Both)
        .map(|(i, _)| i)
        .collect();
    let mut held = [30 * 80 + 10, 30 * 80 + 60].map(|i| scrambled_index(i, 6400) as usize);
    held.sort();
    assert_eq!(both, held);
}

#[test]
fn random_piles_on_their_regions_arrays_give_the_bits_of_one_array() {
    let (mut left_over, mut held_in_both) = (0, 0);
    for seed in 1..=12 {
        // Half of them stored scrambled: split by place.
        let scene = match seed > 6 {
            true => scrambled(random_pile(seed)),
            false => random_pile(seed),
        };
        assert!(scene.4, "seed {seed}: some body is held");
        let (pos, _, rows, deep, holds) = &scene;
        let mut regions = ContactRegions::default();
        regions.build(rows, pos, deep, *holds, false);
        assert!(!regions.far_between.is_empty(), "seed {seed}");
        let half = halfway(pos.len());
        let in_order = (0..pos.len()).all(|i| regions.region[i] == u8::from(i >= half));
        assert_eq!(in_order, seed <= 6, "seed {seed}: split in storage order");
        left_over += regions.groups[0].left_over() + regions.groups[1].left_over();
        let held_here = (0..pos.len()).filter(|&i| regions.homes.of(i) == Home::Both);
        let held_here = held_here.count();
        assert!(held_here > 50, "seed {seed}: {held_here} held bodies");
        held_in_both += held_here;
        let one = substep(&scene, Run::OneArray);
        assert!(one.3, "seed {seed}: the pile splits");
        // The held bodies announced, and not (the build notices them).
        let mut unannounced = scene.clone();
        unannounced.4 = false;
        for scene in [&scene, &unannounced] {
            let own = substep(scene, Run::Step(false));
            assert_eq!(own.0, one.0, "seed {seed}: velocities");
            assert_eq!(own.1, one.1, "seed {seed}: pushes");
            assert_eq!(own.2, one.2, "seed {seed}: impulses");
        }
    }
    // The piles have what the test is about.
    assert!(
        left_over > 0 && held_in_both > 0,
        "{left_over} {held_in_both}"
    );
}

#[test]
fn a_large_pile_splits_in_halves_with_few_contacts_between() {
    // Stored row by row: split in storage order, the rows below y = 40
    // and those above, 80 contacts across.
    let (pos, vel, rows) = lattice(80);
    assert!(pos.len() >= SPLIT_BODIES);
    let mut regions = ContactRegions::default();
    regions.build(&rows, &pos, &[], false, true);
    assert!(regions.is_split());
    assert_eq!(halfway(pos.len()), 3200);
    let in_order = (0..pos.len()).map(|i| u8::from(i >= 3200));
    assert!(regions.region.iter().copied().eq(in_order));
    assert_eq!(regions.picked[2].len(), 80);
    // Stored scrambled: split by place, at x = 39.5, 80 contacts across.
    let (pos, _, rows, _, _) = scrambled((pos, vel, rows, Vec::new(), false));
    regions.build(&rows, &pos, &[], false, true);
    assert!(regions.is_split());
    let by_place = pos.iter().map(|p| u8::from(p.x >= 39.5));
    assert!(regions.region.iter().copied().eq(by_place));
    let count = |g: usize| regions.picked[g].len();
    assert_eq!(count(2), 80);
    assert_eq!(count(0) + count(1) + count(2), rows.len());
    // A small pile does not split.
    let (pos, _, rows) = lattice(20);
    regions.build(&rows, &pos, &[], false, true);
    assert!(!regions.is_split());
}

#[test]
fn every_contact_comes_back_from_its_one_place_whether_split_or_not() {
    // Not split, split in storage order (the second region's rows
    // written side by side with the others'), split by place, and split
    // in storage order with the second region's first row just before
    // the last row between the regions (written in one part).
    let mut swapped = plain(80);
    let first = swapped.2.iter().position(|c| c.a >= 3200).unwrap();
    swapped.2.swap(first - 1, first);
    let scenes = [plain(20), plain(80), scrambled(plain(80)), swapped];
    for (k, (pos, _, mut rows, _, _)) in scenes.into_iter().enumerate() {
        for parallel in [false, true] {
            let mut regions = ContactRegions::default();
            regions.build(&rows, &pos, &[], false, parallel);
            if k == 3 {
                // The case it is about.
                let first = regions.picked[1][0];
                assert!(regions.picked[2].contains(&(first + 1)));
            }
            for g in &mut regions.groups {
                g.mark_rows();
            }
            // Each row's slot names the group, block and lane (or place
            // left over) that hold it, as shock propagation reads them.
            let mut slot_of = vec![Slot::None; rows.len()];
            regions.note_slots(&mut slot_of);
            for (i, &slot) in slot_of.iter().enumerate() {
                let [normal, _, _] = regions.groups[slot.group()].impulses_mut(slot);
                assert_eq!(*normal, i as f32, "slot of row {i} of scene {k}");
            }
            for r in &mut rows {
                r.normal_impulse = -1.0;
            }
            regions.store(&mut rows, parallel);
            for (i, r) in rows.iter().enumerate() {
                assert_eq!(r.normal_impulse, i as f32, "row {i} of scene {k}");
            }
        }
    }
}

#[test]
fn a_body_both_moved_and_read_puts_its_contacts_between_the_regions() {
    // Body 0 is read by the first contact (held there) and moved by
    // the second: both go between the regions.
    let (pos, _, mut rows) = lattice(80);
    rows[0].inv_mass_a = 0.0;
    let mut regions = ContactRegions::default();
    regions.build(&rows, &pos, &[], true, true);
    let touching_0: Vec<u32> = (0..rows.len() as u32)
        .filter(|&i| {
            let c = &rows[i as usize];
            c.a == 0 || c.b.dynamic_index() == Some(0)
        })
        .collect();
    assert!(touching_0.len() >= 2);
    for i in touching_0 {
        assert!(regions.picked[2].contains(&i), "row {i}");
    }
}

#[cfg(feature = "parallel")]
#[test]
fn the_regions_give_the_same_bits_on_any_number_of_threads() {
    for scene in [
        plain(80),
        scrambled(plain(80)),
        held_hub_and_deep(),
        random_pile(1),
        random_pile(2),
        scrambled(random_pile(3)),
    ] {
        let one = substep(&scene, Run::Step(false));
        assert!(one.3, "the pile splits");
        for threads in [1, 2, 4] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let many = pool.install(|| substep(&scene, Run::Step(true)));
            assert_eq!(many.0, one.0, "velocities, {threads} threads");
            assert_eq!(many.1, one.1, "pushes, {threads} threads");
            assert_eq!(many.2, one.2, "impulses, {threads} threads");
        }
    }
}

#[test]
fn bodies_in_no_order_of_their_places_split_at_the_middle_of_the_wider_side() {
    // The scrambled lattice (every other contact crosses the storage
    // halves) laid out wide, then tall: region 1 is the bodies from the
    // middle of the wider side on, the middle taken between the extremes
    // (far from the origin: the sides are differences, not sums).
    for (scale, wide) in [(Vec2::new(3.0, 1.0), true), (Vec2::new(1.0, 2.5), false)] {
        let (mut pos, _, rows, _, _) = scrambled(plain(80));
        for p in &mut pos {
            *p = *p * scale + Vec2::new(-300.0, -200.0);
        }
        let mut regions = ContactRegions::default();
        regions.build(&rows, &pos, &[], false, false);
        assert!(regions.is_split());
        let (axis, middle) = if wide {
            (0, -300.0 + 0.5 * 79.0 * 3.0)
        } else {
            (1, -200.0 + 0.5 * 79.0 * 2.5)
        };
        for (i, p) in pos.iter().enumerate() {
            let expected = u8::from(p[axis] >= middle);
            assert_eq!(
                regions.region[i], expected,
                "body {i} at {p} (wide: {wide})"
            );
        }
    }
}

/// A contact between dynamic bodies `a` and `b`.
fn pair(a: u32, b: u32) -> Constraint {
    let (_, _, rows) = lattice(2);
    Constraint {
        a,
        b: ColliderRef::dynamic(b),
        ..rows[1]
    }
}

#[test]
fn at_most_one_contact_in_max_crossing_across_the_storage_halves_splits_them() {
    // 4 096 bodies, stored in the reverse order of their places along x:
    // a split by place and one in storage order differ everywhere. 320
    // contacts: 10 across the halves (one in `MAX_CROSSING`) split in
    // storage order, 11 by place. Two more join the body at halfway and
    // the next, on the same side of the cut (no other names them).
    let bodies = SPLIT_BODIES;
    let half = halfway(bodies) as u32;
    let pos: Vec<Vec2> = (0..bodies)
        .map(|i| Vec2::new((bodies - i) as f32, 0.0))
        .collect();
    for crossing in [10, 11] {
        let mut rows: Vec<Constraint> = (0..crossing).map(|i| pair(i, half + 2 + i)).collect();
        rows.push(pair(half, half + 1));
        rows.push(pair(half + 1, half));
        let inside = (10 * MAX_CROSSING - rows.len()) as u32;
        rows.extend((0..inside).map(|i| pair(100 + i, 101 + i)));
        let mut regions = ContactRegions::default();
        regions.build(&rows, &pos, &[], false, false);
        assert!(regions.is_split());
        let middle = 0.5 + 0.5 * bodies as f32;
        for (i, p) in pos.iter().enumerate() {
            let expected = match crossing {
                10 => u8::from(i as u32 >= half),
                _ => u8::from(p.x >= middle),
            };
            assert_eq!(regions.region[i], expected, "body {i}, {crossing} across");
        }
    }
}

#[test]
fn a_row_holding_a_body_unannounced_in_either_half_is_noticed() {
    // Rows sorted in two halves side by side: a row that holds a body
    // (inverse mass zero) though the step did not say so, in the first
    // half of the rows or the second, gives the regions the build with
    // `holds` set gives.
    let (pos, _, rows) = lattice(80);
    for held in [0, rows.len() - 1] {
        let mut rows = rows.clone();
        rows[held].inv_mass_a = 0.0;
        let mut noticed = ContactRegions::default();
        noticed.build(&rows, &pos, &[], false, true);
        let mut told = ContactRegions::default();
        told.build(&rows, &pos, &[], true, true);
        assert_eq!(noticed.picked, told.picked, "row {held}");
    }
}
