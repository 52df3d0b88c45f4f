//! The per-leaf bound check: every point of a leaf's run lies in the leaf's cell under the split
//! convention and in the domain, with coordinates `f64` holds exactly. One linear pass over the
//! points, no Morton key: per leaf, two bounds per axis are computed from the cell's boundary
//! lines, then each point costs two comparisons per axis in a branch-free loop over the leaf's
//! contiguous run. With feature `rayon`, [`check_leaves`] splits the leaves into chunks checked on
//! rayon's threads; the first bad point in Morton order is reported either way.
//!
//! Why the bounds equal the key's cell. [`RootGeometry`] puts a coordinate `x` in the finest cell
//! `j` with `b(j) < x <= b(j + 1)` (the first cell includes its lower line), where the boundaries
//! `b` are monotone and those of level `l` are the finest ones at multiples of `2^(F - l)`
//! (`boundary(c, l)` evaluates the same `f64` fraction as `boundary(c 2^(F-l), F)`). So the key's
//! cell at level `l` is `c` exactly when `c == 0 || b_l(c) < x` and `c == 2^l - 1 || x <= b_l(c + 1)`.
//! For a finite `f64` boundary `b`, `b < x` is `x >= b.next_up()`; with the domain's sides the
//! test becomes `lo <= x <= hi` with `lo = max(domain.min, b_l(c).next_up())` (or `domain.min` on
//! the first cell) and `hi = min(domain.max, b_l(c + 1))` (or `domain.max` on the last). A NaN
//! fails both comparisons; an infinity fails the finite domain's. Integer coordinates are
//! compared as the `f64` they convert to, after [`Scalar::converts_exactly`] (64-bit integers
//! beyond 2^53 pass only when `f64` holds them, as everywhere in the crate), so the check agrees
//! with the keys and the queries for every coordinate type.

use crate::error::{Invariant, ValidationError};
use crate::geom::{Aabb, Cell, RootGeometry, Scalar};

/// One leaf: its node id, its cell and its run of points `start..end`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct LeafRun<const D: usize> {
    /// The leaf's node id.
    pub node: u32,
    /// Its cell.
    pub cell: Cell<D>,
    /// The first index of its run.
    pub start: u32,
    /// One past the last.
    pub end: u32,
}

/// Per axis, the smallest and largest `f64` a point of `cell` may hold (both included); see the
/// module doc.
#[inline]
pub(crate) fn cell_bounds<const D: usize>(
    geometry: &RootGeometry<D>,
    domain: &Aabb<f64, D>,
    cell: &Cell<D>,
) -> ([f64; D], [f64; D]) {
    let level = cell.level();
    let last = (1u64 << level) - 1;
    let c = cell.coords();
    let lo = core::array::from_fn(|a| {
        let j = u64::from(c[a]);
        if j == 0 {
            domain.min[a]
        } else {
            domain.min[a].max(geometry.boundary(a, j, level).next_up())
        }
    });
    let hi = core::array::from_fn(|a| {
        let j = u64::from(c[a]);
        if j == last {
            domain.max[a]
        } else {
            domain.max[a].min(geometry.boundary(a, j + 1, level))
        }
    });
    (lo, hi)
}

/// Coordinates per block of [`all_within`]'s unrolled loop: whole points, at most this many.
const BLOCK: usize = 24;

/// Whether the conversion to `f64` of coordinates of `S` must be checked apart from the bounds
/// of `domain`: for 64-bit integers, and for floats when the domain is not finite (every tree's
/// domain is finite, built or read back, so this is a guard only; a float that is not finite
/// fails finite bounds, and `f32` and the smaller integers always convert exactly).
#[inline(always)]
fn needs_exactness<S: Scalar, const D: usize>(domain: &Aabb<f64, D>) -> bool {
    let finite = (0..D).all(|a| domain.min[a].is_finite() && domain.max[a].is_finite());
    (core::mem::size_of::<S>() == 8 && S::zero().integer_value().is_some()) || !finite
}

/// Whether every point of `points` lies within `lo..=hi` on every axis and converts exactly:
/// branch-free passes over blocks of whole points (the bounds repeated to the block's length,
/// so that the comparisons run in vector lanes whatever D), then the remaining points.
#[inline]
fn all_within<S: Scalar, const D: usize>(
    points: &[[S; D]],
    lo: &[f64; D],
    hi: &[f64; D],
    exact: bool,
) -> bool {
    let per_block = (BLOCK / D).max(1);
    let len = per_block * D;
    if D <= BLOCK && points.len() >= per_block {
        let lo_rep: [f64; BLOCK] = core::array::from_fn(|i| lo[i % D]);
        let hi_rep: [f64; BLOCK] = core::array::from_fn(|i| hi[i % D]);
        let (lo_rep, hi_rep) = (&lo_rep[..len], &hi_rep[..len]);
        let flat = points.as_flattened();
        let mut ok = true;
        let mut blocks = flat.chunks_exact(len);
        for block in &mut blocks {
            for ((&x, &l), &h) in block.iter().zip(lo_rep).zip(hi_rep) {
                let x = x.to_f64();
                ok &= (x >= l) & (x <= h);
            }
            if exact {
                ok &= block.iter().all(|&x| Scalar::converts_exactly(x));
            }
        }
        let rest = blocks.remainder();
        for (i, x) in rest.iter().enumerate() {
            let y = Scalar::to_f64(*x);
            ok &= (y >= lo[i % D]) & (y <= hi[i % D]) & (!exact || Scalar::converts_exactly(*x));
        }
        return ok;
    }
    let mut ok = true;
    for p in points {
        for a in 0..D {
            let x = p[a].to_f64();
            ok &= (x >= lo[a]) & (x <= hi[a]) & (!exact || p[a].converts_exactly());
        }
    }
    ok
}

/// The error for the first point of `run` (the run of `leaf`) outside `lo..=hi`.
#[cold]
fn explain<S: Scalar, const D: usize>(
    domain: &Aabb<f64, D>,
    leaf: &LeafRun<D>,
    run: &[[S; D]],
    lo: &[f64; D],
    hi: &[f64; D],
) -> ValidationError {
    for (i, p) in run.iter().enumerate() {
        let at = leaf.start as usize + i;
        for a in 0..D {
            let x = p[a].to_f64();
            if !p[a].converts_exactly() {
                return ValidationError::new(Invariant::InDomain)
                    .point(at)
                    .detail(format!("coordinate {a} is {:?}, not exact as f64", p[a]));
            }
            if !(domain.min[a] <= x && x <= domain.max[a]) {
                return ValidationError::new(Invariant::InDomain)
                    .point(at)
                    .detail(format!(
                        "coordinate {a} is {x}, the domain spans [{}, {}]",
                        domain.min[a], domain.max[a]
                    ));
            }
            if !(lo[a] <= x && x <= hi[a]) {
                return ValidationError::new(Invariant::InLeaf)
                    .node(leaf.node)
                    .point(at)
                    .detail(format!(
                        "coordinate {a} is {x}, the leaf's cell (level {}) takes [{}, {}]",
                        leaf.cell.level(),
                        lo[a],
                        hi[a]
                    ));
            }
        }
    }
    ValidationError::new(Invariant::InLeaf).node(leaf.node)
}

/// Leaves per task of the parallel check.
#[cfg(feature = "rayon")]
const CHUNK: usize = 512;

/// Checks that every point of every leaf lies in its leaf's cell and the domain, exactly (see the
/// module doc); on rayon's threads when `parallel` (and feature `rayon`). Each leaf's run must
/// lie in `points` (the caller's walk checked the runs).
///
/// # Errors
/// The first point out of place in Morton order: [`Invariant::InDomain`] naming the point, axis
/// and domain, or [`Invariant::InLeaf`] naming the leaf, point, axis and the cell's bounds.
///
/// # Complexity
/// O(n D) comparisons for n points, plus O(D) per leaf.
pub(crate) fn check_leaves<S: Scalar, const D: usize>(
    geometry: &RootGeometry<D>,
    domain: &Aabb<f64, D>,
    points: &[[S; D]],
    leaves: &[LeafRun<D>],
    parallel: bool,
) -> Result<(), ValidationError> {
    let exact = needs_exactness::<S, D>(domain);
    first_error(leaves, parallel, |leaf| {
        let (lo, hi) = cell_bounds(geometry, domain, &leaf.cell);
        let run = &points[leaf.start as usize..leaf.end as usize];
        (!all_within(run, &lo, &hi, exact)).then(|| explain(domain, leaf, run, &lo, &hi))
    })
}

/// The first error `find` reports on a leaf of `leaves`, in their order, found on chunks of
/// them on rayon's threads when `parallel` (and feature `rayon`).
fn first_error<const D: usize>(
    leaves: &[LeafRun<D>],
    parallel: bool,
    find: impl Fn(&LeafRun<D>) -> Option<ValidationError> + Sync,
) -> Result<(), ValidationError> {
    let in_chunk = |chunk: &[LeafRun<D>]| chunk.iter().find_map(&find);
    #[cfg(feature = "rayon")]
    if parallel && leaves.len() > CHUNK {
        use rayon::prelude::*;
        return leaves
            .par_chunks(CHUNK)
            .find_map_first(in_chunk)
            .map_or(Ok(()), Err);
    }
    let _ = parallel;
    in_chunk(leaves).map_or(Ok(()), Err)
}

/// Checks that the points of every leaf are in Morton order (the owned tree's updates find a
/// point's place in its leaf by key; the queries do not need it). Computes every point's key;
/// on rayon's threads when `parallel` (and feature `rayon`).
///
/// # Errors
/// [`Invariant::InLeaf`] naming the first leaf and point out of order.
///
/// # Complexity
/// O(n D) for n points.
pub(crate) fn check_leaf_order<S: Scalar, const D: usize>(
    geometry: &RootGeometry<D>,
    points: &[[S; D]],
    leaves: &[LeafRun<D>],
    parallel: bool,
) -> Result<(), ValidationError> {
    first_error(leaves, parallel, |leaf| {
        if leaf.end - leaf.start <= 1 {
            return None;
        }
        let run = &points[leaf.start as usize..leaf.end as usize];
        let (mut previous, mut unordered) = (0u64, None);
        geometry.keys_into(
            run.len(),
            |i| &run[i],
            |i, key| {
                if key < previous && unordered.is_none() {
                    unordered = Some(i);
                }
                previous = key;
            },
        );
        unordered.map(|i| {
            ValidationError::new(Invariant::InLeaf)
                .node(leaf.node)
                .point(leaf.start as usize + i)
                .detail("out of Morton order in its leaf")
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bounds agree with the keys' cells on and next to every boundary line of a few
    /// levels, in a cube away from the origin.
    #[test]
    fn bounds_agree_with_the_keys_on_split_lines() {
        let g = RootGeometry::<2>::new([-3.0, 0.1], 7.0);
        let domain = g.root_box();
        for level in [1u8, 2, 5, 12] {
            for j in 0..(1u32 << level.min(6)) {
                let b = g.boundary(0, u64::from(j), level);
                for x in [b, b.next_up(), b.next_down()] {
                    let p = [x, 0.5];
                    if !domain.contains(&p) {
                        continue;
                    }
                    let cell = g.cell_of(&p, level);
                    let (lo, hi) = cell_bounds(&g, &domain, &cell);
                    assert!(lo[0] <= x && x <= hi[0], "{x} at level {level}");
                    // and no neighbouring cell takes it
                    for other in [cell.coords()[0].wrapping_sub(1), cell.coords()[0] + 1] {
                        if let Some(c) = Cell::new(level, [other, cell.coords()[1]]) {
                            let (lo, hi) = cell_bounds(&g, &domain, &c);
                            assert!(!(lo[0] <= x && x <= hi[0]), "{x} in {c:?}");
                        }
                    }
                }
            }
        }
    }
}
