//! Refused input, each error naming the offending point, axis and value; extreme but valid
//! coordinates (±f64::MAX, subnormals, mixed magnitudes, 64-bit integers); empty and single-point
//! input.

use crate::common;

use common::points::{check_all, check_points};
use orthtree::prelude::*;
use orthtree::{
    geom::AabbError, points::PointTreeBuilder, query::Location, tree::NodeId, Aabb, Cell, Error,
    Octree, PointTree, Quadtree, QueryError,
};
use rand::Rng;

fn random_entries<const D: usize>(seed: u64, n: usize) -> Vec<([f64; D], usize)> {
    let mut r = common::rng(seed);
    (0..n)
        .map(|i| (core::array::from_fn(|_| r.r#gen::<f64>()), i))
        .collect()
}

/// NaN, +inf and -inf anywhere: `NonFiniteCoordinate` naming the first bad point and its first
/// bad axis, with or without a root box, and a message naming the point.
fn non_finite<const D: usize>(seed: u64) {
    let n = 20;
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for index in [0, 7, n - 1] {
            for axis in 0..D {
                let mut e = random_entries::<D>(seed, n);
                e[index].0[axis] = bad;
                // a later bad point on another axis does not mask the first one
                if index + 1 < n {
                    e[index + 1].0[0] = f64::NAN;
                }
                for given in [false, true] {
                    let mut b = PointTreeBuilder::<f64, D>::new();
                    if given {
                        b = b.root_box(Aabb::new([0.0; D], [1.0; D]).unwrap());
                    }
                    let err = b.build(&e).unwrap_err();
                    match &err {
                        Error::NonFiniteCoordinate {
                            index: i,
                            axis: a,
                            value,
                        } => {
                            assert_eq!((*i, *a), (index, axis));
                            assert!(
                                value.get().to_bits() == bad.to_bits()
                                    || (bad.is_nan() && value.get().is_nan())
                            );
                        }
                        other => panic!("expected NonFiniteCoordinate, got {other:?}"),
                    }
                    let msg = err.to_string();
                    assert!(msg.contains(&format!("point {index}")), "{msg}");
                    assert!(msg.contains(&format!("axis {axis}")), "{msg}");
                    let err2 = b.build_from_vec(e.clone()).unwrap_err();
                    assert_eq!(err2.to_string(), msg);
                }
            }
        }
    }
}

#[test]
fn non_finite_coordinates_are_refused() {
    non_finite::<1>(101);
    non_finite::<2>(102);
    non_finite::<3>(103);
    // f32 too
    let e = [([0.0f32, 1.0], ()), ([2.0, f32::NAN], ())];
    let err = PointTree::<f32, (), 2>::new(&e).unwrap_err();
    assert!(
        matches!(err, Error::NonFiniteCoordinate { index: 1, axis: 1, value } if value.get().is_nan())
    );
}

/// The build checks its input in blocks of points: whatever block the first bad point falls in
/// (its first, its last, a later one, the last point of all), it is the one named, not a later
/// bad point of its block or of the next, whether it is not finite or outside the root box.
#[test]
fn the_first_bad_point_is_named_across_blocks() {
    let n = 2600;
    let unit = Aabb::new([0.0; 3], [1.0; 3]).unwrap();
    let named = |err: Error| match err {
        Error::NonFiniteCoordinate { index, axis, .. } => ("not finite", index, axis),
        Error::OutsideRootBox { index, axis, .. } => ("outside", index, axis),
        other => panic!("unexpected {other:?}"),
    };
    for index in [0, 1023, 1024, 2047, 2599] {
        let mut e = random_entries::<3>(121, n);
        for later in [index + 1, index + 700].into_iter().filter(|&l| l < n) {
            e[later].0[0] = f64::INFINITY;
        }
        let boxed = PointTreeBuilder::<f64, 3>::new().root_box(unit);
        e[index].0[2] = f64::NAN;
        for builder in [PointTreeBuilder::new(), boxed] {
            let err = builder.build(&e).unwrap_err();
            assert_eq!(named(err), ("not finite", index, 2));
        }
        e[index].0[2] = 1.5;
        assert_eq!(named(boxed.build(&e).unwrap_err()), ("outside", index, 2));
        // without a root box 1.5 is a good coordinate: the infinity after it is named
        match PointTree::new(&e) {
            Err(err) => assert_eq!(named(err), ("not finite", index + 1, 0)),
            Ok(tree) => assert!(index == n - 1 && tree.len() == n),
        }
    }
}

/// Points outside a given root box: `OutsideRootBox` naming the first such point, its first bad
/// axis, its coordinate and the box's interval.
#[test]
fn points_outside_the_root_box_are_refused() {
    let unit = Aabb::new([0.0; 2], [1.0; 2]).unwrap();
    let cases: [(usize, [f64; 2], usize, f64); 5] = [
        (2, [0.5, 1.5], 1, 1.5),
        (0, [-0.25, 0.5], 0, -0.25),
        (9, [1.0f64.next_up(), 2.0], 0, 1.0f64.next_up()),
        (4, [0.5, -f64::MIN_POSITIVE], 1, -f64::MIN_POSITIVE),
        (3, [f64::MAX, f64::MAX], 0, f64::MAX),
    ];
    for (index, p, axis, value) in cases {
        let mut e = random_entries::<2>(111, 10);
        e[index].0 = p;
        let err = Quadtree::builder().root_box(unit).build(&e).unwrap_err();
        assert_eq!(
            err,
            Error::OutsideRootBox {
                index,
                axis,
                value: value.into(),
                interval: (0.0.into(), 1.0.into())
            }
        );
        let msg = err.to_string();
        assert!(msg.contains(&format!("point {index}")), "{msg}");
        assert!(msg.contains(&format!("axis {axis}")), "{msg}");
    }
    // the box is closed: its boundary, -0.0 included, is inside
    let e = [([0.0, 1.0], 0), ([1.0, -0.0], 1), ([-0.0, 0.0], 2)];
    let t = Quadtree::builder().root_box(unit).build(&e).unwrap();
    check_all(&t, &e);
    // integers
    let e = [([0i32, 0], 0), ([5, 11], 1)];
    let err = PointTreeBuilder::<i32, 2>::new()
        .root_box(Aabb::new([0, 0], [10, 10]).unwrap())
        .build(&e)
        .unwrap_err();
    assert_eq!(
        err,
        Error::OutsideRootBox {
            index: 1,
            axis: 1,
            value: 11.0.into(),
            interval: (0.0.into(), 10.0.into())
        }
    );
}

/// `locate`: NaN or infinite coordinates are refused naming the axis, points outside the
/// domain are `Location::Outside` naming the first axis; the domain's boundary is inside.
#[test]
fn bad_queries_are_refused() {
    let e = random_entries::<3>(121, 200);
    for given in [false, true] {
        let mut b = PointTreeBuilder::<f64, 3>::new();
        if given {
            b = b.root_box(Aabb::new([0.0; 3], [1.0; 3]).unwrap());
        }
        let t = b.build(&e).unwrap();
        let dom = *t.domain();
        for axis in 0..3 {
            let mut q = [0.5; 3];
            q[axis] = f64::NAN;
            assert!(matches!(
                t.locate(&q),
                Err(QueryError::NotFinite { axis: a, value }) if a == axis && value.get().is_nan()
            ));
            q[axis] = f64::INFINITY;
            assert_eq!(
                t.locate(&q),
                Err(QueryError::NotFinite {
                    axis,
                    value: f64::INFINITY.into()
                })
            );
            q[axis] = f64::NEG_INFINITY;
            assert!(matches!(t.locate(&q), Err(QueryError::NotFinite { .. })));
            for outside in [
                dom.max[axis].next_up(),
                dom.min[axis].next_down(),
                1e9,
                -1e9,
            ] {
                q[axis] = outside;
                assert_eq!(t.locate(&q), Ok(Location::Outside { axis }));
            }
            let msg = {
                q[axis] = f64::NAN;
                t.locate(&q).unwrap_err().to_string()
            };
            assert!(msg.contains(&format!("axis {axis}")), "{msg}");
            // the domain's corners are inside and land in leaves whose boxes hold them
            for corner in [dom.min, dom.max] {
                let leaf = t.locate(&corner).unwrap().inside().unwrap();
                assert!(t.tree().is_leaf(leaf));
                assert!(t.cell_box(leaf).contains(&corner));
            }
        }
    }
}

#[test]
fn bad_settings_are_refused() {
    let e = random_entries::<2>(131, 10);
    assert_eq!(
        Quadtree::builder().bucket_size(0).build(&e).unwrap_err(),
        Error::ZeroBucketSize
    );
    assert_eq!(
        PointTreeBuilder::<f64, 2>::new()
            .bucket_size(0)
            .build::<usize>(&[])
            .unwrap_err(),
        Error::ZeroBucketSize
    );
    assert_eq!(
        Quadtree::builder()
            .max_depth(Cell::<2>::MAX_LEVEL + 1)
            .build(&e)
            .unwrap_err(),
        Error::MaxDepthTooLarge {
            requested: Cell::<2>::MAX_LEVEL + 1,
            limit: Cell::<2>::MAX_LEVEL
        }
    );
    assert_eq!(
        PointTreeBuilder::<f64, 3>::new()
            .max_depth(Cell::<3>::MAX_LEVEL + 1)
            .build::<usize>(&[])
            .unwrap_err(),
        Error::MaxDepthTooLarge {
            requested: Cell::<3>::MAX_LEVEL + 1,
            limit: Cell::<3>::MAX_LEVEL
        }
    );
    assert_eq!(
        PointTreeBuilder::<f64, 3>::new()
            .max_depth(u8::MAX)
            .build::<usize>(&[])
            .unwrap_err(),
        Error::MaxDepthTooLarge {
            requested: u8::MAX,
            limit: Cell::<3>::MAX_LEVEL
        }
    );
    // the deepest level itself is fine
    let t = Quadtree::builder()
        .max_depth(Cell::<2>::MAX_LEVEL)
        .build(&e)
        .unwrap();
    t.validate().unwrap();

    // inverted, NaN and infinite root boxes (built by hand: Aabb::new refuses them too)
    let inverted = Aabb {
        min: [0.0, 1.0],
        max: [1.0, 0.0],
    };
    assert_eq!(
        Aabb::new(inverted.min, inverted.max),
        Err(AabbError::Inverted { axis: 1 })
    );
    assert_eq!(
        Quadtree::builder()
            .root_box(inverted)
            .build(&e)
            .unwrap_err(),
        Error::InvalidRootBox(AabbError::Inverted { axis: 1 })
    );
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let b = Aabb {
            min: [0.0, 0.0],
            max: [bad, 1.0],
        };
        assert_eq!(
            Aabb::new(b.min, b.max),
            Err(AabbError::NonFinite { axis: 0 })
        );
        assert_eq!(
            Quadtree::builder().root_box(b).build(&e).unwrap_err(),
            Error::InvalidRootBox(AabbError::NonFinite { axis: 0 })
        );
    }
    let inverted_int = Aabb {
        min: [3i32, 0, 0],
        max: [2, 5, 5],
    };
    let err = PointTree::<i32, (), 3>::builder()
        .root_box(inverted_int)
        .build::<usize>(&[])
        .unwrap_err();
    assert_eq!(err, Error::InvalidRootBox(AabbError::Inverted { axis: 0 }));
    assert!(err.to_string().contains("axis 0"));
    // a degenerate (flat or single-point) box is valid
    let flat = Aabb::new([0.0, 0.5], [1.0, 0.5]).unwrap();
    let e2 = [([0.25, 0.5], 0), ([0.75, 0.5], 1)];
    let t = Quadtree::builder()
        .root_box(flat)
        .bucket_size(1)
        .build(&e2)
        .unwrap();
    check_all(&t, &e2);
    let dot = Aabb::new([2.0, 2.0], [2.0, 2.0]).unwrap();
    let e3 = [([2.0, 2.0], 0), ([2.0, 2.0], 1)];
    let t = Quadtree::builder()
        .root_box(dot)
        .bucket_size(1)
        .build(&e3)
        .unwrap();
    check_all(&t, &e3);
}

/// Builds with and without a root box spanning the points, bucket 1 and the default, and checks
/// everything (every point in its leaf's closed box, the split convention, `validate`, the
/// chapter's definition, balance).
fn extreme<const D: usize>(pts: &[[f64; D]]) {
    let e: Vec<([f64; D], usize)> = pts.iter().enumerate().map(|(i, p)| (*p, i)).collect();
    let min: [f64; D] = core::array::from_fn(|a| pts.iter().map(|p| p[a]).fold(f64::MAX, f64::min));
    let max: [f64; D] =
        core::array::from_fn(|a| pts.iter().map(|p| p[a]).fold(-f64::MAX, f64::max));
    let root = Aabb::new(min, max).unwrap();
    for bucket in [1, 16] {
        let t = PointTreeBuilder::<f64, D>::new()
            .bucket_size(bucket)
            .build(&e)
            .unwrap();
        check_all(&t, &e);
        let t = PointTreeBuilder::<f64, D>::new()
            .bucket_size(bucket)
            .root_box(root)
            .build(&e)
            .unwrap();
        check_all(&t, &e);
    }
}

const TINY: f64 = 5e-324; // the smallest subnormal

#[test]
fn extreme_magnitudes_build_and_validate() {
    let m = f64::MAX;
    extreme(&[[-m, -m], [m, m], [0.0, 0.0], [m, -m], [-m, m], [1.0, -1.0]]);
    extreme(&[[m, m], [m.next_down(), m], [m, m.next_down()]]);
    extreme(&[[-m], [-m.next_down()], [0.0], [m]]);
    extreme(&[[m; 3], [-m; 3], [0.5; 3], [-1e300, 1e-300, 7.0]]);
    // the same point at the extremes (root cube of side 1 at a huge corner)
    extreme(&[[m, -m], [m, -m]]);
    // mixed magnitudes per point
    extreme(&[
        [m, TINY],
        [-m, -TINY],
        [1.0, m],
        [f64::MIN_POSITIVE, -m],
        [TINY, 0.0],
    ]);
}

#[test]
fn subnormal_coordinates_build_and_validate() {
    extreme(&[
        [TINY, 0.0],
        [1e-320, 2.0 * TINY],
        [f64::MIN_POSITIVE, TINY],
        [0.0, 0.0],
        [-3.0 * TINY, 1e-310],
    ]);
    extreme(&[
        [0.0, 0.0],
        [TINY, TINY],
        [2.0 * TINY, TINY],
        [TINY, 2.0 * TINY],
    ]);
    extreme(&[[-2.0 * TINY], [TINY], [0.0]]);
    extreme(&[
        [f64::MIN_POSITIVE, 1.0],
        [f64::MIN_POSITIVE.next_up(), 1.0],
        [f64::MIN_POSITIVE, 0.5],
    ]);
}

/// A fixed defect (`RootGeometry::enclosing` and `RootGeometry::new`): the root
/// cube's lower corner was stored halved (`half_lo = min * 0.5`), and halving is inexact below
/// 2 * f64::MIN_POSITIVE. When the smallest coordinate is an odd number of subnormal steps and the
/// halving rounds up (ties to even: 3 steps -> 1.5 -> 2, -1 step -> -0.5 -> -0), the cube's lower
/// side `2 * half_lo` lies above that coordinate: without a root box, `validate` fails ("point lies
/// outside the domain") and `locate` placed an input point outside the domain; with a root
/// box, the point's leaf box (`cell_box`) does not contain it.
#[test]
fn subnormal_minimum_lies_in_the_root_cube() {
    let steps = |k: i64| f64::from_bits(k.unsigned_abs()) * (k.signum() as f64);
    extreme(&[[steps(3), 1.0], [1.0, steps(3)]]);
    extreme(&[[steps(3)], [1e-300]]);
    extreme(&[[steps(7), steps(7)], [1e-310, 1e-310]]);
    extreme(&[[steps(-1), 1.0], [1.0, 0.0]]);
    extreme(&[[steps(-5)], [steps(8)]]);
    let just_above_min_positive = f64::from_bits(f64::MIN_POSITIVE.to_bits() + 3);
    extreme(&[[just_above_min_positive, 0.5], [1.0, 0.5]]);
}

/// 64-bit integers at their extremes: those `f64` holds exactly build and validate; the others
/// (`i64::MAX`, `u64::MAX`, odd values beyond 2^53) are refused, naming the point and axis. 8- and
/// 16-bit integers convert exactly.
#[test]
fn integer_extremes_build_and_validate() {
    let top = i64::MAX - 1023; // the largest i64 an f64 holds
    let e = [
        ([i64::MIN, top], 0usize),
        ([top, top - 1024], 1),
        ([0, 0], 2),
        ([top - 1024, top], 3),
        ([-1, 1], 4),
    ];
    for bucket in [1, 2] {
        let t = PointTreeBuilder::<i64, 2>::new()
            .bucket_size(bucket)
            .build(&e)
            .unwrap();
        check_points(&t, &e, None);
        check_all(&t, &e);
    }
    for (bad, index, axis) in [([i64::MIN, i64::MAX], 0, 1), ([i64::MAX - 1, 0], 1, 0)] {
        let mut e = e;
        e[index].0 = bad;
        assert_eq!(
            PointTree::new(&e).unwrap_err(),
            Error::InexactCoordinate {
                index,
                axis,
                value: bad[axis] as i128
            }
        );
    }
    let e = [
        ([u64::MAX - 2047], 0usize),
        ([0], 1),
        ([u64::MAX - 4095], 2),
        ([1 << 63], 3),
    ];
    let t = PointTreeBuilder::<u64, 1>::new()
        .bucket_size(1)
        .build(&e)
        .unwrap();
    check_all(&t, &e);
    for bad in [u64::MAX, u64::MAX - 1, (1 << 63) + 1] {
        let mut e = e;
        e[2].0 = [bad];
        let err = PointTree::new(&e).unwrap_err();
        assert_eq!(
            err,
            Error::InexactCoordinate {
                index: 2,
                axis: 0,
                value: bad as i128
            }
        );
        assert!(err
            .to_string()
            .contains(&format!("point 2: coordinate {bad} on axis 0")));
    }
    let e: Vec<([u8; 3], usize)> = (0..=255u8)
        .map(|i| ([i, 255 - i, i / 2], usize::from(i)))
        .collect();
    let t = PointTreeBuilder::<u8, 3>::new()
        .bucket_size(1)
        .build(&e)
        .unwrap();
    check_all(&t, &e);
    let e: Vec<([i16; 2], usize)> = (0..300i16)
        .map(|i| ([i * 100 - 15000, -i], i as usize))
        .collect();
    let t = PointTreeBuilder::<i16, 2>::new()
        .bucket_size(3)
        .build(&e)
        .unwrap();
    check_all(&t, &e);
}

/// Empty input: one leaf, no points, the unit cube as domain unless a root box is given.
fn empty<const D: usize>() {
    let t = PointTreeBuilder::<f64, D>::new()
        .build::<usize>(&[])
        .unwrap();
    assert_eq!(t.len(), 0);
    assert!(t.is_empty());
    assert_eq!(t.node_count(), 1);
    assert_eq!(t.leaf_count(), 1);
    assert_eq!(t.depth(), 0);
    let leaves: Vec<_> = t.leaves().collect();
    assert_eq!(leaves.len(), 1);
    assert_eq!(leaves[0].id, NodeId::ROOT);
    assert!(leaves[0].points.is_empty());
    assert_eq!(
        t.locate(&t.domain().min),
        Ok(Location::Inside(NodeId::ROOT))
    );
    assert_eq!(
        t.locate(&t.domain().max),
        Ok(Location::Inside(NodeId::ROOT))
    );
    check_all(&t, &[]);
    let mut b = t.clone();
    for opts in common::all_options() {
        assert!(b.balance(opts).is_empty());
    }
    b.validate().unwrap();
    let boxed = PointTreeBuilder::<f64, D>::new()
        .root_box(Aabb::new([-3.0; D], [5.0; D]).unwrap())
        .build_from_vec(Vec::<([f64; D], ())>::new())
        .unwrap();
    assert_eq!(boxed.len(), 0);
    assert_eq!(boxed.node_count(), 1);
    assert_eq!(boxed.domain().min, [-3.0; D]);
    assert_eq!(boxed.locate(&[-3.0; D]), Ok(Location::Inside(NodeId::ROOT)));
    assert_eq!(boxed.locate(&[-3.5; D]), Ok(Location::Outside { axis: 0 }));
    boxed.validate().unwrap();
}

#[test]
fn empty_input_builds() {
    empty::<1>();
    empty::<2>();
    empty::<3>();
    empty::<4>();
}

/// A single point: one leaf holding it, whatever the bucket size.
#[test]
fn single_point_builds() {
    for p in [
        [0.0, 0.0],
        [0.3, -7.0],
        [1e300, -1e-300],
        [f64::MAX, -f64::MAX],
    ] {
        for bucket in [1, 16] {
            let e = [(p, 0usize)];
            let t = Quadtree::builder().bucket_size(bucket).build(&e).unwrap();
            assert_eq!(t.len(), 1);
            assert_eq!(t.node_count(), 1);
            assert_eq!(t.depth(), 0);
            assert_eq!(t.locate(&p), Ok(Location::Inside(NodeId::ROOT)));
            assert!(t.domain().contains(&p));
            assert_eq!(t.node_points(NodeId::ROOT), &[p]);
            assert_eq!(t.node_items(NodeId::ROOT), &[0]);
            check_all(&t, &e);
        }
    }
    let e = [([0.25, 0.5, 0.75], 'x')];
    let t = Octree::new(&e).unwrap();
    assert_eq!(t.items(), &['x']);
    assert_eq!(t.leaf_count(), 1);
    t.validate().unwrap();
}

/// The reference for the build's input check: the first point, in input order, with a
/// coordinate that is not finite (then that axis), else the first outside `root` (its first
/// axis outside), one point at a time.
fn first_bad_by_scan(
    points: &[[f64; 2]],
    root: Option<&Aabb<f64, 2>>,
) -> Option<(usize, usize, bool)> {
    points.iter().enumerate().find_map(|(i, p)| {
        if let Some(a) = (0..2).find(|&a| !p[a].is_finite()) {
            return Some((i, a, false));
        }
        let r = root?;
        (0..2)
            .find(|&a| !(r.min[a] <= p[a] && p[a] <= r.max[a]))
            .map(|a| (i, a, true))
    })
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]

    /// Random inputs of up to a few blocks with a few bad coordinates (NaN, infinities, points
    /// just outside the root box) anywhere: the build names what a point-by-point check names,
    /// serially and in parallel, and builds a valid tree when that check finds nothing.
    #[test]
    fn the_build_names_the_first_bad_point_of_a_point_by_point_check(
        n in 1usize..5000,
        seed in 0u64..1000,
        bad in proptest::collection::vec((0usize..5000, 0usize..2, 0u8..5), 0..4),
        boxed in proptest::bool::ANY,
    ) {
        let mut points: Vec<[f64; 2]> = random_entries::<2>(seed, n).into_iter().map(|e| e.0).collect();
        for &(at, axis, kind) in &bad {
            points[at % n][axis] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 1.0f64.next_up(), -0.5][kind as usize];
        }
        let unit = Aabb::new([0.0; 2], [1.0; 2]).unwrap();
        let root = boxed.then_some(unit);
        let builder = match root {
            Some(r) => PointTreeBuilder::<f64, 2>::new().root_box(r),
            None => PointTreeBuilder::new(),
        };
        let named = |result: Result<PointTree<f64, u32, 2>, Error>| match result {
            Ok(tree) => {
                tree.validate().unwrap();
                None
            }
            Err(Error::NonFiniteCoordinate { index, axis, .. }) => Some((index, axis, false)),
            Err(Error::OutsideRootBox { index, axis, .. }) => Some((index, axis, true)),
            Err(other) => panic!("unexpected {other:?}"),
        };
        let expected = first_bad_by_scan(&points, root.as_ref());
        proptest::prop_assert_eq!(named(builder.build_indexed(&points)), expected);
        #[cfg(feature = "rayon")]
        {
            let entries: Vec<([f64; 2], u32)> = points.iter().zip(0..).map(|(p, i)| (*p, i)).collect();
            proptest::prop_assert_eq!(named(builder.par_build(&entries)), expected);
        }
    }
}
