//! Broad phase for moving bodies: a uniform grid.
//!
//! When the proxies are of similar sizes (none more than twice their mean
//! size) and spread over a bounded region, each is binned once, by the cell
//! of its lower-left corner, in a dense grid of cells as large as the
//! largest proxy: two overlapping proxies then have their corners in the
//! same or neighbouring cells, so each proxy is tested against the rest of
//! its own cell, the cell to its right and the three above it (the other
//! half of the neighbourhood finds it in turn), and every pair is found
//! exactly once. The cells are laid out row by row, with an empty column
//! on each side and an empty row on top so that every cell has those
//! neighbours, and the boxes are copied in cell order, so those are two
//! runs of contiguous boxes. (A rain of 10 000 circles: the pair search
//! went from 23 % to 11 % of a step that took 17 % less time; the copy
//! in cell order, the padding and a box test with no early exit
//! ([`Aabb::overlaps`]) took it from 14 % to 10 %.)
//!
//! Otherwise (a few large platforms among small bodies, bodies flung far
//! apart, bodies piled on one spot) every moving proxy (a body's bounding
//! box, swept along how far it can move this step) is binned into the grid
//! cells it covers; cells are
//! hashed into a table sized to the number of entries and grouped with a
//! counting sort, so the whole pass is linear in the number of bodies for
//! evenly spread bodies and allocates nothing once its buffers have grown.
//! The cell size follows the bodies: twice their mean proxy size, so a
//! typical proxy covers at most four cells. The rare proxy much larger than
//! that (over [`LARGE_PROXY_CELLS`] cells across) is not binned: once the
//! others are, it looks them up in the cells it covers (or, if it covers
//! more cells than there are proxies, tests every proxy), so a 30 m
//! platform among 10 000 small bodies meets the few hundred near it, not
//! all of them, and never crowds a cell. A cell holding
//! more than [`CROWDED_CELL`] + 1 proxies is swept along x instead, with
//! its proxies' pairs bounded.
//!
//! A pair sharing several cells is reported once, by the cell holding the
//! lower-left corner of the two boxes' intersection. Output order depends
//! only on the input, so the step stays deterministic.

use crate::Aabb;
use crate::parallel::for_chunks;
use glam::Vec2;

/// A proxy covering more than this many cells along an axis is handled
/// apart: it looks up the proxies binned in the cells it covers. 16: a 4 m
/// platform among 0.2 m circles (about 9 cells across) is binned like the
/// rest. (When such a proxy was tested against every proxy, a threshold of
/// 8 cost 15 % of the step with 20 such platforms among 10 000 circles,
/// `passo bench platforms --above`.)
pub(crate) const LARGE_PROXY_CELLS: i32 = 16;

/// Pairs a proxy may make with the proxies after it in one crowded grid
/// cell: 64. A cell holding more than this many proxies plus one is
/// crowded: bodies spawned on one spot, a crushed pile, or a dense stream
/// of fast bodies whose long proxies make the cells large. Its proxies are
/// swept along x (in order of their left edges), so each meets only those
/// that overlap it in x, looking at most [`CROWDED_SWEEP`] ahead, and each
/// meets at most this many there (whichever cell reports each pair; a
/// kinematic body's pairs are never bounded), so that the work per cell
/// is bounded too. Without the bound, `n` bodies on one spot make `n²/2` pairs
/// (10 000 circles: 50 million, 14 GB); with it at most `64 n` for each
/// cell a proxy covers (four for a proxy no larger than twice the mean,
/// which sets the cell size), and the pile is pushed apart by the contacts
/// it has until no cell is crowded. Ordinary scenes hold a few proxies per
/// cell and never meet it.
pub(crate) const CROWDED_CELL: usize = 64;

/// Proxies of a crowded cell that the sweep looks at after each one, at
/// most: 16 × [`CROWDED_CELL`]. Keeps a cell's search linear in its
/// proxies even when many overlap one another in x and not in y.
const CROWDED_SWEEP: usize = 16 * CROWDED_CELL;

/// The corner grid spans at most this many cells per proxy (plus 1 024),
/// before its padding (a column each side and a row on top, which at most
/// sextuple a grid one cell wide): bodies spread wider are binned in the
/// hashed grid instead.
const CORNER_CELLS_PER_PROXY: usize = 4;

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
    /// Boxes the large proxies of the last search were tested against.
    pub(crate) large_tests: usize,
    /// Cells of the last search holding more than `CROWDED_CELL + 1`
    /// proxies, whose pairs were bounded.
    pub(crate) crowded: usize,
    /// Per proxy: whether its pairs are never bounded in a crowded cell
    /// (a kinematic body, which every body its box overlaps must meet, as
    /// a wall); empty: no such proxy. Set by the caller before a search.
    pub(crate) uncapped: Vec<bool>,
    /// Per proxy: whether it is a kinematic body that is no sensor. Two
    /// such never meet (the narrow phase skips the pair), so the search
    /// does not pair them: a pile of kinematic bodies on one spot, whose
    /// pairs are uncapped, cost a step `O(k²)` pairs for nothing. Empty:
    /// no such proxy. Set by the caller with `uncapped`.
    pub(crate) immovable: Vec<bool>,
    /// Corner grid: each proxy's cell, row by row.
    cell_of: Vec<u32>,
    /// Corner grid: the proxies sorted by cell (stable).
    order: Vec<u32>,
    /// Corner grid: the boxes and cells of `order`, in its order, so the
    /// search reads each cell's candidates from contiguous memory.
    sorted_boxes: Vec<Aabb>,
    sorted_cells: Vec<u32>,
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
        self.large_tests = 0;
        if proxies.len() < 2 {
            return;
        }
        let mean_size =
            proxies.iter().map(|b| b.size().max_element()).sum::<f32>() / proxies.len() as f32;
        if self.find_pairs_by_corner(proxies, asleep, parallel, mean_size, pairs) {
            self.crowded = 0;
            return;
        }
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

        // A bucket holding more than `CROWDED_CELL + 1` entries is sorted
        // by cell, then by the proxies' left edges (then proxy): several
        // cells may share a bucket, and each cell's entries are then side by
        // side, ready for a sweep along x. Ordinary scenes have no such
        // bucket.
        self.crowded = 0;
        let left = |e: &Entry| proxies[e.proxy as usize].min.x;
        for k in 0..table {
            let run = &mut self.sorted[self.starts[k] as usize..self.starts[k + 1] as usize];
            if run.len() > CROWDED_CELL + 1 {
                run.sort_unstable_by(|a, b| {
                    (a.cell.cmp(&b.cell))
                        .then(left(a).total_cmp(&left(b)))
                        .then(a.proxy.cmp(&b.proxy))
                });
                self.crowded += run
                    .chunk_by(|a, b| a.cell == b.cell)
                    .filter(|cell| cell.len() > CROWDED_CELL + 1)
                    .count();
            }
        }

        // The pairs of the buckets in `range`, in bucket order.
        let (sorted, starts) = (&self.sorted, &self.starts);
        // Reported in the cell of the overlap's lower-left corner only;
        // never between two immovable proxies.
        let immovable = |p: u32| self.immovable.get(p as usize) == Some(&true);
        let pair = |ea: &Entry, eb: &Entry, out: &mut Vec<(u32, u32)>| {
            let (a, b) = (&proxies[ea.proxy as usize], &proxies[eb.proxy as usize]);
            if cell_of(a.min.max(b.min)) == ea.cell && !(immovable(ea.proxy) && immovable(eb.proxy))
            {
                out.push(ordered(ea.proxy, eb.proxy));
            }
        };
        let uncapped = &self.uncapped;
        let free = |p: u32| uncapped.get(p as usize) == Some(&true);
        let search = |range: std::ops::Range<usize>, out: &mut Vec<(u32, u32)>| {
            for k in range {
                let run = &sorted[starts[k] as usize..starts[k + 1] as usize];
                if run.len() <= CROWDED_CELL + 1 {
                    // Every two entries of the same cell.
                    for (x, ea) in run.iter().enumerate() {
                        for eb in &run[x + 1..] {
                            if ea.cell != eb.cell || both_asleep(ea.proxy, eb.proxy) {
                                continue; // a hash collision between two cells, or resting
                            }
                            if proxies[ea.proxy as usize].overlaps(&proxies[eb.proxy as usize]) {
                                pair(ea, eb, out);
                            }
                        }
                    }
                    continue;
                }
                // Sorted by cell, then left edge: each cell swept along x.
                for cell in run.chunk_by(|a, b| a.cell == b.cell) {
                    let crowded = cell.len() > CROWDED_CELL + 1;
                    for (x, ea) in cell.iter().enumerate() {
                        let a = &proxies[ea.proxy as usize];
                        let mut others = &cell[x + 1..];
                        if crowded {
                            others = &others[..others.len().min(CROWDED_SWEEP)];
                        }
                        let capped = crowded && !free(ea.proxy);
                        // Overlapping proxies met here, whichever cell
                        // reports the pair, uncapped ones aside (looked
                        // for to the end of the sweep).
                        let mut met = 0;
                        for eb in others {
                            let b = &proxies[eb.proxy as usize];
                            if b.min.x > a.max.x {
                                break; // so does every later one: none overlaps A
                            }
                            let full = capped && met == CROWDED_CELL;
                            if full && uncapped.is_empty() {
                                break; // enough for this proxy in this cell
                            }
                            let always = free(eb.proxy);
                            if (full && !always)
                                || both_asleep(ea.proxy, eb.proxy)
                                || !a.overlaps(b)
                            {
                                continue;
                            }
                            pair(ea, eb, out);
                            met += usize::from(!always);
                        }
                    }
                }
            }
        };
        #[cfg(feature = "parallel")]
        if crate::parallel::goes_parallel(parallel, self.entries.len()) {
            // Runs of buckets holding about PARALLEL_CHUNK entries each.
            let tasks = self
                .entries
                .len()
                .div_ceil(crate::constants::PARALLEL_CHUNK);
            let per_task = table.div_ceil(tasks);
            in_tasks(&mut self.task_pairs, table, per_task, search, pairs);
        } else {
            search(0..table, pairs);
        }
        #[cfg(not(feature = "parallel"))]
        {
            let _ = parallel;
            search(0..table, pairs);
        }

        let mut tests = 0;
        for (x, &l) in self.large.iter().enumerate() {
            let lb = &proxies[l as usize];
            let (lo, hi) = (cell_of(lb.min), cell_of(lb.max));
            // In i64, each span at most 2^32: their product is formed only
            // when both are at most the number of proxies.
            let n = proxies.len() as i64;
            let (w, h) = (
                i64::from(hi.0) - i64::from(lo.0) + 1,
                i64::from(hi.1) - i64::from(lo.1) + 1,
            );
            if w > n || h > n || w * h > n {
                // Larger than the bodies' whole spread in cells: every
                // proxy once (the large ones below).
                for (j, b) in proxies.iter().enumerate() {
                    let j = j as u32;
                    if self.large.binary_search(&j).is_err() && !both_asleep(l, j) && lb.overlaps(b)
                    {
                        pairs.push(ordered(l, j));
                    }
                }
                tests += proxies.len();
            } else {
                // The binned proxies of the cells it covers, each pair in
                // the cell of its overlap's lower-left corner.
                for cy in lo.1..=hi.1 {
                    for cx in lo.0..=hi.0 {
                        let k = bucket((cx, cy), mask);
                        let run = &sorted[starts[k] as usize..starts[k + 1] as usize];
                        tests += run.len();
                        let here = Entry {
                            cell: (cx, cy),
                            proxy: l,
                        };
                        for e in run {
                            let b = &proxies[e.proxy as usize];
                            if e.cell == here.cell && !both_asleep(l, e.proxy) && lb.overlaps(b) {
                                pair(&here, e, pairs);
                            }
                        }
                    }
                }
            }
            // Two large proxies: reported by the lower one.
            for &m in &self.large[x + 1..] {
                if !both_asleep(l, m) && lb.overlaps(&proxies[m as usize]) {
                    pairs.push(ordered(l, m));
                }
            }
            tests += self.large.len() - x - 1;
        }
        self.large_tests = tests;
    }

    /// The corner grid (see the module's documentation): appends the pairs
    /// and returns `true`, or returns `false` having appended nothing when
    /// the proxies do not suit it: sizes too unequal, spread too far for a
    /// dense grid of at most [`CORNER_CELLS_PER_PROXY`] cells a proxy (before
    /// padding), a
    /// coordinate not finite, or a cell holding more than `CROWDED_CELL + 1`
    /// proxies (the hashed grid bounds their pairs). Its cells are no larger
    /// than the hashed grid's, so a pile can crowd a hashed cell and no
    /// corner cell: the corner grid then finds all of its pairs, where the
    /// hashed grid would have bounded each proxy's to `CROWDED_CELL`.
    fn find_pairs_by_corner(
        &mut self,
        proxies: &[Aabb],
        asleep: &[bool],
        parallel: bool,
        mean_size: f32,
        pairs: &mut Vec<(u32, u32)>,
    ) -> bool {
        let Some(CornerBounds { largest, lo, hi }) = CornerBounds::find(proxies, parallel) else {
            return false;
        };
        if largest > 2.0 * f64::from(mean_size) || largest <= 0.0 {
            return false;
        }
        // Overlapping proxies' lower-left corners are at most `largest` apart
        // along each axis, less than one cell: neighbouring cells at most.
        let cell = largest * (1.0 + 1e-6);
        let inv = 1.0 / cell;
        let (w, h) = (
            ((hi[0] - lo[0]) * inv).floor() + 1.0,
            ((hi[1] - lo[1]) * inv).floor() + 1.0,
        );
        if w * h > (CORNER_CELLS_PER_PROXY * proxies.len() + 1024) as f64 {
            return false;
        }
        // An empty column on each side and an empty row on top: every
        // occupied cell has a right neighbour and three above, with no test.
        let (w, h) = (w as usize, h as usize);
        let row_len = w + 2;
        let cells = row_len * (h + 1);

        // Each proxy's cell, then the proxies sorted by cell (a counting
        // sort): `starts[c]` counts cell c's proxies, then holds the end of
        // its run and, once the proxies are dealt from the last to the
        // first, its start (`starts[cells]`: the end of the last).
        // Every entry is written below: only sized.
        self.cell_of.resize(proxies.len(), 0);
        for_chunks(
            parallel,
            (&mut self.cell_of[..], proxies),
            |_, (cells, boxes)| {
                for (c, b) in cells.iter_mut().zip(boxes) {
                    // The ratio is at least zero (`v >= lo`) and within the
                    // grid (cells are limited, above): `i32` holds it, and
                    // converts in one instruction where `usize` takes a dozen.
                    let axis = |k: usize, v: f32, n: usize| {
                        (((f64::from(v) - lo[k]) * inv) as i32 as usize).min(n - 1)
                    };
                    *c = (axis(1, b.min.y, h) * row_len + axis(0, b.min.x, w) + 1) as u32;
                }
                0
            },
        );
        self.starts.clear();
        self.starts.resize(cells + 1, 0);
        for &c in &self.cell_of {
            self.starts[c as usize] += 1;
        }
        let (mut end, mut crowded) = (0, false);
        for s in &mut self.starts[..cells] {
            crowded |= *s as usize > CROWDED_CELL + 1;
            end += *s;
            *s = end;
        }
        if crowded {
            return false;
        }
        self.starts[cells] = end;
        // Every entry of the sorted arrays is written below: they are only
        // sized here (no clearing, which wrote each entry twice a step).
        self.order.resize(proxies.len(), 0);
        for (i, &c) in self.cell_of.iter().enumerate().rev() {
            let slot = &mut self.starts[c as usize];
            *slot -= 1;
            self.order[*slot as usize] = i as u32;
        }
        // The boxes and cells in that order, gathered in chunks on the pool
        // (the deal above writes one index a proxy, not its box).
        let empty = Aabb::from_centre(Vec2::ZERO, Vec2::ZERO);
        self.sorted_boxes.resize(proxies.len(), empty);
        self.sorted_cells.resize(proxies.len(), 0);
        let cell_of = &self.cell_of[..];
        let sorted = (
            &mut self.sorted_boxes[..],
            &mut self.sorted_cells[..],
            &self.order[..],
        );
        for_chunks(parallel, sorted, |_, (boxes, cells, order)| {
            for ((b, c), &i) in boxes.iter_mut().zip(cells.iter_mut()).zip(order) {
                (*b, *c) = (proxies[i as usize], cell_of[i as usize]);
            }
            0
        });

        let (order, starts) = (&self.order, &self.starts);
        let (boxes, sorted_cells) = (&self.sorted_boxes, &self.sorted_cells);
        // The pairs of the proxies at `range` of the sorted order, each with
        // the later proxies of its cell, the cell to its right and the three
        // cells above: two runs of the sorted boxes.
        let search = |range: std::ops::Range<usize>, out: &mut Vec<(u32, u32)>| {
            for k in range {
                let c = sorted_cells[k] as usize;
                let (a, box_a) = (order[k], &boxes[k]);
                let right = k + 1..starts[c + 2] as usize;
                let above = starts[c + row_len - 1] as usize..starts[c + row_len + 2] as usize;
                for run in [right, above] {
                    let (ids, run) = (&order[run.clone()], &boxes[run]);
                    pairs_in_run(a, box_a, ids, run, asleep, out);
                }
            }
        };
        #[cfg(feature = "parallel")]
        if crate::parallel::goes_parallel(parallel, proxies.len()) {
            let chunk = crate::constants::PARALLEL_CHUNK;
            in_tasks(&mut self.task_pairs, proxies.len(), chunk, search, pairs);
            return true;
        }
        let _ = parallel;
        search(0..proxies.len(), pairs);
        true
    }
}

/// Where the proxies' lower-left corners lie and the largest side of any
/// proxy, in f64, where the differences of two f32s and their ratios to the
/// cell are exact or nearly so: the cell must hold the largest proxy
/// whatever the rounding.
#[derive(Clone, Copy)]
struct CornerBounds {
    largest: f64,
    lo: [f64; 2],
    hi: [f64; 2],
}

impl CornerBounds {
    const EMPTY: Self = Self {
        largest: 0.0,
        lo: [f64::INFINITY; 2],
        hi: [f64::NEG_INFINITY; 2],
    };

    /// The bounds of `proxies`, in chunks on the pool when `parallel` and
    /// they are many (the largest and smallest values are exact, so the
    /// chunks give the same bounds); `None` if a coordinate is not finite.
    fn find(proxies: &[Aabb], parallel: bool) -> Option<Self> {
        #[cfg(feature = "parallel")]
        if crate::parallel::goes_parallel(parallel, proxies.len()) {
            use rayon::prelude::*;
            return proxies
                .par_chunks(crate::constants::PARALLEL_CHUNK)
                .map(Self::of)
                .try_reduce(|| Self::EMPTY, |a, b| Some(a.join(&b)));
        }
        let _ = parallel;
        Self::of(proxies)
    }

    fn of(proxies: &[Aabb]) -> Option<Self> {
        let mut bounds = Self::EMPTY;
        for b in proxies {
            if !(b.min.is_finite() && b.max.is_finite()) {
                return None;
            }
            let (min, max) = (
                [b.min.x, b.min.y].map(f64::from),
                [b.max.x, b.max.y].map(f64::from),
            );
            let side = greater(max[0] - min[0], max[1] - min[1]);
            bounds = bounds.join(&Self {
                largest: side,
                lo: min,
                hi: min,
            });
        }
        Some(bounds)
    }

    fn join(&self, other: &Self) -> Self {
        let lesser = |a: f64, b: f64| if b < a { b } else { a };
        Self {
            largest: greater(self.largest, other.largest),
            lo: [0, 1].map(|k| lesser(self.lo[k], other.lo[k])),
            hi: [0, 1].map(|k| greater(self.hi[k], other.hi[k])),
        }
    }
}

/// The larger of two finite values, by compare and select: every value is
/// finite here, so the NaN handling of `f64::max` would be wasted work.
#[inline(always)]
fn greater(a: f64, b: f64) -> f64 {
    if b > a { b } else { a }
}

/// Runs `search` over `0..items` in runs of `per_task` on rayon's pool,
/// each into its own buffer of `task_pairs`, and appends the buffers to
/// `pairs` in order: the pairs and their order are those of one search over
/// everything.
#[cfg(feature = "parallel")]
pub(crate) fn in_tasks(
    task_pairs: &mut Vec<Vec<(u32, u32)>>,
    items: usize,
    per_task: usize,
    search: impl Fn(std::ops::Range<usize>, &mut Vec<(u32, u32)>) + Sync,
    pairs: &mut Vec<(u32, u32)>,
) {
    use rayon::prelude::*;
    let tasks = items.div_ceil(per_task);
    if task_pairs.len() < tasks {
        task_pairs.resize_with(tasks, Vec::new);
    }
    task_pairs[..tasks]
        .par_iter_mut()
        .enumerate()
        .for_each(|(t, out)| {
            out.clear();
            search(t * per_task..((t + 1) * per_task).min(items), out);
        });
    for out in &task_pairs[..tasks] {
        pairs.extend_from_slice(out);
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

/// Appends the pairs of proxy `a` (box `box_a`) with the proxies `ids`
/// (boxes `boxes`) that touch it, unless both are marked in `asleep`.
#[inline(always)]
fn pairs_in_run(
    a: u32,
    box_a: &Aabb,
    ids: &[u32],
    boxes: &[Aabb],
    asleep: &[bool],
    out: &mut Vec<(u32, u32)>,
) {
    for (&b, other) in ids.iter().zip(boxes) {
        let both_asleep = !asleep.is_empty() && asleep[a as usize] && asleep[b as usize];
        if other.overlaps(box_a) && !both_asleep {
            out.push(ordered(a, b));
        }
    }
}

fn ordered(a: u32, b: u32) -> (u32, u32) {
    if a < b { (a, b) } else { (b, a) }
}

#[cfg(test)]
mod tests;
