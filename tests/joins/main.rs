//! The tree-against-tree queries (joins) of every point tree against nested loops over the
//! points: the Euclidean joins and their parallel forms, and the joins on a periodic domain
//! against a scan over all images.
//!
//! One test binary per area: each file is a module of it.

#[path = "../common/mod.rs"]
mod common;

mod joins;
mod periodic_joins;
