//! The compressed quadtree's 64-level cells: points that differ only in their last mantissa
//! bits get leaves of their own and equal points share one; the cells agree with the point
//! tree's down to its deepest level, deeper nodes lying in its deepest leaves; updates and the
//! skip quadtree on such points equal fresh builds; queries agree with brute force.

use crate::common;

use common::points::config;
use orthtree::compressed::SkipQuadtree;
use orthtree::prelude::*;
use orthtree::{geom::DeepCell, Aabb, Cell, CompressedTree, PointTree, Quadtree};
use proptest::prelude::*;

fn unit<const D: usize>() -> Aabb<f64, D> {
    Aabb::new([0.0; D], [1.0; D]).unwrap()
}

fn build<const D: usize>(pts: &[[f64; D]]) -> CompressedTree<f64, usize, D> {
    let e: Vec<([f64; D], usize)> = pts.iter().enumerate().map(|(i, &p)| (p, i)).collect();
    let t = CompressedTree::builder()
        .root_box(unit())
        .build(&e)
        .unwrap();
    t.validate().unwrap();
    t
}

/// Two points share a leaf exactly when they are equal, and every point is in a leaf.
fn leaves_part_points<const D: usize>(t: &CompressedTree<f64, usize, D>, pts: &[[f64; D]]) {
    let at: Vec<_> = pts
        .iter()
        .map(|p| t.locate(p).unwrap().inside().unwrap())
        .collect();
    for (i, a) in at.iter().enumerate() {
        assert!(a.leaf && a.cell.level() == DeepCell::<D>::MAX_LEVEL);
        for (j, b) in at.iter().enumerate() {
            assert_eq!(
                a.node == b.node,
                pts[i] == pts[j],
                "{:?} {:?}",
                pts[i],
                pts[j]
            );
        }
    }
}

#[test]
fn last_mantissa_bits_part_leaves() {
    let tiny = |k: i32| (-(k as f64)).exp2();
    let pairs = [
        (0.5, 0.5 + tiny(53)),
        (1.0 - tiny(53), 1.0 - tiny(52)),
        (0.25, 0.25f64.next_down()),
        (0.75, 0.75f64.next_up()),
        (tiny(11), tiny(11).next_up()),
        (tiny(60), tiny(61)),
    ];
    for (a, b) in pairs {
        assert_ne!(a, b);
        let pts = [[a, 0.3], [b, 0.3], [a, 0.3], [0.3, a], [0.3, b], [0.0, 0.0]];
        let t = build(&pts);
        leaves_part_points(&t, &pts);
        assert_eq!(t.leaf_count(), 5);
        assert!(t.node_count() <= 2 * t.leaf_count());
        let pts3 = [[0.5, a, 0.5], [0.5, b, 0.5], [0.5, b, 0.5], [b, b, b]];
        leaves_part_points(&build(&pts3), &pts3);
    }
    // 32 levels cannot tell these apart: one leaf of the point tree at its deepest level
    let pts = [[0.5, 0.3], [0.5 + tiny(53), 0.3], [0.0, 0.0]];
    let e: Vec<([f64; 2], usize)> = pts.iter().enumerate().map(|(i, &p)| (p, i)).collect();
    let plain = Quadtree::builder().bucket_size(1).build(&e).unwrap();
    assert_eq!(plain.depth(), Cell::<2>::MAX_LEVEL);
    // the caterpillar down to the last bit below 1: 53 legs, each its own leaf, 2 m nodes at most
    let legs: Vec<[f64; 2]> = (1..=53).map(|k| [1.0 - tiny(k), 0.5]).collect();
    let t = build(&legs);
    leaves_part_points(&t, &legs);
    assert!(t.depth() >= 52 && t.node_count() <= 2 * legs.len());
}

/// The compressed tree's cells against a point tree's with bucket size 1 over the same points:
/// a branching node above the point tree's deepest level is an internal node of it, a deeper
/// one lies in one of its deepest leaves, and the conversions keep every point in its cell.
fn agrees_with_point_tree<const D: usize>(t: &CompressedTree<f64, usize, D>) {
    let plain: PointTree<f64, usize, D> = t.to_point_tree(1, Cell::<D>::MAX_LEVEL).unwrap();
    plain.validate().unwrap();
    let tree = plain.tree();
    for (cell, leaf) in t.cells() {
        let c = cell.to_cell();
        let v = tree.locate_cell(&c);
        if cell.level() == 0 {
            continue; // the root, branching or not
        }
        if leaf {
            // the point tree's leaf holding the point
            assert!(tree.is_leaf(v) && tree.cell(v).contains(&c));
        } else if cell.level() < Cell::<D>::MAX_LEVEL {
            assert!(tree.cell(v) == c && !tree.is_leaf(v), "{cell:?}");
        } else {
            assert!(tree.cell(v) == c && tree.is_leaf(v), "{cell:?}");
        }
        assert_eq!(
            DeepCell::from(c).ancestor(c.level()),
            cell.ancestor(c.level())
        );
    }
    let back = CompressedTree::from(&plain);
    back.validate().unwrap();
    let cells = |t: &CompressedTree<f64, usize, D>| t.cells().collect::<Vec<_>>();
    assert_eq!(cells(&back), cells(t));
    let mut items: Vec<usize> = back.items().to_vec();
    items.sort_unstable();
    assert_eq!(items, (0..t.len()).collect::<Vec<_>>());
}

/// Coordinates in [0, 1] a few ulps from split lines and from `1 - 2^-k`: they differ in their
/// last mantissa bits, sit on split lines, and repeat. Values below 2^-11 are moved to 0, so
/// that distinct coordinates are at least 2^-64 apart (64-level cells of the unit square).
fn deep_coordinate() -> impl Strategy<Value = f64> {
    let base = prop_oneof![
        (0u32..=8).prop_map(|j| j as f64 / 8.0),
        (1i32..=53).prop_map(|k| 1.0 - (-k as f64).exp2()),
        (1i32..=11).prop_map(|k| (-k as f64).exp2()),
        (0u32..=16).prop_map(|j| 0.3 + j as f64 * (-50f64).exp2()),
    ];
    (base, -2i32..=2).prop_map(|(mut x, steps)| {
        for _ in 0..steps.unsigned_abs() {
            x = if steps > 0 {
                x.next_up()
            } else {
                x.next_down()
            };
        }
        let x = x.clamp(0.0, 1.0);
        if x < (-11f64).exp2() {
            0.0
        } else {
            x
        }
    })
}

proptest! {
    #![proptest_config(config(64, 711))]
    #[test]
    fn deep_points_get_their_own_leaves_and_the_point_trees_cells(
        pts in prop::collection::vec(proptest::array::uniform2(deep_coordinate()), 1..60),
        pts3 in prop::collection::vec(proptest::array::uniform3(deep_coordinate()), 1..30),
    ) {
        let t = build(&pts);
        leaves_part_points(&t, &pts);
        agrees_with_point_tree(&t);
        let t3 = build(&pts3);
        leaves_part_points(&t3, &pts3);
        agrees_with_point_tree(&t3);
        // queries against brute force
        let b = Aabb::new([0.25, 0.3], [1.0 - (-40f64).exp2(), 0.5f64.next_up()]).unwrap();
        let mut got: Vec<usize> = t.in_box(&b).unwrap().map(|(_, &i)| i).collect();
        got.sort_unstable();
        let want: Vec<usize> = (0..pts.len()).filter(|&i| b.contains(&pts[i])).collect();
        prop_assert_eq!(got, want);
        let q = pts[0];
        let best = pts.iter().map(|p| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2));
        let best = best.fold(f64::INFINITY, f64::min);
        prop_assert_eq!(t.nearest(&q).unwrap().unwrap().distance, best);
    }

    #[test]
    fn deep_updates_equal_a_fresh_build(
        start in prop::collection::vec(proptest::array::uniform2(deep_coordinate()), 0..30),
        ops in prop::collection::vec(
            (any::<bool>(), proptest::array::uniform2(deep_coordinate()), 0usize..40), 1..80),
        seed in any::<u64>(),
    ) {
        let fresh = |e: &[([f64; 2], usize)]| {
            CompressedTree::builder().root_box(unit()).build(e).unwrap()
        };
        let shape = |t: &SkipQuadtree<f64, usize, 2>| -> Vec<Vec<(DeepCell<2>, bool)>> {
            (0..t.level_count()).map(|i| t.level_cells(i).collect()).collect()
        };
        let mut stored: Vec<([f64; 2], usize)> =
            start.iter().enumerate().map(|(i, &p)| (p, i)).collect();
        let mut c = fresh(&stored);
        let mut s = SkipQuadtree::with_seed(fresh(&stored), seed);
        for (i, (insert, p, pick)) in ops.into_iter().enumerate() {
            if insert || stored.is_empty() {
                c.insert(p, 100 + i).unwrap();
                s.insert(p, 100 + i).unwrap();
                stored.push((p, 100 + i));
            } else {
                let (q, item) = stored.swap_remove(pick % stored.len());
                prop_assert!(c.remove(&q, &item));
                prop_assert!(s.remove(&q, &item));
            }
            c.validate().unwrap();
            s.validate().unwrap();
            let f = fresh(&stored);
            prop_assert_eq!(c.cells().collect::<Vec<_>>(), f.cells().collect::<Vec<_>>());
            prop_assert_eq!(shape(&s), shape(&SkipQuadtree::with_seed(f, seed)));
            let (at, walk) = (s.locate(&p).unwrap().inside().unwrap(), c.locate(&p).unwrap().inside().unwrap());
            prop_assert_eq!((at.cell, at.leaf), (walk.cell, walk.leaf));
        }
        let pts: Vec<[f64; 2]> = stored.iter().map(|&(p, _)| p).collect();
        if !pts.is_empty() {
            leaves_part_points(&c, &pts);
        }
    }
}
