//! [`Runs`]: which points each node of a [`super::PointTree`] owns, in 4 bytes per node.
//!
//! The points are sorted by Morton key, so every node owns one contiguous run of them, and the
//! runs of a node's 2^D children partition its own in child order. A node therefore stores only
//! the *end of its run relative to its parent's start*; the root stores the number of points.
//! Child `i` of a node whose run starts at `s` owns `s + end[i - 1] .. s + end[i]` (with
//! `end[-1] = 0`), so:
//!
//! - a walk down from the root (every query) carries each node's absolute run and reads only the
//!   2^D ends of the block it splits into (one cache line up to D = 4);
//! - a node's run from its id alone costs a walk up, O(depth) ([`Runs::run`]);
//! - an update that adds or removes one point changes, on each level of its path, only the ends
//!   of the path node and its later siblings: O(2^D depth) ([`Runs::shift`]), where absolute
//!   runs would shift every node after the point.
//!
//! Absolute `(start, end)` pairs cost 8 bytes per node; this halves that, which brings the nodes
//! of a point tree with the default bucket under half a byte per point.

use crate::geom::Dim;
use crate::tree::{NodeId, Tree};

/// The run ends of every node, indexed by [`NodeId`]: see the module doc.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Runs {
    ends: Vec<u32>,
}

impl Runs {
    /// The runs of a tree holding only its root, which owns all `n` points.
    pub(crate) fn new(n: usize) -> Self {
        Runs {
            ends: vec![n as u32],
        }
    }

    /// The runs of the relative `ends` (one per node slot), unchecked: the tree's `validate`
    /// checks them.
    #[cfg(any(feature = "saved", feature = "serde"))]
    pub(crate) fn from_ends(ends: Vec<u32>) -> Self {
        Runs { ends }
    }

    /// The relative end of every node slot's run.
    #[inline]
    pub(crate) fn ends(&self) -> &[u32] {
        &self.ends
    }

    /// The number of points (the root's run end).
    #[inline]
    pub(crate) fn total(&self) -> u32 {
        self.ends[0]
    }

    /// The number of node slots with an end.
    #[inline]
    pub(crate) fn len(&self) -> usize {
        self.ends.len()
    }

    /// The relative ends of the 2^D children in the block starting at node `first`.
    #[inline]
    pub(crate) fn block<const D: usize>(&self, first: NodeId) -> &[u32] {
        let f = first.index();
        &self.ends[f..f + Dim::<D>::CHILDREN]
    }

    /// The start of `id`'s run relative to its parent's start.
    #[inline]
    fn relative_start<const D: usize>(&self, id: NodeId) -> u32 {
        if id.0 == 0 || (id.0 - 1) as usize & (Dim::<D>::CHILDREN - 1) == 0 {
            0
        } else {
            self.ends[id.index() - 1]
        }
    }

    /// The number of points in `id`'s run: O(1).
    #[inline]
    pub(crate) fn count<const D: usize>(&self, id: NodeId) -> u32 {
        self.ends[id.index()] - self.relative_start::<D>(id)
    }

    /// The absolute run `(start, end)` of `id`, by a walk up to the root: O(depth).
    pub(crate) fn run<const D: usize>(&self, tree: &Tree<D>, id: NodeId) -> (u32, u32) {
        let mut start = 0;
        let mut v = id;
        while let Some(parent) = tree.parent(v) {
            start += self.relative_start::<D>(v);
            v = parent;
        }
        (start, start + self.count::<D>(id))
    }

    /// Sets the children of `v` (just split, its run starting at `start`) to the runs ending at
    /// the absolute indices `ends` (one per child, in child order).
    pub(crate) fn set_children<const D: usize>(
        &mut self,
        tree: &Tree<D>,
        v: NodeId,
        start: u32,
        ends: impl IntoIterator<Item = u32>,
    ) {
        let first = tree.child(v, 0).expect("v has children").index();
        if self.ends.len() < tree.node_count() {
            self.ends.resize(tree.node_count(), 0);
        }
        for (slot, end) in self.ends[first..first + Dim::<D>::CHILDREN]
            .iter_mut()
            .zip(ends)
        {
            *slot = end - start;
        }
    }

    /// Sets the relative end of `id`'s run (the out-of-core build closes each child's run when
    /// its last point has arrived, and the root's at the end).
    #[cfg(feature = "saved")]
    pub(crate) fn set_end(&mut self, id: NodeId, end: u32) {
        self.ends[id.index()] = end;
    }

    /// After one point was added (`delta` 1) to or removed (-1) from the run of the leaf at the
    /// end of `path` (root first): every node on the path, and every later sibling of one, ends
    /// `delta` further from its parent's start. O(2^D depth).
    pub(crate) fn shift<const D: usize>(&mut self, path: &[NodeId], delta: i32) {
        let add = |x: &mut u32| *x = x.wrapping_add_signed(delta);
        add(&mut self.ends[0]);
        for &v in &path[1.min(path.len())..] {
            // Blocks hold nodes 1 + b 2^D ..: `v` and its later siblings run to the block's end.
            let i = v.index();
            let first = i - ((i - 1) & (Dim::<D>::CHILDREN - 1));
            for e in &mut self.ends[i..first + Dim::<D>::CHILDREN] {
                add(e);
            }
        }
    }

    /// Gives back spare capacity.
    pub(crate) fn shrink_to_fit(&mut self) {
        self.ends.shrink_to_fit();
    }

    /// Heap bytes used.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.ends.capacity() * core::mem::size_of::<u32>()
    }
}
