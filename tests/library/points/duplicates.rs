//! Duplicates and near-duplicates: many copies of one point end at the maximum depth instead of
//! looping; points one ulp apart; the maximum depth is respected.

use crate::common;

use common::points::{check_all, check_points};
use orthtree::prelude::*;
use orthtree::{points::PointTreeBuilder, query::Location, tree::NodeId, Aabb, Cell, Quadtree};
use rand::Rng;

/// n copies of one point: no bucket can part them, so the tree is one chain of splits down to the
/// maximum depth (every split node a single child holding everything), 1 + 2^D * max_depth nodes.
fn copies<const D: usize>(p: [f64; D], n: usize, bucket: usize, max_depth: Option<u8>) {
    let e: Vec<([f64; D], usize)> = (0..n).map(|i| (p, i)).collect();
    let mut b = PointTreeBuilder::<f64, D>::new().bucket_size(bucket);
    if let Some(d) = max_depth {
        b = b.max_depth(d);
    }
    let t = b.build(&e).unwrap();
    let depth = max_depth.unwrap_or(Cell::<D>::MAX_LEVEL);
    assert_eq!(t.len(), n);
    if n > bucket {
        assert_eq!(t.depth(), depth);
        assert_eq!(t.node_count(), 1 + (1 << D) * usize::from(depth));
    } else {
        assert_eq!(t.depth(), 0);
    }
    let leaf = t.locate(&p).unwrap().inside().unwrap();
    assert_eq!(t.node_points(leaf).len(), n, "every copy in one leaf");
    let mut items = t.node_items(leaf).to_vec();
    items.sort_unstable();
    assert!(items.into_iter().eq(0..n));
    t.validate().unwrap();
    // the same from an owned vector
    let t2 = b.build_from_vec(e).unwrap();
    assert_eq!(t2.tree(), t.tree());
    assert_eq!(t2.len(), n);
}

#[test]
fn hundred_thousand_copies_of_one_point() {
    let n = 100_000;
    copies::<2>([0.3, 0.7], n, 1, None);
    copies::<2>([0.3, 0.7], n, orthtree::points::DEFAULT_BUCKET_SIZE, None);
    copies::<2>([-5.0, 1e9], n, 1, Some(5));
    copies::<3>([1.0, 2.0, 3.0], n, 1, None);
    copies::<1>([42.0], n, 3, None);
    copies::<2>(
        [0.0, 0.0],
        orthtree::points::DEFAULT_BUCKET_SIZE,
        orthtree::points::DEFAULT_BUCKET_SIZE,
        None,
    );
}

/// Copies inside a given root box, with other points around, and balance afterwards.
#[test]
fn copies_among_other_points() {
    let mut r = common::rng(91);
    let mut e: Vec<([f64; 2], usize)> = (0..300)
        .map(|i| ([r.r#gen::<f64>(), r.r#gen::<f64>()], i))
        .collect();
    for i in 0..2000 {
        e.push(([0.5, 0.25], 300 + i));
    }
    for bucket in [1, 4, 16] {
        let t = Quadtree::builder()
            .bucket_size(bucket)
            .root_box(Aabb::new([0.0; 2], [1.0; 2]).unwrap())
            .build(&e)
            .unwrap();
        assert_eq!(t.depth(), Cell::<2>::MAX_LEVEL);
        check_all(&t, &e);
    }
}

/// Points differing only in the last bit of one coordinate: parted where a split line falls
/// between them, else kept together at the maximum depth; nothing lost either way.
#[test]
fn points_one_ulp_apart() {
    let mut r = common::rng(92);
    // alone: the computed root cube is tiny, they part near the top
    for base in [0.5f64, 1.0, 3.0, 1e-300, 1e300, -7.25] {
        let e = [([base, 0.0], 0usize), ([base.next_up(), 0.0], 1)];
        let t = Quadtree::builder().bucket_size(1).build(&e).unwrap();
        check_all(&t, &e);
        assert_ne!(t.locate(&e[0].0), t.locate(&e[1].0), "parted at {base}");
    }
    // among spread points in [0, 1]^2: the pairs stay together down to level 32 unless a split
    // line lies between them
    let mut e: Vec<([f64; 2], usize)> = Vec::new();
    for i in 0..60 {
        let p = [r.r#gen::<f64>(), r.r#gen::<f64>()];
        e.push((p, 2 * i));
        e.push(([p[0], p[1].next_up()], 2 * i + 1));
    }
    // and pairs straddling split lines: k / 2^j and its successor
    for x in [0.5f64, 0.25, 0.75, 0.125].iter() {
        e.push(([*x, 0.5], e.len()));
        e.push(([x.next_up(), 0.5], e.len()));
    }
    let t = Quadtree::builder()
        .bucket_size(1)
        .root_box(Aabb::new([0.0; 2], [1.0; 2]).unwrap())
        .build(&e)
        .unwrap();
    check_all(&t, &e);
    assert_eq!(t.depth(), Cell::<2>::MAX_LEVEL);
    for (i, x) in [0.5f64, 0.25, 0.75, 0.125].iter().enumerate() {
        // x lies on a split line: x goes below it, its successor above
        assert_ne!(
            t.locate(&[*x, 0.5]),
            t.locate(&[x.next_up(), 0.5]),
            "pair {i}"
        );
    }
}

/// The maximum depth holds whatever the points: leaves at that level keep everything they get.
#[test]
fn max_depth_is_respected() {
    let mut r = common::rng(93);
    let e: Vec<([f64; 2], usize)> = (0..10_000)
        .map(|i| ([r.r#gen::<f64>(), r.r#gen::<f64>().powi(8)], i))
        .collect();
    for max_depth in [0u8, 1, 2, 5] {
        let t = Quadtree::builder()
            .bucket_size(1)
            .max_depth(max_depth)
            .build(&e)
            .unwrap();
        assert_eq!(t.max_depth(), max_depth);
        assert_eq!(t.depth(), max_depth, "10^4 points fill every level");
        check_points(&t, &e, None);
        let full = (0..=u32::from(max_depth))
            .map(|l| 4usize.pow(l))
            .sum::<usize>();
        assert!(t.node_count() <= full);
        assert!(t.leaves().any(|l| l.points.len() > 1));
        if max_depth == 0 {
            assert_eq!(t.node_count(), 1);
            assert_eq!(t.locate(&e[17].0), Ok(Location::Inside(NodeId::ROOT)));
        }
    }
}

/// Squared Euclidean distance, counting the point-to-point distances computed.
#[derive(Default)]
struct Counting(core::cell::Cell<usize>);

impl orthtree::query::Metric<2> for Counting {
    fn distance(&self, a: &[f64; 2], b: &[f64; 2]) -> f64 {
        self.0.set(self.0.get() + 1);
        orthtree::query::SquaredEuclidean.distance(a, b)
    }
    fn box_distance(&self, q: &[f64; 2], b: &Aabb<f64, 2>) -> f64 {
        orthtree::query::SquaredEuclidean.box_distance(q, b)
    }
}

/// A query at a point with many copies (one leaf at the maximum depth holds them all) stops
/// once its `k` nearest are copies it cannot do better than (a later copy could only tie, and
/// ties go to the lower position), instead of measuring every copy; the answer is the scan's
/// first `k` by (distance, position), in every tree, for nearest and k-nearest.
#[test]
fn a_query_among_many_copies_measures_few_of_them() {
    let mut rng = common::rng(11);
    let copy = [0.375, 0.625];
    let mut entries: Vec<([f64; 2], usize)> = (0..20_000)
        .map(|i| {
            let p = if i % 5 == 0 {
                [rng.r#gen(), rng.r#gen()]
            } else {
                copy
            };
            (p, i)
        })
        .collect();
    entries.push(([0.375, 0.625 + 1e-9], 20_000));
    let tree = Quadtree::new(&entries).unwrap();
    let dynamic = orthtree::DynamicPointTree::new(&entries).unwrap();
    let compressed = orthtree::CompressedTree::new(&entries).unwrap();
    for k in [1, 2, 16, 17, 40] {
        let metric = Counting::default();
        let got = tree.k_nearest_by(&copy, k, f64::INFINITY, &metric).unwrap();
        assert!(
            metric.0.get() <= 4 * 64 + 200,
            "k {k}: {} distances",
            metric.0.get()
        );
        // the scan's answer: the copies at the lowest positions of the tree's order
        let slots: Vec<usize> = got.iter().map(|n| n.index).collect();
        let mut want: Vec<(f64, usize)> = (tree.points().iter().enumerate())
            .map(|(s, p)| {
                (
                    orthtree::query::Metric::<2>::distance(
                        &orthtree::query::SquaredEuclidean,
                        &copy,
                        p,
                    ),
                    s,
                )
            })
            .collect();
        want.sort_by(|a, b| a.partial_cmp(b).unwrap());
        let want: Vec<usize> = want[..k].iter().map(|&(_, s)| s).collect();
        assert_eq!(slots, want, "k {k}");
        assert!(got.iter().all(|n| *n.point == copy));
        // the other trees: k copies too
        for found in [
            dynamic
                .k_nearest_by(&copy, k, f64::INFINITY, &metric)
                .unwrap(),
            compressed
                .k_nearest_by(&copy, k, f64::INFINITY, &metric)
                .unwrap(),
        ] {
            assert_eq!(found.len(), k);
            assert!(found.iter().all(|n| *n.point == copy && n.distance == 0.0));
        }
    }
}
