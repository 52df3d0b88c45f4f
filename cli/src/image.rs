//! Boolean operations on binary images with region quadtrees.
//!
//! ```sh
//! orthtree image and|or|xor|sub A B --out C   # or: orthtree image A B --op xor --out C
//! orthtree image not A --out C
//! orthtree image            # built-in disc and ring
//! ```
//!
//! The output may also be an `.svg` (a picture of the tree's leaves). Every bad file or pair of
//! images of different sizes ends with a message and exit code 1 (2 for usage errors), never a
//! panic.
//!
//! Files are PBM (`.pbm`), or PNG (`.png`) when built with `--features png`, chosen by extension.
//! Prints node counts, pixel counts and times. With no arguments it makes a disc and a ring on a
//! 512 x 384 image, writes their symmetric difference as `image_ops.pbm` (and `image_ops.png`
//! with the feature) and an SVG of its tree as `image_ops.svg` in the current directory.

use crate::Failure;
use orthtree::image::{BoolOp, ImageTree};
use orthtree::io::pbm::{self, PbmFormat};
use orthtree::io::svg::write_image_tree_svg;
use std::error::Error;
use std::path::Path;
use std::time::Instant;

fn read(path: &str) -> Result<ImageTree, Box<dyn Error>> {
    match extension(path).as_str() {
        "pbm" => Ok(pbm::read(path).map_err(|e| format!("{path}: {e}"))?),
        #[cfg(feature = "png")]
        "png" => Ok(orthtree::io::png::read(path).map_err(|e| format!("{path}: {e}"))?),
        other => Err(format!(
            "{path}: unsupported extension {other:?} (pbm{})",
            png_hint()
        )
        .into()),
    }
}

/// Boolean operations on binary images with region quadtrees
///
/// `orthtree image xor A B --out C.pbm` (or `orthtree image A B --op xor --out C.pbm`). With no arguments: a built-in disc and ring, their symmetric difference written
/// as image_ops.pbm and image_ops.svg into the current folder.
#[derive(clap::Args, Debug)]
#[command(after_help = crate::EXIT_CODES, allow_negative_numbers = true)]
pub struct ImageArgs {
    /// The operation (unless given by --op), then the input images: .pbm, or .png when built
    /// with the `png` feature
    #[arg(value_name = "[OP] IMAGE", num_args = 0..=3)]
    images: Vec<String>,
    /// and, or, xor, sub (two images of one size) or not (one image)
    #[arg(long, value_enum)]
    op: Option<OpArg>,
    /// The result: .pbm, .png (with the `png` feature) or .svg (a picture of the tree)
    #[arg(long, value_name = "C", value_parser = check_output)]
    out: Option<String>,
}

/// An output path whose folder exists and whose extension names a format this build writes,
/// checked before any work.
fn check_output(raw: &str) -> Result<String, String> {
    crate::limits::output_path(raw)?;
    match extension(raw).as_str() {
        "pbm" | "svg" => Ok(raw.to_string()),
        #[cfg(feature = "png")]
        "png" => Ok(raw.to_string()),
        other => Err(format!(
            "unsupported extension {other:?} (pbm, svg{})",
            png_hint()
        )),
    }
}

/// The operations on the command line.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
enum OpArg {
    And,
    Or,
    Xor,
    Sub,
    Not,
}

impl OpArg {
    fn name(self) -> &'static str {
        match self {
            OpArg::And => "and",
            OpArg::Or => "or",
            OpArg::Xor => "xor",
            OpArg::Sub => "sub",
            OpArg::Not => "not",
        }
    }
}

fn write(tree: &ImageTree, path: &str) -> Result<(), Box<dyn Error>> {
    match extension(path).as_str() {
        "pbm" => Ok(pbm::write(tree, path, PbmFormat::Raw).map_err(|e| format!("{path}: {e}"))?),
        "svg" => {
            let file = std::fs::File::create(path).map_err(|e| format!("{path}: {e}"))?;
            write_image_tree_svg(tree, file).map_err(|e| format!("{path}: {e}"))?;
            Ok(())
        }
        #[cfg(feature = "png")]
        "png" => Ok(
            orthtree::io::png::write(tree, path, orthtree::io::png::PngDepth::One)
                .map_err(|e| format!("{path}: {e}"))?,
        ),
        other => Err(format!(
            "{path}: unsupported extension {other:?} (pbm, svg{})",
            png_hint()
        )
        .into()),
    }
}

fn png_hint() -> &'static str {
    if cfg!(feature = "png") {
        ", png"
    } else {
        "; png with the `png` feature"
    }
}

fn extension(path: &str) -> String {
    Path::new(path)
        .extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .unwrap_or_default()
}

fn describe(name: &str, t: &ImageTree) {
    let [w, h] = t.extent();
    say!(
        "{name:>8}: {w} x {h} (depth {}), {} nodes, {} leaves, {} black pixels",
        t.depth(),
        t.node_count(),
        t.leaf_count(),
        t.len()
    );
}

fn combine(a: &ImageTree, b: Option<&ImageTree>, op: &str) -> Result<ImageTree, Box<dyn Error>> {
    let start = Instant::now();
    let binary = match op {
        "and" => Some(BoolOp::And),
        "or" => Some(BoolOp::Or),
        "xor" => Some(BoolOp::Xor),
        "sub" => Some(BoolOp::Sub),
        "not" => None,
        _ => return Err(Usage(format!("unknown --op {op:?} (and, or, xor, sub, not)")).into()),
    };
    let result = match (binary, b) {
        (None, None) => a.complement(),
        (None, Some(_)) => return Err(Usage("--op not takes one image".into()).into()),
        (Some(_), None) => return Err(Usage(format!("--op {op} needs two images")).into()),
        (Some(op), Some(b)) => a.try_combine(b, op)?,
    };
    say!("{op:>8}: {:.3} ms", start.elapsed().as_secs_f64() * 1e3);
    Ok(result)
}

/// Runs `orthtree image`.
pub fn run(args: &ImageArgs) -> Result<(), Failure> {
    let usage = || {
        Failure::Usage("give an operation (first, or by --op), one or two images and --out".into())
    };
    // The operation as the first word (`orthtree image xor A B`), unless --op names it.
    let (op, images) = match args.images.split_first() {
        Some((first, rest)) if args.op.is_none() => {
            match <OpArg as clap::ValueEnum>::from_str(first, true) {
                Ok(op) => (Some(op), rest),
                Err(_) => (None, &args.images[..]),
            }
        }
        _ => (args.op, &args.images[..]),
    };
    if images.len() > 2 {
        return Err(Failure::Usage(format!(
            "{} images given ({}): an operation takes one or two",
            images.len(),
            images.join(", ")
        )));
    }
    let outcome = match (op, &args.out) {
        (None, None) if images.is_empty() => demo(),
        (Some(op), Some(out)) if !images.is_empty() => apply(images, op, out),
        _ => return Err(usage()),
    };
    outcome.map_err(|e| match e.downcast::<Usage>() {
        Ok(usage) => Failure::Usage(usage.0),
        Err(e) => Failure::Input(e.to_string()),
    })
}

fn apply(files: &[String], op: OpArg, out: &str) -> Result<(), Box<dyn Error>> {
    let writable = [
        "pbm",
        "svg",
        if cfg!(feature = "png") { "png" } else { "pbm" },
    ];
    if !writable.contains(&extension(out).as_str()) {
        return Err(Usage(format!(
            "--out {out}: unsupported extension {:?} (pbm, svg{})",
            extension(out),
            png_hint()
        ))
        .into());
    }
    let start = Instant::now();
    let trees = files
        .iter()
        .map(|f| read(f))
        .collect::<Result<Vec<_>, _>>()?;
    say!("    read: {:.3} ms", start.elapsed().as_secs_f64() * 1e3);
    for (f, t) in files.iter().zip(&trees) {
        describe(f, t);
    }
    let result = combine(&trees[0], trees.get(1), op.name())?;
    describe("result", &result);
    write(&result, out)?;
    say!("wrote {out}");
    Ok(())
}

fn demo() -> Result<(), Box<dyn Error>> {
    let extent = [512, 384];
    let start = Instant::now();
    let disc = ImageTree::from_ball(extent, [200.0, 192.0], 150.0)?;
    let ring = ImageTree::from_ball(extent, [330.0, 180.0], 140.0)?
        - ImageTree::from_ball(extent, [330.0, 180.0], 90.0)?;
    say!("   built: {:.3} ms", start.elapsed().as_secs_f64() * 1e3);
    describe("disc", &disc);
    describe("ring", &ring);
    let result = combine(&disc, Some(&ring), "xor")?;
    describe("result", &result);
    say!(
        "  counts: and {} or {} xor {} sub {} (count-only)",
        disc.intersection_len(&ring),
        disc.union_len(&ring),
        disc.symmetric_difference_len(&ring),
        disc.difference_len(&ring)
    );
    write(&result, "image_ops.pbm")?;
    say!("wrote image_ops.pbm");
    #[cfg(feature = "png")]
    {
        write(&result, "image_ops.png")?;
        say!("wrote image_ops.png");
    }
    write(&result, "image_ops.svg")?;
    say!("wrote image_ops.svg");
    Ok(())
}

/// A mistake in the arguments (exit code 2).
#[derive(Debug)]
struct Usage(String);

impl std::fmt::Display for Usage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl Error for Usage {}
