//! The crate's main job: mesh a circuit board with the chapter's GENERATEMESH (section 14.3).
//!
//! `cargo run --release --example pcb_mesh -- [BOARD.poly|BOARD.txt] [--size U] [--out PREFIX]
//! [--mode book|coarsest] [--unit G] [--near H] [--max H]`
//!
//! With no board it meshes the built-in sample board. `--mode book` (the default) is the
//! chapter's GENERATEMESH; `--mode coarsest` splits a cell only where it must. `--unit` fixes the
//! grid unit (default: detected), `--near` caps the cells meeting component edges and `--max`
//! every cell (in board coordinates; see `MeshOptions`). Writes PREFIX.node, .ele, .edge (Triangle),
//! .msh (Gmsh 4.1), .vtk (legacy VTK) and .svg (default prefix `board`), validates the mesh and
//! prints one summary. A bad board prints the error and exits with status 1.

use orthtree::io::{gmsh, triangle, vtk};
use orthtree::mesh::{sample_board, Board, MeshOptions, Mode};
use std::time::{Duration, Instant};

struct Args {
    board: Option<String>,
    size: Option<i64>,
    out: String,
    options: MeshOptions,
}

const USAGE: &str = "usage: pcb_mesh [BOARD.poly|BOARD.txt] [--size U] [--out PREFIX] \
                     [--mode book|coarsest] [--unit G] [--near H] [--max H]";

fn parse() -> Result<Args, String> {
    let mut args = Args {
        board: None,
        size: None,
        out: "board".into(),
        options: MeshOptions::new(),
    };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        let mut value = || it.next().ok_or(format!("{arg} needs a value"));
        let mut number = || -> Result<i64, String> {
            let v = value()?;
            v.parse().map_err(|e| format!("{arg} {v:?}: {e}"))
        };
        let options = args.options.clone();
        match arg.as_str() {
            "--size" => args.size = Some(number()?),
            "--unit" => args.options = options.grid_unit(number()?),
            "--near" => args.options = options.near_size(number()?),
            "--max" => args.options = options.max_size(number()?),
            "--out" => args.out = value()?,
            "--mode" => {
                let mode = match value()?.as_str() {
                    "book" => Mode::Book,
                    "coarsest" => Mode::Coarsest,
                    other => return Err(format!("--mode {other:?}: use `book` or `coarsest`")),
                };
                args.options = options.mode(mode);
            }
            flag if flag.starts_with("--") => return Err(format!("unknown option {flag:?}")),
            path if args.board.is_none() => args.board = Some(path.to_string()),
            extra => return Err(format!("unexpected argument {extra:?}")),
        }
    }
    Ok(args)
}

fn read_board(args: &Args) -> Result<(Board, String), String> {
    let Some(path) = &args.board else {
        if args.size.is_some() {
            return Err("--size needs a board file (the built-in board has its own size)".into());
        }
        return Ok((sample_board(), "built-in sample board".into()));
    };
    orthtree::io::read_board_file(path, args.size)
        .map(|b| (b, path.clone()))
        .map_err(|e| e.to_string())
}

fn write_all(mesh: &orthtree::mesh::Mesh, board: &Board, prefix: &str) -> std::io::Result<()> {
    triangle::write_triangle_files(mesh, prefix)?;
    gmsh::write_msh_to(mesh, format!("{prefix}.msh"))?;
    vtk::write_vtk_to(mesh, format!("{prefix}.vtk"))?;
    std::fs::write(
        format!("{prefix}.svg"),
        orthtree::io::svg::mesh_svg(mesh, board),
    )
}

fn ms(d: Duration) -> String {
    format!("{:.1} ms", d.as_secs_f64() * 1e3)
}

fn main() {
    let args = parse().unwrap_or_else(|e| {
        eprintln!("error: {e}\n{USAGE}");
        std::process::exit(2);
    });
    let (board, name) = read_board(&args).unwrap_or_else(|e| {
        eprintln!("error: {e}");
        std::process::exit(1);
    });
    let out = args.options.generate(&board).unwrap_or_else(|e| {
        eprintln!("error: {e}");
        std::process::exit(1);
    });
    let start = Instant::now();
    let report = out.mesh.validate(&board);
    let validate_time = start.elapsed();
    let start = Instant::now();
    if let Err(e) = write_all(&out.mesh, &board, &args.out) {
        eprintln!("error: writing {}.*: {e}", args.out);
        std::process::exit(1);
    }
    let write_time = start.elapsed();
    let [lo, hi] = report.angle_range_deg.unwrap_or([f64::NAN; 2]);
    println!(
        "board:       {name}: U = {}, {} components, perimeter {}",
        board.size(),
        board.components().len(),
        board.perimeter_steps()
    );
    println!(
        "quadtree:    {:?} mode, grid unit {}, {} leaves, {} after 2:1 balance",
        args.options.current_mode(),
        out.grid_unit,
        out.leaves_before_balance,
        out.tree.leaf_count()
    );
    println!(
        "mesh:        {} triangles, {} vertices, angles {lo:.1} to {hi:.1} degrees",
        out.mesh.triangles.len(),
        out.mesh.vertices.len()
    );
    println!(
        "validation:  {}",
        if report.is_ok() {
            "ok (conforming, respects input, 45-90 degrees, regions, Euler, Delaunay)".to_string()
        } else {
            report.to_string()
        }
    );
    println!(
        "memory:      {:.1} bytes per triangle",
        out.mesh.heap_bytes() as f64 / out.mesh.triangles.len().max(1) as f64
    );
    println!(
        "time:        build {}, balance {}, triangulate {}, validate {}, write {}",
        ms(out.build_time),
        ms(out.balance_time),
        ms(out.triangulate_time),
        ms(validate_time),
        ms(write_time)
    );
    println!(
        "wrote:       {0}.node {0}.ele {0}.edge {0}.msh {0}.vtk {0}.svg",
        args.out
    );
    if !report.is_ok() {
        std::process::exit(1);
    }
}
