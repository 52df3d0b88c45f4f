//! The node budget of the shape constructors ([`RegionTree::from_region`] and the shapes built
//! on it): a limit on the cells a construction classifies, checked against an estimate before
//! building (so that a ball's boundary at depth 30 is refused at once) and counted while
//! building (so that no construction passes the limit, whatever the estimate said).
//!
//! The estimates are lower bounds, or close to them, of the cells classified: a tree is only
//! refused before building when it would pass the limit anyway.

use super::{ImageError, RegionTree};

/// The default limit on the cells a shape constructor classifies: 2^28, about 268 million.
/// The nodes written are at most 2^D times the cells classified, one byte each; a tree at the
/// limit takes some seconds and a few hundred MiB. The `_with_limit` constructors take another.
pub const DEFAULT_MAX_NODES: u64 = 1 << 28;

/// The error for a construction that classified more than `limit` cells.
pub(super) fn counted(limit: u64) -> ImageError {
    ImageError::TooManyNodes {
        nodes: limit.saturating_add(1),
        limit,
        estimated: false,
    }
}

/// Refuses an estimate of `nodes` cells above `limit`.
pub(super) fn check_estimate(nodes: f64, limit: u64) -> Result<(), ImageError> {
    if nodes > limit as f64 {
        return Err(ImageError::TooManyNodes {
            nodes: nodes.min(u64::MAX as f64) as u64,
            limit,
            estimated: true,
        });
    }
    Ok(())
}

/// Γ(D / 2) for D = 1 to 8 (the surface of the unit sphere is 2 π^(D/2) / Γ(D/2)).
fn half_gamma(d: usize) -> f64 {
    let root_pi = core::f64::consts::PI.sqrt();
    match d {
        1 => root_pi,
        2 => 1.0,
        3 => root_pi / 2.0,
        4 => 1.0,
        5 => 3.0 * root_pi / 4.0,
        6 => 2.0,
        7 => 15.0 * root_pi / 8.0,
        _ => 6.0,
    }
}

/// The cells classified in building the ball of (scaled) `centre` and squared radius `r2`
/// (lengths multiplied by `scale`) on `extent`, estimated from the sphere's surface within the
/// extent: the boundary pixels, at least the surface area over 2 sqrt(D). 0 when the sphere
/// misses the extent or holds all of it.
pub(super) fn ball_estimate<const D: usize>(
    extent: [u32; D],
    centre: [f64; D],
    r2: f64,
    scale: f64,
) -> f64 {
    let (mut near, mut far) = (0.0, 0.0);
    for a in 0..D {
        let (lo, hi) = (0.0, f64::from(extent[a]) * scale);
        let n = (lo - centre[a]).max(centre[a] - hi).max(0.0);
        let f = (centre[a] - lo).abs().max((hi - centre[a]).abs());
        near += n * n;
        far += f * f;
    }
    if near > r2 || far <= r2 {
        return 0.0;
    }
    // In pixels again.
    let r = r2.sqrt() / scale;
    let d = D as f64;
    let sphere = 2.0 * core::f64::consts::PI.powf(d / 2.0) / half_gamma(D) * r.powi(D as i32 - 1);
    // The part of the sphere within the extent is part of the surface of a convex body in the
    // extent's box, so at most the box's surface.
    let faces: f64 = (0..D)
        .map(|a| {
            (0..D)
                .filter(|&b| b != a)
                .map(|b| f64::from(extent[b]))
                .product::<f64>()
        })
        .sum();
    sphere.min(2.0 * faces) / (2.0 * d.sqrt())
}

/// The cells classified in building one box `lo .. hi` alone on `extent` (depth `depth`), a
/// lower bound: every cell that a face of the box (clipped to the extent) cuts holds pixels of
/// the box and pixels outside it (or padding), so it is classified, as is its parent. A face at
/// `c` cuts one cell across of side 2^j for every j above the number of trailing zeros of `c`;
/// the largest count over the faces is returned.
pub(super) fn box_estimate<const D: usize>(
    extent: [u32; D],
    depth: u8,
    (lo, hi): ([u32; D], [u32; D]),
) -> f64 {
    let lo: [u32; D] = core::array::from_fn(|a| lo[a].min(extent[a]));
    let hi: [u32; D] = core::array::from_fn(|a| hi[a].min(extent[a]));
    if (0..D).any(|a| lo[a] >= hi[a]) {
        return 0.0;
    }
    // Cells of side 2^j that the slab lo[b] .. hi[b] meets on axis b.
    let across = |b: usize, j: u32| f64::from(((hi[b] - 1) >> j) - (lo[b] >> j) + 1);
    let mut best: f64 = 0.0;
    for a in 0..D {
        for c in [lo[a], hi[a]] {
            let from = c.trailing_zeros().min(32) + 1;
            let cut: f64 = (from..=u32::from(depth))
                .map(|j| {
                    (0..D)
                        .filter(|&b| b != a)
                        .map(|b| across(b, j))
                        .product::<f64>()
                })
                .sum();
            best = best.max(cut);
        }
    }
    best
}

impl<const D: usize> RegionTree<D> {
    /// The default limit on the cells the shape constructors classify:
    /// [`DEFAULT_MAX_NODES`].
    pub const DEFAULT_MAX_NODES: u64 = DEFAULT_MAX_NODES;
}
