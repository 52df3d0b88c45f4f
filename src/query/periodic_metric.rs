//! The minimum-image metrics [`MinImage`] on a [`Torus`]: squared Euclidean, Manhattan and
//! Chebyshev distances whose per-axis offsets are the shortest over all images of the wrapping
//! axes, with a box bound that never exceeds the computed distance of a point of the box (the
//! exactness argument of [`Torus`]'s offsets and of [`crate::query`]'s metrics), so they plug
//! into every `*_by` nearest-neighbour query, the best-first iterator and the batch forms.

// Loops over axes index the point, the box's min and max together; an index reads best.
#![allow(clippy::needless_range_loop)]

use super::metric::{axis_gap, Chebyshev, Manhattan, Metric, SquaredEuclidean};
use super::periodic::Torus;
use crate::geom::Aabb;

impl<const D: usize> Torus<D> {
    /// The minimum-image squared Euclidean distance ([`MinImage`]).
    pub fn squared_euclidean(&self) -> MinImage<SquaredEuclidean, D> {
        self.min_image(SquaredEuclidean)
    }

    /// The minimum-image Manhattan distance ([`MinImage`]).
    pub fn manhattan(&self) -> MinImage<Manhattan, D> {
        self.min_image(Manhattan)
    }

    /// The minimum-image Chebyshev distance ([`MinImage`]).
    pub fn chebyshev(&self) -> MinImage<Chebyshev, D> {
        self.min_image(Chebyshev)
    }

    /// `metric` on this torus.
    fn min_image<M>(&self, metric: M) -> MinImage<M, D> {
        MinImage {
            torus: *self,
            metric,
        }
    }
}

/// A metric made of per-axis offsets: how [`MinImage`] combines the minimum-image offsets.
pub trait AxisMetric {
    /// The distance so far, `acc`, with one more axis at offset `d >= 0`.
    fn combine(acc: f64, d: f64) -> f64;
}

impl AxisMetric for SquaredEuclidean {
    #[inline(always)]
    fn combine(acc: f64, d: f64) -> f64 {
        acc + d * d
    }
}

impl AxisMetric for Manhattan {
    #[inline(always)]
    fn combine(acc: f64, d: f64) -> f64 {
        acc + d
    }
}

impl AxisMetric for Chebyshev {
    #[inline(always)]
    fn combine(acc: f64, d: f64) -> f64 {
        acc.max(d)
    }
}

/// A metric `M` on a [`Torus`]: the minimum over all images of the wrapping axes. Built by
/// [`Torus::squared_euclidean`], [`Torus::manhattan`] or [`Torus::chebyshev`]; pass it to any
/// `*_by` query ([`PointSet::k_nearest_by`](super::PointSet::k_nearest_by),
/// [`PointSet::nearest_iter_by`](super::PointSet::nearest_iter_by), ...). Query points need not
/// be wrapped first; tree points need not be either, though [`Torus::prepare`] is the way to
/// make the periodic boxes ([`PeriodicBox`](super::PeriodicBox)) see them.
///
/// ```
/// use orthtree::query::{Metric, Torus};
/// let m = Torus::wrapping([0.0; 2], [10.0; 2]).unwrap().squared_euclidean();
/// assert_eq!(m.distance(&[1.0, 1.0], &[9.0, 1.0]), 4.0); // across the face: 2 units
/// assert_eq!(m.distance(&[0.0, 0.0], &[5.0, 5.0]), 50.0); // never more than half a period
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct MinImage<M, const D: usize> {
    /// The domain.
    pub torus: Torus<D>,
    /// The metric combining the per-axis offsets.
    pub metric: M,
}

impl<M: AxisMetric, const D: usize> MinImage<M, D> {
    /// [`Metric::distance`] of points at least a period apart along some wrapping axis: every
    /// offset through [`Torus::offset`], which reduces them from the points' own coordinates.
    #[cold]
    #[inline(never)]
    fn far_distance(&self, a: &[f64; D], b: &[f64; D]) -> f64 {
        let mut s = 0.0;
        for i in 0..D {
            s = M::combine(s, self.torus.offset(i, a[i], b[i]));
        }
        s
    }
}

impl<M: AxisMetric + Metric<D>, const D: usize> Metric<D> for MinImage<M, D> {
    #[inline(always)]
    fn distance(&self, a: &[f64; D], b: &[f64; D]) -> f64 {
        // Without a branch while every plain offset is below its axis's limit (the period on a
        // wrapping axis; every pair of the period box), with the same operations as
        // `Torus::offset` then; the reduction from the remainders of the coordinates otherwise.
        let (mut s, mut far) = (0.0, false);
        for i in 0..D {
            let d = (a[i] - b[i]).abs();
            let limit = self.torus.limit(i);
            far |= d >= limit;
            let e = limit - d;
            s = M::combine(s, if e < d { e } else { d });
        }
        if !far {
            return s;
        }
        // The points' copies through an opaque identity, out of line: the engines' kernels
        // gather each point from columns into registers, and a reference to them reaching the
        // call made those kernels store every point to memory (or spill the coordinates) for
        // this rare case. On 10^6 points in the periodic unit cube, 2 * 10^5 queries of the
        // 10 nearest as a batch took the time they took when this path reduced the rounded
        // offset and needed no coordinates (341 against 340 ms, medians of five runs), where
        // passing `a` and `b` on took 5-9% longer; the 8-nearest self-join took 5% longer.
        let (a, b) = core::hint::black_box((*a, *b));
        self.far_distance(&a, &b)
    }
    #[inline(always)]
    fn box_distance(&self, q: &[f64; D], b: &Aabb<f64, D>) -> f64 {
        let mut s = 0.0;
        for i in 0..D {
            s = M::combine(s, self.torus.offset_range(i, q[i], b.min[i], b.max[i]).0);
        }
        s
    }
    #[inline(always)]
    fn scale_distance(&self, d: f64, factor: f64) -> f64 {
        self.metric.scale_distance(d, factor)
    }
    const HAS_TORUS: bool = true;
    #[inline(always)]
    fn torus(&self) -> Option<&Torus<D>> {
        Some(&self.torus)
    }
    #[inline(always)]
    fn unwrapped_distance(&self, a: &[f64; D], b: &[f64; D]) -> f64 {
        let mut s = 0.0;
        for i in 0..D {
            s = M::combine(s, (a[i] - b[i]).abs());
        }
        s
    }
    #[inline(always)]
    fn unwrapped_box_distance(&self, q: &[f64; D], b: &Aabb<f64, D>, margin: &[f64; D]) -> f64 {
        let mut s = 0.0;
        for i in 0..D {
            let gap = axis_gap(q[i], b.min[i], b.max[i]);
            s = M::combine(s, (gap - margin[i]).max(0.0));
        }
        s
    }
}
