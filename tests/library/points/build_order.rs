//! The bulk build's order (`build.rs`: keys packed with their input index into a `u64`, low key
//! bits given to the index, runs that agree above those bits put in full key order after the
//! gather): the stored points are exactly the input sorted by (Morton key, input index), for
//! spread points, duplicates, and points so close that their keys differ only in the bits the
//! index took; serial and parallel builds agree, and so does the build from the points alone
//! (`build_indexed`), and so do the builds whose fresh pages are mapped ahead (`map_pages_ahead`).

use crate::common;

use common::points::config;
use orthtree::prelude::*;
use orthtree::{points::PointTreeBuilder, PointTree};
use proptest::prelude::*;

/// The input's items in (Morton key, input index) order, under the tree's own geometry.
fn reference<const D: usize>(t: &PointTree<f64, u32, D>, input: &[([f64; D], u32)]) -> Vec<u32> {
    let mut order: Vec<(u64, u32)> = input
        .iter()
        .map(|(p, i)| (t.geometry().key(p), *i))
        .collect();
    order.sort_unstable();
    order.into_iter().map(|(_, i)| i).collect()
}

/// Points around `base`: offsets of `step` times small integers (1e-12 puts them below level 32
/// of the unit box; 1e-8 near level 27, where a 100-point build's index bits begin), copies, and
/// a few spread points.
fn input<const D: usize>(
    base: [f64; D],
    step: f64,
    offsets: &[([u8; D], u8)],
) -> Vec<([f64; D], u32)> {
    offsets
        .iter()
        .enumerate()
        .map(|(i, (o, kind))| {
            let p = match kind % 4 {
                0 => base,
                3 => core::array::from_fn(|a| f64::from(o[a]) / 255.0),
                _ => core::array::from_fn(|a| base[a] + step * f64::from(o[a])),
            };
            (p, i as u32)
        })
        .collect()
}

fn check<const D: usize>(entries: &[([f64; D], u32)], bucket: usize) -> Result<(), TestCaseError> {
    let b: PointTreeBuilder<f64, D> = PointTree::builder().bucket_size(bucket);
    let t = b.build(entries).unwrap();
    if let Err(e) = t.validate() {
        return Err(TestCaseError::fail(format!("validate: {e}")));
    }
    prop_assert_eq!(t.items(), &reference(&t, entries)[..]);
    let moved = b.build_from_vec(entries.to_vec()).unwrap();
    prop_assert_eq!(moved.items(), t.items());
    // Items that are the input positions: the build from the points alone is the same tree.
    if entries.iter().enumerate().all(|(i, e)| e.1 as usize == i) {
        let points: Vec<[f64; D]> = entries.iter().map(|e| e.0).collect();
        let indexed = b.build_indexed(&points).unwrap();
        prop_assert!(indexed.validate().is_ok());
        prop_assert_eq!(indexed.items(), t.items());
        prop_assert_eq!(indexed.points(), t.points());
        prop_assert_eq!(indexed.leaf_count(), t.leaf_count());
    }
    #[cfg(feature = "rayon")]
    {
        let parallel = b.par_build(entries).unwrap();
        prop_assert_eq!(parallel.items(), t.items());
        prop_assert_eq!(parallel.leaf_count(), t.leaf_count());
    }
    Ok(())
}

proptest! {
    #![proptest_config(config(128, 0xb0_11d))]

    #[test]
    fn close_points_2d_in_full_key_order(
        offsets in proptest::collection::vec((proptest::array::uniform::<_, 2>(any::<u8>()), any::<u8>()), 1..300),
        step in prop_oneof![Just(1e-12), Just(1e-10), Just(1e-8), Just(1e-6)],
        bucket in prop_oneof![Just(1usize), Just(4), Just(64)],
    ) {
        check(&input([0.3, 0.7], step, &offsets), bucket)?;
    }

    #[test]
    fn close_points_3d_in_full_key_order(
        offsets in proptest::collection::vec((proptest::array::uniform::<_, 3>(any::<u8>()), any::<u8>()), 1..300),
        step in prop_oneof![Just(1e-9), Just(1e-7), Just(1e-5)],
        bucket in prop_oneof![Just(1usize), Just(4), Just(64)],
    ) {
        check(&input([0.3, 0.7, 0.5], step, &offsets), bucket)?;
    }
}

#[test]
fn sizes_around_the_index_bit_boundaries() {
    // n = 2^k - 1, 2^k, 2^k + 1: the index takes k or k + 1 bits; every point in one tight
    // cluster, so that many keys agree above the index bits.
    for k in [1u32, 2, 7, 8, 12, 16] {
        for n in [(1usize << k) - 1, 1 << k, (1 << k) + 1] {
            let entries: Vec<([f64; 2], u32)> = (0..n)
                .map(|i| {
                    let j = (i * 7919) % n;
                    (
                        [0.5 + j as f64 * 1e-9, 0.25 + (n - j) as f64 * 3e-10],
                        i as u32,
                    )
                })
                .collect();
            check(&entries, 8).unwrap();
        }
    }
}

/// The builds with their fresh buffers mapped on a second thread (`map_pages_ahead`), on an
/// input large enough to be mapped (the sort's 16 bytes per point above 64 MiB), spread points
/// with every eighth a copy of the one before: the same tree as the plain build, item for item.
#[test]
fn pages_mapped_ahead_give_the_same_tree() {
    let n = 4_500_000;
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut points: Vec<[f64; 3]> = Vec::with_capacity(n);
    for i in 0..n {
        let p = match points.last() {
            Some(&last) if i % 8 == 7 => last,
            _ => [next(), next(), next()],
        };
        points.push(p);
    }
    let plain = PointTree::builder().build_indexed(&points).unwrap();
    let ahead = PointTree::builder().map_pages_ahead(true);
    let t = ahead.build_indexed(&points).unwrap();
    t.validate().unwrap();
    assert_eq!(t.items(), plain.items());
    assert_eq!(t.points(), plain.points());
    assert_eq!(t.leaf_count(), plain.leaf_count());
    let entries: Vec<([f64; 3], u32)> = points.iter().zip(0..).map(|(p, i)| (*p, i)).collect();
    assert_eq!(ahead.build(&entries).unwrap().items(), plain.items());
    assert_eq!(
        ahead.build_from_vec(entries).unwrap().items(),
        plain.items()
    );
}
