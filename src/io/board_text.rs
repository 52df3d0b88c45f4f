//! Boards as plain text, one component per line: [`read_board_text`] and [`write_board_text`].
//!
//! The format:
//!
//! ```text
//! # A board of side 16 with two components.
//! size 16
//! 1 14  2 14  2 15  1 15      # a unit square: x y pairs
//! (4, 4) (8, 4) (8, 8)        # a triangle: parentheses and commas are optional
//! ```
//!
//! - `#` starts a comment, anywhere on a line; blank lines are skipped. A UTF-8 byte-order mark
//!   at the start is skipped, lines end at `\n`, `\r\n` or `\r`, and the text must be UTF-8.
//! - `size U` (at most once, anywhere) gives the board's side U, a power of two from 1 to 2^30.
//!   The caller's `size`, when given too, must be the same (else
//!   [`BoardError::SizeMismatch`]); a size that is not a power of two from 1 to 2^30 is refused
//!   wherever it comes from. Given by neither, U is the smallest power of two at least the
//!   largest coordinate (at least 1, at most 2^30).
//! - Every other line is one component: its vertices in order, as integer `x y` pairs (`3.0` is
//!   read as 3; `3.5` is refused). Spaces, tabs, `(`, `)` and `,` separate fields; any other
//!   byte belongs to a field, so `3\u{a0}4` is one field and refused (messages show such
//!   characters escaped, and cut a long field short). The outline closes by itself,
//!   from the last vertex back to the first; a last vertex equal to the first is dropped. Either
//!   orientation is accepted, and vertices between collinear edges are allowed (both are
//!   normalised away).
//! - Component i is the i-th component line, numbered from 1, and edge k runs from its k-th
//!   vertex to the next; errors name both and the line.
//!
//! The rules on the components themselves are those of [`Board::new`]: vertices in [0, U]^2,
//! edges at 0, 45, 90 or 135 degrees, simple outlines, no two components touching and none inside
//! another.
//!
//! ```
//! use orthtree::io::board_text::{read_board_text, write_board_text};
//! let board = read_board_text("size 16\n1 14  2 14  2 15  1 15\n(4, 4) (8, 4) (8, 8)\n", None)
//!     .unwrap();
//! assert_eq!(board.size(), 16);
//! assert_eq!(board.components().len(), 2);
//! assert_eq!(board.components()[1].outline, vec![[4, 4], [8, 4], [8, 8]]);
//! assert_eq!(board.components()[1].lines, vec![Some(3); 3]);
//! let text = write_board_text(&board);
//! assert_eq!(write_board_text(&read_board_text(&text, None).unwrap()), text);
//!
//! let err = read_board_text("0 0  4 0  7 5\n", Some(8)).unwrap_err();
//! assert_eq!(
//!     err.to_string(),
//!     "component 1, edge 2 (line 1): edge (4, 0)-(7, 5) is not at 0, 45, 90 or 135 degrees"
//! );
//! ```

use super::board_syntax::{
    board_comment, parse_coordinate, parse_error, resolve_size, Lines, Quoted,
};
use crate::mesh::{Board, BoardError, Component, Point};
use core::fmt::Write;

/// Reads a board in the text format of the module doc; `size` is the caller's choice of U, which
/// must agree with a `size` line in the text.
///
/// # Errors
///
/// As [`read_board_text_bytes`].
///
/// # Complexity
///
/// O(n + E log E) time and O(n) memory for n bytes of text and E edges.
pub fn read_board_text(text: &str, size: Option<i64>) -> Result<Board, BoardError> {
    read_board_text_bytes(text.as_bytes(), size)
}

/// Reads a board in the text format of the module doc from bytes; `size` is the caller's choice
/// of U, which must agree with a `size` line in the text.
///
/// # Errors
///
/// - [`BoardError::InvalidUtf8`] naming the line and byte offset of bytes that are not UTF-8;
/// - [`BoardError::Parse`] naming the line for a field that is not an integer (quoted, escaped
///   and cut short), an odd number of coordinates, a line of only separators, or a bad, invalid
///   or repeated `size` line;
/// - [`BoardError::SizeNotPowerOfTwo`] for an invalid `size`, [`BoardError::SizeMismatch`] when it
///   differs from the text's;
/// - otherwise any error of [`Board::new`], naming the component's line.
///
/// # Complexity
///
/// O(n + E log E) time and O(n) memory for n bytes and E edges.
pub fn read_board_text_bytes(bytes: &[u8], size: Option<i64>) -> Result<Board, BoardError> {
    let mut size_line: Option<(i64, usize)> = None;
    let mut components = Vec::new();
    for line in Lines::new(bytes) {
        let line = line?;
        let number = line.number;
        let mut fields = line
            .content
            .split([' ', '\t', '(', ')', ','])
            .filter(|f| !f.is_empty());
        let Some(first) = fields.next() else {
            if line.content.contains(['(', ')', ',']) {
                return Err(parse_error(
                    number,
                    "a line of only `(`, `)` and `,` holds no coordinates",
                ));
            }
            continue;
        };
        if first.eq_ignore_ascii_case("size") {
            let u = match (fields.next(), fields.next()) {
                (Some(value), None) => value.parse::<i64>().ok(),
                _ => None,
            }
            .ok_or_else(|| {
                parse_error(
                    number,
                    format!(
                        "expected `size U` with an integer U, found {}",
                        Quoted(line.content.trim())
                    ),
                )
            })?;
            if let Some((_, earlier)) = size_line {
                return Err(parse_error(
                    number,
                    format!("a second size line (the first is line {earlier})"),
                ));
            }
            size_line = Some((u, number));
            continue;
        }
        let mut outline: Vec<Point> = Vec::new();
        let mut fields = core::iter::once(first).chain(fields);
        while let Some(x) = fields.next() {
            let Some(y) = fields.next() else {
                return Err(parse_error(
                    number,
                    format!(
                        "{} coordinates: a component is a list of x y pairs",
                        2 * outline.len() + 1
                    ),
                ));
            };
            let x = parse_coordinate(x).map_err(|m| parse_error(number, m))?;
            let y = parse_coordinate(y).map_err(|m| parse_error(number, m))?;
            outline.push([x, y]);
        }
        if outline.len() > 1 && outline.first() == outline.last() {
            outline.pop();
        }
        let lines = vec![Some(number); outline.len()];
        components.push(Component { outline, lines });
    }
    let size = resolve_size(size_line, size, &components)?;
    Board::new(size, components)
}

/// Writes a board in the text format of the module doc (a `size` line, then one line per
/// component); [`read_board_text`] reads it back to the same board.
pub fn write_board_text(board: &Board) -> String {
    let mut out = board_comment(board);
    let _ = writeln!(out, "size {}", board.size());
    for c in board.components() {
        for (i, p) in c.outline.iter().enumerate() {
            let sep = if i == 0 { "" } else { "  " };
            let _ = write!(out, "{sep}{} {}", p[0], p[1]);
        }
        out.push('\n');
    }
    out
}
