//! Serde for [`CompressedTree`] and [`SkipQuadtree`].
//!
//! A compressed tree is stored as its root cube (`half_lo`, `half_side`), its domain, its points
//! (one flat sequence) and items in slot order, and `order`, the slots in the order the queries
//! read them (deep Morton order, duplicates in their leaf's list order). Its nodes are not
//! stored but rebuilt in O(n) by `CompressedTree::from_slots` (the tree is canonical, so the
//! points and their order decide it), after every point is checked (finite, exact, in the
//! domain) and `order` is checked to be a permutation in Morton order; then `validate` runs.
//!
//! A skip quadtree is `{seed, base}`, `base` a compressed tree as above: its levels are a
//! function of the stored keys and the seed ([`SkipQuadtree::with_seed`]), so they are rebuilt
//! (expected O(n)) and checked by `validate`.

use super::array;
use super::points::flat_points;
use crate::compressed::SkipQuadtree;
use crate::query::{PointSet, SpatialIndex};
use crate::{Aabb, CompressedTree, Scalar};
use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A compressed tree's root cube, domain, points, items and order: sequences of `f64`, of
/// coordinates, of items and of slots; slices written, vectors read back.
#[derive(Serialize, Deserialize)]
struct CompressedFields<F, P, I, O> {
    half_lo: F,
    half_side: f64,
    domain_min: F,
    domain_max: F,
    points: P,
    items: I,
    order: O,
}

type CompressedRef<'a, S, T> = CompressedFields<&'a [f64], &'a [S], &'a [T], &'a [u32]>;
type CompressedOwned<S, T> = CompressedFields<Vec<f64>, Vec<S>, Vec<T>, Vec<u32>>;

impl<'a, S: Scalar, T> CompressedRef<'a, S, T> {
    fn new<const D: usize>(t: &'a CompressedTree<S, T, D>, half_lo: &'a [f64; D]) -> Self {
        CompressedRef {
            half_lo,
            half_side: t.geometry().halves().1,
            domain_min: &t.domain().min,
            domain_max: &t.domain().max,
            points: CompressedTree::points(t).as_flattened(),
            items: t.items(),
            order: t.index().payloads(),
        }
    }
}

impl<S: Scalar, T> CompressedOwned<S, T> {
    fn into_tree<E: serde::de::Error, const D: usize>(self) -> Result<CompressedTree<S, T, D>, E> {
        let domain = Aabb {
            min: array("compressed tree domain_min", &self.domain_min)?,
            max: array("compressed tree domain_max", &self.domain_max)?,
        };
        CompressedTree::from_slots(
            array("compressed tree half_lo", &self.half_lo)?,
            self.half_side,
            domain,
            flat_points::<E, S, D>("compressed tree", self.points)?,
            self.items,
            self.order,
        )
        .map_err(|e| E::custom(format!("compressed tree: {e}")))
    }
}

impl<S: Scalar + Serialize, T: Serialize, const D: usize> Serialize for CompressedTree<S, T, D> {
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        let half_lo = self.geometry().halves().0;
        CompressedRef::new(self, &half_lo).serialize(s)
    }
}

impl<'de, S, T, const D: usize> Deserialize<'de> for CompressedTree<S, T, D>
where
    S: Scalar + Deserialize<'de>,
    T: Deserialize<'de>,
{
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        CompressedOwned::<S, T>::deserialize(d)?.into_tree::<De::Error, D>()
    }
}

/// A skip quadtree's seed and base tree.
#[derive(Serialize, Deserialize)]
struct SkipFields<B> {
    seed: u64,
    base: B,
}

impl<S: Scalar + Serialize, T: Serialize, const D: usize> Serialize for SkipQuadtree<S, T, D> {
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        let half_lo = self.base().geometry().halves().0;
        SkipFields {
            seed: self.seed(),
            base: CompressedRef::new(self.base(), &half_lo),
        }
        .serialize(s)
    }
}

impl<'de, S, T, const D: usize> Deserialize<'de> for SkipQuadtree<S, T, D>
where
    S: Scalar + Deserialize<'de>,
    T: Deserialize<'de>,
{
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        let o = SkipFields::<CompressedOwned<S, T>>::deserialize(d)?;
        let skip = SkipQuadtree::with_seed(o.base.into_tree::<De::Error, D>()?, o.seed);
        skip.validate()
            .map_err(|e| De::Error::custom(format!("skip quadtree: {e}")))?;
        Ok(skip)
    }
}
