//! Serde for the small values users keep in a configuration: [`Torus`] as `{lo, hi, wraps}`
//! (read back through [`Torus::new`], which checks every wrapping axis's period) and
//! [`BalanceOptions`] as `{connectivity, max_level_difference}` (read back through
//! [`BalanceOptions::with_max_level_difference`], which checks the range). The metrics
//! ([`SquaredEuclidean`](crate::query::SquaredEuclidean),
//! [`Manhattan`](crate::query::Manhattan), [`Chebyshev`](crate::query::Chebyshev)), their
//! periodic form [`MinImage`](crate::query::MinImage) and
//! [`OutsidePoints`](crate::query::OutsidePoints) derive both traits (a `MinImage`'s torus goes
//! through the same check).
//!
//! A torus's bounds on an axis that does not wrap are ignored and may be infinite, which JSON
//! cannot hold: a bound that is not finite is written as `null` and read back as `-inf` (lower)
//! or `+inf` (upper), and refused on a wrapping axis.

use super::array;
use crate::query::Torus;
use crate::tree::BalanceOptions;
use crate::Connectivity;
use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A torus's bounds (`None` where not finite) and wrapping axes: a slice written, a vector
/// read back.
#[derive(Serialize, Deserialize)]
struct TorusFields<W> {
    lo: Vec<Option<f64>>,
    hi: Vec<Option<f64>>,
    wraps: W,
}

impl<const D: usize> Serialize for Torus<D> {
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        let finite = |v: &[f64; D]| v.iter().map(|x| x.is_finite().then_some(*x)).collect();
        TorusFields::<&[bool]> {
            lo: finite(self.lo()),
            hi: finite(self.hi()),
            wraps: self.wraps(),
        }
        .serialize(s)
    }
}

impl<'de, const D: usize> Deserialize<'de> for Torus<D> {
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        let o = TorusFields::<Vec<bool>>::deserialize(d)?;
        let lo: [Option<f64>; D] = array("torus lo", &o.lo)?;
        let hi: [Option<f64>; D] = array("torus hi", &o.hi)?;
        let wraps: [bool; D] = array("torus wraps", &o.wraps)?;
        if let Some(axis) = (0..D).find(|&a| wraps[a] && (lo[a].is_none() || hi[a].is_none())) {
            return Err(De::Error::custom(format!(
                "torus: axis {axis} wraps but a bound is null (a period needs finite bounds)"
            )));
        }
        let lo = lo.map(|x| x.unwrap_or(f64::NEG_INFINITY));
        let hi = hi.map(|x| x.unwrap_or(f64::INFINITY));
        Torus::new(lo, hi, wraps).map_err(|e| De::Error::custom(format!("torus: {e}")))
    }
}

#[derive(Serialize, Deserialize)]
struct BalanceShadow {
    connectivity: Connectivity,
    max_level_difference: u8,
}

impl Serialize for BalanceOptions {
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        BalanceShadow {
            connectivity: self.connectivity,
            max_level_difference: self.max_level_difference(),
        }
        .serialize(s)
    }
}

impl<'de> Deserialize<'de> for BalanceOptions {
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        let o = BalanceShadow::deserialize(d)?;
        BalanceOptions::new(o.connectivity)
            .with_max_level_difference(o.max_level_difference)
            .map_err(|e| De::Error::custom(format!("balance options: {e}")))
    }
}
