//! `orthtree mesh`, the crate's main job: mesh a circuit board with the chapter's GENERATEMESH
//! (section 14.3), validate the mesh, print one summary and write it as Triangle, Gmsh, VTK and
//! SVG files.

use crate::limits::{self, shown};
use crate::progress::Phase;
use crate::random_board::RandomBoard;
use crate::Failure;
use orthtree::io::{gmsh, svg, triangle, vtk};
use orthtree::mesh::{sample_board, Board, MeshOptions, Mode};
use std::path::Path;
use std::time::{Duration, Instant};

/// Mesh a circuit board with the chapter's GENERATEMESH (the main job)
///
/// Meshes the board, validates the mesh, prints a summary and writes PREFIX.node, .ele, .edge
/// (Triangle), .msh (Gmsh 4.1), .vtk (legacy VTK) and .svg. With no board it meshes the built-in sample board (U = 1024, 147 components), or
/// random_board(SEED, U, COUNT) with --random. A board the mesher refuses (beyond
/// --max-triangles) or a failed write exits with code 1.
#[derive(clap::Args, Debug)]
#[command(after_help = crate::EXIT_CODES, allow_negative_numbers = true)]
pub struct MeshArgs {
    /// A board file: Triangle's .poly or the plain text format (.txt)
    #[arg(value_name = "BOARD")]
    board: Option<String>,
    /// The board's side U for a file that does not give it
    #[arg(long, value_name = "U")]
    size: Option<i64>,
    /// random_board(SEED, U, COUNT) instead of a file: U a power of two from 8 to 2^30, COUNT at
    /// most 100000 and at most (U / 2)^2
    #[arg(long, value_name = "SEED,U,COUNT", value_parser = parse_random,
          conflicts_with_all = ["board", "size"])]
    random: Option<RandomBoard>,
    /// The prefix of the files written
    #[arg(long, value_name = "PREFIX", default_value = "board", value_parser = check_prefix)]
    out: String,
    /// book: the chapter's GENERATEMESH; coarsest: split a cell only where it must
    #[arg(long, value_enum, default_value = "book")]
    mode: ModeArg,
    /// The grid unit G (default: detected from the board)
    #[arg(long, value_name = "G")]
    unit: Option<i64>,
    /// The largest cell meeting a component edge, in board units
    #[arg(long, value_name = "H")]
    near: Option<i64>,
    /// The largest cell anywhere, in board units
    #[arg(long, value_name = "H")]
    max: Option<i64>,
    /// The mesher's budget: a board needing more triangles is refused before the work is done
    /// (default 2e7, about 2.8 GiB)
    #[arg(long, value_name = "N")]
    max_triangles: Option<u64>,
    /// Leave out the SVG picture
    #[arg(long)]
    no_svg: bool,
    /// Write no files
    #[arg(long)]
    no_files: bool,
}

/// The mesher's modes on the command line.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
enum ModeArg {
    Book,
    Coarsest,
}

/// The most components `--random` asks for: `random_board` places them in O(COUNT^2) time.
const MAX_RANDOM_COUNT: usize = 100_000;

/// `SEED,U,COUNT` of `--random` ([`RandomBoard::parse`]), COUNT at most [`MAX_RANDOM_COUNT`].
fn parse_random(raw: &str) -> Result<RandomBoard, String> {
    let random = RandomBoard::parse(raw)?;
    if random.count > MAX_RANDOM_COUNT {
        return Err(format!(
            "COUNT {}: at most {MAX_RANDOM_COUNT} (placing components takes time quadratic in \
             the count)",
            random.count
        ));
    }
    Ok(random)
}

/// An output prefix whose folder exists, checked before any work.
fn check_prefix(prefix: &str) -> Result<String, String> {
    if prefix.is_empty() {
        return Err("the prefix is empty".into());
    }
    let parent = Path::new(prefix).parent().unwrap_or(Path::new(""));
    limits::check_folder(parent)?;
    Ok(prefix.to_string())
}

impl MeshArgs {
    /// The mesher's options these arguments set.
    fn options(&self) -> MeshOptions {
        let mut options = MeshOptions::new().mode(match self.mode {
            ModeArg::Book => Mode::Book,
            ModeArg::Coarsest => Mode::Coarsest,
        });
        if let Some(unit) = self.unit {
            options = options.grid_unit(unit);
        }
        if let Some(size) = self.near {
            options = options.near_size(size);
        }
        if let Some(size) = self.max {
            options = options.max_size(size);
        }
        if let Some(limit) = self.max_triangles {
            options = options.max_triangles(limit);
        }
        options
    }
}

fn read_board(args: &MeshArgs) -> Result<(Board, String), Failure> {
    if let Some(random) = args.random {
        return random.draw();
    }
    let Some(path) = &args.board else {
        return Ok((sample_board(), "built-in sample board".into()));
    };
    board_file(path, args.size)
}

/// The board in the file at `path` (`mesh` and `heat`), named in errors once, as given on the
/// command line (quoted, cut when long).
pub(crate) fn board_file(path: &str, size: Option<i64>) -> Result<(Board, String), Failure> {
    use orthtree::io::BoardFileError;
    orthtree::io::read_board_file(path, size)
        .map(|b| (b, path.to_string()))
        .map_err(|e| {
            let why = match &e {
                BoardFileError::Io { error, .. } => error.to_string(),
                BoardFileError::Board { error, .. } => error.to_string(),
                // the others name the path themselves
                _ => return Failure::Input(e.to_string()),
            };
            Failure::Input(format!("{}: {why}", shown(path)))
        })
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

/// Runs `orthtree mesh`.
pub fn run(args: &MeshArgs) -> Result<(), Failure> {
    if let (Some(size), None, None) = (args.size, &args.board, args.random) {
        return Err(Failure::Usage(format!(
            "--size {size} needs a board file (the built-in board has its own size)"
        )));
    }
    let options = args.options();
    let (board, name) = read_board(args)?;
    let phase = Phase::start("meshing the board");
    let out = options
        .generate(&board)
        .map_err(|e| Failure::Input(format!("{name}: {e}")))?;
    drop(phase);
    let phase = Phase::start("validating the mesh");
    let start = Instant::now();
    let report = out.mesh.validate(&board);
    let validate_time = start.elapsed();
    drop(phase);
    let start = Instant::now();
    let written = if args.no_files {
        Vec::new()
    } else {
        let _phase = Phase::start("writing the files");
        write_all(&out.mesh, &board, &args.out, !args.no_svg)
            .map_err(|e| Failure::Input(format!("writing {}.*: {e}", args.out)))?
    };
    let write_time = start.elapsed();
    let [lo, hi] = report.angle_range_deg.unwrap_or([f64::NAN; 2]);
    say!(
        "board:       {name}: U = {}, {} components, perimeter {}",
        board.size(),
        board.components().len(),
        board.perimeter_steps()
    );
    say!(
        "quadtree:    {:?} mode, grid unit {}, {} leaves, {} after 2:1 balance",
        options.current_mode(),
        out.grid_unit,
        out.leaves_before_balance,
        out.tree.leaf_count()
    );
    say!(
        "mesh:        {} triangles, {} vertices, angles {lo:.1} to {hi:.1} degrees",
        out.mesh.triangles.len(),
        out.mesh.vertices.len()
    );
    say!(
        "validation:  {}",
        if report.is_ok() {
            "ok (conforming, respects input, 45-90 degrees, regions, Euler, Delaunay)".to_string()
        } else {
            report.to_string()
        }
    );
    say!(
        "memory:      {:.1} bytes per triangle",
        out.mesh.heap_bytes() as f64 / out.mesh.triangles.len().max(1) as f64
    );
    say!(
        "time:        build {}, balance {}, triangulate {}, validate {}, write {}",
        ms(out.build_time),
        ms(out.balance_time),
        ms(out.triangulate_time),
        ms(validate_time),
        ms(write_time)
    );
    if written.is_empty() {
        say!("wrote:       nothing (--no-files)");
    } else {
        say!("wrote:       {}", written.join(" "));
    }
    if report.is_ok() {
        Ok(())
    } else {
        Err(Failure::Input(format!(
            "{name}: the mesh fails validation: {report}"
        )))
    }
}
