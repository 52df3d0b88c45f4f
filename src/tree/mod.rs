//! The topology shared by every consumer, with no payload: an arena of nodes ([`Tree`]), its
//! traversals, neighbour finding and 2:1 balance.

mod arena;
mod balance;
mod incremental;
mod merge;
mod neighbors;
mod ripple;
mod traverse;

pub use arena::{NodeId, SplitError, Tree};
pub use balance::BalanceOptions;
pub use merge::MergeError;
pub use traverse::PreOrder;
