//! A LAS file read and indexed: `io::las::read_entries` (the coordinates in world units, read in
//! one pass and converted on all threads) then `PointTreeBuilder::par_build`, timed run after
//! run, in million points per second from a warm file. `--write` makes the file first: `n`
//! uniform random points in a 1 km cube at millimetre resolution (point format 0, 20 bytes a
//! record).
//!
//! ```text
//! cargo run --release --features las,rayon --example las_build -- --write cloud.las --n 10000000
//! cargo run --release --features las,rayon --example las_build -- --read cloud.las --runs 3
//! ```

use orthtree::cloud::{Cloud, Frame};
use orthtree::io::las;
use orthtree::points::PointTreeBuilder;
use orthtree::PointSet;
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};
use std::path::PathBuf;
use std::time::Instant;

#[macro_use]
#[path = "common/cli.rs"]
mod cli;
use cli::{Cli, CliError};

const USAGE: &str = "\
usage: las_build (--write FILE [--n N] [--seed S] | --read FILE [--runs R])

Writes a LAS file of N uniform random points, or reads one and builds its point octree in
parallel R times, printing the read and build times and the points per second.

options:
  --write FILE  the LAS file to make (its folder must exist)
  --n N         points to write, 1 to 1 000 000 000 (default 10 000 000)
  --seed S      the seed of the points (default 1)
  --read FILE   the LAS file to read and index
  --runs R      reads and builds, 1 to 1000 (default 3)
  -h, --help    this text
";

/// Bytes per point of writing: the cloud (12 + 2 + 1 bytes of columns), with a margin.
const WRITE_BYTES_PER_POINT: f64 = 32.0;

enum Args {
    Write { path: PathBuf, n: usize, seed: u64 },
    Read { path: PathBuf, runs: usize },
}

fn parse(cli: &mut Cli) -> Result<Args, CliError> {
    let (mut write, mut read, mut n, mut seed, mut runs) = (None, None, 10_000_000, 1, 3);
    while let Some(flag) = cli.next_arg()? {
        match flag.as_str() {
            "--write" => write = Some(cli.output_path("--write")?),
            "--read" => read = Some(PathBuf::from(cli.value("--read")?)),
            "--n" => n = cli.number("--n", 1, 1_000_000_000)?,
            "--seed" => seed = cli.number("--seed", 0, u64::MAX)?,
            "--runs" => runs = cli.number("--runs", 1, 1000)?,
            other => return Err(CliError::unknown(other)),
        }
    }
    match (write, read) {
        (Some(path), None) => {
            cli::check_memory("--n", n as f64 * WRITE_BYTES_PER_POINT)?;
            Ok(Args::Write { path, n, seed })
        }
        (None, Some(path)) => Ok(Args::Read { path, runs }),
        _ => Err(CliError::new("give one of --write FILE and --read FILE")),
    }
}

fn main() {
    match cli::parse_or_exit(USAGE, parse) {
        Args::Write { path, n, seed } => {
            let mut rng = SmallRng::seed_from_u64(seed);
            let mut cloud = Cloud::from_points(
                (0..n)
                    .map(|_| core::array::from_fn(|_| rng.gen_range(0..1_000_000)))
                    .collect(),
            );
            cloud.frame = Frame {
                scale: [0.001; 3],
                offset: [500_000.0, 4_000_000.0, 0.0],
            };
            if let Err(e) = las::write(&cloud, &path, false) {
                eprintln!("error: {}: {e}", path.display());
                std::process::exit(1);
            }
            say!("wrote {n} points to {}", path.display());
        }
        Args::Read { path, runs } => {
            let mut rates = Vec::with_capacity(runs);
            for run in 0..runs {
                let start = Instant::now();
                let entries = match las::read_entries(&path) {
                    Ok(entries) => entries,
                    Err(e) => {
                        eprintln!("error: {}: {e}", path.display());
                        std::process::exit(1);
                    }
                };
                let read = start.elapsed().as_secs_f64();
                let tree = PointTreeBuilder::new()
                    .par_build(&entries)
                    .expect("LAS coordinates are finite");
                let total = start.elapsed().as_secs_f64();
                let n = tree.len();
                let rate = n as f64 / total / 1e6;
                say!(
                    "run {run}: {n} points, read {:.3} s, build {:.3} s, {rate:.2} million points/s, \
                     {} leaves",
                    read,
                    total - read,
                    tree.leaf_count()
                );
                rates.push(rate);
            }
            rates.sort_by(f64::total_cmp);
            say!(
                "median {:.2} million points/s (read and build)",
                rates[rates.len() / 2]
            );
        }
    }
}
