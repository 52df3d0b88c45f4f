//! Heat on the board: the steady heat equation `-div(k grad T) = q` solved with linear (P1)
//! finite elements on the quadtree mesh of a circuit board.
//!
//! `orthtree heat [BOARD.poly|BOARD.txt] [--size U] [--random SEED,U,COUNT]
//! [--max-triangles N] [--no-files]`, built with the `heat` feature (faer's sparse Cholesky);
//! without it the command says how to rebuild and exits with code 1.
//!
//! `--max-triangles` caps the mesh (default 2e6, so that the sparse Cholesky factor fits in a
//! few GiB); a board needing more is refused with the number it needs.
//!
//! Meshes the built-in board (or the given one, or `random_board(SEED, U, COUNT)`), gives every
//! region a conductivity `k` and a heat source `q` (chips: k = 20 W/(m K), q = 2e5 W/m^3; copper
//! pads, traces and fingers: k = 400, q = 2e4; the bare board: k = 0.3, q = 0; one board unit is
//! 0.1 mm; a 2D model per unit thickness), fixes `T = 0` on the board's boundary, assembles the
//! stiffness matrix, solves it with faer's sparse Cholesky factorization and writes
//! `heat.svg` (heat map with the component outlines) and `heat.vtk` (legacy VTK, the
//! temperature as point data, the region as cell data) into the current directory.
//!
//! The mesher's 45-90 degree window is what makes this work well: every angle is at most 90
//! degrees, so each off-diagonal stiffness entry `-(cot a + cot b) k / 2` is <= 0, the matrix is
//! an M-matrix and the discrete solution obeys the maximum principle (no spurious negative
//! temperatures), and no angle is below 45 degrees, so the matrix stays well conditioned.

#[cfg(feature = "heat")]
pub mod fem;
#[cfg(feature = "heat")]
mod picture;

use crate::limits;
use crate::random_board::RandomBoard;
use crate::Failure;
#[cfg(feature = "heat")]
use orthtree::mesh::Board;

/// Steady heat on the board's mesh: P1 finite elements, sparse Cholesky
///
/// Solves the steady heat equation on the quadtree mesh of a circuit board (the built-in board,
/// a board file or a seeded random board) and writes heat.svg and heat.vtk into the current
/// folder.
///
/// Needs the `heat` feature: cargo run --release -p orthtree-cli --features heat -- heat
#[derive(clap::Args, Debug)]
#[command(after_help = crate::EXIT_CODES, allow_negative_numbers = true)]
pub struct HeatArgs {
    /// A board file: Triangle's .poly or the plain text format (.txt)
    #[arg(value_name = "BOARD")]
    board: Option<String>,
    /// The board's side U for a file that does not give it (1 to 2^30)
    #[arg(long, value_name = "U", value_parser = limits::number(1i64, 1 << 30))]
    size: Option<i64>,
    /// random_board(SEED, U, COUNT) instead of a file: U a power of two from 8 to 2^30, COUNT at
    /// most (U / 2)^2; counts whose mesh and solve would not fit in memory are refused
    #[arg(long, value_name = "SEED,U,COUNT", value_parser = parse_random,
          conflicts_with_all = ["board", "size"])]
    random: Option<RandomBoard>,
    /// Refuse a mesh of more than N triangles
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_TRIANGLES,
          value_parser = limits::number(1u64, u64::MAX))]
    max_triangles: u64,
    /// Write no files
    #[arg(long)]
    no_files: bool,
}

/// The default mesh limit: about 10^6 unknowns, whose Cholesky factor fits in a few GiB.
const DEFAULT_MAX_TRIANGLES: u64 = 2_000_000;

/// Triangles of a board's mesh per step of its perimeter `p(S)` (Theorem 14.5 bounds them by
/// `O(p(S) log U)`): measured 12.6 to 18.2 on the sample board and on random boards from U = 64
/// to 2^22 (`generate_mesh`); with a margin.
const TRIANGLES_PER_PERIMETER_STEP: f64 = 20.0;
/// Peak bytes per triangle of the mesher (the mesh and its work): measured 43 B on a random
/// board of 1.2 * 10^7 triangles; with a margin.
const MESH_BYTES_PER_TRIANGLE: f64 = 80.0;
/// Peak bytes per triangle of `fem::assemble_board` and `fem::solve` together: the element
/// entries (six of 16 bytes per triangle, sorted), the compressed matrix, and the Cholesky factor
/// with its fill (measured: about 255 B per triangle on random boards of 3 * 10^6 and 6 * 10^6
/// triangles, the peak resident memory of `orthtree heat --no-files` with `/usr/bin/time -v`
/// less the mesher's); with a margin, as the fill grows like `n log n`.
const SOLVE_BYTES_PER_TRIANGLE: f64 = 400.0;
/// Peak bytes per component of drawing and checking a random board (outlines, edge lines,
/// placement boxes, `Board::new`'s work): measured 1.5 KB at 4 * 10^5 components; with a margin.
const BOARD_BYTES_PER_COMPONENT: f64 = 2500.0;
/// Every component has a perimeter of at least 4 steps (a unit square).
const MIN_PERIMETER_STEPS: f64 = 4.0;

/// The estimated peak bytes of meshing and solving on a board of perimeter `steps`.
fn solve_bytes_for_perimeter(steps: f64) -> f64 {
    steps * TRIANGLES_PER_PERIMETER_STEP * (MESH_BYTES_PER_TRIANGLE + SOLVE_BYTES_PER_TRIANGLE)
}

/// Refuses a board whose mesh and solve are estimated not to fit in memory, from its perimeter,
/// before meshing it.
#[cfg(feature = "heat")]
fn check_board_work(board: &Board, name: &str) -> Result<(), Failure> {
    let steps = board.perimeter_steps() as f64;
    limits::check_memory(
        &format!(
            "{name}: perimeter {steps} steps, about {:.2e} triangles",
            steps * TRIANGLES_PER_PERIMETER_STEP
        ),
        solve_bytes_for_perimeter(steps),
    )
    .map_err(Failure::Usage)
}

/// `SEED,U,COUNT` of `--random` ([`RandomBoard::parse`]), refused when even the least board of
/// COUNT components is estimated not to fit in memory.
fn parse_random(raw: &str) -> Result<RandomBoard, String> {
    let RandomBoard { seed, size, count } = RandomBoard::parse(raw)?;
    // A lower bound before the board is drawn (each component at least a unit square); the
    // board's real perimeter is checked once it is drawn.
    let least = count as f64;
    limits::check_memory(
        &format!("{count} components of at least 4 perimeter steps each"),
        least * (BOARD_BYTES_PER_COMPONENT + solve_bytes_for_perimeter(MIN_PERIMETER_STEPS)),
    )?;
    Ok(RandomBoard { seed, size, count })
}

#[cfg(feature = "heat")]
fn read_board(args: &HeatArgs) -> Result<(Board, String), Failure> {
    if let Some(random) = args.random {
        return random.draw();
    }
    let Some(path) = &args.board else {
        return Ok((
            orthtree::mesh::sample_board(),
            "built-in sample board".into(),
        ));
    };
    crate::mesh::board_file(path, args.size)
}

/// `--size` without a board file: the built-in board has its own size.
fn check_size(args: &HeatArgs) -> Result<(), Failure> {
    match (args.size, &args.board, args.random) {
        (Some(size), None, None) => Err(Failure::Usage(format!(
            "--size {size} needs a board file (the built-in board has its own size)"
        ))),
        _ => Ok(()),
    }
}

/// Runs `orthtree heat` without the solver: the message names the rebuild command.
#[cfg(not(feature = "heat"))]
pub fn run(args: &HeatArgs) -> Result<(), Failure> {
    check_size(args)?;
    Err(Failure::Input(
        "orthtree heat needs the `heat` feature (faer's sparse Cholesky); rebuild with \
         `cargo run --release -p orthtree-cli --features heat -- heat`"
            .into(),
    ))
}

#[cfg(feature = "heat")]
fn ms(d: std::time::Duration) -> String {
    format!("{:.1} ms", d.as_secs_f64() * 1e3)
}

/// Runs `orthtree heat`.
#[cfg(feature = "heat")]
pub fn run(args: &HeatArgs) -> Result<(), Failure> {
    use crate::progress::Phase;
    use orthtree::mesh::MeshOptions;
    use std::io::BufWriter;
    use std::time::Instant;

    check_size(args)?;
    let (board, name) = read_board(args)?;
    check_board_work(&board, &name)?;
    let start = Instant::now();
    let options = MeshOptions::new()
        .grid_unit(1)
        .max_triangles(args.max_triangles);
    let phase = Phase::start("meshing the board");
    let out = options
        .generate(&board)
        .map_err(|e| Failure::Input(format!("{name}: {e}")))?;
    drop(phase);
    let mesh_time = start.elapsed();
    let mesh = out.mesh;
    let solve_work = format!("{name}: {} triangles to solve on", mesh.triangles.len());
    let solve_bytes = mesh.triangles.len() as f64 * SOLVE_BYTES_PER_TRIANGLE;
    limits::check_memory(&solve_work, solve_bytes).map_err(Failure::Usage)?;

    let phase = Phase::start("assembling and solving");
    let (k, q) = fem::board_materials(&board);
    let start = Instant::now();
    let sys = fem::assemble_board(&mesh, &k, &q);
    let assembly_time = start.elapsed();
    let (t, times) = fem::solve(&sys)
        .map_err(|e| Failure::Input(format!("{name}: Cholesky factorization failed: {e}")))?;
    drop(phase);
    let t_min = t.iter().copied().fold(f64::INFINITY, f64::min);
    let t_max = t.iter().copied().fold(f64::NEG_INFINITY, f64::max);

    say!(
        "board:      {name}: U = {}, {} components",
        board.size(),
        board.components().len()
    );
    say!(
        "mesh:       {} triangles, {} vertices ({})",
        mesh.triangles.len(),
        mesh.vertices.len(),
        ms(mesh_time)
    );
    say!(
        "system:     {} unknowns, {} stored entries (lower triangle), max off-diagonal {:e}",
        sys.n,
        sys.values.len(),
        sys.max_off_diagonal()
    );
    say!("assembly:   {}", ms(assembly_time));
    say!(
        "solve:      {} (ordering + symbolic {}, Cholesky {}, substitution {})",
        ms(times.total()),
        ms(times.symbolic),
        ms(times.numeric),
        ms(times.substitution)
    );
    say!("temperature: min {t_min:.6e} K, max {t_max:.6} K (rise over the board edge)");
    if !args.no_files {
        let _phase = Phase::start("writing the files");
        let start = Instant::now();
        let svg = |path: &str| {
            let mut out = BufWriter::new(std::fs::File::create(path)?);
            picture::write_heat_svg(&mesh, &board, &t, t_max, &mut out)
        };
        svg("heat.svg")
            .and_then(|_| picture::write_heat_vtk(&mesh, &t, "heat.vtk"))
            .map_err(|e| Failure::Input(format!("writing heat.svg / heat.vtk: {e}")))?;
        say!("wrote:      heat.svg heat.vtk ({})", ms(start.elapsed()));
    }
    Ok(())
}
