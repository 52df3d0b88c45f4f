//! The leaf-against-leaf kernel of the radius joins: every pair of points of two runs within a
//! squared radius, the brute-force base case of the dual-tree traversal (Gray and Moore,
//! "N-body problems in statistical learning", NIPS 2001), made cheap in three ways.
//!
//! - Filter by boxes: two runs whose tight boxes (kept per run in a small cache, as a run meets
//!   its neighbours at nearby times of the traversal) are farther apart than the radius have no
//!   pair and cost two look-ups; otherwise a point of one run farther than the radius from the
//!   other's tight box has no pair there, so only the points of run `b` within the radius of
//!   `a`'s box are gathered, and only the points of run `a` within the radius of the gathered
//!   points' tight box are tested. Between two neighbouring cells this leaves the strips along
//!   their shared faces. The filters run without branches on their answers.
//! - Columns: the gathered points of `b` (up to [`BLOCK`] at a time) are held one array per
//!   axis, so that one point's distances to the whole block are a short loop of arithmetic
//!   without branches, eight at a time, whose answers are compared with one bound (the
//!   boundary folded into it, [`Boundary::limit`]) and packed into a bit mask.
//! - Only the mask's set bits reach the caller, with the distance already computed.
//!
//! A run paired with itself is gathered whole (every point lies in its own box) and each point
//! is tested against the later positions only, so each unordered pair is met once.
//!
//! Exactness: every distance is [`PairDistance::distance`] of the two points as `f64`, the one
//! the rest of the query layer computes; the filters use [`PairDistance::point_box`], a lower
//! bound of that distance over a closed box holding the points (see [`bounds`](super::bounds)),
//! so a point filtered out has no pair within the radius there, at the boundary too.

use super::bounds::PairDistance;
use super::radius::Boundary;
use crate::cpu::{compiled_copy, Avx, Compare, Level, Portable};
use crate::geom::{Aabb, Scalar};
use core::ops::{ControlFlow, Range};

/// The points of `b` gathered and tested at a time: the width of the bit mask.
pub(crate) const BLOCK: usize = 64;

/// The gathered points of one side, in columns, with their positions and the distances of the
/// last point tested against them: the kernel's scratch, allocated once per traversal.
pub(crate) struct Block<const D: usize> {
    cols: [[f64; BLOCK]; D],
    at: [usize; BLOCK],
    /// Per row of the last [`scan_rows`] call, the distances from its point to the block's
    /// points (row 0 for the counts).
    dist: [[f64; BLOCK]; ROWS],
    /// The rows of the last [`scan_rows`] call that have a pair: the position of the point of
    /// run `a`, and the mask of its pairs among the block's points.
    hits: [(usize, u64); ROWS],
    /// How many of `hits` the last [`scan_rows`] call filled.
    filled: usize,
    len: usize,
    /// The tight boxes of the runs met on either side of the leaf pairs.
    tight: [TightBoxes<D>; 2],
    /// The copy of the kernels this processor runs, found once per block.
    level: Level,
}

/// The most runs whose tight boxes are kept per side.
const SLOTS: usize = 1 << SLOTS_LOG2;

/// The hash bits that pick one of [`SLOTS`].
const SLOTS_LOG2: u32 = 10;

/// The tight boxes of recently scanned runs, each in the slot its first position hashes to
/// (the last one there wins): a run meets its neighbours at nearby times of the depth-first
/// traversal, so its box is mostly found instead of computed again.
///
/// Sized for the points the traversal will meet on that side (a slot per 16 points, a power of
/// two from 2 to [`SLOTS`]): a join of a few leaves, or each of the many small parts of a
/// parallel join, clears a few slots instead of 1024 (64 KiB in 3-D) for every part.
struct TightBoxes<const D: usize> {
    /// The run in each slot; a power of two of them.
    runs: Vec<Range<usize>>,
    /// Its tight box.
    boxes: Vec<Aabb<f64, D>>,
}

impl<const D: usize> TightBoxes<D> {
    /// Empty slots for a side of `points` points.
    fn new(points: usize) -> Self {
        let slots = points.div_ceil(16).next_power_of_two().clamp(2, SLOTS);
        TightBoxes {
            runs: vec![0..0; slots],
            boxes: vec![Aabb::empty(); slots],
        }
    }

    /// The tight box of the points of `points[run]` as `f64` (`run` not empty).
    #[inline(always)]
    fn get<S: Scalar>(&mut self, points: &[[S; D]], run: Range<usize>) -> Aabb<f64, D> {
        // Fibonacci hashing of the first position: its top bits, as many as the slots need
        // (an empty slot holds `0..0`, which no run equals).
        let hash = (run.start as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) >> (64 - SLOTS_LOG2);
        let slot = hash as usize & (self.runs.len() - 1);
        if self.runs[slot] != run {
            self.boxes[slot] = Aabb::around(&points[run.clone()]);
            self.runs[slot] = run;
        }
        self.boxes[slot]
    }
}

impl<const D: usize> Block<D> {
    /// An empty block on the heap (a few kilobytes: kept out of the traversal's frames), for a
    /// traversal meeting `points[0]` points of its first set and `points[1]` of its second.
    pub(crate) fn boxed(points: [usize; 2]) -> Box<Self> {
        Box::new(Block {
            cols: [[0.0; BLOCK]; D],
            at: [0; BLOCK],
            dist: [[0.0; BLOCK]; ROWS],
            hits: [(0, 0); ROWS],
            filled: 0,
            len: 0,
            tight: [TightBoxes::new(points[0]), TightBoxes::new(points[1])],
            level: Level::detected(),
        })
    }

    /// The distances from `q` to the points `from..` of the block (kept in row `row` of
    /// `dist`), and the mask of those within `bound` (bit `j` for point `j` when its distance
    /// is `<= bound`).
    ///
    /// The points are taken eight at a time, from the group of eight holding `from` to the one
    /// holding the last point, in a loop of fixed length the compiler turns into vector
    /// arithmetic; the eight answers become a byte of the mask by `compare` (the copy's own
    /// way). Lanes outside `from..len` hold stale coordinates: their bits are cleared at the end.
    #[inline(always)]
    pub(crate) fn mask<P: PairDistance<D>, C: Compare>(
        &mut self,
        row: usize,
        from: usize,
        q: &[f64; D],
        metric: &P,
        bound: f64,
        compare: C,
    ) -> u64 {
        let mut m = 0u64;
        for g in from / LANES..self.len.div_ceil(LANES) {
            let base = g * LANES;
            let lanes: &mut [f64; LANES] = (&mut self.dist[row][base..base + LANES])
                .try_into()
                .expect("a lane group lies inside the block");
            for (l, d) in lanes.iter_mut().enumerate() {
                let p: [f64; D] = core::array::from_fn(|k| self.cols[k][base + l]);
                *d = metric.distance(q, &p);
            }
            m |= compare.le_bits(lanes, bound) << base;
        }
        m & span(from, self.len)
    }
}

/// The points of a block tested together: one byte of the mask.
const LANES: usize = 8;

/// The mask of bits `from..len` (`len <= 64`).
#[inline(always)]
fn span(from: usize, len: usize) -> u64 {
    let below_len = if len >= 64 { !0 } else { (1u64 << len) - 1 };
    let from_on = if from >= 64 { 0 } else { !0u64 << from };
    below_len & from_on
}

impl<const D: usize> Block<D> {
    /// For two different runs, the tight box of run `a` when the tight boxes of the two runs
    /// are within `limit` of each other, `None` when no pair of theirs can be (for a run paired
    /// with itself, an empty box, unused). Out of line: called once per pair of runs, and
    /// compiled once per kind of points and distance rather than into every visitor's loop.
    #[allow(clippy::too_many_arguments)]
    fn near_runs<SA: Scalar, SB: Scalar, P: PairDistance<D>>(
        &mut self,
        pa: &[[SA; D]],
        ra: Range<usize>,
        pb: &[[SB; D]],
        rb: Range<usize>,
        same: bool,
        metric: &P,
        limit: f64,
    ) -> Option<Aabb<f64, D>> {
        let admits = |d: f64| d <= limit;
        if same {
            return Some(Aabb::empty());
        }
        if ra.is_empty() || rb.is_empty() {
            return None;
        }
        let box_a = self.tight[0].get(pa, ra);
        let box_b = self.tight[1].get(pb, rb);
        admits(metric.box_box(&box_a, &box_b).0).then_some(box_a)
    }
}

/// The point at position `i` of `points` as `f64`.
#[inline(always)]
fn point<S: Scalar, const D: usize>(points: &[[S; D]], i: usize) -> [f64; D] {
    points[i].map(Scalar::to_f64)
}

/// One side of a leaf pair: the index's points, the run's positions, the node's closed box.
pub(crate) type Run<'a, S, const D: usize> = (&'a [[S; D]], Range<usize>, &'a Aabb<f64, D>);

/// Calls `each(i, j, d)` for every pair of positions `i` of run `a` and `j` of run `b` whose
/// distance `d` is within `r2` (under `boundary`); with `same` (one run paired with itself),
/// for every `i < j` of it, in the order of `b`'s blocks, then of `i`, then of `j`. Stops at
/// the first [`ControlFlow::Break`].
///
/// Only this loop is compiled once per visitor: the work on the points ([`Cursor::fill`]:
/// [`gather_kept`] and [`scan_rows`]) is compiled once per kind of points and distance and
/// hands over up to [`ROWS`] rows of pairs at a time (their masks and distances, in the
/// block). Each runs the copy compiled for x86-64-v4 (AVX-512) or v3 (AVX2) where the
/// processor has it ([`cpu`](crate::cpu)): the same pairs and distances.
#[allow(clippy::too_many_arguments)]
#[inline]
pub(crate) fn scan_pairs<SA: Scalar, SB: Scalar, P: PairDistance<D>, Br, const D: usize>(
    block: &mut Block<D>,
    (pa, ra, _): Run<'_, SA, D>,
    (pb, rb, _): Run<'_, SB, D>,
    same: bool,
    metric: &P,
    r2: f64,
    boundary: Boundary,
    mut each: impl FnMut(usize, usize, f64) -> ControlFlow<Br>,
) -> ControlFlow<Br> {
    let limit = boundary.limit(r2);
    let Some(box_a) = block.near_runs(pa, ra.clone(), pb, rb.clone(), same, metric, limit) else {
        return ControlFlow::Continue(());
    };
    let mut at = Cursor {
        next: rb.start,
        rows: ra.clone(),
        tight: None,
        box_a,
    };
    while at.fill(block, (pa, ra.clone()), (pb, rb.end), (same, metric, limit)) {
        for row in 0..block.filled {
            let (i, m) = block.hits[row];
            report(block, row, i, m, &mut each)?;
        }
    }
    ControlFlow::Continue(())
}

/// Where [`scan_pairs`] is: the next position of run `b` to gather, the rows of run `a` left
/// against the block gathered (with its tight box, `None` before the first block).
struct Cursor<const D: usize> {
    next: usize,
    rows: Range<usize>,
    tight: Option<Aabb<f64, D>>,
    box_a: Aabb<f64, D>,
}

impl<const D: usize> Cursor<D> {
    /// Fills the block's next rows of pairs ([`scan_rows`], after [`gather_kept`] of the next
    /// block of `b` when the rows against this one are done); `false` at the end. Out of line
    /// and not generic over the visitor: compiled once per kind of points and distance, with
    /// one call per [`ROWS`] rows.
    #[inline(never)]
    fn fill<SA: Scalar, SB: Scalar, P: PairDistance<D>>(
        &mut self,
        block: &mut Block<D>,
        (pa, ra): (&[[SA; D]], Range<usize>),
        (pb, b_end): (&[[SB; D]], usize),
        test: Test<'_, P>,
    ) -> bool {
        loop {
            if let Some(tight) = &self.tight
                && !self.rows.is_empty()
            {
                self.rows.start = scan_rows_any(block, pa, self.rows.clone(), test, tight);
                return true;
            }
            if self.next >= b_end {
                return false;
            }
            self.tight = gather_any(block, pb, &mut self.next, b_end, test, &self.box_a);
            if self.tight.is_some() {
                // With `same`, the block is the contiguous positions `first..`: point `i` pairs
                // with the later ones, so the rows end at the block's last point.
                let end = if test.0 {
                    block.at[block.len - 1]
                } else {
                    ra.end
                };
                self.rows = ra.start..end;
            }
        }
    }
}

/// What [`gather_kept`] and [`scan_rows`] test: whether run `a` is paired with itself, the
/// distance, and the bound a distance must not exceed ([`Boundary::limit`]).
type Test<'m, P> = (bool, &'m P, f64);

/// [`gather_kept`] by the copy this processor runs.
#[inline(always)]
fn gather_any<SB: Scalar, P: PairDistance<D>, const D: usize>(
    block: &mut Block<D>,
    pb: &[[SB; D]],
    next: &mut usize,
    end: usize,
    test: Test<'_, P>,
    box_a: &Aabb<f64, D>,
) -> Option<Aabb<f64, D>> {
    #[cfg(target_arch = "x86_64")]
    if let Some(avx) = block.level.avx() {
        // SAFETY: `gather_v4` and `gather_v3` are `gather_kept` compiled for the features of
        // the v4 and v3 levels; a `Level` has a token only where `has_v3` found the v3
        // features, and says `v4` only where `has_v4` found those of v4.
        #[allow(unsafe_code)]
        unsafe {
            return if block.level.v4() {
                gather_v4(avx, block, pb, next, end, test, box_a)
            } else {
                gather_v3(avx, block, pb, next, end, test, box_a)
            };
        }
    }
    gather_kept(Portable, block, pb, next, end, test, box_a)
}

compiled_copy! {
    /// [`gather_kept`] compiled for x86-64-v3 (see [`cpu`](crate::cpu)).
    gather_v3 = gather_kept for "avx,avx2,bmi1,bmi2,lzcnt,popcnt",
    [SB: Scalar, P: PairDistance<D>, const D: usize]
    (compare: Avx, block: &mut Block<D>, pb: &[[SB; D]], next: &mut usize, end: usize,
     test: Test<'_, P>, box_a: &Aabb<f64, D>) -> Option<Aabb<f64, D>>
}

compiled_copy! {
    /// [`gather_kept`] compiled for x86-64-v4 (see [`cpu`](crate::cpu)).
    gather_v4 = gather_kept
        for "avx,avx2,bmi1,bmi2,lzcnt,popcnt,avx512f,avx512vl,avx512bw,avx512dq",
    [SB: Scalar, P: PairDistance<D>, const D: usize]
    (compare: Avx, block: &mut Block<D>, pb: &[[SB; D]], next: &mut usize, end: usize,
     test: Test<'_, P>, box_a: &Aabb<f64, D>) -> Option<Aabb<f64, D>>
}

/// The next block of run `b`'s points (from `*next`) within the bound of `box_a`, the tight box
/// of run `a` (every point when `same`): [`gather`] with that test, compiled into each copy.
#[inline(always)]
fn gather_kept<SB: Scalar, P: PairDistance<D>, C: Compare, const D: usize>(
    _: C,
    block: &mut Block<D>,
    pb: &[[SB; D]],
    next: &mut usize,
    end: usize,
    (same, metric, limit): Test<'_, P>,
    box_a: &Aabb<f64, D>,
) -> Option<Aabb<f64, D>> {
    gather(block, pb, next, end, |p| {
        same || metric.point_box(p, box_a) <= limit
    })
}

/// [`scan_rows`] by the copy this processor runs.
#[inline(always)]
fn scan_rows_any<SA: Scalar, P: PairDistance<D>, const D: usize>(
    block: &mut Block<D>,
    pa: &[[SA; D]],
    rows: Range<usize>,
    test: Test<'_, P>,
    tight: &Aabb<f64, D>,
) -> usize {
    #[cfg(target_arch = "x86_64")]
    if let Some(avx) = block.level.avx() {
        // SAFETY: as in `gather_any`, for `scan_rows`' copies.
        #[allow(unsafe_code)]
        unsafe {
            return if block.level.v4() {
                scan_rows_v4(avx, block, pa, rows, test, tight)
            } else {
                scan_rows_v3(avx, block, pa, rows, test, tight)
            };
        }
    }
    scan_rows(Portable, block, pa, rows, test, tight)
}

compiled_copy! {
    /// [`scan_rows`] compiled for x86-64-v3 (see [`cpu`](crate::cpu)).
    scan_rows_v3 = scan_rows for "avx,avx2,bmi1,bmi2,lzcnt,popcnt",
    [SA: Scalar, P: PairDistance<D>, const D: usize]
    (compare: Avx, block: &mut Block<D>, pa: &[[SA; D]], rows: Range<usize>, test: Test<'_, P>,
     tight: &Aabb<f64, D>) -> usize
}

compiled_copy! {
    /// [`scan_rows`] compiled for x86-64-v4 (see [`cpu`](crate::cpu)).
    scan_rows_v4 = scan_rows
        for "avx,avx2,bmi1,bmi2,lzcnt,popcnt,avx512f,avx512vl,avx512bw,avx512dq",
    [SA: Scalar, P: PairDistance<D>, const D: usize]
    (compare: Avx, block: &mut Block<D>, pa: &[[SA; D]], rows: Range<usize>, test: Test<'_, P>,
     tight: &Aabb<f64, D>) -> usize
}

/// Rows of run `a` tested against the gathered block from `rows.start` on, until [`ROWS`] of
/// them have a pair (kept in `hits` with their masks, their distances in `dist`, `filled`
/// of them) or `rows` ends; returns the position to go on from. A point farther than the
/// bound from the block's tight box `tight` is passed over; with `same` (the block is run `a`
/// itself, from its position `first`), point `i` is tested against the positions after it.
#[inline(always)]
fn scan_rows<SA: Scalar, P: PairDistance<D>, C: Compare, const D: usize>(
    compare: C,
    block: &mut Block<D>,
    pa: &[[SA; D]],
    rows: Range<usize>,
    (same, metric, limit): Test<'_, P>,
    tight: &Aabb<f64, D>,
) -> usize {
    block.filled = 0;
    let first = block.at[0];
    let admits = |d: f64| d <= limit;
    for i in rows.clone() {
        let q = point(pa, i);
        if !same && !admits(metric.point_box(&q, tight)) {
            continue;
        }
        let from = if same {
            (i + 1).saturating_sub(first)
        } else {
            0
        };
        let row = block.filled;
        let m = block.mask(row, from, &q, metric, limit, compare);
        block.hits[row] = (i, m);
        // Without a branch on the mask: the row is kept by moving on from it.
        block.filled = row + usize::from(m != 0);
        if block.filled == ROWS {
            return i + 1;
        }
    }
    rows.end
}

/// The rows a [`scan_rows`] call hands over at most: `ROWS x BLOCK` distances, 8 KiB.
const ROWS: usize = 16;

/// Fills `block` with the next points of `points[*next..end]` that `keep` takes (up to
/// [`BLOCK`]), moving `next` past those looked at; their tight box, or `None` when none was
/// kept.
#[inline(always)]
fn gather<S: Scalar, const D: usize>(
    block: &mut Block<D>,
    points: &[[S; D]],
    next: &mut usize,
    end: usize,
    keep: impl Fn(&[f64; D]) -> bool,
) -> Option<Aabb<f64, D>> {
    block.len = 0;
    let mut tight = Aabb::<f64, D>::empty();
    let stop = end.min(*next + BLOCK);
    // Without branches on `keep`: each point is written at the next free place, which moves on
    // only when it is kept; the tight box grows only by kept points.
    for at in *next..stop {
        let p = point(points, at);
        let j = block.len;
        for (col, &c) in block.cols.iter_mut().zip(&p) {
            col[j] = c;
        }
        block.at[j] = at;
        let k = keep(&p);
        // Plain comparisons (the coordinates are not NaN): one instruction each.
        for ((lo, hi), &x) in tight.min.iter_mut().zip(&mut tight.max).zip(&p) {
            *lo = if k && x < *lo { x } else { *lo };
            *hi = if k && x > *hi { x } else { *hi };
        }
        block.len = j + usize::from(k);
        if block.len == BLOCK {
            *next = at + 1;
            return Some(tight);
        }
    }
    *next = stop;
    (block.len > 0).then_some(tight)
}

/// The counts of [`scan_pairs`] over sorted squared radii `r2`, of which `lo..hi` are undecided
/// for this pair of runs (radii below `lo` take in none of its pairs; those from `hi` on were
/// given all of them already), added to the differences `diff` (see
/// [`CountWithin`](super::pairs::CountWithin)).
///
/// Each point first bounds its distances to the whole block by the block's tight box: the radii
/// beyond the far bound take in all its pairs with the block at once (one update of `diff`),
/// the radii below the near bound none, and only the radii in between are found pair by pair,
/// by a binary search among them.
///
/// Runs the copy compiled for x86-64-v4 (AVX-512) or v3 (AVX2) where the processor has it
/// ([`cpu`](crate::cpu)): the same counts.
#[allow(clippy::too_many_arguments)]
#[inline]
pub(crate) fn scan_counts<SA: Scalar, SB: Scalar, P: PairDistance<D>, const D: usize>(
    block: &mut Block<D>,
    a: Run<'_, SA, D>,
    b: Run<'_, SB, D>,
    same: bool,
    metric: &P,
    radii: (&[f64], usize, usize),
    boundary: Boundary,
    diff: &mut [i128],
) {
    #[cfg(target_arch = "x86_64")]
    if let Some(avx) = block.level.avx() {
        // SAFETY: as in `gather_any`, for `counts_in`'s copies.
        #[allow(unsafe_code)]
        unsafe {
            return if block.level.v4() {
                scan_counts_v4(avx, block, a, b, same, metric, radii, boundary, diff)
            } else {
                scan_counts_v3(avx, block, a, b, same, metric, radii, boundary, diff)
            };
        }
    }
    counts_in(Portable, block, a, b, same, metric, radii, boundary, diff);
}

compiled_copy! {
    /// [`counts_in`] compiled for x86-64-v3 (see [`cpu`](crate::cpu)).
    scan_counts_v3 = counts_in for "avx,avx2,bmi1,bmi2,lzcnt,popcnt",
    [SA: Scalar, SB: Scalar, P: PairDistance<D>, const D: usize]
    (compare: Avx, block: &mut Block<D>, a: Run<'_, SA, D>, b: Run<'_, SB, D>, same: bool, metric: &P,
     radii: (&[f64], usize, usize), boundary: Boundary, diff: &mut [i128])
}

compiled_copy! {
    /// [`counts_in`] compiled for x86-64-v4 (see [`cpu`](crate::cpu)).
    scan_counts_v4 = counts_in
        for "avx,avx2,bmi1,bmi2,lzcnt,popcnt,avx512f,avx512vl,avx512bw,avx512dq",
    [SA: Scalar, SB: Scalar, P: PairDistance<D>, const D: usize]
    (compare: Avx, block: &mut Block<D>, a: Run<'_, SA, D>, b: Run<'_, SB, D>, same: bool, metric: &P,
     radii: (&[f64], usize, usize), boundary: Boundary, diff: &mut [i128])
}

/// The work of [`scan_counts`], compiled into each of its copies.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn counts_in<SA: Scalar, SB: Scalar, P: PairDistance<D>, C: Compare, const D: usize>(
    compare: C,
    block: &mut Block<D>,
    (pa, ra, _): Run<'_, SA, D>,
    (pb, rb, _): Run<'_, SB, D>,
    same: bool,
    metric: &P,
    (r2, lo, hi): (&[f64], usize, usize),
    boundary: Boundary,
    diff: &mut [i128],
) {
    // The first radius of `range` that takes in distance `d` (the end if none).
    let first = |range: Range<usize>, d: f64| {
        range.start + r2[range].partition_point(|&r| !boundary.admits(d, r))
    };
    if ra.is_empty() || rb.is_empty() {
        return;
    }
    // Two runs (or a run with itself) whose farthest points are within the first radius: all
    // their pairs are counted at once, for every radius. Copies of one point at the maximum
    // depth, kept in one leaf, would otherwise be counted pair by pair (or a block at a time):
    // O(n^2 / 64) for n copies.
    let box_a = block.tight[0].get(pa, ra.clone());
    let box_b = if same {
        box_a
    } else {
        block.tight[1].get(pb, rb.clone())
    };
    let (closest, farthest) = metric.box_box(&box_a, &box_b);
    if boundary.admits(farthest, r2[lo]) {
        let (na, nb) = (ra.len() as i128, rb.len() as i128);
        let n = if same { na * (na - 1) / 2 } else { na * nb };
        diff[lo] += n;
        diff[hi] -= n;
        return;
    }
    let last = r2[hi - 1];
    let last_limit = boundary.limit(last);
    let admits = |d: f64| d <= last_limit;
    // Two different runs too far apart for the last radius have no pair (`near_runs`' test,
    // on the boxes at hand).
    if !same && !admits(closest) {
        return;
    }
    let mut next = rb.start;
    while next < rb.end {
        let Some(tight) = gather(block, pb, &mut next, rb.end, |p| {
            same || admits(metric.point_box(p, &box_a))
        }) else {
            continue;
        };
        let (first_at, last_at) = (block.at[0], block.at[block.len - 1]);
        let upto = if same { last_at } else { ra.end };
        for i in ra.start..upto {
            let q = point(pa, i);
            let from = if same {
                (i + 1).saturating_sub(first_at)
            } else {
                0
            };
            let (near, far) = metric.box_box(&Aabb { min: q, max: q }, &tight);
            let l = first(lo..hi, near);
            if l == hi {
                continue;
            }
            let all = first(l..hi, far);
            if all < hi {
                let n = (block.len - from) as i128;
                diff[all] += n;
                diff[hi] -= n;
            }
            if l == all {
                continue;
            }
            let edge = boundary.limit(r2[all - 1]);
            let mut m = block.mask(0, from, &q, metric, edge, compare);
            let found = i128::from(m.count_ones());
            while m != 0 {
                let j = m.trailing_zeros() as usize;
                m &= m - 1;
                diff[first(l..all, block.dist[0][j])] += 1;
            }
            diff[all] -= found;
        }
    }
}

/// Hands the pairs of point `i` with the block's points of mask `m` (the distances of row `row`)
/// to `each`.
#[inline(always)]
fn report<Br, const D: usize>(
    block: &Block<D>,
    row: usize,
    i: usize,
    mut m: u64,
    each: &mut impl FnMut(usize, usize, f64) -> ControlFlow<Br>,
) -> ControlFlow<Br> {
    while m != 0 {
        let j = m.trailing_zeros() as usize;
        m &= m - 1;
        each(i, block.at[j], block.dist[row][j])?;
    }
    ControlFlow::Continue(())
}

#[cfg(test)]
mod tests {
    use super::{scan_counts, scan_pairs, Block, Run, ROWS};
    use crate::cpu::Level;
    use crate::geom::Aabb;
    use crate::query::join::bounds::Euclid;
    use crate::query::join::radius::Boundary;
    use core::ops::ControlFlow;
    use rand::{rngs::SmallRng, Rng, SeedableRng};

    /// Every pair of `a` and `b` within `r2` by the copy of `level`, with its distance's bits.
    fn pairs_by(
        level: Level,
        (a, b, same): (Run<'_, f64, 3>, Run<'_, f64, 3>, bool),
        r2: f64,
        boundary: Boundary,
    ) -> Vec<(usize, usize, u64)> {
        let mut out = Vec::new();
        let each = |i: usize, j: usize, d: f64| {
            out.push((i, j, d.to_bits()));
            ControlFlow::<()>::Continue(())
        };
        let mut block = Block::<3>::boxed([0, 0]); // two slots a side: evictions all along
        block.level = level;
        let _ = scan_pairs(&mut block, a, b, same, &Euclid, r2, boundary, each);
        out
    }

    /// The count differences of `a` and `b` over the squared radii `r2` by the copy of `level`.
    fn counts_by(
        level: Level,
        (a, b, same): (Run<'_, f64, 3>, Run<'_, f64, 3>, bool),
        r2: &[f64],
        boundary: Boundary,
    ) -> Vec<i128> {
        let mut diff = vec![0i128; r2.len() + 1];
        let radii = (r2, 0, r2.len());
        let mut block = Block::<3>::boxed([0, 0]); // two slots a side: evictions all along
        block.level = level;
        scan_counts(&mut block, a, b, same, &Euclid, radii, boundary, &mut diff);
        diff
    }

    /// A visitor that breaks at the `k`-th pair stops there, with that pair, for every copy:
    /// the kernel hands over rows in chunks, and a break in the middle of one is the last call.
    /// Runs of 150 and 300 points (many chunks of rows), with and without pairs everywhere.
    #[test]
    fn a_break_stops_at_its_pair_in_the_middle_of_a_chunk() {
        let mut rng = SmallRng::seed_from_u64(9);
        let pts: Vec<[f64; 3]> = (0..300)
            .map(|_| core::array::from_fn(|_| rng.gen_range(0.0..0.2)))
            .collect();
        let whole = Aabb::around(&pts);
        let mut levels = Level::fast_available();
        levels.push(Level::BASELINE);
        for (ra, rb) in [(0..300, 0..300), (0..150, 150..300)] {
            let same = ra == rb;
            let runs = || {
                (
                    (&pts[..], ra.clone(), &whole),
                    (&pts[..], rb.clone(), &whole),
                    same,
                )
            };
            for r2 in [1.0, 0.01] {
                let all = pairs_by(Level::BASELINE, runs(), r2, Boundary::Inclusive);
                assert!(
                    all.len() > 100 * ROWS,
                    "pairs over many chunks: {}",
                    all.len()
                );
                for level in levels.clone() {
                    for k in [1, ROWS + 3, all.len() / 2 + 1, all.len()] {
                        let mut calls = 0;
                        let mut block = Block::<3>::boxed([0, 0]);
                        block.level = level;
                        let (a, b, same) = runs();
                        let flow = scan_pairs(
                            &mut block,
                            a,
                            b,
                            same,
                            &Euclid,
                            r2,
                            Boundary::Inclusive,
                            |i, j, d| {
                                calls += 1;
                                if calls == k {
                                    ControlFlow::Break((i, j, d.to_bits()))
                                } else {
                                    ControlFlow::Continue(())
                                }
                            },
                        );
                        assert_eq!(flow, ControlFlow::Break(all[k - 1]), "{level:?} {k}");
                        assert_eq!(calls, k, "{level:?}");
                    }
                }
            }
        }
    }

    /// Runs whose farthest points lie within the first radius (copies of one point, a tight
    /// cluster) are counted whole, with one bound: n copies used to cost n^2 / 128 bounds.
    #[test]
    fn runs_within_the_first_radius_are_counted_whole() {
        use crate::query::join::bounds::Counting;
        let mut pts = vec![[0.5, 0.25, -1.0]; 3000];
        pts.extend((0..1000).map(|i| [0.5 + f64::from(i) * 1e-6, 0.25, -1.0]));
        let whole = Aabb::around(&pts);
        let metric = Counting::default();
        let r2 = [0.0, 1e-6, 1.0];
        for (ra, rb, inclusive, exclusive) in [
            // copies alone: within 0 only when 0 is admitted
            (0..3000, 0..3000, [4_498_500; 3], [0, 4_498_500, 4_498_500]),
            (
                0..1000,
                1000..3000,
                [2_000_000; 3],
                [0, 2_000_000, 2_000_000],
            ),
            // copies and the cluster, 1e-3 wide, whose first point is a copy
            (
                0..3000,
                3000..4000,
                [3_000, 3_000_000, 3_000_000],
                [0, 3_000_000, 3_000_000],
            ),
        ] {
            for (boundary, want) in [
                (Boundary::Inclusive, inclusive),
                (Boundary::Exclusive, exclusive),
            ] {
                let mut diff = vec![0i128; 4];
                let mut block = Block::<3>::boxed([0, 0]);
                metric.reset();
                let same = ra == rb;
                let runs = (
                    (&pts[..], ra.clone(), &whole),
                    (&pts[..], rb.clone(), &whole),
                );
                let radii = (&r2[..], 0, 3);
                scan_counts(
                    &mut block, runs.0, runs.1, same, &metric, radii, boundary, &mut diff,
                );
                let counts: Vec<i128> = diff
                    .iter()
                    .scan(0, |sum, d| {
                        *sum += d;
                        Some(*sum)
                    })
                    .take(3)
                    .collect();
                assert_eq!(counts, want, "{ra:?} {rb:?} {boundary:?}");
                // copies alone, within the first radius when it admits 0: one bound of the
                // two runs, no point visited
                if ra.end <= 3000 && rb.end <= 3000 && boundary == Boundary::Inclusive {
                    let work = (metric.distances(), metric.box_bounds());
                    assert_eq!(work, (0, 1), "{ra:?} {rb:?} {boundary:?}");
                }
            }
        }
    }

    /// Runs of random and grid points (ties, duplicates), paired with themselves and with each
    /// other: every copy the processor can run finds the pairs and counts of the baseline copy,
    /// with the same distances bit for bit.
    #[test]
    fn the_fast_copies_find_the_baseline_pairs() {
        let mut rng = SmallRng::seed_from_u64(5);
        let pts: Vec<[f64; 3]> = (0..400)
            .map(|i| {
                if i % 3 == 0 {
                    core::array::from_fn(|_| f64::from(rng.gen_range(0u8..=4)) / 8.0)
                } else {
                    core::array::from_fn(|_| rng.gen_range(0.0..0.5))
                }
            })
            .collect();
        let whole = Aabb::around(&pts);
        let radii = [0.0, 0.01, 0.05, 0.125, 0.3];
        let r2: Vec<f64> = radii.iter().map(|r| r * r).collect();
        let (baseline, fast) = (Level::BASELINE, Level::fast_available());
        for (ra, rb) in [(0..400, 0..400), (0..150, 150..400), (37..300, 10..90)] {
            let same = ra == rb;
            let runs = || {
                (
                    (&pts[..], ra.clone(), &whole),
                    (&pts[..], rb.clone(), &whole),
                    same,
                )
            };
            for boundary in [Boundary::Inclusive, Boundary::Exclusive] {
                for &r in &radii {
                    let base = pairs_by(baseline, runs(), r * r, boundary);
                    assert!(r == 0.0 || same || !base.is_empty(), "the check sees pairs");
                    for &level in &fast {
                        let got = pairs_by(level, runs(), r * r, boundary);
                        assert_eq!(got, base, "{level:?}");
                    }
                }
                let base = counts_by(baseline, runs(), &r2, boundary);
                assert!(base.iter().any(|&c| c != 0), "the check sees counts");
                for &level in &fast {
                    assert_eq!(counts_by(level, runs(), &r2, boundary), base, "{level:?}");
                }
            }
        }
    }
}
