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

/// A subdivision's vertices and edges: slices written, vectors read back.
#[derive(Serialize, Deserialize)]
struct SubdivisionFields<V, E> {
    vertices: V,
    edges: E,
}

impl Serialize for Subdivision {
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        SubdivisionFields::<&[[f64; 2]], &[[u32; 2]]> {
            vertices: self.vertices(),
            edges: self.edges(),
        }
        .serialize(s)
    }
}

impl<'de> Deserialize<'de> for Subdivision {
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        let o = SubdivisionFields::<Vec<[f64; 2]>, Vec<[u32; 2]>>::deserialize(d)?;
        Subdivision::new(o.vertices, o.edges)
            .map_err(|e| De::Error::custom(format!("subdivision: {e}")))
    }
}

/// A locator's subdivision: by reference written, owned read back.
#[derive(Serialize, Deserialize)]
struct LocatorFields<S> {
    subdivision: S,
}

impl Serialize for PointLocator {
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        LocatorFields {
            subdivision: self.subdivision(),
        }
        .serialize(s)
    }
}

impl<'de> Deserialize<'de> for PointLocator {
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        let o = LocatorFields::<Subdivision>::deserialize(d)?;
        PointLocator::new(o.subdivision)
            .map_err(|e| De::Error::custom(format!("point locator: {e}")))
    }
}
