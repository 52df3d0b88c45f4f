//! [`NearestIter`](super::NearestIter): the points in order of distance, lazily, by best-first search (Hjaltason and
//! Samet, "Distance browsing in spatial databases", ACM TODS 24(2), 1999) on any
//! [`SpatialIndex`] and [`Metric`].
//!
//! One priority queue holds nodes, keyed by their box's lower bound, and points, keyed by their
//! distance. Popping a node pushes its children (or a leaf's points); popping a point reports it:
//! no node or point still queued can be nearer. At equal keys nodes come before points, and points
//! by index, so the order is exactly `(distance, index)`, the order of
//! [`PointSet::k_nearest`](super::PointSet::k_nearest). Each step costs O(log of the queue's size).
//!
//! A leaf's consecutive points at the same distance (copies of one point, which a leaf at the
//! maximum depth keeps however many there are) are queued as one entry, which hands out its
//! positions one by one: a leaf of m copies costs m distances and one push, not m pushes.

use super::index::SpatialIndex;
use super::knn::Neighbor;
use super::metric::Metric;
use super::{check_max, query_point, QueryError};
use crate::geom::{Aabb, Scalar};
use core::cmp::Ordering;
use core::ops::Range;
use std::collections::binary_heap::PeekMut;
use std::collections::BinaryHeap;

/// What a queue entry holds: a node, or the points at consecutive positions, all at the
/// entry's distance.
enum Held<N> {
    Node(N),
    Points(Range<usize>),
}

/// A queued node or group of points at distance (or lower bound) `key`, ordered so that the
/// heap's top is the least `(key, is points, first position)`.
struct Entry<N> {
    key: f64,
    held: Held<N>,
}

impl<N> Entry<N> {
    fn rank(&self) -> (f64, bool, usize) {
        match &self.held {
            Held::Node(_) => (self.key, false, 0),
            Held::Points(at) => (self.key, true, at.start),
        }
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
                Held::Node((root, b)),
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
            let mut top = self.heap.peek_mut()?;
            let key = top.key;
            // A group of several points hands out its first and stays on top of the queue
            // with the rest (the heap moves it down in place if a nearer entry now comes
            // first): one sift per point, not a pop and a push.
            if let Held::Points(at) = &mut top.held
                && at.len() > 1
            {
                let first = at.start;
                at.start += 1;
                return Some(Neighbor::at(self.index, key, first));
            }
            let (node, bbox) = match PeekMut::pop(top).held {
                Held::Node(node) => node,
                Held::Points(at) => return Some(Neighbor::at(self.index, key, at.start)),
            };
            let (heap, metric, q, max) = (&mut self.heap, &self.metric, &self.q, self.max);
            let internal = self.index.for_each_child_in(node, &bbox, |child, b| {
                offer(
                    heap,
                    max,
                    metric.box_distance(q, b),
                    Held::Node((child, *b)),
                );
            });
            if !internal {
                let points = self.index.points();
                let distance = |i: usize| metric.distance(q, &points[i].map(Scalar::to_f64));
                let run = self.index.run(node);
                let Some(mut key) = run.clone().next().map(distance) else {
                    continue;
                };
                // Consecutive positions at the same distance are queued as one group.
                let mut first = run.start;
                for i in run.start + 1..run.end {
                    let d = distance(i);
                    if d.total_cmp(&key).is_ne() {
                        offer(heap, max, key, Held::Points(first..i));
                        (first, key) = (i, d);
                    }
                }
                offer(heap, max, key, Held::Points(first..run.end));
            }
        }
    }
}

/// Queues a node or a group of points at distance (or lower bound) `key`, unless it lies beyond
/// `max`.
#[inline(always)]
fn offer<N>(heap: &mut BinaryHeap<Entry<N>>, max: f64, key: f64, held: Held<N>) {
    if key <= max {
        heap.push(Entry { key, held });
    }
}

#[cfg(test)]
mod tests {
    use super::IndexNearestIter;
    use crate::query::metric::SquaredEuclidean;
    use crate::query::OneLeaf;

    /// A leaf of n copies of one point and one point apart: the copies are one queued group,
    /// handed out in position order at one distance, then the far point.
    #[test]
    fn copies_of_one_point_are_queued_as_one_group() {
        let (p, far) = ([0.5, -2.0, 8.0], [3.5, -2.0, 8.0]);
        let n = 10_000;
        let mut points = vec![p; n];
        points.insert(n / 2, far);
        let leaf = OneLeaf(points);
        let q = [0.5, -2.0, 4.0];
        let mut it = IndexNearestIter::new(&leaf, q, f64::INFINITY, SquaredEuclidean).unwrap();
        let first = it.next().unwrap();
        assert_eq!((first.index, first.distance), (0, 16.0));
        // the copies before the far point, the copies after it, the far point
        assert_eq!(it.heap.len(), 3);
        let rest: Vec<(usize, f64)> = it.map(|nb| (nb.index, nb.distance)).collect();
        let want: Vec<(usize, f64)> = (1..=n)
            .filter(|&i| i != n / 2)
            .map(|i| (i, 16.0))
            .chain([(n / 2, 25.0)])
            .collect();
        assert_eq!(rest, want);
    }
}
