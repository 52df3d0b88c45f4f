//! [`Tree::merge`]: the inverse of a split. A node whose 2^D children are all leaves becomes a
//! leaf again; the child block goes on a free list that the next [`Tree::split`] reuses (most
//! recently freed first), so a tree that splits and merges in turn does not grow.
//!
//! Freed slots keep ids below [`Tree::node_count`] but are never reachable from the root: every
//! traversal, neighbour search and balance walks from the root, or (balance, `is_balanced`) scans
//! the ids for internal nodes, and a freed slot is a leaf (merge frees only blocks of leaves).
//! [`Tree::leaf_count`] counts live blocks only; [`Tree::depth`] stays exact (a count of live
//! blocks per level). O(1) per merge, plus O(levels freed) to lower the depth.

use super::arena::NONE;
use super::{NodeId, Tree};
use crate::geom::Dim;

/// Why [`Tree::merge`] refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MergeError {
    /// The node is a leaf already.
    Leaf(NodeId),
    /// The node has a child that is not a leaf (merge its children first).
    ChildNotLeaf(NodeId),
}

impl core::fmt::Display for MergeError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            MergeError::Leaf(id) => write!(f, "node {} is a leaf", id.0),
            MergeError::ChildNotLeaf(id) => {
                write!(f, "node {} has a child that is not a leaf", id.0)
            }
        }
    }
}

impl std::error::Error for MergeError {}

impl<const D: usize> Tree<D> {
    /// Makes `id`, whose children are all leaves, a leaf again, and frees its child block for
    /// reuse by a later split. The ids of the freed children must no longer be used.
    ///
    /// # Errors
    /// A [`MergeError`]: `id` is a leaf, or one of its children is not.
    ///
    /// # Complexity
    /// O(2^D), plus O(levels) when the tree's depth drops.
    ///
    /// ```
    /// use orthtree::{tree::NodeId, Tree};
    /// let mut t = Tree::<2>::new();
    /// let first = t.split(NodeId::ROOT);
    /// t.merge(NodeId::ROOT).unwrap();
    /// assert!(t.is_leaf(NodeId::ROOT) && t.leaf_count() == 1 && t.depth() == 0);
    /// assert_eq!(t.split(NodeId::ROOT), first); // the freed block is reused
    /// assert_eq!(t.node_count(), 5);
    /// ```
    pub fn merge(&mut self, id: NodeId) -> Result<(), MergeError> {
        let first = self.first_child[id.index()];
        if first == NONE {
            return Err(MergeError::Leaf(id));
        }
        let f = first as usize;
        if self.first_child[f..f + Dim::<D>::CHILDREN]
            .iter()
            .any(|&c| c != NONE)
        {
            return Err(MergeError::ChildNotLeaf(id));
        }
        self.first_child[id.index()] = NONE;
        self.free_blocks.push(first);
        let level = self.level(id) as usize + 1;
        self.live_blocks[level] -= 1;
        while self.depth > 0 && self.live_blocks[self.depth as usize] == 0 {
            self.depth -= 1;
        }
        Ok(())
    }

    /// Merges every node below `id` bottom-up, so that `id` becomes a leaf; returns the number of
    /// blocks freed. O(nodes below `id`).
    ///
    /// # Panics
    /// If `id` is not a node of this tree (like slice indexing).
    ///
    /// # Complexity
    /// O(nodes below `id`).
    pub fn merge_subtree(&mut self, id: NodeId) -> usize {
        // Post-order with an explicit stack: (node, children pushed).
        let mut stack = vec![(id, false)];
        let mut freed = 0;
        while let Some((v, expanded)) = stack.pop() {
            if self.is_leaf(v) {
                continue;
            }
            if expanded {
                self.merge(v).expect("its children were merged first");
                freed += 1;
            } else {
                stack.push((v, true));
                stack.extend(self.children(v).map(|c| (c, false)));
            }
        }
        freed
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Cell;
    use crate::{tree::BalanceOptions, Connectivity};

    #[test]
    fn merge_refuses_leaves_and_grandparents() {
        let mut t = Tree::<2>::new();
        assert_eq!(t.merge(NodeId::ROOT), Err(MergeError::Leaf(NodeId::ROOT)));
        let first = t.split(NodeId::ROOT);
        t.split(first);
        assert_eq!(
            t.merge(NodeId::ROOT),
            Err(MergeError::ChildNotLeaf(NodeId::ROOT))
        );
        assert_eq!(t.depth(), 2);
        t.merge(first).unwrap();
        assert_eq!(t.depth(), 1);
        assert_eq!(t.leaf_count(), 4);
    }

    #[test]
    fn freed_blocks_are_unreachable_and_reused() {
        let mut t = Tree::<3>::new();
        let first = t.split(NodeId::ROOT);
        let a = NodeId(first.0 + 3);
        let b = NodeId(first.0 + 6);
        t.split(a);
        let gb = t.split(b);
        t.split(gb);
        assert_eq!(t.depth(), 3);
        assert_eq!(t.merge_subtree(b), 2);
        assert_eq!(t.depth(), 2);
        assert_eq!(t.leaf_count(), 15);
        let cells: Vec<Cell<3>> = t.leaves().map(|(_, c)| c).collect();
        assert_eq!(cells.len(), t.leaf_count());
        assert_eq!(t.pre_order().count(), 1 + 8 + 8);
        for (id, cell) in t.pre_order() {
            assert_eq!(t.cell(id), cell);
            if id != NodeId::ROOT {
                assert!(t.children(t.parent(id).unwrap()).any(|c| c == id));
            }
        }
        // the neighbour of a's sibling across into a is a's subtree, never a freed node
        let count = t.node_count();
        let g = t.split(NodeId(first.0 + 1));
        assert!(g.index() < count, "a freed block is reused");
        assert_eq!(t.node_count(), count);
        assert_eq!(t.parent(g), Some(NodeId(first.0 + 1)));
        assert_eq!(t.level(g), 2);
        assert_eq!(t.cell(g), Cell::root().child(1).child(0));
        let balance = BalanceOptions::new(Connectivity::Corner);
        let mut u = t.clone();
        u.balance(balance);
        assert!(u.is_balanced(balance));
        for (id, _) in u.pre_order() {
            for c in u.children(id) {
                assert_eq!(u.parent(c), Some(id));
            }
        }
        // merging everything leaves a single root
        let n = t.merge_subtree(NodeId::ROOT);
        assert_eq!(n, 3);
        assert_eq!((t.leaf_count(), t.depth()), (1, 0));
        assert_eq!(t.leaves().count(), 1);
    }

    #[test]
    fn merged_tree_matches_a_fresh_one() {
        // split a path, merge it, split another: same leaves as splitting the other directly
        let mut t = Tree::<2>::new();
        let f = t.split(NodeId::ROOT);
        let g = t.split(NodeId(f.0 + 2));
        t.split(NodeId(g.0 + 1));
        t.merge_subtree(NodeId(f.0 + 2));
        t.split(NodeId(f.0 + 3));
        let mut fresh = Tree::<2>::new();
        let f2 = fresh.split(NodeId::ROOT);
        fresh.split(NodeId(f2.0 + 3));
        let cells = |t: &Tree<2>| t.leaves().map(|(_, c)| c).collect::<Vec<_>>();
        assert_eq!(cells(&t), cells(&fresh));
        assert_eq!(t.depth(), fresh.depth());
        assert_eq!(t.leaf_count(), fresh.leaf_count());
        let dirs: Vec<_> = crate::geom::Direction::all::<2>(Connectivity::Corner).collect();
        for ((a, ca), (b, cb)) in t.pre_order().zip(fresh.pre_order()) {
            assert_eq!(ca, cb);
            for &d in &dirs {
                let na = t.neighbor(a, d).map(|n| t.cell(n));
                let nb = fresh.neighbor(b, d).map(|n| fresh.cell(n));
                assert_eq!(na, nb);
            }
        }
    }
}
