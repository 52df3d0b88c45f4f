//! Range queries over a [`Region`]: the algorithm of exercise 14.13 of the chapter, on any
//! [`SpatialIndex`], with an explicit stack.
//!
//! Start at the root. A node whose closed box is outside the region is skipped; one inside it
//! reports its whole run of points without testing them; one crossing the region's boundary
//! passes to its children, or, at a leaf, tests its points one by one. From 4D up the index may
//! leave out at once the children in a half of a node (either side of a split line) that the
//! region excludes ([`SpatialIndex::for_each_child_unless`], [`Region::excludes`]), and from
//! 6D up those of a node small enough to be tested whole too, whose other children's runs are
//! then tested alone (`for_each_kept_run`, `query/index.rs`);
//! [`PointSet::query_stats`](super::PointSet::query_stats) still classifies every child.
//!
//! # Worst-case query time (exercise 14.13)
//!
//! Let the tree (bucket size 1, the chapter's) have depth `d` and `n` points, and let the answer
//! have `k` points. Every node visited is a child of a crossing internal node (or the root), so the
//! work is `O(2^D * C + k)` for `C` crossing internal nodes: inside cells cost O(1) plus their
//! output, and a crossing leaf holds at most one point. Two facts bound `C` level by level:
//!
//! - internal nodes of one level hold disjoint sets of at least two points, so at most `n / 2` of
//!   them exist per level;
//! - a vertical line `x = c` meets the interior of (or the right-hand face of the cells right of)
//!   at most one column of cells per level, `2^l` cells at level `l`; the boundary of a
//!   rectangle meets at most `4 * 2^l + 4` of them.
//!
//! Summing `min(2^l, n / 2)` over the `d` levels with internal nodes gives, for a half-plane
//! `x <= c` and for a rectangle alike,
//!
//! > `C = O(min(2^d, n + n (d - log2 n)))`, so the query takes `O(n (d - log2 n + 1) + k)` time in
//! > the worst case, which is `O((d + 1) n + k)`, independent of how few points are reported.
//!
//! The bound is tight, even with an empty answer: put `n / 2` pairs of points just right of the
//! line (pair `i` at height `(i + 1/2) / (n / 2)`, its two points `2^-d` apart in x). Below level
//! `log2(n / 2)` every pair sits alone in a column of cells touching the line, and stays crossing
//! until the pair separates near level `d`: `(n / 2) (d - log2 n)` crossing nodes, and nothing
//! reported. `tests/queries.rs` builds this tree and counts the nodes visited through
//! [`PointSet::query_stats`](super::PointSet::query_stats). In contrast, a kd-tree answers the same query in
//! `O(sqrt n + k)`; a quadtree's depth is bounded by the spread of the points (Lemma 14.1), not by
//! their number.

use super::index::{for_each_kept_run, scans_whole, Runs, SpatialIndex};
use super::region::{Region, Relation};
use super::QueryError;
use crate::geom::{Aabb, Scalar};
use crate::geom::{Halves, Kept};
use crate::prefetch::prefetch_run;
use core::convert::Infallible;
use core::ops::{ControlFlow, Range};
use smallvec::SmallVec;

/// Counts of the work a range query did, from [`PointSet::query_stats`](super::PointSet::query_stats).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QueryStats {
    /// Nodes whose box was classified (the root included).
    pub nodes_visited: usize,
    /// Points tested one by one with [`Region::contains`].
    pub points_tested: usize,
    /// Points reported.
    pub count: usize,
}

/// Pending work of a traversal: a node with its closed box, and whether the box is inside the
/// region (report its run) or crossing it (look at its children, or test its points).
type Stack<N, const D: usize> = SmallVec<[(N, Aabb<f64, D>, bool); 48]>;

/// A crossing node whose run holds at most `scan_limit::<D>()` points has them tested one by one
/// instead of its children classified: its run is contiguous, so the scan streams through
/// memory, where descending reads the children's runs and boxes (a cache miss per level) and
/// classifies up to 2^D of them. Used by the iterator, the count and the visitor;
/// [`PointSet::query_stats`](super::PointSet::query_stats) runs the chapter's algorithm as stated (descend to the leaves), so
/// that its counts are the analysis's.
///
/// The limits are measured (`examples/compare`, 10^6 points, boxes and balls with ~100 results,
/// and 3, 10 and 1000 results in 2D): in 2D, 128 makes ball queries 1.2-1.35x and box queries
/// 1.2-1.5x faster than 48 (kd-trees' bucket size, the limit before), on every workload and
/// answer size tried; in 3D, 48 and 96 tie and 128 is slower on uniform balls, so 64. In 4D
/// and 5D 128 again: two alternated rounds of `compare --dim 4 --queries 50000`, against 64,
/// clustered balls 624-678 -> 489-519 ms and boxes 391-424 -> 341-372, uniform balls 520-550
/// -> 505-535, lattice balls 554-586 -> 624-637 (slower, still ahead of kiddo); a 4D/5D
/// program alike (clustered 4D balls 841-865 -> 710-777 ms, 5D 913-977 -> 898-906); 24 was
/// slower on clustered points. From 6D up the limit is 4 points per child anyway.
pub(crate) const fn scan_limit<const D: usize>() -> usize {
    super::index::scan_limit::<D>(if D == 3 { 64 } else { 128 })
}

/// The engine of [`RegionIter`](super::RegionIter): the points of an index in a region with
/// their payloads, lazily, in the index's order within each reported node.
pub(crate) struct IndexRegionIter<'a, I: SpatialIndex<D>, R, const D: usize> {
    index: &'a I,
    region: R,
    stack: Stack<I::Node, D>,
    /// The rest of an inside node's run: reported untested.
    run: Range<usize>,
    /// The rest of a crossing node's run: tested [`CHUNK`] points at a time.
    pending: Range<usize>,
    /// From 6D up, the runs of a node scanned whole still to test, the next last
    /// ([`for_each_kept_run`]); empty below. Inline up to 16 runs (a 6D ball keeps about a
    /// quarter of a node's 64 children), so that most queries do not allocate for them.
    kept: SmallVec<[Range<usize>; 16]>,
    /// The points of the chunk tested last that lie in the region, bit `j` for `base + j`.
    mask: u64,
    base: usize,
}

impl<'a, I: SpatialIndex<D>, R: Region<D>, const D: usize> IndexRegionIter<'a, I, R, D> {
    /// A lazy query of `region` on `index`; the region is checked first.
    pub(crate) fn new(index: &'a I, region: R) -> Result<Self, QueryError> {
        region.validate()?;
        let mut stack = Stack::new();
        if let Some((root, b)) = index.root() {
            push_child(
                &mut stack,
                index,
                &region,
                root,
                &b,
                scan_limit::<D>(),
                true,
            );
        }
        Ok(IndexRegionIter {
            index,
            region,
            stack,
            run: 0..0,
            pending: 0..0,
            kept: SmallVec::new(),
            mask: 0,
            base: 0,
        })
    }
}

impl<'a, I: SpatialIndex<D>, R: Region<D>, const D: usize> Iterator
    for IndexRegionIter<'a, I, R, D>
{
    type Item = (&'a [I::Scalar; D], &'a I::Payload);

    fn next(&mut self) -> Option<Self::Item> {
        let (points, items) = (self.index.points(), self.index.payloads());
        loop {
            if self.mask != 0 {
                let i = self.base + self.mask.trailing_zeros() as usize;
                self.mask &= self.mask - 1;
                return Some((&points[i], &items[i]));
            }
            if let Some(i) = self.run.next() {
                return Some((&points[i], &items[i]));
            }
            if !self.pending.is_empty() {
                let chunk = self.pending.start..self.pending.end.min(self.pending.start + CHUNK);
                self.base = chunk.start;
                self.pending.start = chunk.end;
                self.mask = contains_mask(&self.region, &points[chunk]);
                continue;
            }
            if D >= 6
                && let Some(run) = self.kept.pop()
            {
                self.pending = run;
                continue;
            }
            let (node, b, inside) = self.stack.pop()?;
            if inside {
                if !I::NESTED_RUNS && descend_inside(self.index, &mut self.stack, node, &b) {
                    continue;
                }
                self.run = self.index.run(node);
                continue;
            }
            let (stack, index, region) = (&mut self.stack, self.index, &self.region);
            let out = Excluded(region, true);
            if scans_whole(index, node, scan_limit::<D>()) {
                let kept = &mut self.kept;
                if for_each_kept_run(index, node, &b, out, |run| kept.push(run)) {
                    kept.reverse();
                } else {
                    self.pending = index.run(node);
                }
                continue;
            }
            let internal = index.for_each_child_unless(node, &b, out, |child, b| {
                push_child(stack, index, region, child, b, scan_limit::<D>(), true);
            });
            if !internal {
                self.pending = self.index.run(node);
            }
        }
    }
}

/// The halves of a box a region excludes ([`Halves`] through [`Region::kept_children`]), when
/// the flag is set (else none): the test a region query hands an index.
struct Excluded<'r, R>(&'r R, bool);

impl<R> Clone for Excluded<'_, R> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<R> Copy for Excluded<'_, R> {}

impl<R: Region<D>, const D: usize> Halves<D> for Excluded<'_, R> {
    #[inline(always)]
    fn kept(&self, bbox: &Aabb<f64, D>, mid: &[f64; D]) -> Kept {
        if self.1 {
            self.0.kept_children(bbox, mid)
        } else {
            Some((0, 0))
        }
    }
}

/// The most points [`contains_mask`] tests at once: the bits of its mask.
const CHUNK: usize = 64;

/// Bit `j` set when `points[j]` lies in `region` (at most [`CHUNK`] points). The loop has no
/// branch that depends on the answer (the built-in regions' tests have none either), so it runs
/// at the speed of the arithmetic, where a test-and-report loop mispredicts at every edge of
/// the region (box queries 1.05x faster in 3D; balls within noise).
#[inline(always)]
fn contains_mask<S: Scalar, R: Region<D>, const D: usize>(region: &R, points: &[[S; D]]) -> u64 {
    debug_assert!(points.len() <= CHUNK);
    let mut mask = 0;
    for (j, p) in points.iter().enumerate() {
        mask |= u64::from(region.contains(&p.map(Scalar::to_f64))) << j;
    }
    mask
}

/// Classifies `child` (box `b`) and stacks it unless it is outside, prefetching what will be
/// read of it: the points of a crossing run of at most `scan` points (to be tested), and when
/// the caller `reads` the answer's points and items (not for a count or a list of indices), the
/// items of such a run and the points and items of an inside run.
///
/// The misses of the (up to 2^D) runs pushed together then overlap instead of coming one after
/// another as the stack pops them: the queries are bound by those misses (a leaf run sits
/// anywhere in memory), not by the tests. Measured with 10^6 uniform points in 3D, 10^5
/// queries with ~100 results, best of 15, three alternating runs: balls 586-632 ms without,
/// 459-491 with points prefetched, 338-361 with points and items; boxes 504-549, 390-417,
/// 250-270.
#[inline(always)]
fn push_child<I: SpatialIndex<D>, R: Region<D>, const D: usize>(
    stack: &mut Stack<I::Node, D>,
    index: &I,
    region: &R,
    child: I::Node,
    b: &Aabb<f64, D>,
    scan: usize,
    reads: bool,
) {
    let inside = match region.classify(b) {
        Relation::Outside => return,
        Relation::Inside => true,
        Relation::Crossing => false,
    };
    if reads || !inside {
        let run = index.run(child);
        if inside || run.len() <= scan {
            prefetch_run(index.points(), run.clone());
            if reads {
                prefetch_run(index.payloads(), run);
            }
        }
    }
    stack.push((child, *b, inside));
}

/// Stacks every child of an inside inner `node` (box `b`) as inside; `false` for a leaf. For an
/// index without [`SpatialIndex::NESTED_RUNS`], whose inner nodes have no run to report whole.
fn descend_inside<I: SpatialIndex<D>, const D: usize>(
    index: &I,
    stack: &mut Stack<I::Node, D>,
    node: I::Node,
    b: &Aabb<f64, D>,
) -> bool {
    index.for_each_child_in(node, b, |child, cb| stack.push((child, *cb, true)))
}

/// Calls `report(i)` for every point index `i` in `region`; returns the work done. A crossing
/// node with at most `scan` points has them tested without descending (0: only leaves are);
/// `reads`: whether `report` reads the points and items it is given (see [`push_child`]).
/// Allocates only when more than 48 nodes are pending (deeper than about 16 levels in 2D, 7 in
/// 3D).
#[inline]
pub(crate) fn for_each_in<I: SpatialIndex<D>, R: Region<D>, const D: usize>(
    index: &I,
    region: &R,
    scan: usize,
    reads: bool,
    mut report: impl FnMut(usize),
) -> Result<QueryStats, QueryError> {
    let (stats, _) = for_each_until(index, region, scan, reads, |i| {
        report(i);
        ControlFlow::<Infallible>::Continue(())
    })?;
    Ok(stats)
}

/// [`for_each_in`] whose `report` may stop the traversal: the first [`ControlFlow::Break`] ends
/// it at once and is returned with the work done so far (partial counts then: an inside run is
/// counted whole before it is reported). With a `report` that cannot break
/// (`ControlFlow<Infallible>`) the test of its answer compiles to nothing.
///
/// Only the handling of a run is compiled per `report`: the traversal ([`walk_runs`]) is
/// compiled once per index, region and dimension and hands each run over through `dyn`, one
/// dynamic call per run (the traversal was a thirtieth of the unoptimised code of the
/// library's tests when it was compiled per closure).
pub(crate) fn for_each_until<I: SpatialIndex<D>, R: Region<D>, B, const D: usize>(
    index: &I,
    region: &R,
    scan: usize,
    reads: bool,
    mut report: impl FnMut(usize) -> ControlFlow<B>,
) -> Result<(QueryStats, Option<B>), QueryError> {
    region.validate()?;
    let points = index.points();
    let mut stop = None;
    let stats = walk_runs(index, region, scan, reads, &mut |run, inside, stats| {
        let found = if inside {
            run.into_iter().find_map(|i| report(i).break_value())
        } else {
            test_run(points, region, run, stats, &mut report)
        };
        match found {
            Some(b) => {
                stop = Some(b);
                ControlFlow::Break(())
            }
            None => ControlFlow::Continue(()),
        }
    });
    Ok((stats, stop))
}

/// What [`walk_runs`] hands a run to: the run, whether it lies inside the region (else its
/// points are to be tested), and the work counts (a run inside is already counted).
type RunHandler<'a> = dyn FnMut(Range<usize>, bool, &mut QueryStats) -> ControlFlow<()> + 'a;

/// The traversal of [`for_each_until`]: every run inside `region` and every run to test handed
/// to `each`, until it breaks; the work done.
fn walk_runs<I: SpatialIndex<D>, R: Region<D>, const D: usize>(
    index: &I,
    region: &R,
    scan: usize,
    reads: bool,
    each: &mut RunHandler<'_>,
) -> QueryStats {
    let mut stats = QueryStats::default();
    let Some((root, b)) = index.root() else {
        return stats;
    };
    let mut stack = Stack::new();
    stats.nodes_visited = 1;
    push_child(&mut stack, index, region, root, &b, scan, reads);
    while let Some((node, b, inside)) = stack.pop() {
        if inside {
            if !I::NESTED_RUNS && descend_inside(index, &mut stack, node, &b) {
                continue;
            }
            let run = index.run(node);
            stats.count += run.len();
            if each(run, true, &mut stats).is_break() {
                return stats;
            }
            continue;
        }
        let mut visited = 0;
        // `scan` 0 runs the chapter's algorithm as stated: every child classified and counted.
        let out = Excluded(region, scan != 0);
        let internal = !scans_whole(index, node, scan)
            && index.for_each_child_unless(node, &b, out, |child, b| {
                visited += 1;
                push_child(&mut stack, index, region, child, b, scan, reads);
            });
        stats.nodes_visited += visited;
        if internal {
            continue;
        }
        // A leaf, or a node scanned whole: from 6D up only its children's runs outside the
        // halves that are out, below it the whole run.
        let (whole, mut kept) = (index.run(node), Runs::new());
        let runs = if for_each_kept_run(index, node, &b, out, |run| kept.push(run)) {
            &kept[..]
        } else {
            core::slice::from_ref(&whole)
        };
        for run in runs {
            stats.points_tested += run.len();
            if each(run.clone(), false, &mut stats).is_break() {
                return stats;
            }
        }
    }
    stats
}

/// Tests the points of `run` against `region` [`CHUNK`] at a time, counting and reporting those
/// inside; the first [`ControlFlow::Break`] of `report` is returned.
#[inline(always)]
fn test_run<S: Scalar, R: Region<D>, B, const D: usize>(
    points: &[[S; D]],
    region: &R,
    run: Range<usize>,
    stats: &mut QueryStats,
    report: &mut impl FnMut(usize) -> ControlFlow<B>,
) -> Option<B> {
    for (c, chunk) in points[run.clone()].chunks(CHUNK).enumerate() {
        let mut mask = contains_mask(region, chunk);
        stats.count += mask.count_ones() as usize;
        while mask != 0 {
            let i = run.start + c * CHUNK + mask.trailing_zeros() as usize;
            if let ControlFlow::Break(stop) = report(i) {
                return Some(stop);
            }
            mask &= mask - 1;
        }
    }
    None
}
