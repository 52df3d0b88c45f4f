//! [`Aabb`]: a closed axis-aligned box in D dimensions.

use super::Scalar;

/// A closed axis-aligned box `[min, max]` in D dimensions.
///
/// ```
/// use orthtree::Aabb;
/// let b = Aabb::new([0.0, 0.0], [2.0, 1.0]).unwrap();
/// assert!(b.contains(&[2.0, 1.0])); // closed: the boundary belongs to the box
/// assert!(!b.contains(&[2.5, 0.5]));
/// assert_eq!(b.extent(0), 2.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb<S, const D: usize> {
    /// The lower corner.
    pub min: [S; D],
    /// The upper corner.
    pub max: [S; D],
}

/// Why a box was refused by [`Aabb::new`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AabbError {
    /// A coordinate on this axis is NaN or infinite.
    NonFinite {
        /// The offending axis.
        axis: usize,
    },
    /// `min > max` on this axis.
    Inverted {
        /// The offending axis.
        axis: usize,
    },
    /// A cube's side ([`crate::geom::RootGeometry::try_new`]) that is NaN, infinite or negative.
    InvalidSide {
        /// The side given (compared by its bits: NaN equals itself).
        side: super::FloatBits,
    },
    /// A corner on this axis is an integer that `f64` cannot hold exactly
    /// ([`Scalar::converts_exactly`]).
    Inexact {
        /// The offending axis.
        axis: usize,
        /// The coordinate.
        value: i128,
    },
}

impl core::fmt::Display for AabbError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            AabbError::NonFinite { axis } => {
                write!(f, "box coordinate on axis {axis} is not finite")
            }
            AabbError::Inverted { axis } => write!(f, "box has min > max on axis {axis}"),
            AabbError::InvalidSide { side } => {
                write!(f, "cube side {} is not finite and non-negative", side.get())
            }
            AabbError::Inexact { axis, value } => write!(
                f,
                "box coordinate {value} on axis {axis} {}",
                crate::error::INEXACT
            ),
        }
    }
}

impl std::error::Error for AabbError {}

impl<S: Scalar, const D: usize> Aabb<S, D> {
    /// A box from its corners; an error if a coordinate is not finite or `min > max` on an axis.
    ///
    /// # Errors
    /// [`AabbError::NonFinite`] naming the first axis with a coordinate that is not finite,
    /// [`AabbError::Inverted`] the first axis with `min > max`.
    pub fn new(min: [S; D], max: [S; D]) -> Result<Self, AabbError> {
        for axis in 0..D {
            if !min[axis].is_finite_coordinate() || !max[axis].is_finite_coordinate() {
                return Err(AabbError::NonFinite { axis });
            }
            if min[axis] > max[axis] {
                return Err(AabbError::Inverted { axis });
            }
        }
        Ok(Aabb { min, max })
    }

    /// `true` when `point` lies in the closed box.
    #[inline]
    pub fn contains(&self, point: &[S; D]) -> bool {
        (0..D).all(|a| self.min[a] <= point[a] && point[a] <= self.max[a])
    }

    /// `true` when the closed boxes share at least one point.
    #[inline]
    pub fn intersects(&self, other: &Self) -> bool {
        (0..D).all(|a| self.min[a] <= other.max[a] && other.min[a] <= self.max[a])
    }

    /// `max - min` along `axis`, computed in `f64` (so that no integer box overflows its type:
    /// `i32::MIN..=i32::MAX` is 2^32 - 1 wide); infinite when the difference of two floats
    /// exceeds `f64::MAX` (a box from `-f64::MAX` to `f64::MAX`), rounded like any `f64`
    /// subtraction.
    ///
    /// ```
    /// use orthtree::Aabb;
    /// assert_eq!(Aabb::new([i32::MIN], [i32::MAX]).unwrap().extent(0), 4294967295.0);
    /// assert_eq!(Aabb::new([-f64::MAX], [f64::MAX]).unwrap().extent(0), f64::INFINITY);
    /// ```
    #[inline]
    pub fn extent(&self, axis: usize) -> f64 {
        self.max[axis].to_f64() - self.min[axis].to_f64()
    }

    /// The box converted to `f64` coordinates exactly: an error when a corner is not finite
    /// ([`AabbError::NonFinite`]) or is an integer `f64` cannot hold ([`AabbError::Inexact`]),
    /// naming the first such axis (the check of [`crate::geom::validate_point`] on both corners).
    ///
    /// # Errors
    /// [`AabbError::NonFinite`] or [`AabbError::Inexact`], naming the first such axis.
    ///
    /// ```
    /// use orthtree::{Aabb, geom::AabbError};
    /// let b = Aabb { min: [0i64, 0], max: [1 << 53, (1 << 53) + 1] };
    /// assert_eq!(b.to_exact_f64(), Err(AabbError::Inexact { axis: 1, value: (1 << 53) + 1 }));
    /// let b = Aabb { min: [0i64, 0], max: [1 << 53, (1 << 53) + 2] };
    /// assert_eq!(b.to_exact_f64().unwrap().max[1], 2f64.powi(53) + 2.0);
    /// ```
    pub fn to_exact_f64(&self) -> Result<Aabb<f64, D>, AabbError> {
        for axis in 0..D {
            for c in [self.min[axis], self.max[axis]] {
                if !c.converts_exactly() {
                    return Err(match crate::geom::fault(c) {
                        crate::geom::Fault::NotFinite(_) => AabbError::NonFinite { axis },
                        crate::geom::Fault::Inexact(value) => AabbError::Inexact { axis, value },
                    });
                }
            }
        }
        Ok(self.to_f64())
    }

    /// The box converted to `f64` coordinates (rounded for integers `f64` cannot hold:
    /// [`Aabb::to_exact_f64`] refuses those).
    pub fn to_f64(&self) -> Aabb<f64, D> {
        Aabb {
            min: self.min.map(Scalar::to_f64),
            max: self.max.map(Scalar::to_f64),
        }
    }
}

impl<const D: usize> Aabb<f64, D> {
    /// The empty box (min above max on every axis), the start of a bounding-box fold.
    pub(crate) const fn empty() -> Self {
        Aabb {
            min: [f64::INFINITY; D],
            max: [f64::NEG_INFINITY; D],
        }
    }

    /// The tight box of `points` as `f64` (empty for no points).
    #[inline]
    pub(crate) fn around<S: Scalar>(points: &[[S; D]]) -> Self {
        let mut b = Self::empty();
        for p in points {
            b.add_point(&p.map(Scalar::to_f64));
        }
        b
    }

    /// Grows the box to hold `p`.
    #[inline]
    pub(crate) fn add_point(&mut self, p: &[f64; D]) {
        for (a, &x) in p.iter().enumerate() {
            self.min[a] = self.min[a].min(x);
            self.max[a] = self.max[a].max(x);
        }
    }

    /// Grows the box to hold `other` (nothing for an empty `other`).
    pub(crate) fn add_box(&mut self, other: &Self) {
        for a in 0..D {
            self.min[a] = self.min[a].min(other.min[a]);
            self.max[a] = self.max[a].max(other.max[a]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounding_box_folds() {
        let mut b = Aabb::<f64, 2>::empty();
        b.add_box(&Aabb::empty());
        assert!(b.min[0] > b.max[0]);
        b.add_point(&[1.0, -2.0]);
        b.add_point(&[-1.0, 3.0]);
        let mut c = Aabb::empty();
        c.add_box(&b);
        c.add_box(&Aabb::empty());
        assert_eq!((c.min, c.max), ([-1.0, -2.0], [1.0, 3.0]));
    }

    #[test]
    fn rejects_bad_boxes_naming_the_axis() {
        assert_eq!(
            Aabb::new([0.0, 1.0], [1.0, 0.0]),
            Err(AabbError::Inverted { axis: 1 })
        );
        assert_eq!(
            Aabb::new([f64::NAN, 0.0], [1.0, 1.0]),
            Err(AabbError::NonFinite { axis: 0 })
        );
        let b = Aabb::new([0i32; 3], [4; 3]).unwrap();
        assert!(b.intersects(&Aabb::new([4; 3], [5; 3]).unwrap()));
        assert!(!b.intersects(&Aabb::new([5; 3], [6; 3]).unwrap()));
        assert_eq!(b.to_f64().max, [4.0; 3]);
    }
}
