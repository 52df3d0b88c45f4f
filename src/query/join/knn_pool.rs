//! The candidate pool of one group of the k-nearest joins: every point of the other tree that
//! may be among the `k` nearest of a point of the group, gathered once per group into columns.
//!
//! Given a radius `g` (a squared distance), the pool is the points `p` of the other tree with
//! [`PairDistance::point_box`]`(p, group box) <= g`, found by a depth-first walk of the other
//! tree on an explicit stack that skips every node whose box is farther than `g` from the group's
//! box ([`PairDistance::box_box`]). The points are laid out in [`Chunk`]s of [`CHUNK`]: one array
//! per axis, their positions, and the tight box of the chunk's points, so that one query point
//! skips a chunk beyond its bound with one box test and otherwise computes its distances to the
//! whole chunk in a loop of arithmetic without branches (the columns make it vectorise), then
//! keeps those within its bound by writing every one and advancing the end of its buffer by the
//! comparison's outcome (no branch to mispredict).
//!
//! A point `q` of the group whose `k`-th distance among the pool is at most `g` has found its
//! exact `k` nearest there: every point left out lies strictly farther than `g` from the group's
//! box, so from `q`. [`radius_of`] gives a radius that surely holds, from the tree alone.
//!
//! The chunks are kept from group to group and reused: nothing is allocated once they have
//! grown to the largest pool seen.

use super::bounds::PairDistance;
use super::knn_cands::Cands;
use super::traverse::{push_children, SCAN};
use crate::geom::{Aabb, Scalar};
use crate::query::SpatialIndex;

/// The points of a chunk: the lanes of one query point's distance loop.
pub(crate) const CHUNK: usize = 64;

// The lanes of a chunk are the bits of a `u64` mask.
const _: () = assert!(CHUNK <= 64);

/// Up to [`CHUNK`] points of the pool in columns, with their positions and tight box. Lanes
/// past `len` repeat the first point, so that every lane computes an ordinary distance.
pub(crate) struct Chunk<const D: usize> {
    cols: [[f64; CHUNK]; D],
    at: [usize; CHUNK],
    len: usize,
    /// The mask of the lanes holding a point: the first `len`.
    live: u64,
    tight: Aabb<f64, D>,
}

impl<const D: usize> Chunk<D> {
    /// An empty chunk.
    fn new() -> Self {
        Chunk {
            cols: [[0.0; CHUNK]; D],
            at: [0; CHUNK],
            len: 0,
            live: 0,
            tight: Aabb::empty(),
        }
    }

    /// Takes in `part` (1 to [`CHUNK`] points with their positions) in place of its points;
    /// the lanes past them repeat the first.
    #[inline(always)]
    fn fill(&mut self, part: &[([f64; D], usize)]) {
        self.len = part.len();
        self.live = u64::MAX >> (64 - self.len);
        self.tight = Aabb::empty();
        for j in 0..CHUNK {
            let (p, at) = part.get(j).unwrap_or(&part[0]);
            for (col, &c) in self.cols.iter_mut().zip(p) {
                col[j] = c;
            }
            self.at[j] = *at;
        }
        for (p, _) in part {
            self.tight.add_point(p);
        }
    }
}

/// The pool of one group: its chunks (the first `used` of `chunks`) and the walk's stack.
pub(crate) struct Pool<N, const D: usize> {
    chunks: Vec<Chunk<D>>,
    used: usize,
    /// The points' positions never decrease from one to the next (as in a pool gathered from
    /// one leaf): each chunk's first is its lowest, and the chunks' first ones rise.
    rising: bool,
    stack: Vec<(N, Aabb<f64, D>)>,
    /// The points kept by the walk, with their positions, before they are cut into chunks.
    staged: Vec<([f64; D], usize)>,
}

impl<N: Copy, const D: usize> Pool<N, D> {
    /// An empty pool.
    pub(crate) fn new() -> Self {
        Pool {
            chunks: Vec::new(),
            used: 0,
            rising: true,
            stack: Vec::new(),
            staged: Vec::new(),
        }
    }

    /// Gathers the points of `b` within `g` of `gbox` (see the module doc) in place of the pool's
    /// points.
    #[inline(always)]
    pub(crate) fn gather<B, P>(&mut self, b: &B, metric: &P, gbox: &Aabb<f64, D>, g: f64)
    where
        B: SpatialIndex<D, Node = N>,
        P: PairDistance<D>,
    {
        self.stack.clear();
        let points = b.points();
        // The points kept are `staged[..kept]`; each point looked at is written at `kept`,
        // which moves on when it is kept (no branch on the test).
        let mut kept = 0;
        self.stack.extend(b.root());
        while let Some(side) = self.stack.pop() {
            if metric.box_box(gbox, &side.1).0 > g {
                continue;
            }
            let before = self.stack.len();
            push_children(b, &side, SCAN, |c| self.stack.push(c));
            if self.stack.len() > before {
                continue;
            }
            let run = b.run(side.0);
            if self.staged.len() < kept + run.len() {
                self.staged.resize(kept + run.len(), ([0.0; D], 0));
            }
            for at in run {
                let p = points[at].map(Scalar::to_f64);
                self.staged[kept] = (p, at);
                kept += usize::from(metric.point_box(&p, gbox) <= g);
            }
        }
        for (i, part) in self.staged[..kept].chunks(CHUNK).enumerate() {
            if i == self.chunks.len() {
                self.chunks.push(Chunk::new());
            }
            self.chunks[i].fill(part);
        }
        self.used = kept.div_ceil(CHUNK);
        self.rising = self.staged[..kept].windows(2).all(|w| w[0].1 <= w[1].1);
    }

    /// Offers `cands` every point of the pool within `bound` of `q`, but the position `skip`,
    /// as near when within `near` too; `cands` has room for `full` and a chunk's worth. After
    /// each chunk, once `k` near ones are held, the bound tightens to `near` and the far ones
    /// are forgotten; when `full` are held, the best `k` are kept ([`Cands::shrink`]) and the
    /// bound tightens to the `k`-th distance. Once that distance is 0, a chunk whose positions
    /// all come after the `k` kept cannot change them (its points could only tie, and ties go
    /// to the lower position): it is skipped, and so are all the rest when the chunks' positions
    /// rise. Without that, a group of n copies of one point searched a pool of the n copies for
    /// each of them: O(n^2) for a self-join.
    #[inline(always)]
    pub(crate) fn scan<P: PairDistance<D>>(
        &self,
        metric: &P,
        (q, skip): (&[f64; D], usize),
        (mut bound, mut near): (f64, f64),
        cands: &mut Cands,
        (k, full): (usize, usize),
    ) {
        let chunks = &self.chunks[..self.used];
        for (i, c) in chunks.iter().enumerate() {
            if metric.point_box(q, &c.tight) > bound {
                continue;
            }
            offer_chunk(c, metric, (q, skip), (bound, near), cands);
            if near < bound && cands.near() >= k {
                bound = near;
                cands.drop_far();
            }
            if cands.held() >= full {
                bound = cands.shrink();
                near = bound;
                if bound == 0.0 {
                    self.scan_settled(&chunks[i + 1..], metric, (q, skip), cands, full);
                    return;
                }
            }
        }
    }

    /// The rest of [`Pool::scan`] once the `k` kept are all at distance 0: only a point at
    /// distance 0 and a lower position than the `k`-th kept can enter, so a chunk whose
    /// positions all lie beyond that is skipped (with every chunk after it, when the
    /// positions rise).
    #[inline(never)]
    fn scan_settled<P: PairDistance<D>>(
        &self,
        rest: &[Chunk<D>],
        metric: &P,
        (q, skip): (&[f64; D], usize),
        cands: &mut Cands,
        full: usize,
    ) {
        let mut settled_at = cands.kept_last_position();
        for c in rest {
            if metric.point_box(q, &c.tight) > 0.0 {
                continue;
            }
            let lowest = if self.rising {
                c.at[0]
            } else {
                c.at[..c.len].iter().copied().min().unwrap_or(0)
            };
            if lowest > settled_at {
                if self.rising {
                    break;
                }
                continue;
            }
            offer_chunk(c, metric, (q, skip), (0.0, 0.0), cands);
            if cands.held() >= full {
                cands.shrink();
                settled_at = cands.kept_last_position();
            }
        }
    }
}

/// Offers `cands` every point of chunk `c` within `bound` of `q` but the position `skip`, as
/// near when within `near` too: the distances to the whole chunk in a loop of arithmetic, then
/// the points within the bound by their mask's bits.
#[inline(always)]
fn offer_chunk<P: PairDistance<D>, const D: usize>(
    c: &Chunk<D>,
    metric: &P,
    (q, skip): (&[f64; D], usize),
    (bound, near): (f64, f64),
    cands: &mut Cands,
) {
    let mut dist = [0.0; CHUNK];
    for (j, d) in dist.iter_mut().enumerate() {
        let p: [f64; D] = core::array::from_fn(|a| c.cols[a][j]);
        *d = metric.distance(q, &p);
    }
    let mut mask = 0u64;
    for (j, &d) in dist.iter().enumerate() {
        mask |= u64::from(d <= bound) << j;
    }
    mask &= c.live;
    while mask != 0 {
        let j = mask.trailing_zeros() as usize;
        mask &= mask - 1;
        cands.push(dist[j].to_bits(), c.at[j], skip, dist[j] <= near);
    }
}

/// A radius (squared distance) within which every point of the closed box `gbox` surely has
/// `need` points of `b`: the farthest distance from `gbox` to the box of the smallest node met
/// on the way down from the root, toward `gbox`'s centre, that still holds `need` points. `b`
/// holds at least `need` points.
pub(crate) fn radius_of<B, P, const D: usize>(
    b: &B,
    metric: &P,
    gbox: &Aabb<f64, D>,
    need: usize,
) -> f64
where
    B: SpatialIndex<D>,
    P: PairDistance<D>,
{
    let Some((mut node, mut nb)) = b.root() else {
        return f64::INFINITY;
    };
    let centre: [f64; D] = core::array::from_fn(|a| 0.5 * (gbox.min[a] + gbox.max[a]));
    loop {
        let mut next = None;
        b.for_each_child_in(node, &nb, |c, cb| {
            if next.is_none() && cb.contains(&centre) && b.count(c) >= need {
                next = Some((c, *cb));
            }
        });
        match next {
            Some((c, cb)) => (node, nb) = (c, cb),
            None => return metric.box_box(gbox, &nb).1,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::bounds::Counting;
    use super::{Cands, Pool, CHUNK};
    use crate::geom::Aabb;
    use crate::query::OneLeaf;

    /// A pool of n copies of one point: each copy's search ends once its `k` nearest are the
    /// copies at the lowest positions (a copy of the rest could only tie them), after a few
    /// chunks, instead of computing its distance to all n.
    #[test]
    fn copies_of_one_point_settle_after_a_few_chunks() {
        let n = 64 * CHUNK;
        let p = [0.25, -3.0, 7.5];
        let leaf = OneLeaf(vec![p; n]);
        let metric = Counting::default();
        let gbox = Aabb::new(p, p).unwrap();
        let mut pool = Pool::new();
        pool.gather(&leaf, &metric, &gbox, 0.0);
        for k in [1, 5, 20, 40] {
            for me in [0, 1, k, n / 2, n - 1] {
                let mut cands = Cands::default();
                cands.reset(k, 2 * k + CHUNK);
                metric.reset();
                pool.scan(&metric, (&p, me), (0.0, 0.0), &mut cands, (k, 2 * k));
                let computed = metric.distances();
                assert!(
                    computed <= 3 * CHUNK,
                    "k {k}, copy {me}: {computed} distances"
                );
                // the k lowest positions but its own
                let got: Vec<usize> = cands
                    .ordered()
                    .map(|(d, at)| {
                        assert_eq!(d, 0);
                        at
                    })
                    .collect();
                let want: Vec<usize> = (0..n).filter(|&i| i != me).take(k).collect();
                assert_eq!(got, want, "k {k}, copy {me}");
            }
        }
    }
}
