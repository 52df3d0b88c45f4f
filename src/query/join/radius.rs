//! Radii of the radius joins: whether a pair at exactly the radius counts ([`Boundary`]), and
//! the checks of the radii a caller gives.
//!
//! A pair is within radius `r` when its squared Euclidean distance `d`, computed in `f64` as by
//! every query of [`crate::query`], satisfies `d <= r * r` ([`Boundary::Inclusive`]) or
//! `d < r * r` ([`Boundary::Exclusive`]), with `r * r` rounded to `f64` (so a radius beyond
//! about 1.3e154 takes in every pair, an infinite one too).

use crate::query::{check_radius, QueryError};

/// Whether a pair at distance exactly `r` is within radius `r`.
///
/// ```
/// use orthtree::prelude::*;
/// use orthtree::{query::Boundary, Quadtree};
/// let t = Quadtree::new(&[([0.0, 0.0], 'a'), ([3.0, 4.0], 'b')]).unwrap();
/// assert_eq!(t.count_pairs_within(&[5.0], Boundary::Inclusive).unwrap(), [1]);
/// assert_eq!(t.count_pairs_within(&[5.0], Boundary::Exclusive).unwrap(), [0]);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Boundary {
    /// Within `r` means at distance `<= r` (scipy's `cKDTree` default).
    #[default]
    Inclusive,
    /// Within `r` means at distance `< r` (kiddo's exclusive boundary).
    Exclusive,
}

impl Boundary {
    /// Whether squared distance `d` is within squared radius `r2`.
    #[inline(always)]
    pub(crate) fn admits(self, d: f64, r2: f64) -> bool {
        match self {
            Boundary::Inclusive => d <= r2,
            Boundary::Exclusive => d < r2,
        }
    }
}

impl Boundary {
    /// The largest squared distance within squared radius `r2` as a bound to compare with
    /// `<=`: `r2` itself when inclusive, the float just below it when exclusive (`d < r2` is
    /// `d <= r2.next_down()` for every `f64` but NaN). One comparison, the same for both
    /// boundaries, lets the kernels test distances without a branch on the boundary.
    #[inline(always)]
    pub(crate) fn limit(self, r2: f64) -> f64 {
        match self {
            Boundary::Inclusive => r2,
            Boundary::Exclusive => r2.next_down(),
        }
    }
}

/// The squared radius of a valid radius: not negative, not NaN.
pub(crate) fn squared_radius(r: f64) -> Result<f64, QueryError> {
    check_radius(r).map(|r| r * r)
}

/// The squared radii of a list of valid radii in non-decreasing order; the first bad radius, or
/// the first position where the order breaks, otherwise.
pub(crate) fn squared_radii(radii: &[f64]) -> Result<Vec<f64>, QueryError> {
    let mut out = Vec::with_capacity(radii.len());
    for (i, &r) in radii.iter().enumerate() {
        out.push(squared_radius(r)?);
        if i > 0 && r < radii[i - 1] {
            return Err(QueryError::UnsortedRadii { index: i });
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::Boundary;

    #[test]
    fn limit_agrees_with_admits() {
        let values = [
            0.0,
            f64::from_bits(1),
            f64::MIN_POSITIVE,
            0.5,
            1.0,
            1.0f64.next_up(),
            2.0,
            f64::MAX,
            f64::INFINITY,
        ];
        for b in [Boundary::Inclusive, Boundary::Exclusive] {
            for &r2 in &values {
                for &d in &values {
                    assert_eq!(d <= b.limit(r2), b.admits(d, r2), "{b:?} d {d} r2 {r2}");
                }
            }
        }
    }
}
