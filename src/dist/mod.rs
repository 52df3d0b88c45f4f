//! The forest over MPI ranks (feature `mpi`): points in global Morton order, each rank holding
//! one contiguous run of them, the way p4est distributes a forest of octrees (Burstedde,
//! Wilcox and Ghattas 2011).
//!
//! - [`Partition`]: the replicated table of each rank's first position and first Morton key
//!   (p4est's `global_first_position`), and repartition by counts or weights.
//! - [`DistPointTree`]: built from points scattered arbitrarily over the ranks (an agreement
//!   step, Morton keys over the global root box, a sample sort with one all-to-all exchange,
//!   then a local [`PointTree`](crate::PointTree) over the global root box on every rank);
//!   batch box, ball and k-nearest queries issued on any rank, routed to the ranks that can
//!   hold answers, answered there and merged back. Every answer is the one a single-process
//!   tree over the union of the inputs gives (the union in rank order: rank 0's points first),
//!   ties included: the global slot of a point is its position in that tree.
//! - [`DistForest`]: the leaves of one 2^D-tree in Morton runs over the ranks (p4est's linear
//!   forest, one tree), checked by an agreement step; 2:1 balance for any connectivity with the
//!   same leaves as the serial [`Tree::balance`](crate::Tree::balance) of the union (local
//!   balance, then only the insulation layer exchanged, then a local fix-up: Isaac, Burstedde
//!   and Ghattas 2012); the [`GhostLayer`] (remote leaves adjacent to each rank's, and its
//!   mirrors); repartition by counts, keeping families of sibling leaves on one rank when
//!   asked ([`RepartitionOptions`]).
//!
//! Every operation here is collective: every rank of the communicator calls it, in the same
//! order. A bad input on one rank (a NaN coordinate, a bad query, leaves out of order) is
//! agreed on before any exchange that depends on it and returned as the same [`DistError`] on
//! every rank.
//!
//! Points and items travel as plain bytes, so both are [`bytemuck::Pod`].
//!
//! ```
//! use orthtree::dist::DistPointTree;
//! let universe = mpi::initialize().unwrap();
//! let world = universe.world();
//! let rank = mpi::traits::Communicator::rank(&world) as u32;
//! let mine: Vec<([f64; 2], u32)> = (0..100).map(|i| ([i as f64, rank as f64], rank)).collect();
//! let tree = DistPointTree::builder().build_from_vec(&world, mine).unwrap();
//! let near = tree.k_nearest_batch(&[[10.2, 0.0]], 3).unwrap();
//! assert_eq!(near[0].len(), 3);
//! ```

mod balance;
mod build;
mod comm;
mod error;
mod exchange;
mod families;
mod forest;
mod ghost;
mod partition;
mod queries;
mod tree;

pub use balance::BalanceStats;
pub use build::{DistPointTreeBuilder, MAX_TOTAL};
pub use error::{DistError, LeafProblem};
pub use families::RepartitionOptions;
pub use forest::DistForest;
pub use ghost::GhostLayer;
pub use partition::Partition;
pub use queries::DistNeighbor;
pub use tree::DistPointTree;
