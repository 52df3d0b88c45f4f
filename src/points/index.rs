//! [`PointTree`] as the query engines and users see it: its [`SpatialIndex`] (the tree is its
//! own index: every node owns one contiguous run of the points in Morton order, carried down
//! with the node as a [`PointNode`]), and its [`PointSet`] and [`PointSetMut`] (slots are
//! positions in Morton order, so a neighbour's index is its position in
//! [`PointTree::points`]).

use super::PointTree;
use crate::error::ValidationError;
use crate::geom::{child_box, Aabb, Cell, Scalar};
use crate::query::{nearest_child_by_boxes, Metric, PointSet, SpatialIndex};
use crate::tree::NodeId;
use core::ops::Range;

/// A node of a [`PointTree`] as the query engines see it: its id, its cell and its run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PointNode<const D: usize> {
    /// The node.
    pub id: NodeId,
    /// Its cell (carried along so that boxes need no walk up the tree).
    pub cell: Cell<D>,
    /// The first index of its run of points (carried along: a node records only where its run
    /// ends relative to its parent's start).
    pub start: u32,
    /// One past the last index of its run.
    pub end: u32,
}

impl<S: Scalar, T, const D: usize> SpatialIndex<D> for PointTree<S, T, D> {
    type Scalar = S;
    type Payload = T;
    type Node = PointNode<D>;

    #[inline]
    fn points(&self) -> &[[S; D]] {
        &self.points
    }

    #[inline]
    fn payloads(&self) -> &[T] {
        &self.items
    }

    fn root(&self) -> Option<(PointNode<D>, Aabb<f64, D>)> {
        if self.is_empty() {
            return None;
        }
        let cell = Cell::root();
        let node = PointNode {
            id: NodeId::ROOT,
            cell,
            start: 0,
            end: self.len() as u32,
        };
        Some((node, self.geometry().cell_box(&cell)))
    }

    #[inline]
    fn run(&self, node: PointNode<D>) -> Range<usize> {
        node.start as usize..node.end as usize
    }

    #[inline]
    fn for_each_child(
        &self,
        node: PointNode<D>,
        f: impl FnMut(PointNode<D>, &Aabb<f64, D>),
    ) -> bool {
        let bbox = self.geometry().cell_box(&node.cell);
        self.for_each_child_in(node, &bbox, f)
    }

    /// When `q` lies in the node's closed box, the child holding it is the nearest (distance 0)
    /// and the first of those at 0 is the one the split convention gives `q` (a coordinate on a
    /// split line goes to the lower child): one comparison per axis instead of a box distance
    /// per child. Otherwise, or when that child is empty, the default.
    #[inline(always)]
    fn nearest_child<M: Metric<D>>(
        &self,
        node: PointNode<D>,
        bbox: &Aabb<f64, D>,
        q: &[f64; D],
        metric: &M,
    ) -> Option<(PointNode<D>, Aabb<f64, D>)> {
        let first = self.tree().child(node.id, 0)?;
        if bbox.contains(q) {
            let (i, child) = self.geometry().child_holding(&node.cell, bbox, q);
            let ends = self.runs().block::<D>(first);
            let start = node.start + if i == 0 { 0 } else { ends[i - 1] };
            let end = node.start + ends[i];
            if start < end {
                let id = NodeId(first.0 + i as u32);
                let cell = node.cell.child(i);
                return Some((
                    PointNode {
                        id,
                        cell,
                        start,
                        end,
                    },
                    child,
                ));
            }
        }
        nearest_child_by_boxes(self, node, bbox, q, metric)
    }

    #[inline]
    fn for_each_child_in(
        &self,
        node: PointNode<D>,
        bbox: &Aabb<f64, D>,
        mut f: impl FnMut(PointNode<D>, &Aabb<f64, D>),
    ) -> bool {
        let Some(first) = self.tree().child(node.id, 0) else {
            return false;
        };
        let mid = self.geometry().mids(&node.cell);
        let mut s = node.start;
        for (i, &end) in self.runs().block::<D>(first).iter().enumerate() {
            let e = node.start + end;
            if s == e {
                continue;
            }
            let b = child_box(bbox, &mid, i);
            f(
                PointNode {
                    id: NodeId(first.0 + i as u32),
                    cell: node.cell.child(i),
                    start: s,
                    end: e,
                },
                &b,
            );
            s = e;
        }
        true
    }
}

impl<S: Scalar, T, const D: usize> PointSet<D> for PointTree<S, T, D> {
    type Scalar = S;
    type Item = T;
    type Index = Self;

    #[inline(always)]
    fn index(&self) -> &Self {
        self
    }

    #[inline(always)]
    fn item_of<'a>(&'a self, payload: &'a T) -> &'a T {
        payload
    }

    #[inline(always)]
    fn slot_of(&self, position: usize, _: &T) -> usize {
        position
    }

    /// The items, in the order of [`PointTree::points`] (Morton order).
    #[inline]
    fn items(&self) -> &[T] {
        &self.items
    }

    #[inline]
    fn point(&self, slot: usize) -> &[S; D] {
        &self.points[slot]
    }

    #[inline]
    fn domain(&self) -> &Aabb<f64, D> {
        &self.domain
    }

    /// Checks every invariant and names the first one broken: node runs nest and partition their
    /// parent's; every point lies in its leaf's cell under the split convention and inside the
    /// domain; the points are in Morton order; a leaf holds more than the bucket size only at the
    /// maximum depth; an internal node holds more than the bucket size unless balance split it,
    /// and then the tree is balanced.
    fn validate(&self) -> Result<(), ValidationError> {
        self.check_invariants()
    }

    #[inline]
    fn len(&self) -> usize {
        self.points.len()
    }

    #[inline]
    fn iter(&self) -> impl ExactSizeIterator<Item = (&[S; D], &T)> + '_ {
        self.points.iter().zip(&self.items)
    }
}
