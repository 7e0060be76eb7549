//! One dispatcher for loops over items whose results do not depend on each
//! other: in chunks of [`PARALLEL_CHUNK`] on rayon's pool for large worlds
//! (with the `parallel` feature), in one go otherwise. Each item's result
//! does not depend on the chunking, and the counts the chunks return are
//! integers summed in any order, so the bits are the same with any number
//! of threads.
//!
//! [`PARALLEL_CHUNK`]: crate::constants::PARALLEL_CHUNK

/// Slices walked together, split at the same index: a slice, or a tuple of
/// slices of equal length.
// Without the `parallel` feature nothing splits.
#[cfg_attr(not(feature = "parallel"), allow(dead_code))]
pub(crate) trait Parts: Sized + Send {
    /// Number of items (of each slice).
    fn len(&self) -> usize;
    /// The first `mid` items of each slice, and the rest.
    fn split_at(self, mid: usize) -> (Self, Self);
}

impl<T: Send> Parts for &mut [T] {
    fn len(&self) -> usize {
        <[T]>::len(self)
    }
    fn split_at(self, mid: usize) -> (Self, Self) {
        self.split_at_mut(mid)
    }
}

impl<T: Sync> Parts for &[T] {
    fn len(&self) -> usize {
        <[T]>::len(self)
    }
    fn split_at(self, mid: usize) -> (Self, Self) {
        <[T]>::split_at(self, mid)
    }
}

macro_rules! tuple_parts {
    ($first:ident $(, $rest:ident)*) => {
        #[allow(non_snake_case)]
        impl<$first: Parts, $($rest: Parts),*> Parts for ($first, $($rest),*) {
            fn len(&self) -> usize {
                let ($first, $($rest),*) = self;
                let n = $first.len();
                $(debug_assert_eq!($rest.len(), n);)*
                n
            }
            fn split_at(self, mid: usize) -> (Self, Self) {
                let ($first, $($rest),*) = self;
                let $first = $first.split_at(mid);
                $(let $rest = $rest.split_at(mid);)*
                (($first.0, $($rest.0),*), ($first.1, $($rest.1),*))
            }
        }
    };
}

tuple_parts!(A, B);
tuple_parts!(A, B, C);
tuple_parts!(A, B, C, D, E);

/// Whether a loop over `items` goes to the thread pool.
#[cfg(feature = "parallel")]
pub(crate) fn goes_parallel(parallel: bool, items: usize) -> bool {
    parallel && items >= crate::constants::PARALLEL_MIN_ITEMS
}

/// Calls `f(offset, chunk)` over `parts`: over chunks of at most
/// `PARALLEL_CHUNK` items on the thread pool when `parallel` is set (and
/// the feature is on) and there are at least `PARALLEL_MIN_ITEMS`, else
/// once over everything. `offset` is the chunk's first item. Returns the
/// sum of what `f` returns.
pub(crate) fn for_chunks<P: Parts>(
    parallel: bool,
    parts: P,
    f: impl Fn(usize, P) -> u64 + Sync,
) -> u64 {
    #[cfg(feature = "parallel")]
    if goes_parallel(parallel, parts.len()) {
        return split_join(0, parts, &f);
    }
    let _ = parallel;
    f(0, parts)
}

/// Halves `parts` at a chunk boundary until a chunk is left, running the
/// halves with `rayon::join`.
#[cfg(feature = "parallel")]
fn split_join<P: Parts>(offset: usize, parts: P, f: &(impl Fn(usize, P) -> u64 + Sync)) -> u64 {
    let chunk = crate::constants::PARALLEL_CHUNK;
    let n = parts.len();
    if n <= chunk {
        return f(offset, parts);
    }
    let mid = n.div_ceil(chunk) / 2 * chunk;
    let (left, right) = parts.split_at(mid);
    let (a, b) = rayon::join(
        || split_join(offset, left, f),
        || split_join(offset + mid, right, f),
    );
    a + b
}

#[cfg(test)]
mod tests {
    use super::for_chunks;
    use crate::constants::{PARALLEL_CHUNK, PARALLEL_MIN_ITEMS};

    #[test]
    fn every_item_is_visited_once_at_its_own_offset() {
        for n in [0, 5, PARALLEL_CHUNK + 3, PARALLEL_MIN_ITEMS * 2 + 7] {
            for parallel in [false, true] {
                let mut seen = vec![0u32; n];
                let index: Vec<usize> = (0..n).collect();
                let total = for_chunks(
                    parallel,
                    (&mut seen[..], &index[..]),
                    |offset, (seen, index)| {
                        assert!(seen.len() <= n);
                        for (k, (s, &i)) in seen.iter_mut().zip(index).enumerate() {
                            assert_eq!(offset + k, i);
                            *s += 1;
                        }
                        seen.len() as u64
                    },
                );
                assert_eq!(total, n as u64);
                assert!(seen.iter().all(|&s| s == 1));
            }
        }
    }
}
