//! `DynamicPointTree` (single updates in amortised O(depth)), through the random update
//! sequences that every updatable tree runs (`common::updates::run`): after every update the tree validates and has exactly the leaves (cells) and the points per leaf of a
//! `PointTree` freshly built from the same pairs with the same root box, bucket size and maximum
//! depth; every query kind (box, ball, half-space, count, visitor, nearest, k-nearest under three
//! metrics, the nearest iterator) agrees with a brute-force scan of the stored pairs; and the
//! slots the neighbours report name their items.

use crate::common;

use common::points::unit_builder as builder;
use common::updates::{check_queries, coords, initial, op, point_leaves, sorted_pairs, Op};
use common::updates::{Leaves, Updatable};
use orthtree::prelude::*;
use orthtree::{Aabb, DynamicPointTree, Error, PointTree};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

type Tree<const D: usize> = DynamicPointTree<f64, u8, D>;

/// Every leaf's cell and its sorted (point bits, item) pairs, of a dynamic tree.
fn dynamic_leaves<const D: usize>(t: &Tree<D>) -> Leaves<D> {
    t.leaves()
        .map(|(cell, slots)| {
            let pairs = slots
                .iter()
                .map(|&s| (t.point(s as usize), &t.items()[s as usize]));
            (cell, sorted_pairs(pairs))
        })
        .collect()
}

impl<const D: usize> Updatable<D> for Tree<D> {
    fn leaf_pairs(&self) -> Leaves<D> {
        dynamic_leaves(self)
    }

    /// Every 16 steps: compaction keeps the tree valid and every answer.
    fn after_step(
        &mut self,
        step: usize,
        _fresh: &PointTree<f64, u8, D>,
        model: &[([f64; D], u8)],
    ) -> Result<(), TestCaseError> {
        if step % 16 == 15 {
            self.compact();
            self.validate()
                .map_err(|e| TestCaseError::fail(format!("after compact: {e}")))?;
            check_queries(self, model)?;
        }
        Ok(())
    }
}

fn run<const D: usize>(
    initial: Vec<([u8; D], u8)>,
    ops: Vec<Op<D>>,
    bucket: usize,
    max_depth: Option<u8>,
) -> Result<(), TestCaseError> {
    let b = builder::<D>(bucket, max_depth);
    let model: Vec<([f64; D], u8)> = initial.iter().map(|&(g, i)| (coords(g), i)).collect();
    let t = DynamicPointTree::from(b.build(&model).unwrap());
    common::updates::run(t, &b, model, ops)
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 96,
        rng_seed: RngSeed::Fixed(0xd1_4a31c),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn random_updates_2d_match_a_fresh_build_and_brute_force(
        init in initial::<2>(),
        ops in proptest::collection::vec(op::<2>(), 0..80),
        bucket in 1usize..5,
        max_depth in prop_oneof![Just(None), (1u8..5).prop_map(Some)],
    ) {
        run(init, ops, bucket, max_depth)?;
    }

    #[test]
    fn random_updates_3d_match_a_fresh_build_and_brute_force(
        init in initial::<3>(),
        ops in proptest::collection::vec(op::<3>(), 0..80),
        bucket in 1usize..5,
        max_depth in prop_oneof![Just(None), (1u8..4).prop_map(Some)],
    ) {
        run(init, ops, bucket, max_depth)?;
    }
}

/// Thousands of inserts then removes in a pseudo-random order on a bigger tree: chunks grow,
/// shrink, move and are compacted many times; the shape and answers stay a fresh build's.
#[test]
fn many_updates_grow_shrink_and_compact_the_chunks() {
    let b = builder::<2>(8, None);
    let mut t: Tree<2> = DynamicPointTree::from(b.build(&[]).unwrap());
    let pts: Vec<([f64; 2], u8)> = (0..20_000u32)
        .map(|i| {
            let x = f64::from((i * 7919) % 1009) / 1008.0;
            let y = f64::from((i * 104_729) % 997) / 996.0;
            ([x, y], (i % 251) as u8)
        })
        .collect();
    for (n, &(p, i)) in pts.iter().enumerate() {
        t.insert(p, i).unwrap();
        if n % 997 == 0 {
            t.validate().unwrap();
        }
    }
    assert_eq!(dynamic_leaves(&t), point_leaves(&b.build(&pts).unwrap()));
    let mut model = pts.clone();
    for n in 0..19_000usize {
        let (p, i) = model.swap_remove((n * 31) % model.len());
        assert!(t.remove(&p, &i));
        if n % 1499 == 0 {
            t.validate().unwrap();
            assert_eq!(dynamic_leaves(&t), point_leaves(&b.build(&model).unwrap()));
        }
    }
    t.validate().unwrap();
    check_queries(&t, &model).unwrap();
    // compaction keeps the chunk array within a few times the live points
    assert!(orthtree::query::SpatialIndex::points(t.index()).len() <= 4 * model.len() + 8192);
}

#[test]
fn duplicates_at_the_maximum_depth_are_kept_and_removed_one_at_a_time() {
    let mut t: Tree<3> = DynamicPointTree::from(builder::<3>(2, Some(3)).build(&[]).unwrap());
    for _ in 0..100 {
        t.insert([0.5, 0.5, 0.5], 1).unwrap();
    }
    t.insert([0.5, 0.5, 0.5], 2).unwrap();
    assert_eq!(t.tree().depth(), 3);
    assert_eq!(t.k_nearest(&[0.5; 3], 200).unwrap().len(), 101);
    for _ in 0..100 {
        assert!(t.remove(&[0.5, 0.5, 0.5], &1));
        t.validate().unwrap();
    }
    assert!(!t.remove(&[0.5, 0.5, 0.5], &1));
    assert_eq!((t.len(), t.tree().depth()), (1, 0));
    assert_eq!(t.remove_point(&[0.5, 0.5, 0.5]), Some(2));
    assert_eq!(t.remove_point(&[0.5, 0.5, 0.5]), None);
    assert!(t.is_empty());
    assert_eq!(t.nearest(&[0.0; 3]).unwrap().map(|n| n.distance), None);
    assert_eq!(t.k_nearest(&[0.0; 3], 0).unwrap().len(), 0);
    assert_eq!(
        t.query_count(Aabb::new([0.0; 3], [1.0; 3]).unwrap())
            .unwrap(),
        0
    );
    t.validate().unwrap();
}

#[test]
fn bad_input_is_a_typed_error_or_a_miss() {
    let mut t: Tree<2> =
        DynamicPointTree::from(builder::<2>(1, None).build(&[([0.25, 0.25], 0u8)]).unwrap());
    let e = t.insert([0.5, 1.5], 1).unwrap_err();
    assert_eq!(e.item, 1, "the refused item is handed back");
    assert_eq!(
        e.error,
        Error::OutsideRootBox {
            index: 1,
            axis: 1,
            value: 1.5.into(),
            interval: (0.0.into(), 1.0.into())
        }
    );
    let e = t.insert([f64::NAN, 0.5], 2).unwrap_err();
    assert_eq!(e.item, 2);
    assert!(matches!(
        e.error,
        Error::NonFiniteCoordinate { axis: 0, .. }
    ));
    assert!(!t.remove(&[f64::INFINITY, 0.0], &0));
    assert!(!t.remove(&[-1.0, 0.0], &0));
    assert!(!t.remove(&[0.25, 0.25], &9));
    assert_eq!(t.remove_point(&[0.75, 0.75]), None);
    assert_eq!(t.len(), 1);
    assert!(t.nearest(&[f64::NAN, 0.0]).is_err());
    assert!(t.in_ball(&[0.0, 0.0], -1.0).is_err());
    assert!(t.k_nearest_within(&[0.0, 0.0], 1, f64::NAN).is_err());
    t.validate().unwrap();
}
