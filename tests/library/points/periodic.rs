//! Periodic domains against brute force: every minimum-image query ([`PeriodicQueries`], the
//! `*_by` queries with [`MinImage`] metrics, the periodic ball and wrapping box as regions, the
//! batch forms) on `PointTree`, `DynamicPointTree`, `CompressedTree` and `SkipQuadtree` through
//! one generic check, against a scan over all `3^k` images of the `k` wrapping axes.
//!
//! Points lie on a dyadic grid over a period box `[-1/2, 3/4)` (period 5/4): every distance is
//! exact, so answers are compared exactly; the grid includes both faces (the upper one wraps to
//! the lower), split lines and duplicates. Random off-grid points are compared with a tolerance.
//! D = 1, 2, 3, any subset of wrapping axes, r = 0, r of half a period and more than a period,
//! k above the number of points, and empty trees.

use crate::common;

use common::points::config;
use orthtree::prelude::*;
use orthtree::query::{
    AxisMetric, Metric, MinImage, OutsidePoints, PeriodicBall, PeriodicBox, PeriodicError, Region,
    Torus,
};
use orthtree::query::{Chebyshev, Manhattan, SquaredEuclidean};
use orthtree::{Aabb, CompressedTree, DynamicPointTree, PointTree, SkipQuadtree};
use proptest::prelude::*;

use common::points::{brute_distance, HI, L, LO};

fn torus<const D: usize>(wraps: [bool; D]) -> Torus<D> {
    Torus::new([LO; D], [HI; D], wraps).unwrap()
}

/// `x` on the arc from `lo` up to `hi` of the circle of period `L` starting at `LO`.
fn on_arc(x: f64, lo: f64, hi: f64) -> bool {
    if hi - lo >= L {
        return true;
    }
    let w = |v: f64| LO + (v - LO).rem_euclid(L);
    let (a, b) = (w(lo), w(hi));
    (x - a).rem_euclid(L) <= (b - a).rem_euclid(L)
}

/// The k-nearest answers (and nearest, iterator) to `q` under `metric` against brute force.
fn check_knn<P, M, const D: usize>(
    t: &P,
    pts: &[[f64; D]],
    (q, wq): (&[f64; D], &[f64; D]),
    metric: MinImage<M, D>,
) where
    P: PointSet<D, Scalar = f64, Item = usize>,
    M: AxisMetric + Copy,
    MinImage<M, D>: Metric<D>,
{
    let wraps = metric.torus.wraps();
    let mut all: Vec<f64> = pts
        .iter()
        .map(|p| brute_distance::<M, D>(wraps, wq, p))
        .collect();
    all.sort_by(f64::total_cmp);
    for k in [0, 1, 3, pts.len(), pts.len() + 2] {
        for max in [f64::INFINITY, 0.0, 0.0625] {
            let got = t.k_nearest_by(q, k, max, &metric).unwrap();
            let want: Vec<f64> = all.iter().copied().filter(|&d| d <= max).take(k).collect();
            let dists: Vec<f64> = got.iter().map(|n| n.distance).collect();
            assert_eq!(dists, want, "k = {k}, max = {max}");
            let mut seen: Vec<usize> = got.iter().map(|n| *n.item).collect();
            seen.sort_unstable();
            seen.dedup();
            assert_eq!(seen.len(), got.len(), "a point reported twice");
            for n in &got {
                assert_eq!(*n.point, pts[*n.item]);
                assert_eq!(n.distance, brute_distance::<M, D>(wraps, wq, n.point));
            }
        }
    }
    let one = t.nearest_by(q, f64::INFINITY, &metric).unwrap();
    assert_eq!(one.map(|n| n.distance), all.first().copied());
    let iter: Vec<f64> = t
        .nearest_iter_by(q, f64::INFINITY, metric)
        .unwrap()
        .map(|n| n.distance)
        .collect();
    assert_eq!(iter, all, "the iterator yields every point, nearest first");
}

/// Items of `pts` in `region`, by the brute-force test `inside`, against the tree's answer.
fn check_region<P, R, const D: usize>(
    t: &P,
    pts: &[[f64; D]],
    region: R,
    inside: impl Fn(&[f64; D]) -> bool,
) where
    P: PointSet<D, Scalar = f64, Item = usize>,
    R: Region<D> + Copy,
{
    let want: Vec<usize> = (0..pts.len()).filter(|&i| inside(&pts[i])).collect();
    for (i, p) in pts.iter().enumerate() {
        assert_eq!(region.contains(p), want.contains(&i), "point test of {p:?}");
    }
    let mut got: Vec<usize> = t.query(region).unwrap().map(|(_, &i)| i).collect();
    got.sort_unstable();
    assert_eq!(got, want);
    assert_eq!(t.query_count(region).unwrap(), want.len());
}

/// Every periodic query of `t`, built over `pts` (already in the period box) with items `0..n`.
fn check<P, const D: usize>(
    t: &P,
    pts: &[[f64; D]],
    wraps: [bool; D],
    queries: &[[f64; D]],
    boxes: &[([f64; D], [f64; D])],
) where
    P: PointSet<D, Scalar = f64, Item = usize> + Sync,
{
    let tor = torus(wraps);
    for q in queries {
        // the brute force sees the query wrapped; the tree is given it as it is
        let wq = tor.wrap(q).unwrap();
        check_knn(t, pts, (q, &wq), tor.squared_euclidean());
        check_knn(t, pts, (q, &wq), tor.manhattan());
        check_knn(t, pts, (q, &wq), tor.chebyshev());
        // the convenience forms are the squared Euclidean `*_by` queries
        let by = t
            .k_nearest_by(q, 4, f64::INFINITY, &tor.squared_euclidean())
            .unwrap();
        let conv = t.periodic_k_nearest(&tor, q, 4).unwrap();
        assert!(by.iter().map(|n| n.index).eq(conv.iter().map(|n| n.index)));
        let within = t.periodic_k_nearest_within(&tor, q, 4, 0.0625).unwrap();
        assert!(within.iter().all(|n| n.distance <= 0.0625));
        assert_eq!(
            t.periodic_nearest(&tor, q).unwrap().map(|n| n.distance),
            by.first().map(|n| n.distance)
        );
        assert_eq!(t.periodic_nearest_iter(&tor, q).unwrap().count(), pts.len());
        for r in [0.0, 0.125, 0.3, L / 2.0, 0.9, L, 2.0 * L, f64::INFINITY] {
            let ball = PeriodicBall::new(tor, *q, r).unwrap();
            check_region(t, pts, ball, |p| {
                brute_distance::<SquaredEuclidean, D>(&wraps, &wq, p) <= r * r
            });
            assert_eq!(
                t.periodic_in_ball(&tor, q, r).unwrap().count(),
                t.query_count(ball).unwrap()
            );
        }
    }
    for (lo, hi) in boxes {
        let b = PeriodicBox::new(tor, *lo, *hi).unwrap();
        check_region(t, pts, b, |p| {
            (0..D).all(|a| {
                if wraps[a] {
                    on_arc(p[a], lo[a], hi[a])
                } else {
                    lo[a] <= p[a] && p[a] <= hi[a]
                }
            })
        });
        assert_eq!(
            t.periodic_in_box(&tor, *lo, *hi).unwrap().count(),
            t.query_count(b).unwrap()
        );
    }
    check_batches(t, pts, &tor, queries);
}

/// The parallel forms take the periodic regions as they are.
#[cfg(feature = "rayon")]
fn check_batches<P, const D: usize>(t: &P, pts: &[[f64; D]], tor: &Torus<D>, queries: &[[f64; D]])
where
    P: PointSet<D, Scalar = f64, Item = usize> + Sync,
{
    let balls: Vec<PeriodicBall<D>> = queries
        .iter()
        .map(|q| PeriodicBall::new(*tor, *q, 0.3).unwrap())
        .collect();
    let counts = t.par_query_count(&balls).unwrap();
    let found = t.par_query_indices(&balls).unwrap();
    for ((ball, &count), slots) in balls.iter().zip(&counts).zip(&found) {
        let mut items: Vec<usize> = slots.iter().map(|&s| t.items()[s]).collect();
        items.sort_unstable();
        let want: Vec<usize> = (0..pts.len()).filter(|&i| ball.contains(&pts[i])).collect();
        assert_eq!((items, count), (want.clone(), want.len()));
    }
}

#[cfg(not(feature = "rayon"))]
fn check_batches<P, const D: usize>(_: &P, _: &[[f64; D]], _: &Torus<D>, _: &[[f64; D]]) {}

/// Builds every tree over `raw` (wrapped first) and checks it.
fn all_trees<const D: usize>(
    raw: &[[f64; D]],
    wraps: [bool; D],
    queries: &[[f64; D]],
    boxes: &[([f64; D], [f64; D])],
) {
    let tor = torus(wraps);
    let pts = tor.prepare(raw, OutsidePoints::Wrap).unwrap();
    for (p, r) in pts.iter().zip(raw) {
        for a in 0..D {
            if wraps[a] {
                assert!(LO <= p[a] && p[a] < HI, "wrapped into [lo, hi)");
                assert_eq!(p[a], LO + (r[a] - LO).rem_euclid(L));
            } else {
                assert_eq!(p[a], r[a], "an ordinary axis is left alone");
            }
        }
    }
    let e: Vec<([f64; D], usize)> = pts.iter().enumerate().map(|(i, p)| (*p, i)).collect();
    let root = Aabb::new([-1.0; D], [1.0; D]).unwrap();
    let plain = PointTree::builder()
        .root_box(root)
        .bucket_size(2)
        .build(&e)
        .unwrap();
    let dynamic = DynamicPointTree::from(plain.clone());
    let compressed = CompressedTree::builder().root_box(root).build(&e).unwrap();
    let skip = SkipQuadtree::with_seed(compressed.clone(), 7);
    check(&plain, &pts, wraps, queries, boxes);
    check(&dynamic, &pts, wraps, queries, boxes);
    check(&compressed, &pts, wraps, queries, boxes);
    check(&skip, &pts, wraps, queries, boxes);
}

/// A coordinate of the grid of step 1/16 on [-1/2, 3/4] (both faces included).
fn coord() -> impl Strategy<Value = f64> {
    (0u8..=20).prop_map(|j| LO + f64::from(j) / 16.0)
}

/// A coordinate of the same grid on [-1, 1]: outside the period box too (ordinary axes keep
/// it; `prepare` wraps it on the others).
fn wide_coord() -> impl Strategy<Value = f64> {
    prop_oneof![3 => coord(), 1 => (0u8..=32).prop_map(|j| -1.0 + f64::from(j) / 16.0)]
}

fn point<const D: usize>() -> impl Strategy<Value = [f64; D]> {
    proptest::array::uniform::<_, D>(wide_coord())
}

/// Box corners: lo > hi (wrapping), empty, a point, a whole period and more.
fn periodic_box<const D: usize>() -> impl Strategy<Value = ([f64; D], [f64; D])> {
    (point::<D>(), point::<D>())
}

macro_rules! periodic_proptest {
    ($name:ident, $d:literal) => {
        proptest! {
            #![proptest_config(config(40, 2027))]

            #[test]
            fn $name(
                raw in prop::collection::vec(point::<$d>(), 0..70),
                dup in 0usize..10,
                wraps in proptest::array::uniform::<_, $d>(any::<bool>()),
                queries in prop::collection::vec(point::<$d>(), 1..3),
                boxes in prop::collection::vec(periodic_box::<$d>(), 1..4),
            ) {
                let mut raw = raw;
                if let Some(&p) = raw.first() {
                    raw.extend(std::iter::repeat(p).take(dup));
                }
                all_trees(&raw, wraps, &queries, &boxes);
            }
        }
    };
}

periodic_proptest!(periodic_queries_match_all_images_1d, 1);
periodic_proptest!(periodic_queries_match_all_images_2d, 2);
periodic_proptest!(periodic_queries_match_all_images_3d, 3);

#[test]
fn upper_face_is_lower_face() {
    let tor = torus([true, true]);
    let pts = tor
        .prepare(&[[HI, HI], [LO, LO]], OutsidePoints::Refuse)
        .unwrap();
    assert_eq!(pts, [[LO, LO], [LO, LO]]);
    let e: Vec<([f64; 2], usize)> = pts.iter().enumerate().map(|(i, p)| (*p, i)).collect();
    let t = PointTree::new(&e).unwrap();
    let near = t.periodic_k_nearest(&tor, &[HI, HI], 2).unwrap();
    assert_eq!(
        near.iter().map(|n| n.distance).collect::<Vec<_>>(),
        [0.0, 0.0]
    );
    // a ball wider than the whole torus reports each point once
    assert_eq!(
        t.periodic_in_ball(&tor, &[0.0, 0.0], 10.0).unwrap().count(),
        2
    );
    assert_eq!(
        t.periodic_in_box(&tor, [HI, HI], [HI, HI]).unwrap().count(),
        2
    );
}

#[test]
fn empty_trees_answer_nothing() {
    let tor = torus([true, false, true]);
    let none: [([f64; 3], usize); 0] = [];
    let t = PointTree::builder()
        .root_box(Aabb::new([LO; 3], [HI; 3]).unwrap())
        .build(&none)
        .unwrap();
    assert!(t.periodic_k_nearest(&tor, &[0.0; 3], 5).unwrap().is_empty());
    assert!(t.periodic_nearest(&tor, &[0.0; 3]).unwrap().is_none());
    assert_eq!(t.periodic_in_ball(&tor, &[0.0; 3], 1.0).unwrap().count(), 0);
    assert_eq!(
        t.periodic_in_box(&tor, [0.5; 3], [0.0; 3]).unwrap().count(),
        0
    );
}

#[test]
fn bad_periods_and_points_are_refused_by_name() {
    for (lo, hi) in [
        (0.0, 0.0),
        (1.0, 0.0),
        (f64::NAN, 1.0),
        (0.0, f64::INFINITY),
        (-f64::MAX, f64::MAX),
    ] {
        assert!(matches!(
            Torus::new([0.0, lo], [1.0, hi], [true, true]),
            Err(PeriodicError::InvalidPeriod { axis: 1, .. })
        ));
        // an ordinary axis's bounds are not used
        assert!(Torus::new([0.0, lo], [1.0, hi], [true, false]).is_ok());
    }
    let tor = torus([true, false]);
    let pts = [[0.0, 9.0], [0.1, f64::NAN], [0.8, 0.0]];
    assert_eq!(
        tor.prepare(&pts, OutsidePoints::Refuse),
        Err(PeriodicError::Outside {
            index: 2,
            axis: 0,
            value: 0.8.into()
        })
    );
    assert_eq!(
        tor.prepare(&pts, OutsidePoints::Wrap).unwrap()[2],
        [0.8 - L, 0.0]
    );
    assert!(matches!(
        tor.wrap(&[f64::INFINITY, 0.0]),
        Err(PeriodicError::NotFinite {
            index: 0,
            axis: 0,
            ..
        })
    ));
    assert!(PeriodicBall::new(tor, [0.0, 0.0], f64::NAN).is_err());
    assert!(PeriodicBall::new(tor, [0.0, f64::NAN], 1.0).is_err());
    assert!(PeriodicBox::new(tor, [0.0, f64::NAN], [1.0, 1.0]).is_err());
    let t = PointTree::new(&[([0.0, 0.0], 0usize)]).unwrap();
    assert!(t.periodic_k_nearest(&tor, &[f64::NAN, 0.0], 1).is_err());
    assert!(t
        .periodic_k_nearest_within(&tor, &[0.0, 0.0], 1, -1.0)
        .is_err());
    assert!(!PeriodicError::Outside {
        index: 2,
        axis: 0,
        value: 0.8.into()
    }
    .to_string()
    .is_empty());
}

#[test]
fn random_points_agree_within_rounding() {
    // Off-grid points from a fixed linear congruential sequence, on a period box [0.1, 0.9).
    let mut x = 99u64;
    let mut next = || {
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    let tor = Torus::wrapping([0.1; 3], [0.9; 3]).unwrap();
    let l = tor.period(0);
    let raw: Vec<[f64; 3]> = (0..2000)
        .map(|_| [next() * 2.0 - 0.5, next(), next()])
        .collect();
    let pts = tor.prepare(&raw, OutsidePoints::Wrap).unwrap();
    let e: Vec<([f64; 3], usize)> = pts.iter().enumerate().map(|(i, p)| (*p, i)).collect();
    let t = CompressedTree::new(&e).unwrap();
    let brute = |q: &[f64; 3], p: &[f64; 3]| {
        let mut best = f64::INFINITY;
        for code in 0..27 {
            let s = [code % 3, code / 3 % 3, code / 9].map(|c| c as f64 - 1.0);
            let d: f64 = (0..3).map(|a| (q[a] - p[a] - s[a] * l).powi(2)).sum();
            best = best.min(d);
        }
        best
    };
    for _ in 0..50 {
        let q = [next(), next(), next()].map(|v| 0.1 + v * 0.8);
        let mut all: Vec<f64> = pts.iter().map(|p| brute(&q, p)).collect();
        all.sort_by(f64::total_cmp);
        let got = t.periodic_k_nearest(&tor, &q, 10).unwrap();
        assert_eq!(got.len(), 10);
        for (n, want) in got.iter().zip(&all) {
            assert!(
                (n.distance - want).abs() <= 1e-12,
                "{} vs {want}",
                n.distance
            );
            assert!((n.distance - brute(&q, n.point)).abs() <= 1e-12);
        }
        let r2 = all[30];
        let found = t.periodic_in_ball(&tor, &q, r2.sqrt()).unwrap().count();
        let lo = all.iter().filter(|&&d| d <= r2 - 1e-12).count();
        let hi = all.iter().filter(|&&d| d <= r2 + 1e-12).count();
        assert!(lo <= found && found <= hi, "{lo} <= {found} <= {hi}");
    }
}

#[test]
fn manhattan_and_chebyshev_are_per_axis_minimum_images() {
    let tor = torus([true, true]);
    let (a, b) = ([-0.5, 0.0], [0.625, 0.5]);
    assert_eq!(tor.manhattan().distance(&a, &b), 0.125 + 0.5);
    assert_eq!(tor.chebyshev().distance(&a, &b), 0.5);
    assert_eq!(Manhattan.distance(&a, &b), 1.125 + 0.5);
    assert_eq!(Chebyshev.distance(&a, &b), 1.125);
}
