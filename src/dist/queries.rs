//! Batch queries of a [`DistPointTree`]: box, ball and k-nearest queries issued on any rank,
//! routed by the rank boxes (the bounding box of each rank's points, replicated), answered by
//! the local trees and merged back on the issuing rank.
//!
//! A round sends each request to its ranks with one all-to-all exchange and the answers back
//! with another. Boxes and balls take one round, to every rank whose box the region does not
//! miss (the region's own `classify`, the test the local tree prunes with). k-nearest takes
//! two, as in distributed kd-tree searches (e.g. Patwary et al. 2016, "PANDA: Extreme scale
//! parallel k-nearest neighbor on distributed architectures"): first to the rank whose box is
//! nearest, whose k-th distance r bounds the answer; then, with that bound, to every other
//! rank whose box lies within r. Candidates are merged by (distance, global slot): the local
//! order is the global order, so the answer equals the single-process tree's, ties included.

use super::comm::{self, point_bytes, Reader, Words, Writer};
use super::{DistError, DistPointTree};
use crate::geom::{Aabb, Scalar};
use crate::query::range::{for_each_in, scan_limit};
use crate::query::{k_nearest, SquaredEuclidean};
use crate::query::{query_box, query_point, Ball, Metric, PointSet, QueryError, Region, Relation};
use bytemuck::Pod;

/// A point found by a distributed query: its point and item (copied from the rank holding
/// it), its global slot (its position in the single-process tree over the union) and its
/// squared Euclidean distance from the query point or ball centre (0 for box queries).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DistNeighbor<S, T, const D: usize> {
    /// The point.
    pub point: [S; D],
    /// Its item.
    pub item: T,
    /// Its squared distance from the query point (0 for a box query).
    pub distance: f64,
    /// Its global slot.
    pub slot: u64,
}

/// Every query's answers, in query order.
type Answers<S, T, const D: usize> = Vec<Vec<DistNeighbor<S, T, D>>>;

impl<S: Scalar + Pod, T: Pod, const D: usize> DistPointTree<S, T, D> {
    /// The `k` nearest points (squared Euclidean) of every query point of this rank's batch
    /// (collective: every rank calls it with its own batch, any length, its own `k`); answers
    /// in query order, each sorted by (distance, global slot): exactly the single-process
    /// tree's [`PointSet::k_nearest`] over the union.
    ///
    /// # Errors
    /// The same on every rank: [`DistError::Query`] naming the first bad query point (NaN,
    /// infinite, inexact) of the lowest rank with one; [`DistError::MessageTooLarge`].
    ///
    /// # Complexity
    /// Two rounds of two all-to-all exchanges; each query costs a local k-nearest search on
    /// its nearest rank and on each rank within its k-th distance.
    pub fn k_nearest_batch(
        &self,
        queries: &[[S; D]],
        k: usize,
    ) -> Result<Answers<S, T, D>, DistError> {
        let bad = queries.iter().position(|q| query_point(q).is_err());
        self.agree_query(
            bad,
            point_bytes::<S, D>(),
            |i, w| {
                w.put(&queries[i]);
            },
            |r| query_point(&r.get::<[S; D]>()).expect_err("refused on its rank"),
        )?;
        let q64: Vec<[f64; D]> = queries
            .iter()
            .map(|q| query_point(q).expect("checked"))
            .collect();
        let geometry = self.local.geometry();
        let keys: Vec<u64> = q64.iter().map(|q| geometry.key(q)).collect();
        let bound = |q: usize, r: usize| SquaredEuclidean.box_distance(&q64[q], &self.boxes[r]);
        let ranks = self.partition.nonempty_ranks();
        let bytes = 16 + point_bytes::<S, D>();
        let write = |q: usize, radius: f64, w: &mut Writer<'_>| {
            w.put(&(k as u64)).put(&radius).put(&queries[q]);
        };
        let search = |q: &[f64; D], k: usize, max: f64, hits: &mut Vec<(f64, usize)>| {
            hits.extend(k_nearest(self.local.index(), q, k, max, &SquaredEuclidean));
        };
        let answer = |r: &mut Reader<'_>, hits: &mut Vec<(f64, usize)>| {
            let (k, max) = (r.get::<u64>() as usize, r.get::<f64>());
            let p: [S; D] = r.get();
            // checked on its rank; a NaN bound is never sent
            if let Ok(q) = query_point(&p)
                && !max.is_nan()
            {
                search(&q, k, max, hits);
            }
        };
        // Each query to its home rank, the one whose box is nearest.
        let first: Vec<(usize, usize)> = (0..queries.len())
            .filter(|_| k > 0)
            .filter_map(|q| {
                ranks
                    .iter()
                    .copied()
                    .min_by(|&a, &b| bound(q, a).total_cmp(&bound(q, b)).then(a.cmp(&b)))
                    .map(|r| (r, q))
            })
            .collect();
        // A round of requests, each query's searches bounded by its radius.
        let round = |sends: &[(usize, usize)], radius: &[f64]| {
            self.round(
                sends,
                bytes,
                |q, w| write(q, radius[q], w),
                (answer, |q, hits| search(&q64[q], k, radius[q], hits)),
                Some(&keys),
                queries.len(),
            )
        };
        let mut found = round(&first, &vec![f64::INFINITY; queries.len()])?;
        let radius: Vec<f64> = found
            .iter()
            .map(|f| {
                f.last()
                    .filter(|_| f.len() == k)
                    .map_or(f64::INFINITY, |n| n.distance)
            })
            .collect();
        let second: Vec<(usize, usize)> = first
            .iter()
            .flat_map(|&(h, q)| {
                let (radius, bound) = (&radius, &bound);
                ranks
                    .iter()
                    .copied()
                    .filter(move |&r| r != h && bound(q, r) <= radius[q])
                    .map(move |r| (r, q))
            })
            .collect();
        let more = round(&second, &radius)?;
        for (f, m) in found.iter_mut().zip(more) {
            if m.is_empty() {
                continue; // one rank's answer, already sorted
            }
            f.extend(m);
            f.sort_by(|a, b| a.distance.total_cmp(&b.distance).then(a.slot.cmp(&b.slot)));
            f.truncate(k);
        }
        Ok(found)
    }

    /// The points in each closed box of this rank's batch (collective), each answer in global
    /// slot order: the single-process tree's [`PointSet::in_box`] over the union.
    ///
    /// # Errors
    /// The same on every rank: [`DistError::Query`] naming the first bad box (a NaN bound,
    /// an inexact integer corner) of the lowest rank with one; [`DistError::MessageTooLarge`].
    pub fn in_box_batch(&self, boxes: &[Aabb<S, D>]) -> Result<Answers<S, T, D>, DistError> {
        self.range_batch(
            boxes,
            2 * point_bytes::<S, D>(),
            |b| query_box(b).and_then(|f| f.validate().map(|()| f)),
            |b, w| {
                w.put(&b.min).put(&b.max);
            },
            |r| Aabb {
                min: r.get(),
                max: r.get(),
            },
            |_| None,
        )
    }

    /// The points within Euclidean distance `radius` of `center` for each `(center, radius)`
    /// of this rank's batch (collective), each answer in global slot order with squared
    /// distances: the single-process tree's [`PointSet::in_ball`] over the union.
    ///
    /// # Errors
    /// The same on every rank: [`DistError::Query`] naming the first bad ball (a non-finite
    /// centre, a negative or NaN radius) of the lowest rank with one;
    /// [`DistError::MessageTooLarge`].
    pub fn in_ball_batch(&self, balls: &[([S; D], f64)]) -> Result<Answers<S, T, D>, DistError> {
        self.range_batch(
            balls,
            8 + point_bytes::<S, D>(),
            |(c, r)| Ball::new(query_point(c)?, *r),
            |b, w| {
                w.put(&b.1).put(&b.0);
            },
            |r| {
                let radius = r.get::<f64>();
                (r.get(), radius)
            },
            |b| Some(b.center),
        )
    }

    /// A batch of range queries: `check` turns each query into its region or refuses it (the
    /// refusal agreed on by every rank), then one round sends each region to every non-empty
    /// rank whose box it does not miss, as `write` puts it (`bytes` long) and `read` takes it
    /// back; `center_of` gives the centre to measure distances from, if any.
    fn range_batch<Q, R: Region<D> + core::fmt::Debug>(
        &self,
        queries: &[Q],
        bytes: usize,
        check: impl Fn(&Q) -> Result<R, QueryError>,
        write: impl Fn(&Q, &mut Writer<'_>),
        read: impl Fn(&mut Reader<'_>) -> Q,
        center_of: impl Fn(&R) -> Option<[f64; D]>,
    ) -> Result<Answers<S, T, D>, DistError> {
        let bad = queries.iter().position(|q| check(q).is_err());
        self.agree_query(
            bad,
            bytes,
            |i, w| write(&queries[i], w),
            |r| check(&read(r)).expect_err("refused on its rank"),
        )?;
        let regions: Vec<R> = queries.iter().map(|q| check(q).expect("checked")).collect();
        let ranks = self.partition.nonempty_ranks();
        let sends: Vec<(usize, usize)> = regions
            .iter()
            .enumerate()
            .flat_map(|(q, region)| {
                ranks
                    .iter()
                    .copied()
                    .filter(move |&r| region.classify(&self.boxes[r]) != Relation::Outside)
                    .map(move |r| (r, q))
            })
            .collect();
        let points = self.local.points();
        let search = |region: &R, hits: &mut Vec<(f64, usize)>| {
            let center = center_of(region);
            let _ = for_each_in(&self.local, region, scan_limit::<D>(), true, |i| {
                let d = center.map_or(0.0, |c| {
                    SquaredEuclidean.distance(&c, &points[i].map(Scalar::to_f64))
                });
                hits.push((d, i));
            });
        };
        let mut found = self.round(
            &sends,
            bytes,
            |q, w| write(&queries[q], w),
            (
                |r: &mut Reader<'_>, hits: &mut Vec<(f64, usize)>| {
                    search(&check(&read(r)).expect("checked on its rank"), hits);
                },
                |q, hits: &mut Vec<(f64, usize)>| search(&regions[q], hits),
            ),
            None,
            queries.len(),
        )?;
        for f in &mut found {
            f.sort_by_key(|n| n.slot);
        }
        Ok(found)
    }

    /// The agreement on a batch: if a rank has a bad query (`bad`, its position), the lowest
    /// such rank sends it (`write` puts the query at that position, `bytes` long) and every
    /// rank rebuilds the same error from it (`error`).
    fn agree_query(
        &self,
        bad: Option<usize>,
        bytes: usize,
        write: impl Fn(usize, &mut Writer<'_>),
        error: impl Fn(&mut Reader<'_>) -> QueryError,
    ) -> Result<(), DistError> {
        let Some(rank) = comm::lowest_failing(&self.comm, bad.is_some()) else {
            return Ok(());
        };
        let mut w = Words::with_records(1, 8 + bytes);
        if let Some(index) = bad {
            let mut writer = w.writer(0);
            writer.put(&(index as u64));
            write(index, &mut writer);
        }
        comm::broadcast(&self.comm, rank, &mut w.words);
        let mut r = w.reader(0);
        let index = r.get::<u64>() as usize;
        Err(DistError::Query {
            rank,
            index,
            error: error(&mut r),
        })
    }

    /// One request-and-answer round: request `q` goes to rank `r` for each `(r, q)` of
    /// `sends` (`write` puts its `bytes`); there `answer` reads it and adds its hits
    /// (distance, local slot); the hits come back, grouped by query. A request to this rank
    /// itself is answered here by `local` (the query's number, the same hits), never packed.
    /// With `keys` (each query's Morton key), every rank answers in Morton order.
    fn round<A, L>(
        &self,
        sends: &[(usize, usize)],
        bytes: usize,
        write: impl Fn(usize, &mut Writer<'_>),
        (answer, local): (A, L),
        keys: Option<&[u64]>,
        queries: usize,
    ) -> Result<Answers<S, T, D>, DistError>
    where
        A: Fn(&mut Reader<'_>, &mut Vec<(f64, usize)>),
        L: Fn(usize, &mut Vec<(f64, usize)>),
    {
        let ranks = self.partition.ranks();
        let me = self.rank();
        let key = |q: usize| keys.map_or(0, |k| k[q]);
        // By rank, then in Morton order of the queries: each rank searches its tree in that
        // order, so that consecutive searches walk the same nodes and points (in cache).
        let (mut mine, mut order): (Vec<(usize, usize)>, Vec<_>) =
            sends.iter().partition(|&&(r, _)| r == me);
        for list in [&mut mine, &mut order] {
            list.sort_by_key(|&(r, q)| (r, key(q)));
        }
        let mut requests = Words::with_records(order.len(), 8 + bytes);
        let mut counts = vec![0usize; ranks];
        for (i, &(r, q)) in order.iter().enumerate() {
            let mut w = requests.writer(i);
            w.put(&(q as u64));
            write(q, &mut w);
            counts[r] += 1;
        }
        let (incoming, from) = requests.exchange(&self.comm, &counts)?;
        // Answer in the order received: grouped by the sending rank.
        let first = self.first_slot();
        let reply_bytes = 24 + point_bytes::<S, D>() + core::mem::size_of::<T>();
        let mut replies: Vec<(u64, f64, usize)> = Vec::new();
        let mut reply_counts = vec![0usize; ranks];
        let mut hits = Vec::new();
        let mut j = 0;
        for (source, &n) in from.iter().enumerate() {
            for _ in 0..n {
                let mut r = incoming.reader(j);
                let q = r.get::<u64>();
                hits.clear();
                answer(&mut r, &mut hits);
                replies.extend(hits.iter().map(|&(d, i)| (q, d, i)));
                reply_counts[source] += hits.len();
                j += 1;
            }
        }
        let (points, items) = (self.local.points(), self.local.items());
        let mut out = Words::with_records(replies.len(), reply_bytes);
        for (i, &(q, d, s)) in replies.iter().enumerate() {
            out.writer(i)
                .put(&q)
                .put(&(first + s as u64))
                .put(&d)
                .put(&points[s])
                .put(&items[s]);
        }
        drop((replies, incoming));
        let (back, _) = out.exchange(&self.comm, &reply_counts)?;
        let mut found: Answers<S, T, D> = vec![Vec::new(); queries];
        for (_, q) in mine {
            hits.clear();
            local(q, &mut hits);
            found[q].extend(hits.iter().map(|&(distance, s)| DistNeighbor {
                point: points[s],
                item: items[s],
                distance,
                slot: first + s as u64,
            }));
        }
        for i in 0..back.len() {
            let mut r = back.reader(i);
            let q = r.get::<u64>() as usize;
            // The fields are read in the order written, the order they were packed in.
            found[q].push(DistNeighbor {
                slot: r.get(),
                distance: r.get(),
                point: r.get(),
                item: r.get(),
            });
        }
        Ok(found)
    }
}
