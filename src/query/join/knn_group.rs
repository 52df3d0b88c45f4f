//! The search of one group of the k-nearest joins: the `k` nearest points of the other tree to
//! every point of a group of nearby points of the querying tree (the leaf-level step of the
//! dual-tree k-nearest join of Gray and Moore, "N-body problems in statistical learning", NIPS
//! 2001), with a guessed radius checked afterwards.
//!
//! 1. Pick a radius `g` (a squared distance): 1.5 times the largest `k`-th distance of the group
//!    searched before by this [`Search`] (nearby groups have nearby densities), or, for the
//!    first, one that surely holds ([`radius_of`]).
//! 2. Gather the candidate pool: the points of the other tree within `g` of the group's box, in
//!    columns ([`Pool`]).
//! 3. Search the pool for each point of the group in turn. A point starts from a bound on its
//!    `k`-th distance taken from the point before it (the farthest of that point and its `k`
//!    neighbours: `k` other points, so a true bound) or from `g`, keeps the pool's points within
//!    the bound in a buffer of `2k` (when it fills, a selection keeps its `k` first by
//!    `(distance, position)` and the `k`-th tightens the bound), and ends by ordering its `k`
//!    first ([`Cands`]: one-word keys and a sorting network). The candidates within 1.3 times
//!    the `k`-th distance of the point before it are held apart as near; once `k` are, the
//!    bound tightens to that distance and the others are dropped, so that most points order
//!    few candidates and select none. Consecutive points of a group are
//!    close (the runs are in the tree's order), so the bound is tight from the first candidate
//!    on, and few candidates reach the buffer.
//! 4. A point whose `k`-th distance in the pool exceeds `g` (or which found fewer than `k`) may
//!    have missed a point outside the pool: the pool is gathered again with the largest radius
//!    such points need (their `k`-th distance in the pool; for one that found fewer, four times
//!    `g` or [`radius_of`], the smaller), and only they are searched again, until none is left:
//!    the radius grows each time, and the one of [`radius_of`] holds for every point.
//!
//! Exactness: the pool holds every point within `g` of the group's box, so a point whose `k`-th
//! distance in the pool is at most `g` has every point it lacks strictly farther than that; a
//! chunk or a candidate is skipped only when a lower bound of its distance exceeds the bound
//! strictly, so every point at exactly the `k`-th distance is offered, and the `k` first by
//! `(distance, position)` are kept (distances are compared by their bits, which order
//! non-negative `f64` as their values): each row is exactly what
//! [`PointSet::k_nearest`](crate::query::PointSet::k_nearest) answers, ties included.
//!
//! All the buffers live in a [`Search`] made once per thread and reused for every group:
//! nothing is allocated per group or per point once they have grown.

use super::bounds::PairDistance;
use super::knn_cands::Cands;
use super::knn_pool::{radius_of, Pool, CHUNK};
use crate::geom::{Aabb, Scalar};
use crate::query::SpatialIndex;
use core::ops::Range;

/// The scratch of one thread's group searches, and the lists of the last group searched.
pub(crate) struct Search<N, const D: usize> {
    /// The group's points as `f64`.
    qs: Vec<[f64; D]>,
    /// Per point of the group, `k` entries: its `k` nearest as (distance, position), sorted by
    /// `(distance, position)`, once it is done.
    lists: Vec<(f64, usize)>,
    /// Per point of the group: whether its list is final.
    done: Vec<bool>,
    /// The candidates of the point being searched: `2k` and a chunk's worth of room.
    cands: Cands,
    /// The candidate pool of the group.
    pool: Pool<N, D>,
    /// The list of the last point of the last group searched (empty before the first).
    last: Vec<(f64, usize)>,
    /// That point.
    last_q: [f64; D],
    /// The radius to try first: the largest `k`-th distance of the last group searched
    /// (infinite before the first).
    guess: f64,
}

impl<N: Copy, const D: usize> Search<N, D> {
    /// Empty buffers.
    pub(crate) fn new() -> Self {
        Search {
            qs: Vec::new(),
            lists: Vec::new(),
            done: Vec::new(),
            cands: Cands::default(),
            pool: Pool::new(),
            last: Vec::new(),
            last_q: [0.0; D],
            guess: f64::INFINITY,
        }
    }

    /// The list of point `qi` of the last group searched: its `k` nearest as (distance,
    /// position in the other tree), sorted by `(distance, position)`.
    pub(crate) fn list(&self, qi: usize, k: usize) -> &[(f64, usize)] {
        &self.lists[qi * k..(qi + 1) * k]
    }

    /// Finds the `k` nearest points of `b` to every point of the group `a[run]` (points that
    /// lie in the closed box `gbox`), into the lists of [`Search::list`]. `same`: `b` is
    /// `a`, and a point skips its own position. `k` must be at least 1 and at most what `b`
    /// holds (others, when `same`).
    #[inline(always)]
    pub(crate) fn group<SA, B, P>(
        &mut self,
        a: &[[SA; D]],
        b: &B,
        metric: &P,
        (run, gbox): (Range<usize>, &Aabb<f64, D>),
        k: usize,
        same: bool,
    ) where
        SA: Scalar,
        B: SpatialIndex<D, Node = N>,
        P: PairDistance<D>,
    {
        let m = run.len();
        if m == 0 {
            return;
        }
        self.qs.clear();
        self.qs
            .extend(a[run.clone()].iter().map(|p| p.map(Scalar::to_f64)));
        self.lists.clear();
        self.lists.resize(m * k, (f64::INFINITY, usize::MAX));
        self.done.clear();
        self.done.resize(m, false);
        let need = k + usize::from(same);
        let mut g = if self.guess.is_finite() {
            self.guess
        } else {
            radius_of(b, metric, gbox, need)
        };
        let mut worst = 0.0f64;
        loop {
            self.pool.gather(b, metric, gbox, g);
            let mut again = f64::NEG_INFINITY;
            for qi in 0..m {
                if self.done[qi] {
                    continue;
                }
                let seed = self.seed(qi, b.points(), metric, (run.start, same), k);
                let found = self.point(qi, metric, (run.start, same), k, seed.min(g));
                match found {
                    Some(kth) if kth <= g => {
                        self.done[qi] = true;
                        worst = worst.max(kth);
                    }
                    Some(kth) => again = again.max(kth),
                    None => {
                        // Four times the radius (twice the distance) if that is less than
                        // the radius that surely holds.
                        let sure = radius_of(b, metric, gbox, need);
                        again = again.max(if g > 0.0 { sure.min(4.0 * g) } else { sure });
                    }
                }
            }
            if again == f64::NEG_INFINITY {
                break;
            }
            // Every point left needs at most `again`; a radius that does not grow (which the
            // bounds rule out) would take the whole tree.
            g = if again > g { again } else { f64::INFINITY };
        }
        self.guess = worst * MARGIN;
        self.last.clear();
        self.last.extend_from_slice(&self.lists[(m - 1) * k..]);
        self.last_q = self.qs[m - 1];
    }

    /// A bound on the `k`-th distance of point `qi` when point `qi - 1` is done (or `qi` is 0
    /// and a group was searched before: then its last point stands for point `qi - 1`): the
    /// farthest distance to that point's neighbours and, when `same`, to that point itself, but
    /// `qi`'s own position: at least `k` other points of `b` (whose points are `pb`). Infinite
    /// when there is no such point.
    #[inline(always)]
    fn seed<S: Scalar, P: PairDistance<D>>(
        &self,
        qi: usize,
        pb: &[[S; D]],
        metric: &P,
        (first, same): (usize, bool),
        k: usize,
    ) -> f64 {
        let (list, before) = match qi {
            0 if self.last.is_empty() => return f64::INFINITY,
            0 => (&self.last[..], &self.last_q),
            _ if !self.done[qi - 1] => return f64::INFINITY,
            _ => (&self.lists[(qi - 1) * k..qi * k], &self.qs[qi - 1]),
        };
        let q = &self.qs[qi];
        let me = if same { first + qi } else { usize::MAX };
        let mut s = 0.0f64;
        for &(_, at) in list {
            if at != me {
                s = s.max(metric.distance(q, &pb[at].map(Scalar::to_f64)));
            }
        }
        if same {
            s = s.max(metric.distance(q, before));
        }
        s
    }

    /// Searches the pool for point `qi` of the group within `bound` (at least its `k`-th
    /// distance, or the pool's radius) and, when it finds `k`, writes its list and returns its
    /// `k`-th distance; `None` when fewer than `k` are within `bound`. `first`: the position of
    /// the group's first point (to skip a point itself when `same`).
    #[inline(always)]
    fn point<P: PairDistance<D>>(
        &mut self,
        qi: usize,
        metric: &P,
        (first, same): (usize, bool),
        k: usize,
        bound: f64,
    ) -> Option<f64> {
        let q = self.qs[qi];
        let skip = if same { first + qi } else { usize::MAX };
        let near = match (qi, self.last.is_empty()) {
            (0, true) => f64::INFINITY,
            (0, false) => self.last[k - 1].0 * NEAR,
            _ if !self.done[qi - 1] => f64::INFINITY,
            _ => self.lists[qi * k - 1].0 * NEAR,
        };
        self.cands.reset(k, 2 * k + CHUNK);
        let cands = &mut self.cands;
        self.pool
            .scan(metric, (&q, skip), (bound, near), cands, (k, 2 * k));
        if cands.held() < k {
            return None;
        }
        let mut kth = 0;
        for (l, (d, at)) in self.lists[qi * k..(qi + 1) * k]
            .iter_mut()
            .zip(self.cands.ordered())
        {
            *l = (f64::from_bits(d), at);
            kth = d;
        }
        Some(f64::from_bits(kth))
    }
}

/// The factor from the largest `k`-th distance of a group to the radius the next group tries
/// (squared distances: 1.22 times the distance); the largest `k`-th distance of nearby groups
/// varies, and a group whose points need more gathers its pool again.
const MARGIN: f64 = 1.5;

/// The factor from the `k`-th distance of the point searched before to the distance within
/// which a point's candidates are near (squared distances).
const NEAR: f64 = 1.3;
