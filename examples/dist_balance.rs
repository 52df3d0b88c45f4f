//! The distributed 2:1 balance (feature `mpi`) on p4est's fractal, the workload of p4est's
//! balance benchmarks and of `orthtree balance`: each rank refines its run of the uniform
//! level's cells (the same refinement rule, `benches/workloads/fractal.rs`), the forest is
//! balanced over every rank, and rank 0 prints the leaf counts before and after, the checksum
//! of the leaves (the one `orthtree balance` prints for the same workload, at every rank count)
//! and the phase times (the maximum over ranks, the median over `--reps` runs).
//!
//! ```text
//! cargo build --release --features mpi --example dist_balance
//! mpirun -np 2 target/release/examples/dist_balance [--dim 2|3|4] [--level L]
//!     [--connect face|edge|corner] [--reps N] [--ghost] [--check]
//! ```

use mpi::collective::SystemOperation;
use mpi::traits::*;
use orthtree::dist::{DistForest, Partition};
use orthtree::{Cell, Connectivity};

#[path = "common/cli.rs"]
mod cli;
use cli::{Cli, CliError};

#[path = "../benches/workloads/fractal.rs"]
mod fractal;

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

struct Args {
    dim: usize,
    level: u8,
    connect: Connectivity,
    reps: usize,
    ghost: bool,
    check: bool,
}

/// Peak bytes per leaf of the fractal before balance, over all ranks: the leaves (before and
/// after balance, 2 to 2.2 times as many) and each rank's local tree; measured 60-80 B at
/// levels 10-12 in 2D and 7-8 in 3D, with a margin.
const PEAK_BYTES_PER_LEAF: f64 = 120.0;

/// Leaves of the fractal at `level` in dimension `dim` before balance (the count
/// `orthtree balance` estimates the same way): the uniform level's cells, half of them
/// refined for four more levels, half of each cell's children again.
fn fractal_leaves(dim: usize, level: u8) -> f64 {
    let uniform = level.saturating_sub(4);
    let half = 2f64.powi(dim as i32 - 1);
    let mut below = 1.0;
    for _ in 0..level - uniform {
        below = half * (1.0 + below);
    }
    if uniform == 0 {
        below
    } else {
        2f64.powi((dim * uniform as usize) as i32) / 2.0 * (1.0 + below)
    }
}

fn parse(cli: &mut Cli) -> Result<Args, CliError> {
    let mut args = Args {
        dim: 2,
        level: 8,
        connect: Connectivity::Face,
        reps: 1,
        ghost: false,
        check: false,
    };
    while let Some(flag) = cli.next_arg()? {
        match flag.as_str() {
            "--dim" => args.dim = cli.number("--dim", 2, 4)?,
            "--level" => args.level = cli.number("--level", 0, 32)?,
            "--connect" => {
                args.connect = match cli.value("--connect")?.as_str() {
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
            "--reps" => args.reps = cli.number("--reps", 1, 100)?,
            "--ghost" => args.ghost = true,
            "--check" => args.check = true,
            other => return Err(CliError::unknown(other)),
        }
    }
    let deepest = match args.dim {
        2 => Cell::<2>::MAX_LEVEL,
        3 => Cell::<3>::MAX_LEVEL,
        _ => Cell::<4>::MAX_LEVEL,
    };
    if args.level > deepest {
        return Err(CliError::new(format!(
            "--level {}: the deepest level of a {}D tree is {deepest}",
            args.level, args.dim
        )));
    }
    let leaves = fractal_leaves(args.dim, args.level);
    cli::check_memory(
        &format!(
            "--dim {} --level {}: about {leaves:.3e} leaves before balance",
            args.dim, args.level
        ),
        leaves * PEAK_BYTES_PER_LEAF * if args.check { 1.5 } else { 1.0 },
    )?;
    Ok(args)
}

/// FNV-1a over (level, coordinates) of `cells`, continuing from `h` (`orthtree balance`'s
/// checksum when run over every leaf in Morton order from the offset basis).
fn fnv<const D: usize>(mut h: u64, cells: &[Cell<D>]) -> u64 {
    for cell in cells {
        for x in std::iter::once(cell.level() as u32).chain(cell.coords()) {
            for b in x.to_le_bytes() {
                h = (h ^ b as u64).wrapping_mul(0x0100_0000_01b3);
            }
        }
    }
    h
}

const FNV_BASIS: u64 = 0xcbf2_9ce4_8422_2325;

/// The checksum of every rank's leaves in rank order: each rank continues the hash of the
/// ranks before it (a chain of messages), and the last rank's hash goes to every rank.
fn checksum<const D: usize>(world: &impl Communicator, leaves: &[Cell<D>]) -> u64 {
    let (rank, size) = (world.rank(), world.size());
    let mut h = FNV_BASIS;
    if rank > 0 {
        (h, _) = world.process_at_rank(rank - 1).receive::<u64>();
    }
    h = fnv(h, leaves);
    if rank + 1 < size {
        world.process_at_rank(rank + 1).send(&h);
    }
    world.process_at_rank(size - 1).broadcast_into(&mut h);
    h
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn run<const D: usize>(world: &impl Communicator, args: &Args) {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    let max = |x: f64| {
        let mut m = 0.0;
        world.all_reduce_into(&x, &mut m, SystemOperation::max());
        m
    };
    let sum = |x: u64| {
        let mut m = 0u64;
        world.all_reduce_into(&x, &mut m, SystemOperation::sum());
        m
    };
    world.barrier();
    let t = mpi::time();
    let cells = Partition::uniform(fractal::uniform_cells::<D>(args.level), size);
    let part = fractal::fractal_part::<D>(args.level, cells[rank], cells[rank + 1]);
    let refined = DistForest::new(world, part).unwrap_or_else(|e| panic!("rank {rank}: {e}"));
    let refine_s = max(mpi::time() - t);
    let mut totals = Vec::new();
    let mut phases: Vec<Vec<(&str, f64)>> = Vec::new();
    let mut forest = refined.clone();
    let mut stats = None;
    for _ in 0..args.reps {
        forest = refined.clone();
        world.barrier();
        let t = mpi::time();
        let s = forest
            .balance(world, args.connect)
            .unwrap_or_else(|e| panic!("rank {rank}: {e}"));
        totals.push(max(mpi::time() - t));
        phases.push(s.phases.iter().map(|&(n, x)| (n, max(x))).collect());
        stats = Some(s);
    }
    let stats = stats.expect("at least one run");
    let sent = sum(stats.sent);
    let local_after = forest.leaves().len() as u64;
    let most = {
        let mut m = 0u64;
        world.all_reduce_into(&local_after, &mut m, SystemOperation::max());
        m
    };
    let check = checksum(world, forest.leaves());
    if rank == 0 {
        println!(
            "dist_balance: dim {D}, level {}, {:?}, {size} ranks",
            args.level, args.connect
        );
        println!("leaves before balance: {}", refined.len());
        println!(
            "leaves after balance:  {} (most on one rank {most})",
            forest.len()
        );
        println!("checksum:              {check:016x}");
        println!("refine time:           {refine_s:.4} s");
        let list: Vec<String> = (0..phases[0].len())
            .map(|i| {
                let name = phases[0][i].0;
                format!(
                    "{name} {:.4}",
                    median(phases.iter().map(|p| p[i].1).collect())
                )
            })
            .collect();
        println!(
            "balance time:          {:.4} s (median of {}; {})",
            median(totals),
            args.reps,
            list.join(", ")
        );
        println!(
            "exchange:              {} rounds, {sent} cells sent in all",
            stats.rounds
        );
    }
    if args.ghost {
        world.barrier();
        let t = mpi::time();
        let ghost = forest
            .ghost(world, args.connect)
            .unwrap_or_else(|e| panic!("rank {rank}: {e}"));
        let ghost_s = max(mpi::time() - t);
        let (ghosts, mirrors) = (
            sum(ghost.ghosts().len() as u64),
            sum(ghost.mirrors().len() as u64),
        );
        if rank == 0 {
            println!("ghost layer:           {ghosts} ghosts, {mirrors} mirrors, {ghost_s:.4} s");
        }
    }
    if args.check {
        let all = gather_counts(world, &forest);
        if rank == 0 {
            let mut tree = fractal::fractal::<D>(args.level);
            tree.balance(args.connect);
            let leaves: Vec<Cell<D>> = tree.leaves().map(|(_, c)| c).collect();
            let same = fnv(FNV_BASIS, &leaves) == check && leaves.len() as u64 == all;
            println!(
                "serial balance:        {} leaves, same: {same}",
                leaves.len()
            );
            if !same {
                eprintln!("error: the distributed balance differs from the serial one");
                world.abort(1);
            }
        }
    }
}

/// The number of leaves over all ranks, summed afresh.
fn gather_counts<const D: usize>(world: &impl Communicator, forest: &DistForest<D>) -> u64 {
    let mut n = 0u64;
    world.all_reduce_into(
        &(forest.leaves().len() as u64),
        &mut n,
        SystemOperation::sum(),
    );
    n
}

fn main() {
    let args = cli::parse_or_exit(USAGE, parse);
    let universe = mpi::initialize().expect("MPI initialises once");
    let world = universe.world();
    match args.dim {
        2 => run::<2>(&world, &args),
        3 => run::<3>(&world, &args),
        _ => run::<4>(&world, &args),
    }
}
