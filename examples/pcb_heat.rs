//! Heat on the board: the steady heat equation `-div(k grad T) = q` solved with linear (P1)
//! finite elements on the quadtree mesh of a circuit board.
//!
//! `cargo run --release --example pcb_heat -- [BOARD.poly|BOARD.txt] [--size U]
//! [--random SEED,U,COUNT] [--no-files]`
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
use orthtree::mesh::{generate_mesh, random_board, sample_board, Board, Mesh};
use std::fmt::Write as _;
use std::io::Write as _;
use std::time::{Duration, Instant};

struct Args {
    board: Option<String>,
    size: Option<i64>,
    random: Option<(u64, i64, usize)>,
    files: bool,
}

fn parse() -> Result<Args, String> {
    let mut args = Args {
        board: None,
        size: None,
        random: None,
        files: true,
    };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        let mut value = || it.next().ok_or(format!("{arg} needs a value"));
        match arg.as_str() {
            "--size" => args.size = Some(value()?.parse().map_err(|e| format!("--size: {e}"))?),
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
                args.random = Some((
                    parts[0].parse().map_err(|_| bad())?,
                    u,
                    parts[2].parse().map_err(|_| bad())?,
                ));
            }
            "--no-files" => args.files = false,
            flag if flag.starts_with("--") => return Err(format!("unknown option {flag:?}")),
            path if args.board.is_none() => args.board = Some(path.to_string()),
            extra => return Err(format!("unexpected argument {extra:?}")),
        }
    }
    Ok(args)
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

/// The heat map: each triangle filled with the colour of its mean vertex temperature (256
/// levels, one path per level), the component outlines on top, a colour bar on the right.
fn heat_svg(mesh: &Mesh, board: &Board, t: &[f64], t_max: f64) -> String {
    const LEVELS: usize = 256;
    let u = board.size() as f64;
    let mut paths = vec![String::new(); LEVELS];
    for tri in &mesh.triangles {
        let mean = tri.iter().map(|&v| t[v as usize]).sum::<f64>() / 3.0;
        let level = ((mean / t_max.max(f64::MIN_POSITIVE)) * (LEVELS - 1) as f64).round();
        let path = &mut paths[(level.max(0.0) as usize).min(LEVELS - 1)];
        let [a, b, c] = tri.map(|v| mesh.vertices[v as usize]);
        let _ = write!(
            path,
            "M{} {}L{} {}L{} {}Z",
            a[0], a[1], b[0], b[1], c[0], c[1]
        );
    }
    let bar = u / 16.0;
    let (w, h) = (u + 3.0 * bar, u);
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="{} {} {} {}" width="{}" height="{}">"#,
        -bar / 2.0,
        -bar / 2.0,
        w + bar / 2.0,
        h + bar,
        (w + bar) * 900.0 / (u + bar),
        900.0 * (h + bar) / (u + bar)
    );
    let _ = writeln!(
        s,
        r#"<rect x="{}" y="{}" width="100%" height="100%" fill="white"/>"#,
        -bar / 2.0,
        -bar / 2.0
    );
    let _ = writeln!(s, r#"<g transform="translate(0 {u}) scale(1 -1)">"#);
    let stroke = u / 4096.0;
    for (level, path) in paths.iter().enumerate() {
        if path.is_empty() {
            continue;
        }
        let [r, g, b] = colour(level as f64 / (LEVELS - 1) as f64);
        let _ = writeln!(
            s,
            r##"<path fill="#{r:02x}{g:02x}{b:02x}" stroke="#{r:02x}{g:02x}{b:02x}" stroke-width="{stroke}" d="{path}"/>"##
        );
    }
    let mut outlines = String::new();
    for c in board.components() {
        for (i, p) in c.outline.iter().enumerate() {
            let _ = write!(
                outlines,
                "{}{} {}",
                if i == 0 { "M" } else { "L" },
                p[0],
                p[1]
            );
        }
        outlines.push('Z');
    }
    let _ = writeln!(
        s,
        r##"<path fill="none" stroke="#7fdfff" stroke-width="{}" stroke-linejoin="round" d="{outlines}"/>"##,
        u / 1024.0
    );
    let _ = writeln!(
        s,
        r##"<rect x="0" y="0" width="{u}" height="{u}" fill="none" stroke="black" stroke-width="{}"/>"##,
        u / 512.0
    );
    s.push_str("</g>\n");
    // colour bar
    let x0 = u + bar;
    let steps = 64;
    for i in 0..steps {
        let [r, g, b] = colour((i as f64 + 0.5) / steps as f64);
        let y = u - (i + 1) as f64 * u / steps as f64;
        let _ = writeln!(
            s,
            r##"<rect x="{x0}" y="{y}" width="{}" height="{}" fill="#{r:02x}{g:02x}{b:02x}"/>"##,
            bar / 2.0,
            u / steps as f64 + 0.5
        );
    }
    let font = u / 40.0;
    for (y, label) in [(u, "0 K".to_string()), (font, format!("{t_max:.3} K"))] {
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{y}" font-family="sans-serif" font-size="{font}" transform="rotate(-90 {} {y})" text-anchor="{}">{label}</text>"#,
            x0 + bar * 1.2,
            x0 + bar * 1.2,
            if y == u { "start" } else { "end" }
        );
    }
    s.push_str("</svg>\n");
    s
}

/// The mesh as legacy VTK with the temperature as `POINT_DATA` (and the region as `CELL_DATA`).
fn write_heat_vtk(mesh: &Mesh, t: &[f64], path: &str) -> std::io::Result<()> {
    let mut out = Vec::new();
    vtk::write_vtk(mesh, &mut out)?;
    writeln!(out, "POINT_DATA {}", mesh.vertices.len())?;
    writeln!(out, "SCALARS temperature double 1\nLOOKUP_TABLE default")?;
    for v in t {
        writeln!(out, "{v:e}")?;
    }
    std::fs::write(path, out)
}

fn ms(d: Duration) -> String {
    format!("{:.1} ms", d.as_secs_f64() * 1e3)
}

fn main() {
    let args = parse().unwrap_or_else(|e| {
        eprintln!("error: {e}\nusage: pcb_heat [BOARD.poly|BOARD.txt] [--size U] [--random SEED,U,COUNT] [--no-files]");
        std::process::exit(2);
    });
    let (board, name) = read_board(&args).unwrap_or_else(|e| {
        eprintln!("error: {e}");
        std::process::exit(1);
    });
    let start = Instant::now();
    let out = generate_mesh(&board).unwrap_or_else(|e| {
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
        let written = std::fs::write("pcb_heat.svg", heat_svg(&mesh, &board, &t, t_max))
            .and_then(|_| write_heat_vtk(&mesh, &t, "pcb_heat.vtk"));
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
