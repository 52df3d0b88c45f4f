//! The bulk build at scale: `PointTree::new` (or `par_build`) of `n` uniform random 3-D `f64`
//! points with `u32` items, timed run after run, with the cost per point, the peak resident
//! memory (`VmHWM` of `/proc/self/status`, Linux only) and a digest of the tree (node and leaf
//! counts, a hash of the item order) so that two builds of the library can be compared.
//!
//! ```text
//! cargo run --release --example build_scale -- --n 100000000 --runs 3
//! cargo run --release --features rayon --example build_scale -- --n 100000000 --runs 3 --par
//! cargo run --release --example build_scale -- --n 100000000 --runs 3 --map-ahead
//! ```

use orthtree::points::PointTreeBuilder;
use orthtree::{Octree, PointSet};
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};
use std::time::Instant;

#[macro_use]
#[path = "common/cli.rs"]
mod cli;
use cli::{Cli, CliError};

const USAGE: &str = "\
usage: build_scale [--n N] [--runs R] [--par | --map-ahead] [--seed S]

Builds the point octree of N uniform random points (f64, u32 items) R times and prints the
time per point of each build, their median, the peak resident memory and a digest of the tree.

options:
  --n N       points, 1 to 4 000 000 000 (default 1 000 000); counts whose build would not fit
              in memory are refused
  --runs R    builds, 1 to 1000 (default 3)
  --par       the parallel build (`par_build`, needs the `rayon` feature)
  --map-ahead the serial build with its fresh buffers mapped on a second thread
              (`PointTreeBuilder::map_pages_ahead`)
  --seed S    the seed of the points (default 1)
  -h, --help  this text
";

/// Peak bytes per point: the input (32), the tree's points and items (28), the sort's keys
/// and buffer (16) and the nodes, with a margin.
const PEAK_BYTES_PER_POINT: f64 = 96.0;

struct Args {
    n: usize,
    runs: usize,
    par: bool,
    map_ahead: bool,
    seed: u64,
}

fn parse(cli: &mut Cli) -> Result<Args, CliError> {
    let mut args = Args {
        n: 1_000_000,
        runs: 3,
        par: false,
        map_ahead: false,
        seed: 1,
    };
    while let Some(flag) = cli.next_arg()? {
        match flag.as_str() {
            "--n" => args.n = cli.number("--n", 1, 4_000_000_000)?,
            "--runs" => args.runs = cli.number("--runs", 1, 1000)?,
            "--par" => args.par = true,
            "--map-ahead" => args.map_ahead = true,
            "--seed" => args.seed = cli.number("--seed", 0, u64::MAX)?,
            other => return Err(CliError::unknown(other)),
        }
    }
    if args.par && args.map_ahead {
        return Err(CliError::new(
            "--map-ahead is for the serial build; `par_build` keeps both cores busy",
        ));
    }
    if args.par && !cfg!(feature = "rayon") {
        return Err(CliError::new(
            "--par needs the example built with `--features rayon`",
        ));
    }
    cli::check_memory("--n", args.n as f64 * PEAK_BYTES_PER_POINT)?;
    Ok(args)
}

/// The processor time of the main thread so far in nanoseconds (`/proc/thread-self/schedstat`,
/// Linux only): beside the wall time, a cost less disturbed by other programs on a busy machine.
fn cpu_ns() -> Option<u64> {
    let stat = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    stat.split_whitespace().next()?.parse().ok()
}

/// The processor time so far in nanoseconds, (user, kernel), and the page faults taken, of the
/// whole process (`who` = "self") or of the calling thread ("thread-self"), from
/// `/proc/<who>/stat` (Linux only, times in clock ticks, usually of 10 ms): the kernel's part is
/// mostly the page faults on fresh memory.
fn stat_ns(who: &str) -> Option<(u64, u64, u64)> {
    let stat = std::fs::read_to_string(format!("/proc/{who}/stat")).ok()?;
    // the fields after the command name, which is in parentheses and may hold spaces
    let fields: Vec<&str> = stat.rsplit_once(')')?.1.split_whitespace().collect();
    let tick = 10_000_000; // ns per tick at the usual 100 Hz
    let (user, kernel): (u64, u64) = (fields.get(11)?.parse().ok()?, fields.get(12)?.parse().ok()?);
    Some((user * tick, kernel * tick, fields.get(7)?.parse().ok()?))
}

/// The peak resident memory of this process in KiB, if the system reports it.
fn peak_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

#[cfg(feature = "rayon")]
fn par_build(entries: &[([f64; 3], u32)]) -> Octree<u32> {
    PointTreeBuilder::new()
        .par_build(entries)
        .expect("finite points")
}

#[cfg(not(feature = "rayon"))]
fn par_build(_: &[([f64; 3], u32)]) -> Octree<u32> {
    unreachable!("refused while parsing")
}

fn main() {
    let args = cli::parse_or_exit(USAGE, parse);
    let mut rng = SmallRng::seed_from_u64(args.seed);
    let entries: Vec<([f64; 3], u32)> = (0..args.n)
        .map(|i| ([rng.r#gen(), rng.r#gen(), rng.r#gen()], i as u32))
        .collect();
    let before = peak_kib();
    let mut costs = Vec::with_capacity(args.runs);
    for run in 0..args.runs {
        let (start, cpu_start, process_start, thread_start) = (
            Instant::now(),
            cpu_ns(),
            stat_ns("self"),
            stat_ns("thread-self"),
        );
        let tree = if args.par {
            par_build(&entries)
        } else {
            PointTreeBuilder::new()
                .map_pages_ahead(args.map_ahead)
                .build(&entries)
                .expect("finite points")
        };
        let ns = start.elapsed().as_secs_f64() * 1e9 / args.n as f64;
        let cpu = match (cpu_start, cpu_ns()) {
            (Some(a), Some(b)) => format!(
                " ({:.1} ns/point of the main thread's processor time)",
                (b - a) as f64 / args.n as f64
            ),
            _ => String::new(),
        };
        let share = |who, start: Option<(u64, u64, u64)>| match (start, stat_ns(who)) {
            (Some((u0, k0, f0)), Some((u1, k1, f1))) => format!(
                "{:.1} user + {:.1} kernel ns/point, {} page faults",
                (u1 - u0) as f64 / args.n as f64,
                (k1 - k0) as f64 / args.n as f64,
                f1 - f0
            ),
            _ => String::new(),
        };
        let kernel = format!(
            "; all threads {}; this thread {}",
            share("self", process_start),
            share("thread-self", thread_start)
        );
        // FNV-1a over the item order: equal for equal trees.
        let digest = tree.items().iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &i| {
            (h ^ u64::from(i)).wrapping_mul(0x100_0000_01b3)
        });
        say!(
            "run {run}: {ns:.1} ns/point{cpu}{kernel}, {} nodes, {} leaves, items digest {digest:016x}",
            tree.node_count(),
            tree.leaf_count()
        );
        costs.push(ns);
    }
    costs.sort_by(f64::total_cmp);
    let median = costs[costs.len() / 2];
    let mode = match (args.par, args.map_ahead) {
        (true, _) => "par_build",
        (false, true) => "build, pages mapped ahead",
        (false, false) => "build",
    };
    say_raw!("n {} {mode}: median {median:.1} ns/point", args.n);
    match (before, peak_kib()) {
        (Some(input), Some(peak)) => say!(
            ", peak RSS {:.2} GiB ({:.1} bytes/point; {:.1} before the builds, the input)",
            peak as f64 / (1 << 20) as f64,
            peak as f64 * 1024.0 / args.n as f64,
            input as f64 * 1024.0 / args.n as f64
        ),
        _ => say!(""),
    }
}
