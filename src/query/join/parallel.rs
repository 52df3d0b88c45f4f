//! The joins on rayon's threads (feature `rayon`): [`ParallelJoins`], the same answers as
//! [`Joins`]' serial forms, the work split into independent parts by the engines of
//! [`par_engines`](super::par_engines) (the querying tree's groups for the k-nearest joins, the
//! top node pairs of the dual-tree traversal for the radius joins). Tables, counts and matrices
//! are put in the serial forms' order, so they are equal to them; the pairs visitors see the
//! pairs of the serial forms in an order that varies from run to run.

use super::bounds::Euclid;
use super::knn::KnnTable;
use super::radius::Boundary;
use super::sparse::SparseDistances;
use super::{Join, Joins};
use crate::query::{PointSet, QueryError};
use core::ops::ControlFlow;

/// The parallel forms of [`Joins`], for every point set that can be shared between threads
/// (implemented for all of them; in the prelude under the `rayon` feature).
pub trait ParallelJoins<const D: usize>: Joins<D> + Sync {
    /// [`Joins::k_nearest_join`] on rayon's threads; the same table.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let pts: Vec<([f64; 2], ())> = (0..500).map(|i| ([(i % 25) as f64, (i / 25) as f64], ())).collect();
    /// let (a, b) = (Quadtree::new(&pts[..200]).unwrap(), Quadtree::new(&pts[100..]).unwrap());
    /// assert_eq!(a.par_k_nearest_join(&b, 3), a.k_nearest_join(&b, 3));
    /// ```
    fn par_k_nearest_join<B: PointSet<D> + Sync>(&self, other: &B, k: usize) -> KnnTable {
        Join::new(self, other, &Euclid, false).par_knn(k)
    }

    /// [`Joins::k_nearest_self`] on rayon's threads; the same table.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let pts: Vec<([f64; 2], ())> = (0..500).map(|i| ([(i % 25) as f64, (i / 25) as f64], ())).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// assert_eq!(t.par_k_nearest_self(4), t.k_nearest_self(4));
    /// ```
    fn par_k_nearest_self(&self, k: usize) -> KnnTable {
        Join::new(self, self, &Euclid, true).par_knn(k)
    }

    /// [`Joins::map_k_nearest_join`] on rayon's threads: the same values, `f` called from
    /// several threads at once.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let pts: Vec<([f64; 2], ())> = (0..500).map(|i| ([(i % 25) as f64, (i / 25) as f64], ())).collect();
    /// let (a, b) = (Quadtree::new(&pts[..200]).unwrap(), Quadtree::new(&pts[100..]).unwrap());
    /// let far = |_: usize, _: &[usize], d2: &[f64]| d2[2];
    /// assert_eq!(a.par_map_k_nearest_join(&b, 3, far), a.map_k_nearest_join(&b, 3, far));
    /// ```
    fn par_map_k_nearest_join<B: PointSet<D> + Sync, T: Send>(
        &self,
        other: &B,
        k: usize,
        f: impl Fn(usize, &[usize], &[f64]) -> T + Sync,
    ) -> Vec<T> {
        Join::new(self, other, &Euclid, false).par_map_knn(k, f)
    }

    /// [`Joins::map_k_nearest_self`] on rayon's threads: the same values, `f` called from
    /// several threads at once.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let pts: Vec<([f64; 2], ())> = (0..500).map(|i| ([(i % 25) as f64, (i / 25) as f64], ())).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// let first = |_: usize, s: &[usize], _: &[f64]| s[0];
    /// assert_eq!(t.par_map_k_nearest_self(4, first), t.map_k_nearest_self(4, first));
    /// ```
    fn par_map_k_nearest_self<T: Send>(
        &self,
        k: usize,
        f: impl Fn(usize, &[usize], &[f64]) -> T + Sync,
    ) -> Vec<T> {
        Join::new(self, self, &Euclid, true).par_map_knn(k, f)
    }

    /// [`Joins::pairs_within`] on rayon's threads: calls `visit(s, t, d)` for every unordered
    /// pair of distinct slots `s < t` within `r` (squared distance `d`), each once, from several
    /// threads at once and in no particular order. The first [`ControlFlow::Break`] stops every
    /// thread (calls already under way on other threads finish, and may break too) and is
    /// returned; when several threads break, which break is returned is not decided. Nothing is
    /// collected: each thread holds its traversal's stack only.
    ///
    /// # Errors
    /// A negative or NaN `r` ([`QueryError::InvalidRadius`]); then `visit` is not called.
    ///
    /// # Complexity
    /// That of [`Joins::pairs_within`], shared among the threads.
    ///
    /// ```
    /// use core::ops::ControlFlow;
    /// use core::sync::atomic::{AtomicU64, Ordering};
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Boundary, Quadtree};
    /// let pts: Vec<([f64; 2], ())> = (0..500).map(|i| ([(i % 25) as f64, (i / 25) as f64], ())).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// let n = AtomicU64::new(0);
    /// let flow = t.par_pairs_within(1.0, Boundary::Inclusive, |s, u, d| {
    ///     assert!(s < u && d == 1.0);
    ///     n.fetch_add(1, Ordering::Relaxed);
    ///     ControlFlow::<()>::Continue(())
    /// });
    /// assert_eq!(flow, Ok(ControlFlow::Continue(())));
    /// assert_eq!(n.into_inner(), 24 * 20 + 25 * 19); // the grid's edges
    /// // stop at a pair
    /// let far = t.par_pairs_within(1.0, Boundary::Inclusive, |s, u, _| {
    ///     if s.max(u) > 250 { ControlFlow::Break((s, u)) } else { ControlFlow::Continue(()) }
    /// });
    /// assert!(matches!(far, Ok(ControlFlow::Break((s, u))) if s.max(u) > 250));
    /// ```
    fn par_pairs_within<Br: Send>(
        &self,
        r: f64,
        boundary: Boundary,
        visit: impl Fn(usize, usize, f64) -> ControlFlow<Br> + Sync,
    ) -> Result<ControlFlow<Br>, QueryError> {
        Join::new(self, self, &Euclid, true).par_pairs(r, boundary, visit)
    }

    /// [`Joins::pairs_within_other`] on rayon's threads: calls `visit(s, t, d)` for every slot
    /// `s` of this set and `t` of `other` within `r`, from several threads at once, stopping as
    /// [`ParallelJoins::par_pairs_within`] does.
    ///
    /// # Errors
    /// A negative or NaN `r` ([`QueryError::InvalidRadius`]); then `visit` is not called.
    ///
    /// ```
    /// use core::ops::ControlFlow;
    /// use core::sync::atomic::{AtomicU64, Ordering};
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Boundary, Quadtree};
    /// let pts: Vec<([f64; 2], ())> = (0..500).map(|i| ([(i % 25) as f64, (i / 25) as f64], ())).collect();
    /// let (a, b) = (Quadtree::new(&pts[..300]).unwrap(), Quadtree::new(&pts[200..]).unwrap());
    /// let n = AtomicU64::new(0);
    /// let _ = a.par_pairs_within_other(&b, 0.0, Boundary::Inclusive, |_, _, _| {
    ///     n.fetch_add(1, Ordering::Relaxed);
    ///     ControlFlow::<()>::Continue(())
    /// });
    /// assert_eq!(n.into_inner(), 100); // the shared points, each with itself
    /// ```
    fn par_pairs_within_other<B: PointSet<D> + Sync, Br: Send>(
        &self,
        other: &B,
        r: f64,
        boundary: Boundary,
        visit: impl Fn(usize, usize, f64) -> ControlFlow<Br> + Sync,
    ) -> Result<ControlFlow<Br>, QueryError> {
        Join::new(self, other, &Euclid, false).par_pairs(r, boundary, visit)
    }

    /// The pairs of [`Joins::pairs_within`] folded on rayon's threads: each thread's share of
    /// the traversal starts from `identity()`, `fold(&mut acc, s, t, d)` takes in each of its
    /// pairs (`s < t`, squared distance `d`), and `reduce` combines the accumulators into one.
    /// The pairs are met in an order that varies from run to run, so `reduce` should be
    /// associative and commutative for a repeatable answer. Nothing but the accumulators is
    /// held.
    ///
    /// # Errors
    /// A negative or NaN `r` ([`QueryError::InvalidRadius`]).
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Boundary, Quadtree};
    /// let pts: Vec<([f64; 2], ())> = (0..500).map(|i| ([(i % 25) as f64, (i / 25) as f64], ())).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// // the number of pairs and the largest squared distance
    /// let (n, far) = t
    ///     .par_fold_pairs_within(1.5, Boundary::Inclusive, || (0u64, 0.0f64),
    ///         |acc, _, _, d| { acc.0 += 1; acc.1 = acc.1.max(d); },
    ///         |x, y| (x.0 + y.0, x.1.max(y.1)))
    ///     .unwrap();
    /// assert_eq!((n, far), (24 * 20 + 25 * 19 + 2 * 24 * 19, 2.0));
    /// ```
    fn par_fold_pairs_within<T: Send>(
        &self,
        r: f64,
        boundary: Boundary,
        identity: impl Fn() -> T + Sync + Send,
        fold: impl Fn(&mut T, usize, usize, f64) + Sync,
        reduce: impl Fn(T, T) -> T + Sync + Send,
    ) -> Result<T, QueryError> {
        Join::new(self, self, &Euclid, true).par_fold((r, boundary), identity, fold, reduce)
    }

    /// The pairs of [`Joins::pairs_within_other`] folded on rayon's threads, as
    /// [`ParallelJoins::par_fold_pairs_within`] folds those of one set (`s` a slot of this set,
    /// `t` of `other`).
    ///
    /// # Errors
    /// A negative or NaN `r` ([`QueryError::InvalidRadius`]).
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Boundary, Quadtree};
    /// let a = Quadtree::new(&[([0.0, 0.0], ()), ([5.0, 5.0], ())]).unwrap();
    /// let b = Quadtree::new(&[([0.5, 0.0], ()), ([5.0, 6.0], ()), ([9.0, 9.0], ())]).unwrap();
    /// let n = a.par_fold_pairs_within_other(&b, 1.0, Boundary::Inclusive, || 0, |n, _, _, _| *n += 1, |x, y| x + y);
    /// assert_eq!(n, Ok(2));
    /// ```
    fn par_fold_pairs_within_other<B: PointSet<D> + Sync, T: Send>(
        &self,
        other: &B,
        r: f64,
        boundary: Boundary,
        identity: impl Fn() -> T + Sync + Send,
        fold: impl Fn(&mut T, usize, usize, f64) + Sync,
        reduce: impl Fn(T, T) -> T + Sync + Send,
    ) -> Result<T, QueryError> {
        Join::new(self, other, &Euclid, false).par_fold((r, boundary), identity, fold, reduce)
    }

    /// [`Joins::sparse_distance_matrix`] on rayon's threads; the same matrix.
    ///
    /// # Errors
    /// A negative or NaN `r` ([`QueryError::InvalidRadius`]).
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Boundary, Quadtree};
    /// let pts: Vec<([f64; 2], ())> = (0..500).map(|i| ([(i % 25) as f64, (i / 25) as f64], ())).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// let m = t.par_sparse_distance_matrix(&t, 1.5, Boundary::Inclusive).unwrap();
    /// assert_eq!(m, t.sparse_distance_matrix(&t, 1.5, Boundary::Inclusive).unwrap());
    /// ```
    fn par_sparse_distance_matrix<B: PointSet<D> + Sync>(
        &self,
        other: &B,
        r: f64,
        boundary: Boundary,
    ) -> Result<SparseDistances, QueryError> {
        Join::new(self, other, &Euclid, false).par_sparse(r, boundary)
    }

    /// [`Joins::count_pairs_within`] on rayon's threads; the same counts.
    ///
    /// # Errors
    /// Those of [`Joins::count_pairs_within`].
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Boundary, Quadtree};
    /// let pts: Vec<([f64; 2], ())> = (0..500).map(|i| ([(i % 25) as f64, (i / 25) as f64], ())).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// let radii = [0.5, 1.0, 1.5, 10.0];
    /// let counts = t.par_count_pairs_within(&radii, Boundary::Inclusive).unwrap();
    /// assert_eq!(counts, t.count_pairs_within(&radii, Boundary::Inclusive).unwrap());
    /// assert_eq!(counts[1], 24 * 20 + 25 * 19); // the grid's horizontal and vertical edges
    /// ```
    fn par_count_pairs_within(
        &self,
        radii: &[f64],
        boundary: Boundary,
    ) -> Result<Vec<u64>, QueryError> {
        Join::new(self, self, &Euclid, true).par_count(radii, boundary)
    }

    /// [`Joins::count_neighbors`] on rayon's threads; the same counts.
    ///
    /// # Errors
    /// Those of [`Joins::count_pairs_within`].
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Boundary, Quadtree};
    /// let pts: Vec<([f64; 2], ())> = (0..500).map(|i| ([(i % 25) as f64, (i / 25) as f64], ())).collect();
    /// let (a, b) = (Quadtree::new(&pts[..300]).unwrap(), Quadtree::new(&pts[200..]).unwrap());
    /// let radii = [0.0, 1.0, 3.0];
    /// let counts = a.par_count_neighbors(&b, &radii, Boundary::Exclusive).unwrap();
    /// assert_eq!(counts, a.count_neighbors(&b, &radii, Boundary::Exclusive).unwrap());
    /// assert_eq!(counts[1], 100); // the shared points, each with itself
    /// ```
    fn par_count_neighbors<B: PointSet<D> + Sync>(
        &self,
        other: &B,
        radii: &[f64],
        boundary: Boundary,
    ) -> Result<Vec<u64>, QueryError> {
        Join::new(self, other, &Euclid, false).par_count(radii, boundary)
    }
}

impl<P: Joins<D> + Sync, const D: usize> ParallelJoins<D> for P {}
