//! The distributed point tree (feature `mpi`): uniform and clustered points in the unit
//! square, built over every rank and queried with a batch of k-nearest queries, printing the
//! counts, checksums that equal the single-process run's (point i and query j are drawn from
//! their index alone, so the union is the same at every rank count) and the phase times (the
//! maximum over ranks). The workload is the library's `dist::workload::PointsWorkload`, which
//! `orthtree dist-points` runs too; this file only reads the arguments.
//!
//! ```text
//! cargo build --release --features mpi --example dist_points
//! mpirun -np 2 target/release/examples/dist_points [--n N] [--queries Q] [--k K]
//! ```

use mpi::traits::*;
use orthtree::dist::workload::PointsWorkload;

#[macro_use]
#[path = "common/cli.rs"]
mod cli;
use cli::{Cli, CliError};

const USAGE: &str = "\
usage: dist_points [--n N] [--queries Q] [--k K]

Builds the distributed point tree over uniform and clustered points and answers a batch of
k-nearest queries; prints counts, checksums and phase times (maximum over ranks).

options:
  --n N          points in all, at least 1 (default 1000000)
  --queries Q    k-nearest queries in all (default 100000)
  --k K          neighbours per query, at least 1 (default 8)
  -h, --help     this text
";

fn parse(cli: &mut Cli) -> Result<PointsWorkload, CliError> {
    let mut work = PointsWorkload::default();
    while let Some(flag) = cli.next_arg()? {
        match flag.as_str() {
            "--n" => work.n = cli.number("--n", 1, 1 << 40)?,
            "--queries" => work.queries = cli.number("--queries", 0, 1 << 40)?,
            "--k" => work.k = cli.number("--k", 1, 1 << 20)?,
            other => return Err(CliError::unknown(other)),
        }
    }
    work.validate()
        .map_err(|e| CliError::new(format!("--{e}")))?;
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
    }
}
