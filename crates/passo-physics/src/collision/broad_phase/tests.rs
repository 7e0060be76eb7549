//! Tests of `broad_phase`.

use super::*;
use crate::testing::uniform;
use proptest::prelude::*;

fn brute_force(proxies: &[Aabb]) -> Vec<(u32, u32)> {
    let mut pairs = Vec::new();
    for i in 0..proxies.len() {
        for j in i + 1..proxies.len() {
            if proxies[i].overlaps(&proxies[j]) {
                pairs.push((i as u32, j as u32));
            }
        }
    }
    pairs
}

/// [`brute_force`] without the pairs of two proxies marked asleep.
fn brute_force_awake(proxies: &[Aabb], asleep: &[bool]) -> Vec<(u32, u32)> {
    brute_force(proxies)
        .into_iter()
        .filter(|&(a, b)| asleep.is_empty() || !(asleep[a as usize] && asleep[b as usize]))
        .collect()
}

fn grid_pairs(proxies: &[Aabb]) -> Vec<(u32, u32)> {
    let mut pairs = Vec::new();
    BroadPhase::default().find_pairs(proxies, &[], false, &mut pairs);
    let count = pairs.len();
    pairs.sort_unstable();
    pairs.dedup();
    assert_eq!(pairs.len(), count, "a pair was reported twice");
    pairs
}

fn aabb() -> impl Strategy<Value = Aabb> {
    // Mostly small boxes over a region, a few large ones, some far away.
    (
        -50.0f32..50.0,
        -50.0f32..50.0,
        prop_oneof![8 => 0.01f32..2.0, 1 => 2.0f32..60.0],
        prop_oneof![8 => 0.01f32..2.0, 1 => 2.0f32..60.0],
    )
        .prop_map(|(x, y, w, h)| Aabb {
            min: Vec2::new(x, y),
            max: Vec2::new(x + w, y + h),
        })
}

#[test]
fn cells_sharing_a_crowded_bucket_keep_every_pair() {
    // Seventy cells far apart whose hashes share one bucket, each with
    // two small overlapping proxies: 140 entries in the bucket, but
    // two a cell. The first proxies of every cell come first, so each
    // proxy's partner is seventy entries after it in the bucket's
    // (proxy) order, beyond a bound of the bucket's next 64 entries.
    let size = 0.5;
    let cell = 2.0 * size;
    let mask = (2 * 140usize).next_power_of_two() - 1;
    let cells: Vec<(i32, i32)> = (0..)
        .map(|i| (i % 1000 * 7, i / 1000 * 7))
        .filter(|&c| bucket(c, mask) == 0)
        .take(70)
        .collect();
    let at = |c: (i32, i32), dx: f32| {
        let min = Vec2::new(c.0 as f32 * cell + 0.1 + dx, c.1 as f32 * cell + 0.1);
        Aabb {
            min,
            max: min + Vec2::splat(size),
        }
    };
    let proxies: Vec<Aabb> = [0.0, 0.2]
        .iter()
        .flat_map(|&dx| cells.iter().map(move |&c| at(c, dx)))
        .collect();
    let mut grid = BroadPhase::default();
    let mut pairs = Vec::new();
    grid.find_pairs(&proxies, &[], false, &mut pairs);
    pairs.sort_unstable();
    assert_eq!(pairs, brute_force(&proxies));
    assert_eq!(pairs.len(), 70);
    assert_eq!(grid.crowded, 0, "no cell is crowded");
}

#[test]
fn an_uncapped_proxy_meets_every_proxy_of_a_crowded_cell() {
    // 200 small boxes crowded on one spot and a platform's box across
    // all of them (first in the sweep: its left edge is the lowest).
    let mut next = uniform(7);
    let mut proxies: Vec<Aabb> = (0..200)
        .map(|_| {
            let centre = Vec2::splat(10.0) + Vec2::new(next(), next()) * 0.1;
            Aabb::from_centre(centre, Vec2::splat(0.1))
        })
        .collect();
    proxies.push(Aabb {
        min: Vec2::new(9.0, 9.95),
        max: Vec2::new(11.5, 10.05),
    });
    proxies.push(Aabb::from_centre(Vec2::splat(1e5), Vec2::splat(0.1)));
    let platform = 200u32;
    let platform_pairs = |uncapped: bool| {
        let mut grid = BroadPhase::default();
        if uncapped {
            grid.uncapped = vec![false; proxies.len()];
            grid.uncapped[platform as usize] = true;
        }
        let mut pairs = Vec::new();
        grid.find_pairs(&proxies, &[], false, &mut pairs);
        assert!(grid.crowded > 0, "a crowded cell");
        pairs
            .iter()
            .filter(|&&(a, b)| a == platform || b == platform)
            .count()
    };
    assert_eq!(platform_pairs(true), 200);
    assert!(platform_pairs(false) < 200, "the bound applies otherwise");
}

#[test]
fn immovable_proxies_never_pair_with_each_other() {
    // 300 kinematic boxes on one spot (uncapped, so every one of them
    // used to meet all the others) and 10 small dynamic ones among them.
    let mut next = uniform(11);
    let proxies: Vec<Aabb> = (0..310)
        .map(|_| {
            let centre = Vec2::splat(3.0) + Vec2::new(next(), next()) * 0.05;
            Aabb::from_centre(centre, Vec2::splat(0.5))
        })
        .collect();
    let kinematic = |p: u32| p < 300;
    let mut grid = BroadPhase::default();
    grid.uncapped = (0..310).map(kinematic).collect();
    grid.immovable = grid.uncapped.clone();
    let mut pairs = Vec::new();
    grid.find_pairs(&proxies, &[], false, &mut pairs);
    assert!(grid.crowded > 0, "a crowded cell");
    assert!(pairs.iter().all(|&(a, b)| !(kinematic(a) && kinematic(b))));
    // Each dynamic box still meets every kinematic one, and the other
    // dynamic ones (nine, under the crowded-cell bound).
    for d in 300..310u32 {
        let met = pairs.iter().filter(|&&(a, b)| a == d || b == d).count();
        assert_eq!(met, 300 + 9, "proxy {d}");
    }
    // A kinematic sensor (uncapped, not immovable) meets them all.
    grid.immovable[0] = false;
    pairs.clear();
    grid.find_pairs(&proxies, &[], false, &mut pairs);
    let sensor = pairs.iter().filter(|&&(a, b)| a == 0 || b == 0).count();
    assert_eq!(sensor, 309);
}

#[test]
fn a_crowded_cell_of_a_dense_stream_keeps_every_pair() {
    // A stream of fast bodies: proxies 0.42 m wide and 2 m tall (long
    // with their travel), 0.4 m apart, each overlapping 26 others. The
    // cells (twice the mean proxy size) hold over a hundred proxies each,
    // but no proxy has more than `CROWDED_CELL` pairs: every pair is
    // found. They are stored in a scrambled order, as a scene's bodies
    // may be. One proxy far away sends the search to the hashed grid.
    let mut proxies: Vec<Aabb> = (0..900)
        .map(|i| {
            let at = i * 7919 % 900;
            let min = Vec2::new((at % 30) as f32 * 0.4, (at / 30) as f32 * 0.4);
            Aabb {
                min,
                max: min + Vec2::new(0.42, 2.0),
            }
        })
        .collect();
    proxies.push(Aabb {
        min: Vec2::splat(1e5),
        max: Vec2::splat(1e5 + 2.0),
    });
    let mut grid = BroadPhase::default();
    let mut pairs = Vec::new();
    grid.find_pairs(&proxies, &[], false, &mut pairs);
    assert!(grid.crowded > 0, "the cells are crowded");
    pairs.sort_unstable();
    assert_eq!(pairs, brute_force(&proxies));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]
    #[test]
    fn grid_finds_exactly_the_pairs_brute_force_finds(
        proxies in prop::collection::vec(aabb(), 0..300)
    ) {
        prop_assert_eq!(grid_pairs(&proxies), brute_force(&proxies));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(100))]
    #[test]
    fn pairs_of_two_sleeping_proxies_are_left_out(
        proxies in prop::collection::vec((aabb(), any::<bool>()), 0..200)
    ) {
        let (boxes, asleep): (Vec<Aabb>, Vec<bool>) = proxies.into_iter().unzip();
        let mut pairs = Vec::new();
        BroadPhase::default().find_pairs(&boxes, &asleep, false, &mut pairs);
        pairs.sort_unstable();
        let expected = brute_force_awake(&boxes, &asleep);
        prop_assert_eq!(pairs, expected);
    }
}

/// The pairs of the corner grid, sorted, checked to come once each;
/// `None` when it declines the proxies.
fn corner_pairs(proxies: &[Aabb], asleep: &[bool]) -> Option<Vec<(u32, u32)>> {
    let mean = proxies.iter().map(|b| b.size().max_element()).sum::<f32>() / proxies.len() as f32;
    let mut pairs = Vec::new();
    if !BroadPhase::default().find_pairs_by_corner(proxies, asleep, false, mean, &mut pairs) {
        assert!(pairs.is_empty(), "declined after appending pairs");
        return None;
    }
    let count = pairs.len();
    pairs.sort_unstable();
    pairs.dedup();
    assert_eq!(pairs.len(), count, "a pair was reported twice");
    Some(pairs)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]
    #[test]
    fn the_corner_grid_finds_exactly_the_pairs_brute_force_finds(
        proxies in prop::collection::vec(
            ((-8.0f32..8.0, -8.0f32..8.0, 0.3f32..0.6, 0.3f32..0.6), any::<bool>()),
            2..300,
        ),
        some_asleep in any::<bool>(),
    ) {
        let boxes: Vec<Aabb> = proxies
            .iter()
            .map(|&((x, y, w, h), _)| Aabb { min: Vec2::new(x, y), max: Vec2::new(x + w, y + h) })
            .collect();
        let asleep: Vec<bool> = match some_asleep {
            true => proxies.iter().map(|p| p.1).collect(),
            false => Vec::new(),
        };
        let expected = brute_force_awake(&boxes, &asleep);
        // Sizes within a factor two of each other over a small region:
        // the corner grid takes them.
        prop_assert_eq!(corner_pairs(&boxes, &asleep), Some(expected));
    }
}

#[test]
fn the_corner_grid_finds_boxes_touching_on_cell_boundaries() {
    // A pyramid's boxes: unit squares side by side and half a box
    // offset row to row, touching exactly; at the origin and far from it.
    for origin in [Vec2::ZERO, Vec2::new(40_000.0, -30_000.0)] {
        let unit = |x: f32, y: f32| Aabb {
            min: origin + Vec2::new(x, y),
            max: origin + Vec2::new(x + 1.0, y + 1.0),
        };
        let mut boxes = Vec::new();
        for row in 0..12 {
            for i in 0..12 - row {
                boxes.push(unit(i as f32 + 0.5 * row as f32, row as f32));
            }
        }
        let pairs = corner_pairs(&boxes, &[]).expect("equal boxes suit the corner grid");
        assert_eq!(pairs, brute_force(&boxes));
        assert!(pairs.len() > 150, "{}", pairs.len());
    }
}

#[test]
fn the_corner_grid_declines_unequal_far_or_crowded_proxies() {
    let small = |x: f32| Aabb::from_centre(Vec2::new(x, 0.0), Vec2::splat(0.1));
    let mut platform = vec![small(0.0), small(0.5), small(1.0)];
    platform.push(Aabb::from_centre(Vec2::ZERO, Vec2::new(4.0, 0.1)));
    assert_eq!(
        corner_pairs(&platform, &[]),
        None,
        "a platform among circles"
    );
    let far = [small(0.0), small(0.1), small(1.0e6)];
    assert_eq!(corner_pairs(&far, &[]), None, "a body flung far away");
    let spot = vec![small(0.0); CROWDED_CELL + 2];
    assert_eq!(corner_pairs(&spot, &[]), None, "bodies on one spot");
    // Whatever grid finds them, the pairs are the same.
    for boxes in [&platform[..], &far[..]] {
        assert_eq!(grid_pairs(boxes), brute_force(boxes));
    }
}

#[cfg(feature = "parallel")]
#[test]
fn the_parallel_search_gives_the_same_pairs_in_the_same_order() {
    // Enough boxes for the thread pool, some asleep, spread like a pile.
    let mut next = uniform(0x9E37_79B9_7F4A_7C15);
    let mut boxes = Vec::new();
    let mut asleep = Vec::new();
    for _ in 0..6000 {
        let (x, y, r) = (next() * 40.0, next() * 40.0, 0.1 + next() * 0.3);
        boxes.push(Aabb::from_centre(Vec2::new(x, y), Vec2::splat(r)));
        asleep.push(next() < 0.3);
    }
    let same_both_ways = |boxes: &[Aabb], asleep: &[bool]| {
        let (mut serial, mut threaded) = (Vec::new(), Vec::new());
        BroadPhase::default().find_pairs(boxes, asleep, false, &mut serial);
        let mut grid = BroadPhase::default();
        for _ in 0..2 {
            threaded.clear();
            grid.find_pairs(boxes, asleep, true, &mut threaded);
            assert!(serial.len() > 1000);
            assert_eq!(threaded, serial);
        }
        grid.crowded
    };
    assert_eq!(same_both_ways(&boxes, &asleep), 0);
    // With a crowded spot of 500 and one box far away (the hashed grid
    // and its crowded cells), too.
    for b in &mut boxes[..500] {
        let jitter = Vec2::new(next(), next()) * 0.05;
        *b = Aabb::from_centre(Vec2::splat(20.0) + jitter, Vec2::splat(0.2));
    }
    boxes.push(Aabb::from_centre(Vec2::splat(1e5), Vec2::splat(0.2)));
    asleep.push(false);
    assert!(same_both_ways(&boxes, &asleep) > 0, "a crowded cell");
}

#[test]
fn fast_floor_matches_floor() {
    for x in [
        -2.5f32, -2.0, -1.0000001, -0.5, -0.0, 0.0, 0.3, 1.0, 1.9999, 7e8, -7e8, 3e10, -3e10,
    ] {
        assert_eq!(floor_i32(x), x.floor() as i32, "{x}");
    }
}

/// `n` small boxes (0.2–0.4 m) over a 40 m square and `bars` long ones
/// (`length` m by 0.3 m) across it; some marked asleep when `sleepy`.
fn bars_among_small_boxes(
    n: usize,
    bars: usize,
    length: f32,
    seed: u64,
    sleepy: bool,
) -> (Vec<Aabb>, Vec<bool>) {
    let mut next = uniform(seed);
    let mut boxes = Vec::new();
    let mut asleep = Vec::new();
    for i in 0..n + bars {
        let min = Vec2::new(next(), next()) * 40.0;
        let size = if i % (n / bars.max(1) + 1) == 0 && boxes.len() < n + bars {
            Vec2::new(length, 0.3)
        } else {
            Vec2::splat(0.2 + 0.2 * next())
        };
        boxes.push(Aabb {
            min,
            max: min + size,
        });
        asleep.push(sleepy && next() < 0.5);
    }
    (boxes, asleep)
}

#[test]
fn long_proxies_meet_their_neighbours_not_every_proxy() {
    // 3 000 small boxes and 30 bars 30 m long: each bar covers a few
    // dozen cells and looks only in those.
    for sleepy in [false, true] {
        let (boxes, asleep) = bars_among_small_boxes(3_000, 30, 30.0, 11, sleepy);
        let mut grid = BroadPhase::default();
        let mut pairs = Vec::new();
        grid.find_pairs(&boxes, &asleep, false, &mut pairs);
        let count = pairs.len();
        pairs.sort_unstable();
        pairs.dedup();
        assert_eq!(pairs.len(), count, "a pair was reported twice");
        let expected = brute_force_awake(&boxes, &asleep);
        assert_eq!(pairs, expected);
        let large = boxes.iter().filter(|b| b.size().x > 10.0).count();
        assert_eq!(
            grid.large.len(),
            large,
            "the bars, and only they, are large"
        );
        assert!(
            grid.large_tests < large * boxes.len() / 10,
            "{} tests, against {} for every bar with every proxy",
            grid.large_tests,
            large * boxes.len()
        );
        assert_eq!(grid.crowded, 0);
    }
}

#[test]
fn a_proxy_covering_more_cells_than_there_are_proxies_tests_each_once() {
    // Forty small boxes on a 10 km square: the square sets the cells
    // (about 490 m) and covers some 21 x 21 of them, more than the 41
    // proxies, so it tests each proxy instead of looking in each cell.
    let mut boxes: Vec<Aabb> = (0..40)
        .map(|i| Aabb::from_centre(Vec2::new(i as f32 * 0.3, 0.1), Vec2::splat(0.2)))
        .collect();
    boxes.push(Aabb {
        min: Vec2::splat(-5_000.0),
        max: Vec2::splat(5_000.0),
    });
    let mut grid = BroadPhase::default();
    let mut pairs = Vec::new();
    grid.find_pairs(&boxes, &[], false, &mut pairs);
    pairs.sort_unstable();
    assert_eq!(pairs, brute_force(&boxes));
    assert_eq!(pairs.iter().filter(|p| p.1 == 40).count(), 40);
    assert_eq!(grid.large, [40]);
    assert_eq!(grid.large_tests, boxes.len());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(100))]
    #[test]
    fn long_proxies_find_exactly_the_pairs_brute_force_finds(
        n in 1usize..300,
        bars in 0usize..12,
        length in 2.0f32..200.0,
        seed in any::<u64>(),
        sleepy in any::<bool>(),
    ) {
        let (boxes, asleep) = bars_among_small_boxes(n, bars, length, seed, sleepy);
        let mut pairs = Vec::new();
        BroadPhase::default().find_pairs(&boxes, &asleep, false, &mut pairs);
        pairs.sort_unstable();
        let expected = brute_force_awake(&boxes, &asleep);
        prop_assert_eq!(pairs, expected);
    }
}

#[test]
fn touching_and_identical_boxes_are_pairs() {
    let unit = |x: f32, y: f32| Aabb {
        min: Vec2::new(x, y),
        max: Vec2::new(x + 1.0, y + 1.0),
    };
    let proxies = [
        unit(0.0, 0.0),
        unit(1.0, 0.0),
        unit(0.0, 0.0),
        unit(5.0, 5.0),
    ];
    assert_eq!(grid_pairs(&proxies), [(0, 1), (0, 2), (1, 2)]);
}
