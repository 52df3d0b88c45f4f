//! Compressed quadtrees (64-level cells), skip quadtrees and point location in a planar
//! subdivision.
//!
//! One test binary per area: each former test file is a module of it.

#[path = "../common/mod.rs"]
mod common;
#[path = "../../benches/workloads/compressed.rs"]
mod workload;

mod compressed;
mod compressed_deep;
mod point_location;
#[cfg(feature = "serde")]
mod serde_compressed;
mod skip;
