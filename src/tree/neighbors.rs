//! Neighbour finding: the chapter's NORTHNEIGHBOR (de Berg et al., *Computational Geometry*,
//! section 14.2) generalised to every face, edge and corner direction of a 2^D-tree, and the
//! leaves adjacent to a node across a face, edge or corner.
//!
//! The chapter's recursion is run as two loops: up from the node while the step leaves the
//! parent's cell (remembering at each level which child to take), then down the mirrored path
//! until a leaf or the node's own level is reached. Both loops take at most level(v) steps, so a
//! query costs O(d + 1) (Theorem 14.3) and uses no recursion.

use super::{NodeId, Tree};
use crate::geom::{Connectivity, Direction};
use smallvec::SmallVec;

impl<const D: usize> Tree<D> {
    /// The neighbour of `id` one step in `direction`, with the chapter's contract: the node of
    /// the same level whose cell is the same-size cell in that direction if it exists; else the
    /// deepest shallower node whose cell contains that cell (then a leaf); `None` when the step
    /// leaves the root cube.
    ///
    /// # Complexity
    /// O(level(id) + 1) (Theorem 14.3), no allocation for depth up to 64.
    ///
    /// ```
    /// use orthtree::{geom::Direction, tree::NodeId, Tree};
    /// let mut t = Tree::<2>::new();
    /// let sw = t.split(NodeId::ROOT);            // children: SW = 0, SE = 1, NW = 2, NE = 3
    /// let nw = t.child(NodeId::ROOT, 2).unwrap();
    /// assert_eq!(t.neighbor(sw, Direction::NORTH), Some(nw));
    /// assert_eq!(t.neighbor(nw, Direction::NORTH), None); // on the root's boundary
    /// t.split(sw);
    /// let sw_ne = t.child(sw, 3).unwrap();
    /// // SW's NE child looks north into the NW leaf, which is shallower
    /// assert_eq!(t.neighbor(sw_ne, Direction::NORTH), Some(nw));
    /// ```
    pub fn neighbor(&self, id: NodeId, direction: Direction) -> Option<NodeId> {
        let (v, path, steps) = self.neighbor_steps(id, direction)?;
        Some(self.follow(v, path, steps).0)
    }

    /// The second half of the neighbour search: from `v`, takes the last `steps` child indices
    /// of the packed `path` while there are children, and returns the node reached with the
    /// number of steps left (0 unless it is a leaf).
    pub(super) fn follow(&self, mut v: NodeId, path: u64, mut steps: u8) -> (NodeId, u8) {
        while steps > 0 {
            let c = (path >> (D * usize::from(steps - 1))) & ((1u64 << D) - 1);
            match self.child(v, c as usize) {
                Some(child) => (v, steps) = (child, steps - 1),
                None => break,
            }
        }
        (v, steps)
    }

    /// The first half of the neighbour search: climbs from `id` while the step in `direction`
    /// leaves the current cell, and returns the ancestor where it stops with the child indices to
    /// take on the way back down packed into one word, D bits a step, the first step's in the
    /// lowest bits (D times the deepest level is at most 64), and the number of steps; `None`
    /// when the step leaves the root cube. Allocates nothing.
    pub(crate) fn neighbor_steps(
        &self,
        id: NodeId,
        direction: Direction,
    ) -> Option<(NodeId, u64, u8)> {
        let (mut plus, mut minus) = (direction.plus_mask(), direction.minus_mask());
        let (mut v, mut path, mut steps) = (id, 0u64, 0u8);
        while plus | minus != 0 {
            let parent = self.parent(v)?;
            let c = self.child_index(v) as u8;
            path |= u64::from(c ^ (plus | minus)) << (D * usize::from(steps));
            // Axes on which the step leaves the parent's cell carry over to the parent's level.
            plus &= c;
            minus &= !c;
            v = parent;
            steps += 1;
        }
        Some((v, path, steps))
    }

    /// Appends to `out` every leaf whose cell touches the cell of `id` across the face, edge or
    /// corner given by `direction` (the leaves of the subdivision adjacent there), in Morton order.
    ///
    /// # Complexity
    /// O(level(id) + 1 + k) for k leaves reported, plus the internal nodes on their
    /// paths below the neighbour.
    ///
    /// ```
    /// use orthtree::{geom::Direction, tree::NodeId, Tree};
    /// let mut t = Tree::<2>::new();
    /// let sw = t.split(NodeId::ROOT);
    /// let se = t.child(NodeId::ROOT, 1).unwrap();
    /// t.split(se);
    /// let mut out = Vec::new();
    /// t.leaf_neighbors(sw, Direction::EAST, &mut out);
    /// // the two western children of SE: its SW (0) and NW (2) children
    /// assert_eq!(out, [t.child(se, 0).unwrap(), t.child(se, 2).unwrap()]);
    /// ```
    pub fn leaf_neighbors(&self, id: NodeId, direction: Direction, out: &mut Vec<NodeId>) {
        let Some(n) = self.neighbor(id, direction) else {
            return;
        };
        if self.level(n) < self.level(id) {
            out.push(n);
            return;
        }
        self.touching_leaves(n, direction.opposite(), usize::MAX, |leaf| out.push(leaf));
    }

    /// Every leaf adjacent to `id` under `connectivity`, in direction order then Morton order.
    /// A leaf larger than `id` touching it in several directions is listed once per direction.
    pub fn adjacent_leaves(&self, id: NodeId, connectivity: Connectivity, out: &mut Vec<NodeId>) {
        for d in Direction::all::<D>(connectivity) {
            self.leaf_neighbors(id, d, out);
        }
    }

    /// Calls `visit` for every leaf below `n` (inclusive), at most `max_depth` levels below it,
    /// whose cell touches the side of `n`'s cell facing `toward`, in Morton order. Nodes reached at
    /// `max_depth` below `n` are reported even if internal.
    pub(crate) fn touching_leaves(
        &self,
        n: NodeId,
        toward: Direction,
        max_depth: usize,
        mut visit: impl FnMut(NodeId),
    ) {
        // A child touches that side when its bit is set on every axis `toward` moves up along
        // and clear on every axis it moves down along.
        let (fixed, want) = (toward.axes() as usize, toward.plus_mask() as usize);
        let base = self.level(n) as usize;
        let mut stack: SmallVec<[NodeId; 64]> = SmallVec::new();
        stack.push(n);
        while let Some(v) = stack.pop() {
            if self.is_leaf(v) || self.level(v) as usize - base >= max_depth {
                visit(v);
                continue;
            }
            for (i, child) in self.children(v).enumerate().rev() {
                if i & fixed == want {
                    stack.push(child);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corner_neighbour_crosses_two_parents() {
        let mut t = Tree::<2>::new();
        let f = t.split(NodeId::ROOT);
        let sw = f;
        let ne = NodeId(f.0 + 3);
        let sw_ne = NodeId(t.split(sw).0 + 3);
        let ne_sw = t.split(ne);
        let up_right = Direction::NORTH.combine(Direction::EAST).unwrap();
        assert_eq!(t.neighbor(sw_ne, up_right), Some(ne_sw));
        assert_eq!(t.neighbor(ne_sw, up_right.opposite()), Some(sw_ne));
        assert_eq!(t.neighbor(NodeId::ROOT, Direction::EAST), None);
    }
}
