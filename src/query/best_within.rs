//! `best_n_within`: of the points within a radius of a query point, the `n` whose items rank
//! best by a caller's key (kiddo's `best_n_within`, for every point set). One range pass over
//! the ball ([`for_each_in`]) keeps the `n` best (key, slot) pairs in a bounded max-heap, so
//! memory is O(n) whatever the number of points in the ball.

use super::index::SpatialIndex;
use super::knn::Neighbor;
use super::metric::{Metric, SquaredEuclidean};
use super::point_set::{NeighborIn, PointSet};
use super::range::{for_each_in, scan_limit};
use super::region::Ball;
use super::{query_point, QueryError};
use crate::geom::Scalar;
use std::collections::BinaryHeap;

/// The points of `set` within Euclidean distance `radius` (inclusive) of `center` whose items
/// have the `n` smallest `key`s, ties broken by slot, in that order (see
/// [`PointSet::best_n_within`]).
pub(crate) fn best_n_within<'a, P, K, const D: usize>(
    set: &'a P,
    center: &[P::Scalar; D],
    radius: f64,
    n: usize,
    mut key: impl FnMut(&P::Item) -> K,
) -> Result<Vec<NeighborIn<'a, P, D>>, QueryError>
where
    P: PointSet<D> + ?Sized,
    K: Ord,
{
    let c = query_point(center)?;
    let ball = Ball::new(c, radius)?;
    let index = set.index();
    let (points, payloads) = (index.points(), index.payloads());
    // The worst of the kept pairs on top; capacity bounded by the data, never by `n` alone.
    let mut kept: BinaryHeap<(K, usize, usize)> = BinaryHeap::with_capacity(n.min(set.len()));
    if n > 0 {
        for_each_in(index, &ball, scan_limit::<D>(), true, |i| {
            let slot = set.slot_of(i, &payloads[i]);
            let k = key(set.item_of(&payloads[i]));
            if kept.len() < n {
                kept.push((k, slot, i));
            } else if kept
                .peek()
                .is_some_and(|(wk, ws, _)| (&k, slot) < (wk, *ws))
            {
                kept.pop();
                kept.push((k, slot, i));
            }
        })?;
    }
    Ok(kept
        .into_sorted_vec()
        .into_iter()
        .map(|(_, slot, i)| Neighbor {
            point: &points[i],
            item: set.item_of(&payloads[i]),
            distance: SquaredEuclidean.distance(&c, &points[i].map(Scalar::to_f64)),
            index: slot,
        })
        .collect())
}
