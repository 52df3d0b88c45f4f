//! One door to rayon's thread pool for the parallel queries and joins (feature `rayon`): tasks
//! numbered `0..n`, run by a closure behind a reference.
//!
//! A parallel iterator is compiled once for each closure it is given, and rayon's splitting,
//! joining and job code with it; the engines' closures differ for every point set, metric and
//! visitor they serve, so a program calling the parallel forms on several sets compiled that
//! machinery dozens of times (about a tenth of the code generated for the point trees' tests).
//! Here it is compiled once: [`for_each_index`] takes `&dyn Fn(usize)`, and the helpers built
//! on it hand out results and chunks of work by index. The cost is one indirect call per task (a
//! task is a query, a group of points or a part of a traversal: microseconds of work).

use core::ops::Range;
use rayon::prelude::*;
use std::sync::{Mutex, PoisonError};

/// Tasks per thread when work is cut into chunks: enough for the threads to even out chunks of
/// uneven cost.
const CHUNKS_PER_THREAD: usize = 16;

/// Runs `task(i)` for every `i` in `0..n` on rayon's threads, split as rayon splits a range.
pub(crate) fn for_each_index(n: usize, task: &(dyn Fn(usize) + Sync)) {
    (0..n).into_par_iter().for_each(task);
}

/// `f(i)` for every `i` in `0..n`, computed on rayon's threads, in index order.
pub(crate) fn map_indices<A: Send>(n: usize, f: &(dyn Fn(usize) -> A + Sync)) -> Vec<A> {
    let cells: Vec<Mutex<Option<A>>> = (0..n).map(|_| Mutex::new(None)).collect();
    for_each_index(n, &|i| *lock(&cells[i]) = Some(f(i)));
    cells
        .into_iter()
        .map(|cell| {
            cell.into_inner()
                .unwrap_or_else(PoisonError::into_inner)
                .expect("every task has run once rayon returns")
        })
        .collect()
}

/// `0..n` cut into at most `parts` ranges of consecutive indices, none empty, in order.
fn ranges(n: usize, parts: usize) -> Vec<Range<usize>> {
    let size = n.div_ceil(parts.max(1)).max(1);
    (0..n).step_by(size).map(|s| s..n.min(s + size)).collect()
}

/// `f(range)` for each of at most `chunks` ranges of consecutive indices covering `0..n`, on
/// rayon's threads, in range order (`f` sees a whole range on one thread: scratch space can
/// serve all of it).
pub(crate) fn map_ranges<A: Send>(
    n: usize,
    chunks: usize,
    f: &(dyn Fn(Range<usize>) -> A + Sync),
) -> Vec<A> {
    let rs = ranges(n, chunks);
    map_indices(rs.len(), &|c| f(rs[c].clone()))
}

/// Hands `items` to `work` on rayon's threads in at most `chunks` runs of consecutive items
/// (`work` sees each run whole, in order, on one thread: scratch space can serve a whole run).
pub(crate) fn for_each_chunk<T: Send>(
    items: Vec<T>,
    chunks: usize,
    work: &(dyn Fn(Vec<T>) + Sync),
) {
    let mut rest = items.into_iter();
    let runs: Vec<Mutex<Vec<T>>> = ranges(rest.len(), chunks)
        .into_iter()
        .map(|r| Mutex::new(rest.by_ref().take(r.len()).collect()))
        .collect();
    for_each_index(runs.len(), &|c| work(core::mem::take(&mut *lock(&runs[c]))));
}

/// The number of chunks to cut work into: [`CHUNKS_PER_THREAD`] per thread of rayon's pool.
pub(crate) fn chunks() -> usize {
    rayon::current_num_threads() * CHUNKS_PER_THREAD
}

/// The value behind `m`; a task that panicked while holding it has already made the whole
/// parallel call panic, so its value is taken as it is.
pub(crate) fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::sync::atomic::{AtomicUsize, Ordering};

    #[test]
    fn every_index_runs_once_and_results_keep_their_order() {
        for n in [0, 1, 7, 1000] {
            let runs = AtomicUsize::new(0);
            let squares = map_indices(n, &|i| {
                runs.fetch_add(1, Ordering::Relaxed);
                i * i
            });
            assert_eq!(runs.into_inner(), n);
            assert_eq!(squares, (0..n).map(|i| i * i).collect::<Vec<_>>());
        }
    }

    #[test]
    fn chunks_are_consecutive_runs_covering_every_item_once() {
        for (n, chunks) in [(0, 4), (1, 4), (10, 3), (10, 100), (1000, 32), (5, 0)] {
            let seen = Mutex::new(Vec::new());
            for_each_chunk((0..n).collect(), chunks, &|run: Vec<usize>| {
                assert!(
                    run.windows(2).all(|w| w[1] == w[0] + 1),
                    "a run is consecutive"
                );
                assert!(!run.is_empty());
                lock(&seen).push(run);
            });
            let mut runs = seen.into_inner().unwrap();
            assert!(runs.len() <= chunks.max(1));
            runs.sort();
            assert_eq!(runs.concat(), (0..n).collect::<Vec<_>>());
            let mapped = map_ranges(n, chunks, &|r| r.collect::<Vec<_>>());
            assert!(mapped.len() <= chunks.max(1) && mapped.iter().all(|r| !r.is_empty()));
            assert_eq!(mapped.concat(), (0..n).collect::<Vec<_>>());
        }
    }
}
