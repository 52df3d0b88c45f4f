//! Boards in Triangle's `.poly` format
//! (<https://www.cs.cmu.edu/~quake/triangle.poly.html>): [`read_poly`] and [`write_poly`].
//!
//! What [`read_poly`] reads, record by record (one record a line):
//!
//! 1. `<#vertices> [<dimension, 2>] [<#attributes>] [<#boundary markers, 0 or 1>]`. The vertex
//!    count must be positive (vertices kept in a separate `.node` file are not supported).
//! 2. One line per vertex: `<id> <x> <y> [attributes] [marker]`. Ids run consecutively from the
//!    first one, which must be 0 or 1 (as in Triangle, it sets the numbering of the whole file).
//!    Coordinates must be integers (`3` or `3.0`; `3.5`, `1e3` or `abc` are refused, naming the
//!    line). Attributes and markers are ignored.
//! 3. `<#segments> [<#boundary markers>]`, then one line per segment: `<id> <v1> <v2> [marker]`.
//! 4. Anything after the segments (holes, regional attributes) is ignored.
//!
//! `#` starts a comment anywhere on a line, and blank lines are ignored. The segments must form
//! closed loops, each vertex joining exactly two segments (vertices on no segment are ignored);
//! each loop is one component. Components are numbered from 1 in the order of each loop's first
//! segment in the file, and each runs from that segment's first vertex in its direction, so edge k
//! of a component is the k-th segment met along the loop and the errors of [`Board::new`] name the
//! segment's line.
//!
//! The board's side U is taken from a whole-line comment `# size U` if there is one, else from the
//! `size` argument, else it is the smallest power of two at least the largest coordinate (at least
//! 1, at most 2^30).
//!
//! ```
//! use orthtree::io::poly::{read_poly, write_poly};
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
//! assert_eq!(read_poly(&write_poly(&board), None).unwrap().components()[0].outline,
//!            board.components()[0].outline);
//! ```

use crate::mesh::{Board, BoardError, Component, Point};
use core::fmt::Write;
use core::num::IntErrorKind;

/// Reads a board from the text of a `.poly` file (see the module doc); `size` is the caller's
/// choice of U, used when the file has no `# size U` line.
///
/// Errors: [`BoardError::Parse`] naming the line for text that is not a `.poly` file as described,
/// for a segment endpoint that is no vertex, and for a vertex joining more than two segments;
/// [`BoardError::OpenLoop`] for segments that do not close into a loop; otherwise any error of
/// [`Board::new`].
///
/// Complexity: O(n + E log E) for n input lines and E segments.
pub fn read_poly(text: &str, size: Option<i64>) -> Result<Board, BoardError> {
    let mut data: Vec<(usize, &str)> = Vec::new();
    let mut size_line: Option<(i64, usize)> = None;
    let mut last_line = 1;
    for (i, raw) in text.lines().enumerate() {
        let number = i + 1;
        last_line = number;
        let (content, comment) = match raw.split_once('#') {
            Some((content, comment)) => (content, Some(comment)),
            None => (raw, None),
        };
        if !content.trim().is_empty() {
            data.push((number, content));
        } else if let Some(u) = comment.and_then(size_directive) {
            match size_line {
                Some((v, first)) if v != u => {
                    return Err(BoardError::Parse {
                        line: number,
                        message: format!("size {u} contradicts size {v} given on line {first}"),
                    })
                }
                Some(_) => {}
                None => size_line = Some((u, number)),
            }
        }
    }
    let mut records = data
        .iter()
        .map(|&(number, content)| (number, content.split_whitespace().collect::<Vec<_>>()));
    let mut next = |what: &str| {
        records.next().ok_or_else(|| BoardError::Parse {
            line: last_line,
            message: format!("unexpected end of input: expected {what}"),
        })
    };

    // 1. The vertex header.
    let (line, header) = next("the vertex count line `<#vertices> 2 <#attributes> <#markers>`")?;
    let vertex_count = parse_count(header[0], line, "vertex count")?;
    if vertex_count == 0 {
        return Err(parse_error(
            line,
            "vertex count 0: vertices in a separate .node file are not supported",
        ));
    }
    if let Some(dim) = header.get(1) {
        if *dim != "2" {
            return Err(parse_error(
                line,
                format!("dimension `{dim}`: only 2 is supported"),
            ));
        }
    }
    if let Some(attributes) = header.get(2) {
        parse_count(attributes, line, "attribute count")?;
    }
    if let Some(markers) = header.get(3) {
        if *markers != "0" && *markers != "1" {
            return Err(parse_error(
                line,
                format!("boundary marker count `{markers}`: expected 0 or 1"),
            ));
        }
    }

    // 2. The vertices.
    let mut points: Vec<Point> = Vec::with_capacity(vertex_count.min(data.len()));
    let mut base = 0i64;
    for i in 0..vertex_count {
        let (line, fields) = next(&format!("vertex {} of {vertex_count}", i + 1))?;
        if fields.len() < 3 {
            return Err(parse_error(
                line,
                "a vertex line needs an id and two coordinates: `<id> <x> <y>`",
            ));
        }
        let id = parse_id(fields[0], line, "vertex id")?;
        if i == 0 {
            if id != 0 && id != 1 {
                return Err(parse_error(
                    line,
                    format!("the first vertex id is {id}: it must be 0 or 1"),
                ));
            }
            base = id;
        } else if id != base + i as i64 {
            return Err(parse_error(
                line,
                format!(
                    "vertex id {id} is out of sequence: expected {}",
                    base + i as i64
                ),
            ));
        }
        let x = parse_coordinate(fields[1]).map_err(|m| parse_error(line, m))?;
        let y = parse_coordinate(fields[2]).map_err(|m| parse_error(line, m))?;
        points.push([x, y]);
    }

    // 3. The segments.
    let (line, header) = next("the segment count line `<#segments> <#markers>`")?;
    let segment_count = parse_count(header[0], line, "segment count")?;
    if let Some(markers) = header.get(1) {
        if *markers != "0" && *markers != "1" {
            return Err(parse_error(
                line,
                format!("boundary marker count `{markers}`: expected 0 or 1"),
            ));
        }
    }
    // (first vertex, second vertex, line), vertices from 0
    let mut segments: Vec<(usize, usize, usize)> =
        Vec::with_capacity(segment_count.min(data.len()));
    // Up to two segments at each vertex.
    let mut at: Vec<[usize; 2]> = vec![[usize::MAX; 2]; points.len()];
    let mut degree: Vec<u8> = vec![0; points.len()];
    for s in 0..segment_count {
        let (line, fields) = next(&format!("segment {} of {segment_count}", s + 1))?;
        if fields.len() < 3 {
            return Err(parse_error(
                line,
                "a segment line needs an id and two vertex ids: `<id> <v1> <v2>`",
            ));
        }
        let mut ends = [0usize; 2];
        for (end, field) in ends.iter_mut().zip(&fields[1..3]) {
            let v = parse_id(field, line, "segment endpoint")?;
            *end = v
                .checked_sub(base)
                .and_then(|i| usize::try_from(i).ok())
                .filter(|&i| i < points.len())
                .ok_or_else(|| {
                    parse_error(
                        line,
                        format!(
                            "segment endpoint {v} is not a vertex id (ids run from {base} to {})",
                            base + points.len() as i64 - 1
                        ),
                    )
                })?;
        }
        for &v in &ends {
            if degree[v] == 2 {
                return Err(parse_error(
                    line,
                    format!(
                        "vertex {} is the end of a third segment; each vertex must join \
                         exactly two segments of one loop",
                        v as i64 + base
                    ),
                ));
            }
            at[v][degree[v] as usize] = s;
            degree[v] += 1;
        }
        segments.push((ends[0], ends[1], line));
    }

    // Loops, in the order of their first segment.
    let mut used = vec![false; segments.len()];
    let mut components = Vec::new();
    for first in 0..segments.len() {
        if used[first] {
            continue;
        }
        used[first] = true;
        let (start, mut vertex, first_line) = segments[first];
        let mut outline = vec![points[start]];
        let mut lines = vec![Some(first_line)];
        let mut previous = first;
        while vertex != start {
            outline.push(points[vertex]);
            let other = at[vertex]
                .iter()
                .copied()
                .find(|&s| s != previous && s != usize::MAX && !used[s]);
            let Some(s) = other else {
                return Err(BoardError::OpenLoop {
                    component: components.len() + 1,
                    line: Some(segments[previous].2),
                });
            };
            used[s] = true;
            let (a, b, line) = segments[s];
            vertex = if a == vertex { b } else { a };
            lines.push(Some(line));
            previous = s;
        }
        components.push(Component { outline, lines });
    }

    let size = board_size(size_line.map(|(u, _)| u), size, &components);
    Board::new(size, components)
}

/// Writes a board as a `.poly` file that [`read_poly`] reads back: a `# size U` line, vertices
/// numbered from 1 component by component, one segment per edge in outline order, no holes.
pub fn write_poly(board: &Board) -> String {
    let components = board.components();
    let vertex_count: usize = components.iter().map(|c| c.outline.len()).sum();
    let mut out = String::with_capacity(24 * vertex_count + 64);
    let _ = writeln!(
        out,
        "# orthtree board: side {}, {} components",
        board.size(),
        components.len()
    );
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
    out
}

/// `Some(U)` for a comment (the text after `#`) that reads `size U` with an integer U.
fn size_directive(comment: &str) -> Option<i64> {
    let mut fields = comment.split_whitespace();
    let (keyword, value) = (fields.next()?, fields.next()?);
    if fields.next().is_some() || !keyword.eq_ignore_ascii_case("size") {
        return None;
    }
    value.parse().ok()
}

fn parse_error(line: usize, message: impl Into<String>) -> BoardError {
    BoardError::Parse {
        line,
        message: message.into(),
    }
}

fn parse_count(field: &str, line: usize, what: &str) -> Result<usize, BoardError> {
    field.parse().map_err(|_| {
        parse_error(
            line,
            format!("{what} `{field}` is not a non-negative integer"),
        )
    })
}

fn parse_id(field: &str, line: usize, what: &str) -> Result<i64, BoardError> {
    field
        .parse()
        .map_err(|_| parse_error(line, format!("{what} `{field}` is not an integer")))
}

/// Parses an integer coordinate: decimal digits with an optional sign, optionally followed by a
/// point and zeros (`3`, `-2`, `3.0`, `3.`). The error is a message naming the field.
pub(crate) fn parse_coordinate(field: &str) -> Result<i64, String> {
    let (whole, fraction) = match field.split_once('.') {
        Some((whole, fraction)) => (whole, fraction),
        None => (field, ""),
    };
    let whole_ok = whole
        .strip_prefix(['+', '-'])
        .unwrap_or(whole)
        .bytes()
        .all(|b| b.is_ascii_digit());
    if !fraction.bytes().all(|b| b == b'0') || !whole_ok || whole.is_empty() {
        return Err(if field.parse::<f64>().is_ok() {
            format!("coordinate `{field}` is not an integer")
        } else {
            format!("coordinate `{field}` is not a number")
        });
    }
    whole
        .parse()
        .map_err(|e: core::num::ParseIntError| match e.kind() {
            IntErrorKind::PosOverflow | IntErrorKind::NegOverflow => {
                format!("coordinate `{field}` is out of range")
            }
            _ => format!("coordinate `{field}` is not a number"),
        })
}

/// U for a board read from a file: the file's own size line, else the caller's, else the smallest
/// power of two at least the largest coordinate (at least 1, at most 2^30: larger coordinates are
/// then reported as out of range).
pub(crate) fn board_size(file: Option<i64>, caller: Option<i64>, components: &[Component]) -> i64 {
    file.or(caller).unwrap_or_else(|| {
        let largest = components
            .iter()
            .flat_map(|c| c.outline.iter().flatten())
            .copied()
            .max()
            .unwrap_or(1)
            .clamp(1, 1 << 30);
        (largest as u64).next_power_of_two() as i64
    })
}
