//! # orthtree
//!
//! 2^D-trees for any dimension D from 1 to 8: point quadtrees and octrees with the chapter's
//! split convention, neighbour finding and 2:1 balance (de Berg, Cheong, van Kreveld and
//! Overmars, *Computational Geometry*, chapter 14).
//!
//! Layers, each using only those before it: [`geom`] (scalars, boxes, cells, Morton keys,
//! directions, the root geometry) → [`tree`] (topology: arena, traversals, neighbours, balance)
//! → [`query`] (the engines over an index trait, and the point-set traits) → the consumers
//! [`points`], [`compressed`], [`image`], [`mesh`] and [`cloud`] (and, with the feature `mpi`,
//! `dist`: the point tree distributed over MPI ranks) → [`io`] (readers and writers).
//!
//! # The public surface
//! The crate root names what a first program names: the trees ([`PointTree`] with its aliases
//! [`Quadtree`] and [`Octree`], [`DynamicPointTree`], [`CompressedTree`], [`SkipQuadtree`],
//! [`RegionTree`] with [`ImageTree`] and [`VoxelTree`], and the topology [`Tree`]), the two
//! point-set traits with what their queries take and give ([`PointSet`], [`PointSetMut`],
//! [`Neighbor`], [`Region`], [`Ball`], [`Metric`]), the geometry every tree is built on
//! ([`Aabb`], [`Cell`], [`Scalar`], [`Connectivity`]) and the three error types ([`Error`] for
//! input, [`QueryError`] for queries, [`ValidationError`] for broken invariants). Everything
//! else is reached through the module that defines it, at one path: builders, options and
//! their errors with their tree's module, metrics and regions other than the ball in
//! [`query`], every iterator type in [`iter`]. The reference algorithms that tests compare
//! against (the chapter's balance) are compiled only with the `reference` feature.
//! [`prelude`] brings the point-set traits into scope.
//!
//! # Features
//! `huge-pages` is on by default: on Linux, the large answer tables of the k-nearest joins and
//! the bulk builds' buffers are advised to be backed by transparent huge pages (fewer page
//! faults; a no-op elsewhere and where the system does not offer them). Off by default: `rayon`
//! (the `par_` builds, balances, batch queries and joins), `png` (PNG images), `serde` (every
//! tree, region tree and mesh), `saved` (the binary saved-tree format) and `mmap` (saved trees
//! queried through a memory map), `las` and `laz` (LAS and LAZ point clouds); `full` turns all
//! of these on. `mpi` (the forest and point tree over MPI ranks) needs OpenMPI and libclang on
//! the system; `reference` compiles the reference algorithms.
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
#![warn(clippy::missing_errors_doc)]
#![deny(rustdoc::broken_intra_doc_links)]
// The exceptions, each allowed where it stands with its `// SAFETY:` comment: the cache
// prefetch of the build's gather and of the query engines (`prefetch.rs`, measured there and in
// `query/range.rs`), the huge-page advice for large buffers (`huge_pages.rs`, measured there),
// the memory map of a saved tree (`io/saved/mapped.rs`), the calls into the joins' copies
// compiled for newer x86-64 processors, and the radius kernel's AVX comparison behind its
// detection token (`cpu.rs`, measured there).
#![deny(unsafe_code)]

pub mod cloud;
pub mod compressed;
mod cpu;
#[cfg(feature = "mpi")]
pub mod dist;
pub mod error;
pub mod geom;
mod hash;
mod huge_pages;
pub mod image;
pub mod io;
pub mod mesh;
#[cfg(feature = "rayon")]
mod par_tasks;
pub mod points;
mod prefetch;
pub mod query;
mod sort_network;
pub mod tree;

pub use compressed::{CompressedTree, SkipQuadtree};
pub use error::{Error, ValidationError};
pub use geom::{Aabb, Cell, Connectivity, Scalar};
pub use image::{ImageTree, RegionTree, VoxelTree};
pub use points::{DynamicPointTree, Octree, PointTree, Quadtree};
pub use query::{Ball, Metric, Neighbor, PointSet, PointSetMut, QueryError, Region};
pub use tree::Tree;

/// Every public iterator type of the crate, in one place. Each is returned by a method of the
/// type named in its documentation and is rarely named by hand.
///
/// ```
/// use orthtree::{iter::PreOrder, tree::NodeId, Tree};
/// let mut t = Tree::<2>::new();
/// t.split(NodeId::ROOT);
/// let walk: PreOrder<'_, 2> = t.pre_order();
/// assert_eq!(walk.count(), 5);
/// ```
pub mod iter {
    pub use crate::image::iter::Blocks;
    #[cfg(feature = "las")]
    pub use crate::io::las::entries::LasEntries;
    pub use crate::mesh::halfedge::Outgoing;
    pub use crate::points::leaves::Leaves;
    pub use crate::query::point_set::{NearestIter, RegionIter};
    pub use crate::tree::traverse::PreOrder;
}

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
    pub use crate::query::ParallelQueries;
    pub use crate::query::{
        BatchQueries, Joins, PeriodicJoins, PeriodicQueries, PointSet, PointSetMut,
    };
    #[cfg(feature = "rayon")]
    pub use crate::query::{ParallelJoins, ParallelPeriodicJoins};
}

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
