//! Per-body loops that run in chunks on rayon's pool for large worlds (with
//! the `parallel` feature) and in one go otherwise. Each body's result does
//! not depend on the chunking; counts are integers summed in any order; so
//! the bits are the same with any number of threads.

/// Whether a loop over `items` goes to the thread pool.
#[cfg(feature = "parallel")]
pub(crate) fn goes_parallel(parallel: bool, items: usize) -> bool {
    parallel && items >= crate::constants::PARALLEL_MIN_ITEMS
}

/// Calls `f(offset, a_chunk, b_chunk)` over matching chunks of two slices
/// of equal length; returns the sum of what it returns.
pub(crate) fn chunks2<A: Send, B: Send>(
    parallel: bool,
    a: &mut [A],
    b: &mut [B],
    f: impl Fn(usize, &mut [A], &mut [B]) -> u64 + Sync,
) -> u64 {
    debug_assert_eq!(a.len(), b.len());
    #[cfg(feature = "parallel")]
    if parallel && a.len() >= crate::constants::PARALLEL_MIN_ITEMS {
        use rayon::prelude::*;
        let c = crate::constants::PARALLEL_CHUNK;
        return a
            .par_chunks_mut(c)
            .zip(b.par_chunks_mut(c))
            .enumerate()
            .map(|(k, (a, b))| f(k * c, a, b))
            .sum();
    }
    let _ = parallel;
    f(0, a, b)
}

/// [`chunks2`] over three slices.
pub(crate) fn chunks3<A: Send, B: Send, C: Send>(
    parallel: bool,
    a: &mut [A],
    b: &mut [B],
    c: &mut [C],
    f: impl Fn(usize, &mut [A], &mut [B], &mut [C]) -> u64 + Sync,
) -> u64 {
    debug_assert!(a.len() == b.len() && b.len() == c.len());
    #[cfg(feature = "parallel")]
    if parallel && a.len() >= crate::constants::PARALLEL_MIN_ITEMS {
        use rayon::prelude::*;
        let n = crate::constants::PARALLEL_CHUNK;
        return a
            .par_chunks_mut(n)
            .zip(b.par_chunks_mut(n))
            .zip(c.par_chunks_mut(n))
            .enumerate()
            .map(|(k, ((a, b), c))| f(k * n, a, b, c))
            .sum();
    }
    let _ = parallel;
    f(0, a, b, c)
}
