//! The search of one group of the k-nearest joins: the `k` nearest points of the other tree to
//! every point of a group of nearby points of the querying tree, found together (the leaf-level
//! step of the dual-tree k-nearest join of Gray and Moore, "N-body problems in statistical
//! learning", NIPS 2001).
//!
//! The group pops nodes of the other tree from an explicit stack, the nearest box first, and
//! skips a node whose box-to-box lower bound from the group's box exceeds the group's bound
//! (the largest `k`-th distance of its points, infinite while one holds fewer than `k`). The
//! first nodes reached are the group's own cell and its neighbours, so the bounds of all the
//! group's points are seeded from one search before the farther nodes are weighed. At a node to
//! scan, the points within the group's bound of the group's box are gathered into columns (a
//! [`Block`] of up to 64; between neighbouring cells this keeps the strip along their shared
//! faces), then each point of the group whose own bound reaches the gathered points' tight box
//! computes its distances to the whole block at once into a bit mask of those within its bound,
//! and appends only those to its buffer of candidates. A buffer holds up to `2k` candidates in
//! no order: when it first holds `k`, the point's bound becomes their largest distance; when it
//! is full, a selection keeps the `k` first by `(distance, position)` and the bound becomes the
//! `k`-th distance (a constant cost per candidate, where keeping a sorted list costs up to `k`
//! moves and a mispredicted branch per insertion); at the end the `k` kept are sorted.
//!
//! Exactness: a node or point is skipped only when a lower bound of its distance exceeds the
//! bound strictly, so every point at exactly the `k`-th distance is offered, and a selection
//! keeps the first `k` by `(distance, position)`: each row is exactly what
//! [`PointSet::k_nearest`](crate::query::PointSet::k_nearest) answers, ties included.
//!
//! All the buffers live in a [`Search`] made once per thread and reused for every group:
//! nothing is allocated per group or per point.

use super::bounds::PairDistance;
use super::scan::{Block, BLOCK};
use super::traverse::{children, SCAN};
use crate::geom::{Aabb, Scalar};
use crate::query::SpatialIndex;
use core::ops::Range;

/// The scratch of one thread's group searches, and the lists of the last group searched.
pub(crate) struct Search<N, const D: usize> {
    /// The group's points as `f64`.
    qs: Vec<[f64; D]>,
    /// Per point of the group: its `k`-th distance so far (infinite while it holds fewer).
    bounds: Vec<f64>,
    /// Per point of the group: how many candidates its buffer holds.
    held: Vec<usize>,
    /// Per point of the group, [`Search::cap`] entries each: its candidates, unordered while
    /// the search runs; the first `k`, sorted by `(distance, position)`, at the end.
    lists: Vec<(f64, usize)>,
    /// The entries of each point's buffer: twice `k`.
    cap: usize,
    /// The nodes of the other tree left to look at, with their lower bounds and boxes.
    stack: Vec<(f64, N, Aabb<f64, D>)>,
    /// The gathered points of the node being scanned.
    block: Box<Block<D>>,
}

impl<N: Copy, const D: usize> Search<N, D> {
    /// Empty buffers.
    pub(crate) fn new() -> Self {
        Search {
            qs: Vec::new(),
            bounds: Vec::new(),
            held: Vec::new(),
            lists: Vec::new(),
            cap: 0,
            stack: Vec::new(),
            block: Block::boxed(),
        }
    }

    /// The list of point `qi` of the last group searched: its `k` nearest as (distance,
    /// position in the other tree), sorted by `(distance, position)`.
    pub(crate) fn list(&self, qi: usize, k: usize) -> &[(f64, usize)] {
        &self.lists[qi * self.cap..qi * self.cap + k]
    }

    /// Finds the `k` nearest points of `b` to every point of the group `run` of `a` (whose
    /// points lie in the closed box `gbox`), into the lists of [`Search::list`]. `same`: `b` is `a`, and a
    /// point skips its own position. `k` must be at least 1 and at most what `b` holds (others,
    /// when `same`).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn group<A, B, P>(
        &mut self,
        a: &A,
        b: &B,
        metric: &P,
        (run, gbox): (Range<usize>, &Aabb<f64, D>),
        k: usize,
        same: bool,
    ) where
        A: SpatialIndex<D>,
        B: SpatialIndex<D, Node = N>,
        P: PairDistance<D>,
    {
        let m = run.len();
        self.qs.clear();
        self.qs.extend(
            a.points()[run.clone()]
                .iter()
                .map(|p| p.map(Scalar::to_f64)),
        );
        self.bounds.clear();
        self.bounds.resize(m, f64::INFINITY);
        self.held.clear();
        self.held.resize(m, 0);
        self.cap = 2 * k;
        self.lists.clear();
        self.lists.resize(m * self.cap, (f64::INFINITY, usize::MAX));
        self.stack.clear();
        let Some((root, rbox)) = b.root() else { return };
        let mut gbound = f64::INFINITY;
        let pb = b.points();
        self.stack.push((metric.box_box(gbox, &rbox).0, root, rbox));
        while let Some((lower, node, nb)) = self.stack.pop() {
            if lower > gbound {
                continue;
            }
            let kids = children(b, &(node, nb), SCAN);
            if kids.is_empty() {
                let rb = b.run(node);
                let mut next = rb.start;
                while next < rb.end {
                    let tight = self.gather(pb, &mut next, rb.end, metric, gbox, gbound);
                    if let Some(tight) = tight {
                        self.offer_block(metric, &tight, run.start, k, same);
                    }
                }
                gbound = self.bounds.iter().copied().fold(0.0, f64::max);
                continue;
            }
            // Farthest first, so that the nearest child is popped next.
            let before = self.stack.len();
            for (c, cb) in kids {
                let d = metric.box_box(gbox, &cb).0;
                if d > gbound {
                    continue;
                }
                let mut at = self.stack.len();
                self.stack.push((d, c, cb));
                while at > before && self.stack[at - 1].0 < d {
                    self.stack.swap(at - 1, at);
                    at -= 1;
                }
            }
        }
        for qi in 0..m {
            let buf = &mut self.lists[qi * self.cap..qi * self.cap + self.held[qi]];
            if buf.len() > k {
                buf.select_nth_unstable_by(k - 1, order);
            }
            buf[..k].sort_unstable_by(order);
        }
    }

    /// Gathers into the block the next points of `points[*next..end]` (up to [`BLOCK`]) that
    /// may be within `gbound` of a point of the group's box `gbox`, moving `next` past those
    /// looked at; their tight box, or `None` when none was kept.
    #[inline(always)]
    fn gather<S: Scalar, P: PairDistance<D>>(
        &mut self,
        points: &[[S; D]],
        next: &mut usize,
        end: usize,
        metric: &P,
        gbox: &Aabb<f64, D>,
        gbound: f64,
    ) -> Option<Aabb<f64, D>> {
        let block = &mut self.block;
        block.clear();
        let mut tight = Aabb::<f64, D>::empty();
        while *next < end && block.len() < BLOCK {
            let p = points[*next].map(Scalar::to_f64);
            if metric.point_box(&p, gbox) <= gbound {
                block.push(&p, *next);
                tight.add_point(&p);
            }
            *next += 1;
        }
        (block.len() > 0).then_some(tight)
    }

    /// Offers the gathered points to every point of the group whose bound reaches their tight
    /// box: distances to the whole block at once, then only those within the bound one by one.
    /// `first`: the position of the group's first point (to skip a point itself when `same`).
    #[inline(always)]
    fn offer_block<P: PairDistance<D>>(
        &mut self,
        metric: &P,
        tight: &Aabb<f64, D>,
        first: usize,
        k: usize,
        same: bool,
    ) {
        for (qi, q) in self.qs.iter().enumerate() {
            let bound = self.bounds[qi];
            if metric.point_box(q, tight) > bound {
                continue;
            }
            let mut mask = self.block.mask(0, q, metric, |d| d <= bound);
            let cap = self.cap;
            let buf = &mut self.lists[qi * cap..(qi + 1) * cap];
            let held = &mut self.held[qi];
            let mut bound = bound;
            let me = first + qi;
            while mask != 0 {
                let j = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                let (at, d) = (self.block.at(j), self.block.dist(j));
                if (same && at == me) || d > bound {
                    continue;
                }
                buf[*held] = (d, at);
                *held += 1;
                if *held == k {
                    bound = buf[..k].iter().fold(0.0, |b, c| c.0.max(b));
                } else if *held == cap {
                    buf.select_nth_unstable_by(k - 1, order);
                    *held = k;
                    bound = buf[k - 1].0;
                }
            }
            self.bounds[qi] = bound;
        }
    }
}

/// The order of candidates: by distance, then by position (the order
/// [`PointSet::k_nearest`](crate::query::PointSet::k_nearest) breaks ties in).
#[inline(always)]
fn order(a: &(f64, usize), b: &(f64, usize)) -> core::cmp::Ordering {
    a.0.total_cmp(&b.0).then(a.1.cmp(&b.1))
}
