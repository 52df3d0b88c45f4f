//! The node arrays of a [`PointTree`](crate::PointTree) built from its points' Morton keys
//! streamed in sorted order, one key at a time, in memory proportional to the nodes (not the
//! points): what the out-of-core build ([`super::external`]) writes after the points.
//!
//! The in-memory build splits nodes depth first in child order, each split appending one block
//! of `2^D` children; a node splits when it holds more than the bucket size and lies above the
//! maximum depth. Streaming the sorted keys reproduces that order exactly: a node is found to
//! need a split when its `bucket + 1`-th key arrives, and at that moment every node before it
//! in pre-order has already been found (an ancestor holds at least as many keys; a node before
//! it in Morton order has seen all its keys), with an ancestor split before its descendant when
//! both are found on the same key. So the arrays are equal, slot for slot, to the in-memory
//! build's, and the saved files are equal byte for byte (tested against it).

use crate::geom::{Cell, Dim};

/// Marks a leaf in `first_child` (as the arena does).
const NONE: u32 = u32::MAX;

/// A node on the path from the root to the leaf of the latest key.
#[derive(Clone, Copy, Debug)]
struct Open {
    node: u32,
    level: u8,
    /// The absolute index of its first point.
    start: u64,
    /// For an internal node: the child the latest key went to (children before it are closed).
    child: usize,
}

/// The tree's node arrays, grown as sorted keys arrive ([`Topology::push`]) and completed by
/// [`Topology::finish`].
#[derive(Debug)]
pub(super) struct Topology<const D: usize> {
    bucket_size: u64,
    max_depth: u8,
    pub first_child: Vec<u32>,
    pub level: Vec<u8>,
    pub block_parent: Vec<u32>,
    pub run_ends: Vec<u32>,
    pub live_blocks: Vec<u32>,
    pub depth: u8,
    path: Vec<Open>,
    /// The keys of the current leaf's points while it may still split (at most the bucket
    /// size plus one; empty for a leaf at the maximum depth).
    leaf_keys: Vec<u64>,
    /// Keys pushed so far.
    len: u64,
}

/// The child digit of `key` below a node at `level` (as the in-memory build's).
#[inline]
fn digit<const D: usize>(key: u64, level: u8) -> usize {
    let shift = D as u32 * u32::from(Cell::<D>::MAX_LEVEL - level - 1);
    ((key >> shift) as usize) & (Dim::<D>::CHILDREN - 1)
}

/// Whether the node at `level` holding the point of key `first` holds the point of key `key`.
#[inline]
fn contains<const D: usize>(first: u64, key: u64, level: u8) -> bool {
    let shift = D as u32 * u32::from(Cell::<D>::MAX_LEVEL - level);
    shift >= 64 || (first >> shift) == (key >> shift)
}

impl<const D: usize> Topology<D> {
    /// An empty tree (a root leaf) for leaves of `bucket_size` points above `max_depth`.
    pub fn new(bucket_size: usize, max_depth: u8) -> Self {
        Topology {
            bucket_size: bucket_size as u64,
            max_depth,
            first_child: vec![NONE],
            level: vec![0],
            block_parent: Vec::new(),
            run_ends: vec![0],
            live_blocks: vec![0; Cell::<D>::MAX_LEVEL as usize + 1],
            depth: 0,
            path: vec![Open {
                node: 0,
                level: 0,
                start: 0,
                child: 0,
            }],
            leaf_keys: Vec::new(),
            len: 0,
        }
    }

    /// Sets the relative ends of `open`'s children `open.child..upto` to `at` (absolute).
    fn close_children(&mut self, open: &Open, upto: usize, at: u64) {
        let first = self.first_child[open.node as usize] as usize;
        for c in open.child..upto {
            self.run_ends[first + c] = (at - open.start) as u32;
        }
    }

    /// The key of the path node `open`'s first point: any key it holds agrees above its
    /// level, so the latest key serves for the nodes still open.
    fn holds(&self, open: &Open, last: u64, key: u64) -> bool {
        contains::<D>(last, key, open.level)
    }

    /// Adds the next key (not below the previous one).
    ///
    /// # Panics
    /// When the node arrays would pass 2^32 - 1 slots (more than `u32::MAX` points cannot
    /// come here: the caller refuses them first).
    pub fn push(&mut self, key: u64, last: Option<u64>) {
        let i = self.len;
        self.len += 1;
        // Close the nodes that do not hold the key.
        if let Some(last) = last {
            while self.path.len() > 1 {
                let top = *self.path.last().expect("the root stays");
                if self.holds(&top, last, key) {
                    break;
                }
                if self.first_child[top.node as usize] != NONE {
                    self.close_children(&top, Dim::<D>::CHILDREN, i);
                }
                self.path.pop();
                self.leaf_keys.clear();
            }
        }
        // Descend to the leaf holding the key.
        loop {
            let top = *self.path.last().expect("the root stays");
            let first = self.first_child[top.node as usize];
            if first == NONE {
                break;
            }
            let d = digit::<D>(key, top.level);
            self.close_children(&top, d, i);
            self.path.last_mut().expect("the root stays").child = d;
            self.path.push(Open {
                node: first + d as u32,
                level: top.level + 1,
                start: i,
                child: 0,
            });
            self.leaf_keys.clear();
        }
        let leaf = *self.path.last().expect("a leaf");
        if leaf.level >= self.max_depth {
            return;
        }
        self.leaf_keys.push(key);
        self.split_while_full();
    }

    /// Splits the current leaf while it holds more than the bucket size above the maximum
    /// depth, handing its points to the new children.
    fn split_while_full(&mut self) {
        loop {
            let leaf = *self.path.last().expect("a leaf");
            if (self.leaf_keys.len() as u64) <= self.bucket_size || leaf.level >= self.max_depth {
                return;
            }
            let first = self.first_child.len();
            let n = Dim::<D>::CHILDREN;
            assert!(first + n < NONE as usize, "more than 2^32 - 1 node slots");
            self.first_child.resize(first + n, NONE);
            self.level.resize(first + n, leaf.level + 1);
            self.run_ends.resize(first + n, 0);
            self.block_parent.push(leaf.node);
            self.first_child[leaf.node as usize] = first as u32;
            self.live_blocks[leaf.level as usize + 1] += 1;
            self.depth = self.depth.max(leaf.level + 1);
            let mut open = leaf;
            let mut child_start = 0usize;
            for (j, &k) in self.leaf_keys.iter().enumerate() {
                let d = digit::<D>(k, leaf.level);
                if d != open.child {
                    // The children before `d` end here (the one being filled, empty ones).
                    for c in open.child..d {
                        self.run_ends[first + c] = j as u32;
                    }
                    child_start = j;
                    open.child = d;
                }
            }
            *self.path.last_mut().expect("a leaf") = open;
            self.path.push(Open {
                node: (first + open.child) as u32,
                level: leaf.level + 1,
                start: leaf.start + child_start as u64,
                child: 0,
            });
            self.leaf_keys.drain(..child_start);
        }
    }

    /// Closes every open node after the last of `n` keys.
    pub fn finish(&mut self) {
        let n = self.len;
        while let Some(top) = self.path.pop() {
            if self.first_child[top.node as usize] != NONE {
                self.close_children(&top, Dim::<D>::CHILDREN, n);
            }
        }
        self.run_ends[0] = n as u32;
        self.leaf_keys = Vec::new();
    }

    /// The node slots.
    pub fn slots(&self) -> u64 {
        self.first_child.len() as u64
    }
}
