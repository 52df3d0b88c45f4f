//! The queries of a tree whose [`SpatialIndex`] stores slots (`u32`) instead of items, and whose
//! items sit apart in slot order: [`crate::CompressedTree`] and [`crate::DynamicPointTree`].
//! Each query runs the shared engine on the index (the trait's provided methods) and maps the
//! slots it reports to the items, so neither tree has a copy of any query:
//! [`slot_queries!`](crate::slot_queries) writes the methods, with the names and meanings of
//! [`PointTree`](crate::PointTree)'s, for both.

use super::{Metric, NearestIter, Neighbor, Region, RegionIter, SpatialIndex};
use crate::geom::Scalar;

/// Iterator returned by the `query` of a slotted tree (and `in_box`, `in_ball`,
/// `in_half_space`): the points in a region with their items, lazily.
pub struct SlotRegionIter<'a, I: SpatialIndex<D>, T, R, const D: usize> {
    pub(crate) inner: RegionIter<'a, I, R, D>,
    pub(crate) items: &'a [T],
}

impl<'a, S: Scalar, I, T, R: Region<D>, const D: usize> Iterator for SlotRegionIter<'a, I, T, R, D>
where
    I: SpatialIndex<D, Scalar = S, Item = u32>,
{
    type Item = (&'a [S; D], &'a T);

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        let (p, &slot) = self.inner.next()?;
        Some((p, &self.items[slot as usize]))
    }
}

/// Iterator returned by the `nearest_iter` of a slotted tree (and its `_within` and `_by`
/// forms): every point within the maximum distance, nearest first.
pub struct SlotNearestIter<'a, I: SpatialIndex<D>, T, M, const D: usize> {
    pub(crate) inner: NearestIter<'a, I, M, D>,
    pub(crate) items: &'a [T],
    pub(crate) slot_index: bool,
}

impl<'a, S: Scalar, I, T, M: Metric<D>, const D: usize> Iterator for SlotNearestIter<'a, I, T, M, D>
where
    I: SpatialIndex<D, Scalar = S, Item = u32>,
{
    type Item = Neighbor<'a, S, T, D>;

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        let n = self.inner.next()?;
        Some(with_item(n, self.items, self.slot_index))
    }
}

/// A neighbour found on a slotted index, with the tree's item for its slot; its `index` the slot
/// when `slot_index`, else the position in the index's points.
#[inline]
pub(crate) fn with_item<'a, S, T, const D: usize>(
    n: Neighbor<'a, S, u32, D>,
    items: &'a [T],
    slot_index: bool,
) -> Neighbor<'a, S, T, D> {
    let slot = *n.item as usize;
    Neighbor {
        point: n.point,
        item: &items[slot],
        distance: n.distance,
        index: if slot_index { slot } else { n.index },
    }
}

/// Writes the queries of a slotted tree `$tree<S, T, D>`, whose `index()` is a `$index`
/// ([`SpatialIndex`] with `u32` items) and whose `items()` are in slot order; `$slot_index`:
/// whether [`Neighbor::index`] reports the slot (else the position in the index's points).
/// The type aliases `$region_iter` and `$nearest_iter` name the iterators.
#[macro_export]
#[doc(hidden)]
macro_rules! slot_queries {
    ($tree:ident, $index:ident, $slot_index:expr, $region_iter:ident, $nearest_iter:ident) => {
        #[doc = concat!("Iterator returned by [`", stringify!($tree), "::query`] and its forms.")]
        pub type $region_iter<'a, S, T, R, const D: usize> =
            $crate::query::SlotRegionIter<'a, $index<S, D>, T, R, D>;

        #[doc = concat!("Iterator returned by [`", stringify!($tree), "::nearest_iter`] and its forms.")]
        pub type $nearest_iter<'a, S, T, M, const D: usize> =
            $crate::query::SlotNearestIter<'a, $index<S, D>, T, M, D>;

        impl<S: $crate::Scalar, T, const D: usize> $tree<S, T, D> {
            /// The points in `region` with their items, lazily
            /// ([`PointTree::query`](crate::PointTree::query)).
            ///
            /// ```
            #[doc = concat!("use orthtree::{Aabb, ", stringify!($tree), "};")]
            #[doc = concat!("let t = ", stringify!($tree), "::new(&[([0.0, 0.0], 'a'), ([1.0, 1.0], 'b'), ([2.0, 2.0], 'c')]).unwrap();")]
            /// let b = Aabb::new([0.5, 0.5], [2.0, 2.0]).unwrap();
            /// let mut found: Vec<char> = t.query(&b).unwrap().map(|(_, &c)| c).collect();
            /// found.sort();
            /// assert_eq!(found, ['b', 'c']);
            /// ```
            pub fn query<R: $crate::Region<D>>(
                &self,
                region: R,
            ) -> Result<$region_iter<'_, S, T, R, D>, $crate::QueryError> {
                Ok($crate::query::SlotRegionIter {
                    inner: $crate::SpatialIndex::query(self.index(), region)?,
                    items: self.items(),
                })
            }

            /// The number of points in `region`.
            pub fn query_count<R: $crate::Region<D>>(
                &self,
                region: R,
            ) -> Result<usize, $crate::QueryError> {
                $crate::SpatialIndex::query_count(self.index(), region)
            }

            /// Calls `visit(point, item)` for every point in `region`.
            pub fn query_with<R: $crate::Region<D>>(
                &self,
                region: R,
                mut visit: impl FnMut(&[S; D], &T),
            ) -> Result<(), $crate::QueryError> {
                let items = self.items();
                $crate::SpatialIndex::query_with(self.index(), region, |p, &s| {
                    visit(p, &items[s as usize])
                })
            }

            /// Counts the points in `region` and the nodes visited and points tested,
            /// descending to the leaves as the chapter's algorithm does.
            ///
            /// ```
            #[doc = concat!("use orthtree::{Aabb, ", stringify!($tree), "};")]
            /// let pts: Vec<([f64; 2], ())> = (0..64).map(|i| ([(i % 8) as f64, (i / 8) as f64], ())).collect();
            #[doc = concat!("let t = ", stringify!($tree), "::new(&pts).unwrap();")]
            /// let s = t.query_stats(Aabb::new([-1.0, -1.0], [8.0, 8.0]).unwrap()).unwrap();
            /// assert_eq!(s.count, 64);
            /// ```
            pub fn query_stats<R: $crate::Region<D>>(
                &self,
                region: R,
            ) -> Result<$crate::query::QueryStats, $crate::QueryError> {
                $crate::SpatialIndex::query_stats(self.index(), region)
            }

            /// The points in the closed box `b`.
            pub fn in_box(
                &self,
                b: &$crate::Aabb<S, D>,
            ) -> Result<$region_iter<'_, S, T, $crate::Aabb<f64, D>, D>, $crate::QueryError> {
                self.query($crate::query::query_box(b)?)
            }

            /// The points at Euclidean distance at most `radius` from `center`.
            ///
            /// Errors: a non-finite or inexact centre, a negative or NaN radius.
            pub fn in_ball(
                &self,
                center: &[S; D],
                radius: f64,
            ) -> Result<$region_iter<'_, S, T, $crate::Ball<D>, D>, $crate::QueryError> {
                self.query($crate::Ball::new($crate::query::query_point(center)?, radius)?)
            }

            /// The points `x` with `normal . x <= offset`.
            ///
            /// Errors: a non-finite normal, a NaN offset.
            pub fn in_half_space(
                &self,
                normal: [f64; D],
                offset: f64,
            ) -> Result<$region_iter<'_, S, T, $crate::HalfSpace<D>, D>, $crate::QueryError>
            {
                self.query($crate::HalfSpace::new(normal, offset)?)
            }

            /// The nearest point to `p` (squared Euclidean distance); `None` for an empty tree.
            ///
            /// Errors: a NaN, infinite or inexact coordinate (an integer `f64` cannot hold) in `p`.
            pub fn nearest(
                &self,
                p: &[S; D],
            ) -> Result<Option<$crate::Neighbor<'_, S, T, D>>, $crate::QueryError> {
                self.nearest_within(p, f64::INFINITY)
            }

            /// The nearest point to `p` at squared distance at most `max`.
            pub fn nearest_within(
                &self,
                p: &[S; D],
                max: f64,
            ) -> Result<Option<$crate::Neighbor<'_, S, T, D>>, $crate::QueryError> {
                let found = $crate::SpatialIndex::nearest_by(
                    self.index(),
                    p,
                    max,
                    &$crate::query::SquaredEuclidean,
                )?;
                Ok(found.map(|n| $crate::query::with_item(n, self.items(), $slot_index)))
            }

            /// The `k` nearest points to `p` (squared Euclidean), sorted by distance, ties by
            /// position in the index's points.
            ///
            /// ```
            #[doc = concat!("use orthtree::", stringify!($tree), ";")]
            /// let pts: Vec<([f64; 2], usize)> = (0..10).map(|i| ([i as f64, 0.0], i)).collect();
            #[doc = concat!("let t = ", stringify!($tree), "::new(&pts).unwrap();")]
            /// let near: Vec<usize> = t.k_nearest(&[4.2, 0.0], 3).unwrap().iter().map(|n| *n.item).collect();
            /// assert_eq!(near, [4, 5, 3]);
            /// ```
            pub fn k_nearest(
                &self,
                p: &[S; D],
                k: usize,
            ) -> Result<Vec<$crate::Neighbor<'_, S, T, D>>, $crate::QueryError> {
                self.k_nearest_by(p, k, f64::INFINITY, &$crate::query::SquaredEuclidean)
            }

            #[doc = concat!("[`", stringify!($tree), "::k_nearest`] among the points at squared distance at most `max`.")]
            pub fn k_nearest_within(
                &self,
                p: &[S; D],
                k: usize,
                max: f64,
            ) -> Result<Vec<$crate::Neighbor<'_, S, T, D>>, $crate::QueryError> {
                self.k_nearest_by(p, k, max, &$crate::query::SquaredEuclidean)
            }

            /// The `k` nearest points to `p` at distance at most `max` under `metric`.
            ///
            /// Errors: a non-finite or inexact `p`; a negative or NaN `max`.
            pub fn k_nearest_by<M: $crate::Metric<D>>(
                &self,
                p: &[S; D],
                k: usize,
                max: f64,
                metric: &M,
            ) -> Result<Vec<$crate::Neighbor<'_, S, T, D>>, $crate::QueryError> {
                let found = $crate::SpatialIndex::k_nearest_by(self.index(), p, k, max, metric)?;
                Ok(found
                    .into_iter()
                    .map(|n| $crate::query::with_item(n, self.items(), $slot_index))
                    .collect())
            }

            /// Every point, nearest to `p` first (squared Euclidean), lazily.
            pub fn nearest_iter(
                &self,
                p: &[S; D],
            ) -> Result<$nearest_iter<'_, S, T, $crate::query::SquaredEuclidean, D>, $crate::QueryError>
            {
                self.nearest_iter_by(p, f64::INFINITY, $crate::query::SquaredEuclidean)
            }

            #[doc = concat!("[`", stringify!($tree), "::nearest_iter`] up to squared distance `max`.")]
            pub fn nearest_iter_within(
                &self,
                p: &[S; D],
                max: f64,
            ) -> Result<$nearest_iter<'_, S, T, $crate::query::SquaredEuclidean, D>, $crate::QueryError>
            {
                self.nearest_iter_by(p, max, $crate::query::SquaredEuclidean)
            }

            #[doc = concat!("[`", stringify!($tree), "::nearest_iter`] under `metric`, up to distance `max`.")]
            ///
            /// ```
            #[doc = concat!("use orthtree::{query::Manhattan, ", stringify!($tree), "};")]
            #[doc = concat!("let t = ", stringify!($tree), "::new(&[([1.0, 1.0], 'a'), ([0.0, 1.5], 'b')]).unwrap();")]
            /// let order: Vec<char> = t.nearest_iter_by(&[0.0, 0.0], 10.0, Manhattan).unwrap().map(|n| *n.item).collect();
            /// assert_eq!(order, ['b', 'a']);
            /// ```
            pub fn nearest_iter_by<M: $crate::Metric<D>>(
                &self,
                p: &[S; D],
                max: f64,
                metric: M,
            ) -> Result<$nearest_iter<'_, S, T, M, D>, $crate::QueryError> {
                Ok($crate::query::SlotNearestIter {
                    inner: $crate::SpatialIndex::nearest_iter_by(self.index(), p, max, metric)?,
                    items: self.items(),
                    slot_index: $slot_index,
                })
            }
        }
    };
}
