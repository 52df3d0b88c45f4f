//! Distances for nearest-neighbour queries: the [`Metric`] trait (a point distance and a lower
//! bound of it over a closed box, the pruning test of branch-and-bound search) and three
//! metrics: [`SquaredEuclidean`] (the default), [`Manhattan`] and [`Chebyshev`].
//!
//! Each box bound is computed with the same operations, in the same order, as the point distance,
//! on the box's nearest point along each axis. Rounding is monotone, so the bound never exceeds
//! the computed distance of any point in the box: pruning never loses a neighbour, even at ties.

// Loops over axes index the point, the box's min and max together; an index reads best.
#![allow(clippy::needless_range_loop)]

// Axis loops index several arrays in one fixed order, the order the exactness argument needs.

use super::periodic::Torus;
use crate::geom::Aabb;
use crate::geom::{halves_by_terms, Halves, Kept};

/// A distance between points, and a lower bound of it over a box.
///
/// Contract: `box_distance(q, b) <= distance(q, p)` for every `p` in the closed box `b` (as
/// computed), both non-negative; smaller means nearer.
///
/// ```
/// use orthtree::query::{Chebyshev, Manhattan, Metric, SquaredEuclidean};
/// use orthtree::Aabb;
/// let (p, q) = ([0.0, 0.0], [3.0, 4.0]);
/// assert_eq!(SquaredEuclidean.distance(&p, &q), 25.0);
/// assert_eq!(Manhattan.distance(&p, &q), 7.0);
/// assert_eq!(Chebyshev.distance(&p, &q), 4.0);
/// let b = Aabb { min: [1.0, 1.0], max: [2.0, 2.0] };
/// assert_eq!(SquaredEuclidean.box_distance(&p, &b), 2.0);
/// ```
pub trait Metric<const D: usize> {
    /// The distance between `a` and `b`.
    fn distance(&self, a: &[f64; D], b: &[f64; D]) -> f64;
    /// A lower bound of `distance(q, p)` over the points `p` of the closed box `b` (0 inside it).
    fn box_distance(&self, q: &[f64; D], b: &Aabb<f64, D>) -> f64;
    /// The distance, in this metric's units, of two points `factor` times as far apart as two
    /// at distance `d` (`factor >= 0`): `d * factor` for a norm (the default), `d * factor^2`
    /// for [`SquaredEuclidean`]. The approximate searches
    /// ([`PointSet::k_nearest_approx_by`](super::PointSet::k_nearest_approx_by)) scale their
    /// pruning bound by it, so that `(1 + eps)` means the same for every metric. A metric that
    /// is a power `p` of a norm overrides it with `d * factor^p`.
    ///
    /// ```
    /// use orthtree::query::{Manhattan, Metric, SquaredEuclidean};
    /// assert_eq!(Metric::<2>::scale_distance(&Manhattan, 4.0, 0.5), 2.0);
    /// assert_eq!(Metric::<2>::scale_distance(&SquaredEuclidean, 4.0, 0.5), 1.0);
    /// ```
    #[inline(always)]
    fn scale_distance(&self, d: f64, factor: f64) -> f64 {
        d * factor
    }

    /// Whether [`Metric::torus`] can be `Some` (`false`, the default, for a metric of ordinary
    /// space; `true` for [`MinImage`](super::MinImage)). The k-nearest engines ask for the torus
    /// only when it is `true`, so that the image search is not compiled for the metrics of
    /// ordinary space (it was about a seventh of the compiled code of a crate that queries
    /// several trees by several metrics). A metric that returns a torus without setting it is
    /// still searched correctly, by bounding every box by [`Metric::box_distance`].
    ///
    /// ```
    /// use orthtree::query::{MinImage, Metric, SquaredEuclidean};
    /// assert!(!<SquaredEuclidean as Metric<2>>::HAS_TORUS);
    /// assert!(<MinImage<SquaredEuclidean, 2> as Metric<2>>::HAS_TORUS);
    /// ```
    const HAS_TORUS: bool = false;

    /// The periodic domain of a minimum-image metric ([`MinImage`](super::MinImage)); `None`
    /// (the default) for a metric of ordinary space. When it is `Some` (and
    /// [`Metric::HAS_TORUS`] is set), the exact and approximate k-nearest engines search the
    /// query's images across the period box one by one, each as an ordinary search bounded by
    /// [`Metric::unwrapped_box_distance`], instead of bounding every box by its nearest image.
    ///
    /// ```
    /// use orthtree::query::{Metric, SquaredEuclidean, Torus};
    /// let t = Torus::wrapping([0.0; 2], [1.0; 2]).unwrap();
    /// assert_eq!(t.squared_euclidean().torus(), Some(&t));
    /// assert_eq!(Metric::<2>::torus(&SquaredEuclidean), None);
    /// ```
    #[inline(always)]
    fn torus(&self) -> Option<&Torus<D>> {
        None
    }

    /// For a metric with a [`Metric::torus`]: the distance between `a` and `b` as in ordinary
    /// space (no wrap), their offsets combined as [`Metric::distance`] combines the
    /// minimum-image ones, so that the two are equal, bit for bit, when no offset along a
    /// wrapping axis exceeds half its period. The default, for metrics without a torus, is
    /// [`Metric::distance`].
    ///
    /// ```
    /// use orthtree::query::{Metric, Torus};
    /// let m = Torus::wrapping([0.0; 2], [1.0; 2]).unwrap().squared_euclidean();
    /// assert_eq!(m.unwrapped_distance(&[0.0, 0.0], &[0.75, 0.0]), 0.5625);
    /// assert_eq!(m.distance(&[0.0, 0.0], &[0.75, 0.0]), 0.0625);
    /// ```
    #[inline(always)]
    fn unwrapped_distance(&self, a: &[f64; D], b: &[f64; D]) -> f64 {
        self.distance(a, b)
    }

    /// For a metric with a [`Metric::torus`]: the offsets from `q` to the closed box `b` along
    /// each axis as in ordinary space (no wrap), each lowered by `margin` on its axis (never
    /// below 0), combined as [`Metric::distance`] combines the minimum-image offsets.
    ///
    /// Contract (relied on by the image search): when `q` is an image of a query point `p`
    /// (shifted by whole periods along wrapping axes and wrapped into the period box) whose
    /// rounding along each axis `margin` covers, the result is at most `distance(p, x)` for
    /// every `x` of `b` whose nearest image to `p` is the one `q` stands for. The default,
    /// for metrics without a torus, is [`Metric::box_distance`], ignoring `margin`.
    ///
    /// ```
    /// use orthtree::query::{Metric, Torus};
    /// use orthtree::Aabb;
    /// let m = Torus::wrapping([0.0; 2], [1.0; 2]).unwrap().squared_euclidean();
    /// let b = Aabb { min: [0.5, 0.0], max: [0.75, 0.25] };
    /// assert_eq!(m.unwrapped_box_distance(&[0.0, 0.0], &b, &[0.0; 2]), 0.25);
    /// let wrapped = m.box_distance(&[0.0, 0.0], &b); // through the face at 1: 0.25 away
    /// assert!(0.0624 < wrapped && wrapped <= 0.0625);
    /// ```
    #[inline(always)]
    fn unwrapped_box_distance(&self, q: &[f64; D], b: &Aabb<f64, D>, margin: &[f64; D]) -> f64 {
        let _ = margin;
        self.box_distance(q, b)
    }

    /// The children of the box `cell` split at `mid` outside every half of it (either side of
    /// a split line) whose [`Metric::box_distance`] from `q` exceeds `bound` ([`Kept`]). The
    /// default bounds the 2 D half boxes; [`SquaredEuclidean`] and [`Manhattan`], sums over
    /// the axes, change one term of the box's sum per half, with the same answers.
    ///
    /// ```
    /// use orthtree::query::{Metric, SquaredEuclidean};
    /// use orthtree::Aabb;
    /// let b = Aabb { min: [0.0, 0.0], max: [2.0, 2.0] };
    /// // from (-1, 1) within 1.5 (squared): nothing right of x = 1
    /// assert_eq!(SquaredEuclidean.kept_within(&[-1.0, 1.0], &b, &[1.0, 1.0], 1.5), Some((1, 0)));
    /// ```
    #[inline(always)]
    fn kept_within(&self, q: &[f64; D], cell: &Aabb<f64, D>, mid: &[f64; D], bound: f64) -> Kept {
        (|h: &Aabb<f64, D>| self.box_distance(q, h) > bound).kept(cell, mid)
    }

    /// [`Metric::box_distance`] of the slab of points whose coordinate along `axis` lies in
    /// `[lo, hi]`, every other coordinate free (an infinite end allowed). The k-nearest search
    /// asks it of the 2 D slabs beyond a box's faces to know that its bound's ball lies inside
    /// the box. The default bounds the slab as a box; [`SquaredEuclidean`], [`Manhattan`] and
    /// [`Chebyshev`] answer from the one offset along `axis`, with the same value.
    ///
    /// ```
    /// use orthtree::query::{Metric, SquaredEuclidean};
    /// // from (3, 7), the slab x <= 1: 2 away along x, so 4 squared
    /// assert_eq!(SquaredEuclidean.slab_distance(&[3.0, 7.0], 0, f64::NEG_INFINITY, 1.0), 4.0);
    /// ```
    #[inline(always)]
    fn slab_distance(&self, q: &[f64; D], axis: usize, lo: f64, hi: f64) -> f64 {
        let slab = Aabb {
            min: core::array::from_fn(|i| if i == axis { lo } else { f64::NEG_INFINITY }),
            max: core::array::from_fn(|i| if i == axis { hi } else { f64::INFINITY }),
        };
        self.box_distance(q, &slab)
    }
}

/// The offset from `q` to the nearest point of `[lo, hi]`, as `p - q` would round for that point
/// (0 inside).
#[inline(always)]
pub(crate) fn axis_gap(q: f64, lo: f64, hi: f64) -> f64 {
    // Both offsets computed and the answer selected, with no branch on where `q` lies (a
    // search bounds boxes on every side of the query, so such a branch is mispredicted often):
    // the same value as `if q < lo { lo - q } else if q > hi { q - hi } else { 0.0 }` for
    // every input, NaN and -0.0 included.
    let (below, above) = (lo - q, q - hi);
    let above = if above > 0.0 { above } else { 0.0 };
    if q < lo {
        below
    } else {
        above
    }
}

/// The squared Euclidean distance, sum of `(a_i - b_i)^2` (distances and maximum distances are in
/// these squared units).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SquaredEuclidean;

impl<const D: usize> Metric<D> for SquaredEuclidean {
    #[inline(always)]
    fn distance(&self, a: &[f64; D], b: &[f64; D]) -> f64 {
        let mut s = 0.0;
        for i in 0..D {
            let d = a[i] - b[i];
            s += d * d;
        }
        s
    }
    #[inline(always)]
    fn box_distance(&self, q: &[f64; D], b: &Aabb<f64, D>) -> f64 {
        let mut s = 0.0;
        for i in 0..D {
            let d = axis_gap(q[i], b.min[i], b.max[i]);
            s += d * d;
        }
        s
    }
    #[inline(always)]
    fn slab_distance(&self, q: &[f64; D], axis: usize, lo: f64, hi: f64) -> f64 {
        // The box's sum with every other term 0: `0 + g^2 + 0` is `g^2` exactly.
        let g = axis_gap(q[axis], lo, hi);
        g * g
    }
    #[inline(always)]
    fn scale_distance(&self, d: f64, factor: f64) -> f64 {
        d * (factor * factor)
    }
    #[inline(always)]
    fn kept_within(&self, q: &[f64; D], cell: &Aabb<f64, D>, mid: &[f64; D], bound: f64) -> Kept {
        let term = |a: usize, lo: f64, hi: f64| {
            let d = axis_gap(q[a], lo, hi);
            d * d
        };
        halves_by_terms(cell, mid, term, bound)
    }
}

/// The Manhattan (L1) distance, sum of `|a_i - b_i|`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Manhattan;

impl<const D: usize> Metric<D> for Manhattan {
    #[inline(always)]
    fn distance(&self, a: &[f64; D], b: &[f64; D]) -> f64 {
        let mut s = 0.0;
        for i in 0..D {
            s += (a[i] - b[i]).abs();
        }
        s
    }
    #[inline(always)]
    fn box_distance(&self, q: &[f64; D], b: &Aabb<f64, D>) -> f64 {
        let mut s = 0.0;
        for i in 0..D {
            s += axis_gap(q[i], b.min[i], b.max[i]);
        }
        s
    }
    #[inline(always)]
    fn slab_distance(&self, q: &[f64; D], axis: usize, lo: f64, hi: f64) -> f64 {
        axis_gap(q[axis], lo, hi)
    }
    #[inline(always)]
    fn kept_within(&self, q: &[f64; D], cell: &Aabb<f64, D>, mid: &[f64; D], bound: f64) -> Kept {
        halves_by_terms(cell, mid, |a, lo, hi| axis_gap(q[a], lo, hi), bound)
    }
}

/// The Chebyshev (L-infinity) distance, max of `|a_i - b_i|`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Chebyshev;

impl<const D: usize> Metric<D> for Chebyshev {
    #[inline(always)]
    fn distance(&self, a: &[f64; D], b: &[f64; D]) -> f64 {
        let mut s: f64 = 0.0;
        for i in 0..D {
            s = s.max((a[i] - b[i]).abs());
        }
        s
    }
    #[inline(always)]
    fn box_distance(&self, q: &[f64; D], b: &Aabb<f64, D>) -> f64 {
        let mut s: f64 = 0.0;
        for i in 0..D {
            s = s.max(axis_gap(q[i], b.min[i], b.max[i]));
        }
        s
    }
    #[inline(always)]
    fn slab_distance(&self, q: &[f64; D], axis: usize, lo: f64, hi: f64) -> f64 {
        axis_gap(q[axis], lo, hi)
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::axis_gap;

    /// The values the branch-free offsets must agree on: zeros of both signs, infinities,
    /// NaN, the extremes and ordinary values on either side of one another.
    pub(crate) const SPECIAL: [f64; 13] = [
        f64::NAN,
        f64::NEG_INFINITY,
        -f64::MAX,
        -1.5,
        -f64::MIN_POSITIVE,
        -0.0,
        0.0,
        5e-324,
        1.0,
        1.5,
        2.0,
        f64::MAX,
        f64::INFINITY,
    ];

    /// `axis_gap` selects what the three-way branch it replaced returned, bit for bit, on every
    /// triple of special values (inverted intervals and NaN included).
    #[test]
    fn axis_gap_equals_the_branching_form() {
        let branching = |q: f64, lo: f64, hi: f64| {
            if q < lo {
                lo - q
            } else if q > hi {
                q - hi
            } else {
                0.0
            }
        };
        for q in SPECIAL {
            for lo in SPECIAL {
                for hi in SPECIAL {
                    let (got, want) = (axis_gap(q, lo, hi), branching(q, lo, hi));
                    assert!(
                        got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()),
                        "axis_gap({q}, {lo}, {hi}) = {got}, the branching form {want}"
                    );
                }
            }
        }
    }
}
