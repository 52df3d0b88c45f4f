//! The reference 2:1 balance: the chapter's BALANCEQUADTREE (section 14.2, Theorem 14.4) generalised to D
//! dimensions, to face, edge and corner connectivity, and to the weak balance of exercise 14.6
//! (adjacent leaves may differ by a factor 4, i.e. two levels).
//!
//! A worklist holds leaves to examine. A leaf must be split when some leaf adjacent to it (under
//! the chosen connectivity) is more than `max_level_difference` levels deeper; that is found with
//! [`Tree::neighbor`]: the same-level neighbour has an internal descendant touching the shared
//! side `max_level_difference` levels down. After a split, its 2^D children are examined, and so
//! is every neighbour leaf now too coarse next to them. Every split is forced, so the result is
//! the coarsest balanced refinement.
//!
//! The crate's [`Tree::balance`] (in `balance.rs`) gives the same tree faster; this one stays as
//! the oracle it is tested against, compiled only with the `reference` feature (which the
//! crate's own tests, benches and examples turn on).
//!
//! Splits: the chapter's charging argument carries over to D dimensions and to every connectivity
//! and ratio: each split cell has an original (pre-balance) cell among its 3^D - 1 same-size
//! neighbours, so balancing a tree of m nodes makes at most (3^D - 1) m splits (8m in 2D).
//! Time: O((d + 1)(m + splits)) with d the depth.

use super::{BalanceOptions, NodeId, Tree};
use crate::geom::Direction;

impl<const D: usize> Tree<D> {
    /// The chapter's BALANCEQUADTREE, generalised: the same result as [`Tree::balance`], by a
    /// worklist of leaves and neighbour searches below each neighbour. Kept as the reference that
    /// [`Tree::balance`] is tested against; slower by a constant factor.
    ///
    /// Refines the tree to the coarsest balanced tree containing it and returns the leaves it
    /// split, in the order it split them (each split leaf's children follow from
    /// [`Tree::children`]; the list may hold leaves created by earlier splits in it).
    ///
    /// # Complexity
    /// At most (3^D - 1) m splits for a tree of m nodes (Theorem 14.4, generalised
    /// in the module doc), O(d + 1) per neighbour query.
    pub fn balance_chapter(&mut self, options: impl Into<BalanceOptions>) -> Vec<NodeId> {
        let options = options.into();
        let k = options.max_level_difference();
        let directions: Vec<Direction> = Direction::all::<D>(options.connectivity).collect();
        let mut work: Vec<NodeId> = self.leaves().map(|(id, _)| id).collect();
        let mut split = Vec::new();
        while let Some(leaf) = work.pop() {
            if !self.is_leaf(leaf) || !self.must_split(leaf, &directions, k) {
                continue;
            }
            let first = self.split(leaf);
            split.push(leaf);
            let child_level = self.level(first);
            work.extend(self.children(leaf));
            for &d in &directions {
                if let Some(n) = self.neighbor(leaf, d)
                    && self.is_leaf(n)
                    && self.level(n) + k < child_level
                {
                    work.push(n);
                }
            }
        }
        split
    }

    /// The reference check for [`Tree::is_balanced`]: for every leaf and direction, looks for a
    /// too-deep leaf below the neighbour. `true` when no two adjacent leaves (under `options`'
    /// connectivity) differ by more than `options.max_level_difference()` levels.
    ///
    /// # Complexity
    /// O((d + 1) m) for m nodes and depth d.
    pub fn is_balanced_chapter(&self, options: impl Into<BalanceOptions>) -> bool {
        let options = options.into();
        let directions: Vec<Direction> = Direction::all::<D>(options.connectivity).collect();
        self.leaves()
            .all(|(leaf, _)| !self.must_split(leaf, &directions, options.max_level_difference()))
    }

    /// `true` when some leaf adjacent to `leaf` in one of `directions` is more than `k` levels
    /// deeper.
    fn must_split(&self, leaf: NodeId, directions: &[Direction], k: u8) -> bool {
        let level = self.level(leaf);
        directions.iter().any(|&d| {
            let Some(n) = self.neighbor(leaf, d) else {
                return false;
            };
            if self.level(n) != level || self.is_leaf(n) {
                return false;
            }
            let mut too_deep = false;
            self.touching_leaves(n, d.opposite(), k as usize, |v| {
                too_deep |= !self.is_leaf(v);
            });
            too_deep
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Connectivity;

    #[test]
    fn weak_balance_allows_two_levels() {
        let mut t = Tree::<2>::new();
        let f = t.split(NodeId::ROOT);
        let g = t.split(f); // SW at level 1 split: level-2 leaves next to level-1 SE
        assert!(t.is_balanced_chapter(Connectivity::Corner));
        t.split(NodeId(g.0 + 3)); // level-3 leaves touch SE (level 1) at a corner... and face
        assert!(!t.is_balanced_chapter(Connectivity::Face));
        assert!(t.is_balanced_chapter(BalanceOptions::new(Connectivity::Corner).weak()));
        let split = t.balance_chapter(BalanceOptions::new(Connectivity::Face).weak());
        assert!(split.is_empty());
        let split = t.balance_chapter(Connectivity::Face);
        assert_eq!(split.len(), 2); // SE and NW
        assert!(t.is_balanced_chapter(Connectivity::Face));
        // NE (level 1) still touches a level-3 leaf at the centre point
        assert!(!t.is_balanced_chapter(Connectivity::Corner));
        assert_eq!(t.balance_chapter(Connectivity::Corner).len(), 1);
        assert!(t.is_balanced_chapter(Connectivity::Corner));
    }
}
