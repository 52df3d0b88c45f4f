//! Inputs for the compressed quadtree, the skip quadtree and point location, shared by
//! `benches/compressed.rs`, `tests/skip.rs`, `tests/point_location.rs` and
//! `examples/point_location.rs`.

use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

/// `copies` caterpillars in the unit square, with its corners: the copies sit in a `2^p` by
/// `2^p` grid of squares of side `s = 2^-p` (the smallest such grid), and each holds the points
/// at `1 - 2^-k` of its square along x, halfway up, for `k = 1..=legs`: clusters nested one in
/// the other down to the `legs`-th bit below the square, so that leg `k` is a leaf about
/// `p + k` nodes deep in the compressed tree. `legs` is capped at `53 - p`, where the last leg
/// sits on the last bit of an `f64` below 1 (every point is exact: no rounding merges two legs).
///
/// Returns the points and the number of legs used.
#[allow(dead_code)]
pub fn caterpillars(copies: usize, legs: u32) -> (Vec<[f64; 2]>, u32) {
    let mut p = 0;
    while 1usize << (2 * p) < copies {
        p += 1;
    }
    let legs = legs.min(53 - p);
    let s = (-(p as f64)).exp2();
    let mut pts = vec![[0.0, 0.0], [1.0, 1.0]];
    for c in 0..copies {
        let (cx, cy) = ((c >> p) as f64 * s, (c & ((1 << p) - 1)) as f64 * s);
        for k in 1..=legs {
            pts.push([cx + s - s * (-(k as f64)).exp2(), cy + 0.5 * s]);
        }
    }
    (pts, legs)
}

/// The deepest quarter of every caterpillar's legs (legs `k > 3 legs / 4`): the lookups whose
/// walk from the root is the longest.
#[allow(dead_code)]
pub fn deep_legs(pts: &[[f64; 2]], legs: u32) -> Vec<[f64; 2]> {
    let legs = legs as usize;
    let first = 3 * legs / 4;
    pts[2..]
        .chunks(legs)
        .flat_map(|c| c[first..].iter().copied())
        .collect()
}

/// A triangulation: vertices, edges, and triangles counter-clockwise.
pub type Triangulation = (Vec<[f64; 2]>, Vec<[u32; 2]>, Vec<[u32; 3]>);

/// A `k` by `k` grid on `[0, k - 1]^2`, each vertex moved at most 0.2 per axis (so every square
/// stays convex), cut into triangles by a random diagonal per square.
#[allow(dead_code)]
pub fn triangulated_grid(k: usize, seed: u64) -> Triangulation {
    let mut rng = SmallRng::seed_from_u64(seed);
    let id = |i: usize, j: usize| (i * k + j) as u32;
    let mut v = Vec::new();
    for i in 0..k {
        for j in 0..k {
            v.push([
                j as f64 + rng.gen_range(-0.2..0.2),
                i as f64 + rng.gen_range(-0.2..0.2),
            ]);
        }
    }
    let (mut e, mut t) = (Vec::new(), Vec::new());
    for i in 0..k {
        for j in 0..k {
            if j + 1 < k {
                e.push([id(i, j), id(i, j + 1)]);
            }
            if i + 1 < k {
                e.push([id(i + 1, j), id(i, j)]);
            }
            if i + 1 < k && j + 1 < k {
                let (a, b, c, d) = (id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j));
                if rng.r#gen::<bool>() {
                    e.push([a, c]);
                    t.extend([[a, b, c], [a, c, d]]);
                } else {
                    e.push([d, b]);
                    t.extend([[a, b, d], [b, c, d]]);
                }
            }
        }
    }
    (v, e, t)
}
