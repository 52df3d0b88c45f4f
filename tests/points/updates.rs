//! Insert and remove on `PointTree`: after every update the tree validates, and
//! it has exactly the leaves (cells) and the points per leaf (as multisets) of a tree freshly built
//! from the same (point, item) pairs with the same root box, bucket size and maximum depth; and
//! every query kind (box, ball, half-space, k-nearest) agrees with a brute-force scan of the
//! stored pairs.

use crate::common;

use common::updates::{apply, coords, initial, op, sorted_pairs, Op};
use orthtree::prelude::*;
use orthtree::{query::HalfSpace, Aabb, Ball, Cell, Error, PointTree};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

type Leaves<const D: usize> = Vec<(Cell<D>, Vec<([u64; D], u8)>)>;

/// Every leaf's cell and its sorted multiset of (point bits, item).
fn leaf_structure<const D: usize>(t: &PointTree<f64, u8, D>) -> Leaves<D> {
    t.leaves()
        .map(|l| {
            let mut pts: Vec<([u64; D], u8)> = l
                .points
                .iter()
                .zip(l.items)
                .map(|(p, &i)| (p.map(f64::to_bits), i))
                .collect();
            pts.sort_unstable();
            (l.cell, pts)
        })
        .collect()
}

/// Box, ball and half-space queries whose boundaries pass through grid points, and k-nearest
/// distances, against a scan of `model`.
fn check_queries<const D: usize>(
    t: &PointTree<f64, u8, D>,
    model: &[([f64; D], u8)],
) -> Result<(), TestCaseError> {
    let all = || model.iter().map(|(p, i)| (p, i));
    let (lo, hi) = ([0.25; D], [0.625; D]);
    let in_box = |p: &[f64; D]| (0..D).all(|a| lo[a] <= p[a] && p[a] <= hi[a]);
    prop_assert_eq!(
        sorted_pairs(t.in_box(&Aabb::new(lo, hi).unwrap()).unwrap()),
        sorted_pairs(all().filter(|(p, _)| in_box(p)))
    );
    let (c, r) = ([0.5; D], 0.375);
    let d2 = |p: &[f64; D], q: &[f64; D]| (0..D).map(|a| (p[a] - q[a]).powi(2)).sum::<f64>();
    prop_assert_eq!(
        sorted_pairs(t.query(Ball::new(c, r).unwrap()).unwrap()),
        sorted_pairs(all().filter(|(p, _)| d2(p, &c) <= r * r))
    );
    let mut normal = [0.0; D];
    normal[0] = 1.0;
    normal[D - 1] += 1.0;
    let plane = HalfSpace::new(normal, 0.75).unwrap();
    let below = |p: &[f64; D]| (0..D).map(|a| normal[a] * p[a]).sum::<f64>() <= 0.75;
    prop_assert_eq!(
        sorted_pairs(t.query(plane).unwrap()),
        sorted_pairs(all().filter(|(p, _)| below(p)))
    );
    for q in [[0.5; D], [0.0; D], [0.9; D]] {
        let got: Vec<f64> = t
            .k_nearest(&q, 5)
            .unwrap()
            .iter()
            .map(|n| n.distance)
            .collect();
        let mut want: Vec<f64> = model.iter().map(|(p, _)| d2(p, &q)).collect();
        want.sort_by(f64::total_cmp);
        want.truncate(5);
        prop_assert_eq!(got, want);
    }
    Ok(())
}

use common::points::unit_builder as builder;

fn run<const D: usize>(
    initial: Vec<([u8; D], u8)>,
    ops: Vec<Op<D>>,
    bucket: usize,
    max_depth: Option<u8>,
) -> Result<(), TestCaseError> {
    let b = builder::<D>(bucket, max_depth);
    let mut model: Vec<([f64; D], u8)> = initial.iter().map(|&(g, i)| (coords(g), i)).collect();
    let mut t = b.build(&model).unwrap();
    for op in ops {
        apply(&mut t, &mut model, op)?;
        if let Err(e) = t.validate() {
            return Err(TestCaseError::fail(format!("validate: {e}")));
        }
        prop_assert_eq!(t.len(), model.len());
        let fresh = b.build(&model).unwrap();
        prop_assert_eq!(leaf_structure(&t), leaf_structure(&fresh));
        prop_assert_eq!(t.leaf_count(), fresh.leaf_count());
        prop_assert_eq!(t.depth(), fresh.depth());
        check_queries(&t, &model)?;
    }
    Ok(())
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
    assert_eq!(leaf_structure(&t), leaf_structure(&b.build(&pts).unwrap()));
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
    assert_eq!(leaf_structure(&t), leaf_structure(&b.build(&pts).unwrap()));
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
