//! orthtree's voxel downsampling and statistical outlier removal beside Open3D's
//! `voxel_down_sample` and `remove_statistical_outlier` (through its driver script), on the
//! same seeded points: prints a markdown table of median times and how many times faster
//! orthtree is.
//!
//! ```sh
//! compare/open3d/setup.sh       # once: open3d-cpu 0.20.0 in target/open3d-venv
//! cargo run --release -p orthtree-compare --bin cloud_compare
//! cargo run --release -p orthtree-compare --features rayon --bin cloud_compare -- --n 1000000
//! ```
//!
//! Workloads (N uniform points in the unit cube, `f64`):
//! - `voxel`: one point per occupied voxel of side `--voxel`, the centroid of its points. The
//!   grid is Open3D's: its voxels start half a voxel below the points' lowest corner, so both
//!   give the same voxels (a point exactly on a voxel face goes down in orthtree, up in Open3D;
//!   uniform random points almost never lie on one).
//! - `outliers`: Open3D's rule with `--k` neighbours (the point itself among them, as Open3D
//!   counts) and `--ratio` deviations: orthtree's `remove_statistical` with `k - 1` others, whose
//!   scores are Open3D's times `k / (k - 1)` for every point, so both keep the same points.
//!   Open3D runs its neighbour searches on all cores (OpenMP); orthtree on all of rayon's
//!   threads with the `rayon` feature, else on one.
//!
//! The output counts (voxels, points kept) and the sums of the output points' squared norms
//! are printed for both; times are medians of `--reps` runs after one untimed warm-up.

use clap::{Parser, ValueEnum};
use orthtree::cloud::voxel::{Representative, VoxelGrid};
use orthtree::cloud::{outliers, Cloud};
use orthtree::geom::Aabb;
use orthtree_compare::limits;
use orthtree_compare::points::uniform;
use orthtree_compare::python::PythonRival;
use orthtree_compare::say;
use orthtree_compare::timing;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// orthtree's voxel downsampling and statistical outlier removal beside Open3D's.
#[derive(Parser, Debug)]
#[command(name = "cloud_compare")]
struct Args {
    /// Points per workload
    #[arg(long, value_name = "N", default_value_t = 10_000_000,
          value_parser = limits::number(100usize, u32::MAX as usize))]
    n: usize,
    /// The voxel side of the voxel workload
    #[arg(long, value_name = "SIZE", default_value_t = 0.01, value_parser = limits::number(1e-6, 1.0))]
    voxel: f64,
    /// Neighbours of the outlier workload, the point itself included (Open3D's nb_neighbors)
    #[arg(long, value_name = "K", default_value_t = 20, value_parser = limits::number(2usize, 1000))]
    k: usize,
    /// Deviations above the mean score a point may lie (Open3D's std_ratio)
    #[arg(long, value_name = "R", default_value_t = 2.0, value_parser = limits::number(0.0, 1e6))]
    ratio: f64,
    /// Timed runs per row, median reported
    #[arg(long, value_name = "R", default_value_t = 3, value_parser = limits::number(1usize, 1000))]
    reps: usize,
    /// Only this workload
    #[arg(long, value_name = "NAME")]
    workload: Option<Workload>,
    /// The Python with Open3D (default: the venv of compare/open3d/setup.sh)
    #[arg(long, value_name = "PATH")]
    python: Option<PathBuf>,
}

/// The workloads, in the order they run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Workload {
    Voxel,
    Outliers,
}

/// Peak bytes per point: the points in both processes, the tree and the neighbour table
/// (16 bytes per neighbour), with a margin.
const PEAK_BYTES_PER_POINT: f64 = 1000.0;

/// What one side gave: median ms, points out, the sum of their squared norms.
struct Side {
    ms: f64,
    count: usize,
    dist2: f64,
}

/// The sum of the points' squared norms.
fn sum_of_squares(points: &[[f64; 3]]) -> f64 {
    points.iter().flatten().map(|x| x * x).sum()
}

/// orthtree's downsampling on Open3D's grid.
fn voxel_orthtree(cloud: &Cloud<f64>, voxel: f64, reps: usize) -> Result<Side, String> {
    let run = || -> Result<(usize, f64), String> {
        // Open3D's grid: voxels from half a voxel below the lowest point. The grid from the
        // lowest point ([`VoxelGrid::with_size`], which checks and bounds the points) has the
        // lowest corner; its cube, moved down by half a voxel, covers the points.
        let tight = VoxelGrid::with_size(&cloud.points, voxel).map_err(|e| e.to_string())?;
        let cube = tight.root_box::<f64>().map_err(|e| e.to_string())?;
        let bounds = Aabb {
            min: cube.min.map(|m| m - voxel / 2.0),
            max: cube.max,
        };
        let grid = VoxelGrid::for_box(&bounds, voxel).map_err(|e| e.to_string())?;
        let out = grid
            .downsample(cloud, Representative::Centroid)
            .map_err(|e| e.to_string())?;
        Ok((out.len(), sum_of_squares(&out.points)))
    };
    let (ms, out) = timing::time(reps, run);
    let (count, dist2) = out?;
    Ok(Side { ms, count, dist2 })
}

/// orthtree's statistical outlier removal with `k - 1` others, on rayon's threads with the
/// `rayon` feature.
fn outliers_orthtree(
    cloud: &Cloud<f64>,
    k: usize,
    ratio: f64,
    reps: usize,
) -> Result<Side, String> {
    let run = || -> Result<(usize, f64), String> {
        #[cfg(feature = "rayon")]
        let removed = outliers::par_remove_statistical(cloud, k - 1, ratio);
        #[cfg(not(feature = "rayon"))]
        let removed = outliers::remove_statistical(cloud, k - 1, ratio);
        let (kept, _) = removed.map_err(|e| e.to_string())?;
        Ok((kept.len(), sum_of_squares(&kept.points)))
    };
    let (ms, out) = timing::time(reps, run);
    let (count, dist2) = out?;
    Ok(Side { ms, count, dist2 })
}

/// Open3D's run of `workload`, when it is set up.
fn open3d_side(
    open3d: &PythonRival,
    workload: &str,
    points: &[[f64; 3]],
    args: &[String],
    reps: usize,
) -> Result<Side, String> {
    let run = open3d.run(workload, points, args, reps)?;
    Ok(Side {
        ms: run.query_ms,
        count: run.count.unwrap_or(0) as usize,
        dist2: run.dist2.unwrap_or(f64::NAN),
    })
}

fn main() -> ExitCode {
    let a = Args::parse();
    let bytes = a.n as f64 * PEAK_BYTES_PER_POINT;
    if let Err(e) = limits::check_memory(&format!("--n {}", a.n), bytes) {
        eprintln!("error: {e}");
        return ExitCode::from(2);
    }
    let python = a.python.clone().unwrap_or_else(|| {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/open3d-venv/bin/python")
    });
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("open3d/cloud_ops.py");
    let open3d = PythonRival::find(&python, "open3d", script);
    if open3d.is_none() {
        eprintln!("open3d not set up: run compare/open3d/setup.sh (orthtree's rows only)");
    }
    let points: Vec<[f64; 3]> = uniform::<3>(a.n, 11);
    // (the library's way to a large cloud: memory for huge pages, as its file readers do)
    let mut cloud = Cloud::with_capacity(points.len());
    cloud.points.extend_from_slice(&points);
    say!("| workload | orthtree ms | open3d ms | open3d / orthtree | points out (orthtree / open3d) | sum of squared norms (orthtree / open3d) |");
    say!("| --- | ---: | ---: | ---: | --- | --- |");
    let wanted = |w: Workload| a.workload.is_none_or(|x| x == w);
    let rows: [(Workload, &str, Vec<String>); 2] = [
        (
            Workload::Voxel,
            "voxel",
            vec!["--size".into(), a.voxel.to_string()],
        ),
        (
            Workload::Outliers,
            "outliers",
            vec![
                "--k".into(),
                a.k.to_string(),
                "--ratio".into(),
                a.ratio.to_string(),
            ],
        ),
    ];
    for (w, name, args) in rows.iter().filter(|(w, _, _)| wanted(*w)) {
        let ours = match w {
            Workload::Voxel => voxel_orthtree(&cloud, a.voxel, a.reps),
            Workload::Outliers => outliers_orthtree(&cloud, a.k, a.ratio, a.reps),
        };
        let ours = match ours {
            Ok(s) => s,
            Err(e) => {
                eprintln!("error: orthtree's {name}: {e}");
                return ExitCode::FAILURE;
            }
        };
        let theirs = open3d
            .as_ref()
            .map(|o| open3d_side(o, name, &points, args, a.reps));
        match theirs {
            Some(Ok(t)) => say!(
                "| {name} (N = {}) | {:.1} | {:.1} | {:.2}x | {} / {} | {:.9e} / {:.9e} |",
                a.n,
                ours.ms,
                t.ms,
                t.ms / ours.ms,
                ours.count,
                t.count,
                ours.dist2,
                t.dist2
            ),
            Some(Err(e)) => {
                eprintln!("error: {e}");
                return ExitCode::FAILURE;
            }
            None => say!(
                "| {name} (N = {}) | {:.1} | - | - | {} / - | {:.9e} / - |",
                a.n,
                ours.ms,
                ours.count,
                ours.dist2
            ),
        }
    }
    ExitCode::SUCCESS
}
