//! The sort behind the bulk build: (Morton key, input index) pairs packed as `key << 32 | index`
//! in a `u128`, sorted by key, equal keys in input order.
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

/// Runs this short are sorted by comparison.
const SMALL: usize = 48;

/// Sorts `pairs` (each `key << 32 | index`, the index below 2^32) by key, then index.
pub(super) fn sort_keyed(pairs: &mut [u128]) {
    if pairs.len() <= SMALL {
        pairs.sort_unstable();
        return;
    }
    let mut buffer = vec![0u128; pairs.len()];
    // (start, end, bit shift of the next byte within the key, data in `pairs` rather than `buffer`)
    let mut stack = vec![(0usize, pairs.len(), 56u32, true)];
    let mut counts = [0usize; 256];
    while let Some((start, end, shift, in_pairs)) = stack.pop() {
        let (src, dst) = if in_pairs {
            (&mut *pairs, &mut buffer[..])
        } else {
            (&mut buffer[..], &mut *pairs)
        };
        if end - start <= SMALL {
            src[start..end].sort_unstable();
            if !in_pairs {
                dst[start..end].copy_from_slice(&src[start..end]);
            }
            continue;
        }
        let byte = |p: u128| ((p >> (32 + shift)) & 0xFF) as usize;
        counts.fill(0);
        for &p in &src[start..end] {
            counts[byte(p)] += 1;
        }
        if counts.iter().any(|&c| c == end - start) {
            // one byte value over the whole run: nothing to move
            match shift.checked_sub(8) {
                Some(next) => stack.push((start, end, next, in_pairs)),
                // every key byte consumed: equal keys, in input order; bring them home
                None if in_pairs => {}
                None => dst[start..end].copy_from_slice(&src[start..end]),
            }
            continue;
        }
        let mut offsets = [0usize; 256];
        let mut at = start;
        for (offset, &count) in offsets.iter_mut().zip(&counts) {
            *offset = at;
            at += count;
        }
        let bounds = offsets;
        for &p in &src[start..end] {
            let b = byte(p);
            dst[offsets[b]] = p;
            offsets[b] += 1;
        }
        for b in 0..256 {
            let (s, e) = (bounds[b], offsets[b]);
            if s == e {
                continue;
            }
            match shift.checked_sub(8) {
                Some(next) => stack.push((s, e, next, !in_pairs)),
                // every key byte consumed: equal keys, already in input order (stable scatter)
                // (the run now lives in `dst`; bring it home if that is the buffer)
                None if in_pairs => src[s..e].copy_from_slice(&dst[s..e]),
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
        sort_keyed(&mut pairs);
        assert_eq!(pairs, expected);
    }

    #[test]
    fn sorts_like_a_comparison_sort() {
        let mut rng = rand::rngs::SmallRng::seed_from_u64(7);
        for n in [0, 1, 47, 48, 49, 1000, 100_000] {
            check((0..n).map(|_| rng.gen::<u64>()));
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
