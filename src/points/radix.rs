//! The sort behind the bulk build: (Morton key, input index) pairs packed into one integer
//! ([`Packed`]) and sorted by key, equal keys in input order. The build packs a point's key with
//! its low bits replaced by its index into a `u64` (8 bytes moved per point and pass, see
//! `build.rs`); the batch insert packs the whole key and the index as `key << 32 | index` into a
//! `u128`.
//!
//! Most-significant-digit radix sort (the byte-wise MSD sort of McIlroy, Bostic and McIlroy,
//! "Engineering radix sort", Computing Systems 6, 1993), out of place with one buffer: a run is
//! counted on its next byte of key and scattered stably into 256 runs in the other array; a byte
//! that is the same over the whole run is skipped without moving anything (points inside a small
//! part of the root box share their leading bytes); runs of at most `SMALL` pairs are finished
//! with a comparison sort. The top-down order follows the tree: after one or two bytes the runs
//! are the size of leaves, so uniform points need about two passes over the data instead of the
//! log n of a comparison sort. Runs wait on an explicit stack (at most 8 bytes deep, 255 runs per
//! level), so no recursion.
//!
//! Time O(n × bytes used) plus the small sorts; memory one buffer of n pairs.

use crate::sort_network::sort_by_network;

/// The longest run [`sort_short`] sorts with a network: from 24 keys up the standard library's
/// own sort is as fast on these runs.
const NETWORK_MAX: usize = 23;

/// Sorts a short run: by a network ([`sort_by_network`]) up to [`NETWORK_MAX`] pairs, else by
/// `sort_unstable`.
#[inline]
fn sort_short<P: Packed>(run: &mut [P]) {
    if run.len() <= NETWORK_MAX {
        sort_by_network(run, P::MAX);
    } else {
        run.sort_unstable();
    }
}

/// Runs this short are sorted by comparison ([`sort_short`]). A byte pass over a short run pays
/// for 256 counters and up to 256 runs of a few pairs each; below a few hundred pairs a
/// comparison sort is as fast on random keys and much faster on clustered ones, whose runs
/// just above a small threshold would otherwise scatter into near-empty runs. 10^6 points,
/// medians of 9 builds: clustered 2D 41 ms with 48, 32 ms with 768; uniform 2D unchanged
/// (29 ms); 3 x 10^6 uniform 2D 131 -> 112-115 ms and 3D 177 -> 139-142 ms; 10^5 unchanged.
const SMALL: usize = 768;

/// A (key, index) pair packed into one integer whose order is the pairs' order.
pub(crate) trait Packed: Copy + Ord + Default + Send + Sync {
    /// The greatest value (pads the sorting networks' inputs).
    const MAX: Self;
    /// Byte `shift / 8` (0 the lowest, 7 the highest) of the 64-bit sort key: for a `u128`
    /// `key << 32 | index` the key; for a `u64`, the whole value.
    fn byte(self, shift: u32) -> usize;
}

impl Packed for u128 {
    const MAX: Self = u128::MAX;
    #[inline]
    fn byte(self, shift: u32) -> usize {
        ((self >> (32 + shift)) & 0xFF) as usize
    }
}

impl Packed for u64 {
    const MAX: Self = u64::MAX;
    #[inline]
    fn byte(self, shift: u32) -> usize {
        ((self >> shift) & 0xFF) as usize
    }
}

/// Sorts `pairs` by key, then index (a `u64` by value).
pub(crate) fn sort_keyed<P: Packed>(pairs: &mut [P]) {
    sort_keyed_in(pairs, &mut sort_buffer(pairs.len()));
}

/// The buffer [`sort_keyed_in`] needs for `n` pairs: empty when a comparison sort does it.
pub(crate) fn sort_buffer<P: Packed>(n: usize) -> Vec<P> {
    if n <= SMALL {
        Vec::new()
    } else {
        crate::huge_pages::zeros::<P>(n)
    }
}

/// [`sort_keyed`] with the buffer from [`sort_buffer`]`(pairs.len())`.
pub(crate) fn sort_keyed_in<P: Packed>(pairs: &mut [P], buffer: &mut [P]) {
    if pairs.len() <= SMALL {
        sort_short(pairs);
    } else {
        sort_run(pairs, buffer, 56, true);
    }
}

/// [`sort_keyed`] with the runs after the first byte that differs sorted in parallel.
#[cfg(feature = "rayon")]
pub(super) fn par_sort_keyed<P: Packed>(pairs: &mut [P]) {
    use rayon::prelude::*;
    if pairs.len() <= SMALL {
        sort_short(pairs);
        return;
    }
    let mut shift = 56u32;
    let counts = loop {
        let counts = count_bytes(pairs, shift);
        if counts.iter().all(|&c| c < pairs.len()) {
            break counts;
        }
        match shift.checked_sub(8) {
            Some(next) => shift = next,
            None => return, // every key equal: already in input order
        }
    };
    let mut buffer = crate::huge_pages::zeros::<P>(pairs.len());
    scatter(pairs, &mut buffer, shift, &counts);
    let Some(next) = shift.checked_sub(8) else {
        pairs.copy_from_slice(&buffer);
        return;
    };
    // the 256 runs, as disjoint pieces of both arrays
    let mut runs = Vec::with_capacity(256);
    let (mut rest_pairs, mut rest_buffer) = (&mut *pairs, &mut buffer[..]);
    for &count in &counts {
        let (p, ps) = rest_pairs.split_at_mut(count);
        let (b, bs) = rest_buffer.split_at_mut(count);
        if count > 0 {
            runs.push((p, b));
        }
        (rest_pairs, rest_buffer) = (ps, bs);
    }
    runs.into_par_iter()
        .for_each(|(p, b)| sort_run(p, b, next, false));
}

/// The byte at `shift` (within the key) of every pair, counted.
fn count_bytes<P: Packed>(pairs: &[P], shift: u32) -> [usize; 256] {
    let mut counts = [0usize; 256];
    for &p in pairs {
        counts[p.byte(shift)] += 1;
    }
    counts
}

/// Moves `src` into `dst` ordered by the byte at `shift`, stably; `counts` from [`count_bytes`].
fn scatter<P: Packed>(src: &[P], dst: &mut [P], shift: u32, counts: &[usize; 256]) {
    let mut offsets = [0usize; 256];
    let mut at = 0;
    for (offset, &count) in offsets.iter_mut().zip(counts) {
        *offset = at;
        at += count;
    }
    for &p in src {
        let b = p.byte(shift);
        dst[offsets[b]] = p;
        offsets[b] += 1;
    }
}

/// Sorts one run whose pairs agree on every key byte above `shift`: the run is in `pairs` when
/// `in_pairs`, else in `buffer` (the same positions), and ends sorted in `pairs`.
fn sort_run<P: Packed>(pairs: &mut [P], buffer: &mut [P], shift: u32, in_pairs: bool) {
    // (start, end, bit shift of the next byte within the key, data in `pairs` rather than `buffer`)
    let mut stack = vec![(0usize, pairs.len(), shift, in_pairs)];
    while let Some((start, end, shift, in_pairs)) = stack.pop() {
        let (src, dst) = if in_pairs {
            (&mut *pairs, &mut *buffer)
        } else {
            (&mut *buffer, &mut *pairs)
        };
        let (src, dst) = (&mut src[start..end], &mut dst[start..end]);
        if end - start <= SMALL {
            sort_short(src);
            if !in_pairs {
                dst.copy_from_slice(src);
            }
            continue;
        }
        let counts = count_bytes(src, shift);
        if counts.iter().any(|&c| c == end - start) {
            // one byte value over the whole run: nothing to move
            match shift.checked_sub(8) {
                Some(next) => stack.push((start, end, next, in_pairs)),
                // every key byte consumed: equal keys, in input order; bring them home
                None if in_pairs => {}
                None => dst.copy_from_slice(src),
            }
            continue;
        }
        scatter(src, dst, shift, &counts);
        let mut at = start;
        for &count in &counts {
            let (s, e) = (at, at + count);
            at = e;
            if s == e {
                continue;
            }
            match shift.checked_sub(8) {
                Some(next) => stack.push((s, e, next, !in_pairs)),
                // every key byte consumed: the run is sorted in `dst`; bring it home
                None if in_pairs => {
                    src[s - start..e - start].copy_from_slice(&dst[s - start..e - start])
                }
                None => {}
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    fn check(keys: impl Iterator<Item = u64>) {
        let mut pairs: Vec<u128> = keys
            .enumerate()
            .map(|(i, k)| ((k as u128) << 32) | i as u128)
            .collect();
        let mut expected = pairs.clone();
        expected.sort_unstable();
        let mut parallel = pairs.clone();
        sort_keyed(&mut pairs);
        assert_eq!(pairs, expected);
        #[cfg(feature = "rayon")]
        {
            par_sort_keyed(&mut parallel);
            assert_eq!(parallel, expected);
        }
        let _ = &mut parallel;
        // The same keys as `u64`s (the key's low 32 bits given to the index).
        let mut packed: Vec<u64> = expected.iter().map(|&p| (p >> 32) as u64).collect();
        let mut by_value = packed.clone();
        by_value.sort_unstable();
        sort_keyed(&mut packed);
        assert_eq!(packed, by_value);
        #[cfg(feature = "rayon")]
        {
            let mut parallel = by_value.clone();
            parallel.reverse();
            par_sort_keyed(&mut parallel);
            assert_eq!(parallel, by_value);
        }
    }

    #[test]
    fn sorts_like_a_comparison_sort() {
        let mut rng = rand::rngs::SmallRng::seed_from_u64(7);
        for n in [0, 1, 23, 24, SMALL - 1, SMALL, SMALL + 1, 5000, 100_000] {
            check((0..n).map(|_| rng.r#gen::<u64>()));
            // few distinct keys: long runs of equal keys, every byte consumed
            check((0..n).map(|_| rng.gen_range(0..5u64) << 40));
            // shared leading bytes (a small cluster), then random low bytes
            check((0..n).map(|_| 0xABCD_0000_0000_0000 | rng.gen_range(0..1u64 << 20)));
            // all equal, all zero, extremes
            check((0..n).map(|_| u64::MAX));
            check((0..n).map(|i| if i % 2 == 0 { 0 } else { u64::MAX }));
        }
    }
}
