//! [`PeriodicQueries`]: the queries of every point tree on a periodic domain ([`Torus`]), with
//! minimum-image distances, written once over [`PointSet`]'s `*_by` queries and its range
//! engine with the periodic regions ([`PeriodicBall`], [`PeriodicBox`]). The batch and parallel
//! forms take the same metric and regions
//! ([`ParallelQueries`](super::ParallelQueries) with [`Torus::squared_euclidean`]).

use super::metric::SquaredEuclidean;
use super::periodic::Torus;
use super::periodic_metric::MinImage;
use super::periodic_region::{PeriodicBall, PeriodicBox};
use super::point_set::{NearestIter, NeighborIn, PointSet, RegionIter};
use super::{query_point, QueryError};

/// Minimum-image queries on a periodic domain, for every [`PointSet`] (in the prelude).
///
/// Like scipy's `cKDTree(boxsize=...)`: distances along the wrapping axes of `torus` are the
/// shortest over all images, so a point near the upper face is near one at the lower face.
/// Build the tree from points inside the period box ([`Torus::prepare`] wraps or refuses the
/// others, and moves points on the upper face to the lower one); query points may lie anywhere.
/// Distances and `max` are squared, as in [`PointSet::k_nearest`]; the ball's radius is not.
///
/// ```
/// use orthtree::prelude::*;
/// use orthtree::query::{OutsidePoints, Torus};
/// use orthtree::PointTree;
/// let torus = Torus::wrapping([0.0; 2], [10.0; 2]).unwrap();
/// let pts = torus.prepare(&[[0.5, 5.0], [5.0, 5.0], [10.0, 5.0]], OutsidePoints::Refuse).unwrap();
/// let entries: Vec<([f64; 2], usize)> = pts.iter().enumerate().map(|(i, p)| (*p, i)).collect();
/// let t = PointTree::new(&entries).unwrap();
/// let near = t.periodic_k_nearest(&torus, &[9.5, 5.0], 2).unwrap();
/// assert_eq!((*near[0].item, near[0].distance), (2, 0.25)); // 10.0 became 0.0
/// assert_eq!((*near[1].item, near[1].distance), (0, 1.0)); // across the face
/// assert_eq!(t.periodic_in_ball(&torus, &[9.5, 5.0], 1.0).unwrap().count(), 2);
/// assert_eq!(t.periodic_in_box(&torus, [9.0, 0.0], [1.0, 10.0]).unwrap().count(), 2);
/// ```
pub trait PeriodicQueries<const D: usize>: PointSet<D> {
    /// The nearest point to `p` under the minimum-image squared Euclidean distance.
    ///
    /// # Errors
    /// A NaN, infinite or inexact coordinate in `p`.
    #[inline]
    fn periodic_nearest(
        &self,
        torus: &Torus<D>,
        p: &[Self::Scalar; D],
    ) -> Result<Option<NeighborIn<'_, Self, D>>, QueryError> {
        self.nearest_by(p, f64::INFINITY, &torus.squared_euclidean())
    }

    /// The `k` nearest points to `p` under the minimum-image squared Euclidean distance, sorted
    /// by distance; fewer when the set holds fewer.
    ///
    /// # Errors
    /// A NaN, infinite or inexact coordinate in `p`.
    ///
    /// # Complexity
    /// About that of [`PointSet::k_nearest`]: the query's image in the period box is searched
    /// as in ordinary space, and its images across the faces only when the `k`-th distance
    /// reaches them (the image search of [`Metric::torus`](super::Metric::torus)).
    #[inline]
    fn periodic_k_nearest(
        &self,
        torus: &Torus<D>,
        p: &[Self::Scalar; D],
        k: usize,
    ) -> Result<Vec<NeighborIn<'_, Self, D>>, QueryError> {
        self.k_nearest_by(p, k, f64::INFINITY, &torus.squared_euclidean())
    }

    /// [`PeriodicQueries::periodic_k_nearest`] among the points at squared minimum-image
    /// distance at most `max`.
    ///
    /// # Errors
    /// A non-finite or inexact `p`; a negative or NaN `max`.
    #[inline]
    fn periodic_k_nearest_within(
        &self,
        torus: &Torus<D>,
        p: &[Self::Scalar; D],
        k: usize,
        max: f64,
    ) -> Result<Vec<NeighborIn<'_, Self, D>>, QueryError> {
        self.k_nearest_by(p, k, max, &torus.squared_euclidean())
    }

    /// Every point, nearest to `p` first under the minimum-image squared Euclidean distance,
    /// lazily.
    ///
    /// # Errors
    /// A NaN, infinite or inexact coordinate in `p`.
    #[inline]
    fn periodic_nearest_iter(
        &self,
        torus: &Torus<D>,
        p: &[Self::Scalar; D],
    ) -> Result<NearestIter<'_, Self, MinImage<SquaredEuclidean, D>, D>, QueryError>
    where
        Self: Sized,
    {
        self.nearest_iter_by(p, f64::INFINITY, torus.squared_euclidean())
    }

    /// The points at minimum-image Euclidean distance at most `radius` from `center`
    /// ([`PeriodicBall`]), each once, even for a radius of half a period or more.
    ///
    /// # Errors
    /// A non-finite or inexact centre; a negative or NaN radius.
    #[inline]
    fn periodic_in_ball(
        &self,
        torus: &Torus<D>,
        center: &[Self::Scalar; D],
        radius: f64,
    ) -> Result<RegionIter<'_, Self, PeriodicBall<D>, D>, QueryError>
    where
        Self: Sized,
    {
        self.query(PeriodicBall::new(*torus, query_point(center)?, radius)?)
    }

    /// The points of the box from `lo` to `hi` that may wrap across the period's faces
    /// ([`PeriodicBox`]: `lo > hi` on a wrapping axis runs through the upper face).
    ///
    /// # Errors
    /// A NaN bound ([`QueryError::NanBound`]).
    #[inline]
    fn periodic_in_box(
        &self,
        torus: &Torus<D>,
        lo: [f64; D],
        hi: [f64; D],
    ) -> Result<RegionIter<'_, Self, PeriodicBox<D>, D>, QueryError>
    where
        Self: Sized,
    {
        self.query(PeriodicBox::new(*torus, lo, hi)?)
    }
}

impl<P: PointSet<D> + ?Sized, const D: usize> PeriodicQueries<D> for P {}
