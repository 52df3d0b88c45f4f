//! [`Tree`]: the topology of a 2^D-tree in an arena, with no payload.
//!
//! Nodes are `u32` indices. The root is node 0; every split appends one block of 2^D children
//! stored side by side, so a node keeps only the index of its first child, and a block keeps its
//! parent (4 bytes per node plus 4 per block, plus one byte of level). Node ids never move:
//! a consumer can keep its payload in a `Vec` indexed by [`NodeId`] and extend it after a split.
//!
//! [`Tree::merge`] (in `merge.rs`) turns a node whose children are all leaves back into a leaf and
//! puts the child block on a free list; the next split reuses the most recently freed block, so
//! ids below [`Tree::node_count`] may be free slots, never reachable from the root.

use crate::geom::{Cell, Dim};

pub(super) const NONE: u32 = u32::MAX;

/// The index of a node in a [`Tree`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct NodeId(pub(crate) u32);

impl NodeId {
    /// The root of every tree.
    pub const ROOT: NodeId = NodeId(0);

    /// The id as an index, for payload vectors indexed by node.
    #[inline]
    pub const fn index(self) -> usize {
        self.0 as usize
    }
}

/// The topology of a 2^D-tree: which nodes exist, their parents, children and levels.
///
/// ```
/// use orthtree::{Tree, tree::NodeId};
/// let mut t = Tree::<2>::new();
/// let first = t.split(NodeId::ROOT);
/// assert_eq!(t.node_count(), 5);
/// assert_eq!(t.leaf_count(), 4);
/// assert_eq!(t.parent(first), Some(NodeId::ROOT));
/// assert_eq!(t.cell(t.child(NodeId::ROOT, 3).unwrap()).coords(), [1, 1]);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Tree<const D: usize> {
    pub(super) first_child: Vec<u32>,
    pub(super) level: Vec<u8>,
    block_parent: Vec<u32>,
    pub(super) depth: u8,
    /// First child ids of freed blocks (see [`Tree::merge`]), reused by the next splits.
    pub(super) free_blocks: Vec<u32>,
    /// `live_blocks[l]`: the number of live child blocks at level `l`, so merge keeps `depth`
    /// exact.
    pub(super) live_blocks: Vec<u32>,
}

impl<const D: usize> Default for Tree<D> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const D: usize> Tree<D> {
    /// A tree holding only its root, a leaf.
    pub fn new() -> Self {
        let () = Dim::<D>::CHECK;
        Tree {
            first_child: vec![NONE],
            level: vec![0],
            block_parent: Vec::new(),
            depth: 0,
            free_blocks: Vec::new(),
            live_blocks: vec![0; Cell::<D>::MAX_LEVEL as usize + 1],
        }
    }

    /// Number of node slots: the nodes, internal and leaves, plus the slots of child blocks freed
    /// by [`Tree::merge`] and not yet reused (none unless `merge` was called). Every node id is
    /// below it, so payload vectors indexed by node have this length.
    #[inline]
    pub fn node_count(&self) -> usize {
        self.first_child.len()
    }

    /// Number of leaves: one plus (2^D - 1) per live child block.
    #[inline]
    pub fn leaf_count(&self) -> usize {
        1 + (self.block_parent.len() - self.free_blocks.len()) * (Dim::<D>::CHILDREN - 1)
    }

    /// The depth: the largest level of any node (0 for a single root); exact after merges too.
    #[inline]
    pub fn depth(&self) -> u8 {
        self.depth
    }

    /// `true` when `id` has no children.
    #[inline]
    pub fn is_leaf(&self, id: NodeId) -> bool {
        self.first_child[id.index()] == NONE
    }

    /// The level of `id` (the root is at level 0).
    #[inline]
    pub fn level(&self, id: NodeId) -> u8 {
        self.level[id.index()]
    }

    /// The parent of `id`; `None` for the root.
    #[inline]
    pub fn parent(&self, id: NodeId) -> Option<NodeId> {
        (id.0 != 0).then(|| NodeId(self.block_parent[((id.0 - 1) >> D) as usize]))
    }

    /// Which child of its parent `id` is (bit `a` set: upper half along axis `a`); 0 for the root.
    #[inline]
    pub fn child_index(&self, id: NodeId) -> usize {
        // the root (0) is child 0, the others come in blocks of 2^D from 1
        (id.0.saturating_sub(1) as usize) & (Dim::<D>::CHILDREN - 1)
    }

    /// The `index`-th child of `id`; `None` if `id` is a leaf.
    #[inline]
    pub fn child(&self, id: NodeId, index: usize) -> Option<NodeId> {
        debug_assert!(index < Dim::<D>::CHILDREN);
        let first = self.first_child[id.index()];
        (first != NONE).then(|| NodeId(first + index as u32))
    }

    /// The 2^D children of `id` in child-index order; empty for a leaf.
    #[inline]
    pub fn children(
        &self,
        id: NodeId,
    ) -> impl ExactSizeIterator<Item = NodeId> + DoubleEndedIterator + use<D> {
        let first = self.first_child[id.index()];
        let n = if first == NONE {
            0
        } else {
            Dim::<D>::CHILDREN as u32
        };
        let first = if first == NONE { 0 } else { first };
        (first..first + n).map(NodeId)
    }

    /// The cell of `id`, found by walking up to the root: O(level).
    ///
    /// # Panics
    /// If `id` is not a node of this tree (like slice indexing).
    ///
    /// # Complexity
    /// O(level of `id`).
    pub fn cell(&self, id: NodeId) -> Cell<D> {
        let level = self.level(id);
        let mut coords = [0u32; D];
        let mut v = id;
        for bit in 0..level as u32 {
            let c = self.child_index(v);
            for (a, x) in coords.iter_mut().enumerate() {
                *x |= (((c >> a) & 1) as u32) << bit;
            }
            v = self
                .parent(v)
                .expect("a node above the root level has a parent");
        }
        Cell::new(level, coords).expect("a node's level never exceeds Cell::MAX_LEVEL")
    }

    /// Splits the leaf `id` into 2^D leaves and returns the first of them; the others follow it.
    ///
    /// # Panics
    /// If `id` is not a leaf or is at [`Cell::MAX_LEVEL`]; see [`Tree::try_split`].
    pub fn split(&mut self, id: NodeId) -> NodeId {
        self.try_split(id).unwrap_or_else(|e| panic!("{e}"))
    }

    /// Splits the leaf `id`, or says why it cannot be split.
    ///
    /// # Errors
    /// A [`SplitError`]: `id` is not a leaf, it is at [`Cell::MAX_LEVEL`], or the tree already
    /// has 2^32 - 1 nodes.
    ///
    /// # Complexity
    /// O(2^D).
    pub fn try_split(&mut self, id: NodeId) -> Result<NodeId, SplitError> {
        if !self.is_leaf(id) {
            return Err(SplitError::NotALeaf(id));
        }
        let level = self.level(id);
        if level >= Cell::<D>::MAX_LEVEL {
            return Err(SplitError::MaxLevel(id));
        }
        let n = Dim::<D>::CHILDREN;
        let first = if let Some(first) = self.free_blocks.pop() {
            // A freed block: its nodes are leaves (merge only frees blocks of leaves).
            let f = first as usize;
            self.level[f..f + n].fill(level + 1);
            self.block_parent[(f - 1) >> D] = id.0;
            f
        } else {
            let first = self.first_child.len();
            if first + n > NONE as usize {
                return Err(SplitError::Full);
            }
            self.first_child.resize(first + n, NONE);
            self.level.resize(first + n, level + 1);
            self.block_parent.push(id.0);
            first
        };
        self.first_child[id.index()] = first as u32;
        self.live_blocks[level as usize + 1] += 1;
        self.depth = self.depth.max(level + 1);
        Ok(NodeId(first as u32))
    }

    /// A tree of the given arrays, unchecked: [`Tree::from_raw_parts`] (`raw.rs`) checks them.
    #[cfg(any(feature = "saved", feature = "serde"))]
    pub(super) fn from_arrays(raw: super::raw::OwnedRawTree) -> Self {
        Tree {
            first_child: raw.first_child,
            level: raw.level,
            block_parent: raw.block_parent,
            depth: raw.depth,
            free_blocks: raw.free_blocks,
            live_blocks: raw.live_blocks,
        }
    }

    /// The parent of every child block, by block number (block `b` holds nodes
    /// `1 + b * 2^D ..`); freed blocks keep their last parent.
    #[inline]
    pub(super) fn block_parents(&self) -> &[u32] {
        &self.block_parent
    }

    /// The first children, levels and block parents as stored, for the point trees' run walk.
    #[inline]
    pub(crate) fn link_arrays(&self) -> (&[u32], &[u8], &[u32]) {
        (&self.first_child, &self.level, &self.block_parent)
    }

    /// `true` when child block `b` is in use: a block freed by [`Tree::merge`] keeps its last
    /// parent, which no longer points to it (only checked once something was merged).
    #[inline]
    pub(super) fn block_is_live(&self, b: usize) -> bool {
        self.free_blocks.is_empty()
            || self.first_child[self.block_parent[b] as usize] as usize == 1 + (b << D)
    }

    /// The deepest node whose cell contains `cell`.
    ///
    /// # Complexity
    /// O(level of the result).
    pub fn locate_cell(&self, cell: &Cell<D>) -> NodeId {
        let mut v = NodeId::ROOT;
        while let Some(first) = self.child(v, 0) {
            let level = self.level(v);
            if level >= cell.level() {
                break;
            }
            let c = cell.ancestor(level + 1).child_index();
            v = NodeId(first.0 + c as u32);
        }
        v
    }

    /// Reserves room for `splits` more splits.
    pub fn reserve_splits(&mut self, splits: usize) {
        self.first_child.reserve(splits * Dim::<D>::CHILDREN);
        self.level.reserve(splits * Dim::<D>::CHILDREN);
        self.block_parent.reserve(splits);
    }

    /// Gives back the spare capacity of the node arrays (after a bulk build, say).
    pub fn shrink_to_fit(&mut self) {
        self.first_child.shrink_to_fit();
        self.level.shrink_to_fit();
        self.block_parent.shrink_to_fit();
    }

    /// Heap bytes used by the topology.
    pub fn heap_bytes(&self) -> usize {
        self.first_child.capacity() * 4
            + self.level.capacity()
            + self.block_parent.capacity() * 4
            + self.free_blocks.capacity() * 4
            + self.live_blocks.capacity() * 4
    }
}

/// Why [`Tree::try_split`] refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SplitError {
    /// The node already has children.
    NotALeaf(NodeId),
    /// The node is at [`Cell::MAX_LEVEL`].
    MaxLevel(NodeId),
    /// The tree already has 2^32 - 1 nodes.
    Full,
}

impl core::fmt::Display for SplitError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            SplitError::NotALeaf(id) => write!(f, "node {} is not a leaf", id.0),
            SplitError::MaxLevel(id) => write!(f, "node {} is at the deepest level", id.0),
            SplitError::Full => write!(
                f,
                "the tree has the largest number of nodes a u32 can index"
            ),
        }
    }
}

impl std::error::Error for SplitError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn split_parent_child_and_cells_agree() {
        let mut t = Tree::<3>::new();
        let first = t.split(NodeId::ROOT);
        let c5 = NodeId(first.0 + 5);
        t.split(c5);
        let g = t.child(c5, 6).unwrap();
        assert_eq!(t.parent(g), Some(c5));
        assert_eq!(t.child_index(g), 6);
        assert_eq!(t.cell(g), Cell::root().child(5).child(6));
        assert_eq!(t.locate_cell(&Cell::root().child(5).child(6).child(1)), g);
        assert_eq!(t.leaf_count(), 15);
        assert_eq!(t.depth(), 2);
        assert_eq!(t.try_split(c5), Err(SplitError::NotALeaf(c5)));
        assert!(t.children(g).next().is_none());
    }

    #[test]
    fn splitting_stops_at_the_deepest_level() {
        let mut t = Tree::<8>::new();
        let mut v = NodeId::ROOT;
        for _ in 0..Cell::<8>::MAX_LEVEL {
            v = t.split(v);
        }
        assert_eq!(t.try_split(v), Err(SplitError::MaxLevel(v)));
    }
}
