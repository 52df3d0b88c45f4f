//! A hint to the processor to start loading a value into cache, so that cache misses overlap
//! instead of coming one after another. The bulk build's gather reads the input in Morton
//! order, which for scattered points is a random walk over the input, and asks for the record
//! [`LOOKAHEAD`] steps ahead; the query engines ask for the runs of the nodes they stack
//! ([`prefetch_run`]; measured in `query/range.rs`).
//!
//! The gather, measured (10^6 uniform points, `(point, u64)` input, the build alone, four alternating runs
//! of 21 builds each, medians): 2D 45.5-46.1 ms without, 37.1-39.4 ms with a lookahead of 16
//! records; 3D 46.5-47.3 against 38.3-39.3. Lookaheads of 8, 32 and 64 were no better.
//! After the sort and the keys got faster, a finer scan of the lookahead, three
//! alternating runs of 15 builds each, 2D medians: 16 gave 32.8-33.4 ms, 20 31.8-32.8, 24
//! 31.6-32.0, 28 30.4-31.1, then 30 33.1, 32 34.7-35.1 and 36 38.1-39.9 (3D alike): the
//! processor seems to keep about 28 misses in flight and drops or stalls beyond. 24 keeps a
//! margin from that cliff.
//! A plain load of the record ahead (safe code) did not help: it waits like the one it hides.
//! A record that straddles two cache lines (half of the 32-byte `([f64; 3], u32)` records of a
//! Vec, whose allocation starts 16 bytes past a line) needs both: asking for the line of its
//! last byte too took the gather of 10^6 uniform 3-D points from 21.0-22.3 to 16.2-17.7
//! ns/point and at 10^8 from 40.5-46.4 to 36.9-40.4 (three alternated cold builds each,
//! timers around the gather).

/// How many records ahead of the one being read the gather asks for.
pub(crate) const LOOKAHEAD: usize = 24;

/// Starts loading the cache lines holding the first and the last byte of `value` (a record of
/// up to 64 bytes may straddle two lines); does nothing else (and nothing at all off x86-64).
#[inline(always)]
pub(crate) fn prefetch<T>(value: &T) {
    let first = (value as *const T).cast::<u8>();
    prefetch_line(first);
    if core::mem::size_of::<T>() > 1 {
        prefetch_line(first.wrapping_add(core::mem::size_of::<T>() - 1));
    }
}

/// Starts loading the cache line holding `address`.
#[inline(always)]
fn prefetch_line(address: *const u8) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: `_mm_prefetch` only hints the cache: it neither reads into the program nor
    // faults, whatever the address (here one inside or at the end of a live value). SSE is
    // part of the x86-64 baseline, so the instruction exists on every x86-64 processor.
    #[allow(unsafe_code)]
    unsafe {
        use core::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        _mm_prefetch::<_MM_HINT_T0>(address.cast::<i8>());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = address;
}

/// Starts loading the first lines (up to 16) of `run` in `values` (points or items about to be
/// read).
#[inline(always)]
pub(crate) fn prefetch_run<V>(values: &[V], run: core::ops::Range<usize>) {
    let step = (64 / core::mem::size_of::<V>().max(1)).max(1);
    for i in run.step_by(step).take(16) {
        prefetch_line((&values[i] as *const V).cast::<u8>());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prefetch_leaves_values_alone() {
        let v: Vec<([f64; 2], u64)> = (0..100).map(|i| ([i as f64, 0.5], i)).collect();
        for r in &v {
            prefetch(r);
        }
        prefetch(&());
        assert!(v
            .iter()
            .enumerate()
            .all(|(i, r)| r.1 == i as u64 && r.0[0] == i as f64));
    }
}
