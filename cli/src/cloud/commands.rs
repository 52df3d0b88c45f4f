//! The five `orthtree cloud` commands over the library's public API: each loads its cloud (a
//! file or the built-in scan), does its work in phases that show a spinner past a second, prints
//! a summary and writes its files.

use super::input::{self, to_world};
use super::picture::{self, Raster};
use super::{scan, DiffArgs, DownsampleArgs, InfoArgs, OutliersArgs, Source};
use crate::limits;
use crate::progress::Phase;
use crate::Failure;
use orthtree::cloud::voxel::{Representative, VoxelGrid};
use orthtree::cloud::{outliers, Cloud, CloudError, Column};
use orthtree::geom::Aabb;
use orthtree::image::RegionTree;
use std::time::Instant;

/// Bytes a point costs in these commands beyond the cloud itself (the tree's points, items and
/// sort keys, the world copy): the estimate checked against memory before work starts.
const BYTES_PER_POINT: f64 = 120.0;

/// The cloud of `input`, or the built-in scan of epoch `epoch`, with a name for messages.
pub fn load(
    input: Option<&str>,
    src: &Source,
    epoch: u32,
) -> Result<(Cloud<f64>, String), Failure> {
    let start = Instant::now();
    let (cloud, name) = match input {
        Some(path) => {
            input::format_of(path)?;
            let _phase = Phase::start(&format!("reading {path}"));
            (input::read(path)?, path.to_string())
        }
        None => {
            let what = format!("--points {}", src.points);
            limits::check_memory(&what, src.points as f64 * BYTES_PER_POINT)
                .map_err(Failure::Usage)?;
            let _phase = Phase::start("making the built-in scan");
            let name = format!(
                "built-in scan (seed {}, epoch {epoch}, {} points)",
                src.seed, src.points
            );
            (to_world(scan::scan(src.seed, src.points, epoch)), name)
        }
    };
    say!(
        "input:       {name}: {} points, read in {:.1} ms",
        cloud.len(),
        start.elapsed().as_secs_f64() * 1e3
    );
    Ok((cloud, name))
}

/// A library error on `name`: a grid too fine or an occupancy too large is a usage error (the
/// argument asks for too much), anything else an input error.
fn cloud_failure(name: &str, arg: &str, e: CloudError) -> Failure {
    match e {
        CloudError::TooFine { .. } | CloudError::Image(_) => {
            Failure::Usage(format!("{arg}: {name}: {e}"))
        }
        _ => Failure::Input(format!("{name}: {e}")),
    }
}

/// The bounding box of the points (the origin for none).
pub fn bounds<'a>(points: impl IntoIterator<Item = &'a [f64; 3]>) -> Aabb<f64, 3> {
    let mut min = [f64::INFINITY; 3];
    let mut max = [f64::NEG_INFINITY; 3];
    let mut empty = true;
    for p in points {
        empty = false;
        for k in 0..3 {
            min[k] = min[k].min(p[k]);
            max[k] = max[k].max(p[k]);
        }
    }
    if empty {
        return Aabb {
            min: [0.0; 3],
            max: [0.0; 3],
        };
    }
    Aabb { min, max }
}

/// The box holding both boxes.
fn union(a: &Aabb<f64, 3>, b: &Aabb<f64, 3>) -> Aabb<f64, 3> {
    Aabb {
        min: core::array::from_fn(|k| a.min[k].min(b.min[k])),
        max: core::array::from_fn(|k| a.max[k].max(b.max[k])),
    }
}

/// Writes the density heat map of `points` to `stem` (unless `--no-files`).
fn density_picture(
    points: &[[f64; 3]],
    stem: &std::path::Path,
    src: &Source,
) -> Result<(), Failure> {
    if src.no_files {
        return Ok(());
    }
    let b = bounds(points);
    let mut raster = Raster::for_box(
        [b.min[0], b.min[1]],
        [b.max[0], b.max[1]],
        points.len(),
        12.0,
    );
    for p in points {
        raster.add(p[0], p[1], 0, 1.0);
    }
    let path = picture::write(&raster.density_rgb(), raster.size(), stem)?;
    let (w, h) = raster.size();
    say!(
        "picture:     {} ({w} x {h} cells of {:.3}, point density, log scale)",
        path.display(),
        raster.cell()
    );
    Ok(())
}

/// A coordinate or measure for a report: three decimals in the everyday range, else in
/// scientific notation (a coordinate of 1e38 is not 39 digits of noise).
fn report_number(x: f64) -> String {
    if x == 0.0 || (1e-3..1e9).contains(&x.abs()) {
        format!("{x:.3}")
    } else {
        format!("{x:.4e}")
    }
}

/// `count` points per unit^2 of `area`, or why there is no such density (no points, or all of
/// them on a line or at one point of the x-y plane).
fn per_area(count: usize, area: f64) -> String {
    if count == 0 {
        "no points".to_string()
    } else if area > 0.0 && area.is_finite() {
        format!("{} points per unit^2", report_number(count as f64 / area))
    } else if area > 0.0 {
        "no finite area".to_string()
    } else {
        "no area (the points lie on a line or at one point)".to_string()
    }
}

fn ms(start: Instant) -> String {
    format!("{:.1} ms", start.elapsed().as_secs_f64() * 1e3)
}

/// `orthtree cloud info`.
pub fn info(a: &InfoArgs) -> Result<(), Failure> {
    let (cloud, name) = load(a.input.as_deref(), &a.source, 0)?;
    let b = bounds(&cloud.points);
    if cloud.is_empty() {
        say!("bounds:      none (no points)");
    } else {
        say!(
            "bounds:      x {} .. {}, y {} .. {}, z {} .. {}",
            report_number(b.min[0]),
            report_number(b.max[0]),
            report_number(b.min[1]),
            report_number(b.max[1]),
            report_number(b.min[2]),
            report_number(b.max[2])
        );
    }
    let names = cloud.attributes.names();
    say!(
        "attributes:  {}",
        if names.is_empty() {
            "none".to_string()
        } else {
            names.join(", ")
        }
    );
    let area = (b.max[0] - b.min[0]) * (b.max[1] - b.min[1]);
    let start = Instant::now();
    let phase = Phase::start("voxelising");
    let grid = VoxelGrid::with_size(&cloud.points, a.voxel)
        .map_err(|e| cloud_failure(&name, "--voxel", e))?;
    let voxels = grid
        .occupied_voxels(&cloud.points)
        .map_err(|e| cloud_failure(&name, "--voxel", e))?;
    drop(phase);
    let columns = {
        let mut c: Vec<[u32; 3]> = voxels.iter().map(|v| v.coords()).collect();
        c.iter_mut().for_each(|x| x[2] = 0);
        c.sort_unstable();
        c.dedup();
        c.len()
    };
    say!(
        "density:     x-y box: {}; occupied voxels of side {}: {} ({:.2} points each); \
         occupied columns: {} ({})",
        per_area(cloud.len(), area),
        a.voxel,
        voxels.len(),
        cloud.len() as f64 / voxels.len().max(1) as f64,
        columns,
        per_area(cloud.len(), columns as f64 * a.voxel * a.voxel),
    );
    say!("time:        voxelised in {}", ms(start));
    density_picture(&cloud.points, &a.picture, &a.source)
}

/// `orthtree cloud downsample`.
pub fn downsample(a: &DownsampleArgs) -> Result<(), Failure> {
    let (cloud, name) = load(a.input.as_deref(), &a.source, 0)?;
    let start = Instant::now();
    let phase = Phase::start("downsampling");
    let grid = VoxelGrid::with_size(&cloud.points, a.voxel)
        .map_err(|e| cloud_failure(&name, "--voxel", e))?;
    let representative = match a.representative {
        super::RepresentativeArg::Centroid => Representative::Centroid,
        super::RepresentativeArg::Nearest => Representative::Nearest,
    };
    let down = grid
        .downsample(&cloud, representative)
        .map_err(|e| cloud_failure(&name, "--voxel", e))?;
    drop(phase);
    say!(
        "downsample:  {} points -> {} ({:?} of each voxel of side {}, grid level {}) in {}",
        cloud.len(),
        down.len(),
        representative,
        a.voxel,
        grid.level(),
        ms(start)
    );
    if !a.source.no_files {
        input::write_ply(&down, &a.out)?;
        say!("wrote:       {}", a.out.display());
    }
    density_picture(&down.points, &a.picture, &a.source)
}

/// `orthtree cloud outliers`.
pub fn outliers(a: &OutliersArgs) -> Result<(), Failure> {
    let (cloud, name) = load(a.input.as_deref(), &a.source, 0)?;
    // The scores and verdicts (9 bytes per point) beside the tree: no neighbour table is held.
    let need = cloud.len() as f64 * (9.0 + BYTES_PER_POINT);
    limits::check_memory(&format!("--k {} on {} points", a.k, cloud.len()), need)
        .map_err(Failure::Usage)?;
    let start = Instant::now();
    let phase = Phase::start("finding the outliers");
    #[cfg(feature = "rayon")]
    let removed = outliers::par_remove_statistical(&cloud, a.k, a.ratio);
    #[cfg(not(feature = "rayon"))]
    let removed = outliers::remove_statistical(&cloud, a.k, a.ratio);
    let (kept, _) = removed.map_err(|e| cloud_failure(&name, "--k", e))?;
    drop(phase);
    say!(
        "outliers:    {} of {} points removed ({} kept; k = {}, ratio {}) in {}",
        cloud.len() - kept.len(),
        cloud.len(),
        kept.len(),
        a.k,
        a.ratio,
        ms(start)
    );
    if !a.source.no_files {
        input::write_ply(&kept, &a.out)?;
        say!("wrote:       {}", a.out.display());
    }
    Ok(())
}

/// `orthtree cloud diff`.
pub fn diff(a: &DiffArgs) -> Result<(), Failure> {
    let (before, after) = match &a.inputs[..] {
        [] => (load(None, &a.source, 0)?, load(None, &a.source, 1)?),
        [x, y] => {
            input::format_of(x)?;
            input::format_of(y)?;
            (load(Some(x), &a.source, 0)?, load(Some(y), &a.source, 1)?)
        }
        _ => {
            return Err(Failure::Usage(
                "give two clouds (before, after), or none for the built-in scan".into(),
            ))
        }
    };
    let ((a_cloud, a_name), (b_cloud, b_name)) = (before, after);
    let start = Instant::now();
    let phase = Phase::start("voxelising both clouds");
    let both = union(&bounds(&a_cloud.points), &bounds(&b_cloud.points));
    let both_name = format!("{a_name} and {b_name}");
    let grid =
        VoxelGrid::for_box(&both, a.voxel).map_err(|e| cloud_failure(&both_name, "--voxel", e))?;
    let occupancy = |c: &Cloud<f64>, name: &str| {
        grid.occupancy_of(&c.points)
            .map_err(|e| cloud_failure(name, "--voxel", e))
    };
    let (occ_a, occ_b) = (occupancy(&a_cloud, &a_name)?, occupancy(&b_cloud, &b_name)?);
    let image = |e| cloud_failure(&both_name, "--voxel", CloudError::Image(e));
    let changed = occ_a.try_symmetric_difference(&occ_b).map_err(image)?;
    let gone = occ_a.try_difference(&occ_b).map_err(image)?;
    let new = occ_b.try_difference(&occ_a).map_err(image)?;
    drop(phase);
    say!(
        "occupancy:   {} and {} voxels of side {} (grid level {}; region trees of {} and {} nodes)",
        occ_a.len(),
        occ_b.len(),
        a.voxel,
        grid.level(),
        occ_a.node_count(),
        occ_b.node_count()
    );
    say!(
        "change:      {} voxels changed (XOR, {} nodes): {} gone, {} new, in {}",
        changed.len(),
        changed.node_count(),
        gone.len(),
        new.len(),
        ms(start)
    );
    if a.source.no_files {
        return Ok(());
    }
    let corner = grid
        .root_box::<f64>()
        .map_err(|e| Failure::Input(e.to_string()))?
        .min;
    let size = grid.voxel_size();
    let mut points = Vec::new();
    let mut change = Vec::new();
    // One cell per voxel column (at most the format's side).
    let columns = f64::from(grid.side_voxels()).powi(2) as usize;
    let mut raster = Raster::for_box(
        [both.min[0], both.min[1]],
        [both.max[0], both.max[1]],
        columns,
        1.0,
    );
    for (channel, tree, sign) in [(0, &gone, -1.0), (1, &new, 1.0)] {
        for_each_voxel(tree, |c, side| {
            let lo = [0, 1].map(|k| corner[k] + f64::from(c[k]) * size);
            let hi = [0, 1].map(|k| lo[k] + f64::from(side) * size);
            raster.add_rect(lo, hi, channel, f64::from(side).powi(3));
            for dz in 0..side {
                for dy in 0..side {
                    for dx in 0..side {
                        let v = [c[0] + dx, c[1] + dy, c[2] + dz];
                        points.push(core::array::from_fn(|k| {
                            corner[k] + (f64::from(v[k]) + 0.5) * size
                        }));
                        change.push(sign);
                    }
                }
            }
        });
    }
    let mut out = Cloud::from_points(points);
    out.attributes.extra.push(Column {
        name: "change".into(),
        values: change,
    });
    input::write_ply(&out, &a.out)?;
    say!(
        "wrote:       {} ({} voxel centres)",
        a.out.display(),
        out.len()
    );
    let path = picture::write(&raster.change_rgb(), raster.size(), &a.picture)?;
    say!(
        "picture:     {} (change map seen from above: gone red, new green)",
        path.display()
    );
    Ok(())
}

/// Calls `f(min, side)` for each black block of a region tree.
fn for_each_voxel(tree: &RegionTree<3>, mut f: impl FnMut([u32; 3], u32)) {
    for b in tree.blocks().filter(|b| b.black) {
        f(b.min, b.side);
    }
}
