//! The skip quadtree: every level a canonical compressed quadtree over its sample, linked down,
//! checked with `validate` after every update and compared with a fresh build; point location
//! against the compressed tree's; (1 + eps)-approximate nearest neighbours against brute force;
//! and the nodes a location touches on inputs as deep as the cells allow, beside the walk down
//! the compressed tree from its root.

mod common;
#[path = "../benches/workloads/compressed.rs"]
mod workload;

use common::points::config;
use orthtree::compressed::SkipQuadtree;
use orthtree::{Aabb, CompressedTree, Error};
use proptest::prelude::*;

fn grid_point() -> impl Strategy<Value = [f64; 2]> {
    proptest::array::uniform2((0u32..=32).prop_map(|j| j as f64 / 32.0))
}

fn shape(t: &SkipQuadtree<f64, usize, 2>) -> Vec<Vec<(orthtree::Cell<2>, bool)>> {
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
            let at = t.locate(&p).unwrap();
            let plain = t.base().locate(&p).unwrap();
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
        t.insert([2.0, 0.0], 1),
        Err(Error::OutsideRootBox {
            index: 0,
            axis: 0,
            ..
        })
    ));
    assert!(matches!(
        t.locate(&[f64::NAN, 0.0]),
        Err(Error::QueryNotFinite { axis: 0, .. })
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

#[test]
fn skip_location_touches_log_n_nodes_where_the_compressed_walk_touches_depth() {
    println!("n, compressed depth, mean nodes touched: compressed walk, skip quadtree, levels");
    let mut rows = Vec::new();
    for copies in [1usize, 4, 16, 64, 256, 1024, 4096] {
        let pts = workload::caterpillars(copies);
        let e: Vec<([f64; 2], ())> = pts.iter().map(|&p| (p, ())).collect();
        let t = SkipQuadtree::new(&e).unwrap();
        t.validate().unwrap();
        let (mut walk, mut skip) = (0usize, 0usize);
        for p in &pts {
            walk += t.base().locate(p).unwrap().touched;
            skip += t.locate(p).unwrap().touched;
        }
        let n = pts.len();
        let (walk, skip) = (walk as f64 / n as f64, skip as f64 / n as f64);
        println!(
            "{n}, {}, {walk:.1}, {skip:.1}, {}",
            t.base().depth(),
            t.level_count()
        );
        rows.push((n, walk, skip));
    }
    // the walk grows with the depth, the skip quadtree like log n
    for &(n, _, skip) in &rows {
        assert!(skip <= 3.0 * (n as f64).log2() + 6.0, "n = {n}: {skip}");
    }
    let (_, walk0, skip0) = rows[0];
    assert!(
        skip0 < walk0,
        "one caterpillar: skip {skip0} vs walk {walk0}"
    );
}
