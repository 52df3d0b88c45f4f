//! The tree-against-tree queries ([`Joins`], and [`ParallelJoins`] under the `rayon` feature)
//! against nested loops over the points, through one generic check run on every point tree: the
//! k-nearest join against brute force and against one `k_nearest` per point (ties included), its
//! map forms against its table, the self-join without the point itself, all pairs within a radius
//! (of one tree, each unordered pair once, and between two), the counts over sorted radii, the
//! sparse distance matrix and its CSR form, both boundaries, early stop, the parameter errors, and
//! the parallel forms equal to the serial ones (the tables, counts and matrices exactly; the pairs
//! of the parallel visitor and fold once each, order-normalised; a parallel break one of the
//! pairs). Inputs: grid points (split lines, faces, many duplicates), arbitrary points with extreme
//! values, empty sets, `k` beyond the size, `r = 0` and radii beyond the domain.

use crate::common;

use common::points::config;
use core::ops::ControlFlow;
use orthtree::prelude::*;
use orthtree::query::{Boundary, Payload, QueryError};
use orthtree::{CompressedTree, DynamicPointTree, PointTree, SkipQuadtree};
use proptest::prelude::*;

#[path = "joins_densities.rs"]
mod densities;

/// The squared distance, as the query layer computes it (axis order, `f64`).
fn dist<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
    let mut s = 0.0;
    for i in 0..D {
        let d = a[i] - b[i];
        s += d * d;
    }
    s
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
pub(crate) trait Set<const D: usize>:
    PointSet<D, Scalar = f64, Item = usize> + Sync
{
}
impl<P: PointSet<D, Scalar = f64, Item = usize> + Sync, const D: usize> Set<D> for P {}

/// The k-nearest join of `a` in `b` (`same`: the self-join): per row, exactly the single-tree
/// answer (without the point itself in a self-join), and the brute-force distances.
pub(crate) fn check_knn<A: Set<D>, B: Set<D>, const D: usize>(
    a: &A,
    pa: &[[f64; D]],
    b: &B,
    pb: &[[f64; D]],
    k: usize,
    same: bool,
) {
    let table = if same {
        a.k_nearest_self(k)
    } else {
        a.k_nearest_join(b, k)
    };
    // The map forms hand each slot its row of the table and keep the values in slot order.
    // A function pointer, one type for every set: one instantiation of each map form.
    type Row = (usize, Vec<usize>, Vec<f64>);
    let row: fn(usize, &[usize], &[f64]) -> Row = |s, t, d| (s, t.to_vec(), d.to_vec());
    let rows: Vec<_> = (0..a.len())
        .map(|s| (s, table.row(s).0.to_vec(), table.row(s).1.to_vec()))
        .collect();
    let mapped = if same {
        a.map_k_nearest_self(k, row)
    } else {
        a.map_k_nearest_join(b, k, row)
    };
    assert_eq!(mapped, rows, "the map form sees the table's rows");
    #[cfg(feature = "rayon")]
    {
        let mapped = if same {
            a.par_map_k_nearest_self(k, row)
        } else {
            a.par_map_k_nearest_join(b, k, row)
        };
        assert_eq!(mapped, rows, "the parallel map form sees the table's rows");
    }
    let others = if same {
        pb.len().saturating_sub(1)
    } else {
        pb.len()
    };
    assert_eq!(table.k(), k.min(others));
    assert_eq!(table.rows(), pa.len());
    assert_eq!(table.slots().len(), pa.len() * table.k());
    for s in 0..a.len() {
        let (slots, dists) = table.row(s);
        let p = a.point(s);
        assert_eq!(*p, pa[a.items()[s]], "row s is slot s");
        let single: Vec<(usize, f64)> = b
            .k_nearest(p, k.saturating_add(1))
            .unwrap()
            .iter()
            .filter(|n| !same || n.index != s)
            .take(k)
            .map(|n| (n.index, n.distance))
            .collect();
        let got: Vec<(usize, f64)> = slots.iter().copied().zip(dists.iter().copied()).collect();
        assert_eq!(got, single, "row {s} is the single-tree answer");
        let me = a.items()[s];
        let mut brute: Vec<f64> = (0..pb.len())
            .filter(|&j| !same || j != me)
            .map(|j| dist(p, &pb[j]))
            .collect();
        brute.sort_by(f64::total_cmp);
        brute.truncate(k);
        assert_eq!(dists, &brute[..]);
        for (&t, &d) in slots.iter().zip(dists) {
            assert_eq!(
                d,
                dist(p, b.point(t)),
                "a neighbour's distance is its point's"
            );
        }
    }
}

/// The pairs within `r`, as sorted (input position, input position) with distances, from the
/// join and from nested loops.
fn check_pairs<A: Set<D>, B: Set<D>, const D: usize>(
    a: &A,
    pa: &[[f64; D]],
    b: &B,
    pb: &[[f64; D]],
    r: f64,
    boundary: Boundary,
    same: bool,
) {
    let mut got = Vec::new();
    let mut visit = |s: usize, t: usize, d: f64| {
        if same {
            assert!(s < t, "each unordered pair once, the smaller slot first");
        }
        assert_eq!(d, dist(a.point(s), b.point(t)));
        got.push((a.items()[s], b.items()[t], d));
        ControlFlow::<u8>::Continue(())
    };
    let flow = if same {
        a.pairs_within(r, boundary, &mut visit as Visit)
    } else {
        a.pairs_within_other(b, r, boundary, &mut visit as Visit)
    };
    assert_eq!(flow, Ok(ControlFlow::Continue(())));
    let got = sorted(got.into_iter().map(
        |(i, j, d)| {
            if same && j < i {
                (j, i, d)
            } else {
                (i, j, d)
            }
        },
    ));
    let mut want = Vec::new();
    for (i, p) in pa.iter().enumerate() {
        for (j, q) in pb.iter().enumerate() {
            if (!same || i < j) && admits(boundary, dist(p, q), r) {
                want.push((i, j, dist(p, q)));
            }
        }
    }
    assert_eq!(got, sorted(want.into_iter()));
    check_par_pairs(a, b, r, boundary, same, &got);
    // The visitor's break stops the traversal at once and is returned.
    let mut calls = 0;
    let mut stop = |_: usize, _: usize, _: f64| {
        calls += 1;
        ControlFlow::<u8>::Break(7)
    };
    let flow = if same {
        a.pairs_within(r, boundary, &mut stop as Visit)
    } else {
        a.pairs_within_other(b, r, boundary, &mut stop as Visit)
    };
    let expected = if got.is_empty() {
        ControlFlow::Continue(())
    } else {
        ControlFlow::Break(7)
    };
    assert_eq!((flow, calls), (Ok(expected), usize::from(!got.is_empty())));
}

/// The parallel pairs visitor and fold: the serial form's pairs `want` (input positions,
/// sorted), each once, and a break returned.
#[cfg(feature = "rayon")]
fn check_par_pairs<A: Set<D>, B: Set<D>, const D: usize>(
    a: &A,
    b: &B,
    r: f64,
    boundary: Boundary,
    same: bool,
    want: &[(usize, usize, f64)],
) {
    use std::sync::Mutex;
    let key = |s: usize, t: usize, d: f64| {
        if same {
            assert!(s < t, "each unordered pair once, the smaller slot first");
        }
        assert_eq!(d, dist(a.point(s), b.point(t)));
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
        a.par_pairs_within(r, boundary, &visit as ParVisit)
    } else {
        a.par_pairs_within_other(b, r, boundary, &visit as ParVisit)
    };
    assert_eq!(flow, Ok(ControlFlow::Continue(())));
    assert_eq!(sorted(seen.into_inner().unwrap().into_iter()), want);
    let identity = Vec::new;
    let fold =
        |acc: &mut Vec<(usize, usize, f64)>, s: usize, t: usize, d: f64| acc.push(key(s, t, d));
    let reduce = |mut x: Vec<_>, y: Vec<_>| {
        x.extend(y);
        x
    };
    let folded = if same {
        a.par_fold_pairs_within(r, boundary, identity, fold, reduce)
    } else {
        a.par_fold_pairs_within_other(b, r, boundary, identity, fold, reduce)
    };
    assert_eq!(sorted(folded.unwrap().into_iter()), want);
    // a break is returned, one of the pairs, and stops the visits
    let calls = std::sync::atomic::AtomicUsize::new(0);
    let stop = |s: usize, t: usize, d: f64| {
        calls.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        ControlFlow::Break(key(s, t, d))
    };
    let flow = if same {
        a.par_pairs_within(r, boundary, &stop as ParVisit)
    } else {
        a.par_pairs_within_other(b, r, boundary, &stop as ParVisit)
    };
    match flow.unwrap() {
        ControlFlow::Break(p) => assert!(want.contains(&p), "the break of a pair within r"),
        ControlFlow::Continue(()) => assert!(want.is_empty(), "no pair: no break"),
    }
    assert!(calls.into_inner() <= want.len().min(rayon::current_num_threads()));
}

#[cfg(not(feature = "rayon"))]
fn check_par_pairs<A: Set<D>, B: Set<D>, const D: usize>(
    _: &A,
    _: &B,
    _: f64,
    _: Boundary,
    _: bool,
    _: &[(usize, usize, f64)],
) {
}

fn sorted(it: impl Iterator<Item = (usize, usize, f64)>) -> Vec<(usize, usize, f64)> {
    let mut v: Vec<_> = it.collect();
    v.sort_by_key(|x| (x.0, x.1));
    v
}

/// The counts over sorted `radii` against counting nested loops.
fn check_counts<A: Set<D>, B: Set<D>, const D: usize>(
    a: &A,
    pa: &[[f64; D]],
    b: &B,
    pb: &[[f64; D]],
    radii: &[f64],
    boundary: Boundary,
    same: bool,
) {
    let got = if same {
        a.count_pairs_within(radii, boundary).unwrap()
    } else {
        a.count_neighbors(b, radii, boundary).unwrap()
    };
    let want: Vec<u64> = radii
        .iter()
        .map(|&r| {
            let mut n = 0;
            for (i, p) in pa.iter().enumerate() {
                for (j, q) in pb.iter().enumerate() {
                    if (!same || i < j) && admits(boundary, dist(p, q), r) {
                        n += 1;
                    }
                }
            }
            n
        })
        .collect();
    assert_eq!(got, want, "radii {radii:?}");
    #[cfg(feature = "rayon")]
    {
        let par = if same {
            a.par_count_pairs_within(radii, boundary)
        } else {
            a.par_count_neighbors(b, radii, boundary)
        };
        assert_eq!(par.unwrap(), got, "the parallel counts are the serial ones");
    }
}

/// The sparse matrix between `a` and `b` against nested loops, and its CSR form.
fn check_sparse<A: Set<D>, B: Set<D>, const D: usize>(
    a: &A,
    pa: &[[f64; D]],
    b: &B,
    pb: &[[f64; D]],
    r: f64,
    boundary: Boundary,
) {
    let m = a.sparse_distance_matrix(b, r, boundary).unwrap();
    assert_eq!((m.rows(), m.cols()), (pa.len(), pb.len()));
    let coo: Vec<(usize, usize, f64)> = m.iter().collect();
    assert!(
        coo.windows(2).all(|w| (w[0].0, w[0].1) < (w[1].0, w[1].1)),
        "sorted, no pair twice"
    );
    let by_input = sorted(coo.iter().map(|&(s, t, d)| (a.items()[s], b.items()[t], d)));
    let mut want = Vec::new();
    for (i, p) in pa.iter().enumerate() {
        for (j, q) in pb.iter().enumerate() {
            if admits(boundary, dist(p, q), r) {
                want.push((i, j, dist(p, q)));
            }
        }
    }
    assert_eq!(by_input, sorted(want.into_iter()));
    let csr = m.to_csr();
    assert_eq!(csr.shape(), (pa.len(), pb.len()));
    assert_eq!(*csr.indptr().last().unwrap(), m.len());
    for s in 0..pa.len() {
        let (cols, data) = csr.row(s);
        let from_coo: Vec<(usize, f64)> = coo
            .iter()
            .filter(|c| c.0 == s)
            .map(|c| (c.1, c.2))
            .collect();
        let from_csr: Vec<(usize, f64)> = cols.iter().copied().zip(data.iter().copied()).collect();
        assert_eq!(from_csr, from_coo);
    }
    check_parallel(a, b, r, boundary, &m);
}

#[cfg(feature = "rayon")]
fn check_parallel<A: Set<D>, B: Set<D>, const D: usize>(
    a: &A,
    b: &B,
    r: f64,
    boundary: Boundary,
    serial: &orthtree::query::SparseDistances,
) {
    assert_eq!(
        &a.par_sparse_distance_matrix(b, r, boundary).unwrap(),
        serial
    );
    for k in [0, 1, 3, 50] {
        assert_eq!(a.par_k_nearest_join(b, k), a.k_nearest_join(b, k));
        assert_eq!(a.par_k_nearest_self(k), a.k_nearest_self(k));
    }
}

#[cfg(not(feature = "rayon"))]
fn check_parallel<A: Set<D>, B: Set<D>, const D: usize>(
    _: &A,
    _: &B,
    _: f64,
    _: Boundary,
    _: &orthtree::query::SparseDistances,
) {
}

/// Every join of `a` with itself and with `b`.
fn check_all<A: Set<D>, B: Set<D>, const D: usize>(
    a: &A,
    pa: &[[f64; D]],
    b: &B,
    pb: &[[f64; D]],
    radii: &[f64],
) {
    for k in [0, 1, 2, 5, pb.len() + 3] {
        check_knn(a, pa, b, pb, k, false);
        check_knn(a, pa, a, pa, k, true);
    }
    for boundary in [Boundary::Inclusive, Boundary::Exclusive] {
        for &r in radii {
            check_pairs(a, pa, a, pa, r, boundary, true);
            check_pairs(a, pa, b, pb, r, boundary, false);
            check_sparse(a, pa, b, pb, r, boundary);
        }
        check_counts(a, pa, a, pa, radii, boundary, true);
        check_counts(a, pa, b, pb, radii, boundary, false);
    }
}

/// The radii every check uses, sorted: 0, grid steps, beyond the domain, infinite.
fn radii(extra: f64) -> Vec<f64> {
    let mut r = vec![0.0, 0.125, 0.25, 0.5, 1.0, 4.0, 1e200, f64::INFINITY, extra];
    r.sort_by(f64::total_cmp);
    r
}

pub(crate) fn entries<const D: usize>(pts: &[[f64; D]]) -> Vec<([f64; D], usize)> {
    pts.iter().enumerate().map(|(i, p)| (*p, i)).collect()
}

/// Runs [`check_all`] on every point tree, `a` against `b` of every other kind.
fn all_trees<const D: usize>(pa: &[[f64; D]], pb: &[[f64; D]], radii: &[f64]) {
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
    let sa = SkipQuadtree::with_seed(ca.clone(), 3);
    check_all(&a, pa, &cb, pb, radii);
    check_all(&da, pa, &b, pb, radii);
    check_all(&ca, pa, &db, pb, radii);
    check_all(&sa, pa, &b, pb, radii);
}

/// A point of the grid of step 1/8 on [0, 1]^D: split lines, faces and duplicates.
fn grid_point<const D: usize>() -> impl Strategy<Value = [f64; D]> {
    proptest::array::uniform::<_, D>((0u8..=8).prop_map(|j| f64::from(j) / 8.0))
}

/// A coordinate anywhere: on the grid, arbitrary, or extreme (squares beyond `f64::MAX`).
fn any_coordinate() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => (0u8..=8).prop_map(|j| f64::from(j) / 8.0),
        4 => -2.0f64..2.0,
        1 => prop_oneof![Just(1e300), Just(-1e300), Just(1e154), Just(-1e-300)],
    ]
}

proptest! {
    #![proptest_config(config(40, 2112))]

    #[test]
    fn joins_on_grid_points_equal_nested_loops_2d(
        pa in prop::collection::vec(grid_point::<2>(), 0..60),
        pb in prop::collection::vec(grid_point::<2>(), 0..60),
        r in 0.0f64..1.5,
    ) {
        all_trees(&pa, &pb, &radii(r));
    }

    #[test]
    fn joins_on_grid_points_equal_nested_loops_3d(
        pa in prop::collection::vec(grid_point::<3>(), 0..60),
        pb in prop::collection::vec(grid_point::<3>(), 0..60),
        r in 0.0f64..1.5,
    ) {
        all_trees(&pa, &pb, &radii(r));
    }

    #[test]
    fn joins_on_arbitrary_points_equal_nested_loops(
        pa in prop::collection::vec(proptest::array::uniform2(any_coordinate()), 0..50),
        pb in prop::collection::vec(proptest::array::uniform2(any_coordinate()), 0..50),
        r in 0.0f64..3.0,
    ) {
        all_trees(&pa, &pb, &radii(r));
    }
}

#[test]
fn many_duplicates_and_larger_sets() {
    let mut rng = common::rng(21);
    use rand::Rng;
    // 600 points, each drawn from 150 places: leaves of duplicates beyond the bucket size
    let places: Vec<[f64; 3]> = (0..150)
        .map(|_| [rng.r#gen(), rng.r#gen(), rng.r#gen()])
        .collect();
    let pa: Vec<[f64; 3]> = (0..600).map(|_| places[rng.gen_range(0..150)]).collect();
    let pb: Vec<[f64; 3]> = (0..300)
        .map(|_| [rng.r#gen(), rng.r#gen(), rng.r#gen()])
        .collect();
    let (a, b) = (
        PointTree::new(&entries(&pa)).unwrap(),
        CompressedTree::new(&entries(&pb)).unwrap(),
    );
    for k in [1, 8, 20] {
        check_knn(&a, &pa, &b, &pb, k, false);
        check_knn(&a, &pa, &a, &pa, k, true);
    }
    let radii = [0.0, 0.05, 0.1, 0.2, 0.4];
    for &r in &radii {
        check_pairs(&a, &pa, &a, &pa, r, Boundary::Inclusive, true);
        check_sparse(&a, &pa, &b, &pb, r, Boundary::Exclusive);
    }
    check_counts(&a, &pa, &a, &pa, &radii, Boundary::Inclusive, true);
    check_counts(&a, &pa, &b, &pb, &radii, Boundary::Exclusive, false);
}

/// Leaves of duplicates far beyond the leaf kernel's block of 64 points (a run with itself and
/// with another run, each in several blocks), next to clusters on the cells' faces.
fn crowded<const D: usize>() -> impl Strategy<Value = Vec<[f64; D]>> {
    let place = proptest::array::uniform::<_, D>((0u8..=4).prop_map(|j| f64::from(j) / 4.0));
    prop::collection::vec((place, 1usize..150), 1..5).prop_map(|groups| {
        groups
            .into_iter()
            .flat_map(|(p, n)| core::iter::repeat_n(p, n))
            .collect()
    })
}

proptest! {
    #![proptest_config(config(24, 2113))]

    #[test]
    fn joins_over_runs_longer_than_a_block_equal_nested_loops(
        pa in crowded::<3>(),
        pb in crowded::<3>(),
        r in prop_oneof![Just(0.0), Just(0.25), 0.0f64..1.0],
    ) {
        let (a, b) = (
            PointTree::new(&entries(&pa)).unwrap(),
            PointTree::builder().bucket_size(1).max_depth(2).build(&entries(&pb)).unwrap(),
        );
        let mut radii = [0.0, r.min(0.25), r, 0.5, 2.0];
        radii.sort_by(f64::total_cmp);
        // k-nearest over leaves of more than a block of 64 duplicates
        for k in [1, 17, 70] {
            check_knn(&a, &pa, &b, &pb, k, false);
            check_knn(&b, &pb, &b, &pb, k, true);
            #[cfg(feature = "rayon")]
            {
                assert_eq!(b.par_k_nearest_join(&a, k), b.k_nearest_join(&a, k));
                assert_eq!(b.par_k_nearest_self(k), b.k_nearest_self(k));
            }
        }
        for boundary in [Boundary::Inclusive, Boundary::Exclusive] {
            check_pairs(&a, &pa, &a, &pa, r, boundary, true);
            check_pairs(&b, &pb, &b, &pb, r, boundary, true);
            check_pairs(&a, &pa, &b, &pb, r, boundary, false);
            check_counts(&a, &pa, &a, &pa, &radii, boundary, true);
            check_counts(&b, &pb, &a, &pa, &radii, boundary, false);
        }
    }
}

#[test]
fn bad_radii_are_refused_with_what_is_wrong() {
    let pts = [([0.0, 0.0], 0usize), ([1.0, 1.0], 1)];
    let t = PointTree::new(&pts).unwrap();
    let never = |_: usize, _: usize, _: f64| -> ControlFlow<()> { panic!("not called") };
    for r in [-1.0, f64::NAN, -f64::INFINITY] {
        assert!(matches!(
            t.pairs_within(r, Boundary::Inclusive, never),
            Err(QueryError::InvalidRadius { .. })
        ));
        assert!(matches!(
            t.pairs_within_other(&t, r, Boundary::Exclusive, never),
            Err(QueryError::InvalidRadius { .. })
        ));
        assert!(matches!(
            t.sparse_distance_matrix(&t, r, Boundary::Inclusive),
            Err(QueryError::InvalidRadius { .. })
        ));
        assert!(matches!(
            t.count_pairs_within(&[0.0, r], Boundary::Inclusive),
            Err(QueryError::InvalidRadius { .. })
        ));
        #[cfg(feature = "rayon")]
        {
            let never = |_: usize, _: usize, _: f64| -> ControlFlow<()> { panic!("not called") };
            assert!(matches!(
                t.par_pairs_within(r, Boundary::Inclusive, never),
                Err(QueryError::InvalidRadius { .. })
            ));
            assert!(matches!(
                t.par_fold_pairs_within_other(
                    &t,
                    r,
                    Boundary::Inclusive,
                    || (),
                    |_, _, _, _| (),
                    |_, _| ()
                ),
                Err(QueryError::InvalidRadius { .. })
            ));
            assert!(matches!(
                t.par_count_pairs_within(&[0.0, r], Boundary::Inclusive),
                Err(QueryError::InvalidRadius { .. })
            ));
        }
    }
    let err = t.count_neighbors(&t, &[0.0, 1.0, 2.0, 1.5, 3.0], Boundary::Inclusive);
    assert_eq!(err, Err(QueryError::UnsortedRadii { index: 3 }));
    assert_eq!(
        err.unwrap_err().to_string(),
        "radius 3 is smaller than the radius before it"
    );
    assert_eq!(t.count_pairs_within(&[], Boundary::Inclusive), Ok(vec![]));
    // -0.0 is a radius of 0
    assert_eq!(
        t.count_pairs_within(&[-0.0], Boundary::Inclusive),
        Ok(vec![0])
    );
}

#[test]
fn empty_sets_join_to_nothing() {
    let none: Vec<([f64; 2], usize)> = Vec::new();
    let e = PointTree::new(&none).unwrap();
    let t = PointTree::new(&[([0.0, 0.0], 0usize)]).unwrap();
    let table = t.k_nearest_join(&e, 3);
    assert_eq!((table.rows(), table.k()), (1, 0));
    assert_eq!(t.k_nearest_self(3).k(), 0, "no other point");
    assert_eq!(e.k_nearest_join(&t, 3).rows(), 0);
    assert_eq!(
        t.count_neighbors(&e, &[1.0], Boundary::Inclusive),
        Ok(vec![0])
    );
    assert!(e
        .sparse_distance_matrix(&t, 1.0, Boundary::Inclusive)
        .unwrap()
        .is_empty());
    #[cfg(feature = "rayon")]
    {
        let never = |_: usize, _: usize, _: f64| -> ControlFlow<()> { panic!("not called") };
        assert_eq!(
            e.par_pairs_within(1.0, Boundary::Inclusive, never),
            Ok(ControlFlow::Continue(()))
        );
        assert_eq!(
            t.par_pairs_within_other(&e, 1.0, Boundary::Inclusive, never),
            Ok(ControlFlow::Continue(()))
        );
        assert_eq!(t.par_k_nearest_join(&e, 3), table);
        assert_eq!(
            t.par_count_neighbors(&e, &[1.0], Boundary::Inclusive),
            Ok(vec![0])
        );
    }
}

/// A point set of the caller's own: a compressed tree behind the trait's required methods only,
/// so that the joins find its slots through `slot_of` (`PositionSlots::Other`), not a table.
struct OwnSet(CompressedTree<f64, usize, 2>);

impl PointSet<2> for OwnSet {
    type Scalar = f64;
    type Item = usize;
    type Index = <CompressedTree<f64, usize, 2> as PointSet<2>>::Index;

    fn index(&self) -> &Self::Index {
        self.0.index()
    }
    fn item_of<'a>(&'a self, payload: &'a Payload<Self, 2>) -> &'a usize {
        self.0.item_of(payload)
    }
    fn slot_of(&self, position: usize, payload: &Payload<Self, 2>) -> usize {
        self.0.slot_of(position, payload)
    }
    fn items(&self) -> &[usize] {
        self.0.items()
    }
    fn point(&self, slot: usize) -> &[f64; 2] {
        self.0.point(slot)
    }
    fn domain(&self) -> &orthtree::Aabb<f64, 2> {
        self.0.domain()
    }
    fn validate(&self) -> Result<(), orthtree::ValidationError> {
        self.0.validate()
    }
}

#[test]
fn a_set_without_a_slot_table_joins_as_the_tree_it_wraps() {
    use orthtree::query::PositionSlots;
    let mut rng = common::rng(8);
    use rand::Rng;
    let pa: Vec<[f64; 2]> = (0..300).map(|_| [rng.r#gen(), rng.r#gen()]).collect();
    let pb: Vec<[f64; 2]> = (0..200)
        .map(|_| [f64::from(rng.gen_range(0u8..=8)) / 8.0, rng.r#gen()])
        .collect();
    let own = OwnSet(CompressedTree::new(&entries(&pa)).unwrap());
    assert_eq!(own.position_slots(), PositionSlots::Other);
    assert!(matches!(own.0.position_slots(), PositionSlots::Table(_)));
    let b = PointTree::new(&entries(&pb)).unwrap();
    assert_eq!(b.position_slots(), PositionSlots::Same);
    check_all(&own, &pa, &b, &pb, &radii(0.07));
    check_all(&b, &pb, &own, &pa, &radii(0.07));
}
