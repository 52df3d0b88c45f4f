//! Point location in a planar subdivision with a compressed quadtree (exercise 14.10 of de Berg
//! et al., chapter 14): a jittered triangulated grid with a small detailed wheel inside one
//! triangle, its quadtree's cells, and a lattice of sample points coloured by the face the
//! locator finds for each. Prints sizes and times for both leaf rules, and writes
//! `point_location.svg` (or the path given).
//!
//! ```text
//! cargo run --release --example point_location [-- [--out] out.svg]
//! ```

use orthtree::compressed::{PointLocator, Subdivision};
use orthtree::io::svg::{Style, Svg};
use orthtree::Aabb;
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};
use std::time::Instant;

#[path = "../benches/workloads/compressed.rs"]
mod workload;

#[macro_use]
#[path = "common/cli.rs"]
mod cli;
use cli::{Cli, CliError};
use std::path::PathBuf;

const USAGE: &str = "\
usage: point_location [[--out] FILE.svg]

Point location in a planar subdivision with a compressed quadtree: sizes and times of both leaf
rules, and a picture of the subdivision, its quadtree and located sample points.

options:
  --out FILE     the picture to write, in a folder that exists (default point_location.svg);
                 the path may also be given alone
  -h, --help     this text
";

/// The picture's path: `--out FILE` or one positional path.
fn parse(cli: &mut Cli) -> Result<PathBuf, CliError> {
    let mut out = None;
    while let Some(arg) = cli.next_arg()? {
        let path = match arg.as_str() {
            "--out" => cli.output_path("--out")?,
            other if other.starts_with('-') => return Err(CliError::unknown(other)),
            other => cli::output_path("the picture path", other)?,
        };
        if out.replace(path).is_some() {
            return Err(CliError::new(format!(
                "{}: only one picture path may be given",
                cli::shown(&arg)
            )));
        }
    }
    Ok(out.unwrap_or_else(|| PathBuf::from("point_location.svg")))
}

/// A jittered triangulated `k` by `k` grid ([`workload::triangulated_grid`]) plus a wheel of
/// `spokes` spokes and radius `r` around `centre`, joined to the nearest grid vertex by one
/// edge.
fn subdivision(k: usize, spokes: usize, centre: [f64; 2], r: f64) -> Subdivision {
    let (mut v, mut e, _) = workload::triangulated_grid(k, 3);
    let hub = v.len() as u32;
    v.push(centre);
    for s in 0..spokes {
        let a = s as f64 * std::f64::consts::TAU / spokes as f64;
        v.push([centre[0] + r * a.cos(), centre[1] + r * a.sin()]);
        let rim = hub + 1 + s as u32;
        e.push([hub, rim]);
        e.push([rim, hub + 1 + ((s + 1) % spokes) as u32]);
    }
    let nearest = (0..hub)
        .min_by(|&a, &b| {
            let d = |i: u32| (v[i as usize][0] - centre[0]).hypot(v[i as usize][1] - centre[1]);
            d(a).total_cmp(&d(b))
        })
        .expect("a grid vertex");
    e.push([hub + 1 + (spokes / 2) as u32, nearest]);
    Subdivision::new(v, e).expect("a valid subdivision")
}

/// A colour per face, spread over the hue circle.
fn colour(face: u32) -> String {
    let h = (face as f64 * 0.618_034).fract() * 360.0;
    format!("hsl({h:.0},70%,60%)")
}

fn main() {
    let out = cli::parse_or_exit(USAGE, parse);
    let k = 8;
    let s = subdivision(k, 12, [2.35, 3.3], 0.12);
    say!(
        "{} vertices, {} edges, {} faces",
        s.vertices().len(),
        s.edges().len(),
        s.face_count()
    );
    let mut rng = SmallRng::seed_from_u64(9);
    let queries: Vec<[f64; 2]> = (0..100_000)
        .map(|_| [rng.gen_range(-0.5..k as f64), rng.gen_range(-0.5..k as f64)])
        .collect();
    say!("rule      nodes  height  build (ms)  locate (ns/query)");
    let mut shown = None;
    for (name, exercise) in [("relaxed", false), ("exercise", true)] {
        let t = Instant::now();
        let locator = if exercise {
            PointLocator::with_exercise_rule(s.clone())
        } else {
            PointLocator::new(s.clone())
        }
        .expect("no crossing edges");
        let build = t.elapsed().as_secs_f64() * 1e3;
        let t = Instant::now();
        let sum: u64 = queries
            .iter()
            .map(|q| locator.face(q).unwrap().0 as u64)
            .sum();
        let per = t.elapsed().as_secs_f64() * 1e9 / queries.len() as f64;
        say!(
            "{name:9} {:6} {:7} {build:11.2} {per:18.0}   (checksum {sum})",
            locator.node_count(),
            locator.height()
        );
        shown.get_or_insert(locator);
    }
    let locator = shown.expect("built");
    let g = locator.geometry();
    let view = Aabb::new([-0.5, -0.5], [k as f64 - 0.5, k as f64 - 0.5]).expect("a box");
    let mut svg = Svg::new(view, 900.0);
    svg.background("white");
    // the lattice of samples, one group per face
    let n = 110;
    let mut by_face: Vec<Vec<[f64; 2]>> = vec![Vec::new(); s.face_count()];
    for i in 0..n {
        for j in 0..n {
            let p = [
                -0.5 + (j as f64 + 0.5) * k as f64 / n as f64,
                -0.5 + (i as f64 + 0.5) * k as f64 / n as f64,
            ];
            by_face[locator.face(&p).unwrap().0 as usize].push(p);
        }
    }
    for (f, pts) in by_face.iter().enumerate() {
        let style = Style::points().fill(colour(f as u32)).point_radius(2.0);
        svg.points(pts, &style);
    }
    let cells = locator.cells().map(|(c, _)| g.cell_box(&c));
    svg.boxes(cells, &Style::solid().stroke("#1f3a93").stroke_width(0.9));
    let edges = s
        .edges()
        .iter()
        .map(|e| e.map(|i| s.vertices()[i as usize]));
    svg.segments(edges, &Style::solid().stroke("black").stroke_width(1.4));
    svg.points(s.vertices(), &Style::points().point_radius(2.5));
    if let Err(e) = svg.write_to(&out) {
        eprintln!("error: cannot write {}: {e}", out.display());
        std::process::exit(1);
    }
    say!("wrote {}", out.display());
}
