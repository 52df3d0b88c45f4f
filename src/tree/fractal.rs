//! p4est's fractal refinement (its `timings` example; Burstedde, Wilcox and Ghattas 2011,
//! section 4), the workload of the balance benchmarks: the uniform tree at level L - 4 is
//! refined; then a cell of level l, L - 4 <= l < L, is refined when its child id has an even
//! number of set bits (0 or 3 in 2D; 0, 3, 5 or 6 in 3D; the same parity rule in higher
//! dimensions).
//!
//! The rule is written once (`refines`) and gives the whole tree ([`fractal`], as
//! `orthtree balance` and the benches refine it), the leaves below a run of the uniform level's
//! cells ([`fractal_part`], so that each rank of the forest over MPI ranks refines only its own
//! part, with an explicit stack at most 4 levels deep) and the number of leaves
//! ([`fractal_leaves`], in closed form, to size a run before it starts).

use super::{NodeId, Tree};
use crate::geom::Cell;

/// Whether the fractal at `level` refines a cell of level `l` that is child `child` of its
/// parent.
fn refines(level: u8, l: u8, child: usize) -> bool {
    l < level.saturating_sub(4) || (l < level && child.count_ones().is_multiple_of(2))
}

/// The fractal tree at `level`, refined depth first from the root.
///
/// # Panics
/// When `level` is deeper than [`Cell::MAX_LEVEL`] (the split of a cell at the deepest level
/// panics).
///
/// # Complexity
/// O(leaves); the stack holds at most `level` (2^D - 1) + 1 nodes.
///
/// ```
/// use orthtree::tree::fractal::{fractal, fractal_leaves};
/// let tree = fractal::<2>(6);
/// assert_eq!(tree.leaf_count() as f64, fractal_leaves(2, 6));
/// assert_eq!(tree.depth(), 6);
/// ```
pub fn fractal<const D: usize>(level: u8) -> Tree<D> {
    let mut tree = Tree::<D>::new();
    let mut stack = vec![NodeId::ROOT];
    while let Some(v) = stack.pop() {
        if refines(level, tree.level(v), tree.child_index(v)) {
            tree.split(v);
            stack.extend(tree.children(v));
        }
    }
    tree
}

/// The number of cells of the uniform level (L - 4, or the root) the fractal at `level`
/// starts from.
///
/// # Panics
/// When `D * (level - 4)` is 64 or more (past the deepest level of a `D`-tree).
///
/// ```
/// use orthtree::tree::fractal::uniform_cells;
/// assert_eq!(uniform_cells::<2>(6), 16);
/// assert_eq!(uniform_cells::<3>(3), 1);
/// ```
pub fn uniform_cells<const D: usize>(level: u8) -> u64 {
    1u64 << (D * level.saturating_sub(4) as usize)
}

/// The leaves of the fractal at `level` below the uniform level's cells `first..end` (in Morton
/// order), in Morton order: the whole fractal's leaves for `0..uniform_cells(level)`.
///
/// # Complexity
/// O(leaves) time; the stack holds at most 4 (2^D - 1) + 1 cells.
///
/// ```
/// use orthtree::tree::fractal::{fractal, fractal_part, uniform_cells};
/// let all = fractal_part::<2>(6, 0, uniform_cells::<2>(6));
/// assert!(all.iter().copied().eq(fractal::<2>(6).leaves().map(|(_, c)| c)));
/// // the runs of two ranks, put together, are the whole
/// let (a, b) = (fractal_part::<2>(6, 0, 7), fractal_part::<2>(6, 7, 16));
/// assert_eq!([a, b].concat(), all);
/// // at level 4 and below the one uniform cell is the root (its key the whole key's width)
/// let root = fractal_part::<2>(3, 0, uniform_cells::<2>(3));
/// assert!(root.iter().copied().eq(fractal::<2>(3).leaves().map(|(_, c)| c)));
/// ```
pub fn fractal_part<const D: usize>(level: u8, first: u64, end: u64) -> Vec<Cell<D>> {
    let uniform = level.saturating_sub(4);
    let mut out = Vec::new();
    let mut stack = Vec::new();
    for i in first..end {
        stack.push(Cell::<D>::from_morton(i, uniform));
        while let Some(c) = stack.pop() {
            if refines(level, c.level(), c.child_index()) {
                stack.extend((0..1 << D).rev().map(|k| c.child(k)));
            } else {
                out.push(c);
            }
        }
    }
    out
}

/// The number of leaves of the fractal at `level` in dimension `dim`, before balance (exact
/// while it fits an `f64`'s mantissa): the uniform level's cells, half of them refined for the
/// remaining levels, half of each cell's children again.
///
/// ```
/// use orthtree::tree::fractal::fractal_leaves;
/// assert_eq!(fractal_leaves(2, 12), 1_540_096.0);
/// assert_eq!(fractal_leaves(3, 8), 1_222_656.0);
/// ```
pub fn fractal_leaves(dim: usize, level: u8) -> f64 {
    let uniform = level.saturating_sub(4);
    let half = 2f64.powi(dim as i32 - 1);
    // leaves under an even cell with k levels to go: 1, then half * (1 + below(k - 1))
    let mut below = 1.0;
    for _ in 0..level - uniform {
        below = half * (1.0 + below);
    }
    if uniform == 0 {
        below
    } else {
        2f64.powi((dim * uniform as usize) as i32) / 2.0 * (1.0 + below)
    }
}
