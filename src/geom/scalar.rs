//! The coordinate trait [`Scalar`], implemented for `f32`, `f64` and the primitive integers.
//!
//! Every coordinate is compared and subdivided in `f64` (see [`crate::RootGeometry`]), so a scalar
//! only has to convert to `f64` monotonically: exactly for `f32`, `f64` and integers up to 32 bits,
//! and with rounding (but still monotonically, so never inconsistently) for 64-bit integers beyond
//! 2^53.

use core::fmt::Debug;
use num_traits::{Num, NumCast};

/// A coordinate type: `f32`, `f64`, or a primitive integer.
///
/// NaN and infinities are rejected with an error when a point enters a tree, never stored.
///
/// ```
/// use orthtree::Scalar;
/// assert!(1.5f64.is_finite_coordinate());
/// assert!(!f32::NAN.is_finite_coordinate());
/// assert!(i32::MIN.is_finite_coordinate());
/// assert_eq!(7u16.to_f64(), 7.0);
/// ```
pub trait Scalar:
    Copy + PartialOrd + Debug + Default + Send + Sync + 'static + Num + NumCast
{
    /// The value as an `f64`; monotone (a <= b implies a.to_f64() <= b.to_f64()).
    fn to_f64(self) -> f64;
    /// `false` for NaN and the infinities; always `true` for integers.
    fn is_finite_coordinate(self) -> bool;
}

macro_rules! float_scalar {
    ($($t:ty),*) => {$(
        impl Scalar for $t {
            #[inline]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[inline]
            fn is_finite_coordinate(self) -> bool {
                <$t>::is_finite(self)
            }
        }
    )*};
}

macro_rules! int_scalar {
    ($($t:ty),*) => {$(
        impl Scalar for $t {
            #[inline]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[inline]
            fn is_finite_coordinate(self) -> bool {
                true
            }
        }
    )*};
}

float_scalar!(f32, f64);
int_scalar!(i8, i16, i32, i64, u8, u16, u32, u64);

/// Checks every coordinate of `point`, and names the first bad axis.
///
/// Returns `Err(axis)` for the first axis holding NaN or an infinity.
///
/// ```
/// use orthtree::validate_point;
/// assert_eq!(validate_point(&[0.0, 1.0]), Ok(()));
/// assert_eq!(validate_point(&[0.0, f64::INFINITY]), Err(1));
/// ```
pub fn validate_point<S: Scalar, const D: usize>(point: &[S; D]) -> Result<(), usize> {
    match point.iter().position(|c| !c.is_finite_coordinate()) {
        Some(axis) => Err(axis),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conversions_are_monotone_at_the_extremes() {
        assert!(i64::MAX.to_f64() >= (i64::MAX - 1).to_f64());
        assert!(u64::MAX.to_f64() > 0.0);
        assert_eq!(f32::MAX.to_f64(), f32::MAX as f64);
        assert!(!f64::NEG_INFINITY.is_finite_coordinate());
        assert_eq!(validate_point(&[f32::NAN, 0.0]), Err(0));
    }
}
