//! Batch updates on `PointTree` (`extend_from_vec`, `retain`): the tree equals the one the single
//! updates give (same points and items in the same order, same leaves), validates, and equals a
//! fresh build of the same pairs; bad input leaves the tree unchanged and names the pair.

use crate::common;

use orthtree::prelude::*;
use orthtree::{Aabb, Cell, Connectivity, Error, PointTree};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

use common::points::unit_builder as builder;

/// Grid coordinates 0..=8 on [0, 1]: many on split lines, many repeated.
fn pairs<const D: usize>(raw: &[([u8; D], u8)]) -> Vec<([f64; D], u8)> {
    raw.iter()
        .map(|&(g, i)| (g.map(|x| f64::from(x) / 8.0), i))
        .collect()
}

type Shape<const D: usize> = (Vec<[f64; D]>, Vec<u8>, Vec<(Cell<D>, usize)>);

/// The stored points and items in order, and every leaf's cell and count.
fn shape<const D: usize>(t: &PointTree<f64, u8, D>) -> Shape<D> {
    let leaves = t.leaves().map(|l| (l.cell, l.points.len())).collect();
    (t.points().to_vec(), t.items().to_vec(), leaves)
}

fn raw<const D: usize>(max: usize) -> impl Strategy<Value = Vec<([u8; D], u8)>> {
    proptest::collection::vec((proptest::array::uniform::<_, D>(0u8..=8), 0u8..4), 0..max)
}

fn check_extend<const D: usize>(
    init: &[([u8; D], u8)],
    batch: &[([u8; D], u8)],
    bucket: usize,
    max_depth: Option<u8>,
    balance_first: bool,
) -> Result<(), TestCaseError> {
    let b = builder::<D>(bucket, max_depth);
    let (init, batch) = (pairs(init), pairs(batch));
    let mut single = b.build(&init).unwrap();
    let mut batched = single.clone();
    if balance_first {
        single.balance(Connectivity::Corner);
        batched.balance(Connectivity::Corner);
    }
    for &(p, i) in &batch {
        single.insert(p, i).unwrap();
    }
    batched.extend_from_vec(batch.clone()).unwrap();
    if let Err(e) = batched.validate() {
        return Err(TestCaseError::fail(format!("validate: {e}")));
    }
    prop_assert_eq!(shape(&batched), shape(&single));
    if !(balance_first && batch.is_empty()) {
        // Any insert drops the balance refinement: the canonical tree of all the pairs.
        let all: Vec<_> = init.iter().chain(&batch).copied().collect();
        let fresh = b.build(&all).unwrap();
        prop_assert_eq!(shape(&batched).2, shape(&fresh).2);
    }
    Ok(())
}

fn check_retain<const D: usize>(
    init: &[([u8; D], u8)],
    drop_item: u8,
    bucket: usize,
    max_depth: Option<u8>,
) -> Result<(), TestCaseError> {
    let b = builder::<D>(bucket, max_depth);
    let init = pairs(init);
    let mut t = b.build(&init).unwrap();
    let before = shape(&t);
    let mut calls = 0;
    t.retain(|_, &i| {
        calls += 1;
        i != drop_item
    });
    prop_assert_eq!(calls, init.len());
    if let Err(e) = t.validate() {
        return Err(TestCaseError::fail(format!("validate: {e}")));
    }
    // The kept pairs, in the order they were stored.
    let kept: Vec<(&[f64; D], &u8)> = before
        .0
        .iter()
        .zip(&before.1)
        .filter(|&(_, &i)| i != drop_item)
        .collect();
    let now: Vec<(&[f64; D], &u8)> = t.iter().collect();
    prop_assert_eq!(now, kept);
    let fresh: Vec<_> = init.iter().filter(|p| p.1 != drop_item).copied().collect();
    prop_assert_eq!(shape(&t).2, shape(&b.build(&fresh).unwrap()).2);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 128,
        rng_seed: RngSeed::Fixed(0xba7c4),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn extend_2d_equals_single_inserts(
        init in raw::<2>(40),
        batch in raw::<2>(60),
        bucket in 1usize..5,
        max_depth in prop_oneof![Just(None), (1u8..5).prop_map(Some)],
        balance_first in any::<bool>(),
    ) {
        check_extend(&init, &batch, bucket, max_depth, balance_first)?;
    }

    #[test]
    fn extend_3d_equals_single_inserts(
        init in raw::<3>(40),
        batch in raw::<3>(60),
        bucket in 1usize..5,
        max_depth in prop_oneof![Just(None), (1u8..4).prop_map(Some)],
        balance_first in any::<bool>(),
    ) {
        check_extend(&init, &batch, bucket, max_depth, balance_first)?;
    }

    #[test]
    fn retain_2d_equals_a_fresh_build_of_the_kept(
        init in raw::<2>(80),
        drop_item in 0u8..4,
        bucket in 1usize..5,
        max_depth in prop_oneof![Just(None), (1u8..5).prop_map(Some)],
    ) {
        check_retain(&init, drop_item, bucket, max_depth)?;
    }

    #[test]
    fn retain_3d_equals_a_fresh_build_of_the_kept(
        init in raw::<3>(80),
        drop_item in 0u8..4,
        bucket in 1usize..5,
        max_depth in prop_oneof![Just(None), (1u8..4).prop_map(Some)],
    ) {
        check_retain(&init, drop_item, bucket, max_depth)?;
    }
}

#[test]
fn a_large_batch_into_a_large_tree_matches_single_inserts() {
    let b = PointTree::builder().root_box(Aabb::new([0.0; 2], [1.0; 2]).unwrap());
    let at = |i: u32| {
        let x = f64::from(i.wrapping_mul(2_654_435_761) % 100_003) / 100_003.0;
        let y = f64::from(i.wrapping_mul(40_503) % 99_991) / 99_991.0;
        [x, y]
    };
    let init: Vec<([f64; 2], u8)> = (0..20_000).map(|i| (at(i), (i % 251) as u8)).collect();
    let batch: Vec<([f64; 2], u8)> = (20_000..25_000)
        .map(|i| (at(i % 20_500), (i % 13) as u8)) // some copies of stored points
        .collect();
    let mut single = b.build(&init).unwrap();
    let mut batched = single.clone();
    for &(p, i) in &batch {
        single.insert(p, i).unwrap();
    }
    batched.extend_from_vec(batch).unwrap();
    batched.validate().unwrap();
    assert_eq!(batched.len(), 25_000);
    assert_eq!(shape(&batched), shape(&single));
}

#[test]
fn a_bad_pair_in_a_batch_is_named_and_changes_nothing() {
    let b = builder::<2>(2, None);
    let mut t = b.build(&pairs(&[([1, 2], 0), ([3, 4], 1)])).unwrap();
    let before = shape(&t);
    let batch = vec![([0.5, 0.5], 2u8), ([0.25, f64::NAN], 3), ([2.0, 0.5], 4)];
    match t.extend_from_vec(batch) {
        Err(Error::NonFiniteCoordinate { index, axis, .. }) => assert_eq!((index, axis), (3, 1)),
        other => panic!("expected a non-finite coordinate error, got {other:?}"),
    }
    let batch = vec![([0.5, 0.5], 2u8), ([2.0, 0.5], 4)];
    match t.extend_from_vec(batch) {
        Err(Error::OutsideRootBox {
            index, axis, value, ..
        }) => {
            assert_eq!((index, axis, value.get()), (3, 0, 2.0))
        }
        other => panic!("expected an outside-the-root-box error, got {other:?}"),
    }
    assert_eq!(shape(&t), before);
    t.extend_from_vec(Vec::new()).unwrap();
    assert_eq!(shape(&t), before);
    t.retain(|_, _| false);
    assert!(t.is_empty());
    assert_eq!(t.leaf_count(), 1);
    t.validate().unwrap();
}
