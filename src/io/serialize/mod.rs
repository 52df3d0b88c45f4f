//! `Serialize` and `Deserialize` (feature `serde`) for [`Aabb`](crate::Aabb),
//! [`Cell`](crate::Cell), the topology [`Tree`](crate::Tree), [`PointTree`](crate::PointTree)
//! and [`RegionTree`](crate::RegionTree).
//!
//! Nothing is trusted on the way in: each type is read into a private shadow struct of plain
//! vectors, which is then checked by the type's own constructor or `validate` (a box's corners
//! finite and ordered, a cell's coordinates below 2^level, the arena's links and levels, a point
//! tree's runs, cells and Morton order, a region tree's canonical form), and a broken invariant
//! is a serde error that names it. Coordinates of every dimension are written as sequences (serde
//! has no impls for arrays of a generic length), points as one flat sequence of `n D`
//! coordinates.
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
