//! One dispatcher for loops over items whose results do not depend on each
//! other: in chunks on rayon's pool for large worlds (with the `parallel`
//! feature; about two a thread, of at least [`PARALLEL_CHUNK`] items), in
//! one go otherwise. Each item's result
//! does not depend on the chunking, and the integers the chunks return are
//! summed (or, for [`for_chunks_max`], their largest taken) in any order,
//! so the bits are the same with any number of threads.
//!
//! [`PARALLEL_CHUNK`]: crate::constants::PARALLEL_CHUNK

use crate::columns::{ColumnsMut, ColumnsRef};

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

impl Parts for ColumnsMut<'_> {
    fn len(&self) -> usize {
        ColumnsMut::len(self)
    }
    fn split_at(self, mid: usize) -> (Self, Self) {
        ColumnsMut::split_at(self, mid)
    }
}

impl Parts for ColumnsRef<'_> {
    fn len(&self) -> usize {
        ColumnsRef::len(self)
    }
    fn split_at(self, mid: usize) -> (Self, Self) {
        ColumnsRef::split_at(self, mid)
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
tuple_parts!(A, B, C, D);
tuple_parts!(A, B, C, D, E);

/// Whether a loop over `items` goes to the thread pool (never without the
/// feature).
pub(crate) fn goes_parallel(parallel: bool, items: usize) -> bool {
    cfg!(feature = "parallel") && parallel && items >= crate::constants::PARALLEL_MIN_ITEMS
}

/// Runs `a` and `b`: side by side on the thread pool when `parallel` (and
/// the feature is on), else one after the other.
pub(crate) fn join<A: Send, B: Send>(
    parallel: bool,
    a: impl FnOnce() -> A + Send,
    b: impl FnOnce() -> B + Send,
) -> (A, B) {
    #[cfg(feature = "parallel")]
    if parallel {
        return rayon::join(a, b);
    }
    let _ = parallel;
    (a(), b())
}

/// Calls `f(offset, chunk)` over `parts`: over chunks on the thread pool
/// when `parallel` is set (and the feature is on) and there are at least
/// `PARALLEL_MIN_ITEMS`, else once over everything. The items are halved
/// until each part holds at most `PARALLEL_CHUNK` of them or a
/// `2 × threads`-th of the whole, whichever is more: about two tasks a
/// thread, enough to even out a thread that starts late, and each hand-over costs
/// a few microseconds (with two threads, a loop over 10 000 bodies is
/// four tasks instead of sixteen). `offset` is the chunk's first item.
/// Returns the sum of what `f` returns.
pub(crate) fn for_chunks<P: Parts>(
    parallel: bool,
    parts: P,
    f: impl Fn(usize, P) -> u64 + Sync,
) -> u64 {
    in_chunks(parallel, parts, &f, u64::wrapping_add)
}

/// As [`for_chunks`], without the offset, returning the largest of what `f`
/// returns.
pub(crate) fn for_chunks_max<P: Parts>(
    parallel: bool,
    parts: P,
    f: impl Fn(P) -> u64 + Sync,
) -> u64 {
    in_chunks(parallel, parts, &|_, p| f(p), u64::max)
}

/// [`for_chunks`], with the chunks' results combined by `combine`
/// (associative and commutative: the chunks may finish in any order).
fn in_chunks<P: Parts>(
    parallel: bool,
    parts: P,
    f: &(impl Fn(usize, P) -> u64 + Sync),
    combine: fn(u64, u64) -> u64,
) -> u64 {
    #[cfg(feature = "parallel")]
    if goes_parallel(parallel, parts.len()) {
        let share = parts.len().div_ceil(2 * rayon::current_num_threads());
        let chunk = crate::constants::PARALLEL_CHUNK.max(share);
        return split_join(0, parts, f, combine, chunk);
    }
    let _ = (parallel, combine);
    f(0, parts)
}

/// Where [`for_chunks`] splits `n` items in two: the first half goes to
/// the caller's side of `rayon::join`, the second to the side another
/// worker takes. The contact passes' regions split the bodies here too
/// when they split in storage order (see `regions`), so that each worker
/// moves the bodies whose contacts it solves.
pub(crate) fn halfway(n: usize) -> usize {
    n / 2
}

/// Halves `parts` (at [`halfway`]) until no part is longer than `chunk`,
/// running the halves with `rayon::join`.
#[cfg(feature = "parallel")]
fn split_join<P: Parts>(
    offset: usize,
    parts: P,
    f: &(impl Fn(usize, P) -> u64 + Sync),
    combine: fn(u64, u64) -> u64,
    chunk: usize,
) -> u64 {
    let n = parts.len();
    if n <= chunk {
        return f(offset, parts);
    }
    let mid = halfway(n);
    let (left, right) = parts.split_at(mid);
    let (a, b) = rayon::join(
        || split_join(offset, left, f, combine, chunk),
        || split_join(offset + mid, right, f, combine, chunk),
    );
    combine(a, b)
}

/// Runs `f` (a step) on a worker of rayon's pool, entering the pool if
/// called from outside it, with the pool's other workers kept looking for
/// work until it returns, instead of falling asleep in the step's serial
/// parts.
///
/// A worker with nothing to do yields for a while, then sleeps; waking it
/// costs tens of microseconds (BENCHMARKS.md, "Why the code is shaped this
/// way"), paid at each of
/// the step's stages that follows a serial part longer than that (the
/// narrow phase after the pair sort, the colouring after the regions'
/// split, ...). Here each other worker runs a helper task from when it
/// next looks for work until `f` returns (or [`HELPER_LIMIT`] passes, a
/// safety net): it takes any work handed out (`rayon::yield_now`) and
/// otherwise yields its core to the system. That is busy waiting: the
/// other cores stay in use for the length of the step. A worker that is
/// itself inside `on_pool` (stepping another world, or waiting inside its
/// step) does not help, so steps run side by side on one pool never wait
/// on each other's helpers. The work and its results are the same; only
/// who picks it up, and when, changes.
#[cfg(feature = "parallel")]
pub(crate) fn on_pool<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    use std::sync::Arc;
    use std::sync::atomic::{AtomicBool, Ordering};
    let Some(owner) = rayon::current_thread_index() else {
        return rayon::scope(|_| on_pool(f));
    };
    if rayon::current_num_threads() < 2 {
        return f();
    }
    /// Marks this worker as stepping, and tells the helpers to stop, when
    /// dropped (even if `f` panics).
    struct Done(Arc<AtomicBool>);
    impl Drop for Done {
        fn drop(&mut self) {
            self.0.store(true, Ordering::Release);
            STEPPING.with(|s| s.set(s.get() - 1));
        }
    }
    STEPPING.with(|s| s.set(s.get() + 1));
    let done = Done(Arc::new(AtomicBool::new(false)));
    let flag = Arc::clone(&done.0);
    rayon::spawn_broadcast(move |ctx| {
        // The stepping worker runs its own copy when it next looks for
        // work: it has none to help with. Nor does a worker inside a step
        // of its own: it would not return to that step until this one
        // ended.
        if ctx.index() == owner || STEPPING.with(|s| s.get()) > 0 {
            return;
        }
        let start = std::time::Instant::now();
        while !flag.load(Ordering::Acquire) && start.elapsed() < HELPER_LIMIT {
            if rayon::yield_now() != Some(rayon::Yield::Executed) {
                std::thread::yield_now();
            }
        }
    });
    f()
}

#[cfg(feature = "parallel")]
thread_local! {
    /// How many calls of [`on_pool`] this thread is inside.
    static STEPPING: std::cell::Cell<u32> = const { std::cell::Cell::new(0) };
}

/// How long a helper of [`on_pool`] looks for work at most: far longer
/// than a step, so it only matters if the step never tells it to stop.
#[cfg(feature = "parallel")]
const HELPER_LIMIT: std::time::Duration = std::time::Duration::from_millis(200);

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

    /// `on_pool` runs its closure once, on a worker, whether called from a
    /// worker (of pools of one, two and four) or from outside any pool (the
    /// global pool), and returns what it returns; after a panic inside, the
    /// pool goes on serving.
    #[cfg(feature = "parallel")]
    #[test]
    fn on_pool_runs_once_on_a_worker_and_returns_its_result() {
        use super::on_pool;
        use std::sync::atomic::{AtomicU32, Ordering};
        let runs = AtomicU32::new(0);
        let run = || {
            runs.fetch_add(1, Ordering::Relaxed);
            // Work handed out inside is done, by whichever worker.
            let (a, b) = rayon::join(|| 20, || 22);
            (rayon::current_thread_index().is_some(), a + b)
        };
        for threads in [1, 2, 4] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            assert_eq!(pool.install(|| on_pool(run)), (true, 42));
            let panicked =
                pool.install(|| std::panic::catch_unwind(|| on_pool(|| panic!("inside the step"))));
            assert!(panicked.is_err());
            assert_eq!(pool.install(|| on_pool(|| 7)), 7, "the pool still serves");
        }
        assert_eq!(on_pool(run), (true, 42), "from outside any pool");
        assert_eq!(runs.load(Ordering::Relaxed), 4);
    }

    /// A worker counts as stepping exactly while it is inside `on_pool`
    /// (nested calls too, and after a panic it no longer is): the helper
    /// of another step that such a worker picks up while it waits inside
    /// its own returns at once, so two steps side by side on one pool
    /// never spin waiting for each other.
    #[cfg(feature = "parallel")]
    #[test]
    fn a_worker_counts_as_stepping_while_inside_on_pool() {
        use super::{STEPPING, on_pool};
        let stepping = || STEPPING.with(|s| s.get());
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        pool.install(|| {
            assert_eq!(stepping(), 0);
            let inside = on_pool(|| (stepping(), on_pool(stepping), stepping()));
            assert_eq!(inside, (1, 2, 1));
            assert_eq!(stepping(), 0);
            let panicked = std::panic::catch_unwind(|| on_pool(|| panic!("inside the step")));
            assert!(panicked.is_err());
            assert_eq!(stepping(), 0, "a panic leaves the worker not stepping");
        });
    }
}
