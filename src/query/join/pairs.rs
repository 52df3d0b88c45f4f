//! The radius joins on the dual-tree traversal of [`traverse`](super::traverse): every pair of
//! points within a radius, handed to a visitor as found ([`PairsWithin`]), and the number of
//! pairs within each of a sorted list of radii in one traversal ([`CountWithin`], the two-point
//! correlation count of Gray and Moore, 2001).
//!
//! The counts keep, per node pair, the range `lo..hi` of radii not yet decided for it (every
//! radius below `lo` takes in none of its pairs, every radius from `hi` on all of them, already
//! counted). A node pair narrows it by its boxes' distance range; the radii it newly takes in
//! whole get its number of pairs at once, by multiplying the sizes of the two nodes, without
//! visiting a point; only the radii still undecided go down to the points. The counts are kept
//! as differences (`add c to radii lo..hi` is two updates) and summed at the end.
//!
//! Both hand their pairs of nodes to scan to the leaf kernel of [`scan`](super::scan), which
//! filters each run by the other side's box and tests a point against a block of 64 at a time;
//! the counts also decide, point by point, the radii that take in the whole block.

use super::bounds::PairDistance;
use super::radius::Boundary;
use super::scan::{scan_counts, scan_pairs, Block, Run};
use super::slots::SlotView;
use super::traverse::{Dual, Pair, PairVisitor, Step};
use super::Join;
use crate::geom::{Aabb, Scalar};
use crate::query::{PointSet, SpatialIndex};
use core::ops::{ControlFlow, Range};

/// Every pair within `r2` between sets `a` and `b` (each unordered pair once, the smaller slot
/// first, when `b` is `a` and `unordered`), handed to `visit(slot in a, slot in b, squared
/// distance)`.
///
/// The traversal does not see the visitor's type: it classifies node pairs through [`Within`]
/// (the radius only) and hands pairs of nodes to scan to this join through `dyn`
/// [`LeafPairs`], one dynamic call per pair of leaves, each scanning up to 128 x 128 point
/// pairs. So the traversal is compiled once per pair of index types and distance, not once per
/// visitor (closures of every call site and the parallel forms' wrappers): about a twentieth of
/// the unoptimised code of the library's tests. The kernel, with the visitor inlined, stays
/// per visitor.
pub(crate) struct PairsWithin<'s, A, B, P, F, Br, const D: usize> {
    metric: &'s P,
    unordered: bool,
    a: &'s A,
    b: &'s B,
    r2: f64,
    boundary: Boundary,
    visit: F,
    /// The visitor's break, kept here while the traversal unwinds with `()`.
    found: Option<Br>,
    /// The leaf kernel's scratch.
    block: Box<Block<D>>,
}

impl<'s, A, B, P, F, Br, const D: usize> PairsWithin<'s, A, B, P, F, Br, D>
where
    A: PointSet<D>,
    B: PointSet<D>,
    P: PairDistance<D>,
    F: FnMut(usize, usize, f64) -> ControlFlow<Br>,
{
    /// The pairs of `join` within `r2` (under `boundary`) handed to `visit`, the leaf kernel's
    /// caches sized for a traversal meeting `points` points of each side ([`Block::boxed`]).
    pub(crate) fn new(
        Join(a, b, metric, same, _): Join<'s, A, B, P, D>,
        (r2, boundary): (f64, Boundary),
        points: [usize; 2],
        visit: F,
    ) -> Self {
        PairsWithin {
            metric,
            unordered: same,
            a,
            b,
            r2,
            boundary,
            visit,
            found: None,
            block: Block::boxed(points),
        }
    }

    /// The traversal's view of this join: the radius test, and this join as the handler of
    /// pairs of nodes to scan.
    pub(crate) fn visitor(&mut self) -> Within<'_, D> {
        let (r2, boundary) = (self.r2, self.boundary);
        Within {
            r2,
            boundary,
            leaves: self,
        }
    }

    /// The end of a traversal through [`PairsWithin::visitor`]: the visitor's break, if it broke.
    pub(crate) fn outcome(&mut self, flow: ControlFlow<()>) -> ControlFlow<Br> {
        match (flow, self.found.take()) {
            (ControlFlow::Break(()), Some(br)) => ControlFlow::Break(br),
            _ => ControlFlow::Continue(()),
        }
    }

    /// The traversal from the node pairs `start` (classified by [`PairsWithin::visitor`]) to the
    /// end, or to the visitor's break.
    pub(crate) fn walk(
        &mut self,
        start: Vec<Pair<Node<A, D>, Node<B, D>, (), D>>,
    ) -> ControlFlow<Br> {
        let dual = Dual::new(self.a.index(), self.b.index(), self.metric);
        let flow = dual.run(start, &mut self.visitor());
        self.outcome(flow)
    }
}

/// A node of the index of point set `A`.
pub(crate) type Node<A, const D: usize> = <<A as PointSet<D>>::Index as SpatialIndex<D>>::Node;

/// The handler of the pairs of nodes to scan of a radius join, behind `dyn` ([`PairsWithin`]):
/// `Break(())` when the visitor broke (its break kept by the handler).
pub(crate) trait LeafPairs<const D: usize> {
    /// A pair of scanned nodes: their runs and closed boxes (the same node when `same`).
    fn leaves(
        &mut self,
        a: (Range<usize>, &Aabb<f64, D>),
        b: (Range<usize>, &Aabb<f64, D>),
        same: bool,
    ) -> ControlFlow<()>;
}

/// The dual-tree visitor of the radius joins: node pairs kept while their boxes' nearest
/// distance is within the radius, pairs of nodes to scan handed to `leaves`.
pub(crate) struct Within<'v, const D: usize> {
    r2: f64,
    boundary: Boundary,
    leaves: &'v mut dyn LeafPairs<D>,
}

impl<IA, IB, const D: usize> PairVisitor<IA, IB, (), D> for Within<'_, D>
where
    IA: SpatialIndex<D>,
    IB: SpatialIndex<D>,
{
    type Break = ();

    #[inline]
    fn classify(&mut self, _: &(), near: f64, _far: f64, _pairs: u64) -> Step<()> {
        if self.boundary.admits(near, self.r2) {
            Step::Split(())
        } else {
            Step::Skip
        }
    }

    fn leaves(
        &mut self,
        _: &(),
        a: (Range<usize>, &Aabb<f64, D>),
        b: (Range<usize>, &Aabb<f64, D>),
        same: bool,
    ) -> ControlFlow<()> {
        self.leaves.leaves(a, b, same)
    }
}

impl<'s, A, B, P, F, Br, const D: usize> LeafPairs<D> for PairsWithin<'s, A, B, P, F, Br, D>
where
    A: PointSet<D>,
    B: PointSet<D>,
    P: PairDistance<D>,
    F: FnMut(usize, usize, f64) -> ControlFlow<Br>,
{
    fn leaves(
        &mut self,
        (ra, ba): (Range<usize>, &Aabb<f64, D>),
        (rb, bb): (Range<usize>, &Aabb<f64, D>),
        same: bool,
    ) -> ControlFlow<()> {
        let (a, b, unordered) = (self.a, self.b, self.unordered);
        let (ia, ib) = (a.index(), b.index());
        let to_slots = (SlotView::of(a), SlotView::of(b));
        let (runs, test) = (
            ((ia.points(), ra, ba), (ib.points(), rb, bb)),
            (same, self.metric, self.r2, self.boundary),
        );
        let (block, visit) = (&mut self.block, &mut self.visit);
        let flow = if let (SlotView::Same, SlotView::Same) = to_slots {
            // The common case (two point trees, or one with itself) without a look-up per pair.
            scan(block, runs, test, in_order(unordered, visit))
        } else {
            scan(block, runs, test, in_slots(to_slots, unordered, visit))
        };
        match flow {
            ControlFlow::Continue(()) => ControlFlow::Continue(()),
            ControlFlow::Break(br) => {
                self.found = Some(br);
                ControlFlow::Break(())
            }
        }
    }
}

/// [`scan_pairs`] with its arguments grouped.
#[inline(always)]
fn scan<SA: Scalar, SB: Scalar, P: PairDistance<D>, Br, const D: usize>(
    block: &mut Block<D>,
    (a, b): (Run<'_, SA, D>, Run<'_, SB, D>),
    (same, metric, r2, boundary): (bool, &P, f64, Boundary),
    each: impl FnMut(usize, usize, f64) -> ControlFlow<Br>,
) -> ControlFlow<Br> {
    scan_pairs(block, a, b, same, metric, r2, boundary, each)
}

/// The kernel's visitor where positions are slots: the smaller first when `unordered`, then
/// `visit`. Generic over the visitor only, as [`in_slots`].
#[inline]
fn in_order<'a, F, Br>(
    unordered: bool,
    visit: &'a mut F,
) -> impl FnMut(usize, usize, f64) -> ControlFlow<Br> + 'a
where
    F: FnMut(usize, usize, f64) -> ControlFlow<Br>,
{
    move |s, t, d| {
        if unordered && t < s {
            visit(t, s, d)
        } else {
            visit(s, t, d)
        }
    }
}

/// The kernel's visitor: positions to slots (the smaller first when `unordered`), then
/// `visit`. Generic over the visitor only, so that the kernel it is inlined into is compiled
/// once per visitor, not once per pair of set types.
#[inline]
fn in_slots<'a, F, Br, const D: usize>(
    (a, b): (SlotView<'a, D>, SlotView<'a, D>),
    unordered: bool,
    visit: &'a mut F,
) -> impl FnMut(usize, usize, f64) -> ControlFlow<Br> + 'a
where
    F: FnMut(usize, usize, f64) -> ControlFlow<Br>,
{
    let mut visit = in_order(unordered, visit);
    move |i, j, d| visit(a.slot(i), b.slot(j), d)
}

/// The number of pairs within each of the sorted squared radii `r2`, as differences: radius `i`
/// counts `diff[0] + .. + diff[i]`.
pub(crate) struct CountWithin<'s, A, B, P, const D: usize> {
    metric: &'s P,
    a: &'s A,
    b: &'s B,
    r2: &'s [f64],
    boundary: Boundary,
    pub(crate) diff: Vec<i128>,
    /// The leaf kernel's scratch.
    block: Box<Block<D>>,
}

impl<'s, A, B, P, const D: usize> CountWithin<'s, A, B, P, D> {
    /// The counts of the pairs of `join` within each of the squared radii `r2` (under
    /// `boundary`), all 0, the kernel's caches sized as [`PairsWithin::new`] sizes them.
    pub(crate) fn new(
        Join(a, b, metric, ..): Join<'s, A, B, P, D>,
        (r2, boundary): (&'s [f64], Boundary),
        points: [usize; 2],
    ) -> Self {
        CountWithin {
            metric,
            a,
            b,
            r2,
            boundary,
            diff: vec![0; r2.len() + 1],
            block: Block::boxed(points),
        }
    }

    /// The first radius of `range` that takes in distance `d` (the end if none).
    #[inline(always)]
    fn first_admitting(&self, range: Range<usize>, d: f64) -> usize {
        range.start + self.r2[range].partition_point(|&r2| !self.boundary.admits(d, r2))
    }

    /// The counts, summed from the differences.
    pub(crate) fn counts(&self) -> Vec<u64> {
        let mut sum = 0i128;
        self.diff[..self.r2.len()]
            .iter()
            .map(|&c| {
                sum += c;
                sum as u64
            })
            .collect()
    }
}

impl<'s, A, B, P, const D: usize> PairVisitor<A::Index, B::Index, (usize, usize), D>
    for CountWithin<'s, A, B, P, D>
where
    A: PointSet<D>,
    B: PointSet<D>,
    P: PairDistance<D>,
{
    type Break = core::convert::Infallible;

    #[inline]
    fn classify(
        &mut self,
        &(lo, hi): &(usize, usize),
        near: f64,
        far: f64,
        pairs: u64,
    ) -> Step<(usize, usize)> {
        let lo = self.first_admitting(lo..hi, near);
        let all = self.first_admitting(lo..hi, far);
        if all < hi {
            self.diff[all] += i128::from(pairs);
            self.diff[hi] -= i128::from(pairs);
        }
        if lo == all {
            Step::Skip
        } else {
            Step::Split((lo, all))
        }
    }

    fn leaves(
        &mut self,
        &(lo, hi): &(usize, usize),
        (ra, ba): (Range<usize>, &Aabb<f64, D>),
        (rb, bb): (Range<usize>, &Aabb<f64, D>),
        same: bool,
    ) -> ControlFlow<Self::Break> {
        let (pa, pb) = (self.a.index().points(), self.b.index().points());
        scan_counts(
            &mut self.block,
            (pa, ra, ba),
            (pb, rb, bb),
            same,
            self.metric,
            (self.r2, lo, hi),
            self.boundary,
            &mut self.diff,
        );
        ControlFlow::Continue(())
    }
}
