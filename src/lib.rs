//! # orthtree
//!
//! 2^D-trees for any dimension D from 1 to 8: point quadtrees and octrees with the chapter's
//! split convention, neighbour finding and 2:1 balance (de Berg, Cheong, van Kreveld and
//! Overmars, *Computational Geometry*, chapter 14).
//!
//! Layers: [`geom`] (scalars, boxes, cells, Morton keys, directions) → [`tree`] (topology:
//! arena, traversals, neighbours, balance) → [`points`] (the point tree) → [`io`] (SVG).
//!
//! ```
//! use orthtree::prelude::*;
//! use orthtree::{Connectivity, Quadtree};
//! let pts = [([0.1, 0.1], "a"), ([0.12, 0.1], "b"), ([0.9, 0.8], "c")];
//! let mut t = Quadtree::builder().bucket_size(1).build(&pts).unwrap();
//! let before = t.node_count();
//! t.balance(Connectivity::Face);
//! assert!(t.node_count() >= before);
//! assert_eq!(t.len(), 3);
//! ```
#![warn(missing_docs)]
#![deny(rustdoc::broken_intra_doc_links)]
// One exception, allowed where it stands: the cache prefetch of the build's gather and of the
// query engines (`prefetch.rs`, measured there and in `query/range.rs`).
#![deny(unsafe_code)]

pub mod compressed;
mod error;
pub mod geom;
mod hash;
pub mod image;
pub mod io;
pub mod mesh;
pub mod points;
mod prefetch;
pub mod query;
pub mod tree;

pub use compressed::{CompressedTree, CompressedTreeBuilder, SkipQuadtree};
pub use error::{Error, ValidationError};
pub use geom::{
    morton, validate_point, Aabb, AabbError, Cell, Connectivity, DeepCell, Direction, RootGeometry,
    Scalar,
};
pub use image::{ImageTree, RegionTree, VoxelTree};
pub use points::{
    DynamicPointTree, Leaf, Leaves, Octree, PointTree, PointTreeBuilder, Quadtree,
    DEFAULT_BUCKET_SIZE,
};
pub use query::{
    Ball, HalfSpace, Metric, Neighbor, PointSet, PointSetMut, QueryError, Region, Relation,
    SpatialIndex,
};
pub use tree::{
    BalanceOptions, LevelDifferenceError, NodeId, PreOrder, SplitError, Tree, TreeError,
};

/// The traits whose methods are every point tree's queries and updates, to bring into scope
/// with `use orthtree::prelude::*;`.
///
/// ```
/// use orthtree::prelude::*;
/// use orthtree::Quadtree;
/// let t = Quadtree::new(&[([0.0, 0.0], 'a'), ([1.0, 1.0], 'b')]).unwrap();
/// assert_eq!((t.len(), *t.nearest(&[0.9, 0.8]).unwrap().unwrap().item), (2, 'b'));
/// ```
pub mod prelude {
    #[cfg(feature = "rayon")]
    pub use crate::query::ParallelJoins;
    #[cfg(feature = "rayon")]
    pub use crate::query::ParallelQueries;
    pub use crate::query::{Joins, PointSet, PointSetMut};
}

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
