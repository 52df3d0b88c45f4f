//! The compressed quadtree against brute force and against `PointTree` on the same points: every
//! query kind (box, ball, half-space; nearest, k-nearest, the nearest iterator under three
//! metrics), on grid points (split lines, duplicates), random points and extreme coordinates;
//! updates that keep the tree equal to a fresh build, checked with `validate` after each; the
//! node-count bound on pathological inputs beside the plain tree's count; conversions; errors.

use crate::common;

use common::points::config;
use orthtree::prelude::*;
use orthtree::query::{Chebyshev, Manhattan, Metric, SquaredEuclidean};
use orthtree::{
    geom::DeepCell, query::HalfSpace, Aabb, Ball, CompressedTree, Error, PointTree, Quadtree,
    Region, Scalar,
};
use proptest::prelude::*;

fn f<S: Scalar, const D: usize>(p: &[S; D]) -> [f64; D] {
    p.map(Scalar::to_f64)
}

/// Items in `region` by brute force, sorted.
fn brute<S: Scalar, R: Region<D>, const D: usize>(pts: &[[S; D]], region: &R) -> Vec<usize> {
    (0..pts.len())
        .filter(|&i| region.contains(&f(&pts[i])))
        .collect()
}

fn check_region<S: Scalar, R: Region<D>, const D: usize>(
    c: &CompressedTree<S, usize, D>,
    p: &PointTree<S, usize, D>,
    pts: &[[S; D]],
    region: &R,
) {
    let want = brute(pts, region);
    let mut got: Vec<usize> = c.query(region).unwrap().map(|(_, &i)| i).collect();
    got.sort_unstable();
    assert_eq!(got, want);
    let mut plain: Vec<usize> = p.query(region).unwrap().map(|(_, &i)| i).collect();
    plain.sort_unstable();
    assert_eq!(plain, want);
    assert_eq!(c.query_count(region).unwrap(), want.len());
    assert_eq!(c.query_stats(region).unwrap().count, want.len());
    let mut visited = Vec::new();
    c.query_with(region, |q, &i| {
        assert_eq!(*q, pts[i]);
        visited.push(i)
    })
    .unwrap();
    visited.sort_unstable();
    assert_eq!(visited, want);
}

/// Nearest queries: (distance, item) lists equal brute force's up to ties, and the point tree's
/// up to the choice among points tied at the cut-off distance (the compressed tree orders the
/// points sharing one of the point tree's finest cells by their 64-level keys).
fn check_nearest<S: Scalar, M: Metric<D> + Copy, const D: usize>(
    c: &CompressedTree<S, usize, D>,
    p: &PointTree<S, usize, D>,
    pts: &[[S; D]],
    q: &[S; D],
    k: usize,
    max: f64,
    m: M,
) {
    let mut all: Vec<f64> = pts
        .iter()
        .map(|x| m.distance(&f(q), &f(x)))
        .filter(|&d| d <= max)
        .collect();
    all.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let got = c.k_nearest_by(q, k, max, &m).unwrap();
    let dists: Vec<f64> = got.iter().map(|n| n.distance).collect();
    assert_eq!(dists, all[..k.min(all.len())]);
    for n in &got {
        assert_eq!(pts[*n.item], *n.point);
        assert_eq!(m.distance(&f(q), &f(n.point)), n.distance);
    }
    {
        let plain: Vec<(f64, usize)> = p
            .k_nearest_by(q, k, max, &m)
            .unwrap()
            .iter()
            .map(|n| (n.distance, *n.item))
            .collect();
        let mine: Vec<(f64, usize)> = got.iter().map(|n| (n.distance, *n.item)).collect();
        // the same neighbours but for which of the points tied at the cut-off distance
        let cut = mine.last().map(|m| m.0);
        let below_cut = |v: &[(f64, usize)]| {
            let mut v: Vec<(f64, usize)> = v.iter().filter(|e| Some(e.0) != cut).copied().collect();
            v.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            v
        };
        assert_eq!(below_cut(&mine), below_cut(&plain));
    }
    let lazy: Vec<f64> = c
        .nearest_iter_by(q, max, m)
        .unwrap()
        .map(|n| n.distance)
        .collect();
    assert_eq!(lazy, all);
}

fn entries<S: Scalar, const D: usize>(pts: &[[S; D]]) -> Vec<([S; D], usize)> {
    pts.iter().enumerate().map(|(i, &p)| (p, i)).collect()
}

/// Builds both trees and runs every query on both.
fn run_all<S: Scalar, const D: usize>(
    pts: &[[S; D]],
    boxes: &[([f64; D], [f64; D])],
    balls: &[([f64; D], f64)],
    queries: &[[S; D]],
    k: usize,
) {
    let e = entries(pts);
    let c = CompressedTree::new(&e).unwrap();
    c.validate().unwrap();
    assert!(c.node_count() <= 2 * pts.len());
    let p = PointTree::builder().bucket_size(2).build(&e).unwrap();
    for &(a, b) in boxes {
        let lo = core::array::from_fn(|i| a[i].min(b[i]));
        let hi = core::array::from_fn(|i| a[i].max(b[i]));
        check_region(&c, &p, pts, &Aabb { min: lo, max: hi });
    }
    for &(centre, r) in balls {
        check_region(&c, &p, pts, &Ball::new(centre, r).unwrap());
        let normal = core::array::from_fn(|i| if i == 0 { 1.0 } else { -0.5 });
        check_region(&c, &p, pts, &HalfSpace::new(normal, centre[0]).unwrap());
    }
    for q in queries {
        for max in [f64::INFINITY, 0.0, 0.25] {
            check_nearest(&c, &p, pts, q, k, max, SquaredEuclidean);
            check_nearest(&c, &p, pts, q, k, max, Manhattan);
            check_nearest(&c, &p, pts, q, k, max, Chebyshev);
        }
    }
}

fn grid_point<const D: usize>() -> impl Strategy<Value = [f64; D]> {
    proptest::array::uniform((0u32..=16).prop_map(|j| j as f64 / 8.0))
}

/// Coordinates that make the plain tree deep or the arithmetic fragile.
fn extreme() -> impl Strategy<Value = f64> {
    prop_oneof![
        (1i32..=52).prop_map(|k| 1.0 - (-k as f64).exp2()),
        (0u32..4).prop_map(|j| f64::MIN_POSITIVE * j as f64),
        (0u32..3).prop_map(|j| f64::MAX / (1u64 << j) as f64),
        (0u32..=8).prop_map(|j| j as f64 / 8.0),
        (1i32..=40).prop_map(|k| 0.5 + (-k as f64).exp2()),
    ]
}

proptest! {
    #![proptest_config(config(48, 701))]
    #[test]
    fn grid_points_2d(
        pts in prop::collection::vec(grid_point::<2>(), 0..80),
        boxes in prop::collection::vec((grid_point::<2>(), grid_point::<2>()), 3),
        balls in prop::collection::vec((grid_point::<2>(), (0u32..12).prop_map(|r| r as f64 / 8.0)), 2),
        queries in prop::collection::vec(grid_point::<2>(), 2),
        k in 0usize..12,
    ) {
        run_all(&pts, &boxes, &balls, &queries, k);
    }

    #[test]
    fn grid_points_1d_and_3d(
        a in prop::collection::vec(grid_point::<1>(), 0..40),
        b in prop::collection::vec(grid_point::<3>(), 0..60),
        qa in grid_point::<1>(),
        qb in grid_point::<3>(),
        k in 1usize..8,
    ) {
        run_all(&a, &[([0.25], [1.0])], &[(qa.map(|x| x.max(0.0)), 0.5)], &[qa], k);
        run_all(&b, &[([0.25; 3], [1.0; 3])], &[(qb, 0.5)], &[qb], k);
    }

    #[test]
    fn random_and_extreme_points(
        uniform in prop::collection::vec(proptest::array::uniform2(-1.0f64..1.0), 1..200),
        wild in prop::collection::vec(proptest::array::uniform2(extreme()), 1..60),
        q in proptest::array::uniform2(-1.5f64..1.5),
        k in 1usize..20,
    ) {
        run_all(&uniform, &[([-0.5, -0.5], [0.3, 0.9])], &[(q, 0.4)], &[q, uniform[0]], k);
        let w0 = f(&wild[0]);
        run_all(&wild, &[([0.0, 0.0], [1.0, 1.0]), (w0, w0)], &[(w0, 0.0)], &[wild[0], [1.0, 1.0]], k);
    }

    #[test]
    fn i32_points(
        raw in prop::collection::vec(proptest::array::uniform2(-20i32..20), 0..100),
        q in proptest::array::uniform2(-25i32..25),
        k in 0usize..20,
    ) {
        run_all(&raw, &[([-5.0, -5.0], [5.0, 10.0])], &[(f(&q), 7.0)], &[q], k);
    }
}

/// The canonical form compared after updates: cells in pre-order and the sorted (point, item)
/// multiset of every leaf.
type Shape<const D: usize> = (Vec<(DeepCell<D>, bool)>, Vec<([u64; D], usize)>);

fn shape<const D: usize>(t: &CompressedTree<f64, usize, D>) -> Shape<D> {
    let cells = t.cells().collect();
    let mut pairs: Vec<([u64; D], usize)> = t
        .iter()
        .map(|(p, &i)| (t.geometry().deep_key(p), i))
        .collect();
    pairs.sort_unstable();
    (cells, pairs)
}

proptest! {
    #![proptest_config(config(64, 702))]
    #[test]
    fn updates_equal_a_fresh_build(
        start in prop::collection::vec(grid_point::<2>(), 0..30),
        ops in prop::collection::vec((any::<bool>(), grid_point::<2>(), 0usize..40), 1..80),
    ) {
        let root = Aabb::new([0.0, 0.0], [2.0, 2.0]).unwrap();
        let e = entries(&start);
        let mut t = CompressedTree::builder().root_box(root).build(&e).unwrap();
        let mut stored: Vec<([f64; 2], usize)> = e.clone();
        let mut next = start.len();
        for (insert, p, pick) in ops {
            if insert || stored.is_empty() {
                t.insert(p, next).unwrap();
                stored.push((p, next));
                next += 1;
            } else {
                let (q, item) = stored.swap_remove(pick % stored.len());
                prop_assert!(t.remove(&q, &item));
                prop_assert!(!t.remove(&[3.0, 3.0], &item));
            }
            t.validate().unwrap();
            let fresh = CompressedTree::builder().root_box(root).build(&stored).unwrap();
            prop_assert_eq!(shape(&t), shape(&fresh));
            prop_assert_eq!(t.node_count(), fresh.node_count());
        }
        // queries on the updated tree
        let pts: Vec<[f64; 2]> = t.points().to_vec();
        let b = Aabb::new([0.25, 0.5], [1.5, 1.25]).unwrap();
        let mut got: Vec<usize> = t.query(b).unwrap().map(|(_, &i)| i).collect();
        got.sort_unstable();
        let mut want: Vec<usize> = t.iter().filter(|(p, _)| b.contains(p)).map(|(_, &i)| i).collect();
        want.sort_unstable();
        prop_assert_eq!(got, want);
        if let Some(n) = t.nearest(&[1.0, 1.0]).unwrap() {
            let best = pts.iter().map(|p| SquaredEuclidean.distance(&[1.0, 1.0], p)).fold(f64::INFINITY, f64::min);
            prop_assert_eq!(n.distance, best);
        }
    }
}

proptest! {
    #![proptest_config(config(32, 703))]
    #[test]
    fn updates_with_extreme_coordinates(
        start in prop::collection::vec(proptest::array::uniform2(extreme()), 0..20),
        ops in prop::collection::vec((any::<bool>(), proptest::array::uniform2(extreme()), 0usize..30), 1..60),
    ) {
        let root = Aabb::new([0.0, 0.0], [f64::MAX, f64::MAX]).unwrap();
        let e = entries(&start);
        let mut t = CompressedTree::builder().root_box(root).build(&e).unwrap();
        let mut stored = e.clone();
        for (i, (insert, p, pick)) in ops.into_iter().enumerate() {
            if insert || stored.is_empty() {
                t.insert(p, 1000 + i).unwrap();
                stored.push((p, 1000 + i));
            } else {
                let (q, item) = stored.swap_remove(pick % stored.len());
                prop_assert!(t.remove(&q, &item));
            }
            t.validate().unwrap();
            let fresh = CompressedTree::builder().root_box(root).build(&stored).unwrap();
            prop_assert_eq!(shape(&t), shape(&fresh));
        }
        let q = [1.0, 0.5];
        let best = stored.iter().map(|(p, _)| SquaredEuclidean.distance(&q, p)).fold(f64::INFINITY, f64::min);
        prop_assert_eq!(t.nearest(&q).unwrap().map(|n| n.distance), (!stored.is_empty()).then_some(best));
    }
}

/// Pathological inputs for a plain quadtree (deep corners, tight clusters, tiny spacings), by name, each with the unit square's corners so that
/// the root cube is the unit square and the clusters sit deep inside it.
fn pathological() -> Vec<(&'static str, Vec<[f64; 2]>)> {
    let tiny = |k: i32| (-(k as f64)).exp2();
    let corner: Vec<[f64; 2]> = (1..=50).map(|k| [1.0 - tiny(k), 0.5]).collect();
    let mut clusters = Vec::new();
    for i in 0..100 {
        let d = i as f64 * tiny(30);
        clusters.push([0.1 + d, 0.1 + 0.5 * d]);
        clusters.push([0.9 - d, 0.9 - 0.5 * d]);
    }
    let spaced: Vec<[f64; 2]> = (0..200).map(|i| [0.3 + i as f64 * tiny(40), 0.7]).collect();
    let mut rng = common::rng(7);
    let mut pairs = Vec::new();
    for _ in 0..500 {
        use rand::Rng;
        let p = [rng.r#gen::<f64>(), rng.r#gen::<f64>()];
        pairs.push(p);
        pairs.push([p[0] + tiny(31), p[1]]);
    }
    let with_corners = |mut v: Vec<[f64; 2]>| {
        v.extend([[0.0, 0.0], [1.0, 1.0]]);
        v
    };
    vec![
        ("1 - 2^-k, k <= 50", with_corners(corner)),
        ("two clusters 2^-30 apart inside", with_corners(clusters)),
        ("spaced 2^-40 apart", with_corners(spaced)),
        ("500 pairs 2^-31 apart", with_corners(pairs)),
    ]
}

#[test]
fn node_count_is_linear_on_pathological_inputs() {
    for (name, pts) in pathological() {
        let e = entries(&pts);
        let c = CompressedTree::new(&e).unwrap();
        c.validate().unwrap();
        let plain = Quadtree::builder().bucket_size(1).build(&e).unwrap();
        let distinct = c.leaf_count();
        let branching = c
            .cells()
            .filter(|&(_, leaf)| !leaf)
            .map(|(cell, _)| cell.level());
        let branching = branching.max().unwrap_or(0);
        println!(
            "{name}: n = {}, distinct cells {distinct}, compressed {} nodes (depth {}, deepest \
             branching level {branching}), plain {} nodes (depth {})",
            pts.len(),
            c.node_count(),
            c.depth(),
            plain.node_count(),
            plain.depth()
        );
        assert!(c.node_count() <= 2 * distinct && distinct <= pts.len());
        // 64-level cells tell every point apart, where 32 levels do not always.
        assert_eq!(distinct, pts.len());
        if branching < orthtree::Cell::<2>::MAX_LEVEL {
            assert!(plain.node_count() >= c.node_count());
        } else {
            // the plain tree stops at its deepest level with points still together
            assert_eq!(plain.depth(), orthtree::Cell::<2>::MAX_LEVEL);
        }
        if name.contains("pairs") {
            assert!(plain.node_count() > 10 * c.node_count());
        }
    }
}

#[test]
fn conversions_keep_cells() {
    for (_, pts) in pathological() {
        let e = entries(&pts);
        let plain = Quadtree::builder().bucket_size(3).build(&e).unwrap();
        let c = CompressedTree::from(&plain);
        c.validate().unwrap();
        assert_eq!(c.geometry(), plain.geometry());
        assert_eq!(shape(&c), shape(&CompressedTree::from(plain.clone())));
        let back = c.to_point_tree(3, plain.max_depth()).unwrap();
        back.validate().unwrap();
        assert_eq!(back.geometry(), plain.geometry());
        let leaves =
            |t: &Quadtree<usize>| -> Vec<_> { t.tree().leaves().map(|(_, c)| c).collect() };
        assert_eq!(leaves(&back), leaves(&plain));
        assert_eq!(back.items(), plain.items());
        assert_eq!(c.to_point_tree(0, 4).unwrap_err(), Error::ZeroBucketSize);
        assert!(c.to_point_tree(1, 40).is_err());
    }
}

#[test]
fn bad_input_is_refused_by_name() {
    let err = CompressedTree::new(&[([0.0, 0.0], 0), ([1.0, f64::NAN], 1)]).unwrap_err();
    assert!(matches!(
        err,
        Error::NonFiniteCoordinate {
            index: 1,
            axis: 1,
            ..
        }
    ));
    let mut t = CompressedTree::new(&[([0.0, 0.0], 0), ([1.0, 1.0], 1)]).unwrap();
    let err = t.insert([0.5, 2.0], 2).unwrap_err();
    assert_eq!(err.item, 2, "the refused item is handed back");
    assert!(matches!(
        err.error,
        Error::OutsideRootBox {
            index: 2,
            axis: 1,
            ..
        }
    ));
    assert!(matches!(
        t.insert([f64::INFINITY, 0.0], 2).map_err(|e| e.error),
        Err(Error::NonFiniteCoordinate { axis: 0, .. })
    ));
    assert_eq!(
        t.locate(&[0.5, -1.0]),
        Ok(orthtree::query::Location::Outside { axis: 1 })
    );
    assert!(matches!(
        t.locate(&[f64::NAN, 0.0]),
        Err(orthtree::QueryError::NotFinite { axis: 0, .. })
    ));
    assert_eq!(t.remove_point(&[f64::NAN, 0.0]), None);
    assert!(t.nearest(&[f64::NAN, 0.0]).is_err());
    t.validate().unwrap();
    assert_eq!(t.len(), 2);
}

#[test]
fn empty_and_duplicate_heavy_trees() {
    let t: CompressedTree<f64, u8, 2> = CompressedTree::new(&[]).unwrap();
    assert_eq!((t.node_count(), t.depth()), (0, 0));
    assert!(t.nearest(&[0.0, 0.0]).unwrap().is_none());
    assert_eq!(
        t.query_count(Aabb::new([0.0; 2], [1.0; 2]).unwrap())
            .unwrap(),
        0
    );
    t.validate().unwrap();
    let same = vec![([0.3, 0.3], 7u8); 1000];
    let mut t = CompressedTree::new(&same).unwrap();
    assert_eq!(t.node_count(), 2); // the root and one leaf holding every copy
    assert_eq!(
        t.query_count(Ball::new([0.3, 0.3], 0.0).unwrap()).unwrap(),
        1000
    );
    for _ in 0..1000 {
        assert_eq!(t.remove_point(&[0.3, 0.3]), Some(7));
    }
    assert!(t.is_empty());
    t.validate().unwrap();
}
