//! The crate's main job: mesh a circuit board with the chapter's GENERATEMESH (section 14.3).
//!
//! `cargo run --release --example pcb_mesh -- [BOARD.poly|BOARD.txt] [--size U]
//! [--random SEED,U,COUNT] [--out PREFIX] [--mode book|coarsest] [--unit G] [--near H] [--max H]
//! [--max-triangles N] [--no-svg] [--no-files]`
//!
//! With no board it meshes the built-in sample board (or `random_board(SEED, U, COUNT)` with
//! `--random`). `--mode book` (the default) is the chapter's GENERATEMESH; `--mode coarsest`
//! splits a cell only where it must. `--unit` fixes the grid unit (default: detected), `--near`
//! caps the cells meeting component edges and `--max` every cell (in board coordinates; see
//! `MeshOptions`); `--max-triangles` sets the mesher's budget (default 2e7, about 2.8 GiB): a
//! board needing more is refused before the work is done. Writes PREFIX.node, .ele, .edge
//! (Triangle), .msh (Gmsh 4.1), .vtk (legacy VTK) and .svg (default prefix `board`; `--no-svg`
//! leaves out the picture, `--no-files` writes nothing), validates the mesh and prints one
//! summary. Bad arguments exit with status 2, a refused board or a failed write with status 1.

use orthtree::io::{gmsh, svg, triangle, vtk};
use orthtree::mesh::{random_board, sample_board, Board, MeshOptions, Mode};
use std::path::Path;
use std::time::{Duration, Instant};

struct Args {
    board: Option<String>,
    size: Option<i64>,
    random: Option<(u64, i64, usize)>,
    out: String,
    options: MeshOptions,
    svg: bool,
    files: bool,
}

const USAGE: &str = "usage: pcb_mesh [BOARD.poly|BOARD.txt] [--size U] [--random SEED,U,COUNT] \
                     [--out PREFIX] [--mode book|coarsest] [--unit G] [--near H] [--max H] \
                     [--max-triangles N] [--no-svg] [--no-files] [--help]";

/// The most components `--random` asks for: `random_board` places them in O(COUNT^2) time.
const MAX_RANDOM_COUNT: usize = 100_000;

enum Parsed {
    Run(Args),
    Help,
}

fn parse_number<T: std::str::FromStr>(flag: &str, v: &str) -> Result<T, String>
where
    T::Err: std::fmt::Display,
{
    v.parse().map_err(|e| format!("{flag} {v:?}: {e}"))
}

/// `SEED,U,COUNT` of `--random`, checked so that `random_board` cannot panic.
fn parse_random(v: &str) -> Result<(u64, i64, usize), String> {
    let parts: Vec<&str> = v.split(',').collect();
    let [seed, u, count] = parts[..] else {
        return Err(format!("--random {v:?}: expected SEED,U,COUNT"));
    };
    let seed = parse_number("--random SEED", seed)?;
    let u: i64 = parse_number("--random U", u)?;
    if !(8..=1 << 30).contains(&u) || u & (u - 1) != 0 {
        return Err(format!(
            "--random: U = {u} is not a power of two from 8 to 2^30"
        ));
    }
    let count: usize = parse_number("--random COUNT", count)?;
    if count > MAX_RANDOM_COUNT {
        return Err(format!(
            "--random: COUNT = {count} is above {MAX_RANDOM_COUNT} (placing components takes \
             time quadratic in the count)"
        ));
    }
    Ok((seed, u, count))
}

fn parse(args: impl IntoIterator<Item = String>) -> Result<Parsed, String> {
    let mut args_out = Args {
        board: None,
        size: None,
        random: None,
        out: "board".into(),
        options: MeshOptions::new(),
        svg: true,
        files: true,
    };
    let a = &mut args_out;
    let mut it = args.into_iter();
    while let Some(arg) = it.next() {
        let mut value = || it.next().ok_or(format!("{arg} needs a value"));
        let options = a.options.clone();
        match arg.as_str() {
            "--help" | "-h" => return Ok(Parsed::Help),
            "--size" => a.size = Some(parse_number(&arg, &value()?)?),
            "--random" => a.random = Some(parse_random(&value()?)?),
            "--unit" => a.options = options.grid_unit(parse_number(&arg, &value()?)?),
            "--near" => a.options = options.near_size(parse_number(&arg, &value()?)?),
            "--max" => a.options = options.max_size(parse_number(&arg, &value()?)?),
            "--max-triangles" => a.options = options.max_triangles(parse_number(&arg, &value()?)?),
            "--out" => a.out = value()?,
            "--no-svg" => a.svg = false,
            "--no-files" => a.files = false,
            "--mode" => {
                let mode = match value()?.as_str() {
                    "book" => Mode::Book,
                    "coarsest" => Mode::Coarsest,
                    other => return Err(format!("--mode {other:?}: use `book` or `coarsest`")),
                };
                a.options = options.mode(mode);
            }
            flag if flag.starts_with('-') && flag.len() > 1 => {
                return Err(format!("unknown option {flag:?}"))
            }
            path if a.board.is_none() => a.board = Some(path.to_string()),
            extra => return Err(format!("unexpected argument {extra:?}")),
        }
    }
    if a.board.is_some() && a.random.is_some() {
        return Err("give a board file or --random, not both".into());
    }
    if a.random.is_some() && a.size.is_some() {
        return Err("--size applies to a board file, not to --random (which has its U)".into());
    }
    Ok(Parsed::Run(args_out))
}

fn read_board(args: &Args) -> Result<(Board, String), String> {
    if let Some((seed, u, count)) = args.random {
        let name = format!("random_board({seed}, {u}, {count})");
        return Ok((random_board(seed, u, count), name));
    }
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

/// Refuses an output prefix whose folder does not exist, before any work is done.
fn check_prefix(prefix: &str) -> Result<(), String> {
    if prefix.is_empty() {
        return Err("--out: the prefix is empty".into());
    }
    let parent = Path::new(prefix).parent().unwrap_or(Path::new(""));
    if !parent.as_os_str().is_empty() && !parent.is_dir() {
        return Err(format!(
            "--out {prefix:?}: the folder {} does not exist",
            parent.display()
        ));
    }
    Ok(())
}

/// Writes every file, each streamed through a buffer, the formats on threads of their own;
/// returns the names written.
fn write_all(
    mesh: &orthtree::mesh::Mesh,
    board: &Board,
    prefix: &str,
    with_svg: bool,
) -> std::io::Result<Vec<String>> {
    let mut names: Vec<String> = ["node", "ele", "edge", "msh", "vtk"]
        .iter()
        .map(|s| format!("{prefix}.{s}"))
        .collect();
    if with_svg {
        names.push(format!("{prefix}.svg"));
    }
    std::thread::scope(|scope| {
        let jobs = [
            scope.spawn(|| triangle::write_triangle_files(mesh, prefix)),
            scope.spawn(|| gmsh::write_msh_to(mesh, format!("{prefix}.msh"))),
            scope.spawn(|| vtk::write_vtk_to(mesh, format!("{prefix}.vtk"))),
            scope.spawn(|| match with_svg {
                true => svg::write_mesh_svg_to(mesh, board, format!("{prefix}.svg")),
                false => Ok(()),
            }),
        ];
        for job in jobs {
            job.join()
                .map_err(|_| std::io::Error::other("a writer panicked"))??;
        }
        Ok::<(), std::io::Error>(())
    })?;
    Ok(names)
}

fn ms(d: Duration) -> String {
    format!("{:.1} ms", d.as_secs_f64() * 1e3)
}

fn fail(status: i32, message: String) -> ! {
    eprintln!("error: {message}");
    std::process::exit(status)
}

fn main() {
    let args = match parse(std::env::args().skip(1)) {
        Ok(Parsed::Run(args)) => args,
        Ok(Parsed::Help) => {
            println!("{USAGE}");
            return;
        }
        Err(e) => fail(2, format!("{e}\n{USAGE}")),
    };
    if args.files {
        check_prefix(&args.out).unwrap_or_else(|e| fail(2, e));
    }
    let (board, name) = read_board(&args).unwrap_or_else(|e| fail(1, e));
    let out = (args.options.generate(&board)).unwrap_or_else(|e| fail(1, e.to_string()));
    let start = Instant::now();
    let report = out.mesh.validate(&board);
    let validate_time = start.elapsed();
    let start = Instant::now();
    let written = if args.files {
        write_all(&out.mesh, &board, &args.out, args.svg)
            .unwrap_or_else(|e| fail(1, format!("writing {}.*: {e}", args.out)))
    } else {
        Vec::new()
    };
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
    if written.is_empty() {
        println!("wrote:       nothing (--no-files)");
    } else {
        println!("wrote:       {}", written.join(" "));
    }
    if !report.is_ok() {
        std::process::exit(1);
    }
}
