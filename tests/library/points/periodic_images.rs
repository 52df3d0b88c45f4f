//! The image search of the periodic k-nearest queries against brute force: period boxes that
//! are not cubes (a different lower corner and period on each axis), some axes not wrapping,
//! trees whose root box is the points' own cube (the images are searched) or reaches far beyond
//! the period box (the engines bound boxes by their nearest image instead), queries inside and
//! outside the period box, points on both faces, duplicates, and `k` and `k`-th distances from
//! nothing up to beyond the period (tiny domains: every point is an answer, each once).
//!
//! Coordinates lie on dyadic grids, so every distance is exact: the answers of a `PointTree`
//! (whose slots are its traversal order) are compared, ties included, with the first `k` of
//! all points sorted by (minimum-image distance over all `3^k` images, slot).

use crate::common;

use common::points::config;
use orthtree::prelude::*;
use orthtree::query::{AxisMetric, Metric, MinImage, OutsidePoints};
use orthtree::query::{SquaredEuclidean, Torus};
use orthtree::{Aabb, CompressedTree, DynamicPointTree, PointTree};
use proptest::prelude::*;

/// The minimum over the `3^k` images of `b` of the combined offsets from `a` (`a` wrapped).
fn brute<M: AxisMetric, const D: usize>(t: &Torus<D>, a: &[f64; D], b: &[f64; D]) -> f64 {
    let wraps: Vec<usize> = (0..D).filter(|&i| t.wraps()[i]).collect();
    let mut best = f64::INFINITY;
    for code in 0..3usize.pow(wraps.len() as u32) {
        let mut shift = [0.0; D];
        let mut c = code;
        for &i in &wraps {
            shift[i] = ((c % 3) as f64 - 1.0) * t.period(i);
            c /= 3;
        }
        let mut s = 0.0;
        for i in 0..D {
            s = M::combine(s, (a[i] - (b[i] + shift[i])).abs());
        }
        best = best.min(s);
    }
    best
}

/// The `k` nearest of a `PointTree` (slots = traversal order) under the minimum-image `metric`
/// against brute force, ties included; and the same distances from the other trees.
fn check_metric<M, const D: usize>(
    trees: &Trees<D>,
    pts: &[[f64; D]],
    q: &[f64; D],
    metric: MinImage<M, D>,
) where
    M: AxisMetric + Copy,
    MinImage<M, D>: Metric<D>,
{
    let t = &metric.torus;
    let wq = t.wrap(q).unwrap();
    let tree = &trees.plain;
    let mut all: Vec<(f64, usize)> = (0..tree.len())
        .map(|s| (brute::<M, D>(t, &wq, tree.point(s)), s))
        .collect();
    all.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let n = pts.len();
    for k in [1, 2, 5, n, n + 3] {
        for max in [f64::INFINITY, 0.0, 1.0 / 64.0, 0.5, 4.0] {
            let want: Vec<(f64, usize)> = all
                .iter()
                .copied()
                .filter(|&(d, _)| d <= max)
                .take(k)
                .collect();
            let got: Vec<(f64, usize)> = tree
                .k_nearest_by(q, k, max, &metric)
                .unwrap()
                .iter()
                .map(|nb| (nb.distance, nb.index))
                .collect();
            assert_eq!(got, want, "k = {k}, max = {max}, q = {q:?}");
            let dists: Vec<f64> = want.iter().map(|w| w.0).collect();
            for other in [
                trees.wide.k_nearest_by(q, k, max, &metric).unwrap(),
                trees.dynamic.k_nearest_by(q, k, max, &metric).unwrap(),
                trees.compressed.k_nearest_by(q, k, max, &metric).unwrap(),
            ] {
                let d: Vec<f64> = other.iter().map(|nb| nb.distance).collect();
                assert_eq!(d, dists, "k = {k}, max = {max}");
                let mut items: Vec<usize> = other.iter().map(|nb| *nb.item).collect();
                items.sort_unstable();
                items.dedup();
                assert_eq!(items.len(), other.len(), "a point reported twice");
            }
        }
    }
    // The (1 + eps)-approximate search with eps = 0 takes the same path.
    let exact = tree.k_nearest_by(q, 4, f64::INFINITY, &metric).unwrap();
    let approx = tree
        .k_nearest_approx_by(q, 4, f64::INFINITY, 0.0, &metric)
        .unwrap();
    assert_eq!(exact, approx);
    // A positive eps keeps the guarantee on every answer.
    let loose = tree
        .k_nearest_approx_by(q, 4, f64::INFINITY, 1.0, &metric)
        .unwrap();
    assert_eq!(loose.len(), exact.len());
    for (a, e) in loose.iter().zip(&exact) {
        assert!(a.distance <= metric.scale_distance(e.distance, 2.0));
    }
}

/// One point set in every tree: the `PointTree` over the points' own cube, one over a root box
/// reaching several periods beyond the period box, and the dynamic and compressed trees.
struct Trees<const D: usize> {
    plain: PointTree<f64, usize, D>,
    wide: PointTree<f64, usize, D>,
    dynamic: DynamicPointTree<f64, usize, D>,
    compressed: CompressedTree<f64, usize, D>,
}

fn check_all<const D: usize>(
    lo: [f64; D],
    period: [f64; D],
    wraps: [bool; D],
    raw: &[[f64; D]],
    queries: &[[f64; D]],
) {
    let hi: [f64; D] = core::array::from_fn(|a| lo[a] + period[a]);
    let t = Torus::new(lo, hi, wraps).unwrap();
    let pts = t.prepare(raw, OutsidePoints::Wrap).unwrap();
    let e: Vec<([f64; D], usize)> = pts.iter().enumerate().map(|(i, p)| (*p, i)).collect();
    let plain = PointTree::builder().bucket_size(2).build(&e).unwrap();
    let wide = PointTree::builder()
        .root_box(Aabb::new([-64.0; D], [64.0; D]).unwrap())
        .bucket_size(3)
        .build(&e)
        .unwrap();
    let trees = Trees {
        dynamic: DynamicPointTree::from(plain.clone()),
        compressed: CompressedTree::new(&e).unwrap(),
        plain,
        wide,
    };
    for q in queries {
        check_metric(&trees, &pts, q, t.squared_euclidean());
        check_metric(&trees, &pts, q, t.manhattan());
        check_metric(&trees, &pts, q, t.chebyshev());
        // The best-first iterator agrees with the search, ties included.
        let all = trees
            .plain
            .k_nearest_by(q, pts.len(), f64::INFINITY, &t.squared_euclidean())
            .unwrap();
        let iter: Vec<usize> = trees
            .plain
            .periodic_nearest_iter(&t, q)
            .unwrap()
            .map(|nb| nb.index)
            .collect();
        assert_eq!(iter, all.iter().map(|nb| nb.index).collect::<Vec<_>>());
        assert_eq!(
            trees
                .plain
                .periodic_nearest(&t, q)
                .unwrap()
                .map(|n| n.index),
            all.first().map(|n| n.index)
        );
    }
}

/// A lower corner and a period per axis, both dyadic: periods from a sixteenth (tiny domains,
/// every point near every other) to three.
fn axis() -> impl Strategy<Value = (f64, f64)> {
    (
        prop_oneof![Just(-0.5), Just(0.0), Just(0.25), Just(-3.0)],
        prop_oneof![Just(0.0625), Just(0.25), Just(1.0), Just(1.25), Just(3.0)],
    )
}

/// A coordinate `j / 16` of the period (both faces) along an axis, or up to one period
/// beyond either face.
fn coord((lo, period): (f64, f64)) -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => (0u8..=16).prop_map(move |j| lo + period * f64::from(j) / 16.0),
        1 => (0u8..=48).prop_map(move |j| lo - period + period * f64::from(j) / 16.0),
    ]
}

fn points<const D: usize>(
    axes: [(f64, f64); D],
    n: std::ops::Range<usize>,
) -> impl Strategy<Value = Vec<[f64; D]>> {
    let one: Vec<_> = axes.iter().map(|&a| coord(a)).collect();
    prop::collection::vec(one.prop_map(|v| core::array::from_fn(|i| v[i])), n)
}

macro_rules! images_proptest {
    ($name:ident, $d:literal) => {
        proptest! {
            #![proptest_config(config(48, 4242))]

            #[test]
            fn $name(
                (axes, raw, queries) in proptest::array::uniform::<_, $d>(axis()).prop_flat_map(
                    |axes| (Just(axes), points(axes, 0..60), points(axes, 1..4))
                ),
                dup in 0usize..6,
                wraps in proptest::array::uniform::<_, $d>(any::<bool>()),
            ) {
                let mut raw = raw;
                if let Some(&p) = raw.last() {
                    raw.extend(std::iter::repeat(p).take(dup));
                }
                let lo = axes.map(|a| a.0);
                let period = axes.map(|a| a.1);
                check_all(lo, period, wraps, &raw, &queries);
            }
        }
    };
}

images_proptest!(image_search_matches_all_images_2d, 2);
images_proptest!(image_search_matches_all_images_3d, 3);

/// Uniform points of a periodic unit cube, off any grid: the image search against the scan
/// over all 27 images within rounding, queries near faces, edges and corners included.
#[test]
fn faces_edges_and_corners_agree_with_all_images() {
    let mut x = 7u64;
    let mut next = || {
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    let t = Torus::wrapping([0.0; 3], [1.0; 3]).unwrap();
    let pts: Vec<[f64; 3]> = (0..3000).map(|_| [next(), next(), next()]).collect();
    let e: Vec<([f64; 3], usize)> = pts.iter().enumerate().map(|(i, p)| (*p, i)).collect();
    let tree = PointTree::new(&e).unwrap();
    let metric = t.squared_euclidean();
    let mut queries: Vec<[f64; 3]> = (0..100).map(|_| [next(), next(), next()]).collect();
    // Near a face, an edge, a corner; on the faces; outside the box.
    queries.extend([
        [0.001, 0.5, 0.5],
        [0.999, 0.001, 0.5],
        [0.999, 0.999, 0.001],
        [0.0, 0.0, 0.0],
        [1.0, 1.0, 1.0],
        [-0.01, 1.02, 2.5],
    ]);
    for q in &queries {
        let wq = t.wrap(q).unwrap();
        let mut all: Vec<f64> = pts
            .iter()
            .map(|p| brute::<SquaredEuclidean, 3>(&t, &wq, p))
            .collect();
        all.sort_by(f64::total_cmp);
        for k in [1, 10, 40] {
            let got = tree.periodic_k_nearest(&t, q, k).unwrap();
            assert_eq!(got.len(), k);
            for (nb, want) in got.iter().zip(&all) {
                assert!((nb.distance - want).abs() <= 1e-12, "{q:?}");
                assert_eq!(nb.distance, metric.distance(q, nb.point));
            }
            let mut items: Vec<usize> = got.iter().map(|nb| *nb.item).collect();
            items.sort_unstable();
            items.dedup();
            assert_eq!(items.len(), k);
        }
    }
}

/// A domain smaller than the k-th distance: every point answers once, at its one minimum-image
/// distance, whatever the number of images within reach.
#[test]
fn tiny_domains_report_each_point_once() {
    let t = Torus::new([0.0, 0.0, 0.0], [0.125, 0.25, 10.0], [true, true, false]).unwrap();
    let raw: Vec<[f64; 3]> = (0..40)
        .map(|i| {
            let i = f64::from(i);
            [i / 64.0, i / 32.0, i / 8.0]
        })
        .collect();
    let pts = t.prepare(&raw, OutsidePoints::Wrap).unwrap();
    let e: Vec<([f64; 3], usize)> = pts.iter().enumerate().map(|(i, p)| (*p, i)).collect();
    let tree = PointTree::builder().bucket_size(1).build(&e).unwrap();
    for q in [
        [0.0, 0.0, 0.0],
        [0.0625, 0.125, 2.0],
        [0.1171875, 0.2421875, 5.0],
    ] {
        let got = tree.periodic_k_nearest(&t, &q, 100).unwrap();
        assert_eq!(got.len(), pts.len());
        let mut items: Vec<usize> = got.iter().map(|nb| *nb.item).collect();
        items.sort_unstable();
        assert_eq!(items, (0..pts.len()).collect::<Vec<_>>());
        let wq = t.wrap(&q).unwrap();
        for nb in &got {
            assert_eq!(
                nb.distance,
                brute::<SquaredEuclidean, 3>(&t, &wq, nb.point),
                "{q:?}"
            );
        }
    }
}
