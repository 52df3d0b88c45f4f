//! `orthtree dist-balance`: p4est's fractal refined over every rank, then the distributed 2:1
//! balance (`DistForest::balance`, Isaac, Burstedde and Ghattas 2012), optionally the ghost
//! layer and a serial check on rank 0.

use super::{initialise, max_over, phase_list, slowest, sum_over, timed};
use crate::balance::{check_fractal, checksum, leaf_hash, median, ConnectArg, FNV_BASIS};
use crate::{limits, Failure};
use mpi::traits::*;
use orthtree::dist::{DistError, DistForest, Partition};
use orthtree::tree::fractal::{fractal, fractal_part, uniform_cells};
use orthtree::{Cell, Connectivity};

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

/// Peak bytes per leaf of the fractal before balance, over all ranks: the leaves (before and
/// after balance, 2 to 2.2 times as many), each rank's local tree and the copy of the refined
/// forest kept for repeated runs; measured 60-80 B at levels 10-12 in 2D and 7-8 in 3D, with a
/// margin. `--check` adds half of it for the serial tree.
const PEAK_BYTES_PER_LEAF: f64 = 120.0;

/// Runs `orthtree dist-balance`.
pub fn run_balance(args: &DistBalanceArgs) -> Result<(), Failure> {
    let check = if args.check { 1.5 } else { 1.0 };
    check_fractal(args.dim, args.level, PEAK_BYTES_PER_LEAF * check)?;
    let universe = initialise()?;
    let world = universe.world();
    let same = match args.dim {
        2 => run_in::<2>(args, &world),
        3 => run_in::<3>(args, &world),
        _ => run_in::<4>(args, &world),
    }
    .map_err(|e| Failure::Input(format!("rank {}: {e}", world.rank())))?;
    match same {
        Some(false) => Err(Failure::Input(
            "the distributed balance differs from the serial one".into(),
        )),
        _ => Ok(()),
    }
}

/// The workload in dimension `D` (collective); rank 0 prints. Returns, with `--check`, whether
/// the serial balance gave the same leaves.
fn run_in<const D: usize>(
    args: &DistBalanceArgs,
    comm: &impl Communicator,
) -> Result<Option<bool>, DistError> {
    let (rank, size) = (comm.rank() as usize, comm.size() as usize);
    let connect = Connectivity::from(args.connect);
    let (refined, refine_s) = timed(comm, || {
        let cells = Partition::uniform(uniform_cells::<D>(args.level), size);
        DistForest::new(
            comm,
            fractal_part::<D>(args.level, cells[rank], cells[rank + 1]),
        )
    });
    let refined = refined?;
    let mut totals = Vec::new();
    let mut runs: Vec<Vec<(&'static str, f64)>> = Vec::new();
    let mut forest = refined.clone();
    let mut stats = None;
    for _ in 0..args.reps {
        forest = refined.clone();
        let (s, total) = timed(comm, || forest.balance(comm, connect));
        let s = s?;
        totals.push(total);
        runs.push(slowest(comm, &s.phases));
        stats = Some(s);
    }
    let stats = stats.expect("clap asks for at least one run");
    // Each phase's median over the runs.
    let phases: Vec<_> = (0..runs[0].len())
        .map(|i| {
            let mut times: Vec<f64> = runs.iter().map(|p| p[i].1).collect();
            (runs[0][i].0, median(&mut times))
        })
        .collect();
    let sent = sum_over(comm, stats.sent);
    let mine = forest.leaves().len() as u64;
    let most = max_over(comm, mine);
    let hash = chained_hash(comm, forest.leaves());
    let mut ghost = None;
    if args.ghost {
        let (layer, ghost_s) = timed(comm, || forest.ghost(comm, connect));
        let layer = layer?;
        let ghosts = sum_over(comm, layer.ghosts().len() as u64);
        let mirrors = sum_over(comm, layer.mirrors().len() as u64);
        ghost = Some((ghosts, mirrors, ghost_s));
    }
    let after = sum_over(comm, mine);
    let serial = args.check.then(|| {
        let mut verdict = [0u64; 2];
        if rank == 0 {
            let mut tree = fractal::<D>(args.level);
            tree.balance(connect);
            let same = checksum(&tree) == hash && tree.leaf_count() as u64 == after;
            verdict = [tree.leaf_count() as u64, same.into()];
        }
        comm.process_at_rank(0).broadcast_into(&mut verdict[..]);
        (verdict[0], verdict[1] == 1)
    });
    if rank == 0 {
        say!(
            "dist-balance: dim {D}, level {}, {connect:?}, {size} ranks",
            args.level
        );
        say!("leaves before balance: {}", refined.len());
        say!("leaves after balance:  {after} (most on one rank {most})");
        say!("checksum:              {hash:016x}");
        say!("refine time:           {refine_s:.4} s");
        say!(
            "balance time:          {:.4} s (median of {}; {})",
            median(&mut totals),
            args.reps,
            phase_list(&phases, 4)
        );
        say!(
            "exchange:              {} rounds, {sent} cells sent in all",
            stats.rounds
        );
        if let Some((ghosts, mirrors, s)) = ghost {
            say!("ghost layer:           {ghosts} ghosts, {mirrors} mirrors, {s:.4} s");
        }
        if let Some((leaves, same)) = serial {
            say!("serial balance:        {leaves} leaves, same: {same}");
        }
    }
    Ok(serial.map(|(_, same)| same))
}

/// The checksum of every rank's leaves in rank order (collective): each rank continues the hash
/// of the ranks before it (a chain of messages), and the last rank's hash goes to every rank.
fn chained_hash<const D: usize>(comm: &impl Communicator, leaves: &[Cell<D>]) -> u64 {
    let (rank, size) = (comm.rank(), comm.size());
    let mut h = FNV_BASIS;
    if rank > 0 {
        (h, _) = comm.process_at_rank(rank - 1).receive::<u64>();
    }
    h = leaf_hash(h, leaves.iter().copied());
    if rank + 1 < size {
        comm.process_at_rank(rank + 1).send(&h);
    }
    comm.process_at_rank(size - 1).broadcast_into(&mut h);
    h
}
