//! [`Tree::validate`]: every invariant of the arena checked in one walk from the root, the first
//! broken one named with the node it concerns ([`TreeError`]).
//!
//! The invariants. The arrays agree in length and hold whole child blocks; the root is at level 0
//! and no node is deeper than [`Cell::MAX_LEVEL`]; every internal node's first child starts a
//! block (id 1 + b 2^D), the block records the node as its parent and is not on the free list,
//! and its children are one level deeper; no node is reached twice; every block is either
//! reached from the root or free (once), and a free block holds only leaves; the recorded depth
//! and the live blocks per level equal what the walk counts. Tests call it after every mutation
//! (split, merge, balance), as rstar's `sanity_check`.

use super::arena::NONE;
use super::{NodeId, Tree};
use crate::geom::{Cell, Dim};

/// The first invariant of a [`Tree`] that [`Tree::validate`] found broken.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum TreeError {
    /// The node arrays do not hold the root plus whole blocks of 2^D nodes.
    Arrays {
        /// Node slots.
        nodes: usize,
        /// Recorded child blocks.
        blocks: usize,
    },
    /// A node's level is wrong: the root's is not 0, a child's is not its parent's plus one, or
    /// it exceeds [`Cell::MAX_LEVEL`].
    Level {
        /// The node.
        node: NodeId,
        /// Its recorded level.
        level: u8,
        /// The level it should have.
        expected: u8,
    },
    /// A node's first child is out of range or does not start a child block.
    FirstChild {
        /// The node.
        node: NodeId,
        /// Its recorded first child.
        first_child: u32,
    },
    /// A node's child block records another parent.
    BlockParent {
        /// The node.
        node: NodeId,
        /// The first child of its block.
        first_child: NodeId,
        /// The parent the block records.
        recorded: NodeId,
    },
    /// A node is reached twice from the root (two parents point to its block).
    ReachedTwice(NodeId),
    /// A block in use (reached from the root) is also on the free list.
    FreeBlockInUse(NodeId),
    /// A block is on the free list twice, or its first id does not start a block.
    FreeList(u32),
    /// A node of a free block is not a leaf.
    FreeNodeNotLeaf(NodeId),
    /// A block is neither reached from the root nor free (named by its first node).
    LostBlock(NodeId),
    /// The recorded depth differs from the deepest level reached.
    Depth {
        /// The recorded depth.
        recorded: u8,
        /// The deepest level of a node.
        actual: u8,
    },
    /// The recorded number of live child blocks at a level differs from the count.
    LiveBlocks {
        /// The level of the blocks' nodes.
        level: usize,
        /// The recorded count.
        recorded: u32,
        /// The counted one.
        actual: u32,
    },
}

impl core::fmt::Display for TreeError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            TreeError::Arrays { nodes, blocks } => write!(
                f,
                "{nodes} node slots and {blocks} blocks are not the root plus whole blocks"
            ),
            TreeError::Level {
                node,
                level,
                expected,
            } => write!(
                f,
                "node {} is at level {level}, expected level {expected}",
                node.0
            ),
            TreeError::FirstChild { node, first_child } => write!(
                f,
                "node {}'s first child {first_child} does not start a child block",
                node.0
            ),
            TreeError::BlockParent {
                node,
                first_child,
                recorded,
            } => write!(
                f,
                "node {}'s child block at {} records parent {}",
                node.0, first_child.0, recorded.0
            ),
            TreeError::ReachedTwice(node) => {
                write!(f, "node {} is reached twice from the root", node.0)
            }
            TreeError::FreeBlockInUse(first) => write!(
                f,
                "the child block at {} is in use and on the free list",
                first.0
            ),
            TreeError::FreeList(first) => write!(
                f,
                "free-list entry {first} is repeated or does not start a block"
            ),
            TreeError::FreeNodeNotLeaf(node) => {
                write!(f, "node {} of a free block has children", node.0)
            }
            TreeError::LostBlock(first) => write!(
                f,
                "the child block at {} is neither reached from the root nor free",
                first.0
            ),
            TreeError::Depth { recorded, actual } => write!(
                f,
                "the recorded depth is {recorded}, the deepest node is at level {actual}"
            ),
            TreeError::LiveBlocks {
                level,
                recorded,
                actual,
            } => write!(
                f,
                "{recorded} live blocks recorded at level {level}, {actual} counted"
            ),
        }
    }
}

impl std::error::Error for TreeError {}

impl<const D: usize> Tree<D> {
    /// Checks every invariant of the arena (see the module doc) and names the first one broken.
    /// A tree changed only through its public methods always passes; tests call it after each
    /// mutation.
    ///
    /// # Errors
    /// The first [`TreeError`] found.
    ///
    /// # Complexity
    /// O(node slots) time, one bit per node slot and one word per level of extra memory; no
    /// recursion.
    ///
    /// ```
    /// use orthtree::{tree::NodeId, Tree};
    /// let mut t = Tree::<3>::new();
    /// let first = t.split(NodeId::ROOT);
    /// t.split(first);
    /// t.merge(first).unwrap();
    /// assert_eq!(t.validate(), Ok(()));
    /// ```
    pub fn validate(&self) -> Result<(), TreeError> {
        let n = Dim::<D>::CHILDREN;
        let slots = self.first_child.len();
        let blocks = self.block_parents().len();
        if self.level.len() != slots || slots != 1 + blocks * n {
            return Err(TreeError::Arrays {
                nodes: slots,
                blocks,
            });
        }
        let free = self.free_block_marks()?;
        let root_level = self.level(NodeId::ROOT);
        if root_level != 0 {
            return Err(TreeError::Level {
                node: NodeId::ROOT,
                level: root_level,
                expected: 0,
            });
        }
        let walk = self.walk_from_root(&free)?;
        if let Some(b) = (0..blocks).find(|&b| !walk.reached[b] && !free[b]) {
            return Err(TreeError::LostBlock(NodeId((1 + b * n) as u32)));
        }
        if walk.deepest != self.depth {
            return Err(TreeError::Depth {
                recorded: self.depth,
                actual: walk.deepest,
            });
        }
        let live = &walk.live;
        if let Some(level) = (0..live.len()).find(|&l| live[l] != self.live_blocks[l]) {
            return Err(TreeError::LiveBlocks {
                level,
                recorded: self.live_blocks[level],
                actual: live[level],
            });
        }
        Ok(())
    }

    /// The free list checked (each entry starts a block, once, and the block holds only
    /// leaves), as one mark per block.
    fn free_block_marks(&self) -> Result<Vec<bool>, TreeError> {
        let n = Dim::<D>::CHILDREN;
        let slots = self.first_child.len();
        let mut free = vec![false; self.block_parents().len()];
        for &first in &self.free_blocks {
            let f = first as usize;
            if f == 0 || f >= slots || !(f - 1).is_multiple_of(n) || free[(f - 1) / n] {
                return Err(TreeError::FreeList(first));
            }
            free[(f - 1) / n] = true;
            if let Some(c) = (f..f + n).find(|&c| self.first_child[c] != NONE) {
                return Err(TreeError::FreeNodeNotLeaf(NodeId(c as u32)));
            }
        }
        Ok(free)
    }

    /// The walk from the root, checking each internal node's child block (it starts a block,
    /// records the node as parent, is not free, is reached once, is one level deeper).
    fn walk_from_root(&self, free: &[bool]) -> Result<Walk, TreeError> {
        let mut walk = Walk {
            reached: vec![false; free.len()],
            live: vec![0u32; self.live_blocks.len()],
            deepest: 0,
        };
        let mut stack = vec![NodeId::ROOT];
        while let Some(v) = stack.pop() {
            let level = self.level(v);
            walk.deepest = walk.deepest.max(level);
            let first = self.first_child[v.index()];
            if first == NONE {
                continue;
            }
            self.check_block(v, first, free, &mut walk)?;
            walk.live[level as usize + 1] += 1;
            for c in self.children(v) {
                if self.level(c) != level + 1 {
                    return Err(TreeError::Level {
                        node: c,
                        level: self.level(c),
                        expected: level + 1,
                    });
                }
                stack.push(c);
            }
        }
        Ok(walk)
    }

    /// Checks the child block of internal node `v`, starting at `first`, and marks it reached.
    fn check_block(
        &self,
        v: NodeId,
        first: u32,
        free: &[bool],
        walk: &mut Walk,
    ) -> Result<(), TreeError> {
        let n = Dim::<D>::CHILDREN;
        let f = first as usize;
        if f == 0 || f >= self.first_child.len() || !(f - 1).is_multiple_of(n) {
            return Err(TreeError::FirstChild {
                node: v,
                first_child: first,
            });
        }
        let b = (f - 1) / n;
        let recorded = self.block_parents()[b];
        if recorded != v.0 {
            return Err(TreeError::BlockParent {
                node: v,
                first_child: NodeId(first),
                recorded: NodeId(recorded),
            });
        }
        if free[b] {
            return Err(TreeError::FreeBlockInUse(NodeId(first)));
        }
        if walk.reached[b] {
            return Err(TreeError::ReachedTwice(NodeId(first)));
        }
        walk.reached[b] = true;
        let level = self.level(v);
        if level >= Cell::<D>::MAX_LEVEL {
            return Err(TreeError::Level {
                node: NodeId(first),
                level: level.saturating_add(1),
                expected: Cell::<D>::MAX_LEVEL,
            });
        }
        Ok(())
    }
}

/// What the walk from the root counts: the blocks reached, the live blocks per level, the
/// deepest level.
struct Walk {
    reached: Vec<bool>,
    live: Vec<u32>,
    deepest: u8,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Tree<2> {
        let mut t = Tree::<2>::new();
        let first = t.split(NodeId::ROOT);
        let g = t.split(NodeId(first.0 + 1));
        t.split(NodeId(g.0 + 2));
        t.merge(NodeId(g.0 + 2)).unwrap();
        t
    }

    #[test]
    fn a_tree_built_by_its_methods_is_valid() {
        assert_eq!(sample().validate(), Ok(()));
        assert_eq!(Tree::<8>::new().validate(), Ok(()));
    }

    #[test]
    fn each_broken_invariant_is_named() {
        let t = sample();
        let mut u = t.clone();
        u.depth = 3;
        assert_eq!(
            u.validate(),
            Err(TreeError::Depth {
                recorded: 3,
                actual: 2
            })
        );
        let mut u = t.clone();
        u.first_child[1] = 3;
        assert_eq!(
            u.validate(),
            Err(TreeError::FirstChild {
                node: NodeId(1),
                first_child: 3
            })
        );
        // a second parent for the root's block
        let mut u = t.clone();
        u.first_child[4] = 1;
        assert!(matches!(u.validate(), Err(TreeError::BlockParent { .. })));
        // the freed block taken back without the split's bookkeeping
        let mut u = t.clone();
        u.first_child[7] = 9;
        assert_eq!(u.validate(), Err(TreeError::FreeBlockInUse(NodeId(9))));
        let mut u = t.clone();
        u.free_blocks.clear();
        assert_eq!(u.validate(), Err(TreeError::LostBlock(NodeId(9))));
        let mut u = t.clone();
        u.live_blocks[2] = 5;
        assert!(matches!(
            u.validate(),
            Err(TreeError::LiveBlocks { level: 2, .. })
        ));
        let mut u = t.clone();
        u.first_child[9] = 5;
        assert_eq!(u.validate(), Err(TreeError::FreeNodeNotLeaf(NodeId(9))));
        for (node, level, expected) in [(0, 1, 0), (1, 3, 1), (6, 1, 2)] {
            let mut u = t.clone();
            u.level[node] = level;
            let node = NodeId(node as u32);
            assert_eq!(
                u.validate(),
                Err(TreeError::Level {
                    node,
                    level,
                    expected
                })
            );
        }
        let mut u = t.clone();
        u.first_child.push(NONE);
        assert!(matches!(u.validate(), Err(TreeError::Arrays { .. })));
        let mut u = t;
        u.free_blocks.push(9);
        assert_eq!(u.validate(), Err(TreeError::FreeList(9)));
        assert!(u.validate().unwrap_err().to_string().contains("9"));
    }
}
