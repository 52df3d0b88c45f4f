//! Serde for the geometry: [`Aabb`] as `{min, max}` (checked by [`Aabb::new`]), [`Cell`] as
//! `{level, coords}` (checked by [`Cell::new`]), and [`RegionTree`] as `{extent, nodes}` (checked
//! by [`RegionTree::from_nodes`]).

use super::array;
use crate::image::RegionTree;
use crate::{Aabb, Cell, Scalar};
use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A box's corners: slices written, vectors read back.
#[derive(Serialize, Deserialize)]
struct BoxFields<V> {
    min: V,
    max: V,
}

impl<S: Scalar + Serialize, const D: usize> Serialize for Aabb<S, D> {
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        BoxFields::<&[S]> {
            min: &self.min,
            max: &self.max,
        }
        .serialize(s)
    }
}

impl<'de, S: Scalar + Deserialize<'de>, const D: usize> Deserialize<'de> for Aabb<S, D> {
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        let b = BoxFields::<Vec<S>>::deserialize(d)?;
        let (min, max) = (array("box min", &b.min)?, array("box max", &b.max)?);
        Aabb::new(min, max).map_err(|e| De::Error::custom(format!("box: {e}")))
    }
}

/// A cell's level and coordinates: a slice written, a vector read back.
#[derive(Serialize, Deserialize)]
struct CellFields<V> {
    level: u8,
    coords: V,
}

impl<const D: usize> Serialize for Cell<D> {
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        CellFields::<&[u32]> {
            level: self.level(),
            coords: &self.coords(),
        }
        .serialize(s)
    }
}

impl<'de, const D: usize> Deserialize<'de> for Cell<D> {
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        let c = CellFields::<Vec<u32>>::deserialize(d)?;
        let coords = array("cell coords", &c.coords)?;
        Cell::new(c.level, coords).ok_or_else(|| {
            De::Error::custom(format!(
                "cell: level {} (at most {}) with coordinates {coords:?} (each below 2^level)",
                c.level,
                Cell::<D>::MAX_LEVEL
            ))
        })
    }
}

/// A region tree's extent and nodes: slices written, vectors read back.
#[derive(Serialize, Deserialize)]
struct RegionFields<E, N> {
    extent: E,
    nodes: N,
}

impl<const D: usize> Serialize for RegionTree<D> {
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        RegionFields::<&[u32], &[u8]> {
            extent: &self.extent(),
            nodes: self.nodes(),
        }
        .serialize(s)
    }
}

impl<'de, const D: usize> Deserialize<'de> for RegionTree<D> {
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        let r = RegionFields::<Vec<u32>, Vec<u8>>::deserialize(d)?;
        let extent = array("region tree extent", &r.extent)?;
        RegionTree::from_nodes(extent, r.nodes)
            .map_err(|e| De::Error::custom(format!("region tree: {e}")))
    }
}
