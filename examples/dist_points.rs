//! The distributed point tree (feature `mpi`): uniform and clustered points in the unit
//! square, built over every rank and queried with a batch of k-nearest queries, printing the
//! counts, checksums that equal the single-process run's (point i and query j are drawn from
//! their index alone, so the union is the same at every rank count) and the phase times (the
//! maximum over ranks).
//!
//! ```text
//! cargo build --release --features mpi --example dist_points
//! mpirun -np 2 target/release/examples/dist_points [--n N] [--queries Q] [--k K]
//! ```

use mpi::collective::SystemOperation;
use mpi::traits::*;
use orthtree::dist::{DistPointTree, Partition};
use orthtree::prelude::*;

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

struct Args {
    n: u64,
    queries: u64,
    k: usize,
}

fn parse(cli: &mut Cli) -> Result<Args, CliError> {
    let mut args = Args {
        n: 1_000_000,
        queries: 100_000,
        k: 8,
    };
    while let Some(flag) = cli.next_arg()? {
        match flag.as_str() {
            "--n" => args.n = cli.number("--n", 1, 1 << 40)?,
            "--queries" => args.queries = cli.number("--queries", 0, 1 << 40)?,
            "--k" => args.k = cli.number("--k", 1, 1 << 20)?,
            other => return Err(CliError::unknown(other)),
        }
    }
    Ok(args)
}

/// SplitMix64: a well-mixed 64-bit value of `x`.
fn mix(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^ (x >> 31)
}

/// A number in [0, 1) from `x`.
fn unit(x: u64) -> f64 {
    (mix(x) >> 11) as f64 / (1u64 << 53) as f64
}

/// Point `i` of a data set: uniform, or near one of eight centres.
fn point(i: u64, clustered: bool) -> [f64; 2] {
    let (a, b) = (unit(2 * i), unit(2 * i + 1));
    if !clustered {
        return [a, b];
    }
    let c = mix(i ^ 0x5555) % 8;
    let centre = [0.1 + 0.1 * c as f64, 0.2 + 0.6 * unit(c + 1000)];
    [centre[0] + 0.02 * (a - 0.5), centre[1] + 0.02 * (b - 0.5)]
}

fn main() {
    let args = cli::parse_or_exit(USAGE, parse);
    let universe = mpi::initialize().expect("MPI initialises once");
    let world = universe.world();
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    let max = |x: f64| {
        let mut m = 0.0;
        world.all_reduce_into(&x, &mut m, SystemOperation::max());
        m
    };
    let xor = |x: u64| {
        let mut m = 0u64;
        world.all_reduce_into(&x, &mut m, SystemOperation::bitwise_xor());
        m
    };
    if rank == 0 {
        println!(
            "dist_points: {} points, {} queries, k = {}, {size} ranks",
            args.n, args.queries, args.k
        );
    }
    for clustered in [false, true] {
        let mine = Partition::uniform(args.n, size);
        let entries: Vec<([f64; 2], u64)> = (mine[rank]..mine[rank + 1])
            .map(|i| (point(i, clustered), i))
            .collect();
        let qs = Partition::uniform(args.queries, size);
        let queries: Vec<[f64; 2]> = (qs[rank]..qs[rank + 1])
            .map(|j| point(j + (1 << 50), clustered))
            .collect();
        world.barrier();
        let t0 = mpi::time();
        let tree = DistPointTree::builder()
            .build_from_vec(&world, entries)
            .unwrap_or_else(|e| panic!("rank {rank}: {e}"));
        let build = max(mpi::time() - t0);
        let phases: Vec<(&str, f64)> = tree
            .build_phases()
            .iter()
            .map(|&(name, s)| (name, max(s)))
            .collect();
        let first = tree.first_slot();
        let mut sum = 0u64;
        for (s, item) in tree.local().items().iter().enumerate() {
            sum ^= mix((first + s as u64) ^ mix(*item));
        }
        let build_sum = xor(sum);
        world.barrier();
        let t1 = mpi::time();
        let answers = tree
            .k_nearest_batch(&queries, args.k)
            .unwrap_or_else(|e| panic!("rank {rank}: {e}"));
        let knn = max(mpi::time() - t1);
        let mut sum = 0u64;
        let mut found = 0u64;
        for (j, a) in answers.iter().enumerate() {
            for (t, n) in a.iter().enumerate() {
                let q = qs[rank] + j as u64;
                sum ^= mix(mix(q) ^ (n.slot << 8) ^ t as u64 ^ n.distance.to_bits());
            }
            found += a.len() as u64;
        }
        let knn_sum = xor(sum);
        let mut total_found = 0u64;
        world.all_reduce_into(&found, &mut total_found, SystemOperation::sum());
        if rank == 0 {
            let kind = if clustered { "clustered" } else { "uniform" };
            println!(
                "{kind:9}: {} points, build checksum {build_sum:016x}, {total_found} neighbours, \
                 knn checksum {knn_sum:016x}",
                tree.len()
            );
            let list: Vec<String> = phases
                .iter()
                .map(|(n, s)| format!("{n} {:.3}", s))
                .collect();
            println!(
                "           build {build:.3} s ({}), batch k-nearest {knn:.3} s, total {:.3} s",
                list.join(", "),
                build + knn
            );
        }
    }
}
