//! Triangle counts of the mesher's modes beside a quality Delaunay mesher.
//!
//! `cargo run --release -p orthtree-compare --bin mesh_compare -- [--seeds N] [--runs R] [--target]`
//! (`--help` lists the options)
//!
//! `--target` meshes only the mesher's target workload, `random_board(7, 65536, 640)`, in both
//! modes, and prints the median time of each phase.
//!
//! For Figure 14.2's input, the sample board and seeded random boards, prints the triangle counts
//! and times (median of R runs) of the chapter's mode (`book`) and the `coarsest` mode, each
//! validated by `Mesh::validate` (angles in [45, 90]), and of spade's constrained Delaunay
//! triangulation refined to a 30-degree angle bound (Ruppert's algorithm), with its angle range.
//! spade gets the same input: the board's square and every component outline as constraint edges.

use orthtree::mesh::{random_board, sample_board, Board, Component, MeshOptions, Mode};
use orthtree_compare::say;
use spade::{
    AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation,
};
use std::time::{Duration, Instant};

use clap::Parser;
use orthtree_compare::limits;

/// Triangle counts and times of the mesher's book and coarsest modes beside spade's refined
/// constrained Delaunay triangulation, on Figure 14.2's input, the sample board and random
/// boards.
#[derive(Parser, Debug)]
#[command(name = "mesh_compare", allow_negative_numbers = true)]
struct Args {
    /// Random boards per size; one board is held at a time
    #[arg(long, value_name = "N", default_value_t = 5, value_parser = limits::number(0u64, 10_000))]
    seeds: u64,
    /// Timed runs per mesh, median reported
    #[arg(long, value_name = "R", default_value_t = 3, value_parser = limits::number(1usize, 1000))]
    runs: usize,
    /// Only the mesher's target workload, random_board(7, 65536, 640), phase by phase
    #[arg(long = "target")]
    only_target: bool,
}

/// The median of `runs` timings of `f`, and its last result.
fn timed<T>(runs: usize, mut f: impl FnMut() -> T) -> (Duration, T) {
    let mut times = Vec::with_capacity(runs);
    let mut last = None;
    for _ in 0..runs.max(1) {
        let start = Instant::now();
        last = Some(f());
        times.push(start.elapsed());
    }
    times.sort_unstable();
    (times[times.len() / 2], last.expect("at least one run"))
}

/// One of the mesher's modes: (triangles, median time).
fn ours(board: &Board, mode: Mode, runs: usize) -> (usize, Duration) {
    let options = MeshOptions::new().mode(mode);
    let (time, out) = timed(runs, || options.generate(board).expect("valid options"));
    let report = out.mesh.validate(board);
    assert!(report.is_ok(), "{mode:?}: {report}");
    (out.mesh.triangles.len(), time)
}

/// spade's refined constrained Delaunay triangulation: (triangles, [min, max] angle, time,
/// whether the refinement completed).
fn spade(board: &Board, runs: usize) -> (usize, [f64; 2], Duration, bool) {
    let (time, (cdt, complete)) = timed(runs, || {
        let mut cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::new();
        let u = board.size() as f64;
        let square = [[0.0, 0.0], [u, 0.0], [u, u], [0.0, u]];
        let outlines = (board.components().iter())
            .map(|c| {
                c.outline
                    .iter()
                    .map(|p| [p[0] as f64, p[1] as f64])
                    .collect()
            })
            .chain([square.to_vec()]);
        for outline in outlines {
            let outline: Vec<[f64; 2]> = outline;
            let handles: Vec<_> = (outline.iter())
                .map(|p| cdt.insert(Point2::new(p[0], p[1])).expect("finite"))
                .collect();
            for i in 0..handles.len() {
                cdt.add_constraint(handles[i], handles[(i + 1) % handles.len()]);
            }
        }
        let params = RefinementParameters::new()
            .with_angle_limit(AngleLimit::from_deg(30.0))
            .with_max_additional_vertices(2000 * cdt.num_vertices() + 10_000);
        let result = cdt.refine(params);
        (cdt, result.refinement_complete)
    });
    let mut range = [180.0f64, 0.0f64];
    for face in cdt.inner_faces() {
        let p = face.positions();
        for i in 0..3 {
            let (a, b, c) = (p[i], p[(i + 1) % 3], p[(i + 2) % 3]);
            let (u, v) = ([b.x - a.x, b.y - a.y], [c.x - a.x, c.y - a.y]);
            let angle = (u[0] * v[1] - u[1] * v[0])
                .abs()
                .atan2(u[0] * v[0] + u[1] * v[1])
                .to_degrees();
            range = [range[0].min(angle), range[1].max(angle)];
        }
    }
    (cdt.num_inner_faces(), range, time, complete)
}

fn ms(d: Duration) -> String {
    format!("{:.1} ms", d.as_secs_f64() * 1e3)
}

/// The target workload in both modes: triangles and median phase times.
fn target(runs: usize) {
    let board = random_board(7, 1 << 16, 640);
    for mode in [Mode::Book, Mode::Coarsest] {
        let options = MeshOptions::new().mode(mode);
        let mut phases: [Vec<Duration>; 4] = Default::default();
        let mut triangles = 0;
        for _ in 0..runs.max(1) {
            let start = Instant::now();
            let out = options.generate(&board).expect("valid options");
            let total = start.elapsed();
            triangles = out.mesh.triangles.len();
            for (k, t) in [
                out.build_time,
                out.balance_time,
                out.triangulate_time,
                total,
            ]
            .into_iter()
            .enumerate()
            {
                phases[k].push(t);
            }
        }
        let [build, balance, triangulate, total] = phases.map(|mut v| {
            v.sort_unstable();
            v[v.len() / 2]
        });
        say!(
            "{mode:?}: {triangles} triangles; median of {runs}: build {}, balance {}, \
             triangulate {}, total {}",
            ms(build),
            ms(balance),
            ms(triangulate),
            ms(total)
        );
    }
}

/// One table row: both modes and spade on `board`.
fn row(name: &str, board: &Board, runs: usize) {
    let (book, book_time) = ours(board, Mode::Book, runs);
    let (coarse, coarse_time) = ours(board, Mode::Coarsest, runs);
    let (sp, [lo, hi], sp_time, complete) = spade(board, runs);
    say!(
        "| {name} | {book} | {coarse} | {:.2} | {sp}{} | {lo:.1}-{hi:.1}° | {} | {} | {} |",
        book as f64 / coarse as f64,
        if complete { "" } else { " (incomplete)" },
        ms(book_time),
        ms(coarse_time),
        ms(sp_time)
    );
}

fn main() {
    let Args {
        seeds,
        runs,
        only_target,
    } = Args::parse();
    if only_target {
        return target(runs);
    }
    let u = 16;
    let figure = Board::new(
        u,
        vec![Component::new(vec![
            [1, u - 2],
            [2, u - 2],
            [2, u - 1],
            [1, u - 1],
        ])],
    )
    .expect("Figure 14.2's input is valid");
    say!(
        "| board | book | coarsest | book / coarsest | spade 30° | spade angles | book time | \
         coarsest time | spade time |"
    );
    say!("|---|---|---|---|---|---|---|---|---|");
    row("Figure 14.2 (U = 16)", &figure, runs);
    row("sample_board (U = 1024)", &sample_board(), runs);
    // One random board at a time, so memory does not grow with --seeds.
    for (size, count) in [(1 << 10, 160), (1 << 12, 640)] {
        for seed in 0..seeds {
            let name = format!("random_board({seed}, {size}, {count})");
            row(&name, &random_board(seed, size, count), runs);
        }
    }
    row(
        "random_board(7, 65536, 640)",
        &random_board(7, 1 << 16, 640),
        runs,
    );
    say!("book and coarsest: every angle 45 or 90 degrees (validated); times are medians.");
}
