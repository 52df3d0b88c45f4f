//! Outlier removal on clouds whose distances leave `f64`'s range: points up to `f64::MAX` apart
//! (and `-f64::MAX` to `f64::MAX`, twice that), far points beside a unit cluster, clouds of
//! coordinates near 1e-300 and down to the subnormals, and random mixes of all of them, against
//! a k-nearest scan that measures a quarter of every distance with `f64::hypot` (finite for
//! any finite points, and within a few roundings while normal), takes its means of terms divided
//! before they are summed and its statistics in units of the largest score: no step of it
//! overflows. A cloud scaled by a power of two has the verdict of the unscaled one.

use super::neighbours::threshold;
use crate::common::rng;
use orthtree::cloud::{outliers, Cloud};
use orthtree::{CompressedTree, PointSet, PointTree};
use rand::Rng;

/// A quarter of the Euclidean distance of `p` and `q`: `hypot` of the quartered offsets (each
/// at most `f64::MAX / 2`, so their norm is at most `sqrt(3) / 2 * f64::MAX`).
fn quarter_distance(p: &[f64; 3], q: &[f64; 3]) -> f64 {
    let h = |a: usize| p[a] * 0.25 - q[a] * 0.25;
    h(0).hypot(h(1)).hypot(h(2))
}

/// The scan's scores, in units of the largest (or of 1 when all are 0), the threshold in the
/// same units, and the largest score in quarters of distances.
fn reference(points: &[[f64; 3]], k: usize, ratio: f64) -> (Vec<f64>, f64, f64) {
    let quarters: Vec<f64> = (0..points.len())
        .map(|i| {
            let mut d: Vec<f64> = (0..points.len())
                .filter(|&j| j != i)
                .map(|j| quarter_distance(&points[i], &points[j]))
                .collect();
            d.sort_by(f64::total_cmp);
            d.truncate(k);
            d.iter().map(|x| x / d.len() as f64).sum()
        })
        .collect();
    let top = quarters.iter().fold(0.0f64, |m, &s| m.max(s));
    let unit = if top > 0.0 { top } else { 1.0 };
    let scores: Vec<f64> = quarters.iter().map(|s| s / unit).collect();
    let threshold = threshold(&scores, ratio);
    (scores, threshold, top)
}

/// `x * 2^n` in steps that stay exact while the result is normal.
fn ldexp(mut x: f64, mut n: i32) -> f64 {
    while n > 500 {
        x *= 2f64.powi(500);
        n -= 500;
    }
    while n < -500 {
        x *= 2f64.powi(-500);
        n += 500;
    }
    x * 2f64.powi(n)
}

/// A score or threshold `x` of `o` in units of `top` (quarters of distances), without overflow.
fn in_units_of(x: f64, o: &outliers::Outliers, top: f64) -> f64 {
    if top == 0.0 {
        return ldexp(x, o.scale);
    }
    let e = top.log2().floor() as i32;
    ldexp(x, o.scale - 2 - e) / ldexp(top, -e)
}

/// The verdict of a tree over `points` (items their indices) against the scan: the scores and
/// the threshold within a few roundings of the largest score, the verdict on every point not
/// within rounding of the threshold. Returns the verdict by index (`None` within rounding of
/// the threshold, where either verdict is right).
fn check_against_scan<P: orthtree::query::Joins<3, Item = usize> + Sync>(
    t: &P,
    points: &[[f64; 3]],
    k: usize,
    ratio: f64,
) -> Vec<Option<bool>> {
    let o = outliers::statistical(t, k, ratio).unwrap();
    let (scores, threshold, top) = reference(points, k, ratio);
    assert!(!o.threshold.is_nan(), "a NaN threshold");
    assert!(o.mean_distances.iter().all(|d| d.is_finite() && *d >= 0.0));
    for s in 0..t.len() {
        let i = t.items()[s];
        let got = in_units_of(o.mean_distances[s], &o, top);
        assert!(
            (got - scores[i]).abs() <= 1e-12,
            "score of {i}: {got:e} against {:e}",
            scores[i]
        );
    }
    let got_threshold = in_units_of(o.threshold, &o, top);
    let slack = 1e-9 * (1.0 + threshold.abs()) * (1.0 + ratio.abs());
    if threshold.is_finite() {
        assert!(
            (got_threshold - threshold).abs() <= slack,
            "threshold {got_threshold:e} against {threshold:e}"
        );
    } else {
        assert_eq!(got_threshold, threshold);
    }
    let mut keep = vec![None; points.len()];
    for s in 0..t.len() {
        let i = t.items()[s];
        assert_eq!(o.keep[s], o.mean_distances[s] <= o.threshold);
        if (scores[i] - threshold).abs() > slack {
            assert_eq!(
                o.keep[s],
                scores[i] <= threshold,
                "verdict of {i} ({:e} against {threshold:e})",
                scores[i]
            );
            keep[i] = Some(o.keep[s]);
        }
    }
    #[cfg(feature = "rayon")]
    assert_eq!(outliers::par_statistical(t, k, ratio).unwrap(), o);
    keep
}

/// Both trees over `points` against the scan, with the same verdict; the verdict by index
/// (`None` within rounding of the threshold).
fn check(points: &[[f64; 3]], k: usize, ratio: f64) -> Vec<Option<bool>> {
    let e: Vec<([f64; 3], usize)> = points.iter().copied().zip(0..).collect();
    let plain = check_against_scan(&PointTree::new(&e).unwrap(), points, k, ratio);
    let compressed = check_against_scan(&CompressedTree::new(&e).unwrap(), points, k, ratio);
    assert_eq!(plain, compressed);
    plain
}

#[test]
fn a_far_point_leaves_the_others_kept() {
    let mut pts = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [3.0, 0.0, 0.0],
    ];
    for far in [1e154, 1e200, 1e300, f64::MAX, -f64::MAX] {
        pts.truncate(4);
        pts.push([far, 0.0, 0.0]);
        // scores 1, 1, 1, 1 and |far|: z-score (n - 1) / sqrt(n) = 1.79 for the far one
        assert_eq!(check(&pts, 1, 2.0), [Some(true); 5], "far = {far:e}");
        let far_out = [true, true, true, true, false].map(Some);
        assert_eq!(check(&pts, 1, 1.0), far_out, "far = {far:e}");
        let cloud = Cloud::from_points(pts.clone());
        assert_eq!(
            outliers::remove_statistical(&cloud, 1, 1.0).unwrap().1,
            [0, 1, 2, 3]
        );
        assert_eq!(
            outliers::remove_statistical(&cloud, 1, 2.0).unwrap().1,
            [0, 1, 2, 3, 4]
        );
    }
}

#[test]
fn far_points_are_ranked_by_their_true_distances() {
    // The join's squared distances from 1e200 to 0..3 and to 3e200 are all infinite: the
    // nearest is 3 (about 1e200 away), not 3e200 (2e200).
    let pts = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [3.0, 0.0, 0.0],
        [1e200, 0.0, 0.0],
        [3e200, 0.0, 0.0],
        [-f64::MAX, 0.0, f64::MAX],
        [f64::MAX, f64::MAX, -f64::MAX],
    ];
    for k in 1..=8 {
        for ratio in [-1.0, 0.0, 0.5, 1.0, 2.0] {
            check(&pts, k, ratio);
        }
    }
    let e: Vec<([f64; 3], usize)> = pts.iter().copied().zip(0..).collect();
    let t = PointTree::new(&e).unwrap();
    let o = outliers::statistical(&t, 1, 1.0).unwrap();
    let slot = t.items().iter().position(|&i| i == 4).unwrap();
    assert!((ldexp(o.mean_distances[slot], o.scale) / 1e200 - 1.0).abs() < 1e-15);
}

#[test]
fn the_extremes_of_f64_are_twice_f64_max_apart() {
    let pts = [[-f64::MAX, 0.0, 0.0], [f64::MAX, 0.0, 0.0]];
    for k in [1, 3] {
        let e: Vec<([f64; 3], usize)> = pts.iter().copied().zip(0..).collect();
        let o = outliers::statistical(&PointTree::new(&e).unwrap(), k, 1.0).unwrap();
        // both scores 2 * f64::MAX = 2^1025 (1 - 2^-53): 1 - 2^-53 in units of 2^1025
        assert_eq!(o.scale, 1024);
        assert_eq!(o.mean_distances, [f64::MAX / 2f64.powi(1023); 2]);
        assert_eq!((o.threshold, o.keep), (o.mean_distances[0], vec![true; 2]));
        check(&pts, k, 1.0);
    }
    // with a cluster between them, the extremes are the outliers
    let mut pts = pts.to_vec();
    pts.extend((0..20).map(|i| [f64::from(i), f64::from(i % 3), 0.0]));
    let keep = check(&pts, 2, 1.0);
    assert_eq!((keep[0], keep[1]), (Some(false), Some(false)));
    assert!(keep[2..].iter().all(|&k| k == Some(true)));
}

#[test]
fn tiny_clouds_have_the_verdict_of_their_unit_copies() {
    // A cluster and a few points away from it, in small integers.
    let mut r = rng(5);
    let unit: Vec<[f64; 3]> = (0..60)
        .map(|i| {
            let spread = if i % 12 == 0 { 200 } else { 10 };
            [0, 1, 2].map(|_| f64::from(r.gen_range(-spread..=spread)))
        })
        .collect();
    for k in [1, 4, 9] {
        for ratio in [-0.5, 0.0, 1.0, 2.5] {
            let want = check(&unit, k, ratio);
            // 1e-300 times: every squared distance underflows in the join
            let tiny: Vec<[f64; 3]> = unit.iter().map(|p| p.map(|x| x * 1e-300)).collect();
            for (got, want) in check(&tiny, k, ratio).iter().zip(&want) {
                assert!(got.is_none() || want.is_none() || got == want);
            }
            // exact powers of two, down to the subnormals and up to the largest: the same
            // scores, in units of the scale
            let e: Vec<([f64; 3], usize)> = unit.iter().copied().zip(0..).collect();
            let unit_tree = PointTree::new(&e).unwrap();
            let base = outliers::statistical(&unit_tree, k, ratio).unwrap();
            // by item
            let mut by_item = vec![(0.0, false); unit.len()];
            for s in 0..unit.len() {
                by_item[unit_tree.items()[s]] = (base.mean_distances[s], base.keep[s]);
            }
            for shift in [-1064, -1000, -520, -480, 400, 600, 1000, 1014] {
                let scaled: Vec<([f64; 3], usize)> = e
                    .iter()
                    .map(|&(p, i)| (p.map(|x| ldexp(x, shift)), i))
                    .collect();
                let t = PointTree::new(&scaled).unwrap();
                let o = outliers::statistical(&t, k, ratio).unwrap();
                assert!(!o.threshold.is_nan());
                let top = base.mean_distances.iter().fold(0.0f64, |m, &d| m.max(d));
                let threshold = ldexp(o.threshold, o.scale - shift);
                assert!((threshold - base.threshold).abs() <= 1e-9 * (top + base.threshold.abs()));
                for s in 0..t.len() {
                    let (want, kept) = by_item[t.items()[s]];
                    let got = ldexp(o.mean_distances[s], o.scale - shift);
                    // the subnormal copies' coordinates are exact, their distances' squares are not
                    assert!(
                        (got - want).abs() <= 1e-12 * (1.0 + want),
                        "2^{shift}: {got} against {want}"
                    );
                    if (want - base.threshold).abs() > 1e-9 * (top + base.threshold.abs()) {
                        assert_eq!(o.keep[s], kept, "k = {k}, ratio {ratio}, 2^{shift}");
                    }
                }
            }
        }
    }
}

#[test]
fn fewer_points_than_neighbours_and_infinite_ratios() {
    // one point: score 0, kept; two far apart: equal scores, kept whatever the ratio
    let one = PointTree::new(&[([f64::MAX, -f64::MAX, 1e-300], 0usize)]).unwrap();
    let o = outliers::statistical(&one, 4, f64::INFINITY).unwrap();
    assert_eq!(
        (o.mean_distances, o.threshold, o.scale, o.keep),
        (vec![0.0], 0.0, 0, vec![true])
    );
    for ratio in [f64::NEG_INFINITY, -1.0, 0.0, f64::INFINITY] {
        for pts in [
            [[0.0; 3], [1e300, 0.0, 0.0]],
            [[0.0; 3], [1e-300, 0.0, 0.0]],
            [[0.0; 3]; 2],
        ] {
            let e: Vec<([f64; 3], usize)> = pts.iter().copied().zip(0..).collect();
            let o = outliers::statistical(&PointTree::new(&e).unwrap(), 3, ratio).unwrap();
            assert_eq!(o.keep, [true; 2], "{pts:?}, ratio {ratio}");
            assert!(!o.threshold.is_nan());
        }
    }
    // an infinite ratio past distinct scores: all kept, or all dropped
    let pts = [
        [0.0; 3],
        [1.0, 0.0, 0.0],
        [3.0, 0.0, 0.0],
        [1e250, 0.0, 0.0],
    ];
    let e: Vec<([f64; 3], usize)> = pts.iter().copied().zip(0..).collect();
    let t = PointTree::new(&e).unwrap();
    assert_eq!(
        outliers::statistical(&t, 1, f64::INFINITY).unwrap().keep,
        [true; 4]
    );
    assert_eq!(
        outliers::statistical(&t, 1, f64::NEG_INFINITY)
            .unwrap()
            .keep,
        [false; 4]
    );
    check(&pts, 1, f64::INFINITY);
}

#[test]
fn random_mixes_of_scales_agree_with_the_scan() {
    // Clusters of small integers, each scaled by its own power of two (or a power of ten), so
    // that one cloud holds distances from 1e-300 to beyond f64::MAX.
    let scales = [-1000, -997, -300, 0, 1, 200, 511, 513, 700, 1000, 1013];
    for seed in 0..120u64 {
        let mut r = rng(seed);
        let clusters = r.gen_range(1..5);
        let mut pts = Vec::new();
        for _ in 0..clusters {
            let shift = scales[r.gen_range(0..scales.len())];
            let size = r.gen_range(1..12);
            let centre = [0, 1, 2].map(|_| f64::from(r.gen_range(-3..=3)));
            for _ in 0..size {
                let p = [0, 1, 2].map(|a| centre[a] + f64::from(r.gen_range(-8..=8)));
                pts.push(p.map(|x| {
                    if r.gen_bool(0.2) {
                        x * 1e-300
                    } else {
                        ldexp(x, shift)
                    }
                }));
            }
        }
        let k = r.gen_range(1..7);
        let ratio = [-1.0, 0.0, 0.5, 1.0, 2.0, 3.0][r.gen_range(0..6)];
        check(&pts, k, ratio);
    }
}
