//! Minimum-image k-nearest neighbours on a periodic cube, as in a particle simulation: 10^6
//! uniform random points in `[0, 1)^3` wrapping along every axis, 10^5 queries of the 10
//! nearest, timed against the same queries without the wrap, with a check of a sample of the
//! periodic answers against a scan over all 27 images.
//!
//! ```text
//! cargo run --release --example periodic_knn [-- --help]
//! ```

#[macro_use]
#[path = "common/cli.rs"]
mod cli;

use orthtree::prelude::*;
use orthtree::query::{OutsidePoints, Torus};
use orthtree::PointTree;
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};
use std::time::Instant;

const USAGE: &str = "\
usage: periodic_knn

Times 10^5 periodic 10-nearest queries on 10^6 points in the periodic unit cube against the same
queries without the wrap, and checks a sample against a scan over all 27 images. No options.";

fn main() -> Result<(), Box<dyn std::error::Error>> {
    if let Some(arg) = std::env::args().nth(1) {
        if arg == "--help" || arg == "-h" {
            say!("{USAGE}");
            return Ok(());
        }
        eprintln!("error: unknown argument {arg:?}\n\n{USAGE}");
        std::process::exit(2);
    }
    let (n, queries, k) = (1_000_000, 100_000, 10);
    let mut rng = SmallRng::seed_from_u64(21);
    let torus = Torus::wrapping([0.0; 3], [1.0; 3])?;
    let raw: Vec<[f64; 3]> = (0..n).map(|_| rng.r#gen()).collect();
    let pts = torus.prepare(&raw, OutsidePoints::Refuse)?;
    let entries: Vec<([f64; 3], usize)> = pts.iter().enumerate().map(|(i, p)| (*p, i)).collect();
    let start = Instant::now();
    let tree = PointTree::new(&entries)?;
    say!(
        "build of {n} points: {:.3} s",
        start.elapsed().as_secs_f64()
    );
    let qs: Vec<[f64; 3]> = (0..queries).map(|_| rng.r#gen()).collect();

    let start = Instant::now();
    let mut sum = 0.0;
    for q in &qs {
        sum += tree.periodic_k_nearest(&torus, q, k)?[k - 1].distance;
    }
    let periodic = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let mut plain_sum = 0.0;
    for q in &qs {
        plain_sum += tree.k_nearest(q, k)?[k - 1].distance;
    }
    let plain = start.elapsed().as_secs_f64();
    say!("{queries} periodic k-nearest (k = {k}): {periodic:.3} s (mean k-th squared distance {:.3e})", sum / queries as f64);
    say!(
        "{queries} plain k-nearest    (k = {k}): {plain:.3} s (mean k-th squared distance {:.3e})",
        plain_sum / queries as f64
    );

    let metric = torus.squared_euclidean();
    for q in qs.iter().take(20) {
        let got = tree.periodic_k_nearest(&torus, q, k)?;
        let mut all: Vec<f64> = pts
            .iter()
            .map(|p| {
                let mut best = f64::INFINITY;
                for code in 0..27 {
                    let s = [code % 3, code / 3 % 3, code / 9].map(|c| f64::from(c) - 1.0);
                    best = best.min((0..3).map(|a| (q[a] - p[a] - s[a]).powi(2)).sum());
                }
                best
            })
            .collect();
        all.sort_by(f64::total_cmp);
        for (nb, want) in got.iter().zip(&all) {
            assert!((nb.distance - want).abs() <= 1e-12);
            assert_eq!(
                nb.distance,
                orthtree::query::Metric::distance(&metric, q, nb.point)
            );
        }
    }
    say!("20 periodic answers agree with a scan over all 27 images");
    Ok(())
}
