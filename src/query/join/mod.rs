//! Tree-against-tree queries (joins), written once for every [`PointSet`]: all k-nearest
//! neighbours between two sets or within one, all pairs within a radius, the number of pairs
//! within each of a list of radii, and the sparse distance matrix ([`Joins`]; their parallel
//! forms in `ParallelJoins` and `ParallelPeriodicJoins` under the `rayon` feature).
//!
//! Algorithm: the dual-tree traversal of Gray and Moore ("N-body problems in statistical
//! learning", NIPS 2001) over the cells of both trees: node pairs are pruned, or counted whole,
//! by the minimum and maximum distance between their boxes, on an explicit stack; pairs of
//! small nodes go to a leaf kernel that filters each run by the other node's box and tests one
//! point against a block of the other's points at a time ([`scan`]). Distances are
//! squared Euclidean in `f64`, as [`PointSet::k_nearest`] computes them (exact for integer
//! coordinates whose squares `f64` holds); the only geometry the engines see is the small seam
//! of [`bounds`], so another distance plugs in there: a periodic domain's minimum-image
//! distance gives the same joins on a torus ([`PeriodicJoins`]). Every engine, serial or
//! parallel, is a method of [`Join`] (the two sets, their distance, whether it is a self-join),
//! so that each public method names its sets and distance once and calls one engine.

mod bounds;
mod knn;
mod knn_cands;
mod knn_group;
mod knn_map;
mod knn_pool;
mod pairs;
#[cfg(feature = "rayon")]
mod par_engines;
#[cfg(feature = "rayon")]
mod parallel;
mod periodic;
#[cfg(feature = "rayon")]
mod periodic_parallel;
mod radius;
mod scan;
mod slots;
mod sparse;
mod traverse;

#[cfg(test)]
pub(crate) use knn::assert_copies_agree;
pub use knn::KnnTable;
#[cfg(feature = "rayon")]
pub use parallel::ParallelJoins;
pub use periodic::PeriodicJoins;
#[cfg(feature = "rayon")]
pub use periodic_parallel::ParallelPeriodicJoins;
pub use radius::Boundary;
pub use sparse::{CsrDistances, SparseDistances};

use super::{PointSet, QueryError};
use bounds::{Euclid, PairDistance};
use core::marker::PhantomData;
use core::ops::ControlFlow;
use pairs::{CountWithin, PairsWithin};
use traverse::Dual;

/// The joins of a [`PointSet`] with itself or with another one (implemented for every point
/// set; in the prelude). Slots are the sets' [`PointSet::items`] positions; distances are
/// squared Euclidean; radii are Euclidean, a pair within `r` when its squared distance is
/// within `r * r` (see [`Boundary`]).
pub trait Joins<const D: usize>: PointSet<D> + Sized {
    /// The `k` nearest points of `other` to every point of this set: row `s` of the table holds
    /// slot `s`'s neighbours (slots of `other`), sorted by distance, ties broken as
    /// [`PointSet::k_nearest`] breaks them (row `s` is exactly `other.k_nearest(self.point(s),
    /// k)`). Fewer than `k` per row when `other` holds fewer points.
    ///
    /// # Complexity
    /// About `O(n (log m + k))` on well-spread points: each leaf of this set searches
    /// `other` once for all its points.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{CompressedTree, Quadtree};
    /// let a = Quadtree::new(&[([0.0, 0.0], ()), ([9.0, 9.0], ())]).unwrap();
    /// let b = CompressedTree::new(&[([8.0, 8.0], 'x'), ([1.0, 0.0], 'y'), ([0.0, 2.0], 'z')]).unwrap();
    /// let t = a.k_nearest_join(&b, 2);
    /// let row = |p: [f64; 2]| (0..2).find(|&s| *a.point(s) == p).unwrap();
    /// let (slots, distances) = t.row(row([0.0, 0.0]));
    /// let items: Vec<char> = slots.iter().map(|&s| b.items()[s]).collect();
    /// assert_eq!((items, distances), (vec!['y', 'z'], &[1.0, 4.0][..]));
    /// assert_eq!(b.items()[t.row(row([9.0, 9.0])).0[0]], 'x');
    /// ```
    fn k_nearest_join<B: PointSet<D>>(&self, other: &B, k: usize) -> KnnTable {
        Join::new(self, other, &Euclid, false).knn(k)
    }

    /// The `k` nearest other points to every point of this set: row `s` is
    /// `self.k_nearest(self.point(s), k + 1)` without slot `s` itself (a duplicate of it is
    /// another point, at distance 0). Fewer than `k` per row when the set holds `k` or fewer.
    ///
    /// # Complexity
    /// That of [`Joins::k_nearest_join`].
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::PointTree;
    /// let t = PointTree::new(&[([0, 0], 'a'), ([0, 0], 'b'), ([5, 0], 'c')]).unwrap();
    /// let table = t.k_nearest_self(1);
    /// let near = |s: usize| t.items()[table.row(s).0[0]];
    /// assert_eq!((near(0), near(1), near(2)), ('b', 'a', 'a'));
    /// assert_eq!(table.row(0).1, [0.0]);
    /// ```
    fn k_nearest_self(&self, k: usize) -> KnnTable {
        Join::new(self, self, &Euclid, true).knn(k)
    }

    /// `f(s, neighbours, distances)` for every slot `s` of this set, with the row that
    /// [`Joins::k_nearest_join`] would give it (the slots of its `k` nearest in `other`, sorted,
    /// and their squared distances), and only `f`'s values kept: one per slot, in slot order.
    /// For a few numbers per point (a mean distance, a density, a normal) without the table's
    /// `16 k` bytes per point. `f` is called once per slot, in no particular order.
    ///
    /// # Complexity
    /// That of [`Joins::k_nearest_join`]; memory: the values, and the rows of one group of at
    /// most a few dozen points at a time.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let a = Quadtree::new(&[([0.0, 0.0], ()), ([9.0, 9.0], ())]).unwrap();
    /// let b = Quadtree::new(&[([8.0, 8.0], ()), ([1.0, 0.0], ()), ([0.0, 2.0], ())]).unwrap();
    /// let nearest = a.map_k_nearest_join(&b, 2, |_, _, d2| d2[0]);
    /// let s = |p: [f64; 2]| (0..2).find(|&s| *a.point(s) == p).unwrap();
    /// assert_eq!((nearest[s([0.0, 0.0])], nearest[s([9.0, 9.0])]), (1.0, 2.0));
    /// ```
    fn map_k_nearest_join<B: PointSet<D>, T>(
        &self,
        other: &B,
        k: usize,
        f: impl FnMut(usize, &[usize], &[f64]) -> T,
    ) -> Vec<T> {
        Join::new(self, other, &Euclid, false).map_knn(k, f)
    }

    /// [`Joins::map_k_nearest_join`] for the self-join: `f(s, neighbours, distances)` with the
    /// row of [`Joins::k_nearest_self`] (slot `s` itself excluded), one value per slot, in slot
    /// order.
    ///
    /// # Complexity
    /// That of [`Joins::k_nearest_self`], with the memory of [`Joins::map_k_nearest_join`].
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::PointTree;
    /// let t = PointTree::new(&[([0.0], 'a'), ([1.0], 'b'), ([3.0], 'c'), ([7.0], 'd')]).unwrap();
    /// // the mean distance to the two nearest others, per slot
    /// let mean = t.map_k_nearest_self(2, |_, _, d2| d2.iter().map(|d| d.sqrt()).sum::<f64>() / 2.0);
    /// let by_item = |c: char| mean[t.items().iter().position(|&x| x == c).unwrap()];
    /// assert_eq!((by_item('a'), by_item('b'), by_item('d')), (2.0, 1.5, 5.0));
    /// ```
    fn map_k_nearest_self<T>(
        &self,
        k: usize,
        f: impl FnMut(usize, &[usize], &[f64]) -> T,
    ) -> Vec<T> {
        Join::new(self, self, &Euclid, true).map_knn(k, f)
    }

    /// Calls `visit(s, t, d)` for every unordered pair of distinct slots `s < t` whose points
    /// are within `r` (squared distance `d`), each once, in no particular order; stops at the
    /// first [`ControlFlow::Break`] and returns it. Nothing is collected: memory stays that of
    /// the traversal's stack, however many pairs there are.
    ///
    /// # Errors
    /// A negative or NaN `r` ([`QueryError::InvalidRadius`]); then `visit` is not called.
    ///
    /// # Complexity
    /// About `O(n + p)` for `p` pairs on well-spread points.
    ///
    /// ```
    /// use core::ops::ControlFlow;
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Boundary, Quadtree};
    /// let pts: Vec<([f64; 2], ())> = (0..10).map(|i| ([i as f64, 0.0], ())).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// let mut pairs = Vec::new();
    /// let _ = t.pairs_within(1.0, Boundary::Inclusive, |s, u, _| {
    ///     pairs.push((s, u));
    ///     ControlFlow::<()>::Continue(())
    /// });
    /// assert_eq!(pairs.len(), 9);
    /// assert!(pairs.iter().all(|&(s, u)| s < u));
    /// // stop at the first pair
    /// let first = t.pairs_within(1.0, Boundary::Inclusive, |s, u, _| ControlFlow::Break((s, u)));
    /// assert!(matches!(first, Ok(ControlFlow::Break(_))));
    /// ```
    fn pairs_within<Br>(
        &self,
        r: f64,
        boundary: Boundary,
        visit: impl FnMut(usize, usize, f64) -> ControlFlow<Br>,
    ) -> Result<ControlFlow<Br>, QueryError> {
        Join::new(self, self, &Euclid, true).pairs(r, boundary, visit)
    }

    /// Calls `visit(s, t, d)` for every slot `s` of this set and `t` of `other` whose points
    /// are within `r` (squared distance `d`), in no particular order; stops at the first
    /// [`ControlFlow::Break`] and returns it. Nothing is collected.
    ///
    /// # Errors
    /// A negative or NaN `r` ([`QueryError::InvalidRadius`]); then `visit` is not called.
    ///
    /// ```
    /// use core::ops::ControlFlow;
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Boundary, DynamicPointTree, Quadtree};
    /// let a = Quadtree::new(&[([0.0, 0.0], ()), ([5.0, 5.0], ())]).unwrap();
    /// let b = DynamicPointTree::new(&[([0.5, 0.0], ()), ([5.0, 6.0], ())]).unwrap();
    /// let mut n = 0;
    /// let _ = a.pairs_within_other(&b, 1.0, Boundary::Exclusive, |_, _, _| {
    ///     n += 1;
    ///     ControlFlow::<()>::Continue(())
    /// });
    /// assert_eq!(n, 1); // (5, 5)-(5, 6) is at exactly 1: left out
    /// ```
    fn pairs_within_other<B: PointSet<D>, Br>(
        &self,
        other: &B,
        r: f64,
        boundary: Boundary,
        visit: impl FnMut(usize, usize, f64) -> ControlFlow<Br>,
    ) -> Result<ControlFlow<Br>, QueryError> {
        Join::new(self, other, &Euclid, false).pairs(r, boundary, visit)
    }

    /// For each radius of `radii` (non-decreasing), the number of unordered pairs of distinct
    /// points of this set within it, in one traversal: a node pair whose whole distance range
    /// falls between two radii is counted by multiplying its sizes, without visiting a point.
    ///
    /// # Errors
    /// A negative or NaN radius ([`QueryError::InvalidRadius`]); a radius smaller than the one
    /// before it ([`QueryError::UnsortedRadii`], naming its position).
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::{Boundary, QueryError}, Quadtree};
    /// let pts: Vec<([f64; 2], ())> = (0..4).map(|i| ([i as f64, 0.0], ())).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// assert_eq!(t.count_pairs_within(&[0.5, 1.0, 2.0, 9.0], Boundary::Inclusive).unwrap(), [0, 3, 5, 6]);
    /// assert_eq!(
    ///     t.count_pairs_within(&[2.0, 1.0], Boundary::Inclusive),
    ///     Err(QueryError::UnsortedRadii { index: 1 })
    /// );
    /// ```
    fn count_pairs_within(
        &self,
        radii: &[f64],
        boundary: Boundary,
    ) -> Result<Vec<u64>, QueryError> {
        Join::new(self, self, &Euclid, true).count(radii, boundary)
    }

    /// For each radius of `radii` (non-decreasing), the number of pairs of a point of this set
    /// and a point of `other` within it (scipy's `count_neighbors`), in one traversal.
    ///
    /// # Errors
    /// Those of [`Joins::count_pairs_within`].
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Boundary, Quadtree};
    /// let a = Quadtree::new(&[([0.0, 0.0], ()), ([1.0, 0.0], ())]).unwrap();
    /// let b = Quadtree::new(&[([0.0, 0.0], ()), ([3.0, 0.0], ())]).unwrap();
    /// assert_eq!(a.count_neighbors(&b, &[0.0, 1.0, 3.0], Boundary::Inclusive).unwrap(), [1, 2, 4]);
    /// ```
    fn count_neighbors<B: PointSet<D>>(
        &self,
        other: &B,
        radii: &[f64],
        boundary: Boundary,
    ) -> Result<Vec<u64>, QueryError> {
        Join::new(self, other, &Euclid, false).count(radii, boundary)
    }

    /// Every pair of a point of this set (row) and a point of `other` (column) within `r`,
    /// with its squared distance, as a sparse matrix sorted by row then column (pass the set
    /// itself as `other` for the symmetric matrix with its diagonal, as scipy gives it).
    ///
    /// # Errors
    /// A negative or NaN `r` ([`QueryError::InvalidRadius`]).
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Boundary, Quadtree};
    /// let t = Quadtree::new(&[([0.0, 0.0], ()), ([0.0, 2.0], ())]).unwrap();
    /// let m = t.sparse_distance_matrix(&t, 2.0, Boundary::Inclusive).unwrap();
    /// let all: Vec<_> = m.iter().collect();
    /// assert_eq!(all, [(0, 0, 0.0), (0, 1, 4.0), (1, 0, 4.0), (1, 1, 0.0)]);
    /// ```
    fn sparse_distance_matrix<B: PointSet<D>>(
        &self,
        other: &B,
        r: f64,
        boundary: Boundary,
    ) -> Result<SparseDistances, QueryError> {
        Join::new(self, other, &Euclid, false).sparse(r, boundary)
    }
}

impl<P: PointSet<D>, const D: usize> Joins<D> for P {}

/// A join: the querying set, the other set, the distance between their points, and whether the
/// other set is the querying one (a self-join: unordered pairs once, no point its own
/// neighbour). The engines, serial and parallel, are its methods, so that every front end
/// ([`Joins`], [`PeriodicJoins`] and their parallel forms) names its sets and distance once.
/// The dimension is a parameter of the type (its last field only marks it), so that the bounds
/// the engines need are stated once for each block of them.
pub(crate) struct Join<'s, A, B, P, const D: usize>(
    pub(crate) &'s A,
    pub(crate) &'s B,
    pub(crate) &'s P,
    pub(crate) bool,
    PhantomData<[(); D]>,
);

impl<A, B, P, const D: usize> Clone for Join<'_, A, B, P, D> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<A, B, P, const D: usize> Copy for Join<'_, A, B, P, D> {}

impl<'s, A: PointSet<D>, B: PointSet<D>, P: PairDistance<D>, const D: usize> Join<'s, A, B, P, D> {
    /// The join of `a` with `b` under `metric` (`same`: `b` is `a`).
    fn new(a: &'s A, b: &'s B, metric: &'s P, same: bool) -> Self {
        Join(a, b, metric, same, PhantomData)
    }

    /// The dual-tree traversal of the two sets' indices.
    fn dual(self) -> Dual<'s, A::Index, B::Index, P, D> {
        Dual::new(self.0.index(), self.1.index(), self.2)
    }

    /// The pairs within `r` (under `boundary`) handed to `visit`, each unordered pair once in a
    /// self-join.
    fn pairs<Br>(
        self,
        r: f64,
        boundary: Boundary,
        visit: impl FnMut(usize, usize, f64) -> ControlFlow<Br>,
    ) -> Result<ControlFlow<Br>, QueryError> {
        let Join(a, b, _, same, _) = self;
        let r2 = radius::squared_radius(r)?;
        let mut v = PairsWithin::new(self, (r2, boundary), [a.len(), b.len()], visit);
        let start = self.dual().roots(same, (), &mut v.visitor());
        Ok(v.walk(start))
    }

    /// The counts within each of `radii`.
    fn count(self, radii: &[f64], boundary: Boundary) -> Result<Vec<u64>, QueryError> {
        let Join(a, b, _, same, _) = self;
        let r2 = radius::squared_radii(radii)?;
        if r2.is_empty() {
            return Ok(Vec::new());
        }
        let mut v = CountWithin::new(self, (&r2, boundary), [a.len(), b.len()]);
        let dual = self.dual();
        let start = dual.roots(same, (0, r2.len()), &mut v);
        let _ = dual.run(start, &mut v);
        Ok(v.counts())
    }

    /// The sparse distance matrix of the pairs within `r` (of a join that is not a self-join:
    /// every pair of a row and a column).
    fn sparse(self, r: f64, boundary: Boundary) -> Result<SparseDistances, QueryError> {
        let mut triples = Vec::new();
        let _ = self.pairs(r, boundary, |s, t, d| {
            triples.push((s, t, d));
            ControlFlow::<()>::Continue(())
        })?;
        Ok(SparseDistances::new((self.0.len(), self.1.len()), triples))
    }
}
