//! The saved tree of `orthtree cloud index`: built in memory, or out of core within a memory
//! budget (the library's `io::saved::external`), written to the output file.

use super::IndexArgs;
use crate::Failure;
use orthtree::io::saved;
use orthtree::PointTree;

/// Builds the tree of `entries` as `a` asks and writes it to `a.out`.
///
/// # Errors
/// [`Failure::Input`] naming the cloud (points the build refuses) or the file (writing fails).
pub fn write(entries: &[([f64; 3], u32)], a: &IndexArgs, name: &str) -> Result<(), Failure> {
    let fail = |e: &dyn std::fmt::Display| Failure::Input(format!("{}: {e}", a.out.display()));
    let tree = PointTree::builder()
        .bucket_size(a.bucket_size)
        .build(entries)
        .map_err(|e| Failure::Input(format!("{name}: {e}")))?;
    let file = std::fs::File::create(&a.out).map_err(|e| fail(&e))?;
    let mut out = std::io::BufWriter::new(file);
    saved::write_point_tree(&tree, &mut out).map_err(|e| fail(&e))?;
    std::io::Write::flush(&mut out).map_err(|e| fail(&e))
}
