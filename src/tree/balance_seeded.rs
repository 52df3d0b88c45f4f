//! Refinement toward given cells, and 2:1 balance restarted from the nodes split since the tree
//! was last balanced: the two steps a distributed balance repeats on each rank (the forest over
//! MPI ranks, `dist::balance`) when cells of other ranks arrive.
//!
//! Restarting is sound by the test of `balance.rs`: a balanced tree satisfies it at every
//! internal node, and splits only deepen the tree, so after more splits the test can fail only at
//! the new internal nodes. Seeding the level-by-level repair with them (and the internal nodes its
//! own splits create, as always) restores it everywhere, with the same forced splits as a full
//! pass: the result is the coarsest balanced refinement of the refined tree. The cost is that of
//! the seeds and the splits they force, not of the whole tree.

use super::balance::Levels;
use super::{BalanceOptions, NodeId, Tree};
use crate::geom::{Cell, Dim};

impl<const D: usize> Tree<D> {
    /// Refines the tree until `cell` is a node (splitting the leaves on its path, and calling
    /// `on_split` with each), and returns that node; when the tree is already finer there, the
    /// node at `cell` is internal. O(level of `cell`).
    pub(crate) fn refine_to(&mut self, cell: &Cell<D>, mut on_split: impl FnMut(NodeId)) -> NodeId {
        let mut v = self.locate_cell(cell);
        while self.level(v) < cell.level() {
            let first = self.split(v);
            on_split(v);
            let c = cell.ancestor(self.level(v) + 1).child_index();
            v = NodeId(first.0 + c as u32);
        }
        v
    }

    /// [`Tree::refine_to`] for each of `cells`, in Morton order: the walk down starts from the
    /// deepest node on the previous cell's path that contains the next cell, so a run of n
    /// leaves costs O(n + depth) node visits rather than O(n depth).
    pub(crate) fn refine_to_sorted(&mut self, cells: &[Cell<D>]) {
        let mut path: Vec<(NodeId, Cell<D>)> = vec![(NodeId::ROOT, Cell::root())];
        for cell in cells {
            while path.len() > 1 && !path.last().expect("the root stays").1.contains(cell) {
                path.pop();
            }
            let (mut v, mut at) = *path.last().expect("the root stays");
            while at.level() < cell.level() {
                if self.is_leaf(v) {
                    self.split(v);
                }
                let c = cell.ancestor(at.level() + 1).child_index();
                v = self.child(v, c).expect("split above");
                at = at.child(c);
                path.push((v, at));
            }
        }
    }

    /// Appends to `out` the cells of the leaves below node `v` (itself if a leaf), whose cell
    /// is `cell`, in Morton order, as the tree was when it had `before` nodes (children made
    /// later taken as absent; `u32::MAX`: the tree as it is): one walk with a frame per internal
    /// node on the path (its first child, its cell, the next child to visit) in a fixed array,
    /// each frame's leaf children written out in one loop until an internal one is met.
    pub(crate) fn leaf_cells_below(
        &self,
        v: NodeId,
        cell: Cell<D>,
        before: u32,
        out: &mut Vec<Cell<D>>,
    ) {
        let f = self.first_child[v.index()];
        if f >= before {
            out.push(cell);
            return;
        }
        let n = Dim::<D>::CHILDREN as u32;
        // One frame per level below `v`, at most Cell::MAX_LEVEL <= 32.
        let mut stack = [(f, cell, 0u32); 33];
        let mut top = 0;
        'frames: loop {
            let (first, parent, mut i) = stack[top];
            while i < n {
                let child = parent.child(i as usize);
                let g = self.first_child[(first + i) as usize];
                i += 1;
                if g >= before {
                    out.push(child);
                } else {
                    stack[top].2 = i;
                    top += 1;
                    stack[top] = (g, child, 0);
                    continue 'frames;
                }
            }
            if top == 0 {
                break;
            }
            top -= 1;
        }
    }

    /// [`Tree::balance`] of a tree that was balanced before the nodes `seeds` were split (see the
    /// module doc): returns the leaves it split, each after its parent.
    pub(crate) fn balance_seeded(
        &mut self,
        options: BalanceOptions,
        seeds: &[NodeId],
    ) -> Vec<NodeId> {
        let levels = Levels::seeded(self, options, seeds);
        self.balance_levels(levels, options.connectivity)
    }
}
