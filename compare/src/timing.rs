//! The one timing rule of the comparison programs: the median of a number of timed runs after
//! one untimed warm-up run, each run's result checked equal to the one before.

use std::hint::black_box;
use std::time::Instant;

/// The median time in milliseconds of `reps` runs of `f` (at least one), and its (checked
/// equal) result, after one run that is not timed (a warm-up: the first run pays for fresh pages
/// and cold caches).
///
/// # Panics
/// When two runs of `f` return different results: `f` is not deterministic.
pub fn time<R: PartialEq + std::fmt::Debug>(reps: usize, mut f: impl FnMut() -> R) -> (f64, R) {
    let mut times = Vec::with_capacity(reps);
    let mut result = black_box(f());
    for _ in 0..reps.max(1) {
        let start = Instant::now();
        let r = black_box(f());
        times.push(start.elapsed().as_secs_f64() * 1e3);
        assert_eq!(result, r, "two runs of one workload gave different answers");
        result = r;
    }
    times.sort_by(f64::total_cmp);
    (times[times.len() / 2], result)
}
