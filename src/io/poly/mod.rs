//! Boards in Triangle's `.poly` format
//! (<https://www.cs.cmu.edu/~quake/triangle.poly.html>): [`read_poly`] and [`write_poly`].
//!
//! What [`read_poly`] reads, record by record (one record a line, `#` starting a comment, blank
//! lines skipped; lines, encodings and fields as in the crate's board readers: a UTF-8
//! byte-order mark is skipped, lines end at `\n`, `\r\n` or `\r`, fields are separated by spaces
//! and tabs):
//!
//! 1. `<#vertices> [<dimension, 2>] [<#attributes>] [<#boundary markers, 0 or 1>]`. The vertex
//!    count must be positive (vertices kept in a separate `.node` file are not supported).
//! 2. One line per vertex: `<id> <x> <y>`, then exactly as many attributes (numbers) and boundary
//!    markers (integers) as the header declares. Ids run consecutively from the first one, which
//!    must be 0 or 1 (as in Triangle, it sets the numbering of the whole file). Coordinates must
//!    be integers (`3` or `3.0`; `3.5`, `1e3` or `abc` are refused, naming the line). Attributes
//!    and markers are checked but not used: the mesh carries no per-vertex data.
//! 3. `<#segments> [<#boundary markers, 0 or 1>]`, then one line per segment:
//!    `<id> <v1> <v2> [marker]`, the endpoints vertex ids. A segment id must be an integer but is
//!    otherwise free (as in Triangle: segments are numbered by their order).
//! 4. Optionally `<#holes>`, which must be 0: holes are not supported yet (each loop of segments is
//!    a solid component, so the area of a hole would be meshed as part of the component around
//!    it), and a positive count is refused with [`BoardError::HolesNotSupported`].
//! 5. Optionally `<#regional attributes>`, which must be 0 (the regions of the mesh are its
//!    components): a positive count is refused with [`BoardError::RegionsNotSupported`].
//!
//! Nothing else may follow, and no line may hold more fields than its record has: every item of
//! the file is used or refused. A count that does not match the lines that follow is blamed on
//! the count's line: a section that ends early ("the vertex count is 5, but only 4 vertex lines
//! follow") or a line after it that continues the section's numbering.
//!
//! The segments must form closed loops, each vertex joining exactly two segments; a vertex on no
//! segment is refused ([`BoardError::UnusedVertex`]). Each loop is one component. Components are
//! numbered from 1 in the order of each loop's first segment in the file, and each runs from that
//! segment's first vertex in its direction, so edge k of a component is the k-th segment met along
//! the loop and the errors of [`Board::new`] name the segment's line.
//!
//! The board's side U: a comment line `# size U` (alone on its line, U an integer) gives it; a
//! comment whose text starts with the word `size` in any other form (`# size: 32`,
//! `# size 32 please`, a `# size U` after data on the same line) is refused rather than read as
//! an ordinary comment. The caller's `size`, when given too, must be the same
//! ([`BoardError::SizeMismatch`]); a size that is not a power of two from 1 to 2^30 is refused
//! wherever it comes from. Given by neither, U is the smallest power of two at least the largest
//! coordinate (at least 1, at most 2^30).
//!
//! Memory is bounded by the data: no count in the file reserves anything before the lines it
//! counts are read.
//!
//! ```
//! use orthtree::io::poly::{read_poly, write_poly};
//! use orthtree::mesh::BoardError;
//! let text = "\
//! ## size 16
//! 4 2 0 0          # four vertices
//! 1 1 14
//! 2 2 14
//! 3 2 15
//! 4 1 15
//! 4 0              # four segments: one loop
//! 1 1 2
//! 2 2 3
//! 3 3 4
//! 4 4 1
//! 0                # no holes
//! ";
//! let board = read_poly(text, None).unwrap();
//! assert_eq!(board.size(), 16);
//! assert_eq!(board.components()[0].outline, vec![[1, 14], [2, 14], [2, 15], [1, 15]]);
//! assert_eq!(board.components()[0].lines[0], Some(8));
//! assert_eq!(read_poly(&write_poly(&board).unwrap(), None).unwrap().components()[0].outline,
//!            board.components()[0].outline);
//!
//! // the caller's size must agree with the file's
//! assert_eq!(
//!     read_poly(text, Some(32)).unwrap_err(),
//!     BoardError::SizeMismatch { file: 16, line: 1, caller: 32 }
//! );
//! // a hole is refused, naming its line
//! let holed = text.replace("0                # no holes", "1\n1 1 1");
//! assert_eq!(
//!     read_poly(&holed, None).unwrap_err(),
//!     BoardError::HolesNotSupported { line: 12, count: 1 }
//! );
//! ```

mod records;
mod sections;

use super::board_syntax::{board_comment, resolve_size};
use crate::mesh::{Board, BoardError, Component, Point};
use core::fmt::Write;
use records::Records;
use sections::{read_holes_and_regions, read_segments, read_vertices, Segments};

/// Reads a board from the text of a `.poly` file (see the module doc); `size` is the caller's
/// choice of U, which must agree with a `# size U` line in the file.
///
/// # Errors
///
/// As [`read_poly_bytes`].
///
/// # Complexity
///
/// O(n + E log E) time and O(n) memory for n bytes of text and E segments.
pub fn read_poly(text: &str, size: Option<i64>) -> Result<Board, BoardError> {
    read_poly_bytes(text.as_bytes(), size)
}

/// Reads a board from the bytes of a `.poly` file (see the module doc); `size` is the caller's
/// choice of U, which must agree with a `# size U` line in the file.
///
/// # Errors
///
/// - [`BoardError::InvalidUtf8`] naming the line and byte offset of bytes that are not UTF-8;
/// - [`BoardError::Parse`] naming the line for text that is not a `.poly` file as described (the
///   message quotes the field at fault, escaped and cut short), for a count that does not match
///   its section (on the count's line), for a segment endpoint that is no vertex and for a vertex
///   joining more than two segments;
/// - [`BoardError::HolesNotSupported`], [`BoardError::RegionsNotSupported`] for a positive hole or
///   regional attribute count, [`BoardError::UnusedVertex`] for a vertex on no segment,
///   [`BoardError::OpenLoop`] for segments that do not close into a loop;
/// - [`BoardError::SizeNotPowerOfTwo`] for an invalid `size`, [`BoardError::SizeMismatch`] when it
///   differs from the file's;
/// - otherwise any error of [`Board::new`].
///
/// # Complexity
///
/// O(n + E log E) time and O(n) memory for n bytes and E segments, whatever the counts claim.
pub fn read_poly_bytes(bytes: &[u8], size: Option<i64>) -> Result<Board, BoardError> {
    let mut records = Records::new(bytes);
    let vertices = read_vertices(&mut records)?;
    let segments = read_segments(&mut records, &vertices)?;
    read_holes_and_regions(&mut records, &segments)?;
    if let Some(v) = segments.degree.iter().position(|&degree| degree == 0) {
        return Err(BoardError::UnusedVertex {
            vertex: vertices.base + v as i64,
            line: vertices.lines[v],
        });
    }
    let components = loops(&vertices.points, &segments)?;
    let size = resolve_size(records.size(), size, &components)?;
    Board::new(size, components)
}

/// The loops of the segments, in the order of their first segment (see the module doc).
fn loops(points: &[Point], segments: &Segments) -> Result<Vec<Component>, BoardError> {
    let ends = &segments.ends;
    let mut used = vec![false; ends.len()];
    let mut components = Vec::new();
    for first in 0..ends.len() {
        if used[first] {
            continue;
        }
        used[first] = true;
        let (start, mut vertex, first_line) = ends[first];
        let mut outline = vec![points[start]];
        let mut lines = vec![Some(first_line)];
        let mut previous = first;
        while vertex != start {
            outline.push(points[vertex]);
            let other = segments.at[vertex]
                .iter()
                .copied()
                .find(|&s| s != previous && s != usize::MAX && !used[s]);
            let Some(s) = other else {
                return Err(BoardError::OpenLoop {
                    component: components.len() + 1,
                    line: Some(ends[previous].2),
                });
            };
            used[s] = true;
            let (a, b, line) = ends[s];
            vertex = if a == vertex { b } else { a };
            lines.push(Some(line));
            previous = s;
        }
        components.push(Component { outline, lines });
    }
    Ok(components)
}

/// Why a board cannot be written as a `.poly` file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum PolyWriteError {
    /// The board has no components, so no vertices: a `.poly` file needs at least one (a
    /// vertex count of 0 means, in Triangle's format, that the vertices are in a separate
    /// `.node` file), and [`read_poly`] refuses one without.
    NoVertices {
        /// The board's side.
        size: i64,
    },
}

impl core::fmt::Display for PolyWriteError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            PolyWriteError::NoVertices { size } => write!(
                f,
                "the board of side {size} has no components, so no vertices: a .poly file \
                 needs at least one (a vertex count of 0 means a separate .node file)"
            ),
        }
    }
}

impl std::error::Error for PolyWriteError {}

/// Writes a board as a `.poly` file that [`read_poly`] reads back: a `# size U` line, vertices
/// numbered from 1 component by component, one segment per edge in outline order, no holes.
///
/// ```
/// use orthtree::io::poly::{write_poly, PolyWriteError};
/// use orthtree::mesh::Board;
/// let empty = Board::new(16, vec![]).unwrap();
/// assert_eq!(write_poly(&empty), Err(PolyWriteError::NoVertices { size: 16 }));
/// ```
///
/// # Errors
///
/// [`PolyWriteError::NoVertices`] for a board without components, which the format cannot
/// hold (every board with a component is written).
pub fn write_poly(board: &Board) -> Result<String, PolyWriteError> {
    let components = board.components();
    let vertex_count: usize = components.iter().map(|c| c.outline.len()).sum();
    if vertex_count == 0 {
        return Err(PolyWriteError::NoVertices { size: board.size() });
    }
    let mut out = board_comment(board);
    out.reserve(24 * vertex_count + 24);
    let _ = writeln!(out, "# size {}", board.size());
    let _ = writeln!(out, "{vertex_count} 2 0 0");
    let mut id = 1;
    for c in components {
        for p in &c.outline {
            let _ = writeln!(out, "{id} {} {}", p[0], p[1]);
            id += 1;
        }
    }
    let _ = writeln!(out, "{vertex_count} 0");
    let mut first = 1;
    for c in components {
        let n = c.outline.len();
        for k in 0..n {
            let _ = writeln!(out, "{} {} {}", first + k, first + k, first + (k + 1) % n);
        }
        first += n;
    }
    out.push_str("0\n");
    Ok(out)
}
