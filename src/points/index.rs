//! A point tree as the query engines and users see it, written once for the owned
//! [`PointTree`] and the saved tree's borrowed view (`io::saved::PointTreeView`):
//!
//! - [`PointArrays`]: the arrays a query walks, borrowed (the points and items in Morton order,
//!   each node slot's first child and run end, the root geometry), and their [`SpatialIndex`]:
//!   every node owns one contiguous run of the points, carried down with the node as a
//!   [`PointNode`], so a child's run is read from the 2^D run ends of its block (`runs.rs`);
//! - `point_index!`, through which each tree implements [`SpatialIndex`] by lending its
//!   arrays, and [`PointSet`] (slots are positions in Morton order, so a neighbour's index is
//!   its position in [`PointTree::points`]);
//! - [`PointTree`]'s own use of them.

use super::PointTree;
use crate::geom::Halves;
use crate::geom::{child_box, Aabb, Cell, Dim, RootGeometry, Scalar};
use crate::query::{nearest_child_by_boxes, Metric, SpatialIndex};
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

/// A leaf's marker in the first children (as the arena's).
const NONE: u32 = u32::MAX;

/// The arrays of a point tree the query engines walk, borrowed from the owned tree or from
/// saved bytes (see the module doc). The links followed are trusted: the owned tree keeps them,
/// the view checked them when it was opened.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PointArrays<'a, S, T, const D: usize> {
    /// The points in Morton order.
    pub points: &'a [[S; D]],
    /// Their items.
    pub items: &'a [T],
    /// Per node slot, the id of its first child, `u32::MAX` for a leaf.
    pub first_child: &'a [u32],
    /// Per node slot, the end of its run relative to its parent's start.
    pub run_ends: &'a [u32],
    /// Where the cells lie.
    pub geometry: &'a RootGeometry<D>,
}

impl<S, T, const D: usize> PointArrays<'_, S, T, D> {
    /// The first child of `node`, `None` for a leaf.
    #[inline(always)]
    fn first_child_of(&self, node: &PointNode<D>) -> Option<u32> {
        let f = self.first_child[node.id.index()];
        (f != NONE).then_some(f)
    }

    /// The relative run ends of the block whose first node is `first`.
    #[inline(always)]
    fn block(&self, first: u32) -> &[u32] {
        let f = first as usize;
        &self.run_ends[f..f + Dim::<D>::CHILDREN]
    }
}

impl<S: Scalar, T, const D: usize> SpatialIndex<D> for PointArrays<'_, S, T, D> {
    type Scalar = S;
    type Payload = T;
    type Node = PointNode<D>;
    const LEAVES_OUT_HALVES: bool = true;

    #[inline]
    fn points(&self) -> &[[S; D]] {
        self.points
    }

    #[inline]
    fn payloads(&self) -> &[T] {
        self.items
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
        f: impl FnMut(PointNode<D>, &Aabb<f64, D>),
    ) -> bool {
        self.for_each_child_where(node, bbox, (0, 0), f)
    }

    /// From 4D up (2^D children, each costing D operations to bound), `out` is asked of the
    /// halves of `bbox` on either side of each split line first: a child in a half that is out
    /// is left out without its box (2 D calls for the node instead of 2^D). For the k-nearest
    /// search, a half is out when its box distance exceeds the bound. 10^6 uniform
    /// points, kiddo's `ImmutableKdTree` beside, two alternated rounds: 8D 2 x 10^4 1-NN
    /// 1725-1739 -> 470-487 ms (kiddo 414-503), 10-NN 2976-3003 -> 1402-1427 (1211-1351); 6D
    /// 5 x 10^4 10-NN 1515-1549 -> 1120-1169; 4D 10^5 10-NN 466-471 -> 441-444, 5D 982-983 ->
    /// 853-857. Region queries leave out the halves outside the region: 2 x 10^4 balls of
    /// about 40 points, 8D 4511-4574 -> 2061-2098 ms, 6D 1001-1026 -> 815-829. In 2D and 3D
    /// every child.
    #[inline(always)]
    fn for_each_child_unless(
        &self,
        node: PointNode<D>,
        bbox: &Aabb<f64, D>,
        out: impl Halves<D>,
        f: impl FnMut(PointNode<D>, &Aabb<f64, D>),
    ) -> bool {
        if D < 4 || self.first_child_of(&node).is_none() {
            return self.for_each_child_in(node, bbox, f);
        }
        match out.kept(bbox, &self.geometry.mids(&node.cell)) {
            Some(kept) => self.for_each_child_where(node, bbox, kept, f),
            None => true, // every child is out: an inner node all the same
        }
    }
}

impl<S, T, const D: usize> PointArrays<'_, S, T, D> {
    /// The non-empty children `i` of `node` with `i & mask == want` (bit `a` of a child's
    /// number set: the upper half along axis `a`), with their boxes; `false` for a leaf.
    #[inline(always)]
    fn for_each_child_where(
        &self,
        node: PointNode<D>,
        bbox: &Aabb<f64, D>,
        (mask, want): (usize, usize),
        mut f: impl FnMut(PointNode<D>, &Aabb<f64, D>),
    ) -> bool {
        let Some(first) = self.first_child_of(&node) else {
            return false;
        };
        let mid = self.geometry.mids(&node.cell);
        let mut s = node.start;
        for (i, &end) in self.block(first).iter().enumerate() {
            let e = node.start + end;
            if s == e || i & mask != want {
                s = e;
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

/// Implements [`SpatialIndex`] by the type's `arrays()` (its [`PointArrays`]) and
/// [`PointSet`](crate::PointSet) on its fields `points`, `items` and `domain`, for a point tree
/// over `S` coordinates and `T` items, whose `validate` calls the method named, documented by
/// the attributes given:
///
/// ```ignore
/// point_index!(impl[S: Scalar, T, const D: usize] PointTree<S, T, D>, check_invariants);
/// ```
macro_rules! point_index {
    (impl[$($g:tt)*] $ty:ty, $(#[$doc:meta])* $validate:ident) => {
        impl<$($g)*> $crate::query::SpatialIndex<D> for $ty {
            type Scalar = S;
            type Payload = T;
            type Node = $crate::points::PointNode<D>;
            const LEAVES_OUT_HALVES: bool = true;

            #[inline]
            fn points(&self) -> &[[S; D]] {
                &self.points
            }

            #[inline]
            fn payloads(&self) -> &[T] {
                &self.items
            }

            fn root(&self) -> Option<(Self::Node, $crate::Aabb<f64, D>)> {
                self.arrays().root()
            }

            #[inline]
            fn run(&self, node: Self::Node) -> core::ops::Range<usize> {
                node.start as usize..node.end as usize
            }

            #[inline]
            fn for_each_child(
                &self,
                node: Self::Node,
                f: impl FnMut(Self::Node, &$crate::Aabb<f64, D>),
            ) -> bool {
                self.arrays().for_each_child(node, f)
            }

            /// When `q` lies in the node's closed box, the child holding it under the split
            /// convention (a coordinate on a split line goes to the lower child), if it has
            /// points: one comparison per axis instead of a box distance per child. Otherwise
            /// the default.
            #[inline(always)]
            fn nearest_child<M: $crate::Metric<D>>(
                &self,
                node: Self::Node,
                bbox: &$crate::Aabb<f64, D>,
                q: &[f64; D],
                metric: &M,
            ) -> Option<(Self::Node, $crate::Aabb<f64, D>)> {
                self.arrays().nearest_child(node, bbox, q, metric)
            }

            #[inline]
            fn for_each_child_in(
                &self,
                node: Self::Node,
                bbox: &$crate::Aabb<f64, D>,
                f: impl FnMut(Self::Node, &$crate::Aabb<f64, D>),
            ) -> bool {
                self.arrays().for_each_child_in(node, bbox, f)
            }

            #[inline(always)]
            fn for_each_child_unless(
                &self,
                node: Self::Node,
                bbox: &$crate::Aabb<f64, D>,
                out: impl $crate::geom::Halves<D>,
                f: impl FnMut(Self::Node, &$crate::Aabb<f64, D>),
            ) -> bool {
                self.arrays().for_each_child_unless(node, bbox, out, f)
            }
        }

        impl<$($g)*> $crate::PointSet<D> for $ty {
            type Scalar = S;
            type Item = T;
            type Index = Self;

            #[inline(always)]
            fn index(&self) -> &Self {
                self
            }

            #[inline(always)]
            fn item_of<'p>(&'p self, payload: &'p T) -> &'p T {
                payload
            }

            #[inline(always)]
            fn slot_of(&self, position: usize, _: &T) -> usize {
                position
            }

            #[inline]
            fn position_slots(&self) -> $crate::query::PositionSlots<'_> {
                $crate::query::PositionSlots::Same
            }

            /// The items, in the order of the points (Morton order).
            #[inline]
            fn items(&self) -> &[T] {
                &self.items
            }

            #[inline]
            fn point(&self, slot: usize) -> &[S; D] {
                &self.points[slot]
            }

            #[inline]
            fn domain(&self) -> &$crate::Aabb<f64, D> {
                &self.domain
            }

            $(#[$doc])*
            fn validate(&self) -> Result<(), $crate::ValidationError> {
                self.$validate()
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
    };
}
#[cfg(feature = "saved")]
pub(crate) use point_index;

impl<S: Scalar, T, const D: usize> PointTree<S, T, D> {
    /// The arrays the queries walk.
    #[inline(always)]
    pub(crate) fn arrays(&self) -> PointArrays<'_, S, T, D> {
        PointArrays {
            points: &self.points,
            items: &self.items,
            first_child: self.tree.link_arrays().0,
            run_ends: self.runs.ends(),
            geometry: &self.geometry,
        }
    }
}

point_index!(
    impl[S: Scalar, T, const D: usize] PointTree<S, T, D>,
    /// Checks every invariant and names the first one broken: node runs nest and partition
    /// their parent's; every point lies in its leaf's cell under the split convention and
    /// inside the domain; the points are in Morton order; a leaf holds more than the bucket
    /// size only at the maximum depth; an internal node holds more than the bucket size unless
    /// balance split it, and then the tree is balanced.
    check_invariants
);
