//! Point quadtrees of uniform and of clustered random points in the unit square, before and after
//! 2:1 balance (de Berg et al., chapter 14), with a table of sizes and times and two pictures in
//! the style of Figure 14.5: `quadtree_uniform.svg` and `quadtree_clustered.svg`.
//!
//! ```text
//! cargo run --release --example quadtree_points [-- --n 2000] [--out-dir DIR]
//! ```

use orthtree::io::svg::point_tree_svg;
use orthtree::prelude::*;
use orthtree::{points::DEFAULT_BUCKET_SIZE, Aabb, Connectivity, Quadtree};
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};
use std::path::PathBuf;
use std::time::Instant;

#[macro_use]
#[path = "common/cli.rs"]
mod cli;
use cli::{Cli, CliError};

const USAGE: &str = "\
usage: quadtree_points [--n N] [--out-dir DIR]

Point quadtrees of uniform and clustered random points before and after 2:1 balance: a table,
and the pictures quadtree_uniform.svg and quadtree_clustered.svg.

options:
  --n N          points per data set, at least 1 (default 2000); counts whose trees and
                 pictures would not fit in memory are refused
  --out-dir DIR  the folder for the pictures, which must exist (default: the current folder)
  -h, --help     this text
";

/// Peak bytes per point: the points, the bucket-1 and the bucketed trees, their balanced copies
/// and the picture's text (measured: 520 B per point at n = 10^5, the peak resident memory with
/// `/usr/bin/time -v`); with a margin.
const PEAK_BYTES_PER_POINT: f64 = 800.0;

struct Args {
    n: usize,
    out_dir: PathBuf,
}

fn parse(cli: &mut Cli) -> Result<Args, CliError> {
    let mut args = Args {
        n: 2000,
        out_dir: PathBuf::from("."),
    };
    while let Some(flag) = cli.next_arg()? {
        match flag.as_str() {
            "--n" => args.n = cli.number("--n", 1, usize::MAX)?,
            "--out-dir" => {
                let raw = cli.value("--out-dir")?;
                cli::check_folder("--out-dir", &raw, raw.as_ref())?;
                args.out_dir = PathBuf::from(raw);
            }
            other => return Err(CliError::unknown(other)),
        }
    }
    cli::check_memory(
        &format!("--n {}", args.n),
        args.n as f64 * PEAK_BYTES_PER_POINT,
    )?;
    Ok(args)
}

/// `n` points uniform in the unit square.
fn uniform(n: usize, seed: u64) -> Vec<[f64; 2]> {
    let mut rng = SmallRng::seed_from_u64(seed);
    (0..n).map(|_| [rng.r#gen(), rng.r#gen()]).collect()
}

/// `n` points from a few Gaussian clusters (Box-Muller), redrawn until inside the unit square.
fn clustered(n: usize, seed: u64) -> Vec<[f64; 2]> {
    let mut rng = SmallRng::seed_from_u64(seed);
    let clusters: Vec<([f64; 2], f64)> = (0..5)
        .map(|_| {
            let centre = [rng.gen_range(0.15..0.85), rng.gen_range(0.15..0.85)];
            (centre, rng.gen_range(0.01..0.06))
        })
        .collect();
    let mut points = Vec::with_capacity(n);
    while points.len() < n {
        let (c, sigma) = clusters[rng.gen_range(0..clusters.len())];
        let (u1, u2): (f64, f64) = (1.0 - rng.r#gen::<f64>(), rng.r#gen());
        let r = sigma * (-2.0 * u1.ln()).sqrt();
        let t = std::f64::consts::TAU * u2;
        let p = [c[0] + r * t.cos(), c[1] + r * t.sin()];
        if p.iter().all(|x| (0.0..=1.0).contains(x)) {
            points.push(p);
        }
    }
    points
}

/// Builds, balances and checks one tree; prints a table row; returns the tree before and after
/// balance and whether every check passed.
fn run(name: &str, points: &[[f64; 2]], bucket: usize) -> (Quadtree<usize>, Quadtree<usize>, bool) {
    let entries: Vec<([f64; 2], usize)> = points.iter().enumerate().map(|(i, &p)| (p, i)).collect();
    let unit = Aabb::new([0.0, 0.0], [1.0, 1.0]).expect("the unit square is a box");
    let start = Instant::now();
    let tree = Quadtree::builder()
        .root_box(unit)
        .bucket_size(bucket)
        .build(&entries)
        .expect("points in the unit square are valid");
    let build = start.elapsed();
    let mut balanced = tree.clone();
    let start = Instant::now();
    let splits = balanced.balance(Connectivity::Face).len();
    let balance = start.elapsed();
    let valid = tree.validate().and(balanced.validate());
    let is_balanced = balanced.tree().is_balanced(Connectivity::Face);
    say!(
        "{name:<10} {bucket:>6} {:>7} {:>5} {:>7} {:>7} {:>7} {:>7} {:>7} {:>9.3} {:>9.3}  {:<5} {}",
        tree.len(),
        tree.depth(),
        tree.node_count(),
        tree.leaf_count(),
        balanced.node_count(),
        balanced.leaf_count(),
        splits,
        build.as_secs_f64() * 1e3,
        balance.as_secs_f64() * 1e3,
        if valid.is_ok() { "ok" } else { "FAIL" },
        is_balanced,
    );
    if let Err(e) = &valid {
        eprintln!("{name} (bucket {bucket}): validation failed: {e}");
    }
    (tree, balanced, valid.is_ok() && is_balanced)
}

fn main() {
    let Args { n, out_dir } = cli::parse_or_exit(USAGE, parse);

    let header = "data       bucket       n depth   nodes  leaves  nodes' leaves'  splits  build ms   bal. ms  valid balanced";
    say!("{header}");
    let mut ok = true;
    for (name, points) in [("uniform", uniform(n, 1)), ("clustered", clustered(n, 2))] {
        let (tree, balanced, good) = run(name, &points, 1);
        ok &= good;
        ok &= run(name, &points, DEFAULT_BUCKET_SIZE).2;
        let file = out_dir.join(format!("quadtree_{name}.svg"));
        match std::fs::write(&file, point_tree_svg(&tree, Some(&balanced))) {
            Ok(()) => say!("{:>10} wrote {}", "", file.display()),
            Err(e) => {
                eprintln!("error: cannot write {}: {e}", file.display());
                ok = false;
            }
        }
    }
    say!("(nodes', leaves': after 2:1 balance with face connectivity; solid lines in the");
    say!(" pictures are the bucket-1 quadtree, dotted ones the cells balance adds)");
    if !ok {
        std::process::exit(1);
    }
}
