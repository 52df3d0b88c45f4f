//! Outlier removal and normals against a k-nearest scan: every point's k nearest other points
//! found by sorting all distances, on random clouds with duplicates and clusters, through a plain
//! and a compressed tree, serially and on rayon's threads.

use crate::common::rng;
use orthtree::cloud::normals::{pca_normal, symmetric_eigen};
use orthtree::cloud::{normals, outliers, Cloud};
use orthtree::{CompressedTree, PointSet, PointTree};
use proptest::prelude::*;
use rand::Rng;

/// The squared distances from point `i` to its `k` nearest other points, by a full scan.
fn knn_scan(points: &[[f64; 3]], i: usize, k: usize) -> Vec<f64> {
    let mut d: Vec<f64> = (0..points.len())
        .filter(|&j| j != i)
        .map(|j| (0..3).map(|a| (points[i][a] - points[j][a]).powi(2)).sum())
        .collect();
    d.sort_by(f64::total_cmp);
    d.truncate(k);
    d
}

fn brute_outliers(points: &[[f64; 3]], k: usize, ratio: f64) -> (Vec<f64>, Vec<bool>) {
    let scores: Vec<f64> = (0..points.len())
        .map(|i| {
            let d = knn_scan(points, i, k);
            if d.is_empty() {
                0.0
            } else {
                d.iter().map(|x| x.sqrt()).sum::<f64>() / d.len() as f64
            }
        })
        .collect();
    let t = threshold(&scores, ratio);
    let keep = scores.iter().map(|&s| s <= t).collect();
    (scores, keep)
}

/// The rule's threshold for `scores`: their mean plus `ratio` times their sample deviation
/// (`n - 1`), or the mean alone when they are all equal (whatever the ratio, infinite too).
pub(crate) fn threshold(scores: &[f64], ratio: f64) -> f64 {
    let n = scores.len() as f64;
    let mean = scores.iter().sum::<f64>() / n;
    let std = if scores.len() > 1 {
        (scores.iter().map(|s| (s - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt()
    } else {
        0.0
    };
    if std > 0.0 {
        mean + ratio * std
    } else {
        mean
    }
}

fn clustered(seed: u64, n: usize, copies: usize) -> Vec<[f64; 3]> {
    let mut r = rng(seed);
    let mut pts: Vec<[f64; 3]> = (0..n)
        .map(|i| {
            if i % 10 == 0 {
                [
                    r.gen_range(-5.0..5.0),
                    r.gen_range(-5.0..5.0),
                    r.gen_range(-5.0..5.0),
                ]
            } else {
                [r.r#gen::<f64>(), r.r#gen(), r.r#gen::<f64>() * 0.1]
            }
        })
        .collect();
    for _ in 0..copies {
        let p = pts[r.gen_range(0..pts.len())];
        pts.push(p);
    }
    pts
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn outlier_removal_equals_a_knn_scan(
        n in 1usize..250,
        copies in 0usize..30,
        k in 1usize..12,
        ratio in -0.5f64..3.0,
        seed in any::<u64>(),
    ) {
        let pts = clustered(seed, n, copies);
        let (scores, keep) = brute_outliers(&pts, k, ratio);
        let mut cloud = Cloud::from_points(pts.clone());
        cloud.attributes.intensity = Some((0..pts.len() as u16).collect());
        let (kept_cloud, kept) = outliers::remove_statistical(&cloud, k, ratio).unwrap();
        let expect: Vec<usize> = (0..pts.len()).filter(|&i| keep[i]).collect();
        prop_assert_eq!(&kept, &expect);
        prop_assert_eq!(&kept_cloud, &cloud.select(&expect));
        // the scores per slot, through the tree's items
        let entries: Vec<([f64; 3], usize)> = pts.iter().copied().zip(0..).collect();
        let tree = PointTree::new(&entries).unwrap();
        let o = outliers::statistical(&tree, k, ratio).unwrap();
        for s in 0..tree.len() {
            let i = tree.items()[s];
            prop_assert!((o.mean_distances[s] - scores[i]).abs() <= 1e-12 * (1.0 + scores[i]));
        }
        // a tree whose slots are not its traversal order: the scores still by slot
        let compressed = CompressedTree::new(&entries).unwrap();
        let c = outliers::statistical(&compressed, k, ratio).unwrap();
        for s in 0..compressed.len() {
            let i = compressed.items()[s];
            prop_assert!((c.mean_distances[s] - scores[i]).abs() <= 1e-12 * (1.0 + scores[i]));
            prop_assert_eq!(c.keep[s], keep[i]);
        }
        #[cfg(feature = "rayon")]
        {
            prop_assert_eq!(outliers::par_statistical(&tree, k, ratio).unwrap(), o);
            prop_assert_eq!(outliers::par_statistical(&compressed, k, ratio).unwrap(), c);
            let (par_cloud, par_kept) = outliers::par_remove_statistical(&cloud, k, ratio).unwrap();
            prop_assert_eq!(par_kept, kept);
            prop_assert_eq!(&par_cloud, &kept_cloud);
        }
    }

    /// Points on a random plane: every normal is the plane's (up to rounding), toward +z.
    #[test]
    fn normals_of_a_plane_are_its_normal(seed in any::<u64>(), n in 4usize..200, k in 3usize..10) {
        let mut r = rng(seed);
        let normal = {
            let v = [r.gen_range(-1.0..1.0), r.gen_range(-1.0..1.0), r.gen_range(0.2..1.0f64)];
            let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            v.map(|x| x / l)
        };
        // two directions in the plane
        let u = {
            let v = [normal[1], -normal[0], 0.0];
            let l = (v[0] * v[0] + v[1] * v[1]).sqrt();
            v.map(|x| x / l)
        };
        let w = [
            normal[1] * u[2] - normal[2] * u[1],
            normal[2] * u[0] - normal[0] * u[2],
            normal[0] * u[1] - normal[1] * u[0],
        ];
        let pts: Vec<[f64; 3]> = (0..n)
            .map(|_| {
                let (a, b) = (r.gen_range(-1.0..1.0), r.gen_range(-1.0..1.0));
                core::array::from_fn(|c| 3.0 + a * u[c] + b * w[c])
            })
            .collect();
        #[cfg(feature = "rayon")]
        {
            let entries: Vec<([f64; 3], usize)> = pts.iter().copied().zip(0..).collect();
            let tree = CompressedTree::new(&entries).unwrap();
            prop_assert_eq!(normals::par_normals(&tree, k), normals::normals(&tree, k));
        }
        let mut cloud = Cloud::from_points(pts);
        normals::estimate(&mut cloud, k).unwrap();
        for m in cloud.attributes.normal.unwrap() {
            for c in 0..3 {
                prop_assert!((f64::from(m[c]) - normal[c]).abs() < 1e-4, "{:?} vs {:?}", m, normal);
            }
        }
    }

    #[test]
    fn the_eigen_solver_diagonalises_symmetric_matrices(
        e in proptest::array::uniform6(-100.0f64..100.0),
    ) {
        let a = [[e[0], e[1], e[2]], [e[1], e[3], e[4]], [e[2], e[4], e[5]]];
        let (values, vectors) = symmetric_eigen(a);
        let scale = 1.0 + e.iter().map(|x| x.abs()).fold(0.0, f64::max);
        prop_assert!(values[0] <= values[1] && values[1] <= values[2]);
        for i in 0..3 {
            for j in 0..3 {
                let dot: f64 = (0..3).map(|c| vectors[i][c] * vectors[j][c]).sum();
                let want = f64::from(u8::from(i == j));
                prop_assert!((dot - want).abs() < 1e-12);
            }
            for r in 0..3 {
                let av: f64 = (0..3).map(|c| a[r][c] * vectors[i][c]).sum();
                prop_assert!((av - values[i] * vectors[i][r]).abs() < 1e-10 * scale);
            }
        }
        let trace = e[0] + e[3] + e[5];
        prop_assert!((values.iter().sum::<f64>() - trace).abs() < 1e-10 * scale);
    }
}

#[test]
fn degenerate_neighbourhoods_and_bad_parameters() {
    assert_eq!(pca_normal(&[]), None);
    // one point: no unique normal, but a unit vector
    let n = pca_normal(&[[1.0, 2.0, 3.0]]).unwrap();
    assert!((n.iter().map(|x| x * x).sum::<f64>() - 1.0).abs() < 1e-12);
    // a line along x: a unit vector perpendicular to it
    let n = pca_normal(&[[0.0, 1.0, 1.0], [1.0, 1.0, 1.0], [2.0, 1.0, 1.0]]).unwrap();
    assert!(n[0].abs() < 1e-12 && ((n[1] * n[1] + n[2] * n[2]) - 1.0).abs() < 1e-12);
    let one = PointTree::new(&[([0.0, 0.0, 0.0], 0usize)]).unwrap();
    let o = outliers::statistical(&one, 3, 1.0).unwrap();
    assert_eq!((o.mean_distances, o.keep), (vec![0.0], vec![true]));
    assert!(outliers::statistical(&one, 0, 1.0).is_err());
    assert!(outliers::statistical(&one, 1, f64::NAN).is_err());
    // all points one: every score 0, all kept (Open3D would drop them all)
    let same = PointTree::new(&[([1.0, 1.0, 1.0], 0usize); 5]).unwrap();
    assert!(outliers::statistical(&same, 2, 0.0)
        .unwrap()
        .keep
        .iter()
        .all(|&k| k));
    assert!(normals::normals(&same, 0).is_err());
}
