//! Broad phase for moving bodies: a hashed uniform grid.
//!
//! Each step every moving proxy (a body's bounding box, grown by how far it
//! can move this step) is binned into the grid cells it covers; cells are
//! hashed into a table sized to the number of entries and grouped with a
//! counting sort, so the whole pass is linear in the number of bodies for
//! evenly spread bodies and allocates nothing once its buffers have grown.
//! The cell size follows the bodies: twice their mean proxy size, so a
//! typical proxy covers at most four cells. The rare proxy much larger than
//! that (over [`LARGE_PROXY_CELLS`] cells across) is tested against every
//! proxy instead of being binned into hundreds of cells.
//!
//! A pair sharing several cells is reported once, by the cell holding the
//! lower-left corner of the two boxes' intersection. Output order depends
//! only on the input, so the step stays deterministic.

use crate::Aabb;
use glam::Vec2;

/// A proxy covering more than this many cells along an axis is handled
/// apart, against every other proxy. 16: a 4 m platform among 0.2 m
/// circles (about 9 cells across) is binned like the rest; at 8 it was
/// tested against all 10 000 circles of a rain, every step (15 % of the
/// step with 20 such platforms, `passo bench platforms --above`).
pub(crate) const LARGE_PROXY_CELLS: i32 = 16;

/// In a grid bucket holding more than this many proxies plus one (bodies
/// spawned on one spot, a crushed pile), each proxy is paired with only
/// the next this many of the bucket: 64. Without the bound, `n` bodies on
/// one spot make `n²/2` pairs (10 000 circles: 50 million, 14 GB); with it
/// at most `64 n`, and the pile is pushed apart by the contacts it has
/// until no bucket is crowded. Ordinary scenes hold a few proxies per
/// bucket and never meet it.
pub(crate) const CROWDED_CELL: usize = 64;

#[derive(Clone, Copy, Debug)]
struct Entry {
    cell: (i32, i32),
    proxy: u32,
}

/// Scratch buffers of the grid, kept between steps.
#[derive(Clone, Debug, Default)]
pub(crate) struct BroadPhase {
    entries: Vec<Entry>,
    sorted: Vec<Entry>,
    starts: Vec<u32>,
    large: Vec<u32>,
    /// Buckets of the last search holding more than `CROWDED_CELL + 1`
    /// proxies, whose pairs were bounded.
    pub(crate) crowded: usize,
    /// Pairs found by each parallel task, concatenated in task order.
    #[cfg(feature = "parallel")]
    task_pairs: Vec<Vec<(u32, u32)>>,
}

#[inline]
fn bucket(cell: (i32, i32), mask: usize) -> usize {
    let h = (cell.0 as u32).wrapping_mul(0x9E37_79B1) ^ (cell.1 as u32).wrapping_mul(0x85EB_CA77);
    (h ^ (h >> 15)) as usize & mask
}

impl BroadPhase {
    /// Appends to `pairs` every `(i, j)`, `i < j`, whose boxes overlap,
    /// except pairs of two proxies marked in `asleep` (empty: none is).
    /// With `parallel` (and the feature), a large grid's cells are searched
    /// on rayon's pool in contiguous runs whose results are concatenated in
    /// order: the output is the same, in the same order.
    pub(crate) fn find_pairs(
        &mut self,
        proxies: &[Aabb],
        asleep: &[bool],
        parallel: bool,
        pairs: &mut Vec<(u32, u32)>,
    ) {
        let both_asleep =
            |a: u32, b: u32| !asleep.is_empty() && asleep[a as usize] && asleep[b as usize];
        if proxies.len() < 2 {
            return;
        }
        let mean_size =
            proxies.iter().map(|b| b.size().max_element()).sum::<f32>() / proxies.len() as f32;
        let cell_size = (2.0 * mean_size).max(1e-3);
        let inv = 1.0 / cell_size;
        let cell_of = |p: Vec2| (floor_i32(p.x * inv), floor_i32(p.y * inv));

        self.entries.clear();
        self.large.clear();
        for (i, b) in proxies.iter().enumerate() {
            let lo = cell_of(b.min);
            let hi = cell_of(b.max);
            // In i64: cells saturated at the ends of i32 must not overflow.
            let span = |lo: i32, hi: i32| i64::from(hi) - i64::from(lo);
            let limit = i64::from(LARGE_PROXY_CELLS);
            if span(lo.0, hi.0) >= limit || span(lo.1, hi.1) >= limit {
                self.large.push(i as u32);
                continue;
            }
            for cy in lo.1..=hi.1 {
                for cx in lo.0..=hi.0 {
                    self.entries.push(Entry {
                        cell: (cx, cy),
                        proxy: i as u32,
                    });
                }
            }
        }

        // Counting sort of the entries by bucket (stable: proxy order kept).
        let table = (2 * self.entries.len()).next_power_of_two().max(2);
        let mask = table - 1;
        self.starts.clear();
        self.starts.resize(table + 1, 0);
        for e in &self.entries {
            self.starts[bucket(e.cell, mask) + 1] += 1;
        }
        for k in 1..=table {
            self.starts[k] += self.starts[k - 1];
        }
        self.sorted.clear();
        self.sorted.resize(
            self.entries.len(),
            Entry {
                cell: (0, 0),
                proxy: 0,
            },
        );
        {
            // `starts[k]` is used as the write cursor of bucket k, then restored.
            for e in &self.entries {
                let k = bucket(e.cell, mask);
                self.sorted[self.starts[k] as usize] = *e;
                self.starts[k] += 1;
            }
            for k in (1..=table).rev() {
                self.starts[k] = self.starts[k - 1];
            }
            self.starts[0] = 0;
        }

        // The pairs of the buckets in `range`, in bucket order. In a crowded
        // bucket (bodies piled on one spot) each entry meets only the next
        // `CROWDED_CELL` ones: pairs and time stay linear in the bodies.
        let (sorted, starts) = (&self.sorted, &self.starts);
        let search = |range: std::ops::Range<usize>, out: &mut Vec<(u32, u32)>| {
            for k in range {
                let run = &sorted[starts[k] as usize..starts[k + 1] as usize];
                for (x, ea) in run.iter().enumerate() {
                    let end = (x + 1 + CROWDED_CELL).min(run.len());
                    for eb in &run[x + 1..end] {
                        if ea.cell != eb.cell || both_asleep(ea.proxy, eb.proxy) {
                            continue; // a hash collision between two cells, or resting
                        }
                        let (a, b) = (&proxies[ea.proxy as usize], &proxies[eb.proxy as usize]);
                        if a.overlaps(b) && cell_of(a.min.max(b.min)) == ea.cell {
                            out.push(ordered(ea.proxy, eb.proxy));
                        }
                    }
                }
            }
        };
        self.crowded = starts
            .windows(2)
            .filter(|w| (w[1] - w[0]) as usize > CROWDED_CELL + 1)
            .count();
        #[cfg(feature = "parallel")]
        if crate::parallel::goes_parallel(parallel, self.entries.len()) {
            use rayon::prelude::*;
            // Runs of buckets holding about PARALLEL_CHUNK entries each.
            let tasks = self
                .entries
                .len()
                .div_ceil(crate::constants::PARALLEL_CHUNK);
            let per_task = table.div_ceil(tasks);
            let tasks = table.div_ceil(per_task);
            if self.task_pairs.len() < tasks {
                self.task_pairs.resize_with(tasks, Vec::new);
            }
            self.task_pairs[..tasks]
                .par_iter_mut()
                .enumerate()
                .for_each(|(t, out)| {
                    out.clear();
                    search(t * per_task..((t + 1) * per_task).min(table), out);
                });
            for out in &self.task_pairs[..tasks] {
                pairs.extend_from_slice(out);
            }
        } else {
            search(0..table, pairs);
        }
        #[cfg(not(feature = "parallel"))]
        {
            let _ = parallel;
            search(0..table, pairs);
        }

        for &l in &self.large {
            let lb = &proxies[l as usize];
            for (j, b) in proxies.iter().enumerate() {
                let j = j as u32;
                // A pair of two large proxies is reported by the lower one.
                let j_is_large = self.large.binary_search(&j).is_ok();
                if j == l || (j_is_large && j < l) || both_asleep(l, j) {
                    continue;
                }
                if lb.overlaps(b) {
                    pairs.push(ordered(l, j));
                }
            }
        }
    }
}

/// `x.floor() as i32` without a call to `floorf` (x86-64's baseline has
/// no rounding instruction): truncate, then step down for negatives.
/// Saturates like `as` outside the `i32` range.
#[inline(always)]
fn floor_i32(x: f32) -> i32 {
    let t = x as i32;
    t.saturating_sub(i32::from((t as f32) > x))
}

fn ordered(a: u32, b: u32) -> (u32, u32) {
    if a < b { (a, b) } else { (b, a) }
}

#[cfg(test)]
mod tests {
    use super::*;
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
            let expected: Vec<_> = brute_force(&boxes)
                .into_iter()
                .filter(|&(a, b)| !(asleep[a as usize] && asleep[b as usize]))
                .collect();
            prop_assert_eq!(pairs, expected);
        }
    }

    #[cfg(feature = "parallel")]
    #[test]
    fn the_parallel_search_gives_the_same_pairs_in_the_same_order() {
        // Enough boxes for the thread pool, some asleep, spread like a pile.
        let mut seed = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 40) as f32 / (1u64 << 24) as f32
        };
        let mut boxes = Vec::new();
        let mut asleep = Vec::new();
        for _ in 0..6000 {
            let (x, y, r) = (next() * 40.0, next() * 40.0, 0.1 + next() * 0.3);
            boxes.push(Aabb::from_centre(Vec2::new(x, y), Vec2::splat(r)));
            asleep.push(next() < 0.3);
        }
        let (mut serial, mut threaded) = (Vec::new(), Vec::new());
        BroadPhase::default().find_pairs(&boxes, &asleep, false, &mut serial);
        let mut grid = BroadPhase::default();
        for _ in 0..2 {
            threaded.clear();
            grid.find_pairs(&boxes, &asleep, true, &mut threaded);
            assert!(serial.len() > 1000);
            assert_eq!(threaded, serial);
        }
    }

    #[test]
    fn fast_floor_matches_floor() {
        for x in [
            -2.5f32, -2.0, -1.0000001, -0.5, -0.0, 0.0, 0.3, 1.0, 1.9999, 7e8, -7e8, 3e10, -3e10,
        ] {
            assert_eq!(floor_i32(x), x.floor() as i32, "{x}");
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
}
