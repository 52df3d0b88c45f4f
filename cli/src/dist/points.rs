//! `orthtree dist-points`: uniform and clustered points in the unit square, a `DistPointTree`
//! built over every rank and a batch of k-nearest queries; each point and query drawn from its
//! index alone by SplitMix64 (Steele, Lea and Flood 2014), so the union and the checksums are
//! the same at every rank count.

use super::{initialise, over, phase_list, slowest, sum_over, timed};
use crate::{limits, Failure};
use mpi::collective::SystemOperation;
use mpi::traits::*;
use orthtree::dist::{DistError, DistPointTree, Partition, MAX_TOTAL};
use orthtree::PointSet;

/// A point tree built and queried over MPI ranks (run under mpirun)
///
/// Builds the distributed point tree over uniform and clustered points and answers a batch of
/// k-nearest queries; prints counts, checksums (equal at every rank count) and phase times
/// (maximum over ranks).
#[derive(clap::Args, Debug)]
#[command(after_help = crate::EXIT_CODES)]
pub struct DistPointsArgs {
    /// Points in all; a run whose points and answers would not fit in memory is refused
    #[arg(long, value_name = "N", default_value_t = 1_000_000, value_parser = limits::number(1u64, MAX_TOTAL))]
    n: u64,
    /// k-nearest queries in all
    #[arg(long, value_name = "Q", default_value_t = 100_000, value_parser = limits::number(0u64, 1 << 40))]
    queries: u64,
    /// Neighbours per query
    #[arg(long, value_name = "K", default_value_t = 8, value_parser = limits::number(1usize, 1 << 20))]
    k: usize,
}

/// SplitMix64's finaliser: a well-mixed 64-bit value of `x`.
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

/// Peak bytes per point over all ranks: the generated entries, the build's keys and exchange
/// buffers and the local trees; measured 55 B at one rank (peak resident memory at 10^6 and
/// 4 x 10^6 points), with a margin for the exchange at several ranks.
const PEAK_BYTES_PER_POINT: f64 = 120.0;

/// Bytes per neighbour of a batch answer (slot, distance, point and item, and the exchange's
/// copy): measured 464 B per query at k = 8 (peak resident memory at 10^5 and 10^6 queries),
/// with a margin.
const BYTES_PER_NEIGHBOUR: f64 = 96.0;

/// Runs `orthtree dist-points`.
pub fn run_points(args: &DistPointsArgs) -> Result<(), Failure> {
    let answers = args.queries as f64 * (16.0 + BYTES_PER_NEIGHBOUR * args.k as f64);
    limits::check_memory(
        &format!("--n {} --queries {} --k {}", args.n, args.queries, args.k),
        args.n as f64 * PEAK_BYTES_PER_POINT + answers,
    )
    .map_err(Failure::Usage)?;
    let universe = initialise()?;
    let world = universe.world();
    if world.rank() == 0 {
        say!(
            "dist-points: {} points, {} queries, k = {}, {} ranks",
            args.n,
            args.queries,
            args.k,
            world.size()
        );
    }
    for clustered in [false, true] {
        run_set(args, &world, clustered)
            .map_err(|e| Failure::Input(format!("rank {}: {e}", world.rank())))?;
    }
    Ok(())
}

/// One data set (collective): the build, the checksum of its slots and items, the batch
/// k-nearest and the checksum of its answers; rank 0 prints.
fn run_set(
    args: &DistPointsArgs,
    comm: &impl Communicator,
    clustered: bool,
) -> Result<(), DistError> {
    let (rank, size) = (comm.rank() as usize, comm.size() as usize);
    let mine = Partition::uniform(args.n, size);
    let entries: Vec<([f64; 2], u64)> = (mine[rank]..mine[rank + 1])
        .map(|i| (point(i, clustered), i))
        .collect();
    let qs = Partition::uniform(args.queries, size);
    let queries: Vec<[f64; 2]> = (qs[rank]..qs[rank + 1])
        .map(|j| point(j + (1 << 50), clustered))
        .collect();
    let (tree, build_s) = timed(comm, || {
        DistPointTree::builder().build_from_vec(comm, entries)
    });
    let tree = tree?;
    let phases = slowest(comm, tree.build_phases());
    let first = tree.first_slot();
    let items = tree.local().items().iter().enumerate();
    let sum = items.fold(0, |x, (s, item)| x ^ mix((first + s as u64) ^ mix(*item)));
    let build_sum = over(comm, sum, SystemOperation::bitwise_xor());
    let (answers, knn_s) = timed(comm, || tree.k_nearest_batch(&queries, args.k));
    let answers = answers?;
    let mut sum = 0u64;
    let mut found = 0u64;
    for (j, a) in answers.iter().enumerate() {
        let q = qs[rank] + j as u64;
        for (t, n) in a.iter().enumerate() {
            sum ^= mix(mix(q) ^ (n.slot << 8) ^ t as u64 ^ n.distance.to_bits());
        }
        found += a.len() as u64;
    }
    let found = sum_over(comm, found);
    let knn_sum = over(comm, sum, SystemOperation::bitwise_xor());
    if rank == 0 {
        let kind = if clustered { "clustered" } else { "uniform" };
        say!(
            "{kind:9}: {} points, build checksum {build_sum:016x}, {found} neighbours, knn checksum {knn_sum:016x}",
            tree.len()
        );
        say!(
            "           build {build_s:.3} s ({}), batch k-nearest {knn_s:.3} s, total {:.3} s",
            phase_list(&phases, 3),
            build_s + knn_s
        );
    }
    Ok(())
}
