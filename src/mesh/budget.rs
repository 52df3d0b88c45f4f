//! The mesher's work budget: a limit on the triangles of a mesh ([`MeshOptions::max_triangles`]),
//! checked before any work, while the quadtree is refined, after balance and before the
//! triangles are made, so that a board asking for more never takes more than a bounded amount of
//! time and memory. [`TooManyTriangles`] is the refusal.
//!
//! Every check is a true lower bound on the triangles of the finished mesh, so a board is
//! refused exactly when its mesh would have more triangles than the limit:
//!
//! - before refinement, from the board alone ([`lower_bound`]): with a maximum cell side h
//!   every leaf has side at most h, so the (U / h)^2 cells of side h are a lower bound on the
//!   leaves; every unit step of a component outline lies in a closed leaf meeting that edge,
//!   whose side is at most the near size n, and a closed square of side n holds at most
//!   4n^2 + 2n unit lattice steps, so p(S) / (4n^2 + 2n) is another (the counting argument of
//!   Theorem 14.5, turned around);
//! - during refinement: every leaf becomes at least two triangles, and each split adds three
//!   leaves; refinement stops as soon as twice the leaves exceed the limit (so it builds at
//!   most limit / 2 leaves);
//! - after 2:1 balance (which makes at most 8 splits per node of the refined tree, Theorem 14.4,
//!   so its work is bounded by the refined tree's): twice the leaves again;
//! - before triangulating: the exact number of triangles.
//!
//! [`MeshOptions::max_triangles`]: super::MeshOptions::max_triangles

use super::Board;
use core::fmt;

/// The peak bytes per triangle of a whole run of the mesher and the mesh's validation
/// (quadtree, balance, vertex numbering, outlines, regions, the [`Mesh`](super::Mesh) itself),
/// measured as the peak resident memory of `pcb_mesh --random 7,65536,640 --no-files` (15.9 M
/// triangles, 2.33 GB) and `--random 7,1048576,40` (16.7 M triangles, 2.48 GB), rounded up.
/// Used to state the memory a refused board would need.
pub const PEAK_BYTES_PER_TRIANGLE: u64 = 150;

/// The default of [`MeshOptions::max_triangles`](super::MeshOptions::max_triangles): 2 * 10^7
/// triangles, about 2.8 GiB at [`PEAK_BYTES_PER_TRIANGLE`], so that a run fits in a 4 GB
/// address space.
pub const DEFAULT_MAX_TRIANGLES: u64 = 20_000_000;

/// A board whose mesh would have more triangles than the limit of
/// [`MeshOptions::max_triangles`](super::MeshOptions::max_triangles).
///
/// ```
/// use orthtree::mesh::{Board, MeshOptions, OptionsError};
/// // U = 2^30 with cells of side at most 1: 2^61 triangles
/// let board = Board::new(1 << 30, vec![])?;
/// let err = MeshOptions::new().grid_unit(1).max_size(1).generate(&board).unwrap_err();
/// let OptionsError::TooManyTriangles(e) = err else { panic!("{err}") };
/// assert_eq!(e.at_least, 1 << 61);
/// assert_eq!(
///     e.to_string(),
///     "this board needs at least 2.3e18 triangles (about 3.2e11 GiB); the limit is 20000000 \
///      (max_triangles)"
/// );
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TooManyTriangles {
    /// A lower bound on the triangles of the mesh (the exact count when refused just before
    /// triangulating).
    pub at_least: u64,
    /// The limit.
    pub limit: u64,
}

impl fmt::Display for TooManyTriangles {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let gib = self.at_least as f64 * PEAK_BYTES_PER_TRIANGLE as f64 / (1u64 << 30) as f64;
        write!(
            f,
            "this board needs at least {} triangles (about {} GiB); the limit is {} \
             (max_triangles)",
            Short(self.at_least as f64),
            Short(gib),
            Short(self.limit as f64)
        )
    }
}

impl std::error::Error for TooManyTriangles {}

/// A number for a message: a whole number below 10^10 in full, another number below 10^5 with
/// one decimal, else two significant digits and an exponent (`2.1e9`, `3e7`).
struct Short(f64);

impl fmt::Display for Short {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        if x < 1e10 && x.fract() == 0.0 {
            return write!(f, "{x}");
        }
        if x < 1e5 {
            let rounded = (x * 10.0).round() / 10.0;
            return write!(f, "{rounded}");
        }
        let s = format!("{x:.1e}");
        // "3.0e7" -> "3e7"
        write!(f, "{}", s.replace(".0e", "e"))
    }
}

/// The limit as a check: `Err` when `at_least` triangles are more than it.
pub(super) fn check(at_least: u64, limit: u64) -> Result<(), TooManyTriangles> {
    if at_least > limit {
        Err(TooManyTriangles { at_least, limit })
    } else {
        Ok(())
    }
}

/// The largest power of two at most `x` (x >= 1).
fn floor_pow2(x: i64) -> i64 {
    1 << (63 - x.leading_zeros())
}

/// A lower bound on the triangles of the mesh of `board` (already in grid units) when no cell is
/// larger than `max` and no cell meeting a component edge is larger than `near` (both in grid
/// units, `i64::MAX` for no limit). See the module doc.
pub(super) fn lower_bound(board: &Board, near: i64, max: i64) -> u64 {
    let u = board.size();
    let h = floor_pow2(max.clamp(1, u));
    let per_side = (u / h) as u64;
    let by_max = per_side.saturating_mul(per_side);
    let n = floor_pow2(near.clamp(1, u)) as u64;
    let per_leaf = n.saturating_mul(n).saturating_mul(4).saturating_add(2 * n);
    let by_outline = board.perimeter_steps().div_ceil(per_leaf);
    by_max.max(by_outline).max(1).saturating_mul(2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Component;

    #[test]
    fn numbers_are_short() {
        let s = |x: f64| Short(x).to_string();
        assert_eq!(s(3e7), "30000000");
        assert_eq!(s(2.14e10), "2.1e10");
        assert_eq!(s(2.1e18), "2.1e18");
        assert_eq!(s(94.0), "94");
        assert_eq!(s(0.25), "0.3");
    }

    #[test]
    fn bounds_from_sizes_and_outlines() {
        let empty = Board::new(64, vec![]).unwrap();
        assert_eq!(lower_bound(&empty, i64::MAX, i64::MAX), 2);
        assert_eq!(lower_bound(&empty, 1, 8), 2 * 64);
        // a max size that is not a power of two acts as the next smaller one
        assert_eq!(lower_bound(&empty, 1, 12), 2 * 64);
        let square = Component::new(vec![[1, 1], [61, 1], [61, 61], [1, 61]]);
        let board = Board::new(64, vec![square]).unwrap();
        // 240 unit steps, at most 6 per unit cell
        assert_eq!(lower_bound(&board, 1, i64::MAX), 2 * 40);
        assert_eq!(lower_bound(&board, 2, i64::MAX), 2 * 12);
    }
}
