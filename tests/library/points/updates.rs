//! Insert and remove on `PointTree`, through the random update sequences that every updatable
//! tree runs (`common::updates::run`): after every update the tree validates, and it has exactly
//! the leaves (cells), the points per leaf (as multisets), the leaf count and the depth of a tree
//! freshly built from the same (point, item) pairs with the same root box, bucket size and
//! maximum depth; and every query kind (box, ball, half-space, count, visitor, nearest,
//! k-nearest under three metrics, the nearest iterator) agrees with a brute-force scan of the
//! stored pairs.

use crate::common;

use common::points::unit_builder as builder;
use common::updates::{coords, initial, op, point_leaves, Op, Updatable};
use orthtree::prelude::*;
use orthtree::{Error, PointTree};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

impl<const D: usize> Updatable<D> for PointTree<f64, u8, D> {
    fn leaf_pairs(&self) -> common::updates::Leaves<D> {
        point_leaves(self)
    }

    /// The same number of leaves and the same depth as the fresh build.
    fn after_step(
        &mut self,
        _step: usize,
        fresh: &PointTree<f64, u8, D>,
        _model: &[([f64; D], u8)],
    ) -> Result<(), TestCaseError> {
        prop_assert_eq!(self.leaf_count(), fresh.leaf_count());
        prop_assert_eq!(self.depth(), fresh.depth());
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
    let t = b.build(&model).unwrap();
    common::updates::run(t, &b, model, ops)
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 96,
        rng_seed: RngSeed::Fixed(0x0b7_4e0d),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn random_updates_2d_match_a_fresh_build(
        init in initial::<2>(),
        ops in proptest::collection::vec(op::<2>(), 0..80),
        bucket in 1usize..5,
        max_depth in prop_oneof![Just(None), (1u8..5).prop_map(Some)],
    ) {
        run(init, ops, bucket, max_depth)?;
    }

    #[test]
    fn random_updates_3d_match_a_fresh_build(
        init in initial::<3>(),
        ops in proptest::collection::vec(op::<3>(), 0..80),
        bucket in 1usize..5,
        max_depth in prop_oneof![Just(None), (1u8..4).prop_map(Some)],
    ) {
        run(init, ops, bucket, max_depth)?;
    }
}

#[test]
fn insert_everything_then_remove_everything_returns_to_one_leaf() {
    let b = builder::<2>(1, None);
    let mut t = b.build::<u8>(&[]).unwrap();
    let pts: Vec<([f64; 2], u8)> = (0..200u32)
        .map(|i| {
            let x = f64::from((i * 37) % 101) / 100.0;
            let y = f64::from((i * 59) % 97) / 96.0;
            ([x, y], (i % 7) as u8)
        })
        .collect();
    for &(p, i) in &pts {
        t.insert(p, i).unwrap();
    }
    t.validate().unwrap();
    assert_eq!(point_leaves(&t), point_leaves(&b.build(&pts).unwrap()));
    let slots = t.node_count();
    for &(p, i) in pts.iter().rev() {
        assert!(t.remove(&p, &i));
        t.validate().unwrap();
    }
    assert!(t.is_empty());
    assert_eq!((t.leaf_count(), t.depth()), (1, 0));
    // inserting again reuses the freed node slots
    for &(p, i) in &pts {
        t.insert(p, i).unwrap();
    }
    assert_eq!(t.node_count(), slots);
    assert_eq!(point_leaves(&t), point_leaves(&b.build(&pts).unwrap()));
}

#[test]
fn duplicates_at_the_maximum_depth_are_kept_and_removed_one_at_a_time() {
    let b = builder::<3>(2, Some(3));
    let mut t = b.build::<u8>(&[]).unwrap();
    for _ in 0..10 {
        t.insert([0.5, 0.5, 0.5], 1).unwrap();
    }
    t.insert([0.5, 0.5, 0.5], 2).unwrap();
    assert_eq!(t.depth(), 3);
    assert_eq!(t.remove_point(&[0.5, 0.5, 0.5]), Some(1));
    for _ in 0..9 {
        assert!(t.remove(&[0.5, 0.5, 0.5], &1));
        t.validate().unwrap();
    }
    assert!(!t.remove(&[0.5, 0.5, 0.5], &1));
    assert_eq!(t.len(), 1);
    assert_eq!(t.depth(), 0);
    assert_eq!(t.remove_point(&[0.5, 0.5, 0.5]), Some(2));
    assert_eq!(t.remove_point(&[0.5, 0.5, 0.5]), None);
}

#[test]
fn bad_inserts_are_typed_errors_and_bad_removals_are_misses() {
    let mut t = builder::<2>(1, None).build(&[([0.25, 0.25], 0u8)]).unwrap();
    let e = t.insert([0.5, 1.5], 1).unwrap_err();
    assert_eq!(e.item, 1, "the refused item is handed back");
    assert!(matches!(
        e.error,
        Error::OutsideRootBox { axis: 1, value, interval, .. }
            if value.get() == 1.5 && (interval.0.get(), interval.1.get()) == (0.0, 1.0)
    ));
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
    // a tree built without a root box keeps the enclosing cube of its first points
    let mut u = PointTree::builder()
        .bucket_size(1)
        .build(&[([0.0, 0.0], 0u8), ([2.0, 1.0], 1)])
        .unwrap();
    assert!(u.insert([1.0, 2.0], 2).is_ok());
    assert!(u.insert([3.0, 0.0], 3).is_err());
    u.validate().unwrap();
}
