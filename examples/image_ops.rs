//! Boolean operations on binary images with region quadtrees.
//!
//! ```sh
//! cargo run --release --example image_ops -- A B --op and|or|xor|sub --out C
//! cargo run --release --example image_ops -- A --op not --out C
//! cargo run --release --example image_ops            # built-in disc and ring
//! cargo run --release --example image_ops -- --help
//! ```
//!
//! The output may also be an `.svg` (a picture of the tree's leaves). Every bad argument, file or
//! pair of images of different sizes ends with a message and exit status 1 (2 for usage
//! errors), never a panic.
//!
//! Files are PBM (`.pbm`), or PNG (`.png`) when built with `--features png`, chosen by extension.
//! Prints node counts, pixel counts and times. With no arguments it makes a disc and a ring on a
//! 512 x 384 image, writes their symmetric difference as `image_ops.pbm` (and `image_ops.png`
//! with the feature) and an SVG of its tree as `image_ops.svg` in the current directory.

use orthtree::image::{BoolOp, ImageTree};
use orthtree::io::pbm::{self, PbmFormat};
use orthtree::io::svg::write_image_tree_svg;
use std::error::Error;
use std::path::Path;
use std::time::Instant;

/// `println!` that ignores a closed standard output (a pipe into `head`) instead of panicking.
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout(), $($arg)*);
    }};
}

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

const USAGE: &str = "usage: image_ops A [B] --op and|or|xor|sub|not --out C
       image_ops            (the built-in disc and ring demo)
  A, B   input images: .pbm, or .png when built with --features png
  --op   and, or, xor, sub (two images of one size) or not (one image)
  --out  the result: .pbm, .png (with the feature) or .svg (a picture of the tree)";

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
        "; png with --features png"
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

fn run(args: &[String]) -> Result<(), Box<dyn Error>> {
    let mut files = Vec::new();
    let (mut op, mut out) = (None, None);
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--op" | "--out" => {
                let Some(value) = it.next() else {
                    return Err(Usage(format!("{a} needs a value")).into());
                };
                if a == "--op" {
                    op = Some(value.clone());
                } else {
                    out = Some(value.clone());
                }
            }
            flag if flag.starts_with("--") => {
                return Err(Usage(format!("unknown option {flag}")).into())
            }
            _ => files.push(a.clone()),
        }
    }
    let (Some(op), Some(out), 1..=2) = (op, out, files.len()) else {
        return Err(Usage("give one or two images, --op and --out".into()).into());
    };
    let writable = [
        "pbm",
        "svg",
        if cfg!(feature = "png") { "png" } else { "pbm" },
    ];
    if !writable.contains(&extension(&out).as_str()) {
        return Err(Usage(format!(
            "{out}: unsupported extension {:?} (pbm, svg{})",
            extension(&out),
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
    let result = combine(&trees[0], trees.get(1), &op)?;
    describe("result", &result);
    write(&result, &out)?;
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

/// A mistake in the arguments (exit status 2, with the usage).
#[derive(Debug)]
struct Usage(String);

impl std::fmt::Display for Usage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}\n{USAGE}", self.0)
    }
}

impl Error for Usage {}

fn main() {
    let args: Vec<String> = std::env::args_os()
        .skip(1)
        .map(|a| a.to_string_lossy().into_owned())
        .collect();
    if args.iter().any(|a| a == "--help" || a == "-h") {
        say!("{USAGE}");
        return;
    }
    let outcome = if args.is_empty() { demo() } else { run(&args) };
    if let Err(e) = outcome {
        eprintln!("image_ops: {e}");
        std::process::exit(if e.is::<Usage>() { 2 } else { 1 });
    }
}
