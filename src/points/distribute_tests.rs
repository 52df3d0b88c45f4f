//! The bucketed sort and gather against a stable comparison sort: random keys, many duplicates,
//! keys that differ only in their top or their bottom bit, extremes, and sizes around every
//! threshold (0 and 1 points, the sorting networks' 23, the radix sort's 768, one and several
//! buckets); serial and parallel alike, with items that own memory (moved, never copied).

use super::*;
use crate::points::build::{index_bits, pack};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};

/// Sizes at the thresholds: the networks (23), the radix sort's small runs (768), one bucket
/// ([`BUCKET_TARGET`]), two and more buckets.
const SIZES: [usize; 16] = [
    0,
    1,
    2,
    23,
    24,
    767,
    768,
    769,
    BUCKET_TARGET - 1,
    BUCKET_TARGET,
    BUCKET_TARGET + 1,
    2 * BUCKET_TARGET + 1,
    3 * BUCKET_TARGET + 7,
    5,
    100,
    4000,
];

/// `n` keys of kind `kind` from `seed`.
fn keys(kind: u8, n: usize, seed: u64) -> Vec<u64> {
    let mut rng = rand::rngs::SmallRng::seed_from_u64(seed);
    let base: u64 = rng.gen();
    (0..n)
        .map(|_| match kind {
            // spread
            0 => rng.gen(),
            // few distinct keys: long runs of duplicates
            1 => [3u64, 1 << 40, u64::MAX][rng.gen_range(0..3)],
            // differing in the top bit only
            2 => (base >> 1) | u64::from(rng.gen::<bool>()) << 63,
            // differing in the bottom bit only (a bit the index takes)
            3 => (base & !1) | u64::from(rng.gen::<bool>()),
            // a small cluster: shared top bits, random low bits
            4 => (base & !0xF_FFFF) | rng.gen_range(0..0x10_0000),
            // extremes
            _ => [0, u64::MAX][rng.gen_range(0..2)],
        })
        .collect()
}

/// Sorts keys of kind `kind` both ways and compares with a stable sort by key above the
/// index bits (ties in input order), records and all.
fn check(kind: u8, n: usize, seed: u64) {
    let raw = keys(kind, n, seed);
    let bits = index_bits(n);
    let packed: Vec<u64> = raw
        .iter()
        .enumerate()
        .map(|(i, &k)| pack(k, i, bits))
        .collect();
    let (all, any) = packed
        .iter()
        .fold((u64::MAX, 0), |(a, o), &k| (a & k, o | k));
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by_key(|&i| packed[i] >> bits);
    let expected_keys: Vec<u64> = order.iter().map(|&i| packed[i]).collect();
    let expected_items: Vec<String> = order.iter().map(|i| i.to_string()).collect();
    let record = |i: usize| ([i as f64, -(i as f64)], i.to_string());
    let (keys, points, items) = sort_gather(packed.clone(), all ^ any, bits, [0.0; 2], record);
    assert_eq!(keys, expected_keys, "kind {kind}, n {n}");
    assert_eq!(items, expected_items, "kind {kind}, n {n}");
    for (p, &i) in points.iter().zip(&order) {
        assert_eq!(*p, [i as f64, -(i as f64)]);
    }
    #[cfg(feature = "rayon")]
    {
        let (keys, points, items) = par_sort_gather(packed, all ^ any, bits, [0.0; 2], record);
        assert_eq!(keys, expected_keys, "parallel, kind {kind}, n {n}");
        assert_eq!(items, expected_items, "parallel, kind {kind}, n {n}");
        for (p, &i) in points.iter().zip(&order) {
            assert_eq!(*p, [i as f64, -(i as f64)]);
        }
    }
}

#[test]
fn every_kind_at_every_threshold() {
    for kind in 0..6 {
        for (s, &n) in SIZES.iter().enumerate() {
            check(kind, n, s as u64 * 31 + u64::from(kind));
        }
    }
}

#[test]
fn digits_stay_within_the_keys_and_the_width_limit() {
    // one bucket for few points, or when no bit differs
    assert_eq!(Digit::choose(0, 0).buckets(), 1);
    assert_eq!(Digit::choose(BUCKET_TARGET, u64::MAX).buckets(), 1);
    assert_eq!(Digit::choose(1 << 30, 0).buckets(), 1);
    // about BUCKET_TARGET points a bucket, at most 2^MAX_DIGIT_BITS buckets
    assert_eq!(Digit::choose(BUCKET_TARGET + 1, u64::MAX).buckets(), 2);
    assert_eq!(Digit::choose(64 * BUCKET_TARGET, u64::MAX).buckets(), 64);
    assert_eq!(
        Digit::choose(usize::MAX / 2, u64::MAX).buckets(),
        1 << MAX_DIGIT_BITS
    );
    // the highest bits that may differ: the top one here, at the top of an 11-bit digit
    let d = Digit::choose(1 << 30, 1 << 63);
    assert_eq!(
        (d.buckets(), d.of(1 << 63), d.of(5), d.first_byte()),
        (2048, 1024, 0, 56)
    );
    // the bits below bit 10
    let d = Digit::choose(1 << 30, 0x3FF);
    assert_eq!(
        (d.buckets(), d.of(0x3FF), d.of(0x200), d.first_byte()),
        (1024, 0x3FF, 0x200, 8)
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn sorts_like_a_stable_comparison_sort(
        kind in 0u8..6,
        at in 0usize..SIZES.len(),
        jitter in 0usize..3,
        seed in any::<u64>(),
    ) {
        // sizes at each threshold and one or two past it
        check(kind, SIZES[at] + jitter, seed);
    }
}
