//! [`PointTreeView`] as the query engines see it: its [`SpatialIndex`] (the saved arrays walked
//! as the owned tree walks its own: each node carried down with its cell and absolute run, as a
//! [`PointNode`]) and its [`PointSet`], so every query, join and batch of the crate runs on a
//! view unchanged. Slots are positions in the saved points, as in
//! [`PointTree`](crate::PointTree).
//!
//! The indices followed here were checked when the view was opened (`view.rs`), so the slices
//! are indexed directly.

use super::view::PointTreeView;
use super::SavedScalar;
use crate::error::ValidationError;
use crate::geom::{child_box, Aabb, Cell, Dim};
use crate::points::PointNode;
use crate::query::{nearest_child_by_boxes, Metric, PointSet, SpatialIndex};
use crate::tree::NodeId;
use bytemuck::Pod;
use core::ops::Range;

/// A leaf's marker in the first children.
const NONE: u32 = u32::MAX;

impl<S: SavedScalar, T: Pod, const D: usize> PointTreeView<'_, S, T, D> {
    /// The relative run ends of the block whose first node is `first`.
    #[inline]
    fn block(&self, first: u32) -> &[u32] {
        let f = first as usize;
        &self.run_ends[f..f + Dim::<D>::CHILDREN]
    }

    /// The first child of `node`, `None` for a leaf.
    #[inline]
    fn first_child_of(&self, node: &PointNode<D>) -> Option<u32> {
        let f = self.first_child[node.id.index()];
        (f != NONE).then_some(f)
    }
}

impl<S: SavedScalar, T: Pod, const D: usize> SpatialIndex<D> for PointTreeView<'_, S, T, D> {
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
        if self.points.is_empty() {
            return None;
        }
        let cell = Cell::root();
        let node = PointNode {
            id: NodeId::ROOT,
            cell,
            start: 0,
            end: self.points.len() as u32,
        };
        Some((node, self.geometry.cell_box(&cell)))
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
        let bbox = self.geometry.cell_box(&node.cell);
        self.for_each_child_in(node, &bbox, f)
    }

    /// As the owned tree's: the child holding `q` under the split convention when `q` lies in
    /// the node's box and that child has points, else the default.
    #[inline(always)]
    fn nearest_child<M: Metric<D>>(
        &self,
        node: PointNode<D>,
        bbox: &Aabb<f64, D>,
        q: &[f64; D],
        metric: &M,
    ) -> Option<(PointNode<D>, Aabb<f64, D>)> {
        let first = self.first_child_of(&node)?;
        if bbox.contains(q) {
            let (i, child) = self.geometry.child_holding(&node.cell, bbox, q);
            let ends = self.block(first);
            let start = node.start + if i == 0 { 0 } else { ends[i - 1] };
            let end = node.start + ends[i];
            if start < end {
                let id = NodeId(first + i as u32);
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
        let Some(first) = self.first_child_of(&node) else {
            return false;
        };
        let mid = self.geometry.mids(&node.cell);
        let mut s = node.start;
        for (i, &end) in self.block(first).iter().enumerate() {
            let e = node.start + end;
            if s == e {
                continue;
            }
            let b = child_box(bbox, &mid, i);
            f(
                PointNode {
                    id: NodeId(first + i as u32),
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

impl<S: SavedScalar, T: Pod, const D: usize> PointSet<D> for PointTreeView<'_, S, T, D> {
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

    /// The items, in the order of [`PointTreeView::points`].
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

    /// The check of [`PointTreeView::open`] again (the structure and every point), on rayon's
    /// threads with feature `rayon`.
    fn validate(&self) -> Result<(), ValidationError> {
        match Self::open_unchecked(self.bytes()) {
            Ok((_, leaves)) => self.check_points(&leaves, true),
            Err(super::SavedError::Invalid(e)) => Err(e),
            Err(e) => {
                Err(ValidationError::new(crate::error::Invariant::Settings).detail(e.to_string()))
            }
        }
    }

    #[inline]
    fn len(&self) -> usize {
        self.points.len()
    }

    #[inline]
    fn iter(&self) -> impl ExactSizeIterator<Item = (&[S; D], &T)> + '_ {
        self.points.iter().zip(self.items.iter())
    }
}
