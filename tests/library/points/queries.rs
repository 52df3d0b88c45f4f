//! Every query kind against a brute-force scan: box, ball, half-space and user regions (lazy,
//! count, visitor), nearest, k-nearest and the nearest iterator under three metrics. Inputs on
//! a dyadic grid put points on split lines, on box faces, on spheres at exactly representable
//! distances and on half-space boundaries, with many duplicates; D = 1, 2, 3; f64, f32 and i32.
//! Plus empty trees, k > n, bad input, the untested inside cells, and exercise 14.13's worst case.

use orthtree::geom::Halves;
use orthtree::points::PointNode;
use orthtree::prelude::*;
use orthtree::query::{Chebyshev, Manhattan, Metric, QueryError, SpatialIndex, SquaredEuclidean};
use orthtree::{
    query::HalfSpace, query::Relation, Aabb, Ball, PointTree, Quadtree, Region, Scalar,
};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use std::cell::Cell as Counter;

fn config(cases: u32, seed: u64) -> Config {
    Config {
        cases,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: None,
        ..Config::default()
    }
}

fn f<S: Scalar, const D: usize>(p: &[S; D]) -> [f64; D] {
    p.map(Scalar::to_f64)
}

/// Items of the points in `region`, by brute force, sorted.
fn brute_region<S: Scalar, R: Region<D>, const D: usize>(
    t: &PointTree<S, usize, D>,
    region: &R,
) -> Vec<usize> {
    let mut v: Vec<usize> = t
        .iter()
        .filter(|(p, _)| region.contains(&f(p)))
        .map(|(_, &i)| i)
        .collect();
    v.sort_unstable();
    v
}

/// Checks every range-query form against brute force.
fn check_region<S: Scalar, R: Region<D>, const D: usize>(t: &PointTree<S, usize, D>, region: &R) {
    let want = brute_region(t, region);
    let mut lazy: Vec<usize> = t.query(region).unwrap().map(|(_, &i)| i).collect();
    lazy.sort_unstable();
    assert_eq!(lazy, want);
    assert_eq!(t.query_count(region).unwrap(), want.len());
    let mut visited = Vec::new();
    t.query_with(region, |p, &i| {
        assert!(region.contains(&f(p)));
        visited.push(i)
    })
    .unwrap();
    visited.sort_unstable();
    assert_eq!(visited, want);
}

/// All (distance, index) pairs within `max`, sorted: the oracle of every nearest query.
fn brute_nearest<S: Scalar, M: Metric<D>, const D: usize>(
    t: &PointTree<S, usize, D>,
    q: &[S; D],
    max: f64,
    m: &M,
) -> Vec<(f64, usize)> {
    let mut v: Vec<(f64, usize)> = t
        .points()
        .iter()
        .enumerate()
        .map(|(i, p)| (m.distance(&f(q), &f(p)), i))
        .filter(|&(d, _)| d <= max)
        .collect();
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    v
}

fn check_nearest<S: Scalar, M: Metric<D> + Copy, const D: usize>(
    t: &PointTree<S, usize, D>,
    q: &[S; D],
    k: usize,
    max: f64,
    m: M,
) {
    let all = brute_nearest(t, q, max, &m);
    let got: Vec<(f64, usize)> = t
        .k_nearest_by(q, k, max, &m)
        .unwrap()
        .iter()
        .map(|n| (n.distance, n.index))
        .collect();
    assert_eq!(got, all[..k.min(all.len())]);
    for n in t.k_nearest_by(q, k, max, &m).unwrap() {
        assert_eq!(t.points()[n.index], *n.point);
        assert_eq!(t.items()[n.index], *n.item);
    }
    let lazy: Vec<(f64, usize)> = t
        .nearest_iter_by(q, max, m)
        .unwrap()
        .map(|n| (n.distance, n.index))
        .collect();
    assert_eq!(lazy, all);
}

fn check_default_nearest<S: Scalar, const D: usize>(t: &PointTree<S, usize, D>, q: &[S; D]) {
    let all = brute_nearest(t, q, f64::INFINITY, &SquaredEuclidean);
    let one = t.nearest(q).unwrap().map(|n| (n.distance, n.index));
    assert_eq!(one, all.first().copied());
    let ten: Vec<_> = t
        .k_nearest(q, 10)
        .unwrap()
        .iter()
        .map(|n| (n.distance, n.index))
        .collect();
    assert_eq!(ten, all[..10.min(all.len())]);
    let it: Vec<_> = t
        .nearest_iter(q)
        .unwrap()
        .take(5)
        .map(|n| (n.distance, n.index))
        .collect();
    assert_eq!(it, all[..5.min(all.len())]);
    if let Some(&(d, _)) = all.get(2) {
        let within = t.k_nearest_within(q, 100, d).unwrap();
        assert_eq!(within.len(), all.iter().filter(|x| x.0 <= d).count());
        assert_eq!(
            t.nearest_within(q, d).unwrap().map(|n| n.index),
            Some(all[0].1)
        );
        assert_eq!(t.nearest_iter_within(q, d).unwrap().count(), within.len());
    }
}

/// Builds the tree and runs every query on it.
#[allow(clippy::too_many_arguments)]
fn run_all<S: Scalar, const D: usize>(
    points: &[[S; D]],
    bucket: usize,
    boxes: &[([f64; D], [f64; D])],
    balls: &[([f64; D], f64)],
    planes: &[([f64; D], f64)],
    queries: &[[S; D]],
    k: usize,
) {
    let entries: Vec<([S; D], usize)> = points.iter().enumerate().map(|(i, &p)| (p, i)).collect();
    let t = PointTree::builder()
        .bucket_size(bucket)
        .build(&entries)
        .unwrap();
    t.validate().unwrap();
    for &(a, b) in boxes {
        let lo = core::array::from_fn(|i| a[i].min(b[i]));
        let hi = core::array::from_fn(|i| a[i].max(b[i]));
        check_region(&t, &Aabb { min: lo, max: hi });
        check_region(&t, &Aabb { min: hi, max: lo }); // inverted: empty unless degenerate
    }
    for &(c, r) in balls {
        check_region(&t, &Ball::new(c, r).unwrap());
    }
    for &(n, b) in planes {
        check_region(&t, &HalfSpace::new(n, b).unwrap());
    }
    for q in queries {
        check_default_nearest(&t, q);
        for max in [f64::INFINITY, 0.0, 0.25, 1.0] {
            check_nearest(&t, q, k, max, SquaredEuclidean);
            check_nearest(&t, q, k, max, Manhattan);
            check_nearest(&t, q, k, max, Chebyshev);
        }
    }
}

/// A coordinate on the grid of eighths in [0, 2]: split lines, duplicates, exact distances.
/// A slab's distance under `m` from its one offset, and the same slab bounded as a box, as bits.
fn slab_and_box_bits<M: Metric<3>>(
    m: &M,
    q: &[f64; 3],
    axis: usize,
    slab: &Aabb<f64, 3>,
) -> (u64, u64) {
    let (lo, hi) = (slab.min[axis], slab.max[axis]);
    (
        m.slab_distance(q, axis, lo, hi).to_bits(),
        m.box_distance(q, slab).to_bits(),
    )
}

fn grid() -> impl Strategy<Value = f64> {
    (0u32..=16).prop_map(|j| j as f64 / 8.0)
}

fn grid_point<const D: usize>() -> impl Strategy<Value = [f64; D]> {
    proptest::array::uniform(grid())
}

fn normal<const D: usize>() -> impl Strategy<Value = [f64; D]> {
    proptest::array::uniform((-2i32..=2).prop_map(f64::from))
}

// Sizes reach a few times the engines' scan limit (128 points in 1D and 2D, 64 in 3D: a
// crossing node with fewer is scanned, not descended), so that the descent is tested too.
macro_rules! grid_case {
    ($name:ident, $d:literal, $seed:literal, $max:literal) => {
        proptest! {
            #![proptest_config(config(48, $seed))]
            #[test]
            fn $name(
                points in prop::collection::vec(grid_point::<$d>(), 0..$max),
                bucket in 1usize..4,
                boxes in prop::collection::vec((grid_point::<$d>(), grid_point::<$d>()), 3),
                balls in prop::collection::vec((grid_point::<$d>(), (0u32..12).prop_map(|r| r as f64 / 8.0)), 3),
                planes in prop::collection::vec((normal::<$d>(), (-16i32..=32).prop_map(|b| b as f64 / 8.0)), 3),
                queries in prop::collection::vec(grid_point::<$d>(), 3),
                k in 0usize..12,
            ) {
                run_all(&points, bucket, &boxes, &balls, &planes, &queries, k);
            }
        }
    };
}

grid_case!(grid_points_1d, 1, 101, 500);
grid_case!(grid_points_2d, 2, 102, 500);
grid_case!(grid_points_3d, 3, 103, 300);

proptest! {
    #![proptest_config(config(32, 104))]
    #[test]
    fn random_points_2d(
        points in prop::collection::vec(proptest::array::uniform2(-1.0f64..1.0), 1..600),
        lo in proptest::array::uniform2(-1.0f64..1.0),
        side in 0.0f64..1.0,
        c in proptest::array::uniform2(-1.0f64..1.0),
        r in 0.0f64..0.7,
        n in proptest::array::uniform2(-1.0f64..1.0),
        b in -1.0f64..1.0,
        q in proptest::array::uniform2(-1.5f64..1.5),
        k in 1usize..40,
    ) {
        let hi = [lo[0] + side, lo[1] + side];
        // Query boxes and balls at point coordinates put points on their boundary.
        let p0 = points[0];
        run_all(&points, 4, &[(lo, hi), (p0, hi)], &[(c, r), (p0, 0.0)], &[(n, b)], &[q, p0], k);
        // Leaves of hundreds of points: their tests run in several 64-point chunks.
        run_all(&points, 300, &[(lo, hi)], &[(c, r)], &[(n, b)], &[q], k);
    }

    #[test]
    fn f32_and_i32_points(
        raw in prop::collection::vec(proptest::array::uniform2(-20i32..20), 0..120),
        lo in proptest::array::uniform2(-20i32..20),
        side in 0i32..20,
        r in 0u32..15,
        q in proptest::array::uniform2(-25i32..25),
        k in 0usize..20,
    ) {
        let fl = |p: [i32; 2]| p.map(|x| x as f64);
        let boxes = [(fl(lo), fl([lo[0] + side, lo[1] + side]))];
        let balls = [(fl(q), r as f64)];
        let planes = [([1.0, 0.0], lo[0] as f64), ([1.0, -1.0], side as f64)];
        run_all(&raw, 2, &boxes, &balls, &planes, &[q], k);
        let halves: Vec<[f32; 2]> = raw.iter().map(|p| p.map(|x| x as f32 / 2.0)).collect();
        let qh = q.map(|x| x as f32 / 2.0);
        run_all(&halves, 3, &boxes, &balls, &planes, &[qh], k);
    }
}

#[test]
fn empty_trees_answer_nothing() {
    let t: Quadtree<u8> = Quadtree::new(&[]).unwrap();
    let b = Aabb::new([0.0; 2], [1.0; 2]).unwrap();
    assert_eq!(t.query(b).unwrap().count(), 0);
    assert_eq!(t.query_count(b).unwrap(), 0);
    assert_eq!(t.query_stats(b).unwrap().nodes_visited, 0);
    assert!(t.nearest(&[0.0, 0.0]).unwrap().is_none());
    assert!(t.k_nearest(&[0.0, 0.0], 5).unwrap().is_empty());
    assert_eq!(t.nearest_iter(&[0.0, 0.0]).unwrap().count(), 0);
}

#[test]
fn k_larger_than_n_and_zero() {
    let pts: Vec<([f64; 3], usize)> = (0..7).map(|i| ([i as f64, 0.0, 1.0], i)).collect();
    let t = PointTree::new(&pts).unwrap();
    assert_eq!(t.k_nearest(&[0.0; 3], 100).unwrap().len(), 7);
    assert_eq!(t.k_nearest(&[0.0; 3], usize::MAX).unwrap().len(), 7);
    assert!(t.k_nearest(&[0.0; 3], 0).unwrap().is_empty());
}

/// Points on a circle and queries at and near its centre: every point is about equally near, so
/// most points scanned beat the bound so far and the candidate list turns over again and again
/// (selections of the `k` nearest among `2k` for large `k`), with exact ties between mirrored
/// points. Every `k` from the sorted list's range to beyond `n`, under the three metrics.
#[test]
fn k_nearest_of_points_on_a_circle_equal_a_scan() {
    let n = 3000;
    let mut points: Vec<[f64; 2]> = (0..n)
        .map(|i| {
            let a = i as f64 * std::f64::consts::TAU / n as f64;
            [0.5 + 0.5 * a.cos(), 0.5 + 0.5 * a.sin()]
        })
        .collect();
    // copies of some points: equal distances with different indices
    points.extend_from_within(..40);
    let entries: Vec<([f64; 2], usize)> = points.iter().copied().zip(0..).collect();
    for bucket in [4, 64] {
        let t = PointTree::builder()
            .bucket_size(bucket)
            .build(&entries)
            .unwrap();
        for q in [[0.5, 0.5], [0.5 + 1e-3, 0.5], [0.47, 0.52], [1.2, 0.5]] {
            for k in [15, 16, 17, 33, 100, 257, n + 100] {
                check_nearest(&t, &q, k, f64::INFINITY, SquaredEuclidean);
                check_nearest(&t, &q, k, 0.2501, SquaredEuclidean);
                check_nearest(&t, &q, k, f64::INFINITY, Manhattan);
                check_nearest(&t, &q, k, f64::INFINITY, Chebyshev);
            }
        }
    }
}

#[test]
fn bad_input_is_a_typed_error() {
    let t = Quadtree::new(&[([0.0, 0.0], ()), ([1.0, 1.0], ())]).unwrap();
    let nan = f64::NAN;
    assert!(matches!(
        t.nearest(&[0.0, nan]),
        Err(QueryError::NotFinite { axis: 1, .. })
    ));
    assert!(matches!(
        t.k_nearest(&[f64::INFINITY, 0.0], 3),
        Err(QueryError::NotFinite { axis: 0, .. })
    ));
    assert!(t.nearest_iter(&[nan, 0.0]).is_err());
    assert!(matches!(
        t.in_ball(&[0.0, 0.0], -0.5),
        Err(QueryError::InvalidRadius { .. })
    ));
    assert!(matches!(
        t.in_ball(&[0.0, 0.0], nan),
        Err(QueryError::InvalidRadius { .. })
    ));
    assert!(matches!(
        t.in_ball(&[nan, 0.0], 1.0),
        Err(QueryError::NotFinite { .. })
    ));
    let raw = Ball {
        center: [0.0, 0.0],
        radius: -1.0,
    };
    assert!(t.query_count(raw).is_err());
    assert!(t.query(raw).is_err());
    assert!(matches!(
        t.nearest_within(&[0.0, 0.0], -1.0),
        Err(QueryError::InvalidMaxDistance { .. })
    ));
    assert!(t.nearest_iter_within(&[0.0, 0.0], nan).is_err());
    assert!(matches!(
        t.in_half_space([nan, 0.0], 0.0),
        Err(QueryError::InvalidNormal { axis: 0 })
    ));
    assert!(matches!(
        t.in_half_space([1.0, 0.0], nan),
        Err(QueryError::NanOffset)
    ));
    let b = Aabb {
        min: [0.0, nan],
        max: [1.0, 1.0],
    };
    assert!(matches!(
        t.query_count(b),
        Err(QueryError::NanBound { axis: 1 })
    ));
    // infinite box bounds and radius are fine
    let all = Aabb {
        min: [f64::NEG_INFINITY; 2],
        max: [f64::INFINITY; 2],
    };
    assert_eq!(t.query_count(all).unwrap(), 2);
    assert_eq!(t.in_ball(&[0.0, 0.0], f64::INFINITY).unwrap().count(), 2);
    assert!(!QueryError::NanOffset.to_string().is_empty());
}

/// A region that counts its point tests, and those that accept.
struct Counting<R> {
    inner: R,
    tests: Counter<usize>,
    accepted: Counter<usize>,
    classified: Counter<usize>,
}

impl<R: Region<2>> Region<2> for Counting<R> {
    fn classify(&self, cell: &Aabb<f64, 2>) -> Relation {
        self.classified.set(self.classified.get() + 1);
        self.inner.classify(cell)
    }
    fn contains(&self, p: &[f64; 2]) -> bool {
        self.tests.set(self.tests.get() + 1);
        let inside = self.inner.contains(p);
        self.accepted.set(self.accepted.get() + usize::from(inside));
        inside
    }
}

#[test]
fn inside_cells_are_reported_without_point_tests() {
    // 64 x 64 lattice, the box [0, 31.5]^2 holds the quadrant of 32 x 32 points exactly: the
    // level-1 cell [0, 31.5]^2 of the root cube [0, 63] is inside, none of its points is tested.
    // (The closed boxes of the cells right of and above it touch the box, so their points are
    // tested, and rejected.)
    let pts: Vec<([f64; 2], usize)> = (0..4096)
        .map(|i| ([(i % 64) as f64, (i / 64) as f64], i))
        .collect();
    let t = Quadtree::new(&pts).unwrap();
    let region = Counting {
        inner: Aabb::new([0.0, 0.0], [31.5, 31.5]).unwrap(),
        tests: Counter::new(0),
        accepted: Counter::new(0),
        classified: Counter::new(0),
    };
    assert_eq!(t.query(&region).unwrap().count(), 1024);
    assert_eq!(region.accepted.get(), 0);
    let tested = region.tests.get();
    assert!(tested < 4096 - 1024);
    assert_eq!(t.query_count(&region).unwrap(), 1024);
    assert_eq!(region.accepted.get(), 0);
    assert_eq!(region.tests.get(), 2 * tested);
    // An inside root: one classification, no test at all.
    let everything = Counting {
        inner: Aabb::new([0.0, 0.0], [63.0, 63.0]).unwrap(),
        tests: Counter::new(0),
        accepted: Counter::new(0),
        classified: Counter::new(0),
    };
    assert_eq!(t.query_count(&everything).unwrap(), 4096);
    assert_eq!(
        (everything.classified.get(), everything.tests.get()),
        (1, 0)
    );
    // A box through the middle of leaves does test, and only the points of crossing leaves.
    region.tests.set(0);
    let cut = Counting {
        inner: Aabb::new([0.0, 0.0], [30.5, 30.5]).unwrap(),
        ..region
    };
    let s = t.query_stats(&cut).unwrap();
    assert_eq!(s.count, 31 * 31);
    assert_eq!(s.points_tested, cut.tests.get());
    assert!(s.points_tested < 4096 / 4);
}

/// Exercise 14.13's worst case: n / 2 pairs just right of the line x = 1/2, each pair's points
/// 2^-d apart, so every pair stays crossing from level log2(n / 2) down to about level d.
#[test]
fn half_plane_worst_case_visits_order_n_times_depth() {
    let pairs = 64usize; // n = 128
    let e = 2f64.powi(-28);
    let mut pts = Vec::new();
    for i in 0..pairs {
        let y = (i as f64 + 0.5) / pairs as f64;
        pts.push(([0.5 + e, y], i));
        pts.push(([0.5 + 2.0 * e, y], i));
    }
    pts.push(([0.0, 0.0], 0));
    pts.push(([1.0, 1.0], 0)); // root cube [0, 1]^2
    let t = Quadtree::builder().bucket_size(1).build(&pts).unwrap();
    let d = t.depth() as usize;
    let n = t.len();
    let left = HalfSpace::new([1.0, 0.0], 0.5).unwrap();
    let s = t.query_stats(left).unwrap();
    assert_eq!(s.count, 1); // only (0, 0)
                            // Lower bound: each pair is crossing alone at every level from log2(pairs) + 1 to d - 1.
    let log = pairs.trailing_zeros() as usize;
    assert!(d >= 28, "depth {d}");
    assert!(
        s.nodes_visited >= pairs * (d - log - 2),
        "{} visited, d = {d}",
        s.nodes_visited
    );
    // Upper bound of the analysis: 1 + 4 * sum over levels of min(2^l, n / 2) crossing nodes.
    let bound: usize = 1 + 4
        * (0..d)
            .map(|l| (1usize << l.min(40)).min(n / 2))
            .sum::<usize>();
    assert!(s.nodes_visited <= bound);
    // Ordinary query: the same tree and a half-plane far from the pairs is cheap.
    let cheap = t
        .query_stats(HalfSpace::new([1.0, 0.0], 0.25).unwrap())
        .unwrap();
    assert!(cheap.nodes_visited < 40, "{}", cheap.nodes_visited);
    // The same bound for a rectangle whose right side is that line.
    let rect = Aabb::new([0.0, 0.0], [0.5, 1.0]).unwrap();
    let r = t.query_stats(rect).unwrap();
    assert_eq!(r.count, 1);
    assert!(r.nodes_visited >= pairs * (d - log - 2));
}

#[test]
fn ball_surface_and_plane_boundary_are_closed() {
    // Pythagorean points at distance exactly 5 (and 5^2 = 25 exactly).
    let pts = [
        ([3.0, 4.0], 0),
        ([-4.0, 3.0], 1),
        ([5.0, 0.0], 2),
        ([5.0, 0.5], 3),
        ([0.0, 0.0], 4),
    ];
    let t = Quadtree::builder().bucket_size(1).build(&pts).unwrap();
    let mut got: Vec<i32> = t
        .in_ball(&[0.0, 0.0], 5.0)
        .unwrap()
        .map(|(_, &i)| i)
        .collect();
    got.sort_unstable();
    assert_eq!(got, [0, 1, 2, 4]);
    assert_eq!(t.in_half_space([1.0, 1.0], 7.0).unwrap().count(), 5); // 3 + 4 = 7 is in
    assert_eq!(t.in_half_space([1.0, 1.0], 5.0).unwrap().count(), 3); // (5, 0) on it is in
    assert_eq!(t.in_ball(&[5.0, 0.0], 0.0).unwrap().count(), 1);
    let near = t.k_nearest(&[0.0, 0.0], 4).unwrap();
    assert_eq!(near[0].distance, 0.0);
    assert!(near[1..].iter().all(|n| n.distance == 25.0));
    let idx: Vec<usize> = near.iter().map(|n| n.index).collect();
    assert!(
        idx[1..].windows(2).all(|w| w[0] < w[1]),
        "ties by index: {idx:?}"
    );
}

/// The child of `node` with the nearest box, the first of equals: what
/// `SpatialIndex::nearest_child` promises.
fn nearest_child_by_boxes<M: Metric<D>, const D: usize>(
    t: &PointTree<f64, usize, D>,
    node: PointNode<D>,
    bbox: &Aabb<f64, D>,
    q: &[f64; D],
    metric: &M,
) -> Option<(PointNode<D>, Aabb<f64, D>)> {
    let mut next: Option<(f64, PointNode<D>, Aabb<f64, D>)> = None;
    t.for_each_child_in(node, bbox, |child, cb| {
        let d = metric.box_distance(q, cb);
        if next.as_ref().is_none_or(|n| d < n.0) {
            next = Some((d, child, *cb));
        }
    });
    next.map(|(_, child, cb)| (child, cb))
}

/// Walks down from the root by `nearest_child`, checking each step under `metric`.
fn check_nearest_child_walk<M: Metric<D>, const D: usize>(
    points: &[[f64; D]],
    bucket: usize,
    q: &[f64; D],
    metric: &M,
) {
    let entries: Vec<([f64; D], usize)> = points.iter().enumerate().map(|(i, p)| (*p, i)).collect();
    let t = PointTree::builder()
        .bucket_size(bucket)
        .build(&entries)
        .unwrap();
    let Some((mut node, mut bbox)) = t.root() else {
        return;
    };
    loop {
        let fast = t.nearest_child(node, &bbox, q, metric);
        assert_eq!(fast, nearest_child_by_boxes(&t, node, &bbox, q, metric));
        match fast {
            Some((child, cb)) => (node, bbox) = (child, cb),
            None => break,
        }
    }
}

proptest! {
    #![proptest_config(config(64, 105))]
    /// The point tree finds the child holding the query by comparing with the split lines;
    /// queries on split lines, in empty children and outside the root box get the child the
    /// box distances give (under Chebyshev, outside the box, equally near children abound).
    #[test]
    fn nearest_child_agrees_with_box_distances(
        points2 in prop::collection::vec(grid_point::<2>(), 0..200),
        points3 in prop::collection::vec(grid_point::<3>(), 0..200),
        bucket in 1usize..4,
        q2 in proptest::array::uniform2((-4i32..=20).prop_map(|j| j as f64 / 8.0)),
        q3 in proptest::array::uniform3((-4i32..=20).prop_map(|j| j as f64 / 8.0)),
    ) {
        check_nearest_child_walk(&points2, bucket, &q2, &SquaredEuclidean);
        check_nearest_child_walk(&points3, bucket, &q3, &SquaredEuclidean);
        check_nearest_child_walk(&points2, bucket, &q2, &Chebyshev);
        check_nearest_child_walk(&points3, bucket, &q3, &Chebyshev);
    }
}

/// A value on the dyadic grid of `grid`, scaled by one of several powers of two (tiny, plain
/// and huge), or an infinity.
fn scaled_grid() -> impl Strategy<Value = f64> {
    (
        grid(),
        prop::sample::select(vec![-1040, -520, 0, 500, 1000]),
        0u8..20,
    )
        .prop_map(|(x, e, inf)| match inf {
            0 => f64::INFINITY,
            1 => f64::NEG_INFINITY,
            _ => x * 2f64.powi(e),
        })
}

proptest! {
    #![proptest_config(config(512, 106))]
    /// A ball's shortcut for "outside" answers as its classification does, on boxes and balls
    /// on a grid (spheres through corners), at tiny and huge scales, with infinite sides; the
    /// halves a ball, the Euclidean and the Manhattan metric rule out by changed terms are those
    /// their tests of the half boxes rule out.
    #[test]
    fn ball_excludes_exactly_what_it_classifies_outside(
        lo in proptest::array::uniform3(scaled_grid()),
        hi in proptest::array::uniform3(scaled_grid()),
        c in proptest::array::uniform3(grid()),
        r in scaled_grid(),
        scale in prop::sample::select(vec![2f64.powi(-1040), 1.0, 2f64.powi(1000)]),
    ) {
        let cell = Aabb { min: core::array::from_fn(|a| lo[a].min(hi[a])), max: core::array::from_fn(|a| lo[a].max(hi[a])) };
        let Ok(ball) = Ball::new(c.map(|x| x * scale), r.abs()) else { return Ok(()) };
        // the halves, split anywhere in the box: by changed terms as by the half boxes
        let mid: [f64; 3] = core::array::from_fn(|a| match (cell.min[a], cell.max[a]) {
            (lo, hi) if lo.is_finite() && hi.is_finite() => lo + (hi - lo) / 2.0,
            (lo, hi) if lo.is_finite() => lo.max(hi.min(0.0)),
            (_, hi) => hi,
        });
        let by_boxes = |h: &Aabb<f64, 3>| ball.excludes(h);
        prop_assert_eq!(ball.kept_children(&cell, &mid), by_boxes.kept(&cell, &mid));
        let q = ball.center;
        for bound in [0.0, r.abs(), r.abs() * r.abs()] {
            let euclid = |h: &Aabb<f64, 3>| SquaredEuclidean.box_distance(&q, h) > bound;
            prop_assert_eq!(SquaredEuclidean.kept_within(&q, &cell, &mid, bound), euclid.kept(&cell, &mid));
            let manhattan = |h: &Aabb<f64, 3>| Manhattan.box_distance(&q, h) > bound;
            prop_assert_eq!(Manhattan.kept_within(&q, &cell, &mid, bound), manhattan.kept(&cell, &mid));
        }
        prop_assert_eq!(ball.excludes(&cell), ball.classify(&cell) == Relation::Outside);
        // through a reference, as the engines take a region
        prop_assert_eq!(Region::excludes(&&ball, &cell), ball.excludes(&cell));
        // a slab's distance from its one offset equals the slab bounded as a box
        for axis in 0..3 {
            let (lo, hi) = (cell.min[axis], cell.max[axis]);
            let slab = Aabb {
                min: core::array::from_fn(|a| if a == axis { lo } else { f64::NEG_INFINITY }),
                max: core::array::from_fn(|a| if a == axis { hi } else { f64::INFINITY }),
            };
            for (slab_bits, box_bits) in [
                slab_and_box_bits(&SquaredEuclidean, &q, axis, &slab),
                slab_and_box_bits(&Manhattan, &q, axis, &slab),
                slab_and_box_bits(&Chebyshev, &q, axis, &slab),
            ] {
                prop_assert_eq!(slab_bits, box_bits);
            }
        }
    }
}
