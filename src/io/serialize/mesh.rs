//! Serde for the mesher's values: [`Mesh`] as `{vertices, triangles, regions, segments}` (its
//! public arrays), [`Board`] as `{size, components}` (read back through [`Board::new`], which
//! checks and normalises it), and [`MeshOptions`] as its settings (the size function, a
//! closure, cannot be written; the board-independent settings are checked on the way in).
//! [`Segment`](crate::mesh::Segment), [`SegmentKind`](crate::mesh::SegmentKind),
//! [`Component`](crate::mesh::Component) and [`Mode`](crate::mesh::Mode) derive both traits
//! (they hold no invariant of their own).
//!
//! A mesh read back is checked as a mesh on its own (its board is not stored with it, so the
//! board-dependent checks of [`Mesh::validate`] are the caller's): every vertex in
//! `[0, 2^30]^2` (the largest board), every index in range and one region per triangle
//! ([`Mesh::check_indices`]), every triangle strictly counter-clockwise, no directed edge used
//! twice ([`HalfEdges::new`], the conformity the half-edge view needs), and every segment
//! joining two distinct vertices, on a component numbered from 1. O(T log T) for T triangles.

use crate::mesh::SegmentKind;
use crate::mesh::{Board, Component, HalfEdges, Mesh, MeshOptions, MeshSettings};
use serde::de::Error as _;
use serde::ser::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// The largest vertex coordinate accepted, the largest board side (2^30).
const MAX_COORDINATE: i64 = 1 << 30;

/// A mesh's arrays: slices written, vectors read back.
#[derive(Serialize, Deserialize)]
struct MeshFields<V, T, R, S> {
    vertices: V,
    triangles: T,
    regions: R,
    segments: S,
}

impl Serialize for Mesh {
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        MeshFields {
            vertices: &self.vertices,
            triangles: &self.triangles,
            regions: &self.regions,
            segments: &self.segments,
        }
        .serialize(s)
    }
}

impl<'de> Deserialize<'de> for Mesh {
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        let o = MeshFields::<Vec<_>, Vec<_>, Vec<_>, Vec<_>>::deserialize(d)?;
        let mesh = Mesh {
            vertices: o.vertices,
            triangles: o.triangles,
            regions: o.regions,
            segments: o.segments,
        };
        check_mesh(&mesh).map_err(|m| De::Error::custom(format!("mesh: {m}")))?;
        Ok(mesh)
    }
}

/// The checks of the module doc, the first failure as a message naming the item.
fn check_mesh(mesh: &Mesh) -> Result<(), String> {
    let range = 0..=MAX_COORDINATE;
    if let Some((v, p)) = (mesh.vertices.iter().enumerate())
        .find(|(_, p)| !range.contains(&p[0]) || !range.contains(&p[1]))
    {
        return Err(format!(
            "vertex {v} at ({}, {}) is outside [0, {MAX_COORDINATE}]^2",
            p[0], p[1]
        ));
    }
    mesh.check_indices().map_err(|e| e.to_string())?;
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let [a, b, c] = tri.map(|v| mesh.vertices[v as usize].map(i128::from));
        let doubled = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        if doubled <= 0 {
            return Err(format!(
                "triangle {t} {tri:?} is not counter-clockwise (twice its signed area is \
                 {doubled}, must be positive)"
            ));
        }
    }
    HalfEdges::new(mesh).map_err(|e| e.to_string())?;
    for (i, s) in mesh.segments.iter().enumerate() {
        if s.vertices[0] == s.vertices[1] {
            return Err(format!(
                "segment {i} joins vertex {} to itself",
                s.vertices[0]
            ));
        }
        if s.kind == SegmentKind::Component(0) {
            return Err(format!(
                "segment {i} lies on component 0 (components are numbered from 1)"
            ));
        }
    }
    Ok(())
}

/// A board's size and components: a slice written, a vector read back.
#[derive(Serialize, Deserialize)]
struct BoardFields<C> {
    size: i64,
    components: C,
}

impl Serialize for Board {
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        BoardFields::<&[Component]> {
            size: self.size(),
            components: self.components(),
        }
        .serialize(s)
    }
}

impl<'de> Deserialize<'de> for Board {
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        let o = BoardFields::<Vec<Component>>::deserialize(d)?;
        Board::new(o.size, o.components).map_err(|e| De::Error::custom(format!("board: {e}")))
    }
}

impl Serialize for MeshOptions {
    /// # Errors
    /// When a size function is set: a closure cannot be written.
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        let (settings, has_size_fn) = self.settings();
        if has_size_fn {
            return Err(Se::Error::custom(
                "mesh options: a size function is set, and a closure cannot be serialized",
            ));
        }
        settings.serialize(s)
    }
}

impl<'de> Deserialize<'de> for MeshOptions {
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        MeshOptions::from_settings(MeshSettings::deserialize(d)?)
            .map_err(|e| De::Error::custom(format!("mesh options: {e}")))
    }
}
