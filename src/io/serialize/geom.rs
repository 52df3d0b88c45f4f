//! Serde for the geometry: [`Aabb`] as `{min, max}` (checked by [`Aabb::new`]), [`Cell`] as
//! `{level, coords}` (checked by [`Cell::new`]), and [`RegionTree`] as `{extent, nodes}` (checked
//! by [`RegionTree::from_nodes`]).

use super::array;
use crate::image::RegionTree;
use crate::{Aabb, Cell, Scalar};
use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

#[derive(Serialize)]
struct BoxRef<'a, S> {
    min: &'a [S],
    max: &'a [S],
}

#[derive(Deserialize)]
struct BoxOwned<S> {
    min: Vec<S>,
    max: Vec<S>,
}

impl<S: Scalar + Serialize, const D: usize> Serialize for Aabb<S, D> {
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        BoxRef {
            min: &self.min,
            max: &self.max,
        }
        .serialize(s)
    }
}

impl<'de, S: Scalar + Deserialize<'de>, const D: usize> Deserialize<'de> for Aabb<S, D> {
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        let b = BoxOwned::<S>::deserialize(d)?;
        let (min, max) = (array("box min", &b.min)?, array("box max", &b.max)?);
        Aabb::new(min, max).map_err(|e| De::Error::custom(format!("box: {e}")))
    }
}

#[derive(Serialize)]
struct CellRef<'a> {
    level: u8,
    coords: &'a [u32],
}

#[derive(Deserialize)]
struct CellOwned {
    level: u8,
    coords: Vec<u32>,
}

impl<const D: usize> Serialize for Cell<D> {
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        CellRef {
            level: self.level(),
            coords: &self.coords(),
        }
        .serialize(s)
    }
}

impl<'de, const D: usize> Deserialize<'de> for Cell<D> {
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        let c = CellOwned::deserialize(d)?;
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

#[derive(Serialize)]
struct RegionRef<'a> {
    extent: &'a [u32],
    nodes: &'a [u8],
}

#[derive(Deserialize)]
struct RegionOwned {
    extent: Vec<u32>,
    nodes: Vec<u8>,
}

impl<const D: usize> Serialize for RegionTree<D> {
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        RegionRef {
            extent: &self.extent(),
            nodes: self.nodes(),
        }
        .serialize(s)
    }
}

impl<'de, const D: usize> Deserialize<'de> for RegionTree<D> {
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        let r = RegionOwned::deserialize(d)?;
        let extent = array("region tree extent", &r.extent)?;
        RegionTree::from_nodes(extent, r.nodes)
            .map_err(|e| De::Error::custom(format!("region tree: {e}")))
    }
}
