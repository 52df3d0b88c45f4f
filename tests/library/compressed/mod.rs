//! Compressed quadtrees (64-level cells), skip quadtrees and point location in a planar
//! subdivision.

#[path = "../../../benches/workloads/compressed.rs"]
mod workload;

mod compressed_deep;
mod compressed_tree;
mod point_location;
#[cfg(feature = "serde")]
mod serde_compressed;
mod skip;
