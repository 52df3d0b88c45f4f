//! Heat on the board: the steady heat equation `-div(k grad T) = q` solved with linear (P1)
//! finite elements on the quadtree mesh of a circuit board.
//!
//! `cargo run --release --example pcb_heat -- [BOARD.poly|BOARD.txt] [--size U]
//! [--random SEED,U,COUNT] [--max-triangles N] [--no-files] [--help]`
//!
//! `--max-triangles` caps the mesh (default 2e6, so that the sparse Cholesky factor fits in a
//! few GiB); a board needing more is refused with the number it needs. `--random` takes at most
//! 100000 components. Bad arguments exit with status 2, a refused board or a failed write with
//! status 1.
//!
//! Meshes the built-in board (or the given one, or `random_board(SEED, U, COUNT)`), gives every
//! region a conductivity `k` and a heat source `q` (chips: k = 20 W/(m K), q = 2e5 W/m^3; copper
//! pads, traces and fingers: k = 400, q = 2e4; the bare board: k = 0.3, q = 0; one board unit is
//! 0.1 mm; a 2D model per unit thickness), fixes `T = 0` on the board's boundary, assembles the
//! stiffness matrix, solves it with faer's sparse Cholesky factorization and writes
//! `pcb_heat.svg` (heat map with the component outlines) and `pcb_heat.vtk` (legacy VTK, the
//! temperature as point data, the region as cell data) into the current directory.
//!
//! The mesher's 45-90 degree window is what makes this work well: every angle is at most 90
//! degrees, so each off-diagonal stiffness entry `-(cot a + cot b) k / 2` is <= 0, the matrix is
//! an M-matrix and the discrete solution obeys the maximum principle (no spurious negative
//! temperatures), and no angle is below 45 degrees, so the matrix stays well conditioned.

#[path = "pcb_heat/fem.rs"]
mod fem;

use orthtree::io::vtk;
use orthtree::mesh::{sample_board, try_random_board, Board, Mesh, MeshOptions};
use std::io::{BufWriter, Write};
use std::time::{Duration, Instant};

#[path = "common/cli.rs"]
mod cli;
use cli::{Cli, CliError};

const USAGE: &str = "\
usage: pcb_heat [BOARD.poly|BOARD.txt] [--size U] [--random SEED,U,COUNT]
                [--max-triangles N] [--no-files]

The steady heat equation on the quadtree mesh of a circuit board (the built-in board, a board
file, or a seeded random board), solved with finite elements; writes pcb_heat.svg and
pcb_heat.vtk into the current folder.

options:
  BOARD                    a board file (.poly, or the text format)
  --size U                 the board's side U for a file that does not give it (1 to 2^30)
  --random SEED,U,COUNT    random_board(SEED, U, COUNT) instead of a file: U a power of two from
                           8 to 2^30, COUNT at most (U / 2)^2; counts whose mesh and solve would
                           not fit in memory are refused
  --max-triangles N        refuse a mesh of more than N triangles (default 2000000)
  --no-files               write no files
  -h, --help               this text
";

struct Args {
    board: Option<String>,
    size: Option<i64>,
    random: Option<(u64, i64, usize)>,
    max_triangles: u64,
    files: bool,
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
/// Peak bytes per component of drawing and checking a random board (outlines, edge lines,
/// placement boxes, `Board::new`'s work): measured 1.5 KB at 4 * 10^5 components; with a margin.
const BOARD_BYTES_PER_COMPONENT: f64 = 2500.0;
/// Every component has a perimeter of at least 4 steps (a unit square).
const MIN_PERIMETER_STEPS: f64 = 4.0;

/// The estimated peak bytes of meshing and solving on a board of perimeter `steps`.
fn solve_bytes_for_perimeter(steps: f64) -> f64 {
    steps * TRIANGLES_PER_PERIMETER_STEP * (MESH_BYTES_PER_TRIANGLE + fem::SOLVE_BYTES_PER_TRIANGLE)
}

/// Refuses a board whose mesh and solve are estimated not to fit in memory, from its perimeter,
/// before meshing it.
fn check_board_work(board: &Board, name: &str) -> Result<(), CliError> {
    let steps = board.perimeter_steps() as f64;
    cli::check_memory(
        &format!(
            "{name}: perimeter {steps} steps, about {:.2e} triangles",
            steps * TRIANGLES_PER_PERIMETER_STEP
        ),
        solve_bytes_for_perimeter(steps),
        cli::memory_limit(),
    )
}

/// `SEED,U,COUNT` of `--random`, each checked; the count against the board's capacity.
fn parse_random(raw: &str) -> Result<(u64, i64, usize), CliError> {
    let parts: Vec<&str> = raw.split(',').collect();
    let [seed, size, count] = parts[..] else {
        return Err(CliError::new(format!(
            "--random {}: expected SEED,U,COUNT (three numbers separated by commas)",
            cli::shown(raw)
        )));
    };
    let seed = cli::parse_number("--random SEED", seed, 0, u64::MAX)?;
    let size = cli::parse_number("--random U", size, 8, 1 << 30)?;
    if size & (size - 1) != 0 {
        return Err(CliError::new(format!(
            "--random U {size}: expected a power of two from 8 to 2^30"
        )));
    }
    let count = cli::parse_number("--random COUNT", count, 0, usize::MAX)?;
    let capacity = orthtree::mesh::random_board_capacity(size);
    if count as u64 > capacity {
        return Err(CliError::new(format!(
            "--random COUNT {count}: at most {capacity} components fit a board of side {size}"
        )));
    }
    // A lower bound before the board is drawn (each component at least a unit square); the
    // board's real perimeter is checked once it is drawn.
    let least = count as f64;
    cli::check_memory(
        &format!("--random {raw}: {count} components of at least 4 perimeter steps each"),
        least * (BOARD_BYTES_PER_COMPONENT + solve_bytes_for_perimeter(MIN_PERIMETER_STEPS)),
        cli::memory_limit(),
    )?;
    Ok((seed, size, count))
}

fn parse(cli: &mut Cli) -> Result<Args, CliError> {
    let mut args = Args {
        board: None,
        size: None,
        random: None,
        max_triangles: DEFAULT_MAX_TRIANGLES,
        files: true,
    };
    while let Some(arg) = cli.next_arg()? {
        match arg.as_str() {
            "--size" => args.size = Some(cli.number("--size", 1, 1 << 30)?),
            "--max-triangles" => args.max_triangles = cli.number("--max-triangles", 1, u64::MAX)?,
            "--random" => args.random = Some(parse_random(&cli.value("--random")?)?),
            "--no-files" => args.files = false,
            flag if flag.starts_with('-') => return Err(CliError::unknown(flag)),
            path if args.board.is_none() => args.board = Some(path.to_string()),
            extra => return Err(CliError::unknown(extra)),
        }
    }
    if args.random.is_some() {
        if let Some(path) = &args.board {
            return Err(CliError::new(format!(
                "--random and the board file {}: give one of them",
                cli::shown(path)
            )));
        }
        if let Some(size) = args.size {
            return Err(CliError::new(format!(
                "--size {size} with --random: the random board's side is its U"
            )));
        }
    } else if let (Some(size), None) = (args.size, &args.board) {
        return Err(CliError::new(format!(
            "--size {size} needs a board file (the built-in board has its own size)"
        )));
    }
    Ok(args)
}

fn read_board(args: &Args) -> Result<(Board, String), String> {
    if let Some((seed, u, count)) = args.random {
        return try_random_board(seed, u, count)
            .map(|b| (b, format!("random_board({seed}, {u}, {count})")))
            .map_err(|e| e.to_string());
    }
    let Some(path) = &args.board else {
        return Ok((sample_board(), "built-in sample board".into()));
    };
    orthtree::io::read_board_file(path, args.size)
        .map(|b| (b, path.clone()))
        .map_err(|e| e.to_string())
}

/// An inferno-like colour map: `s` in [0, 1] to RGB.
fn colour(s: f64) -> [u8; 3] {
    const STOPS: [[f64; 3]; 6] = [
        [0.0, 0.0, 4.0],
        [66.0, 10.0, 104.0],
        [147.0, 38.0, 103.0],
        [221.0, 81.0, 58.0],
        [252.0, 165.0, 10.0],
        [252.0, 255.0, 164.0],
    ];
    let s = s.clamp(0.0, 1.0) * (STOPS.len() - 1) as f64;
    let i = (s.floor() as usize).min(STOPS.len() - 2);
    let f = s - i as f64;
    let mut c = [0u8; 3];
    for (ch, out) in c.iter_mut().enumerate() {
        *out = (STOPS[i][ch] * (1.0 - f) + STOPS[i + 1][ch] * f).round() as u8;
    }
    c
}

/// The heat map, streamed to `out`: each triangle filled with the colour of its mean vertex
/// temperature (256 levels, one path per level, triangles sorted into levels by counting), the
/// component outlines on top, a colour bar on the right.
fn write_heat_svg(
    mesh: &Mesh,
    board: &Board,
    t: &[f64],
    t_max: f64,
    out: &mut impl Write,
) -> std::io::Result<()> {
    const LEVELS: usize = 256;
    let u = board.size() as f64;
    let level_of = |tri: &[u32; 3]| {
        let mean = tri.iter().map(|&v| t[v as usize]).sum::<f64>() / 3.0;
        let level = ((mean / t_max.max(f64::MIN_POSITIVE)) * (LEVELS - 1) as f64).round();
        (level.max(0.0) as usize).min(LEVELS - 1)
    };
    // Counting sort of the triangles by level: `order[start[l]..start[l + 1]]` is level l.
    let levels: Vec<u8> = mesh
        .triangles
        .iter()
        .map(|tri| level_of(tri) as u8)
        .collect();
    let mut start = [0usize; LEVELS + 1];
    for &l in &levels {
        start[l as usize + 1] += 1;
    }
    for l in 0..LEVELS {
        start[l + 1] += start[l];
    }
    let mut next = start;
    let mut order = vec![0u32; levels.len()];
    for (k, &l) in levels.iter().enumerate() {
        order[next[l as usize]] = k as u32;
        next[l as usize] += 1;
    }
    drop(levels);

    let bar = u / 16.0;
    let (w, h) = (u + 3.0 * bar, u);
    writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="{} {} {} {}" width="{}" height="{}">"#,
        -bar / 2.0,
        -bar / 2.0,
        w + bar / 2.0,
        h + bar,
        (w + bar) * 900.0 / (u + bar),
        900.0 * (h + bar) / (u + bar)
    )?;
    writeln!(
        out,
        r#"<rect x="{}" y="{}" width="100%" height="100%" fill="white"/>"#,
        -bar / 2.0,
        -bar / 2.0
    )?;
    writeln!(out, r#"<g transform="translate(0 {u}) scale(1 -1)">"#)?;
    let stroke = u / 4096.0;
    for level in 0..LEVELS {
        let members = &order[start[level]..start[level + 1]];
        if members.is_empty() {
            continue;
        }
        let [r, g, b] = colour(level as f64 / (LEVELS - 1) as f64);
        write!(
            out,
            r##"<path fill="#{r:02x}{g:02x}{b:02x}" stroke="#{r:02x}{g:02x}{b:02x}" stroke-width="{stroke}" d=""##
        )?;
        for &k in members {
            let [a, b, c] = mesh.triangles[k as usize].map(|v| mesh.vertices[v as usize]);
            write!(
                out,
                "M{} {}L{} {}L{} {}Z",
                a[0], a[1], b[0], b[1], c[0], c[1]
            )?;
        }
        writeln!(out, "\"/>")?;
    }
    write!(
        out,
        r##"<path fill="none" stroke="#7fdfff" stroke-width="{}" stroke-linejoin="round" d=""##,
        u / 1024.0
    )?;
    for c in board.components() {
        for (i, p) in c.outline.iter().enumerate() {
            write!(out, "{}{} {}", if i == 0 { "M" } else { "L" }, p[0], p[1])?;
        }
        write!(out, "Z")?;
    }
    writeln!(out, "\"/>")?;
    writeln!(
        out,
        r##"<rect x="0" y="0" width="{u}" height="{u}" fill="none" stroke="black" stroke-width="{}"/>"##,
        u / 512.0
    )?;
    writeln!(out, "</g>")?;
    // colour bar
    let x0 = u + bar;
    let steps = 64;
    for i in 0..steps {
        let [r, g, b] = colour((i as f64 + 0.5) / steps as f64);
        let y = u - (i + 1) as f64 * u / steps as f64;
        writeln!(
            out,
            r##"<rect x="{x0}" y="{y}" width="{}" height="{}" fill="#{r:02x}{g:02x}{b:02x}"/>"##,
            bar / 2.0,
            u / steps as f64 + 0.5
        )?;
    }
    let font = u / 40.0;
    for (y, label) in [(u, "0 K".to_string()), (font, format!("{t_max:.3} K"))] {
        writeln!(
            out,
            r#"<text x="{}" y="{y}" font-family="sans-serif" font-size="{font}" transform="rotate(-90 {} {y})" text-anchor="{}">{label}</text>"#,
            x0 + bar * 1.2,
            x0 + bar * 1.2,
            if y == u { "start" } else { "end" }
        )?;
    }
    writeln!(out, "</svg>")?;
    out.flush()
}

/// The mesh as legacy VTK with the temperature as `POINT_DATA` (and the region as `CELL_DATA`),
/// streamed to a file.
fn write_heat_vtk(mesh: &Mesh, t: &[f64], path: &str) -> std::io::Result<()> {
    let mut out = BufWriter::new(std::fs::File::create(path)?);
    vtk::write_vtk(mesh, &mut out)?;
    writeln!(out, "POINT_DATA {}", mesh.vertices.len())?;
    writeln!(out, "SCALARS temperature double 1\nLOOKUP_TABLE default")?;
    for v in t {
        writeln!(out, "{v:e}")?;
    }
    out.flush()
}

fn ms(d: Duration) -> String {
    format!("{:.1} ms", d.as_secs_f64() * 1e3)
}

fn main() {
    let args = cli::parse_or_exit(USAGE, parse);
    let (board, name) = read_board(&args).unwrap_or_else(|e| {
        eprintln!("error: {e}");
        std::process::exit(1);
    });
    if let Err(e) = check_board_work(&board, &name) {
        cli::exit_with(USAGE, e);
    }
    let start = Instant::now();
    let options = MeshOptions::new()
        .grid_unit(1)
        .max_triangles(args.max_triangles);
    let out = options.generate(&board).unwrap_or_else(|e| {
        eprintln!("error: {e}");
        std::process::exit(1);
    });
    let mesh_time = start.elapsed();
    let mesh = out.mesh;
    let solve_work = format!("{name}: {} triangles to solve on", mesh.triangles.len());
    let solve_bytes = fem::estimated_solve_bytes(mesh.triangles.len());
    if let Err(e) = cli::check_memory(&solve_work, solve_bytes, cli::memory_limit()) {
        eprintln!("error: {e}");
        std::process::exit(2);
    }

    let (k, q) = fem::board_materials(&board);
    let start = Instant::now();
    let sys = fem::assemble_board(&mesh, &k, &q);
    let assembly_time = start.elapsed();
    let (t, times) = fem::solve(&sys).unwrap_or_else(|e| {
        eprintln!("error: Cholesky factorization failed: {e}");
        std::process::exit(1);
    });
    let t_min = t.iter().copied().fold(f64::INFINITY, f64::min);
    let t_max = t.iter().copied().fold(f64::NEG_INFINITY, f64::max);

    println!(
        "board:      {name}: U = {}, {} components",
        board.size(),
        board.components().len()
    );
    println!(
        "mesh:       {} triangles, {} vertices ({})",
        mesh.triangles.len(),
        mesh.vertices.len(),
        ms(mesh_time)
    );
    println!(
        "system:     {} unknowns, {} stored entries (lower triangle), max off-diagonal {:e}",
        sys.n,
        sys.values.len(),
        sys.max_off_diagonal()
    );
    println!("assembly:   {}", ms(assembly_time));
    println!(
        "solve:      {} (ordering + symbolic {}, Cholesky {}, substitution {})",
        ms(times.total()),
        ms(times.symbolic),
        ms(times.numeric),
        ms(times.substitution)
    );
    println!("temperature: min {t_min:.6e} K, max {t_max:.6} K (rise over the board edge)");
    if args.files {
        let start = Instant::now();
        let svg = |path: &str| {
            let mut out = BufWriter::new(std::fs::File::create(path)?);
            write_heat_svg(&mesh, &board, &t, t_max, &mut out)
        };
        let written = svg("pcb_heat.svg").and_then(|_| write_heat_vtk(&mesh, &t, "pcb_heat.vtk"));
        if let Err(e) = written {
            eprintln!("error: writing pcb_heat.svg / pcb_heat.vtk: {e}");
            std::process::exit(1);
        }
        println!(
            "wrote:      pcb_heat.svg pcb_heat.vtk ({})",
            ms(start.elapsed())
        );
    }
}
