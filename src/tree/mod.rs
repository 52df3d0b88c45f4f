//! The topology shared by every consumer, with no payload: an arena of nodes ([`Tree`]), its
//! traversals, neighbour finding and 2:1 balance.

mod arena;
mod balance;
mod balance_check;
#[cfg(test)]
mod balance_check_tests;
mod balance_dense;
mod incremental;
mod inner;
mod merge;
mod neighbors;
#[cfg(feature = "rayon")]
mod parallel;
mod ripple;
mod traverse;
mod validate;

pub use arena::{NodeId, SplitError, Tree};
pub use balance::{BalanceOptions, LevelDifferenceError};
pub use merge::MergeError;
pub use traverse::PreOrder;
pub use validate::TreeError;
