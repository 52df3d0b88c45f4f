//! p4est's "timings" fractal, then 2:1 balance: the workload of p4est's balance benchmarks.
//!
//! `cargo run --release --example balance_fractal -- --dim 2|3|4 --level L --connect face|edge|corner [--weak] [--incremental] [--reps N] [--parallel]`
//!
//! `--incremental` also builds the same refinement with `Tree::split_balanced` (exercise 14.8:
//! balanced construction without the unbalanced tree first) and compares time and result.
//!
//! The refinement is p4est's (see `benches/workloads/fractal.rs`). Prints the leaf counts before and after balance, the refine, balance and
//! is_balanced times, peak memory, and a checksum of the sorted leaf cells.

use orthtree::{BalanceOptions, Connectivity, Tree};

#[path = "../benches/workloads/fractal.rs"]
mod fractal;
use std::time::Instant;

struct Args {
    dim: usize,
    level: u8,
    options: BalanceOptions,
    incremental: bool,
    reps: usize,
    parallel: bool,
}

fn parse() -> Result<Args, String> {
    let mut args = Args {
        dim: 2,
        level: 12,
        options: BalanceOptions::new(Connectivity::Face),
        incremental: false,
        reps: 1,
        parallel: false,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let mut value = || it.next().ok_or(format!("{flag} needs a value"));
        match flag.as_str() {
            "--dim" => args.dim = value()?.parse().map_err(|e| format!("--dim: {e}"))?,
            "--level" => args.level = value()?.parse().map_err(|e| format!("--level: {e}"))?,
            "--connect" => {
                args.options.connectivity = match value()?.as_str() {
                    "face" => Connectivity::Face,
                    "edge" => Connectivity::Edge,
                    "corner" | "full" => Connectivity::Corner,
                    other => return Err(format!("--connect: unknown connectivity {other:?}")),
                }
            }
            "--weak" => args.options = args.options.weak(),
            "--incremental" => args.incremental = true,
            "--parallel" if cfg!(feature = "rayon") => args.parallel = true,
            "--parallel" => return Err("--parallel needs --features rayon".into()),
            "--reps" => {
                args.reps = value()?.parse().map_err(|e| format!("--reps: {e}"))?;
                if args.reps == 0 {
                    return Err("--reps must be at least 1".into());
                }
            }
            other => return Err(format!("unknown argument {other:?}")),
        }
    }
    Ok(args)
}

/// FNV-1a over (level, coordinates) of the leaves in Morton order.
fn checksum<const D: usize>(tree: &Tree<D>) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for (_, cell) in tree.leaves() {
        for x in std::iter::once(cell.level() as u32).chain(cell.coords()) {
            for b in x.to_le_bytes() {
                h = (h ^ b as u64).wrapping_mul(0x0100_0000_01b3);
            }
        }
    }
    h
}

/// The serial balance, or with `--parallel` the rayon one.
fn balance<const D: usize>(tree: &mut Tree<D>, args: &Args) -> Vec<orthtree::NodeId> {
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

fn median(times: &mut [f64]) -> f64 {
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

fn peak_memory_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

fn run<const D: usize>(args: &Args) {
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
    println!(
        "dim {D}, level {}, {:?}{}",
        args.level,
        args.options,
        if args.parallel { ", parallel" } else { "" }
    );
    println!("leaves before balance: {before}");
    println!("leaves after balance:  {}", tree.leaf_count());
    println!("splits:                {}", split.len());
    println!("refine time:           {refine_s:.4} s");
    println!(
        "balance time:          {balance_s:.4} s (median of {})",
        args.reps
    );
    println!(
        "is_balanced time:      {check_s:.4} s ({balanced}), balance / is_balanced {:.1}",
        balance_s / check_s
    );
    println!(
        "tree bytes per leaf:   {:.1}",
        tree.heap_bytes() as f64 / tree.leaf_count() as f64
    );
    if let Some(mib) = peak_memory_mib() {
        println!("peak memory:           {mib:.1} MiB");
    }
    println!("checksum:              {:016x}", checksum(&tree));
    if !balanced {
        eprintln!("error: the tree is not balanced after balance()");
        std::process::exit(1);
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
        println!("incremental (14.8):    {incremental_s:.4} s, vs refine + balance {:.4} s; same tree: {same}", refine_s + balance_s);
        if !same {
            std::process::exit(1);
        }
    }
}

fn main() {
    let args = match parse() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("error: {e}\nusage: balance_fractal --dim 2|3|4 --level L --connect face|edge|corner [--weak] [--incremental] [--reps N] [--parallel]");
            std::process::exit(2);
        }
    };
    match args.dim {
        2 => run::<2>(&args),
        3 => run::<3>(&args),
        4 => run::<4>(&args),
        d => {
            eprintln!("error: --dim {d} is not supported (2, 3 or 4)");
            std::process::exit(2);
        }
    }
}
