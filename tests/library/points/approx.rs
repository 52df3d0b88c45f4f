//! The (1 + eps)-approximate k-nearest search (`k_nearest_approx`, `k_nearest_approx_by`)
//! against brute force on every point tree and every metric (squared Euclidean, Manhattan,
//! Chebyshev, minimum-image): `min(k, n)` distinct answers, sorted, each the distance of its
//! point, the `i`-th within `(1 + eps)` of the true `i`-th (squared: `(1 + eps)^2`); `eps = 0`
//! equal to the exact search; the typed errors for a bad `eps`. Inputs: grid points (split
//! lines, duplicates, ties), spread points, huge coordinates, a maximum distance.

use orthtree::prelude::*;
use orthtree::query::{Chebyshev, Manhattan, Metric, QueryError, SquaredEuclidean, Torus};
use orthtree::{CompressedTree, DynamicPointTree, PointTree, SkipQuadtree};
use proptest::prelude::*;

/// One rounding of the pruning bound: the slack the guarantee holds up to.
const ROUNDING: f64 = 1.0 + 1e-12;

/// One tree's approximate answers against the sorted brute-force distances under `metric`.
fn check<P, M, const D: usize>(t: &P, q: &[f64; D], k: usize, max: f64, eps: f64, metric: &M)
where
    P: PointSet<D, Scalar = f64, Item = usize>,
    M: Metric<D>,
{
    let mut truth: Vec<f64> = (0..t.len())
        .map(|s| metric.distance(q, t.point(s)))
        .filter(|&d| d <= max)
        .collect();
    truth.sort_by(f64::total_cmp);
    let got = t.k_nearest_approx_by(q, k, max, eps, metric).unwrap();
    assert_eq!(got.len(), k.min(truth.len()), "min(k, n) answers");
    let mut slots: Vec<usize> = got.iter().map(|n| n.index).collect();
    slots.sort_unstable();
    slots.dedup();
    assert_eq!(slots.len(), got.len(), "no point twice");
    assert!(
        got.windows(2).all(|w| w[0].distance <= w[1].distance),
        "sorted"
    );
    for (i, n) in got.iter().enumerate() {
        assert_eq!(n.point, t.point(n.index));
        assert_eq!(*n.item, t.items()[n.index]);
        assert_eq!(
            n.distance,
            metric.distance(q, n.point),
            "its point's distance"
        );
        assert!(n.distance <= max);
        assert!(n.distance >= truth[i], "never nearer than the truth");
        // A true distance of 0 allows only 0, whatever eps (0 times an infinite factor is NaN).
        let allowed = if truth[i] == 0.0 {
            0.0
        } else {
            metric.scale_distance(truth[i], 1.0 + eps) * ROUNDING
        };
        assert!(
            n.distance <= allowed,
            "answer {i} at {} beyond (1 + {eps}) times the true {} (q {q:?}, k {k})",
            n.distance,
            truth[i]
        );
    }
    let exact = t.k_nearest_by(q, k, max, metric).unwrap();
    assert_eq!(
        t.k_nearest_approx_by(q, k, max, 0.0, metric).unwrap(),
        exact
    );
    assert_eq!(
        t.k_nearest_approx_by(q, k, max, -0.0, metric).unwrap(),
        exact
    );
}

/// [`check`] under every metric, on one tree.
fn check_metrics<P: PointSet<D, Scalar = f64, Item = usize>, const D: usize>(
    t: &P,
    q: &[f64; D],
    k: usize,
    max: f64,
    eps: f64,
) {
    t.validate().unwrap();
    check(t, q, k, max, eps, &SquaredEuclidean);
    check(t, q, k, max, eps, &Manhattan);
    check(t, q, k, max, eps, &Chebyshev);
    let torus = Torus::wrapping([0.0; D], [4.0; D]).unwrap();
    check(t, q, k, max, eps, &torus.squared_euclidean());
    check(t, q, k, max, eps, &torus.manhattan());
    // the squared Euclidean shorthand
    let plain = t.k_nearest_approx(q, k, eps).unwrap();
    let by = t.k_nearest_approx_by(q, k, f64::INFINITY, eps, &SquaredEuclidean);
    assert_eq!(plain, by.unwrap());
}

/// [`check_metrics`] on every point tree built from `pts` (item: input position).
fn all_trees<const D: usize>(pts: &[[f64; D]], q: &[f64; D], k: usize, max: f64, eps: f64) {
    let entries: Vec<([f64; D], usize)> = pts.iter().enumerate().map(|(i, p)| (*p, i)).collect();
    let plain = PointTree::builder().bucket_size(2).build(&entries).unwrap();
    check_metrics(&plain, q, k, max, eps);
    check_metrics(&DynamicPointTree::from(plain), q, k, max, eps);
    let compressed = CompressedTree::new(&entries).unwrap();
    check_metrics(&compressed, q, k, max, eps);
    check_metrics(&SkipQuadtree::with_seed(compressed, 5), q, k, max, eps);
}

fn eps() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        Just(0.01),
        Just(0.5),
        Just(1.0),
        Just(3.0),
        0.0f64..2.0,
        Just(1e300),
        Just(f64::INFINITY),
    ]
}

/// A point of the grid of step 1/4 on [0, 4]^D: split lines, faces, duplicates and ties.
fn grid_point<const D: usize>() -> impl Strategy<Value = [f64; D]> {
    proptest::array::uniform::<_, D>((0u8..=16).prop_map(|j| f64::from(j) / 4.0))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn approx_k_nearest_is_within_one_plus_eps_on_grid_points_2d(
        pts in prop::collection::vec(grid_point::<2>(), 0..150),
        q in grid_point::<2>(),
        k in 0usize..20,
        eps in eps(),
        max in prop_oneof![Just(f64::INFINITY), 0.0f64..6.0],
    ) {
        all_trees(&pts, &q, k, max, eps);
    }

    #[test]
    fn approx_k_nearest_is_within_one_plus_eps_on_spread_points_3d(
        pts in prop::collection::vec(proptest::array::uniform3(-1.0f64..5.0), 0..200),
        q in proptest::array::uniform3(-2.0f64..6.0),
        k in 1usize..30,
        eps in eps(),
    ) {
        all_trees(&pts, &q, k, f64::INFINITY, eps);
    }
}

#[test]
fn many_points_and_huge_coordinates() {
    use rand::Rng;
    let mut rng = crate::common::rng(77);
    let pts: Vec<[f64; 2]> = (0..3000).map(|_| [rng.r#gen(), rng.r#gen()]).collect();
    for eps in [0.1, 0.5, 2.0] {
        for _ in 0..20 {
            let q = [rng.r#gen::<f64>(), rng.r#gen::<f64>()];
            all_trees(&pts, &q, 10, f64::INFINITY, eps);
        }
    }
    // squares beyond f64::MAX: infinite distances tie, and an infinite k-th distance times a
    // zero factor must not stop the search
    let far = [
        [1e300, 0.0],
        [-1e300, 0.0],
        [0.0, 1e300],
        [0.0, 0.0],
        [0.5, 0.5],
    ];
    for eps in [0.5, f64::INFINITY] {
        all_trees(&far, &[0.0, 0.0], 5, f64::INFINITY, eps);
    }
}

#[test]
fn bad_eps_is_refused_with_its_value() {
    let t = PointTree::new(&[([0.0, 0.0], 0usize), ([1.0, 1.0], 1)]).unwrap();
    for eps in [-1e-300, -1.0, f64::NAN, f64::NEG_INFINITY] {
        let err = t.k_nearest_approx(&[0.0, 0.0], 1, eps).unwrap_err();
        assert_eq!(err, QueryError::InvalidEpsilon { value: eps.into() });
        assert!(err.to_string().contains("eps"), "{err}");
    }
    assert!(matches!(
        t.k_nearest_approx(&[f64::NAN, 0.0], 1, 0.5),
        Err(QueryError::NotFinite { axis: 0, .. })
    ));
    assert!(matches!(
        t.k_nearest_approx_by(&[0.0, 0.0], 1, -1.0, 0.5, &Manhattan),
        Err(QueryError::InvalidMaxDistance { .. })
    ));
    let none: Vec<([f64; 2], usize)> = Vec::new();
    let empty = PointTree::new(&none).unwrap();
    assert!(empty
        .k_nearest_approx(&[0.0, 0.0], 3, 0.5)
        .unwrap()
        .is_empty());
}
