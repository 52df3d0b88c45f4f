//! orthtree's periodic and join queries beside kiddo 6 and scipy's `cKDTree`, in one process
//! (scipy through its driver script), every crate on the same seeded points: prints a markdown
//! table of median times and how many times faster orthtree is than each rival.
//!
//! ```sh
//! compare/scipy/setup.sh        # once: scipy 1.17.1 in target/scipy-venv (else scipy is skipped)
//! cargo run --release -p orthtree-compare --features rayon --bin joins_compare
//! cargo run --release -p orthtree-compare --bin joins_compare -- --n 100000 --workload pairs
//! ```
//!
//! Workloads (3-D, `f64`):
//! - `periodic`: the 10 nearest of each of `--queries` uniform queries among N uniform points
//!   in the periodic unit cube, one thread (kiddo's periodic boundary condition, scipy's
//!   `boxsize`); then the same queries as one batch (`periodic_k_nearest_batch`: answered in
//!   Morton order to a visitor, its sort timed), beside the same kiddo and scipy runs;
//! - `self-knn`: the 16 nearest others of every one of N points on a surface (a wavy height
//!   field with noise), on all of rayon's threads with the `rayon` feature (kiddo's parallel
//!   batch query, scipy's `workers = -1`), else on one;
//! - `pairs`: every pair within the radius that gives about 10 neighbours per point, on the
//!   same surface, one thread (kiddo's radius join of two trees, scipy's `query_pairs` with
//!   `output_type="ndarray"`, then again with its default output, a set of tuples);
//! - `count`: the pair counts within each of 20 radii (from a quarter to four times that
//!   radius), one thread (scipy's `count_neighbors`; kiddo has no such query).
//!
//! Every answer (counts, index sums, distance sums) is checked equal to orthtree's before a
//! time is printed; a disagreement ends the program with an error. Times are medians of
//! `--reps` runs after one untimed warm-up.

use clap::{Parser, ValueEnum};
use orthtree_compare::joins::{self, Run};
use orthtree_compare::limits;
use orthtree_compare::points::uniform;
use orthtree_compare::say;
use orthtree_compare::scipy::{self, Scipy};
use std::path::PathBuf;
use std::process::ExitCode;

/// orthtree's periodic k-nearest, k-nearest self-join, pairs within r and pair counts beside
/// kiddo 6 and scipy's cKDTree.
#[derive(Parser, Debug)]
#[command(name = "joins_compare", allow_negative_numbers = true)]
struct Args {
    /// Points per workload
    #[arg(long, value_name = "N", default_value_t = 1_000_000,
          value_parser = limits::number(100usize, u32::MAX as usize))]
    n: usize,
    /// Queries of the periodic workload
    #[arg(long, value_name = "Q", default_value_t = 100_000,
          value_parser = limits::number(1usize, usize::MAX))]
    queries: usize,
    /// Timed runs per row, median reported
    #[arg(long, value_name = "R", default_value_t = 3, value_parser = limits::number(1usize, 1000))]
    reps: usize,
    /// Only this workload
    #[arg(long, value_name = "NAME")]
    workload: Option<Workload>,
    /// The Python with scipy (default: the venv of compare/scipy/setup.sh)
    #[arg(long, value_name = "PATH")]
    python: Option<PathBuf>,
}

/// The workloads, in the order they run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Workload {
    Periodic,
    SelfKnn,
    Pairs,
    Count,
}

/// Peak bytes per point: the points and the trees of each crate, and the self-join's tables
/// (orthtree's 16 and kiddo's 17 neighbours of 16 bytes per point, scipy's in its own
/// process), with a margin.
const PEAK_BYTES_PER_POINT: f64 = 1200.0;
/// Peak bytes per periodic query: the query and its 10 answers in each process.
const PEAK_BYTES_PER_QUERY: f64 = 600.0;

/// The parsed arguments, with the work they ask for checked against the memory.
fn parse() -> Args {
    let a = Args::parse();
    let bytes = a.n as f64 * PEAK_BYTES_PER_POINT + a.queries as f64 * PEAK_BYTES_PER_QUERY;
    if let Err(e) = limits::check_memory(&format!("--n {} --queries {}", a.n, a.queries), bytes) {
        use clap::CommandFactory;
        Args::command()
            .error(clap::error::ErrorKind::ValueValidation, e)
            .exit()
    }
    a
}

/// One row of the table: a workload, its thread count and each crate's run (`None`: the crate
/// has no such query or is not set up).
struct Row {
    name: String,
    threads: usize,
    runs: [Option<Run>; 3],
}

/// The crates of the columns.
const CRATES: [&str; 3] = ["orthtree", "kiddo", "scipy"];

/// Checks every rival's answer against orthtree's; `items`: whether index sums must agree.
fn check(row: &Row, items: bool) -> Result<(), String> {
    let ours = &row.runs[0].as_ref().expect("orthtree always runs").answer;
    for (name, run) in CRATES.iter().zip(&row.runs).skip(1) {
        if let Some(run) = run
            && !ours.agrees_with(&run.answer, items)
        {
            return Err(format!(
                "{}: {name} answered {:?}, orthtree {ours:?}",
                row.name, run.answer
            ));
        }
    }
    Ok(())
}

/// scipy's run of `name`, `None` when it is not set up.
fn scipy_run(
    sp: Option<&Scipy>,
    name: &str,
    points: &[[f64; 3]],
    queries: Option<&[[f64; 3]]>,
    args: &[String],
    reps: usize,
) -> Result<Option<Run>, String> {
    match sp {
        Some(s) => Ok(Some(
            s.run(name, points, queries, args, reps)?
                .into_run(points.len())?,
        )),
        None => Ok(None),
    }
}

fn run(a: &Args) -> Result<(), String> {
    let python = a.python.clone().unwrap_or_else(scipy::default_python);
    let sp = Scipy::find(&python);
    match &sp {
        Some(s) => eprintln!("scipy {} ({})", s.version, python.display()),
        None => say!("{}", scipy::NOT_SET_UP),
    }
    let sp = sp.as_ref();
    let wanted = |w: Workload| a.workload.is_none_or(|x| x == w);
    let (n, reps) = (a.n, a.reps);
    let mut rows = Vec::new();
    if wanted(Workload::Periodic) {
        let k = 10;
        eprintln!(
            "periodic: {n} uniform points, {} queries, k = {k}",
            a.queries
        );
        let points = uniform::<3>(n, 1);
        let queries = uniform::<3>(a.queries, 2);
        let args = [format!("--k={k}"), "--boxsize=1.0".into()];
        let row = Row {
            name: format!("periodic {k}-nearest, {} queries", a.queries),
            threads: 1,
            runs: [
                Some(joins::orthtree_periodic(&points, &queries, k, reps, false)),
                Some(joins::kiddo_periodic(&points, &queries, k, reps)),
                scipy_run(sp, "periodic", &points, Some(&queries), &args, reps)?,
            ],
        };
        check(&row, true)?;
        // The same queries as one batch, answered in Morton order, beside the same kiddo and
        // scipy runs (scipy's `query` takes the array of queries as one call too).
        let as_batch = Row {
            name: format!("periodic {k}-nearest, {} queries as a batch", a.queries),
            threads: 1,
            runs: [
                Some(joins::orthtree_periodic(&points, &queries, k, reps, true)),
                row.runs[1].clone(),
                row.runs[2].clone(),
            ],
        };
        check(&as_batch, true)?;
        rows.push(row);
        rows.push(as_batch);
    }
    let needs_surface =
        wanted(Workload::SelfKnn) || wanted(Workload::Pairs) || wanted(Workload::Count);
    let points = if needs_surface {
        joins::surface(n, 3)
    } else {
        Vec::new()
    };
    if wanted(Workload::SelfKnn) {
        let k = 16;
        let threads = joins::threads();
        eprintln!("self-knn: {n} surface points, k = {k}, {threads} threads");
        let workers = if threads > 1 { -1 } else { 1 };
        let args = [format!("--k={k}"), format!("--workers={workers}")];
        let row = Row {
            name: format!("self-join {k}-nearest"),
            threads,
            runs: [
                Some(joins::orthtree_self_knn(&points, k, reps)),
                Some(joins::kiddo_self_knn(&points, k, reps)),
                scipy_run(sp, "knn", &points, None, &args, reps)?,
            ],
        };
        // Ties may swap neighbours: counts and distance sums only.
        check(&row, false)?;
        rows.push(row);
    }
    let r = if needs_surface {
        joins::radius_for(&points, 10.0)
    } else {
        0.0
    };
    if wanted(Workload::Pairs) {
        eprintln!("pairs: {n} surface points, r = {r:.3e}");
        let args = [format!("--r={r:e}")];
        let row = Row {
            name: "all pairs within r (~10 per point)".into(),
            threads: 1,
            runs: [
                Some(joins::orthtree_pairs(&points, r, reps)),
                Some(joins::kiddo_pairs(&points, r, reps)),
                scipy_run(sp, "pairs", &points, None, &args, reps)?,
            ],
        };
        check(&row, true)?;
        // scipy's `query_pairs(r)` as called by default builds a Python set of tuples; the row
        // above times its fastest form (`output_type="ndarray"`). The same orthtree and kiddo
        // runs beside both.
        let set_args = [args[0].clone(), "--output=set".into()];
        let by_default = Row {
            name: "all pairs within r, scipy's default set output".into(),
            threads: 1,
            runs: [
                row.runs[0].clone(),
                row.runs[1].clone(),
                scipy_run(sp, "pairs", &points, None, &set_args, reps)?,
            ],
        };
        check(&by_default, true)?;
        rows.push(row);
        rows.push(by_default);
    }
    if wanted(Workload::Count) {
        let radii = joins::log_radii(r / 4.0, 4.0 * r, 20);
        eprintln!(
            "count: {n} surface points, 20 radii {:.3e}..{:.3e}",
            radii[0], radii[19]
        );
        let list: Vec<String> = radii.iter().map(|x| format!("{x:e}")).collect();
        let args = [format!("--radii={}", list.join(","))];
        let row = Row {
            name: "count_neighbors, 20 radii".into(),
            threads: 1,
            runs: [
                Some(joins::orthtree_counts(&points, &radii, reps)),
                None,
                scipy_run(sp, "count", &points, None, &args, reps)?,
            ],
        };
        check(&row, true)?;
        rows.push(row);
    }
    print_table(a, &rows);
    Ok(())
}

/// The markdown table: query and build times per crate, and each rival's time over orthtree's.
fn print_table(a: &Args, rows: &[Row]) {
    say!(
        "\nN = {}, 3-D f64, median of {} runs, ms (build: the crate's tree; x: rival time / orthtree time)\n",
        a.n, a.reps
    );
    say!("| workload | threads | orthtree | kiddo | scipy | kiddo / orthtree | scipy / orthtree |");
    say!("| --- | ---: | ---: | ---: | ---: | ---: | ---: |");
    let ms = |r: &Option<Run>, f: fn(&Run) -> f64| {
        r.as_ref().map_or("-".into(), |r| format!("{:.1}", f(r)))
    };
    let x = |r: &Option<Run>, ours: f64, f: fn(&Run) -> f64| {
        r.as_ref()
            .map_or("-".into(), |r| format!("{:.2}x", f(r) / ours))
    };
    for row in rows {
        let ours = row.runs[0].as_ref().expect("orthtree always runs");
        for (label, f) in [
            ("", (|r: &Run| r.query_ms) as fn(&Run) -> f64),
            (" (build)", |r: &Run| r.build_ms),
        ] {
            say!(
                "| {}{label} | {} | {} | {} | {} | {} | {} |",
                row.name,
                row.threads,
                ms(&row.runs[0], f),
                ms(&row.runs[1], f),
                ms(&row.runs[2], f),
                x(&row.runs[1], f(ours), f),
                x(&row.runs[2], f(ours), f),
            );
        }
    }
}

fn main() -> ExitCode {
    let a = parse();
    match run(&a) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
