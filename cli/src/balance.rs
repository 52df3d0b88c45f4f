//! p4est's "timings" fractal, then 2:1 balance: the workload of p4est's balance benchmarks.
//!
//! `orthtree balance [--dim 2|3|4] [--level L] [--connect face|edge|corner] [--weak]
//! [--incremental] [--reps N] [--parallel]` (`--help` lists the options and their limits)
//!
//! `--incremental` also builds the same refinement with `Tree::split_balanced` (exercise 14.8:
//! balanced construction without the unbalanced tree first) and compares time and result.
//!
//! The refinement is p4est's (`orthtree::tree::fractal`). Prints the leaf counts before and after balance, the refine, balance and
//! is_balanced times, peak memory, and a checksum of the sorted leaf cells.

use crate::limits;
use crate::Failure;
use orthtree::tree::fractal::{self, fractal_leaves};
use orthtree::{tree::BalanceOptions, Cell, Connectivity, Tree};
use std::time::Instant;

/// p4est's fractal refinement, then 2:1 balance (its benchmark workload)
///
/// Refines p4est's fractal at level L, balances it and prints leaf counts, times, peak memory
/// and a checksum of the leaves.
#[derive(clap::Args, Debug)]
#[command(after_help = crate::EXIT_CODES, allow_negative_numbers = true)]
pub struct BalanceArgs {
    /// Dimension: 2, 3 or 4
    #[arg(long, value_name = "D", default_value_t = 2, value_parser = limits::number(2usize, 4))]
    dim: usize,
    /// Refinement level, at most the tree's deepest level: 32 in 2D, 21 in 3D, 16 in 4D; levels
    /// whose tree would not fit in memory are refused
    #[arg(long, value_name = "L", default_value_t = 12, value_parser = limits::number(0u8, u8::MAX))]
    level: u8,
    /// Balance across faces, edges or corners
    #[arg(long, value_enum, value_name = "C", default_value = "face")]
    connect: ConnectArg,
    /// Allow a level difference of 2 instead of 1
    #[arg(long)]
    weak: bool,
    /// Also build the tree with split_balanced (exercise 14.8) and compare
    #[arg(long)]
    incremental: bool,
    /// Runs of balance and of the balance check, median reported
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = limits::number(1usize, 1000))]
    reps: usize,
    /// The rayon balance (needs the `rayon` feature)
    #[arg(long)]
    parallel: bool,
}

/// The connectivities on the command line.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum ConnectArg {
    /// Across faces.
    Face,
    /// Across faces and edges.
    Edge,
    /// Across faces, edges and corners.
    #[value(alias = "full")]
    Corner,
}

impl From<ConnectArg> for Connectivity {
    fn from(c: ConnectArg) -> Self {
        match c {
            ConnectArg::Face => Connectivity::Face,
            ConnectArg::Edge => Connectivity::Edge,
            ConnectArg::Corner => Connectivity::Corner,
        }
    }
}

struct Args {
    dim: usize,
    level: u8,
    options: BalanceOptions,
    incremental: bool,
    reps: usize,
    parallel: bool,
}

/// Peak bytes per leaf of the refined fractal (the refined tree, its copy and balance's work),
/// measured with the `peak memory` line: 25 to 27 B at levels 12 and 14 in 2D (face and corner
/// balance), 20 to 21 B at levels 7 and 8 in 3D, 19 B at level 6 in 4D; with a margin.
const PEAK_BYTES_PER_LEAF: f64 = 40.0;
/// The extra peak of `--incremental` (a second tree and the list of split cells): measured 1.2
/// at level 8 in 3D; with a margin.
const INCREMENTAL_FACTOR: f64 = 1.5;

/// The deepest level of a tree in dimension `dim` (`Cell::<D>::MAX_LEVEL`).
fn max_level(dim: usize) -> u8 {
    match dim {
        2 => orthtree::Cell::<2>::MAX_LEVEL,
        3 => orthtree::Cell::<3>::MAX_LEVEL,
        _ => orthtree::Cell::<4>::MAX_LEVEL,
    }
}

/// Checks the fractal at `level` in dimension `dim`: the level against the dimension's deepest
/// level, then its leaves at `bytes_per_leaf` against the memory this process may use.
pub(crate) fn check_fractal(dim: usize, level: u8, bytes_per_leaf: f64) -> Result<(), Failure> {
    if level > max_level(dim) {
        return Err(Failure::Usage(format!(
            "--level {level}: the deepest level of a {dim}D tree is {}",
            max_level(dim)
        )));
    }
    let leaves = fractal_leaves(dim, level);
    limits::check_memory(
        &format!("--dim {dim} --level {level}: about {leaves:.3e} leaves before balance"),
        leaves * bytes_per_leaf,
    )
    .map_err(Failure::Usage)
}

/// The checked arguments: the level against the dimension's deepest level and the memory.
fn checked(args: &BalanceArgs) -> Result<Args, Failure> {
    let (dim, level) = (args.dim, args.level);
    if args.parallel && !cfg!(feature = "rayon") {
        return Err(Failure::Usage(
            "--parallel needs the `rayon` feature".into(),
        ));
    }
    let copies = if args.incremental {
        INCREMENTAL_FACTOR
    } else {
        1.0
    };
    check_fractal(dim, level, PEAK_BYTES_PER_LEAF * copies)?;
    let options = BalanceOptions::new(args.connect.into());
    Ok(Args {
        dim,
        level,
        options: if args.weak { options.weak() } else { options },
        incremental: args.incremental,
        reps: args.reps,
        parallel: args.parallel,
    })
}

/// FNV-1a's offset basis: the hash of no cells.
pub(crate) const FNV_BASIS: u64 = 0xcbf2_9ce4_8422_2325;

/// FNV-1a over (level, coordinates) of `cells`, continuing from `h`: from [`FNV_BASIS`] over
/// every leaf in Morton order, the checksum `orthtree balance` and `orthtree dist-balance` print.
pub(crate) fn leaf_hash<const D: usize>(
    mut h: u64,
    cells: impl IntoIterator<Item = Cell<D>>,
) -> u64 {
    for cell in cells {
        for x in std::iter::once(cell.level() as u32).chain(cell.coords()) {
            for b in x.to_le_bytes() {
                h = (h ^ b as u64).wrapping_mul(0x0100_0000_01b3);
            }
        }
    }
    h
}

/// The checksum of a tree's leaves.
pub(crate) fn checksum<const D: usize>(tree: &Tree<D>) -> u64 {
    leaf_hash(FNV_BASIS, tree.leaves().map(|(_, c)| c))
}

/// The serial balance, or with `--parallel` the rayon one.
fn balance<const D: usize>(tree: &mut Tree<D>, args: &Args) -> Vec<orthtree::tree::NodeId> {
    #[cfg(feature = "rayon")]
    if args.parallel {
        return tree.par_balance(args.options);
    }
    tree.balance(args.options)
}

/// The serial balance test, or with `--parallel` the rayon one.
fn is_balanced<const D: usize>(tree: &Tree<D>, args: &Args) -> bool {
    #[cfg(feature = "rayon")]
    if args.parallel {
        return tree.par_is_balanced(args.options);
    }
    tree.is_balanced(args.options)
}

/// The median of `times` (the upper one of an even count); `times` is not empty.
pub(crate) fn median(times: &mut [f64]) -> f64 {
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

fn peak_memory_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

fn run_in<const D: usize>(args: &Args) -> Result<(), Failure> {
    let t = Instant::now();
    let mut tree = fractal::fractal::<D>(args.level);
    let refine_s = t.elapsed().as_secs_f64();
    let before = tree.leaf_count();
    let refined = tree.clone();
    let mut balance_times = Vec::new();
    let mut split = Vec::new();
    for _ in 0..args.reps {
        tree = refined.clone();
        let t = Instant::now();
        split = balance(&mut tree, args);
        balance_times.push(t.elapsed().as_secs_f64());
    }
    drop(refined);
    let balance_s = median(&mut balance_times);
    let mut check_times = Vec::new();
    let mut balanced = true;
    for _ in 0..args.reps {
        let t = Instant::now();
        balanced &= is_balanced(&tree, args);
        check_times.push(t.elapsed().as_secs_f64());
    }
    let check_s = median(&mut check_times);
    say!(
        "dim {D}, level {}, {:?}{}",
        args.level,
        args.options,
        if args.parallel { ", parallel" } else { "" }
    );
    say!("leaves before balance: {before}");
    say!(
        "estimated before:      {:.0}",
        fractal_leaves(D, args.level)
    );
    say!("leaves after balance:  {}", tree.leaf_count());
    say!("splits:                {}", split.len());
    say!("refine time:           {refine_s:.4} s");
    say!(
        "balance time:          {balance_s:.4} s (median of {})",
        args.reps
    );
    say!(
        "is_balanced time:      {check_s:.4} s ({balanced}), balance / is_balanced {:.1}",
        balance_s / check_s
    );
    say!(
        "tree bytes per leaf:   {:.1}",
        tree.heap_bytes() as f64 / tree.leaf_count() as f64
    );
    if let Some(mib) = peak_memory_mib() {
        say!("peak memory:           {mib:.1} MiB");
    }
    say!("checksum:              {:016x}", checksum(&tree));
    if !balanced {
        return Err(Failure::Input(
            "the tree is not balanced after balance()".into(),
        ));
    }
    if args.incremental {
        // Exercise 14.8: the same refinement, each split made with split_balanced.
        let refined = fractal::fractal::<D>(args.level);
        let cells: Vec<_> = refined
            .pre_order()
            .filter(|&(id, _)| !refined.is_leaf(id))
            .map(|(_, c)| c)
            .collect();
        let t = Instant::now();
        let mut built = Tree::<D>::new();
        for cell in &cells {
            let id = built.locate_cell(cell);
            if built.level(id) == cell.level() && built.is_leaf(id) {
                built.split_balanced(id, args.options, |_, _| {});
            }
        }
        let incremental_s = t.elapsed().as_secs_f64();
        let same = checksum(&built) == checksum(&tree) && built.leaf_count() == tree.leaf_count();
        say!("incremental (14.8):    {incremental_s:.4} s, vs refine + balance {:.4} s; same tree: {same}", refine_s + balance_s);
        if !same {
            return Err(Failure::Input(
                "split_balanced built another tree than refine + balance".into(),
            ));
        }
    }
    Ok(())
}

/// Runs `orthtree balance`.
pub fn run(args: &BalanceArgs) -> Result<(), Failure> {
    let args = checked(args)?;
    let _phase = crate::progress::Phase::start("refining and balancing");
    match args.dim {
        2 => run_in::<2>(&args),
        3 => run_in::<3>(&args),
        _ => run_in::<4>(&args),
    }
}
