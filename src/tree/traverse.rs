//! Traversals of a [`Tree`]: pre-order over all nodes and leaves in Morton (z-) order, each
//! yielding the node's [`Cell`] as it goes, with an explicit stack (no recursion).

use super::{NodeId, Tree};
use crate::geom::Cell;
use smallvec::SmallVec;

/// Iterator returned by [`Tree::pre_order`]: every node with its cell, parents before children,
/// children in child-index order.
pub struct PreOrder<'a, const D: usize> {
    tree: &'a Tree<D>,
    stack: SmallVec<[(NodeId, Cell<D>); 64]>,
    leaves_only: bool,
}

impl<const D: usize> Iterator for PreOrder<'_, D> {
    type Item = (NodeId, Cell<D>);

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            let (id, cell) = self.stack.pop()?;
            let children = self.tree.children(id);
            let is_leaf = children.len() == 0;
            for (i, child) in children.enumerate().rev() {
                self.stack.push((child, cell.child(i)));
            }
            if is_leaf || !self.leaves_only {
                return Some((id, cell));
            }
        }
    }
}

impl<const D: usize> Tree<D> {
    /// Every node with its cell, in pre-order (parents first, children by child index), which
    /// is Morton order of the cells. O(1) amortised per node; the stack holds at most
    /// depth * (2^D - 1) + 1 entries.
    ///
    /// ```
    /// use orthtree::{Tree, tree::NodeId};
    /// let mut t = Tree::<2>::new();
    /// t.split(NodeId::ROOT);
    /// let levels: Vec<u8> = t.pre_order().map(|(_, c)| c.level()).collect();
    /// assert_eq!(levels, [0, 1, 1, 1, 1]);
    /// ```
    pub fn pre_order(&self) -> PreOrder<'_, D> {
        self.walk_from(NodeId::ROOT, false)
    }

    /// The leaves with their cells in Morton order (the chapter's quadtree subdivision).
    ///
    /// ```
    /// use orthtree::{Tree, tree::NodeId};
    /// let mut t = Tree::<1>::new();
    /// let first = t.split(NodeId::ROOT);
    /// t.split(first);
    /// let cells: Vec<[u32; 1]> = t.leaves().map(|(_, c)| c.coords()).collect();
    /// assert_eq!(cells, [[0], [1], [1]]); // two level-2 cells, then one level-1 cell
    /// ```
    pub fn leaves(&self) -> PreOrder<'_, D> {
        self.walk_from(NodeId::ROOT, true)
    }

    /// The subtree below `id` (inclusive) in pre-order, or only its leaves.
    pub fn walk_from(&self, id: NodeId, leaves_only: bool) -> PreOrder<'_, D> {
        PreOrder {
            tree: self,
            stack: smallvec::smallvec![(id, self.cell(id))],
            leaves_only,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn leaves_come_in_morton_order_and_cover_the_root() {
        let mut t = Tree::<2>::new();
        let f = t.split(NodeId::ROOT);
        let g = t.split(NodeId(f.0 + 2));
        t.split(NodeId(g.0 + 1));
        let cells: Vec<Cell<2>> = t.leaves().map(|(_, c)| c).collect();
        assert_eq!(cells.len(), t.leaf_count());
        assert!(cells.windows(2).all(|w| w[0] < w[1]));
        let area: u64 = cells.iter().map(|c| 1u64 << (2 * (8 - c.level()))).sum();
        assert_eq!(area, 1 << 16);
        for (id, c) in t.pre_order() {
            assert_eq!(t.cell(id), c);
        }
        assert_eq!(t.pre_order().count(), t.node_count());
    }
}
