//! [`ParallelPeriodicJoins`]: the joins of [`PeriodicJoins`] on rayon's threads (feature
//! `rayon`), with minimum-image distances. The parallel engines of
//! [`par_engines`](super::par_engines) (the querying tree's groups for the k-nearest joins, the
//! top node pairs of the dual-tree traversal of Gray and Moore, 2001, for the radius joins) run
//! with the minimum-image squared Euclidean distance as their
//! [`PairDistance`](super::bounds::PairDistance), exactly as the serial forms do: tables,
//! counts and matrices equal the serial ones.

use super::knn::KnnTable;
use super::radius::Boundary;
use super::sparse::SparseDistances;
use super::{Join, PeriodicJoins};
use crate::query::{PointSet, QueryError, Torus};
use core::ops::ControlFlow;

/// The parallel forms of [`PeriodicJoins`], for every point set that can be shared between
/// threads (implemented for all of them; in the prelude under the `rayon` feature).
///
/// ```
/// use core::ops::ControlFlow;
/// use core::sync::atomic::{AtomicU64, Ordering};
/// use orthtree::prelude::*;
/// use orthtree::{query::{Boundary, Torus}, Quadtree};
/// let torus = Torus::wrapping([0.0; 2], [20.0; 2]).unwrap();
/// let pts: Vec<([f64; 2], ())> = (0..400).map(|i| ([(i % 20) as f64, (i / 20) as f64], ())).collect();
/// let t = Quadtree::new(&pts).unwrap();
/// // on the torus every point of the 20 x 20 grid has 4 neighbours at 1: 800 pairs
/// let n = AtomicU64::new(0);
/// let _ = t.par_periodic_pairs_within(&torus, 1.0, Boundary::Inclusive, |_, _, _| {
///     n.fetch_add(1, Ordering::Relaxed);
///     ControlFlow::<()>::Continue(())
/// });
/// assert_eq!(n.into_inner(), 800);
/// let radii = [1.0, 1.5];
/// let counts = t.par_periodic_count_pairs_within(&torus, &radii, Boundary::Inclusive).unwrap();
/// assert_eq!(counts, [800, 1600]);
/// assert_eq!(counts, t.periodic_count_pairs_within(&torus, &radii, Boundary::Inclusive).unwrap());
/// assert_eq!(t.par_periodic_k_nearest_self(&torus, 4), t.periodic_k_nearest_self(&torus, 4));
/// ```
pub trait ParallelPeriodicJoins<const D: usize>: PeriodicJoins<D> + Sync {
    /// [`PeriodicJoins::periodic_k_nearest_join`] on rayon's threads; the same table.
    fn par_periodic_k_nearest_join<B: PointSet<D> + Sync>(
        &self,
        torus: &Torus<D>,
        other: &B,
        k: usize,
    ) -> KnnTable {
        Join::new(self, other, &torus.squared_euclidean(), false).par_knn(k)
    }

    /// [`PeriodicJoins::periodic_k_nearest_self`] on rayon's threads; the same table.
    fn par_periodic_k_nearest_self(&self, torus: &Torus<D>, k: usize) -> KnnTable {
        Join::new(self, self, &torus.squared_euclidean(), true).par_knn(k)
    }

    /// [`PeriodicJoins::periodic_pairs_within`] on rayon's threads: `visit` is called from
    /// several threads at once, each unordered pair `s < t` once, and the first break stops every
    /// thread, as [`ParallelJoins::par_pairs_within`](super::ParallelJoins::par_pairs_within)
    /// does.
    ///
    /// # Errors
    /// A negative or NaN `r` ([`QueryError::InvalidRadius`]); then `visit` is not called.
    fn par_periodic_pairs_within<Br: Send>(
        &self,
        torus: &Torus<D>,
        r: f64,
        boundary: Boundary,
        visit: impl Fn(usize, usize, f64) -> ControlFlow<Br> + Sync,
    ) -> Result<ControlFlow<Br>, QueryError> {
        Join::new(self, self, &torus.squared_euclidean(), true).par_pairs(r, boundary, visit)
    }

    /// [`PeriodicJoins::periodic_pairs_within_other`] on rayon's threads, `visit` called from
    /// several threads at once.
    ///
    /// # Errors
    /// A negative or NaN `r` ([`QueryError::InvalidRadius`]); then `visit` is not called.
    fn par_periodic_pairs_within_other<B: PointSet<D> + Sync, Br: Send>(
        &self,
        torus: &Torus<D>,
        other: &B,
        r: f64,
        boundary: Boundary,
        visit: impl Fn(usize, usize, f64) -> ControlFlow<Br> + Sync,
    ) -> Result<ControlFlow<Br>, QueryError> {
        Join::new(self, other, &torus.squared_euclidean(), false).par_pairs(r, boundary, visit)
    }

    /// The pairs of [`PeriodicJoins::periodic_pairs_within`] folded on rayon's threads, as
    /// [`ParallelJoins::par_fold_pairs_within`](super::ParallelJoins::par_fold_pairs_within)
    /// folds the Euclidean ones.
    ///
    /// # Errors
    /// A negative or NaN `r` ([`QueryError::InvalidRadius`]).
    fn par_periodic_fold_pairs_within<T: Send>(
        &self,
        torus: &Torus<D>,
        r: f64,
        boundary: Boundary,
        identity: impl Fn() -> T + Sync + Send,
        fold: impl Fn(&mut T, usize, usize, f64) + Sync,
        reduce: impl Fn(T, T) -> T + Sync + Send,
    ) -> Result<T, QueryError> {
        Join::new(self, self, &torus.squared_euclidean(), true).par_fold(
            (r, boundary),
            identity,
            fold,
            reduce,
        )
    }

    /// [`PeriodicJoins::periodic_count_pairs_within`] on rayon's threads; the same counts.
    ///
    /// # Errors
    /// Those of [`PeriodicJoins::periodic_count_pairs_within`].
    fn par_periodic_count_pairs_within(
        &self,
        torus: &Torus<D>,
        radii: &[f64],
        boundary: Boundary,
    ) -> Result<Vec<u64>, QueryError> {
        Join::new(self, self, &torus.squared_euclidean(), true).par_count(radii, boundary)
    }

    /// [`PeriodicJoins::periodic_count_neighbors`] on rayon's threads; the same counts.
    ///
    /// # Errors
    /// Those of [`PeriodicJoins::periodic_count_pairs_within`].
    fn par_periodic_count_neighbors<B: PointSet<D> + Sync>(
        &self,
        torus: &Torus<D>,
        other: &B,
        radii: &[f64],
        boundary: Boundary,
    ) -> Result<Vec<u64>, QueryError> {
        Join::new(self, other, &torus.squared_euclidean(), false).par_count(radii, boundary)
    }

    /// [`PeriodicJoins::periodic_sparse_distance_matrix`] on rayon's threads; the same matrix.
    ///
    /// # Errors
    /// A negative or NaN `r` ([`QueryError::InvalidRadius`]).
    fn par_periodic_sparse_distance_matrix<B: PointSet<D> + Sync>(
        &self,
        torus: &Torus<D>,
        other: &B,
        r: f64,
        boundary: Boundary,
    ) -> Result<SparseDistances, QueryError> {
        Join::new(self, other, &torus.squared_euclidean(), false).par_sparse(r, boundary)
    }
}

impl<P: PeriodicJoins<D> + Sync, const D: usize> ParallelPeriodicJoins<D> for P {}
