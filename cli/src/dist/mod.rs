//! `orthtree dist-balance` and `orthtree dist-points` (feature `mpi`, run under `mpirun`): the
//! benchmark workloads of the forest and the point tree over MPI ranks (`orthtree::dist`).
//! Every rank runs the same command; rank 0 prints. Times are the maximum over ranks (the
//! slowest rank decides a collective step), medians over repeated runs where a workload repeats.
//!
//! - `orthtree dist-balance [--dim 2|3|4] [--level L] [--connect face|edge|corner] [--reps N]
//!   [--ghost] [--check]` (`balance.rs`): p4est's fractal (the refinement of p4est's `timings`
//!   example, Burstedde, Wilcox and Ghattas 2011, section 4), each rank refining its run of the
//!   uniform level's cells, then `DistForest::balance`; prints the checksum `orthtree balance`
//!   prints for the same `--dim`, `--level` and `--connect`, at every rank count.
//! - `orthtree dist-points [--n N] [--queries Q] [--k K]` (`points.rs`): uniform and clustered
//!   points, point i and query j drawn from their index alone (so the union is the same at
//!   every rank count), a `DistPointTree` built over every rank and a batch of k-nearest
//!   queries; prints checksums equal at every rank count.

mod balance;
mod points;

pub use balance::{run_balance, DistBalanceArgs};
pub use points::{run_points, DistPointsArgs};

use crate::Failure;
use mpi::collective::SystemOperation;
use mpi::environment::Universe;
use mpi::traits::*;

/// MPI, initialised for this command (finalised when the universe is dropped).
fn initialise() -> Result<Universe, Failure> {
    mpi::initialize()
        .ok_or_else(|| Failure::Input("MPI could not be initialised (already initialised?)".into()))
}

/// `x` reduced over the ranks by `op` (collective).
fn over<T: Equivalence + Default>(comm: &impl Communicator, x: T, op: SystemOperation) -> T {
    let mut m = T::default();
    comm.all_reduce_into(&x, &mut m, op);
    m
}

/// The largest `x` over the ranks (collective).
fn max_over<T: Equivalence + Default>(comm: &impl Communicator, x: T) -> T {
    over(comm, x, SystemOperation::max())
}

/// The sum of `x` over the ranks (collective).
fn sum_over(comm: &impl Communicator, x: u64) -> u64 {
    over(comm, x, SystemOperation::sum())
}

/// `work`'s value, and its seconds on the slowest rank, timed from a barrier (collective).
fn timed<T>(comm: &impl Communicator, work: impl FnOnce() -> T) -> (T, f64) {
    comm.barrier();
    let t = mpi::time();
    let value = work();
    (value, max_over(comm, mpi::time() - t))
}

/// Each phase's seconds on the slowest rank (collective).
fn slowest(comm: &impl Communicator, phases: &[(&'static str, f64)]) -> Vec<(&'static str, f64)> {
    phases
        .iter()
        .map(|&(n, s)| (n, max_over(comm, s)))
        .collect()
}

/// `phases` as `name seconds` joined by commas, with `digits` decimals.
fn phase_list(phases: &[(&'static str, f64)], digits: usize) -> String {
    let list = phases.iter().map(|(n, s)| format!("{n} {s:.digits$}"));
    list.collect::<Vec<_>>().join(", ")
}
