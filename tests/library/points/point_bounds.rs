//! The chapter's size and depth bounds for point quadtrees, generalised to D dimensions and
//! buckets: Lemma 14.1 (depth against the closest pair) and Theorem 14.2 (nodes against depth and
//! number of points), on random and adversarial point sets.

use crate::common;

use common::points::check_points;
use common::{closest_pair, dedup_points, rng};
use orthtree::{points::PointTreeBuilder, Aabb, Cell};
use rand::rngs::SmallRng;
use rand::Rng;

/// Lemma 14.1 generalised: with bucket size 1 and distinct points, an internal node at depth i
/// holds two points at distance >= c in a closed cube of diagonal s * sqrt(D) / 2^i, so
/// i <= log2(s / c) + log2(sqrt(D)); the depth is one more than the deepest internal node:
/// depth <= log2(s / c) + log2(sqrt(D)) + 1 (log(s/c) + 3/2 in the plane). The tree also stops
/// at `Cell::MAX_LEVEL`, which only lowers the depth.
fn check_lemma_14_1<const D: usize>(pts: Vec<[f64; D]>, root: Option<Aabb<f64, D>>) {
    let pts = dedup_points(pts);
    let e: Vec<([f64; D], usize)> = pts.iter().enumerate().map(|(i, p)| (*p, i)).collect();
    let mut b = PointTreeBuilder::<f64, D>::new().bucket_size(1);
    if let Some(r) = root {
        b = b.root_box(r);
    }
    let t = b.build(&e).unwrap();
    check_points(&t, &e, None);
    assert!(t.depth() <= Cell::<D>::MAX_LEVEL);
    if pts.len() < 2 {
        assert_eq!(t.depth(), 0);
        return;
    }
    let rb = t.geometry().root_box();
    let s = (0..D).map(|a| rb.max[a] - rb.min[a]).fold(0.0, f64::max);
    let c = closest_pair(&pts);
    assert!(c > 0.0);
    let bound = (s / c).log2() + 0.5 * (D as f64).log2() + 1.0;
    assert!(
        f64::from(t.depth()) <= bound + 1e-9,
        "depth {} > {bound} (s = {s}, c = {c}, n = {})",
        t.depth(),
        pts.len()
    );
}

fn random_point<const D: usize>(r: &mut SmallRng) -> [f64; D] {
    core::array::from_fn(|_| r.r#gen::<f64>())
}

/// Adversarial and random sets in [0, 1]^D.
fn point_sets<const D: usize>(seed: u64) -> Vec<Vec<[f64; D]>> {
    let mut r = rng(seed);
    let mut sets = Vec::new();
    // uniform
    for n in [2usize, 3, 50, 400] {
        sets.push((0..n).map(|_| random_point::<D>(&mut r)).collect());
    }
    // clusters of very different spreads
    for spread in [1e-3, 1e-6, 1e-9] {
        let centres: Vec<[f64; D]> = (0..4).map(|_| random_point::<D>(&mut r)).collect();
        let mut v = Vec::new();
        for c in &centres {
            for _ in 0..40 {
                v.push(c.map(|x| (x + spread * r.gen_range(-1.0..1.0)).clamp(0.0, 1.0)));
            }
        }
        sets.push(v);
    }
    // two very close points among random ones, and alone
    for delta in [1e-4, 1e-9, 1e-13, 2f64.powi(-30)] {
        let mut v: Vec<[f64; D]> = (0..30).map(|_| random_point::<D>(&mut r)).collect();
        let p = [0.5; D]; // on every first-level split line
        let mut q = p;
        q[0] += delta;
        v.push(p);
        v.push(q);
        sets.push(v);
        sets.push(vec![p, q]);
    }
    // along the diagonal, evenly and geometrically toward the lower corner
    sets.push((0..=64).map(|i| [i as f64 / 64.0; D]).collect());
    sets.push((0..=100).map(|i| [i as f64 / 100.0; D]).collect());
    sets.push((0..31).map(|k| [2f64.powi(-k); D]).collect());
    // points differing by tiny amounts: one ulp, a few ulps
    for ulps in [1u32, 3, 1000] {
        let mut v = Vec::new();
        for _ in 0..10 {
            let p = random_point::<D>(&mut r);
            let mut q = p;
            for _ in 0..ulps {
                q[D - 1] = q[D - 1].next_up();
            }
            v.push(p);
            v.push(q);
        }
        sets.push(v);
    }
    sets
}

fn lemma_14_1<const D: usize>(seed: u64) {
    let unit = Aabb::new([0.0; D], [1.0; D]).unwrap();
    for set in point_sets::<D>(seed) {
        check_lemma_14_1(set.clone(), Some(unit));
        check_lemma_14_1(set, None);
    }
}

#[test]
fn lemma_14_1_depth_bound_2d() {
    lemma_14_1::<2>(71);
}

#[test]
fn lemma_14_1_depth_bound_3d() {
    lemma_14_1::<3>(72);
}

/// The lemma is close to tight: two points at distance c straddling no split line until the
/// deepest possible level reach the bound's order of magnitude.
#[test]
fn lemma_14_1_is_nearly_reached() {
    // p = (1/2, 1/2) on the first split lines, q just right of it: they part at the level whose
    // split line lies between them, i.e. when the cell side is below c.
    for k in 3..30 {
        let c = 2f64.powi(-k);
        let pts = [([0.5, 0.5], 0), ([0.5 + c, 0.5], 1)];
        let t = PointTreeBuilder::<f64, 2>::new()
            .bucket_size(1)
            .root_box(Aabb::new([0.0; 2], [1.0; 2]).unwrap())
            .build(&pts)
            .unwrap();
        // (1/2, 1/2) is the upper corner of its SW quadrant, q is in the SE quadrant: parted at
        // level 1, so depth 1; shift both by c/2 instead and they share cells down to level k.
        assert_eq!(t.depth(), 1);
        let pts = [([0.5 + c / 4.0, 0.5], 0), ([0.5 + c, 0.5], 1)];
        let t = PointTreeBuilder::<f64, 2>::new()
            .bucket_size(1)
            .root_box(Aabb::new([0.0; 2], [1.0; 2]).unwrap())
            .build(&pts)
            .unwrap();
        // the cell (1/2, 1/2 + 2^-k] holds both; its half (1/2, 1/2 + c/2] only the first
        assert_eq!(i32::from(t.depth()), k + 1);
        let bound = (1.0 / (0.75 * c)).log2() + 1.5;
        assert!(f64::from(t.depth()) <= bound);
    }
}

/// Theorem 14.2 with buckets: a node splits only when its closed cell holds more than b points,
/// and the cells of one level are disjoint, so each level has at most floor(n / (b + 1)) internal
/// nodes; with `depth` levels of internal nodes and 2^D children per internal node,
/// nodes <= 1 + 2^D * depth * floor(n / (b + 1)). Holds with duplicates (which stop at the
/// maximum depth).
fn check_theorem_14_2<const D: usize>(pts: &[[f64; D]], bucket: usize, max_depth: Option<u8>) {
    let e: Vec<([f64; D], usize)> = pts.iter().enumerate().map(|(i, p)| (*p, i)).collect();
    let mut b = PointTreeBuilder::<f64, D>::new().bucket_size(bucket);
    if let Some(d) = max_depth {
        b = b.max_depth(d);
    }
    let t = b.build(&e).unwrap();
    let n = pts.len();
    let per_level = n / (bucket + 1);
    let mut internal = vec![0usize; usize::from(t.depth()) + 1];
    for (id, cell) in t.tree().pre_order() {
        if !t.tree().is_leaf(id) {
            internal[usize::from(cell.level())] += 1;
            assert!(t.node_points(id).len() > bucket);
        }
    }
    for (level, &count) in internal.iter().enumerate() {
        assert!(
            count <= per_level,
            "level {level}: {count} internal nodes > {per_level}"
        );
    }
    let bound = 1 + (1usize << D) * usize::from(t.depth()) * per_level;
    assert!(
        t.node_count() <= bound,
        "{} nodes > {bound} (n = {n}, b = {bucket}, depth {})",
        t.node_count(),
        t.depth()
    );
    assert_eq!(
        t.node_count(),
        1 + (1usize << D) * internal.iter().sum::<usize>()
    );
}

fn theorem_14_2<const D: usize>(seed: u64) {
    let mut sets = point_sets::<D>(seed);
    let mut r = rng(seed + 1);
    // with duplicates
    let mut dup: Vec<[f64; D]> = (0..100).map(|_| random_point::<D>(&mut r)).collect();
    for i in 0..200 {
        dup.push(dup[i % 7]);
    }
    sets.push(dup);
    sets.push(vec![[0.25; D]; 50]);
    for set in &sets {
        for bucket in [1usize, 2, 4, 8, 16] {
            check_theorem_14_2(set, bucket, None);
            check_theorem_14_2(set, bucket, Some(6));
        }
    }
}

#[test]
fn theorem_14_2_size_bound_2d() {
    theorem_14_2::<2>(81);
}

#[test]
fn theorem_14_2_size_bound_3d() {
    theorem_14_2::<3>(82);
}

#[test]
fn theorem_14_2_size_bound_1d() {
    theorem_14_2::<1>(83);
}
