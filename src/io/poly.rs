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
//! assert_eq!(read_poly(&write_poly(&board), None).unwrap().components()[0].outline,
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

use super::board_syntax::{parse_coordinate, parse_error, resolve_size, Line, Lines, Quoted};
use crate::mesh::{Board, BoardError, Component, Point};
use core::fmt::Write;

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
    let mut records = Records {
        lines: Lines::new(bytes),
        size: None,
    };
    let vertices = read_vertices(&mut records)?;
    let segments = read_segments(&mut records, &vertices)?;
    read_holes_and_regions(&mut records, &vertices, &segments)?;
    for (v, &degree) in segments.degree.iter().enumerate() {
        if degree == 0 {
            return Err(BoardError::UnusedVertex {
                vertex: vertices.base + v as i64,
                line: vertices.lines[v],
            });
        }
    }
    let components = loops(&vertices.points, &segments)?;
    let size = resolve_size(records.size, size, &components)?;
    Board::new(size, components)
}

/// The data lines of a `.poly` file, with the `# size U` comments taken out on the way.
struct Records<'a> {
    lines: Lines<'a>,
    /// The size a comment gives, and its line.
    size: Option<(i64, usize)>,
}

impl<'a> Records<'a> {
    /// The next line holding data, checking every comment before it.
    fn next(&mut self) -> Result<Option<Line<'a>>, BoardError> {
        while let Some(line) = self.lines.next() {
            let line = line?;
            if let Some(comment) = line.comment {
                self.size_comment(&line, comment)?;
            }
            if !line.is_blank() {
                return Ok(Some(line));
            }
        }
        Ok(None)
    }

    /// The next data line, or an error on the last line naming what was `expected`.
    fn expect(&mut self, expected: &str) -> Result<Line<'a>, BoardError> {
        self.next()?.ok_or_else(|| {
            parse_error(
                self.lines.last_number().max(1),
                format!("unexpected end of input: expected {expected}"),
            )
        })
    }

    fn size_comment(&mut self, line: &Line<'_>, comment: &str) -> Result<(), BoardError> {
        let Some(u) = size_directive(comment) else {
            return Ok(());
        };
        let u = u.map_err(|m| parse_error(line.number, m))?;
        if !line.is_blank() {
            return Err(parse_error(
                line.number,
                "a `# size U` comment must be on a line of its own, not after data",
            ));
        }
        match self.size {
            Some((v, first)) if v != u => Err(parse_error(
                line.number,
                format!("size {u} contradicts size {v} given on line {first}"),
            )),
            Some(_) => Ok(()),
            None => {
                self.size = Some((u, line.number));
                Ok(())
            }
        }
    }
}

/// `None` for a comment (the text after `#`) that is not about the size; `Some(Ok(U))` for
/// exactly `size U` with an integer U; `Some(Err(message))` for any other comment whose first
/// word is `size` (in any case, followed by anything but a letter).
fn size_directive(comment: &str) -> Option<Result<i64, String>> {
    let text = comment.trim_matches([' ', '\t']);
    let keyword = text.get(..4)?;
    let rest = &text[4..];
    if !keyword.eq_ignore_ascii_case("size") || rest.starts_with(|c: char| c.is_alphabetic()) {
        return None;
    }
    let mut fields = rest.split([' ', '\t']).filter(|f| !f.is_empty());
    let value = match (rest.starts_with([' ', '\t']), fields.next(), fields.next()) {
        (true, Some(value), None) => value.parse::<i64>().ok(),
        _ => None,
    };
    Some(value.ok_or_else(|| {
        format!(
            "a size comment must read `# size U` with an integer U, not {}",
            Quoted(&format!("#{comment}"))
        )
    }))
}

/// The vertex section.
struct Vertices {
    points: Vec<Point>,
    /// The input line of each vertex.
    lines: Vec<usize>,
    /// The first id, 0 or 1.
    base: i64,
    /// The line of the vertex count.
    header_line: usize,
    /// The number of fields of a vertex line.
    fields: usize,
}

/// The segment section: (first vertex, second vertex, line) with vertices from 0, and the
/// segments at each vertex.
struct Segments {
    /// The line of the segment count.
    header_line: usize,
    /// The number of fields of a segment line.
    fields: usize,
    ends: Vec<(usize, usize, usize)>,
    /// Up to two segments at each vertex.
    at: Vec<[usize; 2]>,
    degree: Vec<u8>,
}

/// The error for a count that does not match its section, on the count's line.
fn count_error(line: usize, what: &str, count: usize, detail: String) -> BoardError {
    parse_error(line, format!("the {what} count is {count}, but {detail}"))
}

/// True when `line` has `fields` fields (at least 3) and, if `id` is given, starts with it: a
/// record continuing a section past its count.
fn continues(line: &Line<'_>, fields: usize, id: Option<i64>) -> bool {
    fields >= 3
        && line.fields().count() == fields
        && id.is_none_or(|id| line.fields().next().and_then(|f| f.parse().ok()) == Some(id))
}

/// True when `line` cannot be a record of at least 3 fields, nor, if `id` is given, the record
/// of that id with fields missing: the section ended before its count.
fn ends_section(line: &Line<'_>, id: Option<i64>) -> bool {
    line.fields().nth(2).is_none()
        && id.is_none_or(|id| line.fields().next().and_then(|f| f.parse().ok()) != Some(id))
}

/// The fields after a record's first three must be `numbers` numbers then `integers` integers
/// and nothing more; `wanted` describes the record for the message.
fn check_fields(
    line: &Line<'_>,
    numbers: usize,
    integers: usize,
    wanted: &str,
) -> Result<(), BoardError> {
    let have = line.fields().count();
    let expected = 3usize.saturating_add(numbers).saturating_add(integers);
    if have != expected {
        return Err(parse_error(
            line.number,
            format!("this line has {have} fields, expected {expected}: {wanted}"),
        ));
    }
    for (k, field) in line.fields().skip(3).enumerate() {
        let ok = if k < numbers {
            field.parse::<f64>().is_ok_and(f64::is_finite)
        } else {
            field.parse::<i64>().is_ok()
        };
        if !ok {
            let what = if k < numbers {
                "attribute"
            } else {
                "boundary marker"
            };
            return Err(parse_error(
                line.number,
                format!(
                    "{what} {} is not a{}",
                    Quoted(field),
                    if k < numbers {
                        " finite number"
                    } else {
                        "n integer"
                    }
                ),
            ));
        }
    }
    Ok(())
}

/// The first field of a data line (which has at least one).
fn first_field<'a>(line: &Line<'a>) -> &'a str {
    line.fields().next().unwrap_or_default()
}

fn read_vertices(records: &mut Records<'_>) -> Result<Vertices, BoardError> {
    let header = records
        .expect("the vertex count line `<#vertices> [2] [<#attributes>] [<#boundary markers>]`")?;
    let line = header.number;
    let mut fields = header.fields();
    let count = parse_count(first_field(&header), line, "vertex count")?;
    if count == 0 {
        return Err(parse_error(
            line,
            "vertex count 0: vertices in a separate .node file are not supported",
        ));
    }
    fields.next();
    if let Some(dim) = fields.next() {
        if dim != "2" {
            return Err(parse_error(
                line,
                format!("dimension {}: only 2 is supported", Quoted(dim)),
            ));
        }
    }
    let attributes = match fields.next() {
        Some(field) => parse_count(field, line, "attribute count")?,
        None => 0,
    };
    let markers = match fields.next() {
        Some(field) => parse_marker_count(field, line)?,
        None => 0,
    };
    if let Some(extra) = fields.next() {
        return Err(parse_error(
            line,
            format!(
                "unexpected field {} after `<#vertices> <dimension> <#attributes> \
                 <#boundary markers>`",
                Quoted(extra)
            ),
        ));
    }
    let wanted = format!(
        "`<id> <x> <y>` (two coordinates), then {attributes} attributes and {markers} boundary \
         markers as the header on line {line} declares"
    );
    let mut vertices = Vertices {
        points: Vec::new(),
        lines: Vec::new(),
        base: 0,
        header_line: line,
        fields: 3usize.saturating_add(attributes).saturating_add(markers),
    };
    for i in 0..count {
        let next_id = vertices.base + i as i64;
        let Some(record) = records.next()? else {
            return Err(if i == 0 {
                records.expect(&format!("vertex 1 of {count}")).unwrap_err()
            } else {
                count_error(
                    line,
                    "vertex",
                    count,
                    format!("the input ends after {i} vertex lines"),
                )
            });
        };
        if i > 0 && ends_section(&record, Some(next_id)) {
            return Err(count_error(
                line,
                "vertex",
                count,
                format!(
                    "only {i} vertex lines follow: line {} ({}) is not vertex {next_id}",
                    record.number,
                    Quoted(record.content.trim())
                ),
            ));
        }
        check_fields(&record, attributes, markers, &wanted)?;
        let mut fields = record.fields();
        let (id, x, y) = (
            fields.next().unwrap_or_default(),
            fields.next().unwrap_or_default(),
            fields.next().unwrap_or_default(),
        );
        let id = parse_id(id, record.number, "vertex id")?;
        if i == 0 {
            if id != 0 && id != 1 {
                return Err(parse_error(
                    record.number,
                    format!("the first vertex id is {id}: it must be 0 or 1"),
                ));
            }
            vertices.base = id;
        } else if id != next_id {
            return Err(parse_error(
                record.number,
                format!("vertex id {id} is out of sequence: expected {next_id}"),
            ));
        }
        let x = parse_coordinate(x).map_err(|m| parse_error(record.number, m))?;
        let y = parse_coordinate(y).map_err(|m| parse_error(record.number, m))?;
        vertices.points.push([x, y]);
        vertices.lines.push(record.number);
    }
    Ok(vertices)
}

fn read_segments(records: &mut Records<'_>, vertices: &Vertices) -> Result<Segments, BoardError> {
    let base = vertices.base;
    let vertex_count = vertices.points.len();
    let header = records.expect("the segment count line `<#segments> [<#boundary markers>]`")?;
    let line = header.number;
    if continues(&header, vertices.fields, Some(base + vertex_count as i64)) {
        return Err(count_error(
            vertices.header_line,
            "vertex",
            vertex_count,
            format!(
                "line {line} continues the vertices (vertex id {})",
                base + vertex_count as i64
            ),
        ));
    }
    let mut fields = header.fields();
    let count = parse_count(first_field(&header), line, "segment count")?;
    fields.next();
    let markers = match fields.next() {
        Some(field) => parse_marker_count(field, line)?,
        None => 0,
    };
    if let Some(extra) = fields.next() {
        return Err(parse_error(
            line,
            format!(
                "unexpected field {} after `<#segments> <#boundary markers>`",
                Quoted(extra)
            ),
        ));
    }
    let wanted = format!(
        "`<id> <v1> <v2>` (two vertex ids), then {markers} boundary markers as the header on \
         line {line} declares"
    );
    let mut segments = Segments {
        header_line: line,
        fields: 3 + markers,
        ends: Vec::new(),
        at: vec![[usize::MAX; 2]; vertex_count],
        degree: vec![0; vertex_count],
    };
    for s in 0..count {
        let Some(record) = records.next()? else {
            return Err(if s == 0 {
                records
                    .expect(&format!("segment 1 of {count}"))
                    .unwrap_err()
            } else {
                count_error(
                    line,
                    "segment",
                    count,
                    format!("the input ends after {s} segment lines"),
                )
            });
        };
        if s > 0 && ends_section(&record, None) {
            return Err(count_error(
                line,
                "segment",
                count,
                format!(
                    "only {s} segment lines follow: line {} ({}) is not a segment line \
                     `<id> <v1> <v2>`",
                    record.number,
                    Quoted(record.content.trim())
                ),
            ));
        }
        check_fields(&record, 0, markers, &wanted)?;
        let mut fields = record.fields();
        parse_id(
            fields.next().unwrap_or_default(),
            record.number,
            "segment id",
        )?;
        let mut ends = [0usize; 2];
        for (end, field) in ends.iter_mut().zip(fields) {
            let v = parse_id(field, record.number, "segment endpoint")?;
            *end = v
                .checked_sub(base)
                .and_then(|i| usize::try_from(i).ok())
                .filter(|&i| i < vertex_count)
                .ok_or_else(|| {
                    parse_error(
                        record.number,
                        format!(
                            "segment endpoint {v} is not a vertex id (ids run from {base} to {})",
                            base + vertex_count as i64 - 1
                        ),
                    )
                })?;
        }
        for &v in &ends {
            if segments.degree[v] == 2 {
                return Err(parse_error(
                    record.number,
                    format!(
                        "vertex {} is the end of a third segment; each vertex must join \
                         exactly two segments of one loop",
                        v as i64 + base
                    ),
                ));
            }
            segments.at[v][segments.degree[v] as usize] = s;
            segments.degree[v] += 1;
        }
        segments.ends.push((ends[0], ends[1], record.number));
    }
    Ok(segments)
}

/// The optional hole and regional attribute counts, which must be 0, and nothing after them.
fn read_holes_and_regions(
    records: &mut Records<'_>,
    vertices: &Vertices,
    segments: &Segments,
) -> Result<(), BoardError> {
    let Some(holes) = records.next()? else {
        return Ok(());
    };
    if continues(&holes, segments.fields, None) {
        return Err(count_error(
            segments.header_line,
            "segment",
            segments.ends.len(),
            format!("line {} continues the segments", holes.number),
        ));
    }
    let count = single_count(&holes, "hole count", "`<#holes>`")?;
    if count > 0 {
        return Err(BoardError::HolesNotSupported {
            line: holes.number,
            count,
        });
    }
    let Some(regions) = records.next()? else {
        return Ok(());
    };
    let count = single_count(
        &regions,
        "regional attribute count",
        "`<#regional attributes>`",
    )?;
    if count > 0 {
        return Err(BoardError::RegionsNotSupported {
            line: regions.number,
            count,
        });
    }
    match records.next()? {
        None => Ok(()),
        Some(extra) => Err(parse_error(
            extra.number,
            format!(
                "unexpected data after the regional attribute count: {}",
                Quoted(extra.content.trim())
            ),
        )),
    }
}

/// A line holding one count and nothing else.
fn single_count(line: &Line<'_>, what: &str, record: &str) -> Result<usize, BoardError> {
    let count = parse_count(first_field(line), line.number, what)?;
    match line.fields().nth(1) {
        Some(extra) => Err(parse_error(
            line.number,
            format!("unexpected field {} after {record}", Quoted(extra)),
        )),
        None => Ok(count),
    }
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

fn parse_count(field: &str, line: usize, what: &str) -> Result<usize, BoardError> {
    field.parse().map_err(|_| {
        parse_error(
            line,
            format!("{what} {} is not a non-negative integer", Quoted(field)),
        )
    })
}

fn parse_marker_count(field: &str, line: usize) -> Result<usize, BoardError> {
    match field {
        "0" => Ok(0),
        "1" => Ok(1),
        _ => Err(parse_error(
            line,
            format!("boundary marker count {}: expected 0 or 1", Quoted(field)),
        )),
    }
}

fn parse_id(field: &str, line: usize, what: &str) -> Result<i64, BoardError> {
    field
        .parse()
        .map_err(|_| parse_error(line, format!("{what} {} is not an integer", Quoted(field))))
}
