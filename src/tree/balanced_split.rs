//! Balanced construction without the unbalanced tree first (the chapter's exercise 14.8): every
//! split keeps the tree balanced by first splitting the neighbours it would leave too coarse.
//!
//! To split a leaf x at level l, every leaf adjacent to x (under the connectivity) must be at level
//! l + 1 - k or deeper afterwards (k the allowed level difference). A neighbour search in each
//! direction finds the coarsest candidate; a too-coarse neighbour is split first, by the same
//! rule, with an explicit stack (its depth is bounded by the number of levels). If the tree was
//! balanced before a split, it is balanced after it, and every extra split is forced, so a
//! sequence of [`Tree::split_balanced`] calls builds the same tree as the plain splits followed by
//! [`Tree::balance`].
//!
//! Cost: O(d + 1) per neighbour search, 3^D - 1 searches per split. Measured on p4est's fractal
//! (`examples/balance_fractal.rs --incremental`), it does not pay: replaying the refinement with
//! balanced splits is slower than refining and balancing once (see README's benchmarks).

use super::{BalanceOptions, NodeId, Tree};
use crate::geom::Direction;

impl<const D: usize> Tree<D> {
    /// Splits the leaf `leaf` and, first, every leaf the split would leave more than
    /// `options.max_level_difference()` levels coarser than a neighbour; calls `on_split` for each
    /// leaf split, `leaf` last. Keeps a balanced tree balanced (exercise 14.8).
    ///
    /// # Panics
    /// If `leaf` is not a leaf or is at [`crate::Cell::MAX_LEVEL`].
    ///
    /// ```
    /// use orthtree::{Connectivity, tree::NodeId, Tree};
    /// let mut t = Tree::<2>::new();
    /// let mut v = NodeId::ROOT;
    /// for c in [0, 3, 3, 3] {
    ///     t.split_balanced(v, Connectivity::Face, |_, _| {});
    ///     v = t.child(v, c).unwrap();
    /// }
    /// assert!(t.is_balanced(Connectivity::Face));
    /// ```
    pub fn split_balanced(
        &mut self,
        leaf: NodeId,
        options: impl Into<BalanceOptions>,
        mut on_split: impl FnMut(&Self, NodeId),
    ) {
        let options = options.into();
        assert!(self.is_leaf(leaf), "split_balanced needs a leaf");
        let k = options.max_level_difference();
        let directions: Vec<Direction> = Direction::all::<D>(options.connectivity).collect();
        let mut stack = vec![leaf];
        while let Some(&x) = stack.last() {
            if !self.is_leaf(x) {
                stack.pop();
                continue;
            }
            let child_level = self.level(x) + 1;
            let coarse = directions.iter().find_map(|&d| {
                self.neighbor(x, d)
                    .filter(|&n| self.is_leaf(n) && self.level(n) + k < child_level)
            });
            match coarse {
                Some(n) => stack.push(n),
                None => {
                    self.split(x);
                    on_split(self, x);
                    stack.pop();
                }
            }
        }
    }
}
