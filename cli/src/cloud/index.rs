//! `orthtree cloud index`: the saved tree of a cloud, built in memory or out of core within a
//! memory budget (the library's `io::saved::external`), then checked and queried: loaded whole
//! after an in-memory build, through a memory map (`io::saved::mapped`) after an out-of-core
//! one.

use super::commands::{bounds, load};
#[cfg(feature = "las")]
use super::input;
use super::{scan, IndexArgs};
use crate::limits::human_bytes;
#[cfg(feature = "las")]
use crate::limits::shown;
use crate::progress::Phase;
use crate::Failure;
use orthtree::geom::Aabb;
use orthtree::io::saved::external::ExternalBuild;
#[cfg(feature = "las")]
use orthtree::io::saved::external::ExternalReport;
use orthtree::io::saved::{self, mapped::MappedTree};
use orthtree::{PointSet, PointTree};
use std::path::Path;
use std::time::Instant;

/// The column through `b`'s centre of `fraction` of its x and y extents and all of its z: the
/// check's queries (a scan is a surface: a box in mid-air would be empty).
fn column(b: &Aabb<f64, 3>, fraction: f64) -> Aabb<f64, 3> {
    let c: [f64; 3] = core::array::from_fn(|k| 0.5 * (b.min[k] + b.max[k]));
    let h: [f64; 3] = core::array::from_fn(|k| 0.5 * fraction * (b.max[k] - b.min[k]));
    Aabb {
        min: [c[0] - h[0], c[1] - h[1], b.min[2]],
        max: [c[0] + h[0], c[1] + h[1], b.max[2]],
    }
}

fn ms(seconds: f64) -> String {
    format!("{:.3} ms", seconds * 1e3)
}

/// Runs `orthtree cloud index`.
pub fn run(a: &IndexArgs) -> Result<(), Failure> {
    let fail = |e: &dyn std::fmt::Display| Failure::Input(format!("{}: {e}", a.out.display()));
    let Some(budget) = a.budget else {
        return in_memory(a);
    };
    if a.source.no_files {
        return Err(Failure::Usage(
            "--budget writes the tree: it cannot go with --no-files".into(),
        ));
    }
    let build = ExternalBuild::new(budget).bucket_size(a.bucket_size);
    let start = Instant::now();
    let phase = Phase::start("sorting runs and merging them into the tree");
    let (report, name) = match a.input.as_deref() {
        #[cfg(feature = "las")]
        Some(path) if input::format_of(path)? == input::Format::Las => (
            las_streamed(&build, path, &a.out),
            format!("{} (streamed)", shown(path)),
        ),
        None => {
            let (seed, n) = (a.source.seed, a.source.points);
            let name = format!("built-in scan (seed {seed}, epoch 0, {n} points, streamed)");
            let returns = || {
                scan::Returns::new(seed, n, 0)
                    .zip(0u32..)
                    .map(|((p, _, _), i)| (p, i))
            };
            let report = build.write(returns, &a.out);
            (
                report.map_err(|e| Failure::Input(format!("{name}: {e}"))),
                name,
            )
        }
        Some(path) => {
            let (cloud, name) = load(Some(path), &a.source, 0)?;
            let entries = || cloud.points.iter().copied().zip(0u32..);
            let report = build.write(entries, &a.out);
            (
                report.map_err(|e| Failure::Input(format!("{name}: {e}"))),
                name,
            )
        }
    };
    let report = report?;
    drop(phase);
    let took = start.elapsed().as_secs_f64();
    say!("input:       {name}");
    say!(
        "tree:        {} points, {} node slots, {} in {:.1} s ({:.2} million points/s), out of \
         core: budget {}, {} sorted runs, {} merge pass(es), {} spilled (at most {} at once)",
        report.points,
        report.slots,
        human_bytes(report.file_bytes as f64),
        took,
        report.points as f64 / took / 1e6,
        human_bytes(budget as f64),
        report.runs,
        report.passes,
        human_bytes(report.spilled_bytes as f64),
        human_bytes(report.peak_temp_bytes as f64)
    );
    let start = Instant::now();
    let mapped = MappedTree::<f64, u32, 3>::open(&a.out).map_err(|e| fail(&e))?;
    let open = start.elapsed().as_secs_f64();
    query_through_map(&mapped, &a.out, &mapped.domain(), "the tree's domain")?;
    say!("check:       mapped in {}", ms(open));
    say!("wrote:       {}", a.out.display());
    Ok(())
}

/// The out-of-core build of an uncompressed LAS file, its points streamed block by block in
/// each of the build's two passes ([`LasEntries`]): the whole cloud is never in memory, so the
/// file may be larger than it.
#[cfg(feature = "las")]
fn las_streamed(build: &ExternalBuild, path: &str, out: &Path) -> Result<ExternalReport, Failure> {
    use orthtree::iter::LasEntries;
    let named = |e: &dyn std::fmt::Display| Failure::Input(format!("{}: {e}", shown(path)));
    // The header's checks, before any pass.
    LasEntries::open(path).map_err(|e| named(&e))?;
    // A read that fails in either pass ends that pass's stream and is reported here, before
    // whatever the build made of the shortened pass.
    let failed = &core::cell::RefCell::new(None);
    let source = || {
        let mut stream = LasEntries::open(path)
            .map_err(|e| *failed.borrow_mut() = Some(e))
            .ok();
        core::iter::from_fn(move || match stream.as_mut()?.next()? {
            Ok(entry) => Some(entry),
            Err(e) => {
                *failed.borrow_mut() = Some(e);
                stream = None;
                None
            }
        })
    };
    let report = build.write(source, out);
    if let Some(e) = failed.take() {
        return Err(named(&e));
    }
    report.map_err(|e| named(&e))
}

/// Box queries through the map, each timed: columns through the centre of `basis` (the
/// points' bounds when they are at hand, else the tree's domain, as `basis_name` says) of a
/// tenth and a hundredth of its x and y extents. Returns the count in the first column.
fn query_through_map(
    mapped: &MappedTree<f64, u32, 3>,
    out: &Path,
    basis: &Aabb<f64, 3>,
    basis_name: &str,
) -> Result<usize, Failure> {
    let fail = |e: &dyn std::fmt::Display| Failure::Input(format!("{}: {e}", out.display()));
    let mut first = None;
    for fraction in [0.1, 0.01] {
        let start = Instant::now();
        let found = mapped
            .query_box(&column(basis, fraction), |_, _| {})
            .map_err(|e| fail(&e))?;
        say!(
            "query:       column through the centre of {basis_name}, {fraction} of its x and y \
             extents: {found} points in {} (through the map)",
            ms(start.elapsed().as_secs_f64())
        );
        first.get_or_insert(found);
    }
    Ok(first.unwrap_or(0))
}

/// A point and its position in the input.
type Entry = ([f64; 3], u32);

/// The points to index, each with its position in the input: an uncompressed LAS file's
/// coordinates alone ([`orthtree::io::las::read_entries`], without the other fields), any
/// other input read whole.
fn entries_of(a: &IndexArgs) -> Result<(Vec<Entry>, String), Failure> {
    #[cfg(feature = "las")]
    if let Some(path) = a.input.as_deref()
        && input::format_of(path)? == input::Format::Las
    {
        let start = Instant::now();
        let phase = Phase::start(&format!("reading {}", shown(path)));
        let entries = orthtree::io::las::read_entries(path)
            .map_err(|e| Failure::Input(format!("{}: {e}", shown(path))))?;
        drop(phase);
        say!(
            "input:       {}: {} points (coordinates only), read in {}",
            shown(path),
            entries.len(),
            ms(start.elapsed().as_secs_f64())
        );
        return Ok((entries, shown(path)));
    }
    let (cloud, name) = load(a.input.as_deref(), &a.source, 0)?;
    let entries = cloud
        .entries()
        .map_err(|e| Failure::Input(format!("{name}: {e}")))?;
    Ok((entries, name))
}

/// The in-memory build, written, loaded back whole (every check) and queried.
fn in_memory(a: &IndexArgs) -> Result<(), Failure> {
    let fail = |e: &dyn std::fmt::Display| Failure::Input(format!("{}: {e}", a.out.display()));
    let (entries, name) = entries_of(a)?;
    let start = Instant::now();
    let phase = Phase::start("building the tree");
    let builder = PointTree::builder().bucket_size(a.bucket_size);
    #[cfg(feature = "rayon")]
    let tree = builder.par_build(&entries);
    #[cfg(not(feature = "rayon"))]
    let tree = builder.build(&entries);
    let tree = tree.map_err(|e| Failure::Input(format!("{name}: {e}")))?;
    drop(phase);
    let build = start.elapsed().as_secs_f64();
    if a.source.no_files {
        say!(
            "tree:        {} points, {} leaves in {} (not written: --no-files)",
            tree.len(),
            tree.tree().leaf_count(),
            ms(build)
        );
        return Ok(());
    }
    let start = Instant::now();
    let file = std::fs::File::create(&a.out).map_err(|e| fail(&e))?;
    let mut out = std::io::BufWriter::new(file);
    saved::write_point_tree(&tree, &mut out).map_err(|e| fail(&e))?;
    std::io::Write::flush(&mut out).map_err(|e| fail(&e))?;
    let write = start.elapsed().as_secs_f64();
    let bytes = std::fs::metadata(&a.out).map_err(|e| fail(&e))?.len();
    say!(
        "tree:        {} points, {} leaves, bucket size {}, {}; build {}, write {}",
        tree.len(),
        tree.tree().leaf_count(),
        a.bucket_size,
        human_bytes(bytes as f64),
        ms(build),
        ms(write)
    );
    drop(tree);
    let start = Instant::now();
    let phase = Phase::start("loading and checking the saved tree");
    let back: PointTree<f64, u32, 3> = saved::read_point_tree_file(&a.out).map_err(|e| fail(&e))?;
    drop(phase);
    let load_time = start.elapsed().as_secs_f64();
    let basis = bounds(entries.iter().map(|(p, _)| p));
    let start = Instant::now();
    let found = back
        .query_count(column(&basis, 0.1))
        .map_err(|e| Failure::Input(e.to_string()))?;
    say!(
        "check:       loaded and validated in {}; column through the centre of the points' \
         bounds, 0.1 of its x and y extents: {found} points in {} (owned tree)",
        ms(load_time),
        ms(start.elapsed().as_secs_f64())
    );
    let mapped = MappedTree::<f64, u32, 3>::open(&a.out).map_err(|e| fail(&e))?;
    let through_map = query_through_map(&mapped, &a.out, &basis, "the points' bounds")?;
    if through_map != found {
        return Err(Failure::Input(format!(
            "{}: the column query found {through_map} points through the map but {found} in \
             the loaded tree",
            a.out.display()
        )));
    }
    say!("wrote:       {}", a.out.display());
    Ok(())
}
