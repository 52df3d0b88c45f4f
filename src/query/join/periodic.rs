//! [`PeriodicJoins`]: the joins of [`Joins`](super::Joins) on a periodic domain ([`Torus`]),
//! with minimum-image distances, for every point set. The same dual-tree traversals (Gray and
//! Moore, 2001) run with the minimum-image squared Euclidean distance ([`MinImage`]) as their
//! [`PairDistance`](super::bounds::PairDistance): its box-to-box bounds wrap each axis, so a
//! node pair across a face is as near as its nearest images (see [`bounds`](super::bounds)).
//!
//! Each pair of points is one pair of the traversal and is judged by its one minimum-image
//! distance, so it is reported (or counted) once whatever the radius, even one of half a period
//! or more, where a ball would meet several images of the same point.

use super::{Boundary, Join, KnnTable, SparseDistances};
use crate::query::{PointSet, QueryError, Torus};
use core::ops::ControlFlow;

/// The joins of [`Joins`](super::Joins) on a periodic domain, for every [`PointSet`] (in the
/// prelude): distances along the wrapping axes of `torus` are the shortest over all images
/// (scipy's `cKDTree(boxsize=...)` joins). Distances are squared, radii are not, as in
/// [`Joins`](super::Joins); a pair is within `r` when its squared minimum-image distance is
/// within `r * r` ([`Boundary`]), so a radius beyond half the diagonal of the period box takes
/// in every pair, each once.
///
/// Build the trees from points in the period box ([`Torus::prepare`] wraps or refuses the
/// others and moves a point on the upper face to the lower one); the distances are minimum
/// images for any coordinates, though.
///
/// ```
/// use core::ops::ControlFlow;
/// use orthtree::prelude::*;
/// use orthtree::query::{Boundary, OutsidePoints, Torus};
/// use orthtree::PointTree;
/// let torus = Torus::wrapping([0.0; 2], [10.0; 2]).unwrap();
/// let pts = torus.prepare(&[[0.5, 5.0], [9.5, 5.0], [5.0, 5.0]], OutsidePoints::Refuse).unwrap();
/// let entries: Vec<([f64; 2], usize)> = pts.iter().enumerate().map(|(i, p)| (*p, i)).collect();
/// let t = PointTree::new(&entries).unwrap();
/// let mut pairs = Vec::new();
/// let _ = t.periodic_pairs_within(&torus, 1.0, Boundary::Inclusive, |s, u, d| {
///     pairs.push((t.items()[s].min(t.items()[u]), t.items()[s].max(t.items()[u]), d));
///     ControlFlow::<()>::Continue(())
/// });
/// assert_eq!(pairs, [(0, 1, 1.0)]); // across the face, at 1
/// // every pair once, however large the radius
/// assert_eq!(t.periodic_count_pairs_within(&torus, &[1.0, 5.0, 100.0], Boundary::Inclusive).unwrap(), [1, 3, 3]);
/// ```
pub trait PeriodicJoins<const D: usize>: PointSet<D> + Sized {
    /// The `k` nearest points of `other` to every point of this set under the minimum-image
    /// squared Euclidean distance: row `s` is exactly
    /// `other.periodic_k_nearest(torus, self.point(s), k)` (ties included).
    ///
    /// # Complexity
    /// That of [`Joins::k_nearest_join`](super::Joins::k_nearest_join).
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Torus, Quadtree};
    /// let torus = Torus::wrapping([0.0; 2], [4.0; 2]).unwrap();
    /// let a = Quadtree::new(&[([0.0, 0.0], ())]).unwrap();
    /// let b = Quadtree::new(&[([3.0, 3.0], 'x'), ([1.5, 1.5], 'y')]).unwrap();
    /// let table = a.periodic_k_nearest_join(&torus, &b, 1);
    /// assert_eq!(b.items()[table.row(0).0[0]], 'x'); // (3, 3) is at (-1, -1)
    /// assert_eq!(table.row(0).1, [2.0]);
    /// ```
    fn periodic_k_nearest_join<B: PointSet<D>>(
        &self,
        torus: &Torus<D>,
        other: &B,
        k: usize,
    ) -> KnnTable {
        Join::new(self, other, &torus.squared_euclidean(), false).knn(k)
    }

    /// The `k` nearest other points to every point of this set under the minimum-image squared
    /// Euclidean distance, the point itself excluded (a duplicate is another point).
    ///
    /// # Complexity
    /// That of [`Joins::k_nearest_join`](super::Joins::k_nearest_join).
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Torus, PointTree};
    /// let torus = Torus::wrapping([0.0], [10.0]).unwrap();
    /// let t = PointTree::new(&[([0.5], 'a'), ([9.0], 'b'), ([4.0], 'c')]).unwrap();
    /// let table = t.periodic_k_nearest_self(&torus, 1);
    /// let near = |c: char| t.items()[table.row(t.items().iter().position(|&x| x == c).unwrap()).0[0]];
    /// assert_eq!((near('a'), near('b'), near('c')), ('b', 'a', 'a')); // 'a', 'b': 1.5 across the face
    /// ```
    fn periodic_k_nearest_self(&self, torus: &Torus<D>, k: usize) -> KnnTable {
        Join::new(self, self, &torus.squared_euclidean(), true).knn(k)
    }

    /// Calls `visit(s, t, d)` for every unordered pair of distinct slots `s < t` within
    /// minimum-image distance `r` (squared distance `d`), each once; stops at the first
    /// [`ControlFlow::Break`] and returns it. Nothing is collected.
    ///
    /// # Errors
    /// A negative or NaN `r` ([`QueryError::InvalidRadius`]); then `visit` is not called.
    ///
    /// # Complexity
    /// About `O(n + p)` for `p` pairs on well-spread points, as
    /// [`Joins::pairs_within`](super::Joins::pairs_within).
    fn periodic_pairs_within<Br>(
        &self,
        torus: &Torus<D>,
        r: f64,
        boundary: Boundary,
        visit: impl FnMut(usize, usize, f64) -> ControlFlow<Br>,
    ) -> Result<ControlFlow<Br>, QueryError> {
        Join::new(self, self, &torus.squared_euclidean(), true).pairs(r, boundary, visit)
    }

    /// Calls `visit(s, t, d)` for every slot `s` of this set and `t` of `other` within
    /// minimum-image distance `r` (squared distance `d`); stops at the first
    /// [`ControlFlow::Break`] and returns it. Nothing is collected.
    ///
    /// # Errors
    /// A negative or NaN `r` ([`QueryError::InvalidRadius`]); then `visit` is not called.
    ///
    /// ```
    /// use core::ops::ControlFlow;
    /// use orthtree::prelude::*;
    /// use orthtree::{query::{Boundary, Torus}, Quadtree};
    /// let torus = Torus::new([0.0; 2], [4.0; 2], [true, false]).unwrap();
    /// let a = Quadtree::new(&[([0.0, 0.0], ())]).unwrap();
    /// let b = Quadtree::new(&[([3.5, 0.0], ()), ([0.0, 3.5], ())]).unwrap();
    /// let mut n = 0;
    /// let _ = a.periodic_pairs_within_other(&torus, &b, 1.0, Boundary::Inclusive, |_, _, d| {
    ///     assert_eq!(d, 0.25);
    ///     n += 1;
    ///     ControlFlow::<()>::Continue(())
    /// });
    /// assert_eq!(n, 1); // only axis 0 wraps
    /// ```
    fn periodic_pairs_within_other<B: PointSet<D>, Br>(
        &self,
        torus: &Torus<D>,
        other: &B,
        r: f64,
        boundary: Boundary,
        visit: impl FnMut(usize, usize, f64) -> ControlFlow<Br>,
    ) -> Result<ControlFlow<Br>, QueryError> {
        Join::new(self, other, &torus.squared_euclidean(), false).pairs(r, boundary, visit)
    }

    /// For each radius of `radii` (non-decreasing), the number of unordered pairs of distinct
    /// points of this set within it under the minimum-image distance, in one traversal.
    ///
    /// # Errors
    /// A negative or NaN radius ([`QueryError::InvalidRadius`]); a radius smaller than the one
    /// before it ([`QueryError::UnsortedRadii`]).
    fn periodic_count_pairs_within(
        &self,
        torus: &Torus<D>,
        radii: &[f64],
        boundary: Boundary,
    ) -> Result<Vec<u64>, QueryError> {
        Join::new(self, self, &torus.squared_euclidean(), true).count(radii, boundary)
    }

    /// For each radius of `radii` (non-decreasing), the number of pairs of a point of this set
    /// and one of `other` within it under the minimum-image distance (scipy's
    /// `count_neighbors` with `boxsize`), in one traversal.
    ///
    /// # Errors
    /// Those of [`PeriodicJoins::periodic_count_pairs_within`].
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::{Boundary, Torus}, PointTree};
    /// let torus = Torus::wrapping([0.0], [8.0]).unwrap();
    /// let a = PointTree::new(&[([0.0], ()), ([4.0], ())]).unwrap();
    /// let b = PointTree::new(&[([7.0], ()), ([2.0], ())]).unwrap();
    /// let counts = a.periodic_count_neighbors(&torus, &b, &[1.0, 2.0, 3.0], Boundary::Inclusive);
    /// assert_eq!(counts.unwrap(), [1, 3, 4]); // 0-7 at 1; 0-2, 4-2 at 2; 4-7 at 3
    /// ```
    fn periodic_count_neighbors<B: PointSet<D>>(
        &self,
        torus: &Torus<D>,
        other: &B,
        radii: &[f64],
        boundary: Boundary,
    ) -> Result<Vec<u64>, QueryError> {
        Join::new(self, other, &torus.squared_euclidean(), false).count(radii, boundary)
    }

    /// Every pair of a point of this set (row) and of `other` (column) within minimum-image
    /// distance `r`, with its squared distance, as a sparse matrix sorted by row then column.
    ///
    /// # Errors
    /// A negative or NaN `r` ([`QueryError::InvalidRadius`]).
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::{Boundary, Torus}, PointTree};
    /// let torus = Torus::wrapping([0.0], [8.0]).unwrap();
    /// let t = PointTree::new(&[([0.0], ()), ([7.0], ())]).unwrap();
    /// let m = t.periodic_sparse_distance_matrix(&torus, &t, 1.0, Boundary::Exclusive).unwrap();
    /// assert_eq!(m.len(), 2); // the diagonal: the pair at exactly 1 is left out
    /// ```
    fn periodic_sparse_distance_matrix<B: PointSet<D>>(
        &self,
        torus: &Torus<D>,
        other: &B,
        r: f64,
        boundary: Boundary,
    ) -> Result<SparseDistances, QueryError> {
        Join::new(self, other, &torus.squared_euclidean(), false).sparse(r, boundary)
    }
}

impl<P: PointSet<D>, const D: usize> PeriodicJoins<D> for P {}
