//! Saved trees against builds: builds an octree of n uniform random points (f64, `u32` items),
//! saves it in the binary saved-tree format, loads it back from the bytes (and from a file when
//! one is given), checks that the copy equals the tree, and prints the build and load times
//! (median of the runs, build and load alternated) and both trees' heap bytes.
//!
//! ```text
//! cargo run --release --features saved --example saved_tree -- --n 10000000 [--file t.bin]
//! ```

use orthtree::io::saved::{read_point_tree, read_point_tree_file, write_point_tree, PointTreeView};
use orthtree::prelude::*;
use orthtree::PointTree;
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};
use std::path::PathBuf;
use std::time::Instant;

#[macro_use]
#[path = "common/cli.rs"]
mod cli;
use cli::{Cli, CliError};

const USAGE: &str = "\
usage: saved_tree [--n N] [--runs R] [--file FILE]

Builds an octree of N uniform random points (f64 coordinates, u32 items), saves it in the
saved-tree format and loads it back without a rebuild; checks that the copy equals the tree and
prints the build and load times (medians of R alternated runs) and both trees' heap bytes.

options:
  --n N          points, 1 to 4294967295 (default 1000000)
  --runs R       builds and loads to take the median of, 1 to 99 (default 3)
  --file FILE    also write the tree to FILE (in a folder that exists) and load it from there
  -h, --help     this text
";

struct Args {
    n: u32,
    runs: usize,
    file: Option<PathBuf>,
}

fn parse(cli: &mut Cli) -> Result<Args, CliError> {
    let mut args = Args {
        n: 1_000_000,
        runs: 3,
        file: None,
    };
    while let Some(arg) = cli.next_arg()? {
        match arg.as_str() {
            "--n" => args.n = cli.number("--n", 1, u32::MAX)?,
            "--runs" => args.runs = cli.number("--runs", 1, 99)?,
            "--file" => args.file = Some(cli.output_path("--file")?),
            other => return Err(CliError::unknown(other)),
        }
    }
    // The input entries, the tree, its bytes and the loaded copy: 28 bytes a point each, and the
    // build's sort keys.
    let what = format!("--n {}", args.n);
    cli::check_memory(&what, args.n as f64 * (4.0 * 28.0 + 16.0))?;
    Ok(args)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// One pass reading every byte of the points section, as the check reads it: the floor for
/// touching the pages (a sum of the words, so that nothing is optimised away).
fn touch(points: &[[f64; 3]]) -> u64 {
    points.iter().fold(0u64, |acc, p| {
        acc.wrapping_add(p[0].to_bits() ^ p[1].to_bits() ^ p[2].to_bits())
    })
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = cli::parse_or_exit(USAGE, parse);
    let n = args.n as usize;
    let mut rng = SmallRng::seed_from_u64(7);
    let entries: Vec<([f64; 3], u32)> = (0..n).map(|i| (rng.r#gen(), i as u32)).collect();
    let (mut builds, mut par_builds, mut loads, mut saves) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let (mut opens, mut par_opens, mut touches) = (Vec::new(), Vec::new(), Vec::new());
    let mut kept = None;
    let mut sink = 0u64;
    for _ in 0..args.runs {
        // Drop the previous runs' trees first, so that each run has the same memory to work in.
        drop(kept.take());
        let start = Instant::now();
        let tree = PointTree::new(&entries)?;
        builds.push(start.elapsed().as_secs_f64());
        #[cfg(feature = "rayon")]
        {
            drop(tree);
            let start = Instant::now();
            let _par = PointTree::builder().par_build(&entries)?;
            par_builds.push(start.elapsed().as_secs_f64());
        }
        #[cfg(feature = "rayon")]
        let tree = PointTree::new(&entries)?;
        let start = Instant::now();
        let mut bytes = Vec::with_capacity(orthtree::io::saved::saved_len(&tree) as usize);
        write_point_tree(&tree, &mut bytes)?;
        saves.push(start.elapsed().as_secs_f64());
        let start = Instant::now();
        let back: PointTree<f64, u32, 3> = read_point_tree(&bytes)?;
        loads.push(start.elapsed().as_secs_f64());
        let start = Instant::now();
        let view = PointTreeView::<f64, u32, 3>::open_serial(&bytes)?;
        opens.push(start.elapsed().as_secs_f64());
        sink ^= view.len() as u64;
        drop(view);
        #[cfg(feature = "rayon")]
        {
            let start = Instant::now();
            let view = PointTreeView::<f64, u32, 3>::open(&bytes)?;
            par_opens.push(start.elapsed().as_secs_f64());
            sink ^= view.len() as u64;
        }
        let start = Instant::now();
        sink ^= touch(back.points());
        touches.push(start.elapsed().as_secs_f64());
        kept = Some((tree, bytes, back));
    }
    let (tree, bytes, back) = kept.expect("at least one run");
    let view = PointTreeView::<f64, u32, 3>::open(&bytes)?;
    let same = back.points() == tree.points()
        && back.items() == tree.items()
        && back.tree() == tree.tree()
        && view.points() == tree.points()
        && (0..1000).all(|_| {
            let q: [f64; 3] = rng.r#gen();
            let want = tree.k_nearest(&q, 10).ok();
            back.k_nearest(&q, 10).ok() == want && view.k_nearest(&q, 10).ok() == want
        });
    // The load's check alone: the tree's own validate, which the load runs once.
    let start = Instant::now();
    back.validate()?;
    let check = start.elapsed().as_secs_f64();
    let (build, load) = (median(builds), median(loads));
    say!(
        "{n} points in 3D (f64, u32 items), {} runs (medians):",
        args.runs
    );
    say!("  build           {:9.1} ms", build * 1e3);
    if !par_builds.is_empty() {
        say!(
            "  par_build       {:9.1} ms",
            median(par_builds.clone()) * 1e3
        );
    }
    say!(
        "  save to memory  {:9.1} ms, {:.1} MB ({:.2} bytes a point)",
        median(saves) * 1e3,
        bytes.len() as f64 / 1e6,
        bytes.len() as f64 / n as f64
    );
    say!(
        "  load from bytes {:9.1} ms: {:.1}x faster than the build (owned PointTree)",
        load * 1e3,
        build / load
    );
    say!(
        "  of which check  {:9.1} ms (validate, run again alone)",
        check * 1e3
    );
    let open = median(opens);
    say!(
        "  view, serial    {:9.2} ms: {:.1}x faster than the build (PointTreeView::open_serial)",
        open * 1e3,
        build / open
    );
    if !par_opens.is_empty() {
        let par = median(par_opens);
        say!(
            "  view, rayon     {:9.2} ms: {:.1}x faster than the build, {:.1}x than par_build \
             (PointTreeView::open)",
            par * 1e3,
            build / par,
            median(par_builds) / par
        );
    }
    let touch_time = median(touches);
    say!(
        "  read the points {:9.2} ms ({:.1} GB/s: one pass over the points section, no check)",
        touch_time * 1e3,
        (n * 24) as f64 / touch_time / 1e9
    );
    say!(
        "  view borrows    {} (heap bytes owned by the view: {})",
        view.is_borrowed(),
        view.heap_bytes()
    );
    drop(view);
    if let Some(path) = &args.file {
        drop(back);
        std::fs::write(path, &bytes)?;
        drop(bytes);
        let start = Instant::now();
        let from_file: PointTree<f64, u32, 3> = read_point_tree_file(path)?;
        let t = start.elapsed().as_secs_f64();
        say!(
            "  load from file  {:9.1} ms: {:.1}x faster than the build ({})",
            t * 1e3,
            build / t,
            path.display()
        );
        if from_file.points() != tree.points() || from_file.tree() != tree.tree() {
            return Err("the tree loaded from the file differs".into());
        }
        say!(
            "  heap bytes      built {}, loaded {}",
            tree.heap_bytes(),
            from_file.heap_bytes()
        );
        drop(from_file);
        #[cfg(feature = "mmap")]
        {
            use orthtree::io::saved::mapped::MappedTree;
            let mut maps = Vec::new();
            for _ in 0..args.runs {
                let start = Instant::now();
                let mapped = MappedTree::<f64, u32, 3>::open(path)?;
                let view = mapped.view()?;
                maps.push(start.elapsed().as_secs_f64());
                if view.points() != tree.points() {
                    return Err("the mapped view differs".into());
                }
            }
            let t = median(maps);
            say!(
                "  map and view    {:9.2} ms: {:.1}x faster than the build (file in the page cache)",
                t * 1e3,
                build / t
            );
        }
    } else {
        say!(
            "  heap bytes      built {}, loaded {}, view {} (plus the {} bytes it borrows)",
            tree.heap_bytes(),
            back.heap_bytes(),
            0,
            bytes.len()
        );
    }
    if !same {
        return Err("the loaded tree differs from the built one".into());
    }
    say!(
        "  the loaded tree and the view equal the built one (arrays, topology, 1000 10-nearest \
         queries) [{}]",
        sink % 10
    );
    Ok(())
}
