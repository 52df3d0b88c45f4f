//! The topology shared by every consumer, with no payload: an arena of nodes ([`Tree`]), its
//! traversals, neighbour finding and 2:1 balance.
//!
//! Files by what they hold: `arena.rs` (the nodes), `traverse.rs`, `neighbors.rs`, `merge.rs`,
//! `validate.rs` ([`Tree::validate`]), `fractal.rs` (p4est's fractal refinement, the balance
//! benchmarks' workload), `raw.rs` (the arrays as stored, for saved trees); `balance_options.rs` ([`BalanceOptions`]), `balance.rs`
//! ([`Tree::balance`]), `balance_check.rs` and `balance_check_dense.rs` ([`Tree::is_balanced`]),
//! `balance_parallel.rs` (feature `rayon`), `balance_seeded.rs` (refinement toward
//! given cells and balance restarted from new splits, for the forest over MPI ranks; feature `mpi`), `balanced_split.rs` ([`Tree::split_balanced`]), and
//! `balance_reference.rs`, the chapter's algorithm that the others are tested against
//! (`Tree::balance_chapter`, feature `reference`; the crate's own tests, benches and examples
//! turn the feature on).

mod arena;
mod balance;
mod balance_check;
mod balance_check_dense;
#[cfg(test)]
mod balance_check_tests;
mod balance_options;
#[cfg(feature = "rayon")]
mod balance_parallel;
#[cfg(any(test, feature = "reference"))]
mod balance_reference;
#[cfg(feature = "mpi")]
mod balance_seeded;
mod balanced_split;
pub mod fractal;
mod inner;
mod merge;
mod neighbors;
#[cfg(any(feature = "saved", feature = "serde"))]
pub(crate) mod raw;
pub(crate) mod traverse;
mod validate;

pub use arena::{NodeId, SplitError, Tree};
pub use balance_options::{BalanceOptions, LevelDifferenceError};
pub use merge::MergeError;
pub use validate::TreeError;
