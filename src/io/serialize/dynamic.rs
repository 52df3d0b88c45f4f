//! Serde for [`DynamicPointTree`]: its stored arrays and settings (`parts.rs` in
//! `points/dynamic`): the topology, the root cube and domain, per node `[count, chunk start,
//! chunk size]`, the chunk array (points as one flat sequence, and the item slot of each entry,
//! `4294967295` for free space) and the items in slot order. Read back through
//! `DynamicPointTree::from_parts`, which checks the settings, the topology, every count and chunk
//! and then the tree's own `validate`; nothing is sorted or moved, so the tree read back answers
//! every query as the one written, ties included.

use super::array;
use super::points::flat_points;
use super::tree::{TreeOwned, TreeRef};
use crate::points::DynamicParts;
use crate::{Aabb, DynamicPointTree, Scalar};
use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A dynamic tree's arrays and settings: `Tr` the topology's, then sequences of `f64`, of node
/// records, of coordinates, of slots and of items; slices written, vectors read back.
#[derive(Serialize, Deserialize)]
struct DynamicFields<Tr, F, N, P, U, I> {
    tree: Tr,
    half_lo: F,
    half_side: f64,
    domain_min: F,
    domain_max: F,
    bucket_size: u64,
    max_depth: u8,
    nodes: N,
    points: P,
    slots: U,
    items: I,
}

type DynamicRef<'a, S, T> =
    DynamicFields<TreeRef<'a>, &'a [f64], &'a [[u32; 3]], &'a [S], &'a [u32], &'a [T]>;
type DynamicOwned<S, T> =
    DynamicFields<TreeOwned, Vec<f64>, Vec<[u32; 3]>, Vec<S>, Vec<u32>, Vec<T>>;

impl<S: Scalar + Serialize, T: Serialize, const D: usize> Serialize for DynamicPointTree<S, T, D> {
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        let v = self.view();
        DynamicRef {
            tree: TreeRef::new::<D>(v.tree),
            half_lo: &v.half_lo,
            half_side: v.half_side,
            domain_min: &v.domain.min,
            domain_max: &v.domain.max,
            bucket_size: v.bucket_size as u64,
            max_depth: v.max_depth,
            nodes: &v.nodes,
            points: v.points.as_flattened(),
            slots: v.slots,
            items: v.items,
        }
        .serialize(s)
    }
}

impl<'de, S, T, const D: usize> Deserialize<'de> for DynamicPointTree<S, T, D>
where
    S: Scalar + Deserialize<'de>,
    T: Deserialize<'de>,
{
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        let o = DynamicOwned::<S, T>::deserialize(d)?;
        let custom = |m: String| De::Error::custom(format!("dynamic point tree: {m}"));
        let parts = DynamicParts {
            tree: o.tree.into_raw::<De::Error, D>()?,
            half_lo: array("half_lo", &o.half_lo)?,
            half_side: o.half_side,
            domain: Aabb {
                min: array("domain_min", &o.domain_min)?,
                max: array("domain_max", &o.domain_max)?,
            },
            bucket_size: usize::try_from(o.bucket_size)
                .map_err(|_| custom(format!("bucket size {} is not a usize", o.bucket_size)))?,
            max_depth: o.max_depth,
            nodes: o.nodes,
            points: flat_points::<De::Error, S, D>("dynamic point tree", o.points)?,
            slots: o.slots,
            items: o.items,
        };
        DynamicPointTree::from_parts(parts).map_err(|e| custom(e.to_string()))
    }
}
