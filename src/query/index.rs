//! [`SpatialIndex`]: the little a query engine needs from a tree (a root, children with their
//! closed boxes, and one contiguous run of points per node), and its implementation for
//! [`PointTree`].
//!
//! The engines in this module ([`range`](super::range), nearest neighbours, the nearest iterator)
//! are written against this trait only, so any hierarchy of boxes over a sorted point array (the
//! point tree, a compressed quadtree) gets every query by implementing five methods: the trait's
//! provided methods ([`SpatialIndex::query`], [`SpatialIndex::k_nearest_by`], ...) are the
//! engines' entry points, which [`crate::CompressedTree`] calls.

use super::knn::{k_nearest, Neighbor};
use super::metric::Metric;
use super::nearest_iter::NearestIter;
use super::range::{for_each_in, scan_limit, QueryStats, RegionIter};
use super::region::Region;
use super::{check_max, query_point, QueryError};
use crate::geom::{Aabb, Cell, Scalar};
use crate::points::{child_box, PointTree};
use crate::tree::NodeId;
use core::ops::Range;

/// A neighbour found in index `I`.
type NeighborIn<'a, I, const D: usize> =
    Neighbor<'a, <I as SpatialIndex<D>>::Scalar, <I as SpatialIndex<D>>::Item, D>;

/// The answer of [`SpatialIndex::k_nearest_by`].
type Neighbors<'a, I, const D: usize> = Vec<NeighborIn<'a, I, D>>;

/// A tree of closed boxes over one array of points, each node owning a contiguous run of it.
///
/// Contract: the run of a node is the union of its children's runs; every point of a node's run
/// lies in the node's closed box (as `f64`); a node without children is a leaf. An index whose
/// leaves keep their points apart (a [`crate::DynamicPointTree`]'s leaves are blocks with
/// slack, anywhere in its array) sets [`SpatialIndex::NESTED_RUNS`] to `false`: then only
/// leaves have runs (an inner node's is empty) and [`SpatialIndex::count`] counts a node's
/// points.
///
/// ```
/// use orthtree::query::SpatialIndex;
/// use orthtree::Quadtree;
/// let t = Quadtree::new(&[([0.0, 0.0], 'a'), ([1.0, 1.0], 'b')]).unwrap();
/// let (root, bbox) = t.root().unwrap();
/// assert_eq!(t.run(root), 0..2);
/// assert!(bbox.contains(&[1.0, 1.0]));
/// let mut children = 0;
/// let internal = t.for_each_child(root, |_, _| children += 1);
/// assert_eq!((internal, children), (false, 0)); // two points fit one bucket
/// ```
pub trait SpatialIndex<const D: usize> {
    /// The coordinate type of the points.
    type Scalar: Scalar;
    /// The payload stored with each point.
    type Item;
    /// A handle on a node, small and cheap to copy.
    type Node: Copy + PartialEq;

    /// `true` when every node owns one contiguous run, the union of its children's (the
    /// engines then scan a small inner node's run without descending, and report an inside
    /// node's run whole); `false` when only leaves have runs (the engines then descend to the
    /// leaves). Decided at compile time: the engines' other branch is not generated.
    const NESTED_RUNS: bool = true;

    /// Every point, in the order the runs index.
    fn points(&self) -> &[[Self::Scalar; D]];
    /// The items, in the order of [`SpatialIndex::points`].
    fn items(&self) -> &[Self::Item];
    /// The root and its closed box; `None` when the index holds no point.
    fn root(&self) -> Option<(Self::Node, Aabb<f64, D>)>;
    /// The indices of the node's points (of a leaf's only, when not
    /// [`SpatialIndex::NESTED_RUNS`]: an inner node's run is then empty).
    fn run(&self, node: Self::Node) -> Range<usize>;

    /// The number of points in the node's subtree; the default is its run's length.
    #[inline]
    fn count(&self, node: Self::Node) -> usize {
        self.run(node).len()
    }
    /// Calls `f` with every child whose run is not empty, and its closed box; returns `false`
    /// (calling nothing) for a leaf.
    fn for_each_child(&self, node: Self::Node, f: impl FnMut(Self::Node, &Aabb<f64, D>)) -> bool;

    /// [`SpatialIndex::for_each_child`] for a node whose closed box `bbox` the caller already
    /// holds (from [`SpatialIndex::root`] or an earlier call), so that an index can build the
    /// children's boxes from it. The default ignores `bbox`.
    #[inline]
    fn for_each_child_in(
        &self,
        node: Self::Node,
        bbox: &Aabb<f64, D>,
        f: impl FnMut(Self::Node, &Aabb<f64, D>),
    ) -> bool {
        let _ = bbox;
        self.for_each_child(node, f)
    }

    /// The child of `node` (whose closed box `bbox` the caller holds) to search first for
    /// points near `q`: the non-empty child whose box is nearest under `metric`, the first of
    /// equals, with its box; `None` for a leaf. The nearest-neighbour engines walk these down
    /// from the root to seed their bound. The default bounds every child; an index that can
    /// tell the child holding `q` directly may override it, returning the same child.
    #[inline]
    fn nearest_child<M: Metric<D>>(
        &self,
        node: Self::Node,
        bbox: &Aabb<f64, D>,
        q: &[f64; D],
        metric: &M,
    ) -> Option<(Self::Node, Aabb<f64, D>)> {
        nearest_child_by_boxes(self, node, bbox, q, metric)
    }

    /// The points in `region` with their items, lazily: the range engine
    /// ([`PointTree::query`]'s) on this index.
    fn query<R: Region<D>>(&self, region: R) -> Result<RegionIter<'_, Self, R, D>, QueryError>
    where
        Self: Sized,
    {
        RegionIter::new(self, region)
    }

    /// The number of points in `region` ([`PointTree::query_count`]'s engine).
    fn query_count<R: Region<D>>(&self, region: R) -> Result<usize, QueryError>
    where
        Self: Sized,
    {
        for_each_in(self, &region, scan_limit(D), false, |_| {}).map(|s| s.count)
    }

    /// Calls `visit(point, item)` for every point in `region` ([`PointTree::query_with`]'s
    /// engine).
    fn query_with<R: Region<D>>(
        &self,
        region: R,
        mut visit: impl FnMut(&[Self::Scalar; D], &Self::Item),
    ) -> Result<(), QueryError>
    where
        Self: Sized,
    {
        let (points, items) = (self.points(), self.items());
        for_each_in(self, &region, scan_limit(D), true, |i| {
            visit(&points[i], &items[i])
        })
        .map(|_| ())
    }

    /// The count of `region` with the work done, descending to the leaves
    /// ([`PointTree::query_stats`]'s engine).
    fn query_stats<R: Region<D>>(&self, region: R) -> Result<QueryStats, QueryError>
    where
        Self: Sized,
    {
        for_each_in(self, &region, 0, false, |_| {})
    }

    /// The `k` nearest points to `p` within distance `max` under `metric`, sorted by distance
    /// then index ([`PointTree::k_nearest_by`]'s engine).
    fn k_nearest_by<M: Metric<D>>(
        &self,
        p: &[Self::Scalar; D],
        k: usize,
        max: f64,
        metric: &M,
    ) -> Result<Neighbors<'_, Self, D>, QueryError>
    where
        Self: Sized,
    {
        let q = query_point(p)?;
        check_max(max)?;
        Ok(k_nearest(self, &q, k, max, metric)
            .into_iter()
            .map(|(d, i)| Neighbor::at(self, d, i))
            .collect())
    }

    /// The nearest point to `p` within distance `max` under `metric`, ties to the lower index
    /// ([`PointTree::nearest_within`]'s engine): [`SpatialIndex::k_nearest_by`] for k = 1,
    /// without allocating.
    fn nearest_by<M: Metric<D>>(
        &self,
        p: &[Self::Scalar; D],
        max: f64,
        metric: &M,
    ) -> Result<Option<NeighborIn<'_, Self, D>>, QueryError>
    where
        Self: Sized,
    {
        let q = query_point(p)?;
        check_max(max)?;
        Ok(k_nearest(self, &q, 1, max, metric)
            .first()
            .map(|&(d, i)| Neighbor::at(self, d, i)))
    }

    /// Every point within distance `max` of `p` under `metric`, nearest first, lazily
    /// ([`PointTree::nearest_iter_by`]'s engine).
    fn nearest_iter_by<M: Metric<D>>(
        &self,
        p: &[Self::Scalar; D],
        max: f64,
        metric: M,
    ) -> Result<NearestIter<'_, Self, M, D>, QueryError>
    where
        Self: Sized,
    {
        NearestIter::new(self, query_point(p)?, max, metric)
    }
}

/// Whether the engines scan `node`'s run whole rather than descend: its run is contiguous
/// ([`SpatialIndex::NESTED_RUNS`]) and holds at most `limit` points. (A leaf is scanned
/// either way.)
#[inline(always)]
pub(crate) fn scans_whole<I: SpatialIndex<D>, const D: usize>(
    index: &I,
    node: I::Node,
    limit: usize,
) -> bool {
    I::NESTED_RUNS && index.count(node) <= limit
}

/// [`SpatialIndex::nearest_child`] by bounding every child: the first child whose box is nearest.
#[inline]
pub(crate) fn nearest_child_by_boxes<I: SpatialIndex<D> + ?Sized, M: Metric<D>, const D: usize>(
    index: &I,
    node: I::Node,
    bbox: &Aabb<f64, D>,
    q: &[f64; D],
    metric: &M,
) -> Option<(I::Node, Aabb<f64, D>)> {
    let mut next: Option<(f64, I::Node, Aabb<f64, D>)> = None;
    index.for_each_child_in(node, bbox, |child, cb| {
        let d = metric.box_distance(q, cb);
        if next.as_ref().is_none_or(|n| d < n.0) {
            next = Some((d, child, *cb));
        }
    });
    next.map(|(_, child, cb)| (child, cb))
}

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
    type Item = T;
    type Node = PointNode<D>;

    #[inline]
    fn points(&self) -> &[[S; D]] {
        PointTree::points(self)
    }

    #[inline]
    fn items(&self) -> &[T] {
        PointTree::items(self)
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
    #[inline]
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
