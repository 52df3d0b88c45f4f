//! orthtree side by side with other spatial crates: the programs `compare` (point queries and
//! updates beside kiddo and rstar), `joins_compare` (periodic and join queries beside kiddo and
//! scipy's cKDTree, [`joins`] and [`scipy`]) and `mesh_compare` (the mesher beside spade's refined
//! Delaunay triangulation), and the criterion benches `build` and `queries`.
//!
//! Every crate sits behind one small adapter ([`rivals::Rival`]), so every crate runs exactly
//! the same workload on the same seeded points ([`points`]), and the answers are checked equal
//! across the crates where they hand back the same thing.

#[macro_use]
#[path = "../../cli/src/print.rs"]
pub mod print;

pub mod joins;
#[path = "../../benches/common/mod.rs"]
pub mod points;
pub mod python;
pub mod rivals;
pub mod scipy;
pub mod timing;

#[path = "../../cli/src/limits.rs"]
pub mod limits;
