//! Serde for [`PointTree`]: its stored arrays and settings (`raw.rs` in `points`), points as one
//! flat sequence, read back through `PointTree::from_parts`, which checks the settings, the
//! topology and then the tree's own `validate`; nothing is sorted or rebuilt.

use super::array;
use super::tree::{TreeOwned, TreeRef};
use crate::points::PointTreeParts;
use crate::tree::BalanceOptions;
use crate::{Aabb, Connectivity, PointTree, Scalar};
use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A point tree's arrays and settings: `Tr` the topology's, then sequences of `f64`, of
/// coordinates, of items and of run ends; slices written, vectors read back.
#[derive(Serialize, Deserialize)]
struct PointTreeFields<Tr, F, P, I, R> {
    tree: Tr,
    half_lo: F,
    half_side: f64,
    domain_min: F,
    domain_max: F,
    points: P,
    items: I,
    run_ends: R,
    bucket_size: u64,
    max_depth: u8,
    balance: Option<(Connectivity, u8)>,
}

type PointTreeRef<'a, S, T> = PointTreeFields<TreeRef<'a>, &'a [f64], &'a [S], &'a [T], &'a [u32]>;
type PointTreeOwned<S, T> = PointTreeFields<TreeOwned, Vec<f64>, Vec<S>, Vec<T>, Vec<u32>>;

impl<S: Scalar + Serialize, T: Serialize, const D: usize> Serialize for PointTree<S, T, D> {
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        let v = self.view();
        PointTreeRef {
            tree: TreeRef::new::<D>(v.tree),
            half_lo: &v.half_lo,
            half_side: v.half_side,
            domain_min: &v.domain.min,
            domain_max: &v.domain.max,
            points: v.points.as_flattened(),
            items: v.items,
            run_ends: v.run_ends,
            bucket_size: v.bucket_size as u64,
            max_depth: v.max_depth,
            balance: v
                .balanced
                .map(|b| (b.connectivity, b.max_level_difference())),
        }
        .serialize(s)
    }
}

impl<'de, S, T, const D: usize> Deserialize<'de> for PointTree<S, T, D>
where
    S: Scalar + Deserialize<'de>,
    T: Deserialize<'de>,
{
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        let o = PointTreeOwned::<S, T>::deserialize(d)?;
        let custom = |m: String| De::Error::custom(format!("point tree: {m}"));
        let points = flat_points::<De::Error, S, D>("point tree", o.points)?;
        let balanced = o
            .balance
            .map(|(c, k)| BalanceOptions::new(c).with_max_level_difference(k))
            .transpose()
            .map_err(|e| custom(e.to_string()))?;
        let parts = PointTreeParts {
            tree: o.tree.into_raw::<De::Error, D>()?,
            half_lo: array("half_lo", &o.half_lo)?,
            half_side: o.half_side,
            domain: Aabb {
                min: array("domain_min", &o.domain_min)?,
                max: array("domain_max", &o.domain_max)?,
            },
            points,
            items: o.items,
            run_ends: o.run_ends,
            bucket_size: usize::try_from(o.bucket_size)
                .map_err(|_| custom(format!("bucket size {} is not a usize", o.bucket_size)))?,
            max_depth: o.max_depth,
            balanced,
        };
        PointTree::from_parts(parts).map_err(|e| custom(e.to_string()))
    }
}

/// `flat` (n D coordinates) as n points, or an error naming `what` and the count.
pub(super) fn flat_points<E: serde::de::Error, S: Copy, const D: usize>(
    what: &str,
    flat: Vec<S>,
) -> Result<Vec<[S; D]>, E> {
    if !flat.len().is_multiple_of(D) {
        return Err(E::custom(format!(
            "{what}: {} coordinates are not whole points of {D}",
            flat.len()
        )));
    }
    Ok(flat
        .chunks_exact(D)
        .map(|c| core::array::from_fn(|a| c[a]))
        .collect())
}
