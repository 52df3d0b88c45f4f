//! Inputs as deep as the cells allow, shared by `benches/compressed.rs` and `tests/skip.rs`.

/// `copies` caterpillars in the unit square (with its corners): copy `c` sits in its own square
/// of side `s` and holds the points at `1 - 2^-k` of it along x for every `k` whose offset is
/// still a distinct finest cell (2D, 32 levels): nested clusters down to the last bits of the
/// cells, so the compressed quadtree is as deep as it can be.
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
