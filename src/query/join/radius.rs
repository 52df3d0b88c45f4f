//! Radii of the radius joins: whether a pair at exactly the radius counts ([`Boundary`]), and
//! the checks of the radii a caller gives.
//!
//! A pair is within radius `r` when its squared Euclidean distance `d`, computed in `f64` as by
//! every query of [`crate::query`], satisfies `d <= r * r` ([`Boundary::Inclusive`]) or
//! `d < r * r` ([`Boundary::Exclusive`]), with `r * r` rounded to `f64` (so a radius beyond
//! about 1.3e154 takes in every pair, an infinite one too).

use crate::query::QueryError;

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

/// The squared radius of a valid radius: not negative, not NaN.
pub(crate) fn squared_radius(r: f64) -> Result<f64, QueryError> {
    if r >= 0.0 {
        Ok(r * r)
    } else {
        Err(QueryError::InvalidRadius { radius: r.into() })
    }
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
