//! Serde for planar point location: a [`Subdivision`] as `{vertices, edges}`, read back through
//! [`Subdivision::new`] (which checks every vertex and edge and recomputes the faces), and a
//! [`PointLocator`] as `{subdivision}`, its quadtree rebuilt by [`PointLocator::new`]
//! (O((V + E) log) time; its squares are a function of the subdivision, so storing them would
//! only add what has to be checked). A locator built with
//! [`PointLocator::with_exercise_rule`] comes back built with the default rule: the faces it
//! reports are the same.

use crate::compressed::{PointLocator, Subdivision};
use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

#[derive(Serialize)]
struct SubdivisionRef<'a> {
    vertices: &'a [[f64; 2]],
    edges: &'a [[u32; 2]],
}

#[derive(Deserialize)]
struct SubdivisionOwned {
    vertices: Vec<[f64; 2]>,
    edges: Vec<[u32; 2]>,
}

impl Serialize for Subdivision {
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        SubdivisionRef {
            vertices: self.vertices(),
            edges: self.edges(),
        }
        .serialize(s)
    }
}

impl<'de> Deserialize<'de> for Subdivision {
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        let o = SubdivisionOwned::deserialize(d)?;
        Subdivision::new(o.vertices, o.edges)
            .map_err(|e| De::Error::custom(format!("subdivision: {e}")))
    }
}

#[derive(Serialize)]
struct LocatorRef<'a> {
    subdivision: &'a Subdivision,
}

#[derive(Deserialize)]
struct LocatorOwned {
    subdivision: Subdivision,
}

impl Serialize for PointLocator {
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        LocatorRef {
            subdivision: self.subdivision(),
        }
        .serialize(s)
    }
}

impl<'de> Deserialize<'de> for PointLocator {
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        let o = LocatorOwned::deserialize(d)?;
        PointLocator::new(o.subdivision)
            .map_err(|e| De::Error::custom(format!("point locator: {e}")))
    }
}
