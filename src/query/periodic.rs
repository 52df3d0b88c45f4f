//! Periodic domains: the [`Torus`] (a period box `[lo, hi)` whose chosen axes wrap), the bringing
//! of points into it before a build, and the per-axis minimum-image offsets and their bounds over
//! a cell that the metrics ([`MinImage`](crate::query::MinImage)) and regions build on.
//!
//! Along a wrapping axis of period `L`, the offset between `a` and `b` is the minimum over the
//! images `b + nL` (the minimum-image convention of molecular dynamics, Allen and Tildesley,
//! *Computer Simulation of Liquids*, section 1.5): `d = |a - b|` reduced modulo `L`, then
//! `min(d, L - d)`, never more than `L / 2`. The distance combines these offsets as the plain
//! metric does (a sum of squares, a sum, a maximum), so it is the minimum over all `3^k` images.
//! Points less than a period apart (every pair of the period box) take their plain difference;
//! points farther apart are reduced from their remainders modulo `L`, which are exact, so that
//! the offset is within a rounding of `L` of the exact one for any finite coordinates (the
//! rounded difference itself is off by up to half a unit of `|a - b|`, which exceeds the
//! period far out, and overflows between the extremes of `f64`).
//!
//! The box bound of a cell `[lo, hi]` along a wrapping axis is the gap from the query to the
//! nearest image of the cell, lowered by a few units of rounding of the coordinates involved
//! (the modular reductions do not round as the point offsets do): it never exceeds the computed
//! offset of any point of the cell, so pruning never loses a neighbour, even at ties.

// Loops over axes index the point, the box's min and max together; an index reads best.
#![allow(clippy::needless_range_loop)]

use crate::geom::FloatBits;

/// A period box `[lo, hi)` whose chosen axes wrap (a torus along each of them); the other axes
/// are ordinary and their bounds are ignored.
///
/// This is scipy's `boxsize` for `cKDTree`, with the box's lower corner free (not only 0) and
/// without its footgun: a point outside the box is neither silently accepted nor given a wrong
/// answer, it is wrapped or refused as the caller chooses ([`Torus::prepare`]). A point exactly
/// on the upper face is the point on the lower face.
///
/// ```
/// use orthtree::query::{OutsidePoints, Torus};
/// let torus = Torus::new([0.0, 0.0], [10.0, 10.0], [true, false]).unwrap();
/// assert_eq!(torus.wrap(&[12.5, 12.5]).unwrap(), [2.5, 12.5]); // only axis 0 wraps
/// assert_eq!(torus.wrap(&[10.0, 3.0]).unwrap(), [0.0, 3.0]); // upper face = lower face
/// assert!(torus.prepare(&[[1.0, 1.0], [-1.0, 1.0]], OutsidePoints::Refuse).is_err());
/// assert!(Torus::new([0.0], [0.0], [true]).is_err()); // zero period
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Torus<const D: usize> {
    lo: [f64; D],
    hi: [f64; D],
    period: [f64; D],
    wraps: [bool; D],
    /// The period on wrapping axes, infinity on the others: `d.min(limit - d)` is the
    /// minimum-image offset of a plain offset `d < limit` on every axis, without a branch.
    limit: [f64; D],
}

/// What [`Torus::prepare`] does with a point outside the period box on a wrapping axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum OutsidePoints {
    /// Bring it into `[lo, hi)` by whole periods.
    Wrap,
    /// Refuse it with [`PeriodicError::Outside`].
    Refuse,
}

/// A period box or a point the periodic domain refuses, naming the axis (and the point).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum PeriodicError {
    /// A wrapping axis whose bounds are not finite, or whose period `hi - lo` is not positive
    /// and finite.
    InvalidPeriod {
        /// The axis.
        axis: usize,
        /// Its lower bound.
        lo: FloatBits,
        /// Its upper bound.
        hi: FloatBits,
    },
    /// Point `index` has NaN or an infinity on a wrapping `axis`.
    NotFinite {
        /// The point's position in the input (0 for [`Torus::wrap`]).
        index: usize,
        /// The axis.
        axis: usize,
        /// The coordinate.
        value: FloatBits,
    },
    /// Point `index` lies outside `[lo, hi]` on a wrapping `axis` and was refused
    /// ([`OutsidePoints::Refuse`]).
    Outside {
        /// The point's position in the input.
        index: usize,
        /// The axis.
        axis: usize,
        /// The coordinate.
        value: FloatBits,
    },
}

impl core::fmt::Display for PeriodicError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            PeriodicError::InvalidPeriod { axis, lo, hi } => write!(
                f,
                "period box [{}, {}) on axis {axis} is not finite and non-empty",
                lo.get(),
                hi.get()
            ),
            PeriodicError::NotFinite { index, axis, value } => write!(
                f,
                "point {index} has the non-finite coordinate {} on axis {axis}",
                value.get()
            ),
            PeriodicError::Outside { index, axis, value } => write!(
                f,
                "point {index} has the coordinate {} on axis {axis}, outside the period box",
                value.get()
            ),
        }
    }
}

impl std::error::Error for PeriodicError {}

impl<const D: usize> Torus<D> {
    /// The period box `[lo, hi)`, wrapping along the axes where `wraps` is `true`.
    ///
    /// # Errors
    /// [`PeriodicError::InvalidPeriod`] for the first wrapping axis with a non-finite bound or a
    /// period `hi - lo` that is not positive and finite.
    pub fn new(lo: [f64; D], hi: [f64; D], wraps: [bool; D]) -> Result<Self, PeriodicError> {
        let mut period = [0.0; D];
        for axis in 0..D {
            period[axis] = hi[axis] - lo[axis];
            let bad = !(lo[axis].is_finite() && hi[axis].is_finite() && period[axis].is_finite())
                || period[axis] <= 0.0;
            if wraps[axis] && bad {
                return Err(PeriodicError::InvalidPeriod {
                    axis,
                    lo: lo[axis].into(),
                    hi: hi[axis].into(),
                });
            }
        }
        let limit = core::array::from_fn(|a| if wraps[a] { period[a] } else { f64::INFINITY });
        Ok(Torus {
            lo,
            hi,
            period,
            wraps,
            limit,
        })
    }

    /// The period box `[lo, hi)` wrapping along every axis.
    ///
    /// # Errors
    /// As [`Torus::new`].
    ///
    /// ```
    /// use orthtree::query::Torus;
    /// let t = Torus::wrapping([0.0; 3], [1.0; 3]).unwrap();
    /// assert_eq!(t.wrap(&[1.25, -0.25, 0.5]).unwrap(), [0.25, 0.75, 0.5]);
    /// ```
    pub fn wrapping(lo: [f64; D], hi: [f64; D]) -> Result<Self, PeriodicError> {
        Self::new(lo, hi, [true; D])
    }

    /// The lower corner of the period box.
    pub fn lo(&self) -> &[f64; D] {
        &self.lo
    }

    /// The upper corner of the period box (excluded on wrapping axes).
    pub fn hi(&self) -> &[f64; D] {
        &self.hi
    }

    /// Which axes wrap.
    pub fn wraps(&self) -> &[bool; D] {
        &self.wraps
    }

    /// The period `hi - lo` along `axis` (meaningful on wrapping axes).
    ///
    /// # Panics
    /// If `axis >= D`.
    pub fn period(&self, axis: usize) -> f64 {
        self.period[axis]
    }

    /// `true` when `x` lies in `[lo, hi)` along `axis` (always on an ordinary axis).
    #[inline]
    pub(crate) fn in_period(&self, axis: usize, x: f64) -> bool {
        !self.wraps[axis] || (self.lo[axis] <= x && x < self.hi[axis])
    }

    /// `x` brought into `[lo, hi)` along wrapping `axis` by whole periods (a finite `x`).
    #[inline]
    pub(crate) fn wrap_axis(&self, axis: usize, x: f64) -> f64 {
        let (lo, hi, l) = (self.lo[axis], self.hi[axis], self.period[axis]);
        if lo <= x && x < hi {
            return x;
        }
        if x == hi {
            return lo;
        }
        // Both remainders are exact; only their difference and the final sum round.
        let r = (x.rem_euclid(l) - lo.rem_euclid(l)).rem_euclid(l);
        let y = lo + r;
        if lo <= y && y < hi {
            y
        } else {
            lo
        }
    }

    /// `p` brought into the period box along every wrapping axis (by whole periods; a value
    /// that would round up to `hi` becomes `lo`); ordinary axes are left as they are.
    ///
    /// # Errors
    /// [`PeriodicError::NotFinite`] (index 0) for NaN or an infinity on a wrapping axis.
    pub fn wrap(&self, p: &[f64; D]) -> Result<[f64; D], PeriodicError> {
        self.wrap_one(0, p, OutsidePoints::Wrap)
    }

    fn wrap_one(
        &self,
        index: usize,
        p: &[f64; D],
        how: OutsidePoints,
    ) -> Result<[f64; D], PeriodicError> {
        let mut out = *p;
        for axis in (0..D).filter(|&a| self.wraps[a]) {
            let x = p[axis];
            if !x.is_finite() {
                return Err(PeriodicError::NotFinite {
                    index,
                    axis,
                    value: x.into(),
                });
            }
            if how == OutsidePoints::Refuse && !(self.lo[axis] <= x && x <= self.hi[axis]) {
                return Err(PeriodicError::Outside {
                    index,
                    axis,
                    value: x.into(),
                });
            }
            out[axis] = self.wrap_axis(axis, x);
        }
        Ok(out)
    }

    /// The points ready for a build: each inside the period box on every wrapping axis. A point
    /// on the upper face `hi` is always moved to `lo`; one farther out is wrapped or refused as
    /// `how` says.
    ///
    /// # Errors
    /// [`PeriodicError::NotFinite`] or [`PeriodicError::Outside`] naming the first bad point
    /// and its axis.
    ///
    /// # Complexity
    /// `O(n D)`.
    ///
    /// ```
    /// use orthtree::query::{OutsidePoints, PeriodicError, Torus};
    /// let t = Torus::wrapping([0.0; 2], [4.0; 2]).unwrap();
    /// let pts = [[1.0, 4.0], [5.0, -1.0]];
    /// assert_eq!(t.prepare(&pts, OutsidePoints::Wrap).unwrap(), [[1.0, 0.0], [1.0, 3.0]]);
    /// assert!(matches!(
    ///     t.prepare(&pts, OutsidePoints::Refuse),
    ///     Err(PeriodicError::Outside { index: 1, axis: 0, .. })
    /// ));
    /// ```
    pub fn prepare(
        &self,
        points: &[[f64; D]],
        how: OutsidePoints,
    ) -> Result<Vec<[f64; D]>, PeriodicError> {
        points
            .iter()
            .enumerate()
            .map(|(i, p)| self.wrap_one(i, p, how))
            .collect()
    }

    /// The minimum-image offset `|a - b|` along `axis` (the plain one on an ordinary axis), for
    /// any finite `a` and `b`.
    #[inline(always)]
    pub(crate) fn offset(&self, axis: usize, a: f64, b: f64) -> f64 {
        let d = (a - b).abs();
        if !self.wraps[axis] {
            return d;
        }
        let l = self.period[axis];
        // Points within a period of each other (every pair of the period box) keep their
        // plain offset; those farther apart are reduced from their remainders, not from `d`,
        // which has rounded by up to half a unit of `|a - b|` (many periods far out) or
        // overflowed. A `d` of exactly `l` is an offset of 0 either way (as `l % l`).
        let d = if d < l {
            d
        } else if d == l {
            0.0
        } else {
            far_offset(a, b, l)
        };
        // For d >= l / 2, l - d is exact (Sterbenz), so the result never exceeds l / 2.
        d.min(l - d)
    }

    /// The period on a wrapping `axis`, infinity on an ordinary one.
    #[inline(always)]
    pub(crate) fn limit(&self, axis: usize) -> f64 {
        self.limit[axis]
    }

    /// A lower and an upper bound of [`Torus::offset`]`(axis, q, x)` over `x` in `[lo, hi]`.
    #[inline(always)]
    pub(crate) fn offset_range(&self, axis: usize, q: f64, lo: f64, hi: f64) -> (f64, f64) {
        if !self.wraps[axis] {
            let near = super::metric::axis_gap(q, lo, hi);
            return (near, (q - lo).abs().max((hi - q).abs()));
        }
        let l = self.period[axis];
        let w = hi - lo;
        // A few roundings of the coordinates involved: the bounds' safety margin.
        let slack = 8.0 * f64::EPSILON * (q.abs() + lo.abs().max(hi.abs()) + l);
        if w >= l || w.is_nan() {
            return (0.0, l / 2.0 + slack);
        }
        // q sits at t past lo, modulo l; the cell spans [0, w] from lo.
        let t = reduce(q - lo, l);
        let near = if t <= w { 0.0 } else { (t - w).min(l - t) };
        // x - q runs over [u, u + w] modulo l; its image offset peaks at l / 2 if it is crossed.
        let u = if t > 0.0 { l - t } else { 0.0 };
        let half = l / 2.0;
        let image = |v: f64| {
            let v = reduce(v, l);
            v.min(l - v)
        };
        let far = if (u <= half && half <= u + w) || (u <= half + l && half + l <= u + w) {
            half
        } else {
            image(u).max(image(u + w))
        };
        ((near - slack).max(0.0), far + slack)
    }
}

/// `|a - b|` modulo `l`, in `[0, l]`, for finite `a` and `b` more than `l` apart: the
/// remainders `a % l` and `b % l` are exact and lie within a period of 0, so their difference
/// rounds once, by at most half a unit of `2 l`, and bringing it below `l` is exact (Sterbenz):
/// within `l * f64::EPSILON` of the exact offset, however far out the points lie.
#[inline(always)]
fn far_offset(a: f64, b: f64, l: f64) -> f64 {
    // (`x % l` is `x` below a period: the call is saved for a point in or near the box)
    let rem = |x: f64| if x.abs() < l { x } else { x % l };
    let d = (rem(a) - rem(b)).abs();
    if d >= l {
        d - l
    } else {
        d
    }
}

/// `x` modulo `l`, in `[0, l)` up to rounding: one subtraction or addition in the common case
/// of `x` within a period of `[0, l)`, the exact remainder otherwise (the callers' margin covers
/// the difference).
#[inline(always)]
fn reduce(x: f64, l: f64) -> f64 {
    if (0.0..l).contains(&x) {
        x
    } else if x < 0.0 && x >= -l {
        (x + l).min(l.next_down())
    } else if x >= l && x < 2.0 * l {
        x - l
    } else {
        x.rem_euclid(l)
    }
}
