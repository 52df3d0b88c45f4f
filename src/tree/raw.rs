//! A [`Tree`]'s arrays as they are stored, for the saved-tree format and serde: a borrowed view
//! ([`Tree::raw_parts`]) and the checked constructor that takes them back
//! ([`Tree::from_raw_parts`]), which refuses any arrays [`Tree::validate`] or the bounds every
//! other method relies on would reject, so that no later call on the tree can panic.

use super::{NodeId, Tree, TreeError};
use crate::geom::{Cell, Dim};

/// The arrays of a [`Tree`] (see the module doc), `W` a sequence of `u32` and `B` of `u8`.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct RawArrays<W, B> {
    /// Per node slot, the first child's id or `u32::MAX` for a leaf.
    pub first_child: W,
    /// Per node slot, its level.
    pub level: B,
    /// Per child block, its parent (freed blocks keep their last one).
    pub block_parent: W,
    /// The first ids of the freed blocks, in the order the next splits take them (last first).
    pub free_blocks: W,
    /// Per level 0..=[`Cell::MAX_LEVEL`], the live child blocks whose nodes are at that level.
    pub live_blocks: W,
    /// The deepest level of a node.
    pub depth: u8,
}

/// The arrays of a [`Tree`], by reference.
pub(crate) type RawTree<'a> = RawArrays<&'a [u32], &'a [u8]>;

/// The owned arrays [`Tree::from_raw_parts`] takes.
pub(crate) type OwnedRawTree = RawArrays<Vec<u32>, Vec<u8>>;

impl<const D: usize> Tree<D> {
    /// The stored arrays, by reference.
    pub(crate) fn raw_parts(&self) -> RawTree<'_> {
        RawTree {
            first_child: &self.first_child,
            level: &self.level,
            block_parent: self.block_parents(),
            free_blocks: &self.free_blocks,
            live_blocks: &self.live_blocks,
            depth: self.depth,
        }
    }

    /// The tree of the arrays `raw`, checked: one live-block count per level, every level and
    /// recorded block parent in range (freed blocks included, which [`Tree::validate`] does not
    /// walk), then [`Tree::validate`].
    ///
    /// # Errors
    /// The first [`TreeError`] found.
    ///
    /// # Complexity
    /// O(node slots), no recursion.
    pub(crate) fn from_raw_parts(raw: OwnedRawTree) -> Result<Self, TreeError> {
        let () = Dim::<D>::CHECK;
        let levels = Cell::<D>::MAX_LEVEL as usize + 1;
        if raw.live_blocks.len() != levels {
            return Err(TreeError::LiveBlocks {
                level: raw.live_blocks.len().min(levels),
                recorded: raw.live_blocks.len() as u32,
                actual: levels as u32,
            });
        }
        let slots = raw.first_child.len();
        let blocks = raw.block_parent.len();
        let whole = blocks
            .checked_mul(Dim::<D>::CHILDREN)
            .and_then(|x| x.checked_add(1));
        if raw.level.len() != slots || whole != Some(slots) || slots > u32::MAX as usize {
            return Err(TreeError::Arrays {
                nodes: slots,
                blocks,
            });
        }
        if let Some(i) = raw.level.iter().position(|&l| l > Cell::<D>::MAX_LEVEL) {
            return Err(TreeError::Level {
                node: NodeId(i as u32),
                level: raw.level[i],
                expected: Cell::<D>::MAX_LEVEL,
            });
        }
        if let Some(b) = raw.block_parent.iter().position(|&p| p as usize >= slots) {
            return Err(TreeError::BlockParent {
                node: NodeId(raw.block_parent[b]),
                first_child: NodeId((1 + b * Dim::<D>::CHILDREN) as u32),
                recorded: NodeId(raw.block_parent[b]),
            });
        }
        let tree = Tree::from_arrays(raw);
        tree.validate().map(|()| tree)
    }
}
