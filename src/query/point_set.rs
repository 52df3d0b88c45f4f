//! [`PointSet`]: the one public trait of every point tree. A tree supplies its
//! [`SpatialIndex`] and how a point of the index maps to its item; every user-facing query
//! (range, counts, visitors, nearest, k-nearest, the nearest iterator, under any [`Metric`]) is
//! a provided method, written once here over the engines of this module; the iterators its
//! queries return. [`PointSetMut`](super::PointSetMut) (`point_set_mut.rs`) adds the updates of
//! the trees that take them.
//!
//! # Slots: the one meaning of an index
//! Every tree keeps its items in one slice, [`PointSet::items`], and the point of item `s` is
//! [`PointSet::point`]`(s)`: `s` is the item's *slot*. [`Neighbor::index`] and the indices of
//! [`ParallelQueries::par_query_indices`](super::ParallelQueries::par_query_indices) are slots,
//! in every tree. Ties between equally near points are broken by the tree's traversal order
//! (Morton order, which for a [`PointTree`](crate::PointTree) is also slot order).

use super::index::SpatialIndex;
use super::knn::{k_nearest, k_nearest_approx, Found, Neighbor};
use super::metric::{Metric, SquaredEuclidean};
use super::nearest_iter::IndexNearestIter;
use super::range::{for_each_in, for_each_until, scan_limit, IndexRegionIter, QueryStats};
use super::region::{Ball, HalfSpace, Region};
use super::{check_max, non_negative, query_box, query_point, QueryError};
use crate::error::ValidationError;
use crate::geom::{Aabb, Scalar};
use core::ops::ControlFlow;

/// What the index of set `P` stores with each point.
pub type Payload<P, const D: usize> = <<P as PointSet<D>>::Index as SpatialIndex<D>>::Payload;

/// A neighbour found in set `P`.
pub(crate) type NeighborIn<'a, P, const D: usize> =
    Neighbor<'a, <P as PointSet<D>>::Scalar, <P as PointSet<D>>::Item, D>;

/// How the positions of a [`PointSet`]'s index points map to its slots, as
/// [`PointSet::position_slots`] tells.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PositionSlots<'a> {
    /// The slot of each position is the position.
    Same,
    /// The slot of position `i` is `table[i]`.
    Table(&'a [u32]),
    /// Only [`PointSet::slot_of`] knows.
    Other,
}

/// A set of (point, item) pairs in a 2^D-tree, with every query.
///
/// Implemented by [`PointTree`](crate::PointTree), [`DynamicPointTree`](crate::DynamicPointTree),
/// [`CompressedTree`](crate::CompressedTree) and [`SkipQuadtree`](crate::SkipQuadtree); bring it
/// into scope with `use orthtree::prelude::*`. Code written against it runs on any of them:
///
/// ```
/// use orthtree::prelude::*;
/// use orthtree::{Aabb, CompressedTree, DynamicPointTree, Quadtree};
/// fn near_and_in<P: PointSet<2, Scalar = f64, Item = char>>(t: &P) -> (char, usize) {
///     let near = t.nearest(&[0.9, 0.9]).unwrap().unwrap();
///     let inside = t.in_box(&Aabb::new([0.0, 0.0], [0.5, 0.5]).unwrap()).unwrap().count();
///     (*near.item, inside)
/// }
/// let pts = [([0.0, 0.0], 'a'), ([1.0, 1.0], 'b'), ([0.5, 0.5], 'c')];
/// assert_eq!(near_and_in(&Quadtree::new(&pts).unwrap()), ('b', 2));
/// assert_eq!(near_and_in(&DynamicPointTree::new(&pts).unwrap()), ('b', 2));
/// assert_eq!(near_and_in(&CompressedTree::new(&pts).unwrap()), ('b', 2));
/// ```
///
/// Coordinates are compared as `f64` exactly (see [`crate::query`]); a query point or corner
/// that `f64` cannot hold is refused with [`QueryError::Inexact`].
pub trait PointSet<const D: usize> {
    /// The coordinate type of the points.
    type Scalar: Scalar;
    /// The item stored with each point.
    type Item;
    /// The index the query engines run on.
    type Index: SpatialIndex<D, Scalar = Self::Scalar>;

    /// The index the query engines run on.
    fn index(&self) -> &Self::Index;
    /// The item of a point of the index, from the payload the index stores with it.
    fn item_of<'a>(&'a self, payload: &'a Payload<Self, D>) -> &'a Self::Item;
    /// The slot of the point at `position` in the index's points, whose payload is `payload`.
    fn slot_of(&self, position: usize, payload: &Payload<Self, D>) -> usize;
    /// [`slot_of`](Self::slot_of) for every position at once, when it is the position itself or
    /// a table of slots: the joins' kernels then read slots without knowing the set's type, and
    /// are compiled once per index and visitor instead of once per pair of set types. An
    /// implementation must agree with `slot_of`. The default, [`PositionSlots::Other`], is
    /// right for every set (the joins then call `slot_of`).
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::query::{PositionSlots, SpatialIndex};
    /// use orthtree::{CompressedTree, PointTree};
    /// let pts = [([0.0, 0.0], 'a'), ([1.0, 1.0], 'b')];
    /// // A point tree keeps its points in slot order; a compressed tree has a table.
    /// assert_eq!(PointTree::new(&pts).unwrap().position_slots(), PositionSlots::Same);
    /// let t = CompressedTree::new(&pts).unwrap();
    /// let PositionSlots::Table(table) = t.position_slots() else { panic!() };
    /// let q = t.index().payloads();
    /// assert!((0..2).all(|i| table[i] as usize == t.slot_of(i, &q[i])));
    /// ```
    #[inline]
    fn position_slots(&self) -> PositionSlots<'_> {
        PositionSlots::Other
    }
    /// The items, by slot.
    fn items(&self) -> &[Self::Item];
    /// The point of slot `slot`.
    ///
    /// # Panics
    /// When `slot >= self.len()`.
    fn point(&self, slot: usize) -> &[Self::Scalar; D];
    /// The closed box every point lies in: the given root box, or the computed root cube (up
    /// to `f64::MAX` where the cube's far side rounds beyond it: its corners are finite).
    fn domain(&self) -> &Aabb<f64, D>;
    /// Checks every invariant of the tree and names the first one broken.
    ///
    /// # Errors
    /// The broken invariant, as a [`ValidationError`].
    ///
    /// # Complexity
    /// At least linear in the points and nodes: meant for tests and after suspicious updates.
    fn validate(&self) -> Result<(), ValidationError>;

    /// The number of points (duplicates counted).
    #[inline]
    fn len(&self) -> usize {
        self.items().len()
    }

    /// `true` when no point is stored.
    #[inline]
    fn is_empty(&self) -> bool {
        self.items().is_empty()
    }

    /// Every (point, item), by slot.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::CompressedTree;
    /// let t = CompressedTree::new(&[([0.0, 0.0], 'a'), ([1.0, 1.0], 'b')]).unwrap();
    /// let mut all: Vec<char> = t.iter().map(|(_, &c)| c).collect();
    /// all.sort();
    /// assert_eq!(all, ['a', 'b']);
    /// ```
    fn iter(&self) -> impl ExactSizeIterator<Item = (&[Self::Scalar; D], &Self::Item)> + '_ {
        let items = self.items();
        (0..items.len()).map(move |s| (self.point(s), &items[s]))
    }

    /// The points in `region` (any [`Region`], by value or by reference) with their items, as a
    /// lazy iterator. A cell inside the region yields its run of points untested.
    ///
    /// # Errors
    /// The region's own check ([`Region::validate`]), e.g. a NaN box bound.
    ///
    /// # Complexity
    /// `O((d + 1) n + k)` in the worst case for depth `d` and `k` answers (see
    /// [`range`](crate::query::range)), far less on ordinary regions.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{Aabb, Quadtree};
    /// let t = Quadtree::new(&[([0.0, 0.0], 'a'), ([1.0, 1.0], 'b'), ([2.0, 2.0], 'c')]).unwrap();
    /// let b = Aabb::new([0.5, 0.5], [2.0, 2.0]).unwrap();
    /// let mut found: Vec<char> = t.query(&b).unwrap().map(|(_, &c)| c).collect();
    /// found.sort();
    /// assert_eq!(found, ['b', 'c']); // closed: (2, 2) on the boundary is in
    /// ```
    #[inline]
    fn query<R: Region<D>>(&self, region: R) -> Result<RegionIter<'_, Self, R, D>, QueryError>
    where
        Self: Sized,
    {
        Ok(RegionIter {
            set: self,
            inner: IndexRegionIter::new(self.index(), region)?,
        })
    }

    /// The number of points in `region`, without allocating (unless more than 48 nodes are
    /// pending at once). An inside cell counts its run in O(1).
    ///
    /// # Errors
    /// Those of [`PointSet::query`].
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Ball, Quadtree};
    /// let pts: Vec<([f64; 2], ())> = (0..100).map(|i| ([(i % 10) as f64, (i / 10) as f64], ())).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// assert_eq!(t.query_count(Ball::new([0.0, 0.0], 1.0).unwrap()).unwrap(), 3);
    /// ```
    #[inline]
    fn query_count<R: Region<D>>(&self, region: R) -> Result<usize, QueryError> {
        for_each_in(self.index(), &region, scan_limit::<D>(), false, |_| {}).map(|s| s.count)
    }

    /// Calls `visit(point, item)` for every point in `region`, in the traversal's order.
    ///
    /// # Errors
    /// Those of [`PointSet::query`]; then `visit` is not called.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::HalfSpace, Quadtree};
    /// let t = Quadtree::new(&[([0.0, 0.0], 1), ([1.0, 0.0], 2), ([2.0, 0.0], 4)]).unwrap();
    /// let mut sum = 0;
    /// t.query_with(HalfSpace::new([1.0, 0.0], 1.0).unwrap(), |_, &v| sum += v).unwrap();
    /// assert_eq!(sum, 3);
    /// ```
    #[inline]
    fn query_with<R: Region<D>>(
        &self,
        region: R,
        mut visit: impl FnMut(&[Self::Scalar; D], &Self::Item),
    ) -> Result<(), QueryError> {
        let index = self.index();
        let (points, payloads) = (index.points(), index.payloads());
        for_each_in(index, &region, scan_limit::<D>(), true, |i| {
            visit(&points[i], self.item_of(&payloads[i]))
        })
        .map(|_| ())
    }

    /// Calls `visit(point, item)` for the points in `region`, in [`PointSet::query_with`]'s
    /// order, until it returns [`ControlFlow::Break`]: the traversal stops at once and the
    /// break's value is returned; `None` when every point was visited. Streams a radius (or any
    /// region) query's results without collecting them, and stops early: the first `m`, the
    /// first point passing a test, a budget spent.
    ///
    /// # Errors
    /// Those of [`PointSet::query`]; then `visit` is not called.
    ///
    /// # Complexity
    /// That of [`PointSet::query_with`] up to the point that breaks.
    ///
    /// ```
    /// use core::ops::ControlFlow;
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Ball, Quadtree};
    /// let pts: Vec<([f64; 2], u32)> = (0..100).map(|i| ([(i % 10) as f64, (i / 10) as f64], i)).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// let ball = Ball::new([5.0, 5.0], 2.0).unwrap(); // 13 points
    /// let mut seen = 0;
    /// let stop = t.query_until(&ball, |_, &id| {
    ///     seen += 1;
    ///     if seen == 3 { ControlFlow::Break(id) } else { ControlFlow::Continue(()) }
    /// });
    /// assert!(matches!(stop, Ok(Some(_))));
    /// assert_eq!(seen, 3);
    /// let all = t.query_until(&ball, |_, _| ControlFlow::<()>::Continue(()));
    /// assert_eq!(all, Ok(None));
    /// ```
    #[inline]
    fn query_until<R: Region<D>, B>(
        &self,
        region: R,
        mut visit: impl FnMut(&[Self::Scalar; D], &Self::Item) -> ControlFlow<B>,
    ) -> Result<Option<B>, QueryError> {
        let index = self.index();
        let (points, payloads) = (index.points(), index.payloads());
        for_each_until(index, &region, scan_limit::<D>(), true, |i| {
            visit(&points[i], self.item_of(&payloads[i]))
        })
        .map(|(_, stop)| stop)
    }

    /// Counts the points in `region` and the work it took (nodes visited, points tested),
    /// descending to the leaves as the chapter's algorithm does.
    ///
    /// # Errors
    /// Those of [`PointSet::query`].
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{Aabb, Quadtree};
    /// let pts: Vec<([f64; 2], ())> = (0..64).map(|i| ([(i % 8) as f64, (i / 8) as f64], ())).collect();
    /// let t = Quadtree::builder().bucket_size(1).build(&pts).unwrap();
    /// let s = t.query_stats(Aabb::new([-1.0, -1.0], [8.0, 8.0]).unwrap()).unwrap();
    /// assert_eq!((s.count, s.nodes_visited, s.points_tested), (64, 1, 0)); // the root is inside
    /// ```
    fn query_stats<R: Region<D>>(&self, region: R) -> Result<QueryStats, QueryError> {
        for_each_in(self.index(), &region, 0, false, |_| {})
    }

    /// The points in the closed box `b` ([`PointSet::query`] with an [`Aabb`]).
    ///
    /// # Errors
    /// A NaN bound ([`QueryError::NanBound`]); an integer corner `f64` cannot hold
    /// ([`QueryError::Inexact`]). Infinite float bounds are open-ended.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{Aabb, PointTree};
    /// let t = PointTree::new(&[([1i32, 1], 'a'), ([5, 5], 'b')]).unwrap();
    /// assert_eq!(t.in_box(&Aabb::new([0, 0], [1, 1]).unwrap()).unwrap().count(), 1);
    /// ```
    #[inline]
    fn in_box(
        &self,
        b: &Aabb<Self::Scalar, D>,
    ) -> Result<RegionIter<'_, Self, Aabb<f64, D>, D>, QueryError>
    where
        Self: Sized,
    {
        self.query(query_box(b)?)
    }

    /// The points at Euclidean distance at most `radius` from `center` ([`Ball`]).
    ///
    /// # Errors
    /// A non-finite or inexact centre, a negative or NaN radius.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let t = Quadtree::new(&[([3.0, 4.0], 'a'), ([4.0, 4.0], 'b')]).unwrap();
    /// let found: Vec<char> = t.in_ball(&[0.0, 0.0], 5.0).unwrap().map(|(_, &c)| c).collect();
    /// assert_eq!(found, ['a']);
    /// ```
    #[inline]
    fn in_ball(
        &self,
        center: &[Self::Scalar; D],
        radius: f64,
    ) -> Result<RegionIter<'_, Self, Ball<D>, D>, QueryError>
    where
        Self: Sized,
    {
        self.query(Ball::new(query_point(center)?, radius)?)
    }

    /// The points `x` with `normal . x <= offset` ([`HalfSpace`]).
    ///
    /// # Errors
    /// A non-finite normal, a NaN offset.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let t = Quadtree::new(&[([0.0, 0.0], 'a'), ([1.0, 1.0], 'b')]).unwrap();
    /// let found: Vec<char> = t.in_half_space([1.0, 1.0], 1.0).unwrap().map(|(_, &c)| c).collect();
    /// assert_eq!(found, ['a']);
    /// ```
    #[inline]
    fn in_half_space(
        &self,
        normal: [f64; D],
        offset: f64,
    ) -> Result<RegionIter<'_, Self, HalfSpace<D>, D>, QueryError>
    where
        Self: Sized,
    {
        self.query(HalfSpace::new(normal, offset)?)
    }

    /// The nearest point to `p` (squared Euclidean distance); `None` for an empty set.
    ///
    /// # Errors
    /// A NaN, infinite or inexact coordinate (an integer `f64` cannot hold) in `p`.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let t = Quadtree::new(&[([0.0, 0.0], 'a'), ([3.0, 4.0], 'b')]).unwrap();
    /// let n = t.nearest(&[2.0, 3.0]).unwrap().unwrap();
    /// assert_eq!((*n.item, n.distance), ('b', 2.0)); // squared distance
    /// ```
    #[inline]
    fn nearest(
        &self,
        p: &[Self::Scalar; D],
    ) -> Result<Option<NeighborIn<'_, Self, D>>, QueryError> {
        self.nearest_by(p, f64::INFINITY, &SquaredEuclidean)
    }

    /// Of the points within Euclidean distance `radius` of `center` (inclusive), the `n`
    /// whose items have the smallest `key`, ties broken by slot, best first (kiddo's
    /// `best_n_within`: e.g. the `n` lowest ids near a point). Each neighbour's `distance` is
    /// squared. Memory is O(n) however many points the ball holds.
    ///
    /// # Errors
    /// A non-finite or inexact `center`; a negative or NaN `radius`.
    ///
    /// # Complexity
    /// One range query over the ball, plus O(log n) per point in it.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let t = Quadtree::new(&[([0.0, 0.0], 9), ([1.0, 0.0], 4), ([0.0, 1.0], 7), ([5.0, 5.0], 1)]).unwrap();
    /// let best = t.best_n_within(&[0.0, 0.0], 1.0, 2, |&id| id).unwrap();
    /// let ids: Vec<i32> = best.iter().map(|nb| *nb.item).collect();
    /// assert_eq!(ids, [4, 7]); // 1 is out of reach, 9 ranks third
    /// assert_eq!(best[0].distance, 1.0);
    /// ```
    fn best_n_within<K: Ord>(
        &self,
        center: &[Self::Scalar; D],
        radius: f64,
        n: usize,
        key: impl FnMut(&Self::Item) -> K,
    ) -> Result<Vec<NeighborIn<'_, Self, D>>, QueryError> {
        super::best_within::best_n_within(self, center, radius, n, key)
    }

    /// The nearest point to `p` at squared distance at most `max`; `None` if there is none.
    ///
    /// # Errors
    /// A non-finite or inexact `p`; a negative or NaN `max`.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let t = Quadtree::new(&[([0.0, 0.0], 'a'), ([3.0, 4.0], 'b')]).unwrap();
    /// assert!(t.nearest_within(&[3.0, 0.0], 8.0).unwrap().is_none());
    /// assert_eq!(*t.nearest_within(&[3.0, 0.0], 9.0).unwrap().unwrap().item, 'a');
    /// ```
    #[inline]
    fn nearest_within(
        &self,
        p: &[Self::Scalar; D],
        max: f64,
    ) -> Result<Option<NeighborIn<'_, Self, D>>, QueryError> {
        self.nearest_by(p, max, &SquaredEuclidean)
    }

    /// The nearest point to `p` at distance at most `max` under `metric`, ties to the first in
    /// traversal order: [`PointSet::k_nearest_by`] for k = 1, without allocating.
    ///
    /// # Errors
    /// A non-finite or inexact `p`; a negative or NaN `max`.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Manhattan, Quadtree};
    /// let t = Quadtree::new(&[([3.0, 3.0], 'a'), ([0.0, 4.0], 'b')]).unwrap();
    /// assert_eq!(*t.nearest_by(&[0.0, 0.0], 10.0, &Manhattan).unwrap().unwrap().item, 'b');
    /// ```
    #[inline]
    fn nearest_by<M: Metric<D>>(
        &self,
        p: &[Self::Scalar; D],
        max: f64,
        metric: &M,
    ) -> Result<Option<NeighborIn<'_, Self, D>>, QueryError> {
        let q = query_point(p)?;
        check_max(max)?;
        let index = self.index();
        Ok(k_nearest(index, &q, 1, max, metric)
            .first()
            .map(|&(d, i)| with_item(self, Neighbor::at(index, d, i))))
    }

    /// The `k` nearest points to `p` (squared Euclidean), sorted by distance, ties in traversal
    /// order. Fewer when the set holds fewer; empty for `k = 0` or an empty set.
    ///
    /// # Errors
    /// A NaN, infinite or inexact coordinate (an integer `f64` cannot hold) in `p`.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let pts: Vec<([f64; 2], usize)> = (0..10).map(|i| ([i as f64, 0.0], i)).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// let near: Vec<usize> = t.k_nearest(&[4.2, 0.0], 3).unwrap().iter().map(|n| *n.item).collect();
    /// assert_eq!(near, [4, 5, 3]);
    /// assert!(t.k_nearest(&[4.2, 0.0], 0).unwrap().is_empty());
    /// ```
    #[inline]
    fn k_nearest(
        &self,
        p: &[Self::Scalar; D],
        k: usize,
    ) -> Result<Vec<NeighborIn<'_, Self, D>>, QueryError> {
        self.k_nearest_by(p, k, f64::INFINITY, &SquaredEuclidean)
    }

    /// [`PointSet::k_nearest`] among the points at squared distance at most `max`.
    ///
    /// # Errors
    /// A non-finite or inexact `p`; a negative or NaN `max`.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let pts: Vec<([f64; 2], usize)> = (0..10).map(|i| ([i as f64, 0.0], i)).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// assert_eq!(t.k_nearest_within(&[0.0, 0.0], 5, 4.0).unwrap().len(), 3);
    /// ```
    #[inline]
    fn k_nearest_within(
        &self,
        p: &[Self::Scalar; D],
        k: usize,
        max: f64,
    ) -> Result<Vec<NeighborIn<'_, Self, D>>, QueryError> {
        self.k_nearest_by(p, k, max, &SquaredEuclidean)
    }

    /// The `k` nearest points to `p` at distance at most `max` (inclusive; `f64::INFINITY` for
    /// no limit) under `metric`, sorted by distance, ties in traversal order.
    ///
    /// # Errors
    /// A non-finite or inexact `p`; a negative or NaN `max`.
    ///
    /// # Complexity
    /// Depth-first branch and bound (see [`crate::query`]): about `O(depth + k log k)` on
    /// well-spread points.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::{Chebyshev, Manhattan}, Quadtree};
    /// let t = Quadtree::new(&[([3.0, 3.0], 'a'), ([0.0, 4.0], 'b')]).unwrap();
    /// let q = [0.0, 0.0];
    /// assert_eq!(*t.k_nearest_by(&q, 1, f64::INFINITY, &Manhattan).unwrap()[0].item, 'b');
    /// assert_eq!(*t.k_nearest_by(&q, 1, f64::INFINITY, &Chebyshev).unwrap()[0].item, 'a');
    /// ```
    fn k_nearest_by<M: Metric<D>>(
        &self,
        p: &[Self::Scalar; D],
        k: usize,
        max: f64,
        metric: &M,
    ) -> Result<Vec<NeighborIn<'_, Self, D>>, QueryError> {
        // The exact search alone, not `k_nearest_approx_by` with 0: a caller of the exact
        // queries does not compile the approximate search.
        let q = query_point(p)?;
        check_max(max)?;
        Ok(with_items(
            self,
            k_nearest(self.index(), &q, k, max, metric),
        ))
    }

    /// `k` points near `p` (squared Euclidean), sorted by distance, found by a
    /// (1 + eps)-approximate search: the `i`-th has a Euclidean distance at most `1 + eps`
    /// times the true `i`-th nearest's, for every `i` (up to one rounding of the bound).
    /// `min(k, len)` of them, distinct; `eps = 0` is [`PointSet::k_nearest`] exactly.
    ///
    /// # Errors
    /// A non-finite or inexact `p`; `eps` negative or NaN ([`QueryError::InvalidEpsilon`]).
    ///
    /// # Complexity
    /// At most that of [`PointSet::k_nearest`]; a larger `eps` prunes more nodes (Arya and
    /// Mount's approximate search).
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::QueryError, Quadtree};
    /// let pts: Vec<([f64; 2], usize)> = (0..100).map(|i| ([(i % 10) as f64, (i / 10) as f64], i)).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// let exact = t.k_nearest(&[4.4, 4.4], 5).unwrap();
    /// let near = t.k_nearest_approx(&[4.4, 4.4], 5, 0.5).unwrap();
    /// assert_eq!(near.len(), 5);
    /// for (a, e) in near.iter().zip(&exact) {
    ///     assert!(a.distance <= 1.5 * 1.5 * e.distance); // squared distances
    /// }
    /// assert_eq!(t.k_nearest_approx(&[4.4, 4.4], 5, 0.0).unwrap(), exact);
    /// assert!(matches!(t.k_nearest_approx(&[0.0, 0.0], 1, -0.1), Err(QueryError::InvalidEpsilon { .. })));
    /// ```
    #[inline]
    fn k_nearest_approx(
        &self,
        p: &[Self::Scalar; D],
        k: usize,
        eps: f64,
    ) -> Result<Vec<NeighborIn<'_, Self, D>>, QueryError> {
        self.k_nearest_approx_by(p, k, f64::INFINITY, eps, &SquaredEuclidean)
    }

    /// [`PointSet::k_nearest_approx`] under `metric`, among the points at distance at most
    /// `max`: the `i`-th answer is at most the true `i`-th distance scaled by `1 + eps`
    /// ([`Metric::scale_distance`]); `min(k, n)` answers for `n` points within `max`.
    ///
    /// # Errors
    /// A non-finite or inexact `p`; a negative or NaN `max` or `eps`.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Manhattan, PointTree};
    /// let t = PointTree::new(&[([0, 0], 'a'), ([3, 0], 'b'), ([0, 4], 'c')]).unwrap();
    /// let near = t.k_nearest_approx_by(&[0, 0], 3, 3.5, 1.0, &Manhattan).unwrap();
    /// let items: Vec<char> = near.iter().map(|n| *n.item).collect();
    /// assert_eq!(items, ['a', 'b']); // 'c' is beyond the maximum
    /// ```
    fn k_nearest_approx_by<M: Metric<D>>(
        &self,
        p: &[Self::Scalar; D],
        k: usize,
        max: f64,
        eps: f64,
        metric: &M,
    ) -> Result<Vec<NeighborIn<'_, Self, D>>, QueryError> {
        let q = query_point(p)?;
        check_max(max)?;
        non_negative(eps, |value| QueryError::InvalidEpsilon { value })?;
        let index = self.index();
        let found = if eps == 0.0 {
            k_nearest(index, &q, k, max, metric)
        } else {
            k_nearest_approx(index, &q, k, max, metric, eps)
        };
        Ok(with_items(self, found))
    }

    /// Every point, nearest to `p` first (squared Euclidean), lazily: taking `k` of them costs
    /// about what [`PointSet::k_nearest`] does, without knowing `k` in advance.
    ///
    /// # Errors
    /// A NaN, infinite or inexact coordinate (an integer `f64` cannot hold) in `p`.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let pts: Vec<([f64; 2], usize)> = (0..100).map(|i| ([(i % 10) as f64, (i / 10) as f64], i)).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// let mut it = t.nearest_iter(&[0.0, 0.0]).unwrap();
    /// assert_eq!(*it.next().unwrap().item, 0);
    /// let next: Vec<usize> = it.take(2).map(|n| *n.item).collect();
    /// assert_eq!(next.len(), 2);
    /// assert!(next.contains(&1) && next.contains(&10));
    /// ```
    #[inline]
    fn nearest_iter(
        &self,
        p: &[Self::Scalar; D],
    ) -> Result<NearestIter<'_, Self, SquaredEuclidean, D>, QueryError>
    where
        Self: Sized,
    {
        self.nearest_iter_by(p, f64::INFINITY, SquaredEuclidean)
    }

    /// [`PointSet::nearest_iter`] up to squared distance `max` (inclusive).
    ///
    /// # Errors
    /// A non-finite or inexact `p`; a negative or NaN `max`.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let t = Quadtree::new(&[([0.0, 0.0], 'a'), ([1.0, 0.0], 'b'), ([2.0, 0.0], 'c')]).unwrap();
    /// assert_eq!(t.nearest_iter_within(&[0.0, 0.0], 1.0).unwrap().count(), 2);
    /// ```
    #[inline]
    fn nearest_iter_within(
        &self,
        p: &[Self::Scalar; D],
        max: f64,
    ) -> Result<NearestIter<'_, Self, SquaredEuclidean, D>, QueryError>
    where
        Self: Sized,
    {
        self.nearest_iter_by(p, max, SquaredEuclidean)
    }

    /// [`PointSet::nearest_iter`] under `metric`, up to distance `max` (`f64::INFINITY` for no
    /// limit).
    ///
    /// # Errors
    /// A non-finite or inexact `p`; a negative or NaN `max`.
    ///
    /// # Complexity
    /// Each step costs `O(log q)` for `q` queued nodes and points (best-first search).
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Manhattan, Quadtree};
    /// let t = Quadtree::new(&[([1.0, 1.0], 'a'), ([0.0, 1.5], 'b')]).unwrap();
    /// let order: Vec<char> = t.nearest_iter_by(&[0.0, 0.0], 10.0, Manhattan).unwrap().map(|n| *n.item).collect();
    /// assert_eq!(order, ['b', 'a']);
    /// ```
    #[inline]
    fn nearest_iter_by<M: Metric<D>>(
        &self,
        p: &[Self::Scalar; D],
        max: f64,
        metric: M,
    ) -> Result<NearestIter<'_, Self, M, D>, QueryError>
    where
        Self: Sized,
    {
        Ok(NearestIter {
            set: self,
            inner: IndexNearestIter::new(self.index(), query_point(p)?, max, metric)?,
        })
    }
}

/// The (distance, position) pairs a k-nearest engine found on `set`'s index as neighbours
/// with their items and slots, in their order.
fn with_items<P: PointSet<D> + ?Sized, const D: usize>(
    set: &P,
    found: Found,
) -> Vec<NeighborIn<'_, P, D>> {
    let index = set.index();
    found
        .into_iter()
        .map(|(d, i)| with_item(set, Neighbor::at(index, d, i)))
        .collect()
}

/// A neighbour found on `set`'s index, with its item and slot.
#[inline(always)]
pub(super) fn with_item<'a, P: PointSet<D> + ?Sized, const D: usize>(
    set: &'a P,
    n: Neighbor<'a, P::Scalar, Payload<P, D>, D>,
) -> NeighborIn<'a, P, D> {
    Neighbor {
        point: n.point,
        item: set.item_of(n.item),
        distance: n.distance,
        index: set.slot_of(n.index, n.item),
    }
}

/// Iterator returned by [`PointSet::query`] (and [`PointSet::in_box`], [`PointSet::in_ball`],
/// [`PointSet::in_half_space`]): the points in a region with their items, lazily, in traversal
/// order within each reported node.
pub struct RegionIter<'a, P: PointSet<D>, R, const D: usize> {
    set: &'a P,
    inner: IndexRegionIter<'a, P::Index, R, D>,
}

impl<'a, P: PointSet<D>, R: Region<D>, const D: usize> Iterator for RegionIter<'a, P, R, D> {
    type Item = (&'a [P::Scalar; D], &'a P::Item);

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        let (p, payload) = self.inner.next()?;
        Some((p, self.set.item_of(payload)))
    }
}

/// Iterator returned by [`PointSet::nearest_iter`] (and its `_within` and `_by` forms): every
/// point within the maximum distance, nearest first, ties in traversal order.
pub struct NearestIter<'a, P: PointSet<D>, M, const D: usize> {
    set: &'a P,
    inner: IndexNearestIter<'a, P::Index, M, D>,
}

impl<'a, P: PointSet<D>, M: Metric<D>, const D: usize> Iterator for NearestIter<'a, P, M, D> {
    type Item = NeighborIn<'a, P, D>;

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        let n = self.inner.next()?;
        Some(with_item(self.set, n))
    }
}
