//! Batch queries on rayon's threads (feature `rayon`): many k-nearest or range queries against
//! one [`PointSet`], each answered by the serial engine, the batch spread over threads
//! ([`ParallelQueries`], written once for every tree).
//!
//! Results come back in the order of the queries. The k-nearest queries are answered in Morton
//! order, as the serial [`BatchQueries`](super::BatchQueries) answers them, so that each
//! thread's share walks one part of the tree: 10^5 10-nearest queries among 10^6 uniform 3-D
//! points on two threads, medians of 9 runs, three alternated pairs: 118.3-129.3 ms against
//! 134.3-165.0 in the order given. A bad query (a NaN coordinate, a negative radius) fails the
//! batch with a [`BatchError`] naming the first bad query's position.

use super::index::SpatialIndex;
use super::ordered_batch::{in_query_order, morton_order};
use super::point_set::NeighborIn;
use super::range::{for_each_in, scan_limit};
use super::{BatchError, PointSet, QueryError, Region};
use crate::par_tasks::map_indices;

/// Runs `answer` on every query in parallel, in the order given; the first error in batch
/// order wins, as for the k-nearest batch ([`in_query_order`] with the identity order).
fn run_batch<Q: Sync, A: Send>(
    queries: &[Q],
    answer: impl Fn(&Q) -> Result<A, QueryError> + Sync,
) -> Result<Vec<A>, BatchError> {
    let order: Vec<usize> = (0..queries.len()).collect();
    in_query_order(&order, map_indices(queries.len(), &|i| answer(&queries[i])))
}

/// The batch forms of [`PointSet`]'s queries, on rayon's threads, for every point set that can
/// be shared between threads (implemented for all of them; in the prelude).
pub trait ParallelQueries<const D: usize>: PointSet<D> + Sync
where
    Self::Scalar: Sync,
    Self::Item: Sync,
{
    /// [`PointSet::k_nearest`] for every query point, in parallel; answers in query order.
    ///
    /// # Errors
    /// The first bad query in batch order, as a [`BatchError`] naming its position.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let pts: Vec<([f64; 2], usize)> = (0..100).map(|i| ([i as f64, 0.0], i)).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// let answers = t.par_k_nearest(&[[10.2, 0.0], [97.9, 0.0]], 2).unwrap();
    /// let items: Vec<Vec<usize>> =
    ///     answers.iter().map(|a| a.iter().map(|n| *n.item).collect()).collect();
    /// assert_eq!(items, [vec![10, 11], vec![98, 97]]);
    /// ```
    fn par_k_nearest(
        &self,
        queries: &[[Self::Scalar; D]],
        k: usize,
    ) -> Result<Vec<Vec<NeighborIn<'_, Self, D>>>, BatchError> {
        // In Morton order, as the serial batch (`ordered_batch.rs`): each thread's share of the
        // queries then walks one part of the tree.
        let order = morton_order(queries, self.domain());
        let answers = map_indices(order.len(), &|j| self.k_nearest(&queries[order[j]], k));
        in_query_order(&order, answers)
    }

    /// [`PointSet::query_count`] for every region, in parallel; counts in region order.
    ///
    /// # Errors
    /// The first bad region in batch order, as a [`BatchError`] naming its position.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Ball, Quadtree};
    /// let pts: Vec<([f64; 2], ())> = (0..100).map(|i| ([(i % 10) as f64, (i / 10) as f64], ())).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// let balls = [Ball::new([0.0, 0.0], 1.0).unwrap(), Ball::new([5.0, 5.0], 1.0).unwrap()];
    /// assert_eq!(t.par_query_count(&balls).unwrap(), [3, 5]);
    /// ```
    fn par_query_count<R: Region<D> + Sync>(
        &self,
        regions: &[R],
    ) -> Result<Vec<usize>, BatchError> {
        run_batch(regions, |r| self.query_count(r))
    }

    /// The points in every region, in parallel: for each region, the slots
    /// ([`PointSet::items`] positions) of its points, ascending.
    ///
    /// # Errors
    /// The first bad region in batch order, as a [`BatchError`] naming its position.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{Aabb, Quadtree};
    /// let t = Quadtree::new(&[([0.0, 0.0], 'a'), ([1.0, 1.0], 'b'), ([2.0, 2.0], 'c')]).unwrap();
    /// let boxes = [Aabb::new([0.5, 0.5], [2.0, 2.0]).unwrap(), Aabb::new([5.0, 5.0], [6.0, 6.0]).unwrap()];
    /// let found = t.par_query_indices(&boxes).unwrap();
    /// let items: Vec<char> = found[0].iter().map(|&i| t.items()[i]).collect();
    /// assert_eq!((items, found[1].len()), (vec!['b', 'c'], 0));
    /// ```
    fn par_query_indices<R: Region<D> + Sync>(
        &self,
        regions: &[R],
    ) -> Result<Vec<Vec<usize>>, BatchError> {
        run_batch(regions, |r| {
            let index = self.index();
            let payloads = index.payloads();
            let mut found = Vec::new();
            for_each_in(index, r, scan_limit::<D>(), false, |i| {
                found.push(self.slot_of(i, &payloads[i]))
            })?;
            found.sort_unstable();
            Ok(found)
        })
    }
}

impl<P: PointSet<D> + Sync, const D: usize> ParallelQueries<D> for P
where
    P::Scalar: Sync,
    P::Item: Sync,
{
}
