//! Region trees in every dimension the crate supports, D = 1 to 8, on small random images (cube
//! and non-cube extents, blocky and noisy pixels): construction from a predicate, from booleans,
//! from a packed bitmap and from boxes, the Boolean operations (methods, `try_` forms and
//! operators), the complement, the pixel counts and the block iterator, each against a plain
//! array of pixels.
//!
//! One generic check, instantiated for each D by `every_dimension!`. The images stay small (at
//! most 1024 pixels) so the 8-D ones, whose internal nodes have 256 children, run in
//! milliseconds; they are deep enough for a node with all 256 children visited.

use orthtree::image::BoolOp;
use orthtree::RegionTree;
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

/// Every pixel of `extent` in row-major order (axis 0 fastest).
fn pixels<const D: usize>(extent: [u32; D]) -> Vec<[u32; D]> {
    let n: usize = extent.iter().map(|&e| e as usize).product();
    (0..n)
        .map(|mut i| {
            core::array::from_fn(|a| {
                let c = (i % extent[a] as usize) as u32;
                i /= extent[a] as usize;
                c
            })
        })
        .collect()
}

/// A random image on `extent`: black in a few random boxes, plus noise with probability `noise`.
fn sample_image<const D: usize>(rng: &mut SmallRng, extent: [u32; D], noise: f64) -> Vec<bool> {
    let boxes: Vec<([u32; D], [u32; D])> = (0..3)
        .map(|_| {
            let lo: [u32; D] = core::array::from_fn(|a| rng.gen_range(0..extent[a]));
            let hi = core::array::from_fn(|a| rng.gen_range(lo[a]..=extent[a]));
            (lo, hi)
        })
        .collect();
    pixels(extent)
        .iter()
        .map(|p| in_boxes(&boxes, p) || rng.gen_bool(noise))
        .collect()
}

/// Whether `p` lies in one of the half-open boxes.
fn in_boxes<const D: usize>(boxes: &[([u32; D], [u32; D])], p: &[u32; D]) -> bool {
    boxes
        .iter()
        .any(|(lo, hi)| (0..D).all(|a| lo[a] <= p[a] && p[a] < hi[a]))
}

/// The tree holds exactly the black pixels of `want`, is valid and canonical, and its counts and
/// blocks agree.
fn assert_image<const D: usize>(t: &RegionTree<D>, extent: [u32; D], want: &[bool], what: &str) {
    t.validate().unwrap();
    assert!(t.is_canonical(), "D = {D}: {what} is canonical");
    assert_eq!(t.extent(), extent);
    let all = pixels(extent);
    for (p, &black) in all.iter().zip(want) {
        assert_eq!(t.contains(*p), black, "D = {D}: {what} at {p:?}");
    }
    let count = want.iter().filter(|&&b| b).count() as u64;
    assert_eq!(t.len(), count, "D = {D}: {what} count");
    assert_eq!(t.is_empty(), count == 0);
    let mut from_blocks = 0u64;
    let mut leaves = 0;
    for b in t.blocks() {
        leaves += 1;
        if b.black {
            from_blocks += (0..D)
                .map(|a| u64::from(b.side.min(extent[a].saturating_sub(b.min[a]))))
                .product::<u64>();
        }
    }
    assert_eq!(leaves, t.leaf_count());
    assert_eq!(from_blocks, count, "D = {D}: {what} black blocks");
}

/// A Boolean operation on two pixels.
type PixelOp = fn(bool, bool) -> bool;

fn check_image<const D: usize>(rng: &mut SmallRng, extent: [u32; D]) {
    let noise = [0.0, 0.05, 0.5][rng.gen_range(0..3)];
    let (pa, pb) = (
        sample_image(rng, extent, noise),
        sample_image(rng, extent, noise),
    );
    let all = pixels(extent);
    let index = |p: [u32; D]| {
        let mut i = 0usize;
        for a in (0..D).rev() {
            i = i * extent[a] as usize + p[a] as usize;
        }
        i
    };
    let a = RegionTree::from_fn(extent, |p| pa[index(p)]).unwrap();
    let b = RegionTree::from_bools(extent, &pb).unwrap();
    assert_image(&a, extent, &pa, "from_fn");
    assert_image(&b, extent, &pb, "from_bools");
    let mut words = vec![0u64; pa.len().div_ceil(64)];
    for (i, _) in pa.iter().enumerate().filter(|&(_, &x)| x) {
        words[i / 64] |= 1 << (i % 64);
    }
    assert_eq!(RegionTree::from_packed(extent, &words).unwrap(), a);
    assert_eq!(a.to_packed(), words);
    assert_eq!(
        RegionTree::from_nodes(extent, a.nodes().to_vec()).unwrap(),
        a
    );

    let boxes: Vec<([u32; D], [u32; D])> = (0..3)
        .map(|_| {
            let lo: [u32; D] = core::array::from_fn(|a| rng.gen_range(0..extent[a]));
            let hi = core::array::from_fn(|a| rng.gen_range(lo[a]..=extent[a] + 1));
            (lo, hi)
        })
        .collect();
    let want: Vec<bool> = all.iter().map(|p| in_boxes(&boxes, p)).collect();
    assert_image(
        &RegionTree::from_boxes(extent, &boxes).unwrap(),
        extent,
        &want,
        "from_boxes",
    );

    let ops: [(BoolOp, PixelOp); 4] = [
        (BoolOp::And, |x, y| x && y),
        (BoolOp::Or, |x, y| x || y),
        (BoolOp::Xor, |x, y| x != y),
        (BoolOp::Sub, |x, y| x && !y),
    ];
    for (op, f) in ops {
        let want: Vec<bool> = pa.iter().zip(&pb).map(|(&x, &y)| f(x, y)).collect();
        let got = a.try_combine(&b, op).unwrap();
        assert_image(&got, extent, &want, &format!("{op:?}"));
        assert_eq!(a.combine_len(&b, op), got.len(), "D = {D}: {op:?} count");
        let by_name = match op {
            BoolOp::And => (a.intersection(&b), &a & &b, a.intersection_len(&b)),
            BoolOp::Or => (a.union(&b), &a | &b, a.union_len(&b)),
            BoolOp::Xor => (
                a.symmetric_difference(&b),
                &a ^ &b,
                a.symmetric_difference_len(&b),
            ),
            BoolOp::Sub => (a.difference(&b), &a - &b, a.difference_len(&b)),
        };
        assert_eq!(
            (by_name.0, by_name.1, by_name.2),
            (got.clone(), got.clone(), got.len())
        );
        if op == BoolOp::And {
            assert_eq!(a.is_disjoint(&b), got.is_empty());
        }
    }
    let flipped: Vec<bool> = pa.iter().map(|&x| !x).collect();
    assert_image(&a.complement(), extent, &flipped, "complement");
    assert_eq!(!&a, a.complement());
    assert_image(
        &RegionTree::empty(extent).unwrap(),
        extent,
        &vec![false; pa.len()],
        "empty",
    );
    assert_image(
        &RegionTree::full(extent).unwrap(),
        extent,
        &vec![true; pa.len()],
        "full",
    );
}

/// Cube extents of side `side` and random non-cube ones up to it.
fn run<const D: usize>(seed: u64, side: u32) {
    let mut r = SmallRng::seed_from_u64(seed);
    for round in 0..6 {
        let extent: [u32; D] = if round < 2 {
            [side; D]
        } else {
            core::array::from_fn(|_| r.gen_range(1..=side))
        };
        check_image(&mut r, extent);
    }
}

macro_rules! every_dimension {
    ($($name:ident: $d:literal, $side:literal;)*) => {
        $(
            #[test]
            fn $name() {
                run::<$d>(3000 + $d, $side);
            }
        )*
    };
}

every_dimension! {
    regions_in_1d: 1, 64;
    regions_in_2d: 2, 16;
    regions_in_3d: 3, 8;
    regions_in_4d: 4, 4;
    regions_in_5d: 5, 4;
    regions_in_6d: 6, 2;
    regions_in_7d: 7, 2;
    regions_in_8d: 8, 2;
}
