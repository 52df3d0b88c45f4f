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
//! both are found on the same key. The splits are the in-memory build's own code (the arena's
//! split, the build's split rule and its partition of a run among the children), so the arrays
//! are equal, slot for slot, to the in-memory build's, and the saved files are equal byte for
//! byte (tested against it).

use crate::geom::{digit, same_cell, Dim};
use crate::points::{partition_children, splits, Runs};
use crate::tree::{NodeId, Tree};

/// A node on the path from the root to the leaf of the latest key.
#[derive(Clone, Copy, Debug)]
struct Open {
    node: NodeId,
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
    bucket_size: usize,
    max_depth: u8,
    /// The nodes.
    pub tree: Tree<D>,
    /// Their runs (each child's closed when its last key has arrived).
    pub runs: Runs,
    path: Vec<Open>,
    /// The keys of the current leaf's points while it may still split (at most the bucket
    /// size plus one; empty for a leaf at the maximum depth).
    leaf_keys: Vec<u64>,
    /// Keys pushed so far.
    len: u64,
}

impl<const D: usize> Topology<D> {
    /// An empty tree (a root leaf) for leaves of `bucket_size` points above `max_depth`.
    pub fn new(bucket_size: usize, max_depth: u8) -> Self {
        Topology {
            bucket_size,
            max_depth,
            tree: Tree::new(),
            runs: Runs::new(0),
            path: vec![Open {
                node: NodeId::ROOT,
                level: 0,
                start: 0,
                child: 0,
            }],
            leaf_keys: Vec::new(),
            len: 0,
        }
    }

    /// Sets the relative ends of `open`'s children `open.child..upto` to `at` (absolute);
    /// nothing for a leaf.
    fn close_children(&mut self, open: &Open, upto: usize, at: u64) {
        if let Some(first) = self.tree.child(open.node, 0) {
            for c in open.child..upto {
                let child = NodeId(first.0 + c as u32);
                self.runs.set_end(child, (at - open.start) as u32);
            }
        }
    }

    /// Adds the next key (not below the previous one, `last`).
    ///
    /// # Panics
    /// When the node arrays would pass 2^32 - 1 slots (more than `u32::MAX` points cannot
    /// come here: the caller refuses them first).
    pub fn push(&mut self, key: u64, last: Option<u64>) {
        let i = self.len;
        self.len += 1;
        // Close the nodes that do not hold the key (any key a node holds agrees with the
        // latest above its level).
        if let Some(last) = last {
            while self.path.len() > 1 {
                let top = *self.path.last().expect("the root stays");
                if same_cell::<D>(last, key, top.level) {
                    break;
                }
                self.close_children(&top, Dim::<D>::CHILDREN, i);
                self.path.pop();
                self.leaf_keys.clear();
            }
        }
        // Descend to the leaf holding the key.
        loop {
            let top = *self.path.last().expect("the root stays");
            let Some(first) = self.tree.child(top.node, 0) else {
                break;
            };
            let d = digit::<D>(key, top.level);
            self.close_children(&top, d, i);
            self.path.last_mut().expect("the root stays").child = d;
            self.path.push(Open {
                node: NodeId(first.0 + d as u32),
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
    /// depth, handing its points to the new children: those before the latest key's child are
    /// closed, that child is the new leaf (its end and its later siblings' are set when it
    /// closes).
    fn split_while_full(&mut self) {
        loop {
            let leaf = *self.path.last().expect("a leaf");
            let keys = &self.leaf_keys;
            if !splits(keys.len(), leaf.level, self.bucket_size, self.max_depth) {
                return;
            }
            let first = self.tree.split(leaf.node);
            let s = leaf.start as u32;
            let run = (s, s + keys.len() as u32);
            partition_children(&self.tree, &mut self.runs, leaf.node, run, |j| {
                keys[j - s as usize]
            });
            let latest = digit::<D>(*keys.last().expect("more than the bucket"), leaf.level);
            let child_start = match latest {
                0 => 0,
                c => self.runs.block::<D>(first)[c - 1] as usize,
            };
            self.path.last_mut().expect("a leaf").child = latest;
            self.path.push(Open {
                node: NodeId(first.0 + latest as u32),
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
            self.close_children(&top, Dim::<D>::CHILDREN, n);
        }
        self.runs.set_end(NodeId::ROOT, n as u32);
        self.leaf_keys = Vec::new();
    }

    /// The node slots.
    pub fn slots(&self) -> u64 {
        self.tree.node_count() as u64
    }
}
