//! Readers and writers at the edge of the crate: nothing in the trees depends on them.
//!
//! - [`svg`]: SVG pictures of 2D trees (cells, refinements, points), y axis up, written as
//!   plain strings with no dependencies; [`mesh_svg`] draws a mesh on its board.
//! - [`triangle`]: a mesh as Triangle's `.node`, `.ele` and `.edge` files.
//! - [`gmsh`]: a mesh as a Gmsh MSH 4.1 ASCII file with physical groups.
//! - [`vtk`]: a mesh as a legacy VTK ASCII unstructured grid with a `region` cell array.
//! - [`poly`]: a board for the mesher in Triangle's `.poly` format (read and write).
//! - [`pbm`]: 2D region trees as PBM bitmaps (P1 and P4); `png` (behind the `png`
//!   feature) the same as PNG; [`svg::image_tree_svg`] draws a region tree's leaves.
//! - [`board_text`]: a board for the mesher as plain text, one component per line (read and
//!   write); [`read_board_file`] reads either format from a file, [`BoardFormat`] from bytes or
//!   any reader.
//! - `saved` (behind the `saved` feature): a point tree in a compact, versioned binary format,
//!   read back without a rebuild.
//! - [`ply`] and [`xyz`]: point clouds ([`crate::cloud::Cloud`]) as PLY (ASCII and binary)
//!   and as XYZ/CSV text, read and written with their attributes; `las` (behind the `las`
//!   feature; LAZ with `laz`) as ASPRS LAS with integer coordinates kept.
//! - `serialize` (behind the `serde` feature, private): `Serialize` and `Deserialize` for boxes,
//!   cells, the arena, every point tree (plain, dynamic, compressed, skip), region trees, the
//!   mesher's board, mesh and options, planar subdivisions and their locators, tori, metrics
//!   and balance options, each checked on the way in.

mod board_file;
mod board_syntax;
pub mod board_text;
mod columns;
pub mod gmsh;
#[cfg(feature = "las")]
pub mod las;
mod limits;
pub mod pbm;
pub mod ply;
#[cfg(feature = "png")]
pub mod png;
pub mod poly;
#[cfg(feature = "saved")]
pub mod saved;
#[cfg(feature = "serde")]
mod serialize;
pub mod svg;
mod text_out;
pub mod triangle;
pub mod vtk;
pub mod xyz;

/// Reads into `buf` until it is full or the input ends (retrying an interrupted read); the bytes
/// read.
fn read_full(reader: &mut impl std::io::Read, buf: &mut [u8]) -> std::io::Result<usize> {
    let mut got = 0;
    while got < buf.len() {
        match reader.read(&mut buf[got..]) {
            Ok(0) => break,
            Ok(n) => got += n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(got)
}

/// Creates the file at `path` and writes it through a buffer with `write`, then flushes it.
fn write_file(
    path: impl AsRef<std::path::Path>,
    write: impl FnOnce(&mut std::io::BufWriter<std::fs::File>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    write(&mut out)?;
    std::io::Write::flush(&mut out)
}

pub use board_file::{
    read_board_file, read_board_file_with_limit, BoardFileError, BoardFormat, BoardReadError,
    MAX_BOARD_FILE_BYTES,
};
pub use limits::{LimitError, Limits};
pub use svg::{mesh_svg, point_tree_svg, write_mesh_svg, write_mesh_svg_to, Style, Svg};
