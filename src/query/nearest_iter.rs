//! [`NearestIter`](super::NearestIter): the points in order of distance, lazily, by best-first search (Hjaltason and
//! Samet, "Distance browsing in spatial databases", ACM TODS 24(2), 1999) on any
//! [`SpatialIndex`] and [`Metric`].
//!
//! One priority queue holds nodes, keyed by their box's lower bound, and points, keyed by their
//! distance. Popping a node pushes its children (or a leaf's points); popping a point reports it:
//! no node or point still queued can be nearer. At equal keys nodes come before points, and points
//! by index, so the order is exactly `(distance, index)`, the order of
//! [`PointSet::k_nearest`](super::PointSet::k_nearest). Each step costs O(log of the queue's size).

use super::index::SpatialIndex;
use super::knn::Neighbor;
use super::metric::Metric;
use super::{check_max, query_point, QueryError};
use crate::geom::{Aabb, Scalar};
use core::cmp::Ordering;
use std::collections::BinaryHeap;

/// A queued node (`node: Some`) or point, ordered so that the heap's top is the least
/// `(key, is point, index)`.
struct Entry<N> {
    key: f64,
    node: Option<N>,
    index: usize,
}

impl<N> Entry<N> {
    fn rank(&self) -> (f64, bool, usize) {
        (self.key, self.node.is_none(), self.index)
    }
}

impl<N> PartialEq for Entry<N> {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl<N> Eq for Entry<N> {}

impl<N> PartialOrd for Entry<N> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl<N> Ord for Entry<N> {
    fn cmp(&self, other: &Self) -> Ordering {
        let (a, b) = (self.rank(), other.rank());
        // Reversed: BinaryHeap is a max-heap.
        b.0.total_cmp(&a.0).then(b.1.cmp(&a.1)).then(b.2.cmp(&a.2))
    }
}

/// The engine of [`NearestIter`](super::NearestIter): every point of an index within the
/// maximum distance, nearest first, ties by position in [`SpatialIndex::points`].
pub(crate) struct IndexNearestIter<'a, I: SpatialIndex<D>, M, const D: usize> {
    index: &'a I,
    metric: M,
    q: [f64; D],
    max: f64,
    heap: BinaryHeap<Entry<(I::Node, Aabb<f64, D>)>>,
}

impl<'a, I: SpatialIndex<D>, M: Metric<D>, const D: usize> IndexNearestIter<'a, I, M, D> {
    /// A lazy nearest-first search from `q` on `index`, up to distance `max` (inclusive).
    ///
    /// # Errors
    /// A non-finite `q`; a negative or NaN `max`.
    pub(crate) fn new(index: &'a I, q: [f64; D], max: f64, metric: M) -> Result<Self, QueryError> {
        query_point(&q)?;
        check_max(max)?;
        let mut heap = BinaryHeap::new();
        if let Some((root, b)) = index.root() {
            offer(
                &mut heap,
                max,
                metric.box_distance(&q, &b),
                Some((root, b)),
                0,
            );
        }
        Ok(IndexNearestIter {
            index,
            metric,
            q,
            max,
            heap,
        })
    }
}

impl<'a, I: SpatialIndex<D>, M: Metric<D>, const D: usize> Iterator
    for IndexNearestIter<'a, I, M, D>
{
    type Item = Neighbor<'a, I::Scalar, I::Payload, D>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            let entry = self.heap.pop()?;
            let Some((node, bbox)) = entry.node else {
                return Some(Neighbor::at(self.index, entry.key, entry.index));
            };
            let (heap, metric, q, max) = (&mut self.heap, &self.metric, &self.q, self.max);
            let internal = self.index.for_each_child_in(node, &bbox, |child, b| {
                offer(heap, max, metric.box_distance(q, b), Some((child, *b)), 0);
            });
            if !internal {
                let points = self.index.points();
                for i in self.index.run(node) {
                    let key = metric.distance(q, &points[i].map(Scalar::to_f64));
                    offer(heap, max, key, None, i);
                }
            }
        }
    }
}

/// Queues a node (`node: Some`) or the point at `index` at distance `key`, unless it lies
/// beyond `max`.
#[inline(always)]
fn offer<N>(heap: &mut BinaryHeap<Entry<N>>, max: f64, key: f64, node: Option<N>, index: usize) {
    if key <= max {
        heap.push(Entry { key, node, index });
    }
}
