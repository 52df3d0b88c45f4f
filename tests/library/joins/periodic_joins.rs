//! The joins on a periodic domain ([`PeriodicJoins`]) against nested loops over all `3^k`
//! images of the `k` wrapping axes, on every point tree: the k-nearest join (each row exactly
//! the single-tree `periodic_k_nearest`, ties included) and the self-join without the point
//! itself, all pairs within a radius (each unordered pair once), the counts over sorted radii,
//! the sparse distance matrix, both boundaries, early stop, bad radii, empty trees; and under the
//! `rayon` feature every parallel form ([`ParallelPeriodicJoins`]) equal to the serial one (the
//! pairs of the visitor and the fold order-normalised).
//!
//! Points lie on a dyadic grid over the period box `[-1/2, 3/4)` (period 5/4), both faces
//! included (a point on the upper face is its image on the lower one, prepared or not), with
//! split lines and duplicates: every distance is exact, so answers compare exactly. Radii run
//! from 0 through half a period to beyond the period and infinity; any subset of axes wraps.

use core::ops::ControlFlow;
use orthtree::prelude::*;
use orthtree::query::{Boundary, OutsidePoints, QueryError, SquaredEuclidean, Torus};
use orthtree::{CompressedTree, DynamicPointTree, PointTree, SkipQuadtree};
use proptest::prelude::*;

use crate::common::points::{brute_distance, HI, L, LO};

/// The squared distance from `a` to the nearest of the `3^k` images of `b`, tried one by one.
fn brute<const D: usize>(wraps: &[bool; D], a: &[f64; D], b: &[f64; D]) -> f64 {
    brute_distance::<SquaredEuclidean, D>(wraps, a, b)
}

/// The serial pairs visitors of the checks as one trait-object type, so that one instantiation
/// of each join serves every visitor (and the checks of a set with itself and with another
/// share theirs): the tests compile in less time, and the joins run as for any visitor.
type Visit<'v> = &'v mut dyn FnMut(usize, usize, f64) -> ControlFlow<u8>;

/// The same for the parallel visitors, which break with a pair.
#[cfg(feature = "rayon")]
type ParVisit<'v> = &'v (dyn Fn(usize, usize, f64) -> ControlFlow<(usize, usize, f64)> + Sync);

fn admits(boundary: Boundary, d: f64, r: f64) -> bool {
    match boundary {
        Boundary::Inclusive => d <= r * r,
        Boundary::Exclusive => d < r * r,
    }
}

/// Every set here stores the input position of each point as its item.
trait Set<const D: usize>: PointSet<D, Scalar = f64, Item = usize> + Sync {}
impl<P: PointSet<D, Scalar = f64, Item = usize> + Sync, const D: usize> Set<D> for P {}

/// The pairs (input positions, distance) within `r` by nested loops (`same`: `i < j` once).
fn brute_pairs<const D: usize>(
    wraps: &[bool; D],
    pa: &[[f64; D]],
    pb: &[[f64; D]],
    r: f64,
    boundary: Boundary,
    same: bool,
) -> Vec<(usize, usize, f64)> {
    let mut out = Vec::new();
    for (i, p) in pa.iter().enumerate() {
        for (j, q) in pb.iter().enumerate() {
            let d = brute(wraps, p, q);
            if (!same || i < j) && admits(boundary, d, r) {
                out.push((i, j, d));
            }
        }
    }
    out.sort_by_key(|x| (x.0, x.1));
    out
}

/// The k-nearest join of `a` in `b` (`same`: the self-join) on `torus`.
fn check_knn<A: Set<D>, B: Set<D>, const D: usize>(
    torus: &Torus<D>,
    (a, pa): (&A, &[[f64; D]]),
    (b, pb): (&B, &[[f64; D]]),
    k: usize,
    same: bool,
) {
    let table = if same {
        a.periodic_k_nearest_self(torus, k)
    } else {
        a.periodic_k_nearest_join(torus, b, k)
    };
    let others = if same {
        pb.len().saturating_sub(1)
    } else {
        pb.len()
    };
    assert_eq!((table.rows(), table.k()), (pa.len(), k.min(others)));
    for s in 0..a.len() {
        let (slots, dists) = table.row(s);
        let p = a.point(s);
        let single: Vec<(usize, f64)> = b
            .periodic_k_nearest(torus, p, k.saturating_add(1))
            .unwrap()
            .iter()
            .filter(|n| !same || n.index != s)
            .take(k)
            .map(|n| (n.index, n.distance))
            .collect();
        let got: Vec<(usize, f64)> = slots.iter().copied().zip(dists.iter().copied()).collect();
        assert_eq!(got, single, "row {s} is the single-tree answer");
        let me = a.items()[s];
        let mut want: Vec<f64> = (0..pb.len())
            .filter(|&j| !same || j != me)
            .map(|j| brute(torus.wraps(), p, &pb[j]))
            .collect();
        want.sort_by(f64::total_cmp);
        want.truncate(k);
        assert_eq!(dists, &want[..], "row {s} against all images");
    }
    #[cfg(feature = "rayon")]
    {
        let par = if same {
            a.par_periodic_k_nearest_self(torus, k)
        } else {
            a.par_periodic_k_nearest_join(torus, b, k)
        };
        assert_eq!(par, table, "the parallel table is the serial one");
    }
}

/// The pairs within `r` (of `a` with itself when `same`), the early stop, the sparse matrix.
fn check_pairs<A: Set<D>, B: Set<D>, const D: usize>(
    torus: &Torus<D>,
    (a, pa): (&A, &[[f64; D]]),
    (b, pb): (&B, &[[f64; D]]),
    r: f64,
    boundary: Boundary,
    same: bool,
) {
    let mut got = Vec::new();
    let mut visit = |s: usize, t: usize, d: f64| {
        assert!(
            !same || s < t,
            "each unordered pair once, the smaller slot first"
        );
        let (i, j) = (a.items()[s], b.items()[t]);
        got.push(if same && j < i { (j, i, d) } else { (i, j, d) });
        ControlFlow::<u8>::Continue(())
    };
    let flow = if same {
        a.periodic_pairs_within(torus, r, boundary, &mut visit as Visit)
    } else {
        a.periodic_pairs_within_other(torus, b, r, boundary, &mut visit as Visit)
    };
    assert_eq!(flow, Ok(ControlFlow::Continue(())));
    got.sort_by_key(|x| (x.0, x.1));
    let want = brute_pairs(torus.wraps(), pa, pb, r, boundary, same);
    assert_eq!(got, want, "r = {r}, {boundary:?}");
    // a break stops at once and is returned
    let mut calls = 0;
    let mut stop = |_: usize, _: usize, _: f64| {
        calls += 1;
        ControlFlow::<u8>::Break(3)
    };
    let flow = if same {
        a.periodic_pairs_within(torus, r, boundary, &mut stop as Visit)
    } else {
        a.periodic_pairs_within_other(torus, b, r, boundary, &mut stop as Visit)
    };
    let expected = if want.is_empty() {
        ControlFlow::Continue(())
    } else {
        ControlFlow::Break(3)
    };
    assert_eq!((flow, calls), (Ok(expected), usize::from(!want.is_empty())));
    #[cfg(feature = "rayon")]
    check_par_pairs(torus, (a, b), r, boundary, same, &want);
    if !same {
        let m = a
            .periodic_sparse_distance_matrix(torus, b, r, boundary)
            .unwrap();
        assert_eq!((m.rows(), m.cols()), (pa.len(), pb.len()));
        let coo: Vec<(usize, usize, f64)> = m.iter().collect();
        assert!(
            coo.windows(2).all(|w| (w[0].0, w[0].1) < (w[1].0, w[1].1)),
            "sorted, no pair twice"
        );
        let mut by_input: Vec<_> = coo
            .iter()
            .map(|&(s, t, d)| (a.items()[s], b.items()[t], d))
            .collect();
        by_input.sort_by_key(|x| (x.0, x.1));
        assert_eq!(by_input, want);
        #[cfg(feature = "rayon")]
        assert_eq!(
            a.par_periodic_sparse_distance_matrix(torus, b, r, boundary)
                .unwrap(),
            m
        );
    }
}

/// The parallel pairs visitor (and, within one set, the fold): the pairs `want` of nested loops
/// (input positions, sorted), each once, and a break returned.
#[cfg(feature = "rayon")]
fn check_par_pairs<A: Set<D>, B: Set<D>, const D: usize>(
    torus: &Torus<D>,
    (a, b): (&A, &B),
    r: f64,
    boundary: Boundary,
    same: bool,
    want: &[(usize, usize, f64)],
) {
    use std::sync::Mutex;
    let key = |s: usize, t: usize, d: f64| {
        assert!(!same || s < t, "each unordered pair once");
        let (i, j) = (a.items()[s], b.items()[t]);
        if same && j < i {
            (j, i, d)
        } else {
            (i, j, d)
        }
    };
    let seen = Mutex::new(Vec::new());
    let visit = |s: usize, t: usize, d: f64| {
        seen.lock().unwrap().push(key(s, t, d));
        ControlFlow::Continue(())
    };
    let flow = if same {
        a.par_periodic_pairs_within(torus, r, boundary, &visit as ParVisit)
    } else {
        a.par_periodic_pairs_within_other(torus, b, r, boundary, &visit as ParVisit)
    };
    assert_eq!(flow, Ok(ControlFlow::Continue(())));
    let mut got = seen.into_inner().unwrap();
    got.sort_by_key(|x| (x.0, x.1));
    assert_eq!(got, want);
    if same {
        let mut folded = a
            .par_periodic_fold_pairs_within(
                torus,
                r,
                boundary,
                Vec::new,
                |acc: &mut Vec<_>, s, t, d| acc.push(key(s, t, d)),
                |mut x, y| {
                    x.extend(y);
                    x
                },
            )
            .unwrap();
        folded.sort_by_key(|x| (x.0, x.1));
        assert_eq!(folded, want);
    }
    let stop = |s: usize, t: usize, d: f64| ControlFlow::Break(key(s, t, d));
    let flow = if same {
        a.par_periodic_pairs_within(torus, r, boundary, &stop as ParVisit)
    } else {
        a.par_periodic_pairs_within_other(torus, b, r, boundary, &stop as ParVisit)
    };
    match flow.unwrap() {
        ControlFlow::Break(p) => assert!(want.contains(&p), "the break of a pair within r"),
        ControlFlow::Continue(()) => assert!(want.is_empty(), "no pair: no break"),
    }
}

/// The counts over sorted `radii` against counting nested loops.
fn check_counts<A: Set<D>, B: Set<D>, const D: usize>(
    torus: &Torus<D>,
    (a, pa): (&A, &[[f64; D]]),
    (b, pb): (&B, &[[f64; D]]),
    radii: &[f64],
    boundary: Boundary,
    same: bool,
) {
    let got = if same {
        a.periodic_count_pairs_within(torus, radii, boundary)
    } else {
        a.periodic_count_neighbors(torus, b, radii, boundary)
    };
    let want: Vec<u64> = radii
        .iter()
        .map(|&r| brute_pairs(torus.wraps(), pa, pb, r, boundary, same).len() as u64)
        .collect();
    let got = got.unwrap();
    assert_eq!(got, want, "radii {radii:?}");
    #[cfg(feature = "rayon")]
    {
        let par = if same {
            a.par_periodic_count_pairs_within(torus, radii, boundary)
        } else {
            a.par_periodic_count_neighbors(torus, b, radii, boundary)
        };
        assert_eq!(par.unwrap(), got, "the parallel counts are the serial ones");
    }
}

/// Every periodic join of `a` with itself and with `b`.
fn check_all<A: Set<D>, B: Set<D>, const D: usize>(
    torus: &Torus<D>,
    a: (&A, &[[f64; D]]),
    b: (&B, &[[f64; D]]),
    radii: &[f64],
) {
    a.0.validate().unwrap();
    b.0.validate().unwrap();
    for k in [0, 1, 3, b.1.len() + 2] {
        check_knn(torus, a, b, k, false);
        check_knn(torus, a, a, k, true);
    }
    for boundary in [Boundary::Inclusive, Boundary::Exclusive] {
        for &r in radii {
            check_pairs(torus, a, a, r, boundary, true);
            check_pairs(torus, a, b, r, boundary, false);
        }
        check_counts(torus, a, a, radii, boundary, true);
        check_counts(torus, a, b, radii, boundary, false);
    }
}

/// The radii every check uses, sorted: 0, grid steps, half a period, the period and beyond.
fn radii(extra: f64) -> Vec<f64> {
    let mut r = vec![
        0.0,
        0.125,
        0.375,
        L / 2.0,
        0.9,
        L,
        2.0 * L,
        f64::INFINITY,
        extra,
    ];
    r.sort_by(f64::total_cmp);
    r
}

fn entries<const D: usize>(pts: &[[f64; D]]) -> Vec<([f64; D], usize)> {
    pts.iter().enumerate().map(|(i, p)| (*p, i)).collect()
}

/// [`check_all`] on every point tree, `a` against `b` of another kind.
fn all_trees<const D: usize>(wraps: [bool; D], pa: &[[f64; D]], pb: &[[f64; D]], extra: f64) {
    let torus = Torus::new([LO; D], [HI; D], wraps).unwrap();
    let radii = radii(extra);
    let (ea, eb) = (entries(pa), entries(pb));
    let plain = |e: &[([f64; D], usize)]| PointTree::builder().bucket_size(2).build(e).unwrap();
    let (a, b) = (plain(&ea), plain(&eb));
    let (da, db) = (
        DynamicPointTree::from(a.clone()),
        DynamicPointTree::from(b.clone()),
    );
    let (ca, cb) = (
        CompressedTree::new(&ea).unwrap(),
        CompressedTree::new(&eb).unwrap(),
    );
    let sa = SkipQuadtree::with_seed(ca.clone(), 4);
    check_all(&torus, (&a, pa), (&cb, pb), &radii);
    check_all(&torus, (&da, pa), (&b, pb), &radii);
    check_all(&torus, (&ca, pa), (&db, pb), &radii);
    check_all(&torus, (&sa, pa), (&a, pa), &radii);
}

/// A point of the grid of step 1/8 on `[LO, HI]^D`: both faces, split lines, duplicates.
fn grid_point<const D: usize>() -> impl Strategy<Value = [f64; D]> {
    proptest::array::uniform::<_, D>((0u8..=10).prop_map(|j| LO + f64::from(j) / 8.0))
}

fn wraps<const D: usize>() -> impl Strategy<Value = [bool; D]> {
    proptest::array::uniform::<_, D>(any::<bool>())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn periodic_joins_equal_nested_loops_over_all_images_2d(
        w in wraps::<2>(),
        pa in prop::collection::vec(grid_point::<2>(), 0..40),
        pb in prop::collection::vec(grid_point::<2>(), 0..40),
        extra in 0.0f64..2.0,
    ) {
        all_trees(w, &pa, &pb, extra);
    }

    #[test]
    fn periodic_joins_equal_nested_loops_over_all_images_3d(
        w in wraps::<3>(),
        pa in prop::collection::vec(grid_point::<3>(), 0..40),
        pb in prop::collection::vec(grid_point::<3>(), 0..40),
        extra in 0.0f64..2.0,
    ) {
        all_trees(w, &pa, &pb, extra);
    }

    #[test]
    fn periodic_joins_equal_nested_loops_over_all_images_1d(
        pa in prop::collection::vec(grid_point::<1>(), 0..30),
        pb in prop::collection::vec(grid_point::<1>(), 0..30),
        extra in 0.0f64..2.0,
    ) {
        all_trees([true], &pa, &pb, extra);
    }
}

#[test]
fn prepared_points_on_the_faces_and_many_duplicates() {
    // Every corner and face of the period box, many times, wrapped onto the lower faces by
    // `prepare`: the same answers as the raw points, which lie on both faces.
    let mut raw = Vec::new();
    for _ in 0..4 {
        for (x, y) in [
            (LO, LO),
            (HI, LO),
            (LO, HI),
            (HI, HI),
            (0.0, HI),
            (HI, 0.125),
        ] {
            raw.push([x, y]);
        }
    }
    let torus = Torus::wrapping([LO; 2], [HI; 2]).unwrap();
    let prepared = torus.prepare(&raw, OutsidePoints::Refuse).unwrap();
    all_trees([true, true], &raw, &prepared, 0.3);
    all_trees([true, false], &prepared, &raw, 0.01);
}

#[test]
fn bad_radii_and_empty_trees() {
    let torus = Torus::wrapping([LO; 2], [HI; 2]).unwrap();
    let t = PointTree::new(&[([0.0, 0.0], 0usize), ([0.5, 0.5], 1)]).unwrap();
    let never = |_: usize, _: usize, _: f64| -> ControlFlow<()> { panic!("not called") };
    for r in [-1.0, f64::NAN] {
        assert!(matches!(
            t.periodic_pairs_within(&torus, r, Boundary::Inclusive, never),
            Err(QueryError::InvalidRadius { .. })
        ));
        assert!(matches!(
            t.periodic_sparse_distance_matrix(&torus, &t, r, Boundary::Inclusive),
            Err(QueryError::InvalidRadius { .. })
        ));
    }
    assert_eq!(
        t.periodic_count_neighbors(&torus, &t, &[1.0, 0.5], Boundary::Inclusive),
        Err(QueryError::UnsortedRadii { index: 1 })
    );
    let none: Vec<([f64; 2], usize)> = Vec::new();
    let e = PointTree::new(&none).unwrap();
    assert_eq!(t.periodic_k_nearest_join(&torus, &e, 2).k(), 0);
    assert_eq!(e.periodic_k_nearest_self(&torus, 2).rows(), 0);
    assert_eq!(
        e.periodic_count_pairs_within(&torus, &[0.0, 10.0], Boundary::Inclusive),
        Ok(vec![0, 0])
    );
    assert_eq!(
        t.periodic_pairs_within_other(&torus, &e, 10.0, Boundary::Inclusive, never),
        Ok(ControlFlow::Continue(()))
    );
    #[cfg(feature = "rayon")]
    {
        for r in [-1.0, f64::NAN] {
            assert!(matches!(
                t.par_periodic_pairs_within(&torus, r, Boundary::Inclusive, never),
                Err(QueryError::InvalidRadius { .. })
            ));
            assert!(matches!(
                t.par_periodic_sparse_distance_matrix(&torus, &t, r, Boundary::Inclusive),
                Err(QueryError::InvalidRadius { .. })
            ));
        }
        assert_eq!(
            t.par_periodic_count_neighbors(&torus, &t, &[1.0, 0.5], Boundary::Inclusive),
            Err(QueryError::UnsortedRadii { index: 1 })
        );
        assert_eq!(t.par_periodic_k_nearest_join(&torus, &e, 2).k(), 0);
        assert_eq!(e.par_periodic_k_nearest_self(&torus, 2).rows(), 0);
        assert_eq!(
            e.par_periodic_count_pairs_within(&torus, &[0.0, 10.0], Boundary::Inclusive),
            Ok(vec![0, 0])
        );
        assert_eq!(
            e.par_periodic_pairs_within(&torus, 10.0, Boundary::Inclusive, never),
            Ok(ControlFlow::Continue(()))
        );
    }
}
