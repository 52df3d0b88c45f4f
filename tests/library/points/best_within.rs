//! `best_n_within` against brute force on every point tree: the `n` points within the radius
//! whose items rank best by a key, ties by slot; grid points (split lines, duplicates, exact
//! distances), duplicate keys, r = 0 and r = infinity, n = 0 and n beyond the ball.

use orthtree::prelude::*;
use orthtree::{CompressedTree, DynamicPointTree, PointTree, QueryError, SkipQuadtree};
use proptest::prelude::*;

/// The brute-force answer: (key, slot, squared distance) of the `n` best points in the ball.
fn brute<P: PointSet<2, Scalar = f64, Item = u32>>(
    t: &P,
    q: [f64; 2],
    r: f64,
    n: usize,
) -> Vec<(u32, usize, f64)> {
    let mut all: Vec<(u32, usize, f64)> = (0..t.len())
        .filter_map(|s| {
            let p = t.point(s);
            let d = (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
            (d <= r * r).then_some((t.items()[s] % 5, s, d))
        })
        .collect();
    all.sort_by_key(|a| (a.0, a.1));
    all.truncate(n);
    all
}

/// One tree's answers against [`brute`], the key being the item modulo 5 (many ties).
fn check<P: PointSet<2, Scalar = f64, Item = u32>>(t: &P, q: [f64; 2], r: f64, n: usize) {
    let got: Vec<(u32, usize, f64)> = t
        .best_n_within(&q, r, n, |&v| v % 5)
        .unwrap()
        .iter()
        .map(|nb| {
            assert_eq!(nb.point, t.point(nb.index));
            assert_eq!(nb.item, &t.items()[nb.index]);
            (*nb.item % 5, nb.index, nb.distance)
        })
        .collect();
    assert_eq!(got, brute(t, q, r, n), "q {q:?}, r {r}, n {n}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn best_n_within_is_brute_force(
        cells in prop::collection::vec((0u8..9, 0u8..9), 0..120),
        q in (0u8..17, 0u8..17),
        r in prop::sample::select(vec![0.0, 0.25, 0.5, 1.0, 1.5, 2.0, 3.25, 100.0, f64::INFINITY]),
        n in 0usize..12,
    ) {
        let entries: Vec<([f64; 2], u32)> = cells
            .iter()
            .enumerate()
            .map(|(i, &(x, y))| ([x as f64 * 0.5, y as f64 * 0.5], i as u32))
            .collect();
        let q = [q.0 as f64 * 0.25, q.1 as f64 * 0.25];
        let plain = PointTree::new(&entries).unwrap();
        check(&plain, q, r, n);
        check(&DynamicPointTree::new(&entries).unwrap(), q, r, n);
        check(&CompressedTree::new(&entries).unwrap(), q, r, n);
        check(&SkipQuadtree::new(&entries).unwrap(), q, r, n);
        check(&plain, q, r, entries.len() + 3);
    }
}

#[test]
fn bad_parameters_are_refused() {
    let t = PointTree::new(&[([0.0, 0.0], 1u32)]).unwrap();
    assert!(matches!(
        t.best_n_within(&[f64::NAN, 0.0], 1.0, 1, |&v| v),
        Err(QueryError::NotFinite { axis: 0, .. })
    ));
    assert!(matches!(
        t.best_n_within(&[0.0, 0.0], -1.0, 1, |&v| v),
        Err(QueryError::InvalidRadius { .. })
    ));
    assert!(matches!(
        t.best_n_within(&[0.0, 0.0], f64::NAN, 0, |&v| v),
        Err(QueryError::InvalidRadius { .. })
    ));
    // a huge n allocates by the data, not by the request
    assert_eq!(
        t.best_n_within(&[0.0, 0.0], 1.0, usize::MAX, |&v| v)
            .unwrap()
            .len(),
        1
    );
}
