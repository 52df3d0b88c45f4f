//! All k-nearest neighbours between two trees, and within one: a dual-tree traversal (Gray and
//! Moore, "N-body problems in statistical learning", 2001) whose query side is split down to
//! groups of nearby points, each group searching the other tree once for all its points.
//!
//! A group is a leaf of the query tree, or a node whose contiguous run is small enough to scan
//! (at most 32 points), with the tight box of its points; the search of one group is in
//! [`knn_group`](super::knn_group). Each point keeps its best `k` candidates sorted by
//! `(distance, position)`, so the answer is, for each point, exactly the first `k` of all
//! points of the other tree in that order: what [`PointSet::k_nearest`] answers, ties included.
//! In the self-join a point skips its own position; its duplicates are other points at
//! distance 0.
//!
//! The groups are independent, the unit of the parallel form: each writes its own rows of one
//! table laid out in group order ([`parts`]), which is the table itself when the rows of the
//! groups are the slots in order (a [`PointTree`](crate::PointTree)), and is otherwise put
//! into slot order at the end, in place
//! ([`to_slot_order`](super::knn_map::to_slot_order)).

use super::bounds::PairDistance;
use super::knn_group::Search;
use super::knn_map::{swap_rows, to_slot_order};
use super::slots::SlotView;
use super::traverse::{children, Side, SCAN};
use super::Join;
use crate::cpu::compiled_copy;
use crate::geom::{Aabb, Scalar};
use crate::huge_pages;
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

/// A group of the querying tree: the positions of its points (their tight box is computed by
/// [`fill`], on the thread that searches the group).
pub(crate) type Group = Range<usize>;

/// The groups of `index` (see the module doc), in traversal order.
pub(crate) fn groups<I: SpatialIndex<D>, const D: usize>(index: &I) -> Vec<Group> {
    let mut out = Vec::new();
    let mut stack: Vec<Side<I::Node, D>> = index.root().into_iter().collect();
    while let Some(side) = stack.pop() {
        let kids = children(index, &side, SCAN);
        if kids.is_empty() {
            let run = index.run(side.0);
            if !run.is_empty() {
                out.push(run);
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

/// One group's share of a join: the group and its rows of the table in group order (slots
/// of the other set and distances, `k` per point).
pub(crate) type Part<'t> = (&'t Group, &'t mut [usize], &'t mut [f64]);

/// The rows of a table of `k` per point cut into the parts of `groups`, in group order.
pub(crate) fn parts<'t>(
    groups: &'t [Group],
    k: usize,
    mut slots: &'t mut [usize],
    mut distances: &'t mut [f64],
) -> Vec<Part<'t>> {
    let mut out = Vec::with_capacity(groups.len());
    for g in groups {
        let n = g.len() * k;
        let (s, rest_s) = core::mem::take(&mut slots).split_at_mut(n);
        let (d, rest_d) = core::mem::take(&mut distances).split_at_mut(n);
        slots = rest_s;
        distances = rest_d;
        out.push((g, s, d));
    }
    out
}

/// Searches one part's group ([`Search::group`]) and writes its rows: the neighbours' slots in
/// `b` and their distances. `k` is at least 1. The work is [`fill_from`], which sees `a`'s
/// points, `b`'s index and `b`'s slots without the sets' types.
#[inline]
pub(crate) fn fill<A, B, P, const D: usize>(
    search: &mut Search<<B::Index as SpatialIndex<D>>::Node, D>,
    Join(a, b, metric, same, _): Join<'_, A, B, P, D>,
    part: Part<'_>,
    k: usize,
) where
    A: PointSet<D>,
    B: PointSet<D>,
    P: PairDistance<D>,
{
    fill_from(
        search,
        (a.index().points(), b.index(), SlotView::of(b), metric),
        part,
        k,
        same,
    );
}

/// The sides of a group's search: the query points, the index searched, its slots, the metric.
type Sides<'a, SA, I, P, const D: usize> = (&'a [[SA; D]], &'a I, SlotView<'a, D>, &'a P);

/// [`fill`]'s work, compiled once per point type, index and metric. Runs the copy compiled for
/// x86-64-v3 where the processor has it ([`cpu`](crate::cpu)): the same rows.
#[inline(never)]
fn fill_from<SA: Scalar, I: SpatialIndex<D>, P: PairDistance<D>, const D: usize>(
    search: &mut Search<I::Node, D>,
    sides: Sides<'_, SA, I, P, D>,
    part: Part<'_>,
    k: usize,
    same: bool,
) {
    #[cfg(target_arch = "x86_64")]
    if crate::cpu::has_v3() {
        // SAFETY: `fill_v3` is `fill_rows` compiled for the features `has_v3` has just found
        // on this processor.
        #[allow(unsafe_code)]
        unsafe {
            return fill_v3(search, sides, part, k, same);
        }
    }
    fill_rows(search, sides, part, k, same);
}

compiled_copy! {
    /// [`fill_rows`] compiled for x86-64-v3 (see [`cpu`](crate::cpu)).
    fill_v3 = fill_rows for "avx,avx2,bmi1,bmi2,lzcnt,popcnt",
    [SA: Scalar, I: SpatialIndex<D>, P: PairDistance<D>, const D: usize]
    (search: &mut Search<I::Node, D>, sides: Sides<'_, SA, I, P, D>, part: Part<'_>, k: usize,
     same: bool)
}

/// The work of [`fill_from`], compiled into each of its copies.
#[inline(always)]
fn fill_rows<SA: Scalar, I: SpatialIndex<D>, P: PairDistance<D>, const D: usize>(
    search: &mut Search<I::Node, D>,
    (pa, b, slots_b, metric): Sides<'_, SA, I, P, D>,
    (group, slots, distances): Part<'_>,
    k: usize,
    same: bool,
) {
    let gbox = Aabb::around(&pa[group.clone()]);
    search.group(pa, b, metric, (group.clone(), &gbox), k, same);
    let rows = slots.chunks_mut(k).zip(distances.chunks_mut(k));
    for (qi, (rs, rd)) in rows.enumerate() {
        for ((&(d, j), s), t) in search.list(qi, k).iter().zip(rs).zip(rd) {
            *s = slots_b.slot(j);
            *t = d;
        }
    }
}

/// Puts rows in the order of `groups` into slot order in `a` by `swap` ([`to_slot_order`]);
/// nothing to do when row `i` is slot `i` already (as in a [`PointTree`](crate::PointTree)).
pub(crate) fn in_slot_order<A: PointSet<D>, const D: usize>(
    a: &A,
    groups: &[Group],
    swap: impl FnMut(usize, usize),
) {
    let qa = a.index().payloads();
    let order = || {
        groups
            .iter()
            .flat_map(|g| g.clone())
            .map(|i| a.slot_of(i, &qa[i]))
    };
    // Checked before anything is allocated: the identity is the common case.
    if !order().enumerate().all(|(r, s)| r == s) {
        to_slot_order(&mut order().collect::<Vec<_>>(), swap);
    }
}

impl<A: PointSet<D>, B: PointSet<D>, P: PairDistance<D>, const D: usize> Join<'_, A, B, P, D> {
    /// The k-nearest table, serially.
    pub(crate) fn knn(self, k: usize) -> KnnTable {
        self.table(k, |parts, w| self.fill_parts(parts, w))
    }

    /// Fills `parts` (`w` neighbours per point, at least 1) one after the other with one group
    /// searcher: the serial table's work, and that of each run of the parallel one.
    pub(crate) fn fill_parts(self, parts: Vec<Part<'_>>, w: usize) {
        let mut search = Search::new();
        for part in parts {
            fill(&mut search, self, part, w);
        }
    }

    /// The table of the `k` nearest: its rows cut into the parts of the querying set's groups
    /// ([`parts`]), filled by `fill_parts(parts, width)` (`width` at least 1), then put into
    /// slot order.
    pub(crate) fn table(self, k: usize, fill_parts: impl FnOnce(Vec<Part<'_>>, usize)) -> KnnTable {
        let Join(a, b, _, same, _) = self;
        let (rows, w) = (a.len(), width(k, b.len(), same));
        let (mut slots, mut distances) = (huge_pages::zeros(rows * w), huge_pages::zeros(rows * w));
        if w > 0 {
            let gs = groups(a.index());
            fill_parts(parts(&gs, w, &mut slots, &mut distances), w);
            in_slot_order(a, &gs, |x, y| {
                swap_rows(&mut slots, x, y, w);
                swap_rows(&mut distances, x, y, w);
            });
        }
        KnnTable {
            k: w,
            rows,
            slots,
            distances,
        }
    }
}

/// Checks that every part's rows through [`fill`] (the copy the processor runs) and through
/// the baseline copy are the same slots and the same distances, bit for bit: the test of the
/// dispatch, called by the point trees' tests (which may name the trees; this layer may not).
#[cfg(test)]
pub(crate) fn assert_copies_agree<P: PointSet<D>, const D: usize>(set: &P, k: usize) {
    use super::bounds::Euclid;
    let gs = groups(set.index());
    let n = set.len() * k;
    let (mut s1, mut d1) = (vec![0; n], vec![0.0; n]);
    let (mut s2, mut d2) = (vec![0; n], vec![0.0; n]);
    let (mut search1, mut search2) = (Search::new(), Search::new());
    for (p1, p2) in parts(&gs, k, &mut s1, &mut d1)
        .into_iter()
        .zip(parts(&gs, k, &mut s2, &mut d2))
    {
        fill(&mut search1, Join::new(set, set, &Euclid, true), p1, k);
        let sides = (
            set.index().points(),
            set.index(),
            SlotView::of(set),
            &Euclid,
        );
        fill_rows(&mut search2, sides, p2, k, true);
    }
    assert_eq!(s1, s2);
    assert!(d1.iter().zip(&d2).all(|(x, y)| x.to_bits() == y.to_bits()));
}
