//! `Serialize` and `Deserialize` (feature `serde`), one file per family:
//!
//! - `geom.rs`: [`Aabb`](crate::Aabb), [`Cell`](crate::Cell), [`RegionTree`](crate::RegionTree);
//! - `tree.rs`: the topology [`Tree`](crate::Tree);
//! - `points.rs`: [`PointTree`](crate::PointTree), its own arrays;
//! - `dynamic.rs`: [`DynamicPointTree`](crate::DynamicPointTree), its own arrays;
//! - `compressed.rs`: [`CompressedTree`](crate::CompressedTree) and
//!   [`SkipQuadtree`](crate::compressed::SkipQuadtree): points, items and the query order, the
//!   nodes and skip levels rebuilt (they are functions of the points and the seed);
//! - `locator.rs`: [`Subdivision`](crate::compressed::Subdivision) and
//!   [`PointLocator`](crate::compressed::PointLocator), rebuilt;
//! - `mesh.rs`: the mesher's [`Mesh`](crate::mesh::Mesh), [`Board`](crate::mesh::Board) and
//!   [`MeshOptions`](crate::mesh::MeshOptions);
//! - `settings.rs`: [`Torus`](crate::query::Torus) and
//!   [`BalanceOptions`](crate::tree::BalanceOptions); the metrics, `MinImage`, `Connectivity`,
//!   `OutsidePoints` and the mesh's segments and components derive both traits.
//!
//! Nothing is trusted on the way in: each type is read into a private shadow struct of plain
//! vectors, which is then checked by the type's own constructor or `validate` (a box's corners
//! finite and ordered, a cell's coordinates below 2^level, the arena's links and levels, a point
//! tree's runs, cells and Morton order, a dynamic tree's counts and chunks, every compressed
//! tree's point and its order, a region tree's canonical form, a mesh's indices, orientation and
//! conformity), and a broken invariant is a serde error that names the item (point, node,
//! triangle, axis) and the limit. Memory is bounded by the document: every array is as long as
//! it is written, and no claimed count is allocated before it is checked against them.
//! Coordinates of every dimension are written as sequences (serde has no impls for arrays of a
//! generic length), points as one flat sequence of `n D` coordinates.
//!
//! Every float a tree writes is finite (its domain stops at `f64::MAX` where its root cube goes
//! beyond), so formats without infinities, such as JSON, hold every tree. A round trip is exact
//! only if the format reads back every `f64` it wrote: serde_json does with its feature
//! `float_roundtrip`; its default parser can come back a unit in the last place off (for example
//! for `f64::MAX / 2`, the halved corner of a root cube at `f64::MAX`), and the tree read is then
//! refused by the checks above, or holds the points so moved where they stay in their cells.
//!
//! ```
//! use orthtree::prelude::*;
//! use orthtree::{Aabb, Quadtree};
//! let t = Quadtree::new(&[([0.0, 0.0], 'a'), ([1.0, 0.5], 'b'), ([0.25, 1.0], 'c')]).unwrap();
//! let json = serde_json::to_string(&t).unwrap();
//! let back: Quadtree<char> = serde_json::from_str(&json).unwrap();
//! assert_eq!((back.points(), back.items()), (t.points(), t.items()));
//! let b: Aabb<f64, 2> = serde_json::from_str(r#"{"min":[0.0,1.0],"max":[2.0,3.0]}"#).unwrap();
//! assert_eq!(b.max, [2.0, 3.0]);
//! let bad = serde_json::from_str::<Aabb<f64, 2>>(r#"{"min":[3.0,1.0],"max":[2.0,3.0]}"#);
//! assert!(bad.unwrap_err().to_string().contains("axis 0"));
//!
//! use orthtree::{CompressedTree, DynamicPointTree};
//! let pts = [([0.0, 0.0], 1u32), ([1.0, 0.5], 2), ([1.0, 0.5], 3)];
//! let d = DynamicPointTree::new(&pts).unwrap();
//! let back: DynamicPointTree<f64, u32, 2> =
//!     serde_json::from_str(&serde_json::to_string(&d).unwrap()).unwrap();
//! assert_eq!(back.items(), d.items());
//! let c = CompressedTree::new(&pts).unwrap();
//! let mut doc = serde_json::to_value(&c).unwrap();
//! doc["points"][2] = serde_json::json!(f64::MAX); // point 1 leaves the domain
//! let e = serde_json::from_value::<CompressedTree<f64, u32, 2>>(doc).unwrap_err();
//! assert!(e.to_string().contains("point 1"), "{e}");
//! ```

mod compressed;
mod dynamic;
mod geom;
mod locator;
mod mesh;
mod points;
mod settings;
mod tree;

/// `v` as an array of `D` values, or an error naming `what` and the lengths.
pub(super) fn array<E: serde::de::Error, X: Copy, const D: usize>(
    what: &str,
    v: &[X],
) -> Result<[X; D], E> {
    <[X; D]>::try_from(v)
        .map_err(|_| E::custom(format!("{what}: {} values for {D} dimensions", v.len())))
}
