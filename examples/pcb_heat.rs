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
use orthtree::mesh::{random_board, sample_board, Board, Mesh, MeshOptions};
use std::io::{BufWriter, Write};
use std::time::{Duration, Instant};

struct Args {
    board: Option<String>,
    size: Option<i64>,
    random: Option<(u64, i64, usize)>,
    max_triangles: u64,
    files: bool,
}

const USAGE: &str = "usage: pcb_heat [BOARD.poly|BOARD.txt] [--size U] [--random SEED,U,COUNT] \
                     [--max-triangles N] [--no-files] [--help]";

/// The default mesh limit: about 10^6 unknowns, whose Cholesky factor fits in a few GiB.
const DEFAULT_MAX_TRIANGLES: u64 = 2_000_000;

/// The most components `--random` asks for: `random_board` places them in O(COUNT^2) time.
const MAX_RANDOM_COUNT: usize = 100_000;

/// `None` for `--help`.
fn parse() -> Result<Option<Args>, String> {
    let mut args = Args {
        board: None,
        size: None,
        random: None,
        max_triangles: DEFAULT_MAX_TRIANGLES,
        files: true,
    };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        let mut value = || it.next().ok_or(format!("{arg} needs a value"));
        match arg.as_str() {
            "--help" | "-h" => return Ok(None),
            "--size" => args.size = Some(value()?.parse().map_err(|e| format!("--size: {e}"))?),
            "--max-triangles" => {
                let v = value()?;
                args.max_triangles = v.parse().map_err(|e| format!("--max-triangles {v:?}: {e}"))?
            }
            "--random" => {
                let v = value()?;
                let parts: Vec<&str> = v.split(',').collect();
                let bad = || format!("--random {v:?}: expected SEED,U,COUNT");
                if parts.len() != 3 {
                    return Err(bad());
                }
                let u: i64 = parts[1].parse().map_err(|_| bad())?;
                if !(8..=1 << 30).contains(&u) || u & (u - 1) != 0 {
                    return Err(format!(
                        "--random: U = {u} is not a power of two from 8 to 2^30"
                    ));
                }
                let count: usize = parts[2].parse().map_err(|_| bad())?;
                if count > MAX_RANDOM_COUNT {
                    return Err(format!(
                        "--random: COUNT = {count} is above {MAX_RANDOM_COUNT} (placing \
                         components takes time quadratic in the count)"
                    ));
                }
                args.random = Some((parts[0].parse().map_err(|_| bad())?, u, count));
            }
            "--no-files" => args.files = false,
            flag if flag.starts_with('-') && flag.len() > 1 => {
                return Err(format!("unknown option {flag:?}"))
            }
            path if args.board.is_none() => args.board = Some(path.to_string()),
            extra => return Err(format!("unexpected argument {extra:?}")),
        }
    }
    if args.board.is_some() && args.random.is_some() {
        return Err("give a board file or --random, not both".into());
    }
    Ok(Some(args))
}

fn read_board(args: &Args) -> Result<(Board, String), String> {
    if let Some((seed, u, count)) = args.random {
        return Ok((
            random_board(seed, u, count),
            format!("random_board({seed}, {u}, {count})"),
        ));
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
    let levels: Vec<u8> = mesh.triangles.iter().map(|tri| level_of(tri) as u8).collect();
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
            write!(out, "M{} {}L{} {}L{} {}Z", a[0], a[1], b[0], b[1], c[0], c[1])?;
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
    let args = match parse() {
        Ok(Some(args)) => args,
        Ok(None) => {
            println!("{USAGE}");
            return;
        }
        Err(e) => {
            eprintln!("error: {e}\n{USAGE}");
            std::process::exit(2);
        }
    };
    let (board, name) = read_board(&args).unwrap_or_else(|e| {
        eprintln!("error: {e}");
        std::process::exit(1);
    });
    let start = Instant::now();
    let options = MeshOptions::new().grid_unit(1).max_triangles(args.max_triangles);
    let out = options.generate(&board).unwrap_or_else(|e| {
        eprintln!("error: {e}");
        std::process::exit(1);
    });
    let mesh_time = start.elapsed();
    let mesh = out.mesh;

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
