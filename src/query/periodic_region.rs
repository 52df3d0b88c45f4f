//! Regions on a [`Torus`]: the minimum-image ball [`PeriodicBall`] and the box that may wrap
//! across the period's faces [`PeriodicBox`], as [`Region`]s, so that the range engine of
//! [`crate::query`] prunes with them as with plain boxes and balls.
//!
//! The ball's cell test bounds each axis's minimum-image offset over the cell from below and
//! above ([`Torus`]'s bounds, which carry a margin of a few roundings), then compares the sums
//! of squares with `radius^2` as the point test does: a cell called `Inside` or `Outside` is so
//! for every point the point test sees. A radius of half a period or more along an axis covers
//! that axis, and each point is reported once (the engine visits each stored point once).
//!
//! The box is, along each wrapping axis, the arc of the circle from its lower bound up to its
//! upper bound (so `lo > hi` wraps across the faces), and the whole axis when `hi - lo` is at
//! least the period. Its tests compare coordinates only, so they agree exactly.

// Loops over axes index the point, the box's min and max together; an index reads best.
#![allow(clippy::needless_range_loop)]

use super::periodic::Torus;
use super::region::{range_relation, Region, Relation};
use super::{check_radius, query_point, QueryError};
use crate::geom::Aabb;

/// The closed ball of points at minimum-image Euclidean distance at most `radius` from `center`
/// on a [`Torus`]: the sum of squared per-axis offsets is at most `radius^2` (in `f64`; an
/// infinite radius holds everything, 0 only the centre and its images).
///
/// ```
/// use orthtree::query::{PeriodicBall, Region, Torus};
/// let t = Torus::wrapping([0.0; 2], [10.0; 2]).unwrap();
/// let b = PeriodicBall::new(t, [0.5, 0.5], 1.0).unwrap();
/// assert!(b.contains(&[9.5, 0.5])); // across the face
/// assert!(!b.contains(&[5.0, 5.0]));
/// let all = PeriodicBall::new(t, [0.5, 0.5], 7.1).unwrap(); // beyond the half diagonal
/// assert!(all.contains(&[5.5, 5.5]));
/// assert!(PeriodicBall::new(t, [0.0, 0.0], -1.0).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PeriodicBall<const D: usize> {
    torus: Torus<D>,
    center: [f64; D],
    radius: f64,
}

impl<const D: usize> PeriodicBall<D> {
    /// The ball on `torus`; the centre is wrapped into the period box.
    ///
    /// # Errors
    /// [`QueryError::NotFinite`] for a non-finite centre (naming the axis),
    /// [`QueryError::InvalidRadius`] for a negative or NaN radius.
    pub fn new(torus: Torus<D>, center: [f64; D], radius: f64) -> Result<Self, QueryError> {
        query_point(&center)?;
        check_radius(radius)?;
        // Every coordinate is finite now: wrapping cannot fail.
        let center = torus.wrap(&center).expect("a finite centre wraps");
        Ok(PeriodicBall {
            torus,
            center,
            radius,
        })
    }

    /// The centre, in the period box.
    pub fn center(&self) -> &[f64; D] {
        &self.center
    }

    /// The radius.
    pub fn radius(&self) -> f64 {
        self.radius
    }
}

impl<const D: usize> Region<D> for PeriodicBall<D> {
    #[inline]
    fn classify(&self, cell: &Aabb<f64, D>) -> Relation {
        if self.radius == f64::INFINITY {
            return Relation::Inside;
        }
        let r2 = self.radius * self.radius;
        let (mut near, mut far) = (0.0, 0.0);
        for a in 0..D {
            let (n, f) = self
                .torus
                .offset_range(a, self.center[a], cell.min[a], cell.max[a]);
            near += n * n;
            far += f * f;
        }
        range_relation(near, far, r2)
    }
    #[inline]
    fn contains(&self, p: &[f64; D]) -> bool {
        if self.radius == f64::INFINITY {
            return true;
        }
        let mut d2 = 0.0;
        for a in 0..D {
            let d = self.torus.offset(a, p[a], self.center[a]);
            d2 += d * d;
        }
        d2 <= self.radius * self.radius
    }
}

/// One axis of a [`PeriodicBox`].
#[derive(Clone, Copy, Debug, PartialEq)]
enum Span {
    /// Every coordinate.
    Full,
    /// `lo <= x <= hi`.
    Interval(f64, f64),
    /// `x >= lo` or `x <= hi`: the arc across the faces.
    Across(f64, f64),
}

/// A closed box on a [`Torus`] that may wrap across the period's faces: along a wrapping axis,
/// the arc from `lo` up to `hi` (both wrapped into the period box first), so `lo > hi` means
/// the box runs from `lo` through the upper face to `hi`; `hi - lo` of a period or more (or an
/// infinite bound) takes the whole axis. Along an ordinary axis it is the plain closed interval.
///
/// Only points inside the period box on every wrapping axis belong to it: build the tree from
/// points brought there by [`Torus::prepare`].
///
/// ```
/// use orthtree::query::{PeriodicBox, Region, Torus};
/// let t = Torus::wrapping([0.0; 2], [10.0; 2]).unwrap();
/// let b = PeriodicBox::new(t, [9.0, 2.0], [1.0, 3.0]).unwrap(); // wraps along x
/// assert!(b.contains(&[9.5, 2.5]) && b.contains(&[0.5, 2.5]));
/// assert!(!b.contains(&[5.0, 2.5]));
/// let same = PeriodicBox::new(t, [9.0, 2.0], [11.0, 3.0]).unwrap(); // 9 to 11 = 9 to 1
/// assert!(same.contains(&[0.5, 2.5]) && !same.contains(&[5.0, 2.5]));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PeriodicBox<const D: usize> {
    torus: Torus<D>,
    spans: [Span; D],
}

impl<const D: usize> PeriodicBox<D> {
    /// The box from `lo` to `hi` on `torus`.
    ///
    /// # Errors
    /// [`QueryError::NanBound`] naming the first axis with a NaN bound.
    pub fn new(torus: Torus<D>, lo: [f64; D], hi: [f64; D]) -> Result<Self, QueryError> {
        let mut spans = [Span::Full; D];
        for axis in 0..D {
            let (a, b) = (lo[axis], hi[axis]);
            if a.is_nan() || b.is_nan() {
                return Err(QueryError::NanBound { axis });
            }
            spans[axis] = if !torus.wraps()[axis] {
                Span::Interval(a, b)
            } else if !(a.is_finite() && b.is_finite()) || b - a >= torus.period(axis) {
                Span::Full
            } else {
                let (a, b) = (torus.wrap_axis(axis, a), torus.wrap_axis(axis, b));
                if a <= b {
                    Span::Interval(a, b)
                } else {
                    Span::Across(a, b)
                }
            };
        }
        Ok(PeriodicBox { torus, spans })
    }
}

impl<const D: usize> Region<D> for PeriodicBox<D> {
    #[inline]
    fn classify(&self, cell: &Aabb<f64, D>) -> Relation {
        let mut inside = true;
        for a in 0..D {
            let (mut c0, mut c1) = (cell.min[a], cell.max[a]);
            let wraps = self.torus.wraps()[a];
            if wraps {
                // Only points of [plo, phi) belong: clip the cell to it.
                let (plo, phi) = (self.torus.lo()[a], self.torus.hi()[a]);
                if c1 < plo || c0 >= phi {
                    return Relation::Outside;
                }
                inside &= plo <= c0 && c1 < phi;
                c0 = c0.max(plo);
                c1 = c1.min(phi);
            }
            match self.spans[a] {
                Span::Full => {}
                Span::Interval(lo, hi) => {
                    if c1 < lo || c0 > hi {
                        return Relation::Outside;
                    }
                    inside &= lo <= c0 && c1 <= hi;
                }
                Span::Across(lo, hi) => {
                    if c0 > hi && c1 < lo {
                        return Relation::Outside;
                    }
                    inside &= c0 >= lo || c1 <= hi;
                }
            }
        }
        if inside {
            Relation::Inside
        } else {
            Relation::Crossing
        }
    }
    #[inline]
    fn contains(&self, p: &[f64; D]) -> bool {
        (0..D).all(|a| {
            let x = p[a];
            self.torus.in_period(a, x)
                && match self.spans[a] {
                    Span::Full => true,
                    Span::Interval(lo, hi) => lo <= x && x <= hi,
                    Span::Across(lo, hi) => x >= lo || x <= hi,
                }
        })
    }
}
