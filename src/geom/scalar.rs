//! The coordinate trait [`Scalar`], implemented for `f32`, `f64` and the primitive integers, and
//! the one check every coordinate passes before it enters a tree or a query.
//!
//! Every coordinate is compared and subdivided in `f64` (see [`crate::geom::RootGeometry`]). That is
//! exact for `f32`, `f64` and integers up to 32 bits; a 64-bit integer is exact only when `f64`
//! holds it (every value up to 2^53 in magnitude, and beyond that the multiples of a large enough
//! power of two: `2^53 + 2`, `u64::MAX - 2047`, `i64::MIN`, but not `2^53 + 1`, `u64::MAX` or
//! `i64::MAX`). [`Scalar::converts_exactly`] tells them apart, and [`validate_point`] (the check
//! behind every build, insert, query point, query box, ball centre and root box) refuses a
//! coordinate that does not convert exactly, so that no two distinct stored or queried values
//! ever meet as the same `f64`. Comparisons, cell membership, keys and box queries are therefore
//! exact for every accepted coordinate; distances (differences, squares and sums) are computed
//! in `f64` and round like any float arithmetic.

use core::fmt::Debug;
use num_traits::{Num, NumCast, ToPrimitive};

/// A coordinate type: `f32`, `f64`, or a primitive integer.
///
/// A coordinate enters a tree or a query only when [`Scalar::converts_exactly`] holds: NaN and
/// the infinities are refused, and so is a 64-bit integer that `f64` cannot hold exactly (above
/// 2^53 in magnitude and not a multiple of the spacing of `f64`s there), each with an error
/// naming the axis and the value. Accepted coordinates are compared exactly; distances between
/// them are `f64` arithmetic and round (two integer points 2^60 apart along one axis have an
/// exact squared distance of 2^120, but one 2^60 + 2^8 away has its squared distance rounded).
///
/// ```
/// use orthtree::Scalar;
/// assert!(1.5f64.is_finite_coordinate());
/// assert!(!f32::NAN.is_finite_coordinate());
/// assert!(i32::MIN.is_finite_coordinate());
/// assert_eq!(7u16.to_f64(), 7.0);
/// // 2^53 + 1 has no f64: refused; 2^53 + 2 has one
/// assert!(!((1i64 << 53) + 1).converts_exactly());
/// assert!(((1i64 << 53) + 2).converts_exactly());
/// assert!(!u64::MAX.converts_exactly());
/// assert!((u64::MAX - 2047).converts_exactly());
/// assert!(!f64::INFINITY.converts_exactly());
/// ```
pub trait Scalar:
    Copy + PartialOrd + Debug + Default + Send + Sync + 'static + Num + NumCast
{
    /// The value as an `f64`; monotone (a <= b implies a.to_f64() <= b.to_f64()), and exact when
    /// [`Scalar::converts_exactly`] holds.
    fn to_f64(self) -> f64;
    /// `false` for NaN and the infinities; always `true` for integers.
    fn is_finite_coordinate(self) -> bool;
    /// `true` when the value is finite and [`Scalar::to_f64`] holds it exactly: the condition
    /// for entering a tree or a query. Always `true` for integers of at most 32 bits; for
    /// 64-bit integers, `true` up to 2^53 in magnitude and for the multiples of the `f64`
    /// spacing beyond.
    fn converts_exactly(self) -> bool;
    /// The value as an `i128` when it is an integer (for error messages that must show an
    /// integer `f64` cannot hold); `None` for floats.
    fn integer_value(self) -> Option<i128>;
}

/// Implements [`Scalar`] for each type, with the bodies of the three methods that tell floats
/// from integers (each a closure over the value).
macro_rules! scalar {
    ($finite:expr, $exact:expr, $integer:expr; $($t:ty),*) => {$(
        impl Scalar for $t {
            #[inline]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[inline]
            fn is_finite_coordinate(self) -> bool {
                ($finite)(self)
            }
            #[inline]
            fn converts_exactly(self) -> bool {
                ($exact)(self)
            }
            #[inline]
            fn integer_value(self) -> Option<i128> {
                ($integer)(self)
            }
        }
    )*};
}

// f32 -> f64 is exact for every finite value.
scalar!(|x: Self| x.is_finite(), |x: Self| x.is_finite(), |_| None; f32, f64);
// Back through i128, which holds every f64 these types round to (up to 2^64): a cast back to the
// type itself would saturate, taking i64::MAX (which rounds to 2^63) for exact.
scalar!(
    |_| true,
    |x: Self| (x as f64) as i128 == x as i128,
    |x: Self| x.to_i128();
    i8, i16, i32, i64, u8, u16, u32, u64
);

/// Checks every coordinate of `point` with [`Scalar::converts_exactly`], and names the first bad
/// axis: the one point check of the crate, behind every error for a point, a query point, a
/// query box, a ball centre and a root box.
///
/// Returns `Err(axis)` for the first axis holding NaN, an infinity or an integer `f64` cannot
/// hold exactly.
///
/// # Errors
/// The first axis holding NaN, an infinity or an integer `f64` cannot hold exactly.
///
/// # Complexity
/// O(D).
///
/// ```
/// use orthtree::geom::validate_point;
/// assert_eq!(validate_point(&[0.0, 1.0]), Ok(()));
/// assert_eq!(validate_point(&[0.0, f64::INFINITY]), Err(1));
/// assert_eq!(validate_point(&[1i64 << 53, (1 << 53) + 1]), Err(1));
/// ```
pub fn validate_point<S: Scalar, const D: usize>(point: &[S; D]) -> Result<(), usize> {
    (point.iter().position(|c| !c.converts_exactly())).map_or(Ok(()), Err)
}

/// Why a coordinate failed [`validate_point`], for the callers' own error types.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Fault {
    /// NaN or an infinity (the value as `f64`).
    NotFinite(f64),
    /// An integer `f64` cannot hold exactly.
    Inexact(i128),
}

/// `point` in `f64`, exactly, or the first bad axis and why ([`validate_point`]).
#[inline]
pub(crate) fn exact_point<S: Scalar, const D: usize>(
    point: &[S; D],
) -> Result<[f64; D], (usize, Fault)> {
    match validate_point(point) {
        Ok(()) => Ok(point.map(Scalar::to_f64)),
        Err(axis) => Err((axis, fault(point[axis]))),
    }
}

/// The point check every tree and query shares: `point` in `f64` exactly, inside the closed
/// box `domain` or outside it (first on some axis), or the first axis whose coordinate is no
/// point coordinate at all and why.
#[inline]
pub(crate) fn check_point<S: Scalar, const D: usize>(
    point: &[S; D],
    domain: &crate::geom::Aabb<f64, D>,
) -> Result<Checked<D>, (usize, Fault)> {
    let p = exact_point(point)?;
    let outside = (0..D).find(|&a| !(domain.min[a] <= p[a] && p[a] <= domain.max[a]));
    Ok(outside.map_or(Checked::Inside(p), |axis| Checked::Outside(axis, p)))
}

/// A point that passed [`validate_point`], placed against a domain ([`check_point`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Checked<const D: usize> {
    /// Inside the closed box; the point in `f64`.
    Inside([f64; D]),
    /// Outside it, first on the axis given; the point in `f64`.
    Outside(usize, [f64; D]),
}

/// Why `x` fails [`Scalar::converts_exactly`] (taken to fail it).
pub(crate) fn fault<S: Scalar>(x: S) -> Fault {
    match x.integer_value() {
        Some(v) if x.is_finite_coordinate() => Fault::Inexact(v),
        _ => Fault::NotFinite(x.to_f64()),
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

    /// Exactness against the definition (the f64 names one integer only), around every power
    /// of two and at the extremes of each 64-bit type.
    #[test]
    fn exact_conversion_matches_the_round_trip() {
        let exact_i = |x: i64| {
            let f = x as f64;
            f >= -(2f64.powi(63)) && f < 2f64.powi(63) && f as i64 == x
        };
        let exact_u = |x: u64| {
            let f = x as f64;
            f < 2f64.powi(64) && f as u64 == x
        };
        for e in 0..64u32 {
            for d in [-3i64, -2, -1, 0, 1, 2, 3] {
                let x = (1u64 << e).wrapping_add(d as u64);
                assert_eq!(x.converts_exactly(), exact_u(x), "{x}");
                let y = x as i64;
                assert_eq!(y.converts_exactly(), exact_i(y), "{y}");
                assert_eq!(
                    y.wrapping_neg().converts_exactly(),
                    exact_i(y.wrapping_neg())
                );
            }
        }
        for x in [
            i64::MIN,
            i64::MIN + 1,
            i64::MAX,
            i64::MAX - 511,
            i64::MAX - 1023,
        ] {
            assert_eq!(x.converts_exactly(), exact_i(x), "{x}");
        }
        assert!(i64::MIN.converts_exactly());
        assert!(!i64::MAX.converts_exactly());
        assert!((i64::MAX - 1023).converts_exactly());
        assert!(!u64::MAX.converts_exactly());
        assert!(u32::MAX.converts_exactly() && i32::MIN.converts_exactly());
        assert_eq!(fault(u64::MAX), Fault::Inexact(u64::MAX as i128));
        assert!(matches!(fault(f64::NAN), Fault::NotFinite(v) if v.is_nan()));
        assert_eq!(
            exact_point(&[1u64 << 60, (1 << 60) + 1]),
            Err((1, Fault::Inexact((1i128 << 60) + 1)))
        );
        assert_eq!(exact_point(&[1u64 << 60, 7]), Ok([2f64.powi(60), 7.0]));
    }
}
