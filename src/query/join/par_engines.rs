//! The engines of the parallel joins (feature `rayon`), once for every distance of
//! [`bounds`](super::bounds): the same answers as the serial engines, the work split into
//! independent parts run on rayon's threads.
//!
//! - The k-nearest joins hand the querying tree's groups (see [`knn`](super::knn)) to the
//!   threads in runs of consecutive groups; each run reuses one [`Search`] for all its groups
//!   and writes their rows of one table directly.
//! - The radius joins split the top of the dual-tree traversal (Gray and Moore, 2001) into at
//!   least 16 independent node pairs per thread ([`split_top`]) and traverse each on a thread:
//!   the counts of the parts are summed, the pairs of the sparse matrix concatenated and sorted,
//!   the pairs of the visitors handed over as found (with one shared flag that stops every
//!   thread at the first break), or folded into one accumulator per part and reduced.
//!
//! Nothing here holds all the pairs of a visitor or a fold in memory: each thread holds its
//! traversal's stack and a block of 64 gathered points. The threads are reached through
//! [`par_tasks`](crate::par_tasks), so that rayon's machinery is compiled once for all the
//! engines' closures.

use super::bounds::PairDistance;
use super::knn::{fill, groups, parts, row_slots, table, width, KnnTable};
use super::knn_group::Search;
use super::knn_map::{swap_rows, to_slot_order};
use super::pairs::{CountWithin, PairsWithin};
use super::radius::{squared_radii, squared_radius, Boundary};
use super::scan::Block;
use super::sparse::SparseDistances;
use super::traverse::{roots, run, split_top, Pair};
use crate::huge_pages;
use crate::par_tasks::{chunks, for_each_chunk, for_each_index, lock, map_indices};
use crate::query::{PointSet, QueryError, SpatialIndex};
use core::convert::Infallible;
use core::ops::ControlFlow;
use core::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, PoisonError};

/// The k-nearest join of `a` in `b` under `metric` (`same`: the self-join), the groups of `a`
/// on rayon's threads.
pub(crate) fn par_knn<A, B, P, const D: usize>(
    a: &A,
    b: &B,
    metric: &P,
    k: usize,
    same: bool,
) -> KnnTable
where
    A: PointSet<D> + Sync,
    B: PointSet<D> + Sync,
    P: PairDistance<D>,
{
    let (n, w) = (a.len(), width(k, b.len(), same));
    if w == 0 {
        return table(0, n, Vec::new(), Vec::new());
    }
    let gs = groups(a.index());
    let (mut slots, mut distances) = (huge_pages::zeros(n * w), huge_pages::zeros(n * w));
    let parts = parts(&gs, w, &mut slots, &mut distances);
    for_each_chunk(parts, chunks(), &|run| {
        let mut search = Search::new();
        for part in run {
            fill(&mut search, (a, b, metric), part, w, same);
        }
    });
    if let Some(mut order) = row_slots(a, &gs) {
        to_slot_order(&mut order, |x, y| {
            swap_rows(&mut slots, x, y, w);
            swap_rows(&mut distances, x, y, w);
        });
    }
    table(w, n, slots, distances)
}

/// The visitor of the pairs within `r2` between `a` and `b` under `metric` (`same`: `b` is `a`,
/// unordered pairs once) that hands them to `visit`.
fn pairs_visitor<'s, A, B, P, F, Br, const D: usize>(
    (a, b, metric): (&'s A, &'s B, &'s P),
    same: bool,
    r2: f64,
    boundary: Boundary,
    points: [usize; 2],
    visit: F,
) -> PairsWithin<'s, A, B, P, F, D>
where
    F: FnMut(usize, usize, f64) -> ControlFlow<Br>,
{
    PairsWithin {
        metric,
        unordered: same,
        a,
        b,
        r2,
        boundary,
        visit,
        block: Block::boxed(points),
    }
}

/// The points of each side of a frontier pair: all that its part of the traversal can meet, to
/// size the kernel's caches ([`Block::boxed`]).
fn part_points<A: PointSet<D>, B: PointSet<D>, T, const D: usize>(
    (a, b): (&A, &B),
    pair: &Pair<<A::Index as SpatialIndex<D>>::Node, <B::Index as SpatialIndex<D>>::Node, T, D>,
) -> [usize; 2] {
    [
        a.index().run(pair.0 .0).len(),
        b.index().run(pair.1 .0).len(),
    ]
}

/// Every pair within `r` between `a` and `b` under `metric` (`same`: `b` is `a`, unordered pairs
/// once) handed to `visit` from rayon's threads; the first break seen stops every thread (pairs
/// being visited on other threads at that moment finish) and is returned.
#[allow(clippy::too_many_arguments)]
pub(crate) fn par_pairs<A, B, P, F, Br, const D: usize>(
    a: &A,
    b: &B,
    metric: &P,
    same: bool,
    r: f64,
    boundary: Boundary,
    visit: F,
) -> Result<ControlFlow<Br>, QueryError>
where
    A: PointSet<D> + Sync,
    B: PointSet<D> + Sync,
    P: PairDistance<D>,
    F: Fn(usize, usize, f64) -> ControlFlow<Br> + Sync,
    Br: Send,
{
    let r2 = squared_radius(r)?;
    let (ia, ib) = (a.index(), b.index());
    let frontier = {
        let mut v = pairs_visitor(
            (a, b, metric),
            same,
            r2,
            boundary,
            [a.len(), b.len()],
            &visit,
        );
        let start = roots((ia, ib, metric), same, (), &mut v);
        match split_top(ia, ib, metric, start, chunks(), &mut v) {
            ControlFlow::Continue(f) => f,
            ControlFlow::Break(br) => return Ok(ControlFlow::Break(br)),
        }
    };
    let stopped = AtomicBool::new(false);
    let found = Mutex::new(None);
    for_each_index(frontier.len(), &|i| {
        if stopped.load(Ordering::Relaxed) {
            return;
        }
        let pair = frontier[i];
        let each = until_stopped(&visit, &stopped);
        let points = part_points((a, b), &pair);
        let mut v = pairs_visitor((a, b, metric), same, r2, boundary, points, each);
        if let ControlFlow::Break(Some(br)) = run(a.index(), b.index(), metric, vec![pair], &mut v)
        {
            // The first break is kept; a later one (from a part that had not yet seen the flag)
            // is dropped.
            lock(&found).get_or_insert(br);
        }
    });
    let found = found.into_inner().unwrap_or_else(PoisonError::into_inner);
    Ok(found.map_or(ControlFlow::Continue(()), ControlFlow::Break))
}

/// Every pair within `r` between `a` and `b` under `metric` (`same`: `b` is `a`, unordered pairs
/// once) folded by `fold` into accumulators made by `identity`, one per part of the traversal,
/// then combined by `reduce`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn par_fold_pairs<A, B, P, T, I, F, R, const D: usize>(
    a: &A,
    b: &B,
    metric: &P,
    same: bool,
    (r, boundary): (f64, Boundary),
    identity: I,
    fold: F,
    reduce: R,
) -> Result<T, QueryError>
where
    A: PointSet<D> + Sync,
    B: PointSet<D> + Sync,
    P: PairDistance<D>,
    T: Send,
    I: Fn() -> T + Sync + Send,
    F: Fn(&mut T, usize, usize, f64) + Sync,
    R: Fn(T, T) -> T + Sync + Send,
{
    let r2 = squared_radius(r)?;
    let (ia, ib) = (a.index(), b.index());
    let mut top = identity();
    let frontier = {
        let each = folding(&fold, &mut top);
        let mut v = pairs_visitor((a, b, metric), same, r2, boundary, [a.len(), b.len()], each);
        let start = roots((ia, ib, metric), same, (), &mut v);
        let ControlFlow::Continue(f) = split_top(ia, ib, metric, start, chunks(), &mut v);
        f
    };
    let accs = map_indices(frontier.len(), &|i| {
        let pair = frontier[i];
        let mut acc = identity();
        let each = folding(&fold, &mut acc);
        let points = part_points((a, b), &pair);
        let mut v = pairs_visitor((a, b, metric), same, r2, boundary, points, each);
        let _ = run(a.index(), b.index(), metric, vec![pair], &mut v);
        drop(v);
        acc
    });
    Ok(accs.into_iter().fold(top, reduce))
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

/// The sparse distance matrix of the pairs within `r` between `a` and `b` under `metric`.
pub(crate) fn par_sparse<A, B, P, const D: usize>(
    a: &A,
    b: &B,
    metric: &P,
    r: f64,
    boundary: Boundary,
) -> Result<SparseDistances, QueryError>
where
    A: PointSet<D> + Sync,
    B: PointSet<D> + Sync,
    P: PairDistance<D>,
{
    let triples = par_fold_pairs(
        a,
        b,
        metric,
        false,
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
    Ok(SparseDistances::new((a.len(), b.len()), triples))
}

/// The counts within each of `radii` between `a` and `b` under `metric` (`same`: `b` is `a`),
/// the top of the traversal split into node pairs counted on rayon's threads.
pub(crate) fn par_count<A, B, P, const D: usize>(
    a: &A,
    b: &B,
    metric: &P,
    same: bool,
    radii: &[f64],
    boundary: Boundary,
) -> Result<Vec<u64>, QueryError>
where
    A: PointSet<D> + Sync,
    B: PointSet<D> + Sync,
    P: PairDistance<D>,
{
    let r2 = squared_radii(radii)?;
    if r2.is_empty() {
        return Ok(Vec::new());
    }
    let counter = |points| CountWithin {
        metric,
        a,
        b,
        r2: &r2,
        boundary,
        diff: vec![0; r2.len() + 1],
        block: Block::boxed(points),
    };
    let (ia, ib) = (a.index(), b.index());
    let mut top = counter([a.len(), b.len()]);
    let start = roots((ia, ib, metric), same, (0, r2.len()), &mut top);
    let ControlFlow::Continue(frontier) = split_top(ia, ib, metric, start, chunks(), &mut top);
    let parts = map_indices(frontier.len(), &|i| {
        let pair = frontier[i];
        let mut c = counter(part_points((a, b), &pair));
        let _ = run(a.index(), b.index(), metric, vec![pair], &mut c);
        c.diff
    });
    for part in parts {
        for (t, p) in top.diff.iter_mut().zip(part) {
            *t += p;
        }
    }
    Ok(top.counts())
}
