//! The two benchmark workloads of the forest over MPI ranks, shared by the examples
//! `dist_balance` and `dist_points` and the command-line program's `orthtree dist-balance` and
//! `orthtree dist-points`: each caller only reads its arguments into a
//! [`BalanceWorkload`] or a [`PointsWorkload`], runs it, and prints the report rank 0 gets.
//!
//! - [`BalanceWorkload`]: p4est's fractal (the refinement of p4est's `timings` example,
//!   Burstedde, Wilcox and Ghattas 2011, section 4), each rank refining its run of the uniform
//!   level's cells, then [`DistForest::balance`](super::DistForest::balance); the checksum of
//!   the leaves equals the serial `orthtree balance`'s at every rank count.
//! - [`PointsWorkload`]: uniform and clustered points in the unit square, point i and query j
//!   drawn from their index alone (so the union is the same at every rank count), a
//!   [`DistPointTree`](super::DistPointTree) built over every rank and a batch of k-nearest
//!   queries; the checksums equal the single-process run's.
//!
//! Times are the maximum over ranks (the slowest rank decides a collective step), medians over
//! repeated runs where a workload repeats.

mod balance;
mod points;

use crate::tree::fractal;
pub use balance::{BalanceReport, BalanceWorkload};
pub use fractal::{fractal_leaves, fractal_part, uniform_cells};
pub use points::{PointsReport, PointsRun, PointsWorkload};

use mpi::collective::SystemOperation;
use mpi::traits::*;

/// A setting of a workload that cannot be run, naming the setting and its limit. Each message
/// starts with the setting's name, which is the option of the examples and of the
/// command-line program without its `--`.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum WorkloadError {
    /// The dimension is not one the workload is compiled for.
    Dimension {
        /// The dimension asked for.
        dim: usize,
    },
    /// The refinement level is deeper than the tree's deepest level in that dimension.
    Level {
        /// The level asked for.
        level: u8,
        /// The dimension.
        dim: usize,
        /// The deepest level of a tree in that dimension.
        deepest: u8,
    },
    /// A count is outside its range.
    Count {
        /// The argument's name.
        what: &'static str,
        /// The value asked for.
        value: u64,
        /// The smallest value allowed.
        min: u64,
        /// The largest value allowed.
        max: u64,
    },
}

impl core::fmt::Display for WorkloadError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            WorkloadError::Dimension { dim } => write!(f, "dim {dim}: expected 2, 3 or 4"),
            WorkloadError::Level {
                level,
                dim,
                deepest,
            } => write!(
                f,
                "level {level}: the deepest level of a {dim}D tree is {deepest}"
            ),
            WorkloadError::Count {
                what,
                value,
                min,
                max,
            } => write!(f, "{what} {value}: expected a number from {min} to {max}"),
        }
    }
}

impl std::error::Error for WorkloadError {}

/// Checks that `value` of argument `what` lies in `min..=max`.
fn check_count(what: &'static str, value: u64, min: u64, max: u64) -> Result<(), WorkloadError> {
    if (min..=max).contains(&value) {
        Ok(())
    } else {
        Err(WorkloadError::Count {
            what,
            value,
            min,
            max,
        })
    }
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

/// The median of `v` (the upper one of an even count); 0 for none.
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(0.0)
}

/// `phases` as `name seconds` joined by commas, with `digits` decimals.
fn phase_list(phases: &[(&'static str, f64)], digits: usize) -> String {
    let list = phases.iter().map(|(n, s)| format!("{n} {s:.digits$}"));
    list.collect::<Vec<_>>().join(", ")
}
