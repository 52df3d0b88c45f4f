//! Nearest and k-nearest neighbours: depth-first branch and bound (Arya and Mount's priority
//! search in depth-first form; Friedman, Bentley and Finkel's kd-tree search on a 2^D-tree) with
//! a bounded candidate list on any [`SpatialIndex`] and [`Metric`].
//!
//! Keep the best `k` (distance, index) pairs found so far, sorted. Pop a node from an explicit
//! stack; skip it if its box's lower bound exceeds the `k`-th distance (or the maximum distance
//! while fewer than `k` are known); scan a leaf's run; push an internal node's children farthest
//! first, so the nearest box is searched first and tightens the bound soonest. Before that, one
//! walk down the nearest child at every level ([`SpatialIndex::nearest_child`]; the point tree
//! compares the query with the split lines instead of bounding every child: 10^5 1-NN queries
//! on 10^6 uniform points, 2D 59 -> 47 ms, 3D 101 -> 81 ms) scans the node around the query and
//! seeds the bound; the search then backtracks along that walk, deepest level first, stacking
//! only the children beside it that can still hold a neighbour, and stops going up once the
//! ball of the bound lies inside the box walked through. Any node of at most `SCAN` points is
//! scanned as a leaf (its run is contiguous), as kd-trees scan buckets; for k = 1 the scan keeps
//! the run's nearest point without a branch per point. From 4D up, where a node has 16 to 256
//! children, the index is asked only for the children outside the halves of the node whose box
//! is beyond the bound ([`SpatialIndex::for_each_child_unless`]), and from 6D up the children
//! pushed are ordered once rather than by insertion.
//!
//! A minimum-image metric on a periodic domain ([`Metric::torus`]) runs the same search from the
//! query's images, one after another into the same candidate list ([`super::knn_images`]).
//!
//! Ties are broken by position in [`SpatialIndex::points`] (Morton order): the answer is exactly the
//! first `k` of all points within the maximum distance sorted by `(distance, index)`. A box whose
//! bound equals the `k`-th distance is still searched, so a tie cannot be lost.

use super::index::{for_each_kept_run, scan_limit, scans_whole, Runs, SpatialIndex};
use super::knn_images::Images;
use super::metric::Metric;
use crate::geom::{Aabb, Scalar};
use crate::geom::{Halves, Kept};
use crate::prefetch::prefetch_run;
use smallvec::SmallVec;

/// A point found by a nearest-neighbour query of a [`PointSet`](super::PointSet).
///
/// ```
/// use orthtree::prelude::*;
/// use orthtree::{CompressedTree, DynamicPointTree, Quadtree};
/// let pts = [([0.0, 0.0], 'a'), ([3.0, 4.0], 'b'), ([1.0, 1.0], 'c')];
/// let (p, d, c) = (
///     Quadtree::new(&pts).unwrap(),
///     DynamicPointTree::new(&pts).unwrap(),
///     CompressedTree::new(&pts).unwrap(),
/// );
/// // `index` is where the item sits in the tree's `items()`, in every tree
/// let n = p.nearest(&[2.9, 4.0]).unwrap().unwrap();
/// assert_eq!((p.items()[n.index], *n.item), ('b', 'b'));
/// let n = d.nearest(&[2.9, 4.0]).unwrap().unwrap();
/// assert_eq!((d.items()[n.index], d.point(n.index)), ('b', n.point));
/// let n = c.nearest(&[2.9, 4.0]).unwrap().unwrap();
/// assert_eq!((c.items()[n.index], c.point(n.index)), ('b', n.point));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Neighbor<'a, S, T, const D: usize> {
    /// The point.
    pub point: &'a [S; D],
    /// Its item.
    pub item: &'a T,
    /// Its distance from the query point, in the metric's units (squared for
    /// [`SquaredEuclidean`](super::SquaredEuclidean)).
    pub distance: f64,
    /// Its slot: the position of its item in the set's [`PointSet::items`](super::PointSet::items)
    /// (and of its point in [`PointSet::point`](super::PointSet::point)), in every tree. Ties
    /// are broken by the tree's traversal order (Morton order), not by this number.
    pub index: usize,
}

impl<'a, S, T, const D: usize> Neighbor<'a, S, T, D> {
    /// The point at `i` in `index`, with its payload; `index` is `i` for now.
    pub(crate) fn at<I: SpatialIndex<D, Scalar = S, Payload = T>>(
        index: &'a I,
        distance: f64,
        i: usize,
    ) -> Self {
        Neighbor {
            point: &index.points()[i],
            item: &index.payloads()[i],
            distance,
            index: i,
        }
    }
}

/// The answer of [`k_nearest`]: held inline for k = 1, so that a nearest query allocates nothing.
pub(crate) type Found = SmallVec<[(f64, usize); 1]>;

/// The best `k` candidates so far, each index at most once (the image search may offer a point
/// again, with the same distance).
///
/// Up to [`SORTED_MAX`] candidates stay sorted by `(distance, index)`, a new one put in place by
/// one step of insertion sort. For more, candidates within the bound are appended, and when `2k`
/// are held the `k` nearest are selected (quickselect, `select_nth_unstable`) and the bound
/// becomes the `k`-th distance: O(1) per candidate on average, where keeping the list sorted
/// costs a search and a move of half the list each. The bound between two selections is the
/// previous `k`-th distance, never below the true one, so nothing within the final `k`-th
/// distance is pruned. On a curve (10^6 points on a circle, queries anywhere in the square around
/// it), where most points scanned are nearer than the bound so far, 20 000 100-nearest queries
/// took 4.2 s with the sorted list, 2.4 s with a binary search in it and 0.95 s this way; on 10^6
/// uniform points 100-NN 1.35-1.46x kiddo's time became 0.99-1.03x. At k = 20 on uniform points
/// the sorted list is 7% faster; at 32 the two are even. The list is the answer's own `SmallVec`
/// (inline for k = 1): a larger `Best`, with 16 places inline, made 1-NN on 10^4 2-D points 9%
/// slower (15.8 -> 17.3-17.5 ms for 10^5 queries; probably no longer kept in registers).
pub(super) struct Best {
    k: usize,
    max: f64,
    /// The candidates: up to [`SORTED_MAX`] sorted, above it unsorted, up to `held` (`2k`).
    list: Found,
    held: usize,
    /// The distance a candidate must not exceed: the `k`-th distance (at the last selection,
    /// above [`SORTED_MAX`]) once `k` candidates are known, `max` before.
    limit: f64,
    /// `k` candidates are known.
    full: bool,
    /// A point may be offered twice (the image search): it is kept once.
    repeats: bool,
}

/// Up to this `k` [`Best`] keeps its candidates sorted.
const SORTED_MAX: usize = 16;

/// The order of candidates: by distance, then index.
#[inline(always)]
fn by_distance(a: &(f64, usize), b: &(f64, usize)) -> core::cmp::Ordering {
    a.partial_cmp(b).unwrap_or(core::cmp::Ordering::Equal)
}

impl Best {
    /// No candidate yet, for the `k` nearest within `max` among `n` points.
    #[inline(always)]
    fn new(k: usize, max: f64, n: usize) -> Self {
        let held = if k > SORTED_MAX {
            k.saturating_mul(2)
        } else {
            k
        };
        Best {
            k,
            max,
            list: SmallVec::with_capacity(held.min(n)),
            held,
            limit: max,
            full: false,
            repeats: false,
        }
    }

    /// Lets the same point be offered again (the image search): it is kept once.
    pub(super) fn allow_repeats(&mut self) {
        self.repeats = true;
    }

    /// The distance a candidate must not exceed.
    #[inline(always)]
    pub(super) fn bound(&self) -> f64 {
        self.limit
    }

    /// The bound node boxes are pruned by: `cut` of the `k`-th distance once `k` candidates are
    /// known, the maximum distance before.
    #[inline(always)]
    pub(super) fn prune(&self, cut: impl Fn(f64) -> f64) -> f64 {
        if self.full {
            cut(self.limit)
        } else {
            self.max
        }
    }

    #[inline(always)]
    fn offer(&mut self, d: f64, i: usize) {
        if d > self.limit {
            return;
        }
        if self.k > SORTED_MAX {
            self.list.push((d, i));
            if self.list.len() == self.held {
                self.select();
            }
            return;
        }
        if self.repeats && self.list.contains(&(d, i)) {
            return;
        }
        if self.full {
            let (wd, wi) = self.list[self.k - 1];
            // `i == wi` at `d == wd`: the last candidate offered again.
            if d == wd && i >= wi {
                return;
            }
        } else {
            self.list.push((d, i));
        }
        // Insertion: the worse candidates move up one place (the `k`-th drops out when full).
        let list = self.list.as_mut_slice();
        let mut at = list.len() - 1;
        while at > 0 && (d, i) < list[at - 1] {
            list[at] = list[at - 1];
            at -= 1;
        }
        list[at] = (d, i);
        if list.len() == self.k {
            self.full = true;
            self.limit = list[self.k - 1].0;
        }
    }

    /// Keeps the `k` nearest candidates (without repeats) and bounds the next by the `k`-th.
    #[cold]
    fn select(&mut self) {
        if self.repeats {
            self.list.sort_unstable_by(by_distance);
            self.list.dedup();
        } else if self.list.len() > self.k {
            self.list.select_nth_unstable_by(self.k - 1, by_distance);
        }
        if self.list.len() >= self.k {
            self.list.truncate(self.k);
            self.limit = self.list[self.k - 1].0;
            self.full = true;
        }
    }

    /// `k` candidates are known, all at distance 0, each at an index below `next`: no point at
    /// `next` or after can enter the list (it could only tie them, and ties go to the lower
    /// index). Every candidate is within the bound, so at distance 0 when the bound is.
    #[inline]
    fn settled_before(&self, next: usize) -> bool {
        self.full && self.limit == 0.0 && self.list.iter().all(|&(_, i)| i < next)
    }

    /// The answer: the `k` nearest, sorted by `(distance, index)`.
    fn finish(mut self) -> Found {
        if self.k <= SORTED_MAX {
            return self.list;
        }
        self.list.sort_unstable_by(by_distance);
        if self.repeats {
            self.list.dedup();
        }
        self.list.truncate(self.k);
        self.list
    }
}

/// A node whose run holds at most this many points is scanned as if it were a leaf: its run is
/// contiguous, and a tight loop over a few points costs less than bounding and ordering its
/// children (kd-trees scan buckets of this size). More from 6D up ([`scan_limit`]).
const SCAN: usize = 48;

/// Nodes still to search: (lower bound, node, closed box), nearest on top.
type Pending<N, const D: usize> = SmallVec<[(f64, N, Aabb<f64, D>); 64]>;

/// A query as a search sees it: the point and metric that measure points, then those that
/// bound boxes (the same for an ordinary search; see [`seeded`]).
pub(super) type Query<'a, P, B, const D: usize> = ((&'a [f64; D], &'a P), (&'a [f64; D], &'a B));

/// The `k` nearest points to `q` within distance `max` (inclusive) as (distance, index) pairs,
/// sorted by distance then index. `q` finite, `max` not NaN.
#[inline]
pub(crate) fn k_nearest<I: SpatialIndex<D>, M: Metric<D>, const D: usize>(
    index: &I,
    q: &[f64; D],
    k: usize,
    max: f64,
    metric: &M,
) -> Found {
    search(index, q, k, max, metric, |kth| kth)
}

/// A (1 + eps)-approximate [`k_nearest`] (Arya, Mount, Netanyahu, Silverman and Wu, "An optimal
/// algorithm for approximate nearest neighbor searching in fixed dimensions", J. ACM 1998): a
/// node is pruned once its box is farther than the `k`-th distance shrunk by `1 + eps`
/// ([`Metric::scale_distance`]), so the `i`-th answer is within `1 + eps` times the true
/// `i`-th distance, for every `i`. `eps` finite and positive (0 is [`k_nearest`]), `q` finite,
/// `max` not NaN.
///
/// Why: let the `i`-th answer be at `d_i` and suppose some true `j`-th neighbour (`j <= i`)
/// at `t_j <= t_i` was never offered. It lay in a node pruned while the `k`-th distance was some
/// `b >= d_k >= d_i`, with `t_j >= box distance > b / (1 + eps)`: so `d_i < (1 + eps) t_i`.
/// If every one of the true first `i` was offered, `d_i <= t_i`.
pub(crate) fn k_nearest_approx<I: SpatialIndex<D>, M: Metric<D>, const D: usize>(
    index: &I,
    q: &[f64; D],
    k: usize,
    max: f64,
    metric: &M,
    eps: f64,
) -> Found {
    let shrink = 1.0 / (1.0 + eps);
    search(index, q, k, max, metric, |kth| {
        // An infinite k-th distance (coordinates whose squares overflow) times a zero factor
        // (an eps so large that 1 + eps overflows) is NaN: keep the plain bound then.
        let cut = metric.scale_distance(kth, shrink);
        if cut.is_nan() {
            kth
        } else {
            cut
        }
    })
}

/// The branch and bound of the module doc; `cut(kth)` is the bound node boxes are pruned by
/// once `k` candidates are known (the `k`-th distance itself for the exact search). A metric
/// with a [`Metric::torus`] is searched image by image ([`super::knn_images`]) when the index's
/// root box allows it.
#[inline(always)]
fn search<I: SpatialIndex<D>, M: Metric<D>, const D: usize>(
    index: &I,
    q: &[f64; D],
    k: usize,
    max: f64,
    metric: &M,
    cut: impl Fn(f64) -> f64,
) -> Found {
    let mut best = Best::new(k, max, index.points().len());
    if k == 0 {
        return best.finish();
    }
    let Some((root, b)) = index.root() else {
        return best.finish();
    };
    if M::HAS_TORUS
        && let Some(torus) = metric.torus()
        && let Some(images) = Images::new(torus, metric, q, &b)
    {
        best.allow_repeats();
        images.search(index, q, metric, &mut best, (root, b), &cut);
        return best.finish();
    }
    let plain = (q, metric);
    seeded(index, (plain, plain), &mut best, (root, b), &cut);
    best.finish()
}

/// One search of `index` into `best`, seeded by a walk down to the node around the query:
/// points are measured from the point under the metric of `q`'s first half, boxes bounded from
/// those of its second (the same point and metric for an ordinary search; an image of the
/// query and its unwrapped bound in the image search).
#[inline(always)]
pub(super) fn seeded<I: SpatialIndex<D>, P: Metric<D>, B: Metric<D>, const D: usize>(
    index: &I,
    q @ (p, (qb, bm)): Query<'_, P, B, D>,
    best: &mut Best,
    (root, b): (I::Node, Aabb<f64, D>),
    cut: &impl Fn(f64) -> f64,
) {
    let points = index.points();
    // Seed the bound: walk down to the nearest child at every level (the one holding `q` when
    // it lies in the root box) and scan the first node small enough. The nodes walked through
    // are kept: the rest of the search backtracks along them, as a kd-tree search does, instead
    // of descending again from the root.
    let mut path: SmallVec<[(I::Node, Aabb<f64, D>); 24]> = SmallVec::new();
    let seeded = {
        let (mut node, mut nb) = (root, b);
        loop {
            path.push((node, nb));
            let next = if !scans_whole(index, node, scan_limit::<D>(SCAN)) {
                index.nearest_child(node, &nb, qb, bm)
            } else {
                None
            };
            match next {
                Some((child, cb)) => (node, nb) = (child, cb),
                None => break index.run(node),
            }
        }
    };
    // Ask for the seeded run's points at once, rather than miss after miss as the scan walks
    // them, and for its items, which the caller reads and which sit in another array (most
    // answers come from this run). A/B, 10^5 1-NN queries reading the item, 10^6 uniform
    // points, medians: 2D 60.7 -> 50.3 ms, 3D 109 -> 89 ms.
    prefetch_run(points, seeded.clone());
    prefetch_run(index.payloads(), seeded.clone());
    let first = best.bound();
    // `bound`: what a candidate must not exceed; `prune`: what a node's box must not exceed
    // (the same for the exact search).
    let mut bound = scan_run(best, points, seeded, p, first);
    let mut prune = best.prune(cut);
    let mut stack: Pending<I::Node, D> = SmallVec::new();
    // Deepest first: the children of each path node beside the path, each searched in full
    // before going up, until the ball of the bound lies inside the path node's box (no point
    // outside it can then be within the bound).
    for level in (0..path.len() - 1).rev() {
        let (inner, inner_box) = path[level + 1];
        if ball_inside(bm, qb, prune, &inner_box) {
            break;
        }
        let (node, nb) = path[level];
        index.for_each_child_unless(node, &nb, Beyond(bm, qb, prune), |child, cb| {
            if child != inner {
                push_nearer(index, points, &mut stack, 0, (qb, bm), prune, child, cb);
            }
        });
        order_pushed(&mut stack, 0);
        (bound, prune) = drain(index, &mut stack, q, best, cut, (bound, prune));
    }
}

/// One search of `index` into `best` from its root, without a seeding walk (for a query image
/// whose nearest box is rarely within the bound `best` already holds); `q` as in [`seeded`].
/// Kept out of line: it runs for few queries, and inlined beside [`seeded`] it made the
/// compiler call the index's child visitor out of line in both.
#[inline(never)]
pub(super) fn descend<I: SpatialIndex<D>, P: Metric<D>, B: Metric<D>, const D: usize>(
    index: &I,
    q @ (_, bq): Query<'_, P, B, D>,
    best: &mut Best,
    (root, b): (I::Node, Aabb<f64, D>),
    cut: &impl Fn(f64) -> f64,
) {
    let (bound, prune) = (best.bound(), best.prune(cut));
    let mut stack: Pending<I::Node, D> = SmallVec::new();
    push_nearer(index, index.points(), &mut stack, 0, bq, prune, root, &b);
    drain(index, &mut stack, q, best, cut, (bound, prune));
}

/// Searches every node on `stack` in full, nearest first, scanning leaves (and nodes of at
/// most [`SCAN`] points) into `best`; returns the final `(bound, prune)`.
#[inline(always)]
fn drain<I: SpatialIndex<D>, P: Metric<D>, B: Metric<D>, const D: usize>(
    index: &I,
    stack: &mut Pending<I::Node, D>,
    q @ (p, (qb, bm)): Query<'_, P, B, D>,
    best: &mut Best,
    cut: &impl Fn(f64) -> f64,
    (mut bound, mut prune): (f64, f64),
) -> (f64, f64) {
    let points = index.points();
    while let Some((lower, node, b)) = stack.pop() {
        if lower > prune {
            continue;
        }
        let before = stack.len();
        if scans_whole(index, node, scan_limit::<D>(SCAN)) {
            bound = scan_node(index, (node, &b), best, q, (bound, prune));
            prune = best.prune(cut);
            continue;
        }
        let internal = index.for_each_child_unless(node, &b, Beyond(bm, qb, prune), |child, cb| {
            push_nearer(index, points, stack, before, (qb, bm), prune, child, cb);
        });
        order_pushed(stack, before);
        if !internal {
            bound = scan_run(best, points, index.run(node), p, bound);
            prune = best.prune(cut);
        }
    }
    (bound, prune)
}

/// The halves of a box farther than a bound from a query under a metric ([`Halves`] through
/// [`Metric::kept_within`]): the test a k-nearest search hands an index.
#[derive(Clone, Copy)]
struct Beyond<'m, M, const D: usize>(&'m M, &'m [f64; D], f64);

impl<M: Metric<D>, const D: usize> Halves<D> for Beyond<'_, M, D> {
    #[inline(always)]
    fn kept(&self, bbox: &Aabb<f64, D>, mid: &[f64; D]) -> Kept {
        self.0.kept_within(self.1, bbox, mid, self.2)
    }
}

/// Scans the points of `node` (with box `b`), a node small enough to be scanned whole, into
/// `best`; returns the new bound. From 6D up only the runs of the children outside the halves
/// of `b` beyond `prune` ([`for_each_kept_run`]).
#[inline(always)]
fn scan_node<I: SpatialIndex<D>, P: Metric<D>, B: Metric<D>, const D: usize>(
    index: &I,
    (node, b): (I::Node, &Aabb<f64, D>),
    best: &mut Best,
    (p, (qb, bm)): Query<'_, P, B, D>,
    (mut bound, prune): (f64, f64),
) -> f64 {
    let points = index.points();
    // Gathered first: a visitor that scans is too large to be inlined into the index's child
    // loop.
    let mut runs = Runs::new();
    let out = Beyond(bm, qb, prune);
    if !for_each_kept_run(index, node, b, out, |run| runs.push(run)) {
        return scan_run(best, points, index.run(node), p, bound);
    }
    for run in &runs {
        bound = scan_run(best, points, run.clone(), p, bound);
    }
    bound
}

/// Scans a run, offering every point within `bound` of `q` to `best`; returns the new bound.
#[inline(always)]
fn scan_run<S: Scalar, M: Metric<D>, const D: usize>(
    best: &mut Best,
    points: &[[S; D]],
    run: core::ops::Range<usize>,
    (q, metric): (&[f64; D], &M),
    mut bound: f64,
) -> f64 {
    let start = run.start;
    if best.k == 1 {
        if let Some((near, at)) = nearest_in(&points[run.clone()], q, metric)
            && near <= bound
        {
            best.offer(near, start + at);
            bound = best.bound();
        }
        return bound;
    }
    for (c, block) in points[run].chunks(SETTLE_BLOCK).enumerate() {
        let at = start + c * SETTLE_BLOCK;
        for (j, p) in block.iter().enumerate() {
            let d = metric.distance(q, &p.map(Scalar::to_f64));
            if d <= bound {
                best.offer(d, at + j);
                bound = best.bound();
            }
        }
        if bound == 0.0 && best.settled_before(at + block.len()) {
            break;
        }
    }
    bound
}

/// A run is scanned in blocks of this many points; after each, a search whose `k` candidates
/// are all at distance 0 and before the rest of the run stops scanning it (the rest could only
/// tie them, and ties go to the lower position). Without it a leaf of many copies of one point
/// (a leaf at the maximum depth keeps them all) costs every query at that point a scan of the
/// whole leaf: a self-join of n copies took O(n^2).
const SETTLE_BLOCK: usize = 64;

/// The nearest of `points` to `q` (its distance and position), the first of equals; `None` for
/// no point. Without a branch per point: strictly nearer replaces. (Four interleaved running
/// minima, to break the chain of compare and select through every point, measured 1.2x
/// slower: 2D 1-NN 41 -> 51 ms, 3D 71 -> 85.)
#[inline(always)]
fn nearest_in<S: Scalar, M: Metric<D>, const D: usize>(
    points: &[[S; D]],
    q: &[f64; D],
    metric: &M,
) -> Option<(f64, usize)> {
    let (mut near, mut at) = (f64::INFINITY, 0);
    for (c, block) in points.chunks(SETTLE_BLOCK).enumerate() {
        for (j, p) in block.iter().enumerate() {
            let d = metric.distance(q, &p.map(Scalar::to_f64));
            let nearer = d < near;
            near = if nearer { d } else { near };
            at = if nearer { c * SETTLE_BLOCK + j } else { at };
        }
        // Nothing after the first point at distance 0 can replace it.
        if near == 0.0 {
            break;
        }
    }
    (!points.is_empty()).then_some((near, at))
}

/// Pushes `child` (with its box `cb`) on `stack` when its box is within `bound` of `q`, keeping
/// the entries above `before` farthest first, so that the nearest is popped next; starts loading
/// the run of a child small enough to be scanned.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn push_nearer<I: SpatialIndex<D>, M: Metric<D>, const D: usize>(
    index: &I,
    points: &[[I::Scalar; D]],
    stack: &mut Pending<I::Node, D>,
    before: usize,
    (q, metric): (&[f64; D], &M),
    bound: f64,
    child: I::Node,
    cb: &Aabb<f64, D>,
) {
    let d = metric.box_distance(q, cb);
    if d > bound {
        return;
    }
    let run = index.run(child);
    if run.len() <= scan_limit::<D>(SCAN) {
        // It will be scanned if the bound still lets it: start the load now.
        prefetch_run(points, run);
    }
    let mut at = stack.len();
    stack.push((d, child, *cb));
    if many_children::<D>() {
        return; // ordered once all are pushed (`order_pushed`)
    }
    // Insertion sort, farthest first.
    while at > before && stack[at - 1].0 < d {
        stack.swap(at - 1, at);
        at -= 1;
    }
}

/// `true` from 4D up: a node has up to 2^D children, and moving each child's entry (its box
/// alone is 16 D bytes) about half the pushed ones over in an insertion sort costs more than
/// ordering the lot once ([`order_pushed`]).
#[inline(always)]
const fn many_children<const D: usize>() -> bool {
    D >= 6
}

/// Puts the entries pushed above `before` farthest first (the nearest on top), when
/// [`push_nearer`] left them in child order: their distances sorted beside their positions,
/// then each entry moved once.
#[inline(always)]
fn order_pushed<N: Copy, const D: usize>(stack: &mut Pending<N, D>, before: usize) {
    if !many_children::<D>() || stack.len() - before < 2 {
        return;
    }
    let pushed = &mut stack[before..];
    let mut order: SmallVec<[(f64, u32); 256]> = pushed
        .iter()
        .enumerate()
        .map(|(i, e)| (e.0, i as u32))
        .collect();
    order.sort_unstable_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    let moved: Pending<N, D> = order.iter().map(|&(_, i)| pushed[i as usize]).collect();
    pushed.copy_from_slice(&moved);
}

/// `true` when no point outside the closed box `b` can be within `bound` of `q` under `metric`:
/// every such point lies in one of the 2D closed slabs beyond a face of `b` (a point on a face
/// may belong to the neighbouring cell), and `slab_distance` bounds each from below.
#[inline(always)]
fn ball_inside<M: Metric<D>, const D: usize>(
    metric: &M,
    q: &[f64; D],
    bound: f64,
    b: &Aabb<f64, D>,
) -> bool {
    (0..D).all(|a| {
        metric.slab_distance(q, a, f64::NEG_INFINITY, b.min[a]) > bound
            && metric.slab_distance(q, a, b.max[a], f64::INFINITY) > bound
    })
}
