//! Batches of k-nearest queries answered in an order that keeps the tree in cache
//! ([`BatchQueries`], written once for every point set), and the [`BatchError`] of every batch
//! form (these and the `par_` forms of [`ParallelQueries`](super::ParallelQueries)).
//!
//! Every query is checked first, in the order given. Then the batch is answered query by query
//! by the serial engine, but not in that order: the queries are sorted by the Morton key of
//! their place in the set's domain, the order of the tree's own points ([`morton_order`]).
//! Consecutive queries then walk mostly the same nodes and scan the same runs, still in cache
//! from the query before, where queries in a random order each fetch their nodes and points
//! from memory (the locality space-filling-curve orderings give a batch of tree queries, as in
//! Warren and Salmon's hashed octree, 1993). Each answer, exactly the single query's, is handed
//! to a visitor with the query's position, in one list reused from query to query: nothing is
//! held for the whole batch (a table of every answer, written at its query's row, made the
//! batch no faster than the queries one by one in the order given).
//!
//! Measured (`cargo run --release -p orthtree-compare --bin joins_compare -- --workload
//! periodic`): see README's "Periodic and join queries".

use super::index::SpatialIndex;
use super::knn::{k_nearest, Neighbor};
use super::metric::{Metric, SquaredEuclidean};
use super::periodic::Torus;
use super::point_set::{with_item, NeighborIn};
use super::{query_point, PointSet, QueryError};
use crate::geom::{Aabb, RootGeometry, Scalar};

/// A batch refused because of one query: its position in the batch and what is wrong with it.
///
/// ```
/// use orthtree::prelude::*;
/// use orthtree::{query::BatchError, Quadtree};
/// let t = Quadtree::new(&[([0.0, 0.0], 'a')]).unwrap();
/// let err = t.k_nearest_batch(&[[0.0, 0.0], [f64::NAN, 1.0]], 1, |_, _| ()).unwrap_err();
/// assert_eq!(err.index, 1);
/// assert!(err.to_string().contains("query 1"));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BatchError {
    /// The position of the first bad query in the batch.
    pub index: usize,
    /// What is wrong with it.
    pub error: QueryError,
}

impl core::fmt::Display for BatchError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "query {} of the batch: {}", self.index, self.error)
    }
}

impl std::error::Error for BatchError {}

/// The positions of `queries` sorted by their Morton keys in the cube enclosing `domain`
/// ([`RootGeometry::key`], the order of a point tree's own points): a coordinate outside the
/// cube counts as on its nearest face, and a NaN lands on a face too (such a query is refused
/// when answered; its place in the order only decides when).
///
/// # Complexity
/// O(n log n) time, 16 bytes per query.
pub(crate) fn morton_order<S: Scalar, const D: usize>(
    queries: &[[S; D]],
    domain: &Aabb<f64, D>,
) -> Vec<usize> {
    let geometry = RootGeometry::enclosing(domain);
    let mut keyed: Vec<(u64, usize)> = queries
        .iter()
        .enumerate()
        .map(|(i, q)| (geometry.scalar_key(q), i))
        .collect();
    keyed.sort_unstable();
    keyed.into_iter().map(|(_, i)| i).collect()
}

/// The answers of a batch put back in query order: `answers[j]` is the answer to query
/// `order[j]`, `order` a permutation of the positions. The first bad query in batch order (the
/// smallest position) fails the batch.
#[cfg(feature = "rayon")]
pub(crate) fn in_query_order<A>(
    order: &[usize],
    answers: Vec<Result<A, QueryError>>,
) -> Result<Vec<A>, BatchError> {
    let mut placed: Vec<Option<A>> = core::iter::repeat_with(|| None).take(order.len()).collect();
    let mut first: Option<BatchError> = None;
    for (&index, answer) in order.iter().zip(answers) {
        match answer {
            Ok(a) => placed[index] = Some(a),
            Err(error) if first.is_none_or(|f| index < f.index) => {
                first = Some(BatchError { index, error });
            }
            Err(_) => {}
        }
    }
    match first {
        Some(e) => Err(e),
        None => Ok(placed.into_iter().flatten().collect()),
    }
}

/// Hands `visit` the `k` nearest points of `set` to each query under `metric`, query by query
/// in Morton order, with the query's position; one list reused for every query.
fn visit_by<'s, P: PointSet<D> + ?Sized, M: Metric<D>, const D: usize>(
    set: &'s P,
    queries: &[[P::Scalar; D]],
    k: usize,
    metric: &M,
    mut visit: impl FnMut(usize, &[NeighborIn<'s, P, D>]),
) -> Result<(), BatchError> {
    let exact = queries
        .iter()
        .enumerate()
        .map(|(index, p)| query_point(p).map_err(|error| BatchError { index, error }))
        .collect::<Result<Vec<[f64; D]>, BatchError>>()?;
    let index = set.index();
    let mut list = Vec::with_capacity(k.min(index.points().len()));
    for q in morton_order(&exact, set.domain()) {
        let found = k_nearest(index, &exact[q], k, f64::INFINITY, metric);
        list.clear();
        list.extend(
            found
                .into_iter()
                .map(|(d, i)| with_item(set, Neighbor::at(index, d, i))),
        );
        visit(q, &list);
    }
    Ok(())
}

/// The serial batch forms of the k-nearest queries, for every point set (in the prelude): each
/// query's neighbours, exactly as the single query finds them, handed to a visitor with the
/// query's position, in the cache-friendly order of the module doc (not the order given).
pub trait BatchQueries<const D: usize>: PointSet<D> {
    /// [`PointSet::k_nearest`] of every query point: `visit(q, neighbours)` once for each
    /// position `q` in `queries`, nearest first, in Morton order of the queries.
    ///
    /// # Errors
    /// The first bad query (a NaN, infinite or inexact coordinate), as a [`BatchError`] naming
    /// its position; nothing is visited then.
    ///
    /// # Complexity
    /// That of the single queries, plus O(q log q) to order `q` queries; 8 (D + 2) bytes per
    /// query while it runs, one list of `k` neighbours.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let pts: Vec<([f64; 2], usize)> = (0..100).map(|i| ([i as f64, 0.0], i)).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// let mut items = vec![Vec::new(); 2];
    /// t.k_nearest_batch(&[[97.9, 0.0], [10.2, 0.0]], 2, |q, near| {
    ///     items[q] = near.iter().map(|n| *n.item).collect();
    /// })
    /// .unwrap();
    /// assert_eq!(items, [vec![98, 97], vec![10, 11]]);
    /// ```
    fn k_nearest_batch<'s>(
        &'s self,
        queries: &[[Self::Scalar; D]],
        k: usize,
        visit: impl FnMut(usize, &[NeighborIn<'s, Self, D>]),
    ) -> Result<(), BatchError> {
        visit_by(self, queries, k, &SquaredEuclidean, visit)
    }

    /// [`PeriodicQueries::periodic_k_nearest`](super::PeriodicQueries::periodic_k_nearest) of
    /// every query point on `torus`: `visit(q, neighbours)` once for each position `q` in
    /// `queries`, nearest first (squared minimum-image distances), in Morton order of the
    /// queries.
    ///
    /// # Errors
    /// The first bad query, as a [`BatchError`] naming its position; nothing is visited then.
    ///
    /// # Complexity
    /// As [`BatchQueries::k_nearest_batch`].
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Torus, Quadtree};
    /// let torus = Torus::wrapping([0.0; 2], [10.0; 2]).unwrap();
    /// let t = Quadtree::new(&[([0.5, 5.0], 'a'), ([5.0, 5.0], 'b')]).unwrap();
    /// let mut nearest = [(' ', 0.0); 2];
    /// t.periodic_k_nearest_batch(&torus, &[[9.5, 5.0], [4.0, 5.0]], 1, |q, near| {
    ///     nearest[q] = (*near[0].item, near[0].distance);
    /// })
    /// .unwrap();
    /// assert_eq!(nearest, [('a', 1.0), ('b', 1.0)]); // 'a' across the face
    /// ```
    fn periodic_k_nearest_batch<'s>(
        &'s self,
        torus: &Torus<D>,
        queries: &[[Self::Scalar; D]],
        k: usize,
        visit: impl FnMut(usize, &[NeighborIn<'s, Self, D>]),
    ) -> Result<(), BatchError> {
        visit_by(self, queries, k, &torus.squared_euclidean(), visit)
    }
}

impl<P: PointSet<D>, const D: usize> BatchQueries<D> for P {}

#[cfg(test)]
mod tests {
    use super::morton_order;
    use crate::geom::Aabb;

    /// Answers land at their queries' positions; of several errors the smallest position wins.
    #[cfg(feature = "rayon")]
    #[test]
    fn answers_come_back_in_query_order_and_the_first_error_wins() {
        use super::in_query_order;
        use crate::query::QueryError;
        let order = [2, 0, 1];
        assert_eq!(
            in_query_order(&order, vec![Ok('c'), Ok('a'), Ok('b')]).unwrap(),
            ['a', 'b', 'c']
        );
        let bad = vec![
            Err(QueryError::NanOffset),
            Ok('a'),
            Err(QueryError::NanOffset),
        ];
        assert_eq!(in_query_order(&order, bad).unwrap_err().index, 1);
        assert!(in_query_order::<char>(&[], Vec::new()).unwrap().is_empty());
    }

    /// The order is a permutation, nearby queries are neighbours in it, and points outside the
    /// domain or NaN are ordered without a panic.
    #[test]
    fn the_order_is_a_permutation_that_groups_nearby_queries() {
        let domain = Aabb::new([0.0, 0.0], [8.0, 8.0]).unwrap();
        let queries = [
            [7.9, 7.9],
            [0.1, 0.1],
            [7.8, 7.9],
            [f64::NAN, 1.0],
            [-5.0, 100.0],
            [0.2, 0.1],
        ];
        let order = morton_order(&queries, &domain);
        let mut sorted = order.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, [0, 1, 2, 3, 4, 5]);
        let at = |i: usize| order.iter().position(|&j| j == i).unwrap();
        assert_eq!(at(1).abs_diff(at(5)), 1);
        assert_eq!(at(0).abs_diff(at(2)), 1);
        // A degenerate domain (one point, as a tree of one point has) orders them too.
        let flat = Aabb::new([1.0, 1.0], [1.0, 1.0]).unwrap();
        let mut sorted = morton_order(&queries, &flat);
        sorted.sort_unstable();
        assert_eq!(sorted, [0, 1, 2, 3, 4, 5]);
    }
}
