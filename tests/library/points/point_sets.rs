//! One generic check of every [`PointSet`] query against brute force, run on each tree that
//! implements the trait (`PointTree`, `DynamicPointTree`, `CompressedTree`, `SkipQuadtree`):
//! range queries over boxes, balls, half-spaces and a user region (lazy, count, visitor, stats),
//! nearest, k-nearest and the nearest iterator under three metrics with and without a maximum
//! distance, the accessors, the one meaning of a neighbour's index (a slot of `items()`), the
//! serial batch forms and the parallel ones (feature `rayon`), and the updates of [`PointSetMut`] against a model. Points lie
//! on a dyadic grid (split lines, box faces, exact distances, many duplicates), D = 2 and 3.

use crate::common;

use common::points::config;
use orthtree::prelude::*;
use orthtree::query::{Chebyshev, Manhattan, Metric, SquaredEuclidean};
use orthtree::{
    query::HalfSpace, query::Relation, Aabb, Ball, CompressedTree, DynamicPointTree, PointTree,
    Region, SkipQuadtree,
};
use proptest::prelude::*;

/// The slab `lo <= x[0] <= hi`: a region the crate does not define.
#[derive(Clone, Copy)]
struct Slab {
    lo: f64,
    hi: f64,
}

impl<const D: usize> Region<D> for Slab {
    fn contains(&self, p: &[f64; D]) -> bool {
        self.lo <= p[0] && p[0] <= self.hi
    }
    fn classify(&self, b: &Aabb<f64, D>) -> Relation {
        if b.max[0] < self.lo || b.min[0] > self.hi {
            Relation::Outside
        } else if self.lo <= b.min[0] && b.max[0] <= self.hi {
            Relation::Inside
        } else {
            Relation::Crossing
        }
    }
}

/// The items (original positions) of `pts` in `region`, sorted.
fn brute_region<R: Region<D>, const D: usize>(pts: &[[f64; D]], region: &R) -> Vec<usize> {
    (0..pts.len())
        .filter(|&i| region.contains(&pts[i]))
        .collect()
}

/// Every range query form on `region` gives the brute-force answer.
fn check_region<P, R, const D: usize>(t: &P, pts: &[[f64; D]], region: R)
where
    P: PointSet<D, Scalar = f64, Item = usize>,
    R: Region<D> + Copy,
{
    let want = brute_region(pts, &region);
    let mut got: Vec<usize> = t.query(region).unwrap().map(|(_, &i)| i).collect();
    got.sort_unstable();
    assert_eq!(got, want);
    for (p, &i) in t.query(region).unwrap() {
        assert_eq!(*p, pts[i], "a region answer's point is its item's");
    }
    assert_eq!(t.query_count(region).unwrap(), want.len());
    assert_eq!(t.query_stats(region).unwrap().count, want.len());
    let mut visited = Vec::new();
    t.query_with(region, |p, &i| {
        assert_eq!(*p, pts[i]);
        visited.push(i);
    })
    .unwrap();
    visited.sort_unstable();
    assert_eq!(visited, want);
}

/// The k-nearest answer to `q` under `metric` within `max`: the first `k` distances of the
/// brute-force sort, each neighbour's distance its point's, no point twice, and its index a slot.
fn check_neighbors<P, M, const D: usize>(
    t: &P,
    pts: &[[f64; D]],
    q: &[f64; D],
    k: usize,
    max: f64,
    metric: &M,
) where
    P: PointSet<D, Scalar = f64, Item = usize>,
    M: Metric<D> + Copy,
{
    let mut all: Vec<f64> = pts
        .iter()
        .map(|p| metric.distance(q, p))
        .filter(|&d| d <= max)
        .collect();
    all.sort_by(f64::total_cmp);
    let want: Vec<f64> = all.iter().copied().take(k).collect();
    let got = t.k_nearest_by(q, k, max, metric).unwrap();
    let dists: Vec<f64> = got.iter().map(|n| n.distance).collect();
    assert_eq!(dists, want);
    let mut seen: Vec<usize> = got.iter().map(|n| *n.item).collect();
    seen.sort_unstable();
    seen.dedup();
    assert_eq!(seen.len(), got.len(), "a point reported twice");
    for n in &got {
        assert_eq!(n.distance, metric.distance(q, n.point));
        assert_eq!(*n.point, pts[*n.item]);
        assert_eq!(t.items()[n.index], *n.item, "index is the item's slot");
        assert_eq!(t.point(n.index), n.point, "index is the point's slot");
    }
    let one = t.nearest_by(q, max, metric).unwrap().map(|n| n.distance);
    assert_eq!(one, all.first().copied());
    let iter: Vec<f64> = t
        .nearest_iter_by(q, max, *metric)
        .unwrap()
        .map(|n| n.distance)
        .collect();
    assert_eq!(
        iter, all,
        "the iterator yields every point in range, nearest first"
    );
}

/// Every query of `t`, built over `pts` with items `0..n`, against brute force.
fn check<P, const D: usize>(t: &P, pts: &[[f64; D]], queries: &[[f64; D]])
where
    P: PointSet<D, Scalar = f64, Item = usize> + Sync,
{
    t.validate().unwrap();
    assert_eq!((t.len(), t.is_empty()), (pts.len(), pts.is_empty()));
    assert_eq!(t.iter().len(), pts.len());
    let mut items: Vec<usize> = t.items().to_vec();
    items.sort_unstable();
    assert_eq!(items, (0..pts.len()).collect::<Vec<_>>());
    for (s, (p, &i)) in t.iter().enumerate() {
        assert_eq!((p, *p), (t.point(s), pts[i]));
        assert_eq!(t.items()[s], i);
        assert!(t.domain().contains(p));
    }
    for q in queries {
        let [a, b] = [q[0].min(q[D - 1]), q[0].max(q[D - 1])];
        let bx = Aabb::new([a; D], [b; D]).unwrap();
        check_region(t, pts, bx);
        let in_box: Vec<usize> = t.in_box(&bx).unwrap().map(|(_, &i)| i).collect();
        assert_eq!(in_box.len(), brute_region(pts, &bx).len());
        let radius = (b - a) * (b - a);
        check_region(t, pts, Ball::new(*q, radius).unwrap());
        assert_eq!(
            t.in_ball(q, radius).unwrap().count(),
            brute_region(pts, &Ball::new(*q, radius).unwrap()).len()
        );
        let mut normal = [1.0; D];
        normal[D - 1] = -0.5;
        let half = HalfSpace::new(normal, q[0]).unwrap();
        check_region(t, pts, half);
        assert_eq!(
            t.in_half_space(normal, q[0]).unwrap().count(),
            brute_region(pts, &half).len()
        );
        check_region(t, pts, Slab { lo: a, hi: b });
        for k in [0, 1, 3, 17] {
            for max in [f64::INFINITY, radius] {
                check_neighbors(t, pts, q, k, max, &SquaredEuclidean);
                check_neighbors(t, pts, q, k, max, &Manhattan);
                check_neighbors(t, pts, q, k, max, &Chebyshev);
            }
        }
        let d = |n: Option<orthtree::Neighbor<'_, f64, usize, D>>| n.map(|n| n.distance);
        assert_eq!(
            d(t.nearest(q).unwrap()),
            d(t.nearest_by(q, f64::INFINITY, &SquaredEuclidean).unwrap())
        );
        assert_eq!(
            d(t.nearest_within(q, radius).unwrap()),
            d(t.nearest_by(q, radius, &SquaredEuclidean).unwrap())
        );
        let plain: Vec<f64> = t
            .k_nearest(q, 5)
            .unwrap()
            .iter()
            .map(|n| n.distance)
            .collect();
        let by = t
            .k_nearest_by(q, 5, f64::INFINITY, &SquaredEuclidean)
            .unwrap();
        assert_eq!(plain, by.iter().map(|n| n.distance).collect::<Vec<_>>());
        let within = t.k_nearest_within(q, 5, radius).unwrap();
        assert!(within.iter().all(|n| n.distance <= radius));
        assert_eq!(t.nearest_iter(q).unwrap().count(), pts.len());
        let inside = t.nearest_iter_within(q, radius).unwrap().count();
        let near = pts
            .iter()
            .filter(|p| SquaredEuclidean.distance(q, p) <= radius);
        assert_eq!(inside, near.count(), "squared distances up to `max`");
    }
    check_serial_batches(t, queries);
    check_batches(t, pts, queries);
}

/// The serial batches ([`BatchQueries`]) visit every query once with the single query's answer
/// (plain and on the torus of the unit box), also for queries outside the domain, and a bad
/// query fails the batch before any visit, naming the first bad position.
fn check_serial_batches<P, const D: usize>(t: &P, queries: &[[f64; D]])
where
    P: PointSet<D, Scalar = f64, Item = usize>,
{
    let mut queries = queries.to_vec();
    queries.extend([[2.0; D], [-1.0; D], [0.5; D]]);
    let torus = orthtree::query::Torus::wrapping([0.0; D], [1.0; D]).unwrap();
    let key = |n: &orthtree::Neighbor<'_, f64, usize, D>| (n.index, *n.item, n.distance);
    for k in [0, 1, 3, 17] {
        let mut seen = vec![0; queries.len()];
        t.k_nearest_batch(&queries, k, |q, near| {
            seen[q] += 1;
            let single = t.k_nearest(&queries[q], k).unwrap();
            assert!(near.iter().map(key).eq(single.iter().map(key)), "query {q}");
        })
        .unwrap();
        assert!(seen.iter().all(|&v| v == 1), "each query visited once");
        t.periodic_k_nearest_batch(&torus, &queries, k, |q, near| {
            seen[q] += 1;
            let single = t.periodic_k_nearest(&torus, &queries[q], k).unwrap();
            assert!(near.iter().map(key).eq(single.iter().map(key)), "query {q}");
        })
        .unwrap();
        assert!(seen.iter().all(|&v| v == 2), "each query visited once more");
    }
    let mut bad = queries.clone();
    bad.insert(1, [f64::NAN; D]);
    bad.push([f64::INFINITY; D]);
    let err = t
        .k_nearest_batch(&bad, 2, |_, _| panic!("a visit"))
        .unwrap_err();
    assert_eq!(err.index, 1);
    assert!(err.to_string().contains("query 1"), "{err}");
    let err = t
        .periodic_k_nearest_batch(&torus, &bad[2..], 2, |_, _| panic!("a visit"))
        .unwrap_err();
    assert_eq!(err.index, bad.len() - 3);
}

/// The batch forms give the serial answers, in order; their indices are slots.
#[cfg(feature = "rayon")]
fn check_batches<P, const D: usize>(t: &P, pts: &[[f64; D]], queries: &[[f64; D]])
where
    P: PointSet<D, Scalar = f64, Item = usize> + Sync,
{
    let mut bad = queries.to_vec();
    let first = bad.len().min(1);
    bad.insert(first, [f64::NAN; D]);
    bad.push([f64::INFINITY; D]);
    let err = t.par_k_nearest(&bad, 2).unwrap_err();
    assert_eq!(err.index, first, "the first bad query");
    let batch = t.par_k_nearest(queries, 4).unwrap();
    for (q, answer) in queries.iter().zip(&batch) {
        let serial = t.k_nearest(q, 4).unwrap();
        assert!(answer
            .iter()
            .map(|n| n.index)
            .eq(serial.iter().map(|n| n.index)));
    }
    let balls: Vec<Ball<D>> = queries
        .iter()
        .map(|q| Ball::new(*q, 0.1).unwrap())
        .collect();
    let counts = t.par_query_count(&balls).unwrap();
    let found = t.par_query_indices(&balls).unwrap();
    for ((ball, &count), slots) in balls.iter().zip(&counts).zip(&found) {
        let mut items: Vec<usize> = slots.iter().map(|&s| t.items()[s]).collect();
        items.sort_unstable();
        assert_eq!(items, brute_region(pts, ball));
        assert_eq!(count, items.len());
        assert!(slots.windows(2).all(|w| w[0] < w[1]), "slots ascending");
    }
}

#[cfg(not(feature = "rayon"))]
fn check_batches<P, const D: usize>(_: &P, _: &[[f64; D]], _: &[[f64; D]]) {}

/// Inserts and removals through [`PointSetMut`] keep the set equal to a model (item `i` at
/// `model[i]`), and every query afterwards still agrees with brute force.
fn check_updates<P, const D: usize>(t: &mut P, pts: &[[f64; D]], extra: &[[f64; D]])
where
    P: PointSetMut<D, Scalar = f64, Item = usize> + Sync,
{
    let mut model: Vec<[f64; D]> = pts.to_vec();
    for p in extra {
        t.insert(*p, model.len()).unwrap();
        model.push(*p);
        t.validate().unwrap();
    }
    assert!(
        t.insert([2.0; D], usize::MAX).is_err(),
        "outside the root box"
    );
    assert_eq!(t.remove_point(&[2.0; D]), None);
    for step in 0..extra.len() / 2 {
        let last = model.len() - 1;
        let p = model[last];
        if step % 2 == 0 {
            assert!(t.remove(&p, &last));
            assert!(!t.remove(&p, &last), "each item is stored once");
        } else {
            let got = t.remove_point(&p).unwrap();
            assert_eq!(model[got], p, "remove_point returns an item stored there");
            if got != last {
                t.insert(p, got).unwrap();
                assert!(t.remove(&p, &last));
            }
        }
        model.pop();
        t.validate().unwrap();
    }
    check(t, &model, &extra[..extra.len().min(3)]);
}

/// The builds of every tree over the same entries.
fn entries<const D: usize>(pts: &[[f64; D]]) -> Vec<([f64; D], usize)> {
    pts.iter().enumerate().map(|(i, p)| (*p, i)).collect()
}

fn root<const D: usize>() -> Aabb<f64, D> {
    Aabb::new([0.0; D], [1.0; D]).unwrap()
}

fn all_trees<const D: usize>(pts: &[[f64; D]], queries: &[[f64; D]], extra: &[[f64; D]]) {
    let e = entries(pts);
    let plain = PointTree::builder()
        .root_box(root())
        .bucket_size(2)
        .build(&e)
        .unwrap();
    let dynamic = DynamicPointTree::from(plain.clone());
    let compressed = CompressedTree::builder()
        .root_box(root())
        .build(&e)
        .unwrap();
    let skip = SkipQuadtree::with_seed(compressed.clone(), 7);
    check(&plain, pts, queries);
    check(&dynamic, pts, queries);
    check(&compressed, pts, queries);
    check(&skip, pts, queries);
    check_updates(&mut plain.clone(), pts, extra);
    check_updates(&mut dynamic.clone(), pts, extra);
    check_updates(&mut compressed.clone(), pts, extra);
    check_updates(&mut skip.clone(), pts, extra);
}

/// A point of the grid of step 1/8 on [0, 1]^D: split lines, faces and duplicates.
fn grid_point<const D: usize>() -> impl Strategy<Value = [f64; D]> {
    proptest::array::uniform::<_, D>((0u8..=8).prop_map(|j| f64::from(j) / 8.0))
}

proptest! {
    #![proptest_config(config(48, 2026))]

    #[test]
    fn every_tree_answers_every_query_as_brute_force_2d(
        pts in prop::collection::vec(grid_point::<2>(), 0..120),
        queries in prop::collection::vec(grid_point::<2>(), 1..4),
        extra in prop::collection::vec(grid_point::<2>(), 0..8),
    ) {
        all_trees(&pts, &queries, &extra);
    }

    #[test]
    fn every_tree_answers_every_query_as_brute_force_3d(
        pts in prop::collection::vec(grid_point::<3>(), 0..120),
        queries in prop::collection::vec(grid_point::<3>(), 1..4),
        extra in prop::collection::vec(grid_point::<3>(), 0..8),
    ) {
        all_trees(&pts, &queries, &extra);
    }
}

#[test]
fn random_points_in_every_tree() {
    // Points off the grid, from a fixed linear congruential sequence.
    let mut x = 12345u64;
    let mut next = || {
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    let pts: Vec<[f64; 2]> = (0..2000).map(|_| [next(), next()]).collect();
    let queries: Vec<[f64; 2]> = (0..5).map(|_| [next(), next()]).collect();
    let extra: Vec<[f64; 2]> = (0..6).map(|_| [next(), next()]).collect();
    all_trees(&pts, &queries, &extra);
}
