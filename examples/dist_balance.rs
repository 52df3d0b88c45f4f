//! The distributed 2:1 balance (feature `mpi`) on p4est's fractal, the workload of p4est's
//! balance benchmarks and of `orthtree balance`: each rank refines its run of the uniform
//! level's cells, the forest is balanced over every rank, and rank 0 prints the leaf counts
//! before and after, the checksum of the leaves (the one `orthtree balance` prints for the same
//! workload, at every rank count) and the phase times (the maximum over ranks, the median over
//! `--reps` runs). The workload is the library's `dist::workload::BalanceWorkload`, which
//! `orthtree dist-balance` runs too; this file only reads the arguments.
//!
//! ```text
//! cargo build --release --features mpi --example dist_balance
//! mpirun -np 2 target/release/examples/dist_balance [--dim 2|3|4] [--level L]
//!     [--connect face|edge|corner] [--reps N] [--ghost] [--check]
//! ```

use mpi::traits::*;
use orthtree::dist::workload::BalanceWorkload;
use orthtree::Connectivity;

#[macro_use]
#[path = "common/cli.rs"]
mod cli;
use cli::{Cli, CliError};

const USAGE: &str = "\
usage: dist_balance [--dim D] [--level L] [--connect C] [--reps N] [--ghost] [--check]

Refines p4est's fractal at level L over every rank, balances the forest and prints the leaf
counts, the checksum of the leaves (equal to `orthtree balance`'s) and the phase times (maximum
over ranks, median over the runs).

options:
  --dim D        dimension: 2, 3 or 4 (default 2)
  --level L      refinement level, at most the tree's deepest level (32 in 2D, 21 in 3D, 16 in
                 4D); levels whose leaves would not fit in memory are refused (default 8)
  --connect C    face, edge or corner (default face)
  --reps N       balance runs, 1 to 100, median reported (default 1)
  --ghost        also builds the ghost layer of the balanced forest (same connectivity)
  --check        rank 0 also balances the whole fractal serially and compares
  -h, --help     this text
";

fn parse(cli: &mut Cli) -> Result<BalanceWorkload, CliError> {
    let mut work = BalanceWorkload::default();
    while let Some(flag) = cli.next_arg()? {
        match flag.as_str() {
            "--dim" => work.dim = cli.number("--dim", 2, 4)?,
            "--level" => work.level = cli.number("--level", 0, 32)?,
            "--connect" => {
                work.connect = match cli.value("--connect")?.as_str() {
                    "face" => Connectivity::Face,
                    "edge" => Connectivity::Edge,
                    "corner" | "full" => Connectivity::Corner,
                    other => {
                        return Err(CliError::new(format!(
                            "--connect {other:?}: expected face, edge or corner"
                        )))
                    }
                }
            }
            "--reps" => work.reps = cli.number("--reps", 1, 100)?,
            "--ghost" => work.ghost = true,
            "--check" => work.check = true,
            other => return Err(CliError::unknown(other)),
        }
    }
    work.validate()
        .map_err(|e| CliError::new(format!("--{e}")))?;
    cli::check_memory(
        &format!(
            "--dim {} --level {}: about {:.3e} leaves before balance",
            work.dim,
            work.level,
            work.leaves_before()
        ),
        work.estimated_bytes(),
    )?;
    Ok(work)
}

fn main() {
    let work = cli::parse_or_exit(USAGE, parse);
    let universe = mpi::initialize().expect("MPI initialises once");
    let world = universe.world();
    let report = work.run(&world).unwrap_or_else(|e| {
        eprintln!("error: rank {}: {e}", world.rank());
        world.abort(1)
    });
    if world.rank() == 0 {
        say_raw!("{report}");
        if report.serial.is_some_and(|(_, same)| !same) {
            eprintln!("error: the distributed balance differs from the serial one");
            world.abort(1);
        }
    }
}
