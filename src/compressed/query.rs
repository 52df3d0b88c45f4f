//! The queries of [`crate::query`] on a [`CompressedTree`]: range (box, ball, half-space, any
//! [`Region`]), nearest, k-nearest and the nearest iterator, with the names and meanings of
//! [`PointTree`](crate::PointTree)'s. Each runs the shared engine on the tree's
//! [`CompressedIndex`] (the trait's provided methods of [`SpatialIndex`]) and maps the slots the
//! index reports back to the tree's items: there is no second copy of any query.
//!
//! Indices in [`Neighbor::index`] are positions in `self.index().points()` (Morton order), which
//! break ties as in the point tree; on a freshly built tree they equal the point tree's, except
//! among points sharing one of its finest cells, which the compressed tree orders by their
//! 64-level keys.

use super::{CompressedIndex, CompressedTree};
use crate::geom::{Aabb, Scalar};
use crate::query::{
    Ball, HalfSpace, Metric, NearestIter, Neighbor, QueryError, QueryStats, Region, RegionIter,
    SpatialIndex, SquaredEuclidean,
};

/// Iterator returned by [`CompressedTree::query`] (and `in_box`, `in_ball`, `in_half_space`):
/// the points in a region with their items, lazily.
pub struct CompressedRegionIter<'a, S: Scalar, T, R, const D: usize> {
    inner: RegionIter<'a, CompressedIndex<S, D>, R, D>,
    items: &'a [T],
}

impl<'a, S: Scalar, T, R: Region<D>, const D: usize> Iterator
    for CompressedRegionIter<'a, S, T, R, D>
{
    type Item = (&'a [S; D], &'a T);

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        let (p, &slot) = self.inner.next()?;
        Some((p, &self.items[slot as usize]))
    }
}

/// Iterator returned by [`CompressedTree::nearest_iter`] (and its `_within` and `_by` forms):
/// every point within the maximum distance, nearest first.
pub struct CompressedNearestIter<'a, S: Scalar, T, M, const D: usize> {
    inner: NearestIter<'a, CompressedIndex<S, D>, M, D>,
    items: &'a [T],
}

impl<'a, S: Scalar, T, M: Metric<D>, const D: usize> Iterator
    for CompressedNearestIter<'a, S, T, M, D>
{
    type Item = Neighbor<'a, S, T, D>;

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        self.inner.next().map(|n| with_item(n, self.items))
    }
}

/// A neighbour found on the index, with the tree's item for its slot.
fn with_item<'a, S, T, const D: usize>(
    n: Neighbor<'a, S, u32, D>,
    items: &'a [T],
) -> Neighbor<'a, S, T, D> {
    Neighbor {
        point: n.point,
        item: &items[*n.item as usize],
        distance: n.distance,
        index: n.index,
    }
}

impl<S: Scalar, T, const D: usize> CompressedTree<S, T, D> {
    /// The points in `region` with their items, lazily ([`PointTree::query`](crate::PointTree::query)).
    ///
    /// ```
    /// use orthtree::{Aabb, CompressedTree};
    /// let t = CompressedTree::new(&[([0.0, 0.0], 'a'), ([1.0, 1.0], 'b'), ([2.0, 2.0], 'c')]).unwrap();
    /// let b = Aabb::new([0.5, 0.5], [2.0, 2.0]).unwrap();
    /// let mut found: Vec<char> = t.query(&b).unwrap().map(|(_, &c)| c).collect();
    /// found.sort();
    /// assert_eq!(found, ['b', 'c']);
    /// ```
    pub fn query<R: Region<D>>(
        &self,
        region: R,
    ) -> Result<CompressedRegionIter<'_, S, T, R, D>, QueryError> {
        Ok(CompressedRegionIter {
            inner: self.index().query(region)?,
            items: self.items(),
        })
    }

    /// The number of points in `region`; an inside cell counts its run in O(1).
    pub fn query_count<R: Region<D>>(&self, region: R) -> Result<usize, QueryError> {
        self.index().query_count(region)
    }

    /// Calls `visit(point, item)` for every point in `region`.
    pub fn query_with<R: Region<D>>(
        &self,
        region: R,
        mut visit: impl FnMut(&[S; D], &T),
    ) -> Result<(), QueryError> {
        let items = self.items();
        self.index()
            .query_with(region, |p, &s| visit(p, &items[s as usize]))
    }

    /// Counts the points in `region` and the nodes visited and points tested, descending to the
    /// leaves as the chapter's algorithm does.
    ///
    /// ```
    /// use orthtree::{Aabb, CompressedTree};
    /// let pts: Vec<([f64; 2], ())> = (0..64).map(|i| ([(i % 8) as f64, (i / 8) as f64], ())).collect();
    /// let t = CompressedTree::new(&pts).unwrap();
    /// let s = t.query_stats(Aabb::new([-1.0, -1.0], [8.0, 8.0]).unwrap()).unwrap();
    /// assert_eq!((s.count, s.nodes_visited), (64, 1)); // the root is inside
    /// ```
    pub fn query_stats<R: Region<D>>(&self, region: R) -> Result<QueryStats, QueryError> {
        self.index().query_stats(region)
    }

    /// The points in the closed box `b`.
    pub fn in_box(
        &self,
        b: &Aabb<S, D>,
    ) -> Result<CompressedRegionIter<'_, S, T, Aabb<f64, D>, D>, QueryError> {
        self.query(b.to_f64())
    }

    /// The points at Euclidean distance at most `radius` from `center`.
    ///
    /// Errors: a non-finite centre, a negative or NaN radius.
    pub fn in_ball(
        &self,
        center: &[S; D],
        radius: f64,
    ) -> Result<CompressedRegionIter<'_, S, T, Ball<D>, D>, QueryError> {
        self.query(Ball::new(center.map(Scalar::to_f64), radius)?)
    }

    /// The points `x` with `normal . x <= offset`.
    ///
    /// Errors: a non-finite normal, a NaN offset.
    pub fn in_half_space(
        &self,
        normal: [f64; D],
        offset: f64,
    ) -> Result<CompressedRegionIter<'_, S, T, HalfSpace<D>, D>, QueryError> {
        self.query(HalfSpace::new(normal, offset)?)
    }

    /// The nearest point to `p` (squared Euclidean distance); `None` for an empty tree.
    ///
    /// Errors: a NaN or infinite coordinate in `p`.
    pub fn nearest(&self, p: &[S; D]) -> Result<Option<Neighbor<'_, S, T, D>>, QueryError> {
        self.nearest_within(p, f64::INFINITY)
    }

    /// The nearest point to `p` at squared distance at most `max`.
    pub fn nearest_within(
        &self,
        p: &[S; D],
        max: f64,
    ) -> Result<Option<Neighbor<'_, S, T, D>>, QueryError> {
        let found = self.index().nearest_by(p, max, &SquaredEuclidean)?;
        Ok(found.map(|n| with_item(n, self.items())))
    }

    /// The `k` nearest points to `p` (squared Euclidean), sorted by distance, ties by index.
    ///
    /// ```
    /// use orthtree::CompressedTree;
    /// let pts: Vec<([f64; 2], usize)> = (0..10).map(|i| ([i as f64, 0.0], i)).collect();
    /// let t = CompressedTree::new(&pts).unwrap();
    /// let near: Vec<usize> = t.k_nearest(&[4.2, 0.0], 3).unwrap().iter().map(|n| *n.item).collect();
    /// assert_eq!(near, [4, 5, 3]);
    /// ```
    pub fn k_nearest(
        &self,
        p: &[S; D],
        k: usize,
    ) -> Result<Vec<Neighbor<'_, S, T, D>>, QueryError> {
        self.k_nearest_by(p, k, f64::INFINITY, &SquaredEuclidean)
    }

    /// [`CompressedTree::k_nearest`] among the points at squared distance at most `max`.
    pub fn k_nearest_within(
        &self,
        p: &[S; D],
        k: usize,
        max: f64,
    ) -> Result<Vec<Neighbor<'_, S, T, D>>, QueryError> {
        self.k_nearest_by(p, k, max, &SquaredEuclidean)
    }

    /// The `k` nearest points to `p` at distance at most `max` under `metric`.
    ///
    /// Errors: a non-finite `p`; a negative or NaN `max`.
    pub fn k_nearest_by<M: Metric<D>>(
        &self,
        p: &[S; D],
        k: usize,
        max: f64,
        metric: &M,
    ) -> Result<Vec<Neighbor<'_, S, T, D>>, QueryError> {
        let found = self.index().k_nearest_by(p, k, max, metric)?;
        Ok(found
            .into_iter()
            .map(|n| with_item(n, self.items()))
            .collect())
    }

    /// Every point, nearest to `p` first (squared Euclidean), lazily.
    pub fn nearest_iter(
        &self,
        p: &[S; D],
    ) -> Result<CompressedNearestIter<'_, S, T, SquaredEuclidean, D>, QueryError> {
        self.nearest_iter_by(p, f64::INFINITY, SquaredEuclidean)
    }

    /// [`CompressedTree::nearest_iter`] up to squared distance `max`.
    pub fn nearest_iter_within(
        &self,
        p: &[S; D],
        max: f64,
    ) -> Result<CompressedNearestIter<'_, S, T, SquaredEuclidean, D>, QueryError> {
        self.nearest_iter_by(p, max, SquaredEuclidean)
    }

    /// [`CompressedTree::nearest_iter`] under `metric`, up to distance `max`.
    ///
    /// ```
    /// use orthtree::{query::Manhattan, CompressedTree};
    /// let t = CompressedTree::new(&[([1.0, 1.0], 'a'), ([0.0, 1.5], 'b')]).unwrap();
    /// let order: Vec<char> = t.nearest_iter_by(&[0.0, 0.0], 10.0, Manhattan).unwrap().map(|n| *n.item).collect();
    /// assert_eq!(order, ['b', 'a']);
    /// ```
    pub fn nearest_iter_by<M: Metric<D>>(
        &self,
        p: &[S; D],
        max: f64,
        metric: M,
    ) -> Result<CompressedNearestIter<'_, S, T, M, D>, QueryError> {
        Ok(CompressedNearestIter {
            inner: self.index().nearest_iter_by(p, max, metric)?,
            items: self.items(),
        })
    }
}
