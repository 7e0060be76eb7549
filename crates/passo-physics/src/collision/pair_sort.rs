//! The narrow phase's order: its candidate pairs sorted by key (the pair's
//! body slots), stably and without allocating once the buffers have grown,
//! on one thread or two with the same result.

use crate::body::collider::ColliderRef;
use crate::parallel::{goes_parallel, join};

/// A candidate pair in the narrow phase's order: `(order key, proxy A,
/// B)`, where B is a proxy (as `ColliderRef::dynamic(proxy)`) or a static
/// body.
pub(crate) type KeyedPair = (u64, u32, ColliderRef);

/// Sorts the pairs by key, stably (the same input gives the same order; the
/// keys of distinct pairs differ anyway), without allocating once the
/// buffers have grown. A rain of 10 000 circles sorts 12 000–20 000 pairs
/// a step, where a comparison sort took 7 % of the step.
///
/// A counting pass by the lower slot, one counter a slot (`counts`), then
/// an insertion sort, which only has to order each slot's few pairs; if a
/// pair would move more than a few places (a long run out of order, such as
/// a level's ground with its pairs in the order of the bodies' storage),
/// two more counting passes instead, by the higher slot and then by the
/// lower. When the slots are sparse (more than a few per pair) a radix sort
/// over the bits of the two slots does it, and a few pairs are sorted by
/// insertion. `slots` is one more than the highest slot in the keys (the
/// caller finds it while making them).
pub(crate) fn sort_by_key(
    pairs: &mut Vec<KeyedPair>,
    slots: usize,
    scratch: &mut Vec<KeyedPair>,
    counts: &mut Vec<u32>,
    parallel: bool,
) {
    if pairs.len() < 64 {
        // No pair can move more places than the list is long: sorted whole.
        let n = pairs.len();
        let sorted = insertion_sort_within(pairs, n);
        debug_assert!(sorted);
        return;
    }
    let parallel = goes_parallel(parallel, pairs.len());
    // Each pass deals every pair into it: only sized.
    scratch.resize(pairs.len(), (0, 0, ColliderRef::fixed(0)));
    if slots <= 4 * pairs.len() + 1024 {
        // By the lower slot, then by insertion within each lower slot's
        // run (a body's pairs with higher slots, a few as a rule): one
        // counting pass instead of two. No run crosses from the deal's
        // first half to its second: the halves are sorted side by side.
        let lower = |k: &KeyedPair| (k.0 >> 32) as usize;
        let half = deal(pairs, scratch, counts, slots, lower, parallel);
        let (first, second) = pairs.split_at_mut(half);
        let sorted = join(
            parallel,
            || insertion_sort_within(first, 32),
            || insertion_sort_within(second, 32),
        );
        if sorted != (true, true) {
            // A long run out of order: by the higher slot, then by the
            // lower, both stable (and the insertion kept equal keys in
            // their order), so the order is still a stable sort's.
            let higher = |k: &KeyedPair| (k.0 & 0xFFFF_FFFF) as usize;
            deal(pairs, scratch, counts, slots, higher, parallel);
            deal(pairs, scratch, counts, slots, lower, parallel);
        }
        return;
    }
    // Sparse slots: a least-significant-digit radix sort over the bits the
    // keys use. Keys are `lower << 32 | higher`: packed into
    // `lower << bits | higher`, which orders the same.
    const DIGIT: u32 = 10;
    let (lo_max, hi_max) = pairs.iter().fold((0u64, 0u64), |(l, h), k| {
        (l | (k.0 & 0xFFFF_FFFF), h | (k.0 >> 32))
    });
    let bits = u64::BITS - (lo_max | hi_max).leading_zeros();
    let packed = |key: u64| (key >> 32) << bits | (key & 0xFFFF_FFFF);
    for shift in (0..2 * bits).step_by(DIGIT as usize) {
        let digit = |k: &KeyedPair| ((packed(k.0) >> shift) & ((1 << DIGIT) - 1)) as usize;
        deal(pairs, scratch, counts, 1 << DIGIT, digit, parallel);
    }
}

/// One stable counting pass: deals `pairs` into `buckets` buckets by
/// `bucket` (through `scratch`, which it leaves in `pairs`' place), keeping
/// their order within a bucket, and returns where its second half begins.
/// `counts` holds the counters. Once counted, the buckets are cut in two
/// halves of about as many pairs, and each half's pairs are dealt into its
/// part of `scratch`, side by side when `parallel`: each side reads every
/// pair and writes those of its own buckets. The halves depend on the pairs
/// alone: the same order on any number of threads.
fn deal(
    pairs: &mut Vec<KeyedPair>,
    scratch: &mut Vec<KeyedPair>,
    counts: &mut Vec<u32>,
    buckets: usize,
    bucket: impl Fn(&KeyedPair) -> usize + Sync,
    parallel: bool,
) -> usize {
    counts.clear();
    counts.resize(buckets, 0);
    for k in pairs.iter() {
        counts[bucket(k)] += 1;
    }
    let mut sum = 0;
    for n in counts.iter_mut() {
        (*n, sum) = (sum, sum + *n);
    }
    // The first bucket starting at or past the middle, and where it starts.
    let cut = counts.partition_point(|&start| (start as usize) < pairs.len() / 2);
    let half = counts.get(cut).map_or(pairs.len(), |&start| start as usize);
    let (first_starts, second_starts) = counts.split_at_mut(cut);
    let (first, second) = scratch.split_at_mut(half);
    let all = &pairs[..];
    // Deals the pairs of the buckets from `from` on that `starts` covers
    // into `out`, which begins at `base` of the whole.
    let deal_part = |out: &mut [KeyedPair], starts: &mut [u32], from: usize, base: usize| {
        for k in all {
            let Some(at) = bucket(k).checked_sub(from).and_then(|b| starts.get_mut(b)) else {
                continue;
            };
            out[*at as usize - base] = *k;
            *at += 1;
        }
    };
    join(
        parallel,
        || deal_part(first, first_starts, 0, 0),
        || deal_part(second, second_starts, cut, half),
    );
    std::mem::swap(pairs, scratch);
    half
}

/// Sorts by key by insertion (stable), `O(n + inversions)`, unless some pair
/// would move more than `reach` places: then stops, with `pairs` in some
/// order, and returns `false`. `O(n reach)` at most.
fn insertion_sort_within(pairs: &mut [KeyedPair], reach: usize) -> bool {
    for i in 1..pairs.len() {
        let mut j = i;
        while j > 0 && pairs[j - 1].0 > pairs[j].0 {
            if i - j == reach {
                return false;
            }
            pairs.swap(j - 1, j);
            j -= 1;
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::store::pair_order;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(60))]
        #[test]
        fn the_sort_orders_pairs_as_a_comparison_sort_does(
            ids in prop::collection::vec((0u32..70_000, 0u32..70_000), 0..3000),
            // Few slots: many pairs share a key, and the order must be
            // stable. Few and a middling number of slots take the counting
            // passes, many (sparse) the radix sort.
            slots in prop_oneof![Just(40u32), Just(5_000), Just(70_000)],
        ) {
            // Keys as the narrow phase makes them (`pair_order`).
            let mut pairs: Vec<KeyedPair> = ids
                .iter()
                .enumerate()
                .map(|(i, &(x, y))| {
                    let key = pair_order(x % slots, y % slots);
                    (key, i as u32, ColliderRef::fixed(i as u32))
                })
                .collect();
            let mut expected = pairs.clone();
            expected.sort_by_key(|k| (k.0, k.1));
            let highest = pairs.iter().map(|k| k.0 & 0xFFFF_FFFF).max().unwrap_or(0);
            sort_by_key(&mut pairs, highest as usize + 1, &mut Vec::new(), &mut Vec::new(), false);
            prop_assert_eq!(pairs, expected);
        }
    }

    /// On the pool (enough pairs for the deal's halves to go side by
    /// side), with two workers and four: the order of a comparison sort,
    /// equal keys in their order, whether the insertion within slots
    /// holds (slots in order, as the broad phase gives them), fails (a
    /// slot's pairs far out of order) or the slots are sparse.
    #[cfg(feature = "parallel")]
    #[test]
    fn the_sort_on_the_pool_orders_pairs_as_a_comparison_sort_does() {
        let mut next = crate::testing::uniform(7);
        let n = 3 * crate::constants::PARALLEL_MIN_ITEMS;
        for (slots, spread) in [
            (40u32, 40.0),
            (5_000, 3.0),
            (5_000, 5_000.0),
            (70_000, 70_000.0),
        ] {
            let pairs: Vec<KeyedPair> = (0..n)
                .map(|i| {
                    let near = (i as u32 * slots / n as u32) as f32;
                    let x = (near + spread * next()) as u32 % slots;
                    let y = (near + spread * next()) as u32 % slots;
                    (pair_order(x, y), i as u32, ColliderRef::fixed(i as u32))
                })
                .collect();
            let mut expected = pairs.clone();
            expected.sort_by_key(|k| (k.0, k.1));
            let highest = pairs.iter().map(|k| k.0 & 0xFFFF_FFFF).max().unwrap_or(0);
            for threads in [2, 4] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                let mut sorted = pairs.clone();
                pool.install(|| {
                    sort_by_key(
                        &mut sorted,
                        highest as usize + 1,
                        &mut Vec::new(),
                        &mut Vec::new(),
                        true,
                    )
                });
                assert_eq!(
                    sorted, expected,
                    "{slots} slots, spread {spread}, {threads} threads"
                );
            }
        }
    }
}
