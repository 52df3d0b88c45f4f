//! The engines of the parallel joins (feature `rayon`), methods of [`Join`] as the serial
//! engines are, once for every distance of [`bounds`](super::bounds): the same answers as the
//! serial engines, the work split into independent parts run on rayon's threads.
//!
//! - The k-nearest joins hand the querying tree's groups (see [`knn`](super::knn)) to the
//!   threads in runs of consecutive groups; each run reuses one
//!   [`Search`](super::knn_group::Search) for all its groups, as the serial table does
//!   ([`Join::fill_parts`]), and writes their rows of one table directly.
//! - The radius joins split the top of the dual-tree traversal (Gray and Moore, 2001) into at
//!   least 16 independent node pairs per thread ([`Dual::split_top`](super::traverse::Dual::split_top)) and traverse each on a thread:
//!   the counts of the parts are summed, the pairs of the sparse matrix concatenated and sorted,
//!   the pairs of the visitors handed over as found (with one shared flag that stops every
//!   thread at the first break), or folded into one accumulator per part and reduced.
//!
//! Nothing here holds all the pairs of a visitor or a fold in memory: each thread holds its
//! traversal's stack and a block of 64 gathered points. The threads are reached through
//! [`par_tasks`](crate::par_tasks), so that rayon's machinery is compiled once for all the
//! engines' closures.

use super::bounds::PairDistance;
use super::knn::KnnTable;
use super::pairs::{CountWithin, PairsWithin};
use super::radius::{squared_radii, squared_radius, Boundary};
use super::sparse::SparseDistances;
use super::traverse::{Frontier, Pair, PairVisitor};
use super::Join;
use crate::par_tasks::{chunks, for_each_chunk, for_each_index, lock, map_indices};
use crate::query::{PointSet, QueryError, SpatialIndex};
use core::convert::Infallible;
use core::ops::ControlFlow;
use core::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, PoisonError};

/// A node of the index of point set `A`.
type Node<A, const D: usize> = <<A as PointSet<D>>::Index as SpatialIndex<D>>::Node;

/// A node pair of the traversal of the indices of point sets `A` and `B`.
type SetPair<A, B, T, const D: usize> = Pair<Node<A, D>, Node<B, D>, T, D>;

impl<A, B, P, const D: usize> Join<'_, A, B, P, D>
where
    A: PointSet<D> + Sync,
    B: PointSet<D> + Sync,
    P: PairDistance<D>,
{
    /// The k-nearest table, the groups of the querying set on rayon's threads.
    pub(crate) fn par_knn(self, k: usize) -> KnnTable {
        self.table(k, |parts, w| {
            for_each_chunk(parts, chunks(), &|run| self.fill_parts(run, w));
        })
    }

    /// The node pairs the top of the traversal is split into from the root pair (state
    /// `state`), `visitor` taking the pairs met on the way.
    fn split<T, V>(
        self,
        state: T,
        visitor: &mut V,
    ) -> Frontier<Node<A, D>, Node<B, D>, T, V::Break, D>
    where
        V: PairVisitor<A::Index, B::Index, T, D>,
    {
        let dual = self.dual();
        let start = dual.roots(self.3, state, visitor);
        dual.split_top(start, chunks(), visitor)
    }

    /// One part of a split traversal: the node pair `pair` and its descendants, taken by the
    /// visitor `visitor(points)` makes from the points of each side of the pair (all that the
    /// part can meet, to size the kernel's caches: [`Block::boxed`](super::scan::Block::boxed));
    /// the part's end and the visitor.
    fn part<T, V>(
        self,
        pair: SetPair<A, B, T, D>,
        visitor: impl FnOnce([usize; 2]) -> V,
    ) -> (ControlFlow<V::Break>, V)
    where
        V: PairVisitor<A::Index, B::Index, T, D>,
    {
        let mut v = visitor(self.part_points(&pair));
        (self.dual().run(vec![pair], &mut v), v)
    }

    /// The points of each side of the node pair `pair`: all that a part of the traversal from it
    /// can meet.
    fn part_points<T>(self, pair: &SetPair<A, B, T, D>) -> [usize; 2] {
        let (ia, ib) = (self.0.index(), self.1.index());
        [ia.run(pair.0 .0).len(), ib.run(pair.1 .0).len()]
    }

    /// Every pair within `r` (under `boundary`) handed to `visit` from rayon's threads; the
    /// first break seen stops every thread (pairs being visited on other threads at that moment
    /// finish) and is returned.
    pub(crate) fn par_pairs<Br: Send>(
        self,
        r: f64,
        boundary: Boundary,
        visit: impl Fn(usize, usize, f64) -> ControlFlow<Br> + Sync,
    ) -> Result<ControlFlow<Br>, QueryError> {
        let within = (squared_radius(r)?, boundary);
        let all = [self.0.len(), self.1.len()];
        let mut top = PairsWithin::new(self, within, all, &visit);
        let frontier = match self.split((), &mut top.visitor()) {
            ControlFlow::Continue(f) => f,
            ControlFlow::Break(()) => return Ok(top.outcome(ControlFlow::Break(()))),
        };
        let stopped = AtomicBool::new(false);
        let found = Mutex::new(None);
        for_each_index(frontier.len(), &|i| {
            if stopped.load(Ordering::Relaxed) {
                return;
            }
            let each = until_stopped(&visit, &stopped);
            let mut part = PairsWithin::new(self, within, self.part_points(&frontier[i]), each);
            if let ControlFlow::Break(Some(br)) = part.walk(vec![frontier[i]]) {
                // The first break is kept; a later one (from a part that had not yet seen the
                // flag) is dropped.
                lock(&found).get_or_insert(br);
            }
        });
        let found = found.into_inner().unwrap_or_else(PoisonError::into_inner);
        Ok(found.map_or(ControlFlow::Continue(()), ControlFlow::Break))
    }

    /// Every pair within `r` (under `boundary`) folded by `fold` into accumulators made by
    /// `identity`, one per part of the traversal, then combined by `reduce`.
    pub(crate) fn par_fold<T: Send>(
        self,
        (r, boundary): (f64, Boundary),
        identity: impl Fn() -> T + Sync + Send,
        fold: impl Fn(&mut T, usize, usize, f64) + Sync,
        reduce: impl Fn(T, T) -> T + Sync + Send,
    ) -> Result<T, QueryError> {
        let within = (squared_radius(r)?, boundary);
        let mut top = identity();
        let all = [self.0.len(), self.1.len()];
        let each = folding(&fold, &mut top);
        let frontier =
            match self.split((), &mut PairsWithin::new(self, within, all, each).visitor()) {
                ControlFlow::Continue(f) => f,
                // A fold never breaks.
                ControlFlow::Break(()) => Vec::new(),
            };
        let accs = map_indices(frontier.len(), &|i| {
            let mut acc = identity();
            let each = folding(&fold, &mut acc);
            let _ = PairsWithin::new(self, within, self.part_points(&frontier[i]), each)
                .walk(vec![frontier[i]]);
            acc
        });
        Ok(accs.into_iter().fold(top, reduce))
    }

    /// The sparse distance matrix of the pairs within `r` (of a join that is not a self-join).
    pub(crate) fn par_sparse(
        self,
        r: f64,
        boundary: Boundary,
    ) -> Result<SparseDistances, QueryError> {
        let triples = self.par_fold(
            (r, boundary),
            Vec::new,
            |acc: &mut Vec<(usize, usize, f64)>, s, t, d| acc.push((s, t, d)),
            |mut x, mut y| {
                if x.len() < y.len() {
                    core::mem::swap(&mut x, &mut y);
                }
                x.extend(y);
                x
            },
        )?;
        Ok(SparseDistances::new((self.0.len(), self.1.len()), triples))
    }

    /// The counts within each of `radii`, the top of the traversal split into node pairs
    /// counted on rayon's threads.
    pub(crate) fn par_count(
        self,
        radii: &[f64],
        boundary: Boundary,
    ) -> Result<Vec<u64>, QueryError> {
        let r2 = squared_radii(radii)?;
        if r2.is_empty() {
            return Ok(Vec::new());
        }
        let counts = |n| CountWithin::new(self, (&r2, boundary), n);
        let mut top = counts([self.0.len(), self.1.len()]);
        let ControlFlow::Continue(frontier) = self.split((0, r2.len()), &mut top);
        let parts = map_indices(frontier.len(), &|i| self.part(frontier[i], counts).1.diff);
        for part in parts {
            for (t, p) in top.diff.iter_mut().zip(part) {
                *t += p;
            }
        }
        Ok(top.counts())
    }
}

/// `visit`, stopping every part once one has broken (`stopped`): its break, `None` for the
/// others. Generic over the visitor only (not the sets), as the leaf kernel it goes into.
fn until_stopped<'a, F, Br>(
    visit: &'a F,
    stopped: &'a AtomicBool,
) -> impl FnMut(usize, usize, f64) -> ControlFlow<Option<Br>> + 'a
where
    F: Fn(usize, usize, f64) -> ControlFlow<Br>,
{
    move |s, t, d| {
        if stopped.load(Ordering::Relaxed) {
            return ControlFlow::Break(None);
        }
        visit(s, t, d).map_break(|br| {
            stopped.store(true, Ordering::Relaxed);
            Some(br)
        })
    }
}

/// Every pair folded into `acc` by `fold`. Generic over the fold only (not the sets), as the
/// leaf kernel it goes into.
fn folding<'a, T, F>(
    fold: &'a F,
    acc: &'a mut T,
) -> impl FnMut(usize, usize, f64) -> ControlFlow<Infallible> + 'a
where
    F: Fn(&mut T, usize, usize, f64),
{
    move |s, t, d| {
        fold(acc, s, t, d);
        ControlFlow::Continue(())
    }
}
