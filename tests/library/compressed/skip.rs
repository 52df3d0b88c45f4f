//! The skip quadtree: every level a canonical compressed quadtree over its sample, linked down,
//! checked with `validate` after every update and compared with a fresh build; point location
//! against the compressed tree's; (1 + eps)-approximate nearest neighbours against brute force;
//! and the nodes a location touches on inputs as deep as the cells allow, beside the walk down
//! the compressed tree from its root.

use super::workload;
use crate::common;

use common::points::config;
use orthtree::compressed::SkipQuadtree;
use orthtree::prelude::*;
use orthtree::{Aabb, CompressedTree, Error};
use proptest::prelude::*;

fn grid_point() -> impl Strategy<Value = [f64; 2]> {
    proptest::array::uniform2((0u32..=32).prop_map(|j| j as f64 / 32.0))
}

fn shape(t: &SkipQuadtree<f64, usize, 2>) -> Vec<Vec<(orthtree::geom::DeepCell<2>, bool)>> {
    (0..t.level_count())
        .map(|i| t.level_cells(i).collect())
        .collect()
}

proptest! {
    #![proptest_config(config(64, 801))]
    #[test]
    fn updates_equal_a_fresh_build(
        start in prop::collection::vec(grid_point(), 0..40),
        ops in prop::collection::vec((any::<bool>(), grid_point(), 0usize..60), 1..120),
        seed in any::<u64>(),
    ) {
        let root = Aabb::new([0.0, 0.0], [1.0, 1.0]).unwrap();
        let build = |e: &[([f64; 2], usize)]| {
            let base = CompressedTree::builder().root_box(root).build(e).unwrap();
            SkipQuadtree::with_seed(base, seed)
        };
        let mut stored: Vec<([f64; 2], usize)> = start.iter().enumerate().map(|(i, &p)| (p, i)).collect();
        let mut t = build(&stored);
        t.validate().unwrap();
        let mut next = stored.len();
        for (insert, p, pick) in ops {
            if insert || stored.is_empty() {
                t.insert(p, next).unwrap();
                stored.push((p, next));
                next += 1;
            } else {
                let (q, item) = stored.swap_remove(pick % stored.len());
                prop_assert!(t.remove(&q, &item));
            }
            t.validate().unwrap();
            prop_assert_eq!(shape(&t), shape(&build(&stored)));
            let at = t.locate(&p).unwrap().inside().unwrap();
            let plain = t.base().locate(&p).unwrap().inside().unwrap();
            prop_assert_eq!((at.node, at.cell, at.leaf), (plain.node, plain.cell, plain.leaf));
        }
        prop_assert_eq!(t.len(), stored.len());
    }

    #[test]
    fn approximate_nearest_is_within_one_plus_eps(
        pts in prop::collection::vec(proptest::array::uniform2(-1.0f64..1.0), 1..300),
        q in proptest::array::uniform2(-1.5f64..1.5),
        eps in prop_oneof![Just(0.0), 0.0f64..2.0],
    ) {
        let e: Vec<([f64; 2], usize)> = pts.iter().enumerate().map(|(i, &p)| (p, i)).collect();
        let t = SkipQuadtree::new(&e).unwrap();
        let d2 = |p: &[f64; 2]| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
        let best = pts.iter().map(d2).fold(f64::INFINITY, f64::min);
        let (found, visited) = t.approx_nearest(&q, eps).unwrap();
        let found = found.unwrap();
        prop_assert!(visited >= 1);
        prop_assert_eq!(found.distance, d2(found.point));
        prop_assert_eq!(*found.point, pts[*found.item]);
        prop_assert!(found.distance <= best * (1.0 + eps) * (1.0 + eps) * (1.0 + 1e-12));
        if eps == 0.0 {
            prop_assert_eq!(found.distance, best);
        }
    }
}

proptest! {
    #![proptest_config(config(32, 802))]
    #[test]
    fn updates_in_3d_equal_a_fresh_build(
        ops in prop::collection::vec((any::<bool>(), proptest::array::uniform3(0u32..=8), 0usize..40), 1..80),
        seed in any::<u64>(),
    ) {
        let root = Aabb::new([0.0; 3], [1.0; 3]).unwrap();
        let build = |e: &[([f64; 3], usize)]| {
            SkipQuadtree::with_seed(CompressedTree::builder().root_box(root).build(e).unwrap(), seed)
        };
        let levels = |t: &SkipQuadtree<f64, usize, 3>| -> Vec<Vec<_>> {
            (0..t.level_count()).map(|i| t.level_cells(i).collect()).collect()
        };
        let mut t = build(&[]);
        let mut stored = Vec::new();
        for (i, (insert, p, pick)) in ops.into_iter().enumerate() {
            let p = p.map(|x| x as f64 / 8.0);
            if insert || stored.is_empty() {
                t.insert(p, i).unwrap();
                stored.push((p, i));
            } else {
                let (q, item) = stored.swap_remove(pick % stored.len());
                prop_assert!(t.remove(&q, &item));
            }
            t.validate().unwrap();
            prop_assert_eq!(levels(&t), levels(&build(&stored)));
        }
    }
}

#[test]
fn bad_input_and_empty_trees() {
    let mut t: SkipQuadtree<f64, u8, 2> = SkipQuadtree::new(&[]).unwrap();
    assert_eq!((t.len(), t.level_count()), (0, 1));
    assert!(t.approx_nearest(&[0.0, 0.0], 0.1).unwrap().0.is_none());
    assert!(matches!(
        t.insert([2.0, 0.0], 1).map_err(|e| e.error),
        Err(Error::OutsideRootBox {
            index: 0,
            axis: 0,
            ..
        })
    ));
    assert!(matches!(
        t.locate(&[f64::NAN, 0.0]),
        Err(orthtree::QueryError::NotFinite { axis: 0, .. })
    ));
    assert!(matches!(
        t.approx_nearest(&[0.0, 0.0], -1.0),
        Err(orthtree::QueryError::InvalidEpsilon { .. })
    ));
    assert!(t.approx_nearest(&[0.0, f64::INFINITY], 1.0).is_err());
    t.insert([0.5, 0.5], 1).unwrap();
    t.insert([0.5, 0.5], 2).unwrap();
    assert_eq!(t.remove_point(&[0.5, 0.5]), Some(1));
    assert_eq!(t.remove_point(&[0.25, 0.5]), None);
    assert_eq!(t.remove_point(&[0.5, 0.5]), Some(2));
    assert!(t.is_empty());
    t.validate().unwrap();
}

/// Mean nodes touched per location on caterpillars: (n, depth, levels, walk from the root and
/// skip quadtree over every point, the same over the deepest quarter of the legs).
fn touched(copies: usize, legs: u32) -> (usize, usize, usize, [f64; 4]) {
    let (pts, legs) = workload::caterpillars(copies, legs);
    let e: Vec<([f64; 2], ())> = pts.iter().map(|&p| (p, ())).collect();
    let t = SkipQuadtree::new(&e).unwrap();
    t.validate().unwrap();
    assert_eq!(
        t.base().leaf_count(),
        pts.len(),
        "every leg is its own leaf"
    );
    let mean = |qs: &[[f64; 2]], f: &dyn Fn(&[f64; 2]) -> usize| {
        qs.iter().map(f).sum::<usize>() as f64 / qs.len() as f64
    };
    let walk = |q: &[f64; 2]| t.base().locate(q).unwrap().inside().unwrap().touched;
    let skip = |q: &[f64; 2]| t.locate(q).unwrap().inside().unwrap().touched;
    let deep = workload::deep_legs(&pts, legs);
    let means = [
        mean(&pts, &walk),
        mean(&pts, &skip),
        mean(&deep, &walk),
        mean(&deep, &skip),
    ];
    println!(
        "{}, {legs}, {}, {}, {:.1}, {:.1}, {:.1}, {:.1}",
        pts.len(),
        t.base().depth(),
        t.level_count(),
        means[0],
        means[1],
        means[2],
        means[3]
    );
    (pts.len(), t.base().depth(), t.level_count(), means)
}

#[test]
fn skip_location_touches_log_n_nodes_where_the_compressed_walk_touches_depth() {
    println!("n, legs, compressed depth, levels, mean nodes touched: walk, skip; deepest legs: walk, skip");
    // As deep as f64 allows (53 bits below the unit square), n growing.
    let mut rows = Vec::new();
    for copies in [1usize, 4, 16, 64, 256, 1024, 4096] {
        rows.push(touched(copies, 53));
    }
    for &(n, depth, levels, [walk, skip, deep_walk, deep_skip]) in &rows {
        let log_n = (n as f64).log2();
        assert!(depth >= 50, "n = {n}: depth {depth}");
        assert!(
            deep_walk >= 0.85 * depth as f64,
            "n = {n}: walk {deep_walk}"
        );
        // the skip quadtree: O(log n) whatever the depth, and the same on deep and shallow legs
        assert!(
            skip <= 2.5 * log_n + 6.0 && deep_skip <= 2.5 * log_n + 6.0,
            "n = {n}"
        );
        assert!((levels as f64) <= log_n + 5.0, "n = {n}: {levels} levels");
        assert!(
            deep_skip <= 0.75 * deep_walk,
            "n = {n}: {deep_skip} vs {deep_walk}"
        );
        if n < 1000 {
            assert!(skip <= 0.75 * walk, "n = {n}: {skip} vs {walk}");
        }
    }
    // the skip quadtree's count grows with log n: about 2 nodes per doubling, far below depth
    let (first, last) = (rows[0], rows[rows.len() - 1]);
    let doublings = (last.0 as f64 / first.0 as f64).log2();
    assert!(
        last.3[3] - first.3[3] <= 2.5 * doublings,
        "{first:?} {last:?}"
    );
    assert!(last.3[3] > first.3[3], "{first:?} {last:?}");

    // n fixed near 2^14, the depth growing: the walk follows the depth, the skip quadtree not.
    let mut rows = Vec::new();
    for legs in [6u32, 12, 24, 48] {
        rows.push(touched((1 << 14) / legs as usize, legs));
    }
    for pair in rows.windows(2) {
        let (w0, w1) = (pair[0].3[2], pair[1].3[2]);
        assert!(w1 >= w0 + 4.0, "the walk grows with the depth: {pair:?}");
    }
    // over the deepest legs: the walk's count spreads with the depth, the skip quadtree's little
    let spread = |i: usize| {
        let v = || rows.iter().map(|r| r.3[i]);
        v().fold(f64::MIN, f64::max) - v().fold(f64::MAX, f64::min)
    };
    assert!(spread(3) <= 0.35 * spread(2), "{rows:?}");
    let (shallow, deep) = (rows[0].3, rows[rows.len() - 1].3);
    assert!(deep[2] >= 3.0 * shallow[2], "{shallow:?} {deep:?}");
    assert!(deep[3] <= 0.7 * deep[2], "{deep:?}");
}
