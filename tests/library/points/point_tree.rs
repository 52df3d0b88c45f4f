//! `PointTree` property tests in 1, 2 and 3 dimensions over f64, f32 and i32 coordinates: random
//! points, duplicates and points exactly on split lines (dyadic coordinates in a dyadic root box),
//! checked against the chapter's recursive definition and every structural property, before and
//! after balance with every option.

use crate::common;

use common::points::*;
use orthtree::prelude::*;
use orthtree::{
    points::PointTreeBuilder, points::DEFAULT_BUCKET_SIZE, Aabb, Octree, PointTree, Quadtree,
    Scalar,
};
use proptest::collection::vec;
use proptest::prelude::*;
use proptest::sample::Index;
use std::fmt::Debug;

/// k / 2^j for j <= 7: lies on a split line of every level >= j of the root box [0, 1].
fn dyadic() -> impl Strategy<Value = f64> + Clone {
    (0u32..=7)
        .prop_flat_map(|j| (0u64..=(1u64 << j)).prop_map(move |k| k as f64 / (1u64 << j) as f64))
}

/// Coordinates in [0, 1]: on split lines, anywhere, or one ulp off a split line.
fn unit_f64() -> impl Strategy<Value = f64> + Clone {
    prop_oneof![
        3 => dyadic(),
        2 => 0.0..=1.0f64,
        1 => dyadic().prop_map(|x| x.next_up().min(1.0)),
        1 => dyadic().prop_map(|x| x.next_down().max(0.0)),
    ]
}

/// The same in f32 (every dyadic above is exact in f32).
fn unit_f32() -> impl Strategy<Value = f32> + Clone {
    prop_oneof![
        3 => dyadic().prop_map(|x| x as f32),
        2 => 0.0..=1.0f32,
        1 => dyadic().prop_map(|x| (x as f32).next_up().min(1.0)),
    ]
}

/// Up to `max` points from `coord`, then up to `max / 3` exact copies of random earlier points;
/// items are the input positions.
fn entries<T: Scalar, const D: usize>(
    coord: impl Strategy<Value = T> + Clone,
    max: usize,
) -> impl Strategy<Value = Vec<([T; D], usize)>> {
    (vec(vec(coord, D), 0..max), vec(any::<Index>(), 0..max / 3)).prop_map(|(pts, dups)| {
        let mut pts: Vec<[T; D]> = pts
            .into_iter()
            .map(|v| core::array::from_fn(|i| v[i]))
            .collect();
        if !pts.is_empty() {
            for d in dups {
                let copy = pts[d.index(pts.len())];
                pts.push(copy);
            }
        }
        pts.into_iter().enumerate().map(|(i, p)| (p, i)).collect()
    })
}

fn bucket() -> impl Strategy<Value = usize> {
    prop::sample::select(vec![1usize, 1, 2, 3, 5, 16])
}

fn max_depth() -> impl Strategy<Value = Option<u8>> {
    prop::option::weighted(0.3, 1u8..=10)
}

/// Builds with the given settings (both from a slice and from a vector) and checks everything.
fn run<S: Scalar, const D: usize>(
    entries: &[([S; D], usize)],
    bucket: usize,
    max_depth: Option<u8>,
    root: Option<Aabb<S, D>>,
) where
    [S; D]: Debug,
{
    let mut b = PointTreeBuilder::<S, D>::new().bucket_size(bucket);
    if let Some(d) = max_depth {
        b = b.max_depth(d);
    }
    if let Some(r) = root {
        b = b.root_box(r);
    }
    let t = b.build(entries).unwrap();
    assert_eq!(t.bucket_size(), bucket);
    if let Some(d) = max_depth {
        assert_eq!(t.max_depth(), d);
    }
    if let Some(r) = root {
        assert_eq!(*t.domain(), r.to_f64());
    }
    check_all(&t, entries);
    let t2 = b.build_from_vec(entries.to_vec()).unwrap();
    assert_eq!(t2.tree(), t.tree());
    assert_eq!(leaves_with_items(&t2), leaves_with_items(&t));
}

fn unit_box<S: Scalar, const D: usize>(given: bool) -> Option<Aabb<S, D>> {
    given.then(|| Aabb::new([S::zero(); D], [S::one(); D]).unwrap())
}

proptest! {
    #![proptest_config(config(160, 0x0d7e_0001))]

    #[test]
    fn f64_1d(e in entries::<f64, 1>(unit_f64(), 120), b in bucket(), d in max_depth(), given in any::<bool>()) {
        run(&e, b, d, unit_box(given));
    }

    #[test]
    fn f64_2d(e in entries::<f64, 2>(unit_f64(), 150), b in bucket(), d in max_depth(), given in any::<bool>()) {
        run(&e, b, d, unit_box(given));
    }

    #[test]
    fn f64_3d(e in entries::<f64, 3>(unit_f64(), 120), b in bucket(), d in max_depth(), given in any::<bool>()) {
        run(&e, b, d, unit_box(given));
    }

    /// A root box that is not a cube: the tree subdivides the cube [0, 2]^2, points lie in
    /// [0, 2] x [0, 1], many on split lines.
    #[test]
    fn f64_2d_flat_box(e in entries::<f64, 2>(unit_f64(), 150), b in bucket(), d in max_depth()) {
        let e: Vec<([f64; 2], usize)> = e.into_iter().map(|([x, y], i)| ([2.0 * x, y], i)).collect();
        run(&e, b, d, Some(Aabb::new([0.0, 0.0], [2.0, 1.0]).unwrap()));
    }

    /// Arbitrary magnitudes and signs, root cube computed from the points.
    #[test]
    fn f64_2d_wide(e in entries::<f64, 2>(prop_oneof![-1e6..1e6f64, -1.0..1.0f64, Just(0.0), Just(-3.5)], 150), b in bucket(), d in max_depth()) {
        run(&e, b, d, None);
    }

    #[test]
    fn f32_2d(e in entries::<f32, 2>(unit_f32(), 150), b in bucket(), d in max_depth(), given in any::<bool>()) {
        run(&e, b, d, unit_box(given));
    }

    #[test]
    fn f32_3d(e in entries::<f32, 3>(unit_f32(), 120), b in bucket(), d in max_depth(), given in any::<bool>()) {
        run(&e, b, d, unit_box(given));
    }

    /// Integers in [-64, 64] in the root box [-64, 64]^2: every integer is on a split line of some
    /// level (the cube's side is 128).
    #[test]
    fn i32_2d(e in entries::<i32, 2>(-64i32..=64, 150), b in bucket(), d in max_depth(), given in any::<bool>()) {
        let root = given.then(|| Aabb::new([-64; 2], [64; 2]).unwrap());
        run(&e, b, d, root);
    }

    /// The full i32 range, root cube computed.
    #[test]
    fn i32_3d(e in entries::<i32, 3>(prop_oneof![any::<i32>(), -8i32..=8, Just(i32::MIN), Just(i32::MAX)], 100), b in bucket(), d in max_depth()) {
        run(&e, b, d, None);
    }
}

/// Bucket size 1 and distinct points: exactly the chapter's quadtree, each leaf with at most one
/// point (no point pair is closer than the deepest level can separate).
#[test]
fn bucket_one_distinct_points_is_the_chapters_quadtree() {
    use rand::Rng;
    let mut r = common::rng(61);
    for n in [0usize, 1, 2, 3, 10, 100, 500] {
        let mut pts: Vec<[f64; 2]> = (0..n)
            .map(|_| {
                if r.gen_bool(0.5) {
                    [
                        r.gen_range(0..=64) as f64 / 64.0,
                        r.gen_range(0..=64) as f64 / 64.0,
                    ]
                } else {
                    [r.r#gen::<f64>(), r.r#gen::<f64>()]
                }
            })
            .collect();
        pts = common::dedup_points(pts);
        let e: Vec<([f64; 2], usize)> = pts.iter().enumerate().map(|(i, p)| (*p, i)).collect();
        let t = Quadtree::builder()
            .bucket_size(1)
            .root_box(Aabb::new([0.0; 2], [1.0; 2]).unwrap())
            .build(&e)
            .unwrap();
        check_all(&t, &e);
        assert!(t.leaves().all(|l| l.points.len() <= 1));
        // card(P) <= 1 at leaves; card(P) >= 2 at internal nodes
        for (id, _) in t.tree().pre_order() {
            assert_eq!(t.tree().is_leaf(id), t.node_points(id).len() <= 1);
        }
    }
}

/// The chapter's example conventions in the plane: SW = 0, SE = 1, NW = 2, NE = 3; a point on
/// the vertical split line belongs to the western quadrants, on the horizontal one to the
/// southern ones.
#[test]
fn chapter_quadrant_convention() {
    let root = Aabb::new([0.0; 2], [1.0; 2]).unwrap();
    let pts = [
        ([0.5, 0.5], 0),   // on both lines: SW
        ([0.75, 0.5], 1),  // east of x_mid, on y_mid: SE
        ([0.5, 0.75], 2),  // on x_mid, north: NW
        ([0.75, 0.75], 3), // NE
        ([0.0, 0.0], 4),   // root corner: SW
        ([1.0, 1.0], 5),   // root corner: NE
    ];
    let t = Quadtree::builder()
        .bucket_size(2)
        .root_box(root)
        .build(&pts)
        .unwrap();
    let quadrant = |item: usize| {
        let leaf = t.locate(&pts[item].0).unwrap().inside().unwrap();
        t.tree().cell(leaf).ancestor(1).child_index()
    };
    assert_eq!(quadrant(0), 0);
    assert_eq!(quadrant(1), 1);
    assert_eq!(quadrant(2), 2);
    assert_eq!(quadrant(3), 3);
    assert_eq!(quadrant(4), 0);
    assert_eq!(quadrant(5), 3);
    let e: Vec<([f64; 2], usize)> = pts.to_vec();
    check_all(&t, &e);
}

/// `PointTree::new` is the builder with its defaults.
#[test]
fn new_uses_the_defaults() {
    use rand::Rng;
    let mut r = common::rng(62);
    let e: Vec<([f64; 3], usize)> = (0..2000)
        .map(|i| {
            (
                [r.r#gen::<f64>(), r.r#gen::<f64>(), r.r#gen::<f64>() * 0.01],
                i,
            )
        })
        .collect();
    let t = Octree::new(&e).unwrap();
    assert_eq!(t.bucket_size(), DEFAULT_BUCKET_SIZE);
    let b = PointTreeBuilder::new().build(&e).unwrap();
    assert_eq!(t.tree(), b.tree());
    check_all(&t, &e);
    let t2: PointTree<f64, usize, 3> = PointTree::new(&e).unwrap();
    assert_eq!(t2.tree(), t.tree());
}

/// A bulk build keeps no spare capacity: beyond the points and items, 13 bytes per node (its run,
/// first child and level) plus 4 per child block, so the bytes per point are a known number.
#[test]
fn a_build_keeps_no_spare_capacity() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand::rngs::SmallRng::seed_from_u64(9);
    let entries: Vec<([f64; 2], u64)> = (0..100_000)
        .map(|i| ([rng.r#gen(), rng.r#gen()], i))
        .collect();
    let t = Quadtree::new(&entries).unwrap();
    let payload = entries.len() * core::mem::size_of::<([f64; 2], u64)>();
    let nodes = t.node_count();
    let topology = nodes * 13 + (nodes - 1) / 4 * 4;
    let slack = 4096; // the tree's small per-level tables
    assert!(
        t.heap_bytes() <= payload + topology + slack,
        "{} bytes for {} nodes",
        t.heap_bytes(),
        nodes
    );
}
