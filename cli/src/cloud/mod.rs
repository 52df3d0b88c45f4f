//! `orthtree cloud`: point-cloud work over the library's `cloud` module and its formats.
//!
//! ```sh
//! orthtree cloud info [CLOUD]                       # count, bounds, attributes, density
//! orthtree cloud downsample [CLOUD] --voxel SIZE    # one point per occupied voxel
//! orthtree cloud outliers [CLOUD] --k K --ratio R   # statistical outlier removal
//! orthtree cloud diff [A B] --voxel SIZE            # the XOR change map of two occupancies
//! orthtree cloud index [CLOUD] [--budget BYTES]     # the saved point tree
//! ```
//!
//! Clouds are PLY, XYZ/CSV or LAS/LAZ (features `las`, `laz`), by extension; results are PLY,
//! pictures PNG (feature `png`) or SVG. With no file, a built-in synthetic scan
//! ([`scan`]): two epochs of it for `diff`.

mod commands;
mod index;
mod input;
mod picture;
pub mod scan;

use crate::limits;
use crate::Failure;
use std::path::PathBuf;

/// Point clouds: info, voxel downsampling, outlier removal, change maps, saved trees
///
/// Reads PLY, XYZ/CSV (.xyz, .csv, .txt) and LAS/LAZ (with the features `las`, `laz`), chosen by
/// extension; LAS coordinates are taken to world units by the file's scale and offset. With no
/// file: a built-in synthetic scan (terrain, buildings, noise; 300 000 points, seeded). Writes
/// PLY results and a top-down picture (PNG with the `png` feature, else SVG).
#[derive(clap::Args, Debug)]
#[command(after_help = crate::EXIT_CODES)]
pub struct CloudArgs {
    #[command(subcommand)]
    command: CloudCommand,
}

#[derive(clap::Subcommand, Debug)]
enum CloudCommand {
    Info(InfoArgs),
    Downsample(DownsampleArgs),
    Outliers(OutliersArgs),
    Diff(DiffArgs),
    Index(IndexArgs),
}

/// Where a command's cloud comes from, and what it writes.
#[derive(clap::Args, Debug, Clone)]
pub struct Source {
    /// The built-in scan's number of points (no file given): at most 4e9 for `index
    /// --budget`, which streams them; the other commands refuse what memory cannot hold
    #[arg(long, value_name = "N", default_value_t = scan::DEFAULT_POINTS,
          value_parser = limits::number(1usize, 4_000_000_000))]
    points: usize,
    /// The built-in scan's seed
    #[arg(long, value_name = "SEED", default_value_t = 1)]
    seed: u64,
    /// Write no files (no PLY, no picture, no tree)
    #[arg(long)]
    no_files: bool,
}

/// Count, bounds, attributes and density of a cloud; a density heat map
///
/// Prints the number of points, their bounding box, the attribute columns, the density over the
/// x-y footprint and per occupied voxel of --voxel, and writes a top-down heat map of the point
/// density as PICTURE.png (feature png) or PICTURE.svg.
#[derive(clap::Args, Debug)]
#[command(after_help = crate::EXIT_CODES, allow_negative_numbers = true)]
pub struct InfoArgs {
    /// The cloud: .ply, .xyz, .csv, .txt, .las, .laz (none: the built-in scan)
    #[arg(value_name = "CLOUD")]
    input: Option<String>,
    /// The voxel side for the occupancy figures, in the cloud's units
    #[arg(long, value_name = "SIZE", default_value_t = 1.0, value_parser = positive)]
    voxel: f64,
    /// The picture's path without extension
    #[arg(long, value_name = "PICTURE", default_value = "density", value_parser = limits::output_path)]
    picture: PathBuf,
    #[command(flatten)]
    source: Source,
}

/// Voxel-grid downsampling: one point per occupied voxel
///
/// Keeps one point per occupied voxel of side SIZE (voxels on the tree's cells, the grid's
/// corner at the cloud's lowest corner): the centroid with the attributes averaged, or the
/// point nearest it with its own. Writes OUT (PLY) and a density picture of the result.
#[derive(clap::Args, Debug)]
#[command(after_help = crate::EXIT_CODES, allow_negative_numbers = true)]
pub struct DownsampleArgs {
    /// The cloud: .ply, .xyz, .csv, .txt, .las, .laz (none: the built-in scan)
    #[arg(value_name = "CLOUD")]
    input: Option<String>,
    /// The voxel side, in the cloud's units
    #[arg(long, value_name = "SIZE", value_parser = positive)]
    voxel: f64,
    /// centroid: the mean of the voxel's points; nearest: the point nearest that mean
    #[arg(long, value_enum, default_value = "centroid")]
    representative: RepresentativeArg,
    /// The result (PLY)
    #[arg(long, value_name = "OUT", default_value = "downsampled.ply", value_parser = limits::output_path)]
    out: PathBuf,
    /// The picture's path without extension
    #[arg(long, value_name = "PICTURE", default_value = "downsampled", value_parser = limits::output_path)]
    picture: PathBuf,
    #[command(flatten)]
    source: Source,
}

/// Which point stands for a voxel.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
enum RepresentativeArg {
    Centroid,
    Nearest,
}

/// Statistical outlier removal (Open3D's and PCL's rule)
///
/// Drops every point whose mean distance to its K nearest other points exceeds the cloud's mean
/// of those distances plus R standard deviations. Writes the points kept to OUT (PLY).
#[derive(clap::Args, Debug)]
#[command(after_help = crate::EXIT_CODES, allow_negative_numbers = true)]
pub struct OutliersArgs {
    /// The cloud: .ply, .xyz, .csv, .txt, .las, .laz (none: the built-in scan)
    #[arg(value_name = "CLOUD")]
    input: Option<String>,
    /// The neighbours per point, 1 to 1000
    #[arg(long, value_name = "K", default_value_t = 20, value_parser = limits::number(1usize, 1000))]
    k: usize,
    /// The deviations above the mean a point may lie (any finite number)
    #[arg(long, value_name = "R", default_value_t = 2.0, value_parser = finite)]
    ratio: f64,
    /// The points kept (PLY)
    #[arg(long, value_name = "OUT", default_value = "inliers.ply", value_parser = limits::output_path)]
    out: PathBuf,
    #[command(flatten)]
    source: Source,
}

/// Change map of two scans: the XOR of their voxel occupancies
///
/// Voxelises both clouds on one grid (the box of both, voxels of side SIZE), as region trees,
/// and XORs them. Writes the changed voxels' centres to OUT (PLY, with a `change` column: -1
/// gone, +1 new) and a top-down change map (gone red, new green). With no files: two epochs
/// of the built-in scan (one building torn down, one built).
#[derive(clap::Args, Debug)]
#[command(after_help = crate::EXIT_CODES, allow_negative_numbers = true)]
pub struct DiffArgs {
    /// The two clouds, before and after (none: the built-in scan's two epochs)
    #[arg(value_name = "CLOUD", num_args = 0..=2)]
    inputs: Vec<String>,
    /// The voxel side, in the clouds' units
    #[arg(long, value_name = "SIZE", value_parser = positive)]
    voxel: f64,
    /// The changed voxels (PLY)
    #[arg(long, value_name = "OUT", default_value = "changes.ply", value_parser = limits::output_path)]
    out: PathBuf,
    /// The picture's path without extension
    #[arg(long, value_name = "PICTURE", default_value = "changes", value_parser = limits::output_path)]
    picture: PathBuf,
    #[command(flatten)]
    source: Source,
}

/// Build the point tree of a cloud and save it (the library's saved-tree format)
///
/// Builds an octree of the cloud's points (f64 world coordinates, each point's index as its u32
/// item) and writes it in the saved format, then opens the file again, checks it and runs a box
/// query. With --budget the build is out of core: the points are sorted in runs that fit BYTES,
/// spilled to temporary files next to OUT and merged, so that clouds larger than memory can be
/// indexed (the built-in scan is then streamed, never held; a file is read whole first); the
/// file is the same, byte for byte, and is checked and queried through a memory map.
#[derive(clap::Args, Debug)]
#[command(after_help = crate::EXIT_CODES, allow_negative_numbers = true)]
pub struct IndexArgs {
    /// The cloud: .ply, .xyz, .csv, .txt, .las, .laz (none: the built-in scan)
    #[arg(value_name = "CLOUD")]
    input: Option<String>,
    /// The saved tree
    #[arg(long, value_name = "OUT", default_value = "cloud.tree", value_parser = limits::output_path)]
    out: PathBuf,
    /// The points per leaf, 1 to 2^20
    #[arg(long, value_name = "N", default_value_t = orthtree::points::DEFAULT_BUCKET_SIZE,
          value_parser = limits::number(1usize, 1 << 20))]
    bucket_size: usize,
    /// Build out of core within this memory budget in bytes, from 1M to 2^50 (suffixes k, M,
    /// G for 2^10, 2^20, 2^30)
    #[arg(long, value_name = "BYTES", value_parser = parse_bytes)]
    budget: Option<u64>,
    #[command(flatten)]
    source: Source,
}

/// A positive finite number.
fn positive(raw: &str) -> Result<f64, String> {
    match raw.trim().parse::<f64>() {
        Ok(v) if v > 0.0 && v.is_finite() => Ok(v),
        _ => Err("expected a positive finite number".into()),
    }
}

/// A finite number.
fn finite(raw: &str) -> Result<f64, String> {
    match raw.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err("expected a finite number".into()),
    }
}

/// A byte count with an optional binary suffix, at least 1 MiB.
fn parse_bytes(raw: &str) -> Result<u64, String> {
    let raw = raw.trim();
    let (digits, shift) = match raw.char_indices().last() {
        Some((i, 'k' | 'K')) => (&raw[..i], 10),
        Some((i, 'm' | 'M')) => (&raw[..i], 20),
        Some((i, 'g' | 'G')) => (&raw[..i], 30),
        _ => (raw, 0),
    };
    let bad = || format!("expected a byte count from 1M to 2^50 (suffixes k, M, G), not {raw:?}");
    let n: u64 = digits.parse().map_err(|_| bad())?;
    let bytes = n
        .checked_shl(shift)
        .filter(|b| b >> shift == n)
        .ok_or_else(bad)?;
    if !(1 << 20..=1 << 50).contains(&bytes) {
        return Err(bad());
    }
    Ok(bytes)
}

impl CloudArgs {
    /// The name of the command given (`info`, `downsample`, ...).
    pub fn name(&self) -> &'static str {
        match &self.command {
            CloudCommand::Info(_) => "info",
            CloudCommand::Downsample(_) => "downsample",
            CloudCommand::Outliers(_) => "outliers",
            CloudCommand::Diff(_) => "diff",
            CloudCommand::Index(_) => "index",
        }
    }
}

/// Runs `orthtree cloud`.
pub fn run(args: &CloudArgs) -> Result<(), Failure> {
    match &args.command {
        CloudCommand::Info(a) => commands::info(a),
        CloudCommand::Downsample(a) => commands::downsample(a),
        CloudCommand::Outliers(a) => commands::outliers(a),
        CloudCommand::Diff(a) => commands::diff(a),
        CloudCommand::Index(a) => index::run(a),
    }
}
