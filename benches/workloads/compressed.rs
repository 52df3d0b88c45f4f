//! Inputs for the compressed quadtree, the skip quadtree and point location, shared by
//! `benches/compressed.rs`, `tests/skip.rs`, `tests/point_location.rs` and
//! `examples/point_location.rs`.

use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

/// `copies` caterpillars in the unit square (with its corners): copy `c` sits in its own square
/// of side `s` and holds the points at `1 - 2^-k` of it along x for every `k` whose offset is
/// still a distinct finest cell (2D, 32 levels): nested clusters down to the last bits of the
/// cells, so the compressed quadtree is as deep as it can be.
#[allow(dead_code)]
pub fn caterpillars(copies: usize) -> Vec<[f64; 2]> {
    let side = (copies as f64).sqrt().ceil() as usize;
    let s = 1.0 / side as f64;
    let levels = 32 - (side as f64).log2().ceil() as i32 - 1;
    let mut pts = vec![[0.0, 0.0], [1.0, 1.0]];
    for c in 0..copies {
        let (cx, cy) = ((c % side) as f64 * s, (c / side) as f64 * s);
        for k in 1..=levels {
            pts.push([cx + s * (1.0 - (-(k as f64)).exp2()), cy + 0.5 * s]);
        }
    }
    pts
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
                if rng.gen::<bool>() {
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
