//! p4est's "timings" fractal refinement, shared by `cli/src/balance.rs`, `benches/balance.rs`
//! and the tests (the distributed workload, `orthtree::dist::workload`, has its own copy of the
//! rule behind the feature `mpi`; the MPI test `forest::fractal_parts_equal_the_fractal` checks
//! that the two give the same leaves).
//!
//! The uniform tree at level L - 4 is refined; then a cell of level l, L - 4 <= l < L, is refined
//! when its child id has an even number of set bits: 0 or 3 in 2D, 0, 3, 5 or 6 in 3D (p4est's
//! rule), and the same parity rule in higher dimensions. [`fractal_part`] gives the leaves below a
//! run of the uniform level's cells, so that each MPI rank refines only its own part.

#![allow(dead_code)]

use orthtree::{tree::NodeId, Cell, Tree};

/// Whether the fractal at `level` refines a cell of level `l` that is child `child` of its
/// parent.
fn refines(level: u8, l: u8, child: usize) -> bool {
    l < level.saturating_sub(4) || (l < level && child.count_ones() % 2 == 0)
}

/// The fractal tree of p4est's timings example at `level`.
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

/// The number of cells of the uniform level the fractal at `level` starts from.
pub fn uniform_cells<const D: usize>(level: u8) -> u64 {
    1u64 << (D * level.saturating_sub(4) as usize)
}

/// The leaves of the fractal at `level` below the uniform level's cells `first..end` (in Morton
/// order), in Morton order: the whole fractal's leaves for `0..uniform_cells(level)`.
pub fn fractal_part<const D: usize>(level: u8, first: u64, end: u64) -> Vec<Cell<D>> {
    let uniform = level.saturating_sub(4);
    let mut out = Vec::new();
    let mut stack = Vec::new();
    for i in first..end {
        let key = i << (D * (Cell::<D>::MAX_LEVEL - uniform) as usize);
        stack.push(Cell::<D>::from_aligned_key(key, uniform));
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
