//! The one seam between the joins and the geometry of their domain: the distance between two
//! points and the range of distances between the points of two closed boxes.
//!
//! Every join engine of this folder reads distances through [`PairDistance`] only, so that a
//! domain with another distance (a periodic box, whose minimum-image distance wraps each axis)
//! plugs in by one more implementation. [`Euclid`] is the squared Euclidean distance of the
//! rest of the query layer ([`SquaredEuclidean`](crate::query::SquaredEuclidean)); the
//! minimum-image squared Euclidean distance of a [`Torus`](crate::query::Torus)
//! ([`MinImage`]) is the periodic joins' one.
//!
//! Exactness: each bound is computed with the operations of the point distance, in the same axis
//! order, on the nearest (farthest) pair of coordinates the two boxes allow. Rounding is
//! monotone, so for `p` in box `a` and `q` in box `b` (as `f64`), `min <= distance(p, q) <=
//! max` holds for the computed values, even at ties: pruning a node pair whose minimum exceeds a
//! bound never loses a pair, and counting a node pair whose maximum is within a radius never
//! counts a pair outside it.
//!
//! On a torus, the offsets `p - q` of `p` in `[a.min, a.max]` and `q` in `[b.min, b.max]` along
//! an axis lie in `[a.min - b.max, a.max - b.min]` as computed (rounding is monotone), and a
//! point pair's minimum-image offset is the one of its computed difference when that is within
//! a period, and within a rounding of the period of the exact one when it is not: the bounds of
//! the offset from 0 to that interval ([`Torus`](crate::query::Torus)'s own, whose rounding
//! margin covers a few roundings of the interval's ends and of the period) bound every pair's
//! offset, and combine as the distance does.

// Loops over axes index both boxes together, in the fixed order the exactness argument needs.
#![allow(clippy::needless_range_loop)]

use crate::geom::Aabb;
use crate::query::metric::{Metric, SquaredEuclidean};
use crate::query::periodic_metric::MinImage;

/// The distance between points and its range over pairs of closed boxes (see the module doc).
pub(crate) trait PairDistance<const D: usize>: Sync {
    /// The distance between `a` and `b`.
    fn distance(&self, a: &[f64; D], b: &[f64; D]) -> f64;
    /// A lower bound of `distance(q, p)` over the points `p` of the closed box `b`.
    fn point_box(&self, q: &[f64; D], b: &Aabb<f64, D>) -> f64;
    /// A lower and an upper bound of `distance(p, q)` over `p` in `a` and `q` in `b`.
    fn box_box(&self, a: &Aabb<f64, D>, b: &Aabb<f64, D>) -> (f64, f64);
}

/// The squared Euclidean distance, sum of `(a_i - b_i)^2`.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Euclid;

impl<const D: usize> PairDistance<D> for Euclid {
    #[inline(always)]
    fn distance(&self, a: &[f64; D], b: &[f64; D]) -> f64 {
        SquaredEuclidean.distance(a, b)
    }

    #[inline(always)]
    fn point_box(&self, q: &[f64; D], b: &Aabb<f64, D>) -> f64 {
        // `SquaredEuclidean.box_distance` without branches: the gap `lo - q` below the box,
        // `q - hi` above it, 0 inside, as the same subtraction in each case.
        let mut s = 0.0;
        for i in 0..D {
            let (below, above) = (b.min[i] - q[i], q[i] - b.max[i]);
            let gap = if below > above { below } else { above };
            let gap = if gap > 0.0 { gap } else { 0.0 };
            s += gap * gap;
        }
        s
    }

    #[inline(always)]
    fn box_box(&self, a: &Aabb<f64, D>, b: &Aabb<f64, D>) -> (f64, f64) {
        let (mut near, mut far) = (0.0, 0.0);
        for i in 0..D {
            let gap = if a.max[i] < b.min[i] {
                b.min[i] - a.max[i]
            } else if b.max[i] < a.min[i] {
                a.min[i] - b.max[i]
            } else {
                0.0
            };
            let span = (b.max[i] - a.min[i]).max(a.max[i] - b.min[i]);
            near += gap * gap;
            far += span * span;
        }
        (near, far)
    }
}

impl<const D: usize> PairDistance<D> for MinImage<SquaredEuclidean, D> {
    #[inline(always)]
    fn distance(&self, a: &[f64; D], b: &[f64; D]) -> f64 {
        Metric::distance(self, a, b)
    }

    #[inline(always)]
    fn point_box(&self, q: &[f64; D], b: &Aabb<f64, D>) -> f64 {
        self.box_distance(q, b)
    }

    #[inline(always)]
    fn box_box(&self, a: &Aabb<f64, D>, b: &Aabb<f64, D>) -> (f64, f64) {
        let (mut near, mut far) = (0.0, 0.0);
        for i in 0..D {
            let (lo, hi) =
                self.torus
                    .offset_range(i, 0.0, a.min[i] - b.max[i], a.max[i] - b.min[i]);
            near += lo * lo;
            far += hi * hi;
        }
        (near, far)
    }
}

/// Squared Euclidean distance ([`Euclid`]) counting the point-to-point distances and the
/// box-to-box bounds computed: the kernels' tests check how much work a case takes.
#[cfg(test)]
#[derive(Default)]
pub(crate) struct Counting(
    std::sync::atomic::AtomicUsize,
    std::sync::atomic::AtomicUsize,
);

#[cfg(test)]
impl Counting {
    /// The distances computed since the last reset.
    pub(crate) fn distances(&self) -> usize {
        self.0.load(std::sync::atomic::Ordering::Relaxed)
    }

    /// The box-to-box bounds computed since the last reset.
    pub(crate) fn box_bounds(&self) -> usize {
        self.1.load(std::sync::atomic::Ordering::Relaxed)
    }

    pub(crate) fn reset(&self) {
        self.0.store(0, std::sync::atomic::Ordering::Relaxed);
        self.1.store(0, std::sync::atomic::Ordering::Relaxed);
    }
}

#[cfg(test)]
impl<const D: usize> PairDistance<D> for Counting {
    fn distance(&self, a: &[f64; D], b: &[f64; D]) -> f64 {
        self.0.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        Euclid.distance(a, b)
    }
    fn point_box(&self, q: &[f64; D], b: &Aabb<f64, D>) -> f64 {
        Euclid.point_box(q, b)
    }
    fn box_box(&self, a: &Aabb<f64, D>, b: &Aabb<f64, D>) -> (f64, f64) {
        self.1.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        Euclid.box_box(a, b)
    }
}
