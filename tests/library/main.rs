//! The library's integration tests, one module per area, in one test binary: the areas share
//! most of their generic instantiations (the point trees, the queries, the readers), which one
//! crate compiles once; as separate binaries they took about a tenth more processor time to
//! build. Run one area with a filter: `cargo test --test library joins::`.
//!
//! - `points`: the point trees (`PointTree`, `DynamicPointTree`): build, bounds, duplicates,
//!   queries against brute force, updates, every dimension, bad input, saved trees and serde;
//! - `joins`: the tree-against-tree queries against nested loops, Euclidean and periodic;
//! - `compressed`: compressed and skip quadtrees, point location in a planar subdivision;
//! - `cloud`: point-cloud readers and writers, voxel operations, the out-of-core build;
//! - `tree`: the arena topology, 2:1 balance, neighbour finding, the module graph;
//! - `mesh`: the board mesher against an independent oracle, board input, the mesh writers;
//! - `image`: region trees of images, their Boolean operations, PBM and PNG;
//! - `hostile`: hostile input, which must neither panic nor exhaust memory.
//!
//! Every test runs under `counting`'s allocator, the system's with a count of the bytes each
//! thread holds, through which the hostile-input tests check that memory stays bounded by the
//! data.

mod common;
mod counting;
mod mesh_oracle;

mod cloud;
mod compressed;
mod hostile;
mod image;
mod joins;
mod mesh;
mod points;
mod tree;
