//! p4est's "timings" fractal refinement, shared by `examples/balance_fractal.rs` and
//! `benches/balance.rs`.
//!
//! The uniform tree at level L - 4 is refined; then a cell of level l, L - 4 <= l < L, is refined
//! when its child id has an even number of set bits: 0 or 3 in 2D, 0, 3, 5 or 6 in 3D (p4est's
//! rule), and the same parity rule in higher dimensions.

use orthtree::{tree::NodeId, Tree};

/// The fractal tree of p4est's timings example at `level`.
pub fn fractal<const D: usize>(level: u8) -> Tree<D> {
    let uniform = level.saturating_sub(4);
    let mut tree = Tree::<D>::new();
    let mut stack = vec![NodeId::ROOT];
    while let Some(v) = stack.pop() {
        let l = tree.level(v);
        let even = tree.child_index(v).count_ones() % 2 == 0;
        if l < uniform || (l < level && even) {
            tree.split(v);
            stack.extend(tree.children(v));
        }
    }
    tree
}
