//! [`DynamicIndex`]: a [`DynamicPointTree`](super::DynamicPointTree)'s topology, node counts and
//! chunks, as the [`SpatialIndex`] the shared query engines run on (without nested runs: only a
//! leaf's chunk is a run). Its payloads are slots, which the tree's
//! [`PointSet`](crate::query::PointSet) maps to its items.

use super::pool::Pool;
use super::NodeData;
use crate::geom::Halves;
use crate::geom::{child_box, Aabb, Cell, RootGeometry, Scalar};
use crate::query::{Metric, SpatialIndex};
use crate::tree::{NodeId, Tree};
use core::ops::Range;

/// The index of a [`DynamicPointTree`](super::DynamicPointTree): its [`SpatialIndex::points`] are the chunk array (with
/// gaps no run covers) and its payloads the slots of the tree's items.
#[derive(Clone, Debug)]
pub struct DynamicIndex<S, const D: usize> {
    pub(super) tree: Tree<D>,
    pub(super) geometry: RootGeometry<D>,
    pub(super) nodes: Vec<NodeData>,
    pub(super) pool: Pool<S, D>,
}

/// A node of a [`DynamicIndex`] as the engines see it: its id and its cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DynamicNode<const D: usize> {
    /// The node.
    pub id: NodeId,
    /// Its cell (carried along so that boxes need no walk up the tree).
    pub cell: Cell<D>,
}

impl<S: Scalar, const D: usize> DynamicIndex<S, D> {
    /// Child `i` of `node`, whose children start at `first`.
    #[inline]
    fn child(node: DynamicNode<D>, first: NodeId, i: usize) -> DynamicNode<D> {
        DynamicNode {
            id: NodeId(first.0 + i as u32),
            cell: node.cell.child(i),
        }
    }

    /// The non-empty children `i` of `node` with `i & mask == want` (bit `a` of a child's
    /// number set: the upper half along axis `a`), with their boxes; `false` for a leaf.
    #[inline(always)]
    fn for_each_child_where(
        &self,
        node: DynamicNode<D>,
        bbox: &Aabb<f64, D>,
        (mask, want): (usize, usize),
        mut f: impl FnMut(DynamicNode<D>, &Aabb<f64, D>),
    ) -> bool {
        let Some(first) = self.tree.child(node.id, 0) else {
            return false;
        };
        let mid = self.geometry.mids(&node.cell);
        for i in 0..1 << D {
            if i & mask == want && self.nodes[first.index() + i].count != 0 {
                f(Self::child(node, first, i), &child_box(bbox, &mid, i));
            }
        }
        true
    }
}

impl<S: Scalar, const D: usize> SpatialIndex<D> for DynamicIndex<S, D> {
    type Scalar = S;
    type Payload = u32;
    type Node = DynamicNode<D>;
    const NESTED_RUNS: bool = false;
    const LEAVES_OUT_HALVES: bool = true;

    #[inline]
    fn points(&self) -> &[[S; D]] {
        &self.pool.points
    }

    #[inline]
    fn payloads(&self) -> &[u32] {
        &self.pool.slots
    }

    fn root(&self) -> Option<(DynamicNode<D>, Aabb<f64, D>)> {
        if self.nodes[0].count == 0 {
            return None;
        }
        let cell = Cell::root();
        let node = DynamicNode {
            id: NodeId::ROOT,
            cell,
        };
        Some((node, self.geometry.cell_box(&cell)))
    }

    #[inline]
    fn run(&self, node: DynamicNode<D>) -> Range<usize> {
        if !self.tree.is_leaf(node.id) {
            return 0..0;
        }
        let d = self.nodes[node.id.index()];
        d.start as usize..(d.start + d.count) as usize
    }

    #[inline]
    fn count(&self, node: DynamicNode<D>) -> usize {
        self.nodes[node.id.index()].count as usize
    }

    #[inline]
    fn for_each_child(
        &self,
        node: DynamicNode<D>,
        f: impl FnMut(DynamicNode<D>, &Aabb<f64, D>),
    ) -> bool {
        let bbox = self.geometry.cell_box(&node.cell);
        self.for_each_child_in(node, &bbox, f)
    }

    #[inline]
    fn for_each_child_in(
        &self,
        node: DynamicNode<D>,
        bbox: &Aabb<f64, D>,
        f: impl FnMut(DynamicNode<D>, &Aabb<f64, D>),
    ) -> bool {
        self.for_each_child_where(node, bbox, (0, 0), f)
    }

    /// As [`PointTree`](crate::PointTree)'s: from 4D up the halves of the node that are out
    /// are left out whole ([`Halves`]); in 2D and 3D every child.
    #[inline(always)]
    fn for_each_child_unless(
        &self,
        node: DynamicNode<D>,
        bbox: &Aabb<f64, D>,
        out: impl Halves<D>,
        f: impl FnMut(DynamicNode<D>, &Aabb<f64, D>),
    ) -> bool {
        if D < 4 || self.tree.child(node.id, 0).is_none() {
            return self.for_each_child_in(node, bbox, f);
        }
        match out.kept(bbox, &self.geometry.mids(&node.cell)) {
            Some(kept) => self.for_each_child_where(node, bbox, kept, f),
            None => true, // every child is out: an inner node all the same
        }
    }

    /// The child holding `q` by the split lines when `q` lies in the node's box (as
    /// [`PointTree`](crate::PointTree)'s), else, or when that child is empty, the default.
    #[inline]
    fn nearest_child<M: Metric<D>>(
        &self,
        node: DynamicNode<D>,
        bbox: &Aabb<f64, D>,
        q: &[f64; D],
        metric: &M,
    ) -> Option<(DynamicNode<D>, Aabb<f64, D>)> {
        let first = self.tree.child(node.id, 0)?;
        if bbox.contains(q) {
            let (i, child) = self.geometry.child_holding(&node.cell, bbox, q);
            if self.nodes[first.index() + i].count != 0 {
                return Some((Self::child(node, first, i), child));
            }
        }
        crate::query::nearest_child_by_boxes(self, node, bbox, q, metric)
    }
}
