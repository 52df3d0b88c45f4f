//! `orthtree dist-balance` and `orthtree dist-points` (feature `mpi`, run under `mpirun`): the
//! library's distributed workloads (`orthtree::dist::workload`), which the examples
//! `dist_balance` and `dist_points` run too. This module only reads the arguments into the
//! workload's settings, checks them (the library's check, then the memory estimate), runs the
//! workload on MPI's world and prints rank 0's report.
//!
//! `orthtree dist-balance [--dim 2|3|4] [--level L] [--connect face|edge|corner] [--reps N]
//! [--ghost] [--check]` prints the checksum `orthtree balance` prints for the same `--dim`,
//! `--level` and `--connect`, at every rank count.
//!
//! `orthtree dist-points [--n N] [--queries Q] [--k K]` prints checksums equal at every rank
//! count.

use crate::balance::ConnectArg;
use crate::limits;
use crate::Failure;
use mpi::traits::*;
use orthtree::dist::workload::{BalanceWorkload, PointsWorkload};

/// p4est's fractal balanced over MPI ranks (run under mpirun)
///
/// Each rank refines its run of p4est's fractal at level L; the forest is balanced over every
/// rank. Prints the leaf counts, the checksum of the leaves (equal to `orthtree balance`'s) and
/// the phase times (maximum over ranks, median over the runs).
#[derive(clap::Args, Debug)]
#[command(after_help = crate::EXIT_CODES, allow_negative_numbers = true)]
pub struct DistBalanceArgs {
    /// Dimension: 2, 3 or 4
    #[arg(long, value_name = "D", default_value_t = 2, value_parser = limits::number(2usize, 4))]
    dim: usize,
    /// Refinement level, at most the tree's deepest level: 32 in 2D, 21 in 3D, 16 in 4D; levels
    /// whose leaves would not fit in memory are refused
    #[arg(long, value_name = "L", default_value_t = 8, value_parser = limits::number(0u8, u8::MAX))]
    level: u8,
    /// Balance across faces, edges or corners
    #[arg(long, value_enum, value_name = "C", default_value = "face")]
    connect: ConnectArg,
    /// Balance runs, median reported
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = limits::number(1usize, 100))]
    reps: usize,
    /// Also build the ghost layer of the balanced forest (same connectivity)
    #[arg(long)]
    ghost: bool,
    /// Rank 0 also balances the whole fractal serially and compares
    #[arg(long)]
    check: bool,
}

/// A point tree built and queried over MPI ranks (run under mpirun)
///
/// Builds the distributed point tree over uniform and clustered points and answers a batch of
/// k-nearest queries; prints counts, checksums (equal at every rank count) and phase times
/// (maximum over ranks).
#[derive(clap::Args, Debug)]
#[command(after_help = crate::EXIT_CODES)]
pub struct DistPointsArgs {
    /// Points in all
    #[arg(long, value_name = "N", default_value_t = 1_000_000, value_parser = limits::number(1u64, 1 << 40))]
    n: u64,
    /// k-nearest queries in all
    #[arg(long, value_name = "Q", default_value_t = 100_000, value_parser = limits::number(0u64, 1 << 40))]
    queries: u64,
    /// Neighbours per query
    #[arg(long, value_name = "K", default_value_t = 8, value_parser = limits::number(1usize, 1 << 20))]
    k: usize,
}

/// Runs `orthtree dist-balance`.
pub fn run_balance(args: &DistBalanceArgs) -> Result<(), Failure> {
    let work = BalanceWorkload {
        dim: args.dim,
        level: args.level,
        connect: args.connect.into(),
        reps: args.reps,
        ghost: args.ghost,
        check: args.check,
    };
    work.validate()
        .map_err(|e| Failure::Usage(format!("--{e}")))?;
    limits::check_memory(
        &format!(
            "--dim {} --level {}: about {:.3e} leaves before balance",
            work.dim,
            work.level,
            work.leaves_before()
        ),
        work.estimated_bytes(),
    )
    .map_err(Failure::Usage)?;
    let universe = mpi::initialize().ok_or_else(|| {
        Failure::Input("MPI could not be initialised (already initialised?)".into())
    })?;
    let world = universe.world();
    let report = work
        .run(&world)
        .map_err(|e| Failure::Input(format!("rank {}: {e}", world.rank())))?;
    if world.rank() == 0 {
        say_raw!("{report}");
    }
    match report.serial {
        Some((_, false)) => Err(Failure::Input(
            "the distributed balance differs from the serial one".into(),
        )),
        _ => Ok(()),
    }
}

/// Runs `orthtree dist-points`.
pub fn run_points(args: &DistPointsArgs) -> Result<(), Failure> {
    let work = PointsWorkload {
        n: args.n,
        queries: args.queries,
        k: args.k,
    };
    work.validate()
        .map_err(|e| Failure::Usage(format!("--{e}")))?;
    let universe = mpi::initialize().ok_or_else(|| {
        Failure::Input("MPI could not be initialised (already initialised?)".into())
    })?;
    let world = universe.world();
    let report = work
        .run(&world)
        .map_err(|e| Failure::Input(format!("rank {}: {e}", world.rank())))?;
    if world.rank() == 0 {
        say_raw!("{report}");
    }
    Ok(())
}
