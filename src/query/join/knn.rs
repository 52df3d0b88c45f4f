//! All k-nearest neighbours between two trees, and within one: a dual-tree traversal (Gray and
//! Moore, "N-body problems in statistical learning", 2001) whose query side is split down to
//! groups of nearby points, each group searching the other tree once for all its points.
//!
//! A group is a leaf of the query tree, or a node whose contiguous run is small enough to scan
//! (at most 32 points), with the tight box of its points. Each of its points keeps its best `k`
//! candidates, sorted by `(distance, position)`; the group's bound is the largest of their `k`-th
//! distances (infinite while one has fewer). The group pops nodes of the other tree from an
//! explicit stack, nearest box first, and skips a node whose box-to-box lower bound exceeds the
//! group's bound; at a node to scan, each point skips it when its own point-to-box bound exceeds
//! its own `k`-th distance, and offers the node's points otherwise. A node at exactly the bound
//! is still searched, so the answer is, for each point, exactly the first `k` of all points of
//! the other tree sorted by `(distance, position)`: what [`PointSet::k_nearest`] answers, ties
//! included. In the self-join a point skips its own position; its duplicates are other points
//! at distance 0.
//!
//! The groups are independent, the unit of the parallel form.

use super::bounds::PairDistance;
use super::traverse::{children, Side, SCAN};
use crate::geom::{Aabb, Scalar};
use crate::query::{PointSet, SpatialIndex};
use core::ops::Range;

/// The k nearest neighbours of every point of a set, in a compact table: row `r` is the set's
/// slot `r` ([`PointSet::items`]`()[r]`), its [`KnnTable::k`] entries sorted by distance (squared
/// Euclidean), ties in the other tree's traversal order, as [`PointSet::k_nearest`] gives them.
///
/// ```
/// use orthtree::prelude::*;
/// use orthtree::Quadtree;
/// let t = Quadtree::new(&[([0.0, 0.0], 'a'), ([1.0, 0.0], 'b'), ([3.0, 0.0], 'c')]).unwrap();
/// let table = t.k_nearest_self(1);
/// assert_eq!((table.rows(), table.k()), (3, 1));
/// assert_eq!(table.row(2), (&[1][..], &[4.0][..])); // 'c' is nearest to 'b', at squared 4
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct KnnTable {
    k: usize,
    rows: usize,
    slots: Vec<usize>,
    distances: Vec<f64>,
}

impl KnnTable {
    /// The entries per row: the `k` asked for, or fewer when the other set holds fewer points
    /// (fewer others, in a self-join).
    pub fn k(&self) -> usize {
        self.k
    }
    /// The number of rows: the points of the querying set.
    pub fn rows(&self) -> usize {
        self.rows
    }
    /// The neighbours of slot `row`: their slots in the other set and their squared distances.
    ///
    /// # Panics
    /// When `row >= self.rows()`.
    pub fn row(&self, row: usize) -> (&[usize], &[f64]) {
        assert!(
            row < self.rows,
            "row {row} of a table of {} rows",
            self.rows
        );
        let at = row * self.k..(row + 1) * self.k;
        (&self.slots[at.clone()], &self.distances[at])
    }
    /// Every row's slots, row after row (`k` per row).
    pub fn slots(&self) -> &[usize] {
        &self.slots
    }
    /// Every row's squared distances, row after row (`k` per row).
    pub fn distances(&self) -> &[f64] {
        &self.distances
    }
}

/// A group of the querying tree: the positions of its points and their tight box.
pub(crate) type Group<const D: usize> = (Range<usize>, Aabb<f64, D>);

/// The groups of `index` (see the module doc), in traversal order.
pub(crate) fn groups<I: SpatialIndex<D>, const D: usize>(index: &I) -> Vec<Group<D>> {
    let mut out = Vec::new();
    let mut stack: Vec<Side<I::Node, D>> = index.root().into_iter().collect();
    let points = index.points();
    while let Some(side) = stack.pop() {
        let kids = children(index, &side, SCAN);
        if kids.is_empty() {
            let run = index.run(side.0);
            if let Some(first) = run.clone().next() {
                let mut b = Aabb {
                    min: points[first].map(Scalar::to_f64),
                    max: points[first].map(Scalar::to_f64),
                };
                for p in &points[run.clone()] {
                    for (axis, c) in p.iter().enumerate() {
                        let c = c.to_f64();
                        b.min[axis] = b.min[axis].min(c);
                        b.max[axis] = b.max[axis].max(c);
                    }
                }
                out.push((run, b));
            }
        } else {
            stack.extend(kids.into_iter().rev());
        }
    }
    out
}

/// The width of the table of `k` neighbours in a set of `len` points (`len - 1` others in a
/// self-join).
pub(crate) fn width(k: usize, len: usize, same: bool) -> usize {
    k.min(if same { len.saturating_sub(1) } else { len })
}

/// The `k` nearest points of `b` to every point of `group` of `a`, as (distance, position in `b`)
/// lists, `k` per point of the group, appended to `out`. `same`: `b` is `a`, and a point skips
/// its own position. `k` must not exceed what `b` holds (others, when `same`).
pub(crate) fn group_knn<A, B, P, const D: usize>(
    a: &A,
    b: &B,
    metric: &P,
    (run, gbox): &Group<D>,
    k: usize,
    same: bool,
    out: &mut Vec<(f64, usize)>,
) where
    A: SpatialIndex<D>,
    B: SpatialIndex<D>,
    P: PairDistance<D>,
{
    let Some(root) = b.root() else { return };
    if k == 0 {
        return;
    }
    let qs: Vec<[f64; D]> = a.points()[run.clone()]
        .iter()
        .map(|p| p.map(Scalar::to_f64))
        .collect();
    let base = out.len();
    out.resize(base + qs.len() * k, (f64::INFINITY, usize::MAX));
    let lists = &mut out[base..];
    let mut held = vec![0usize; qs.len()];
    let mut bounds = vec![f64::INFINITY; qs.len()];
    let mut group_bound = f64::INFINITY;
    let pb = b.points();
    let mut stack: Vec<(f64, B::Node, Aabb<f64, D>)> = Vec::new();
    stack.push((metric.box_box(gbox, &root.1).0, root.0, root.1));
    while let Some((lower, node, nb)) = stack.pop() {
        if lower > group_bound {
            continue;
        }
        let kids = children(b, &(node, nb), SCAN);
        if kids.is_empty() {
            let rb = b.run(node);
            for (qi, q) in qs.iter().enumerate() {
                if metric.point_box(q, &nb) > bounds[qi] {
                    continue;
                }
                let me = run.start + qi;
                let list = &mut lists[qi * k..(qi + 1) * k];
                for j in rb.clone() {
                    if same && j == me {
                        continue;
                    }
                    let d = metric.distance(q, &pb[j].map(Scalar::to_f64));
                    if d <= bounds[qi] && offer(list, &mut held[qi], d, j) {
                        bounds[qi] = list[k - 1].0;
                    }
                }
            }
            group_bound = bounds.iter().copied().fold(0.0, f64::max);
            continue;
        }
        // Farthest first, so that the nearest child is popped next.
        let before = stack.len();
        for (c, cb) in kids {
            let d = metric.box_box(gbox, &cb).0;
            if d > group_bound {
                continue;
            }
            let mut at = stack.len();
            stack.push((d, c, cb));
            while at > before && stack[at - 1].0 < d {
                stack.swap(at - 1, at);
                at -= 1;
            }
        }
    }
}

/// Offers `(d, j)` to the sorted `list`, of which `held` entries are filled; `true` when the list
/// is full afterwards (its last distance is then the point's bound).
#[inline(always)]
fn offer(list: &mut [(f64, usize)], held: &mut usize, d: f64, j: usize) -> bool {
    let k = list.len();
    if *held == k {
        let (wd, wj) = list[k - 1];
        if d > wd || (d == wd && j > wj) {
            return true;
        }
    } else {
        *held += 1;
    }
    let mut at = *held - 1;
    while at > 0 && (d, j) < list[at - 1] {
        list[at] = list[at - 1];
        at -= 1;
    }
    list[at] = (d, j);
    *held == k
}

/// Writes the lists of `group` (as [`group_knn`] leaves them, `k` per point) into `table`, in
/// the rows of the points' slots in `a`, as slots of `b`.
pub(crate) fn write_rows<A: PointSet<D>, B: PointSet<D>, const D: usize>(
    a: &A,
    b: &B,
    run: Range<usize>,
    lists: &[(f64, usize)],
    table: &mut KnnTable,
) {
    let k = table.k;
    let (qa, qb) = (a.index().payloads(), b.index().payloads());
    for (qi, i) in run.enumerate() {
        let row = a.slot_of(i, &qa[i]);
        for (t, &(d, j)) in lists[qi * k..(qi + 1) * k].iter().enumerate() {
            table.slots[row * k + t] = b.slot_of(j, &qb[j]);
            table.distances[row * k + t] = d;
        }
    }
}

/// An empty table of `rows` rows of `k` entries, to be filled by [`write_rows`].
pub(crate) fn table(rows: usize, k: usize) -> KnnTable {
    KnnTable {
        k,
        rows,
        slots: vec![0; rows * k],
        distances: vec![0.0; rows * k],
    }
}

/// The k-nearest join of `a` in `b` (`same`: the self-join of `a`, `b` being `a`), serially.
pub(crate) fn knn_join<A: PointSet<D>, B: PointSet<D>, P: PairDistance<D>, const D: usize>(
    a: &A,
    b: &B,
    metric: &P,
    k: usize,
    same: bool,
) -> KnnTable {
    let w = width(k, b.len(), same);
    let mut t = table(a.len(), w);
    if w == 0 {
        return t;
    }
    let mut lists = Vec::new();
    for g in groups(a.index()) {
        lists.clear();
        group_knn(a.index(), b.index(), metric, &g, w, same, &mut lists);
        write_rows(a, b, g.0, &lists, &mut t);
    }
    t
}
