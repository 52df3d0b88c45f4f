//! The sections of a `.poly` file in order: vertices, segments, then the optional hole and
//! regional attribute counts.

use super::super::board_syntax::{parse_coordinate, parse_error, Line, Quoted};
use super::records::{
    check_fields, continues, count_error, ends_section, extra_field, first_field, parse_count,
    parse_id, parse_marker_count, single_count, Records,
};
use crate::mesh::{BoardError, Point};

/// The vertex section.
pub(super) struct Vertices {
    pub(super) points: Vec<Point>,
    /// The input line of each vertex.
    pub(super) lines: Vec<usize>,
    /// The first id, 0 or 1.
    pub(super) base: i64,
    /// The line of the vertex count.
    pub(super) header_line: usize,
    /// The number of fields of a vertex line.
    pub(super) fields: usize,
}

/// The segment section: (first vertex, second vertex, line) with vertices from 0, and the
/// segments at each vertex.
pub(super) struct Segments {
    /// The line of the segment count.
    pub(super) header_line: usize,
    /// The number of fields of a segment line.
    pub(super) fields: usize,
    pub(super) ends: Vec<(usize, usize, usize)>,
    /// Up to two segments at each vertex.
    pub(super) at: Vec<[usize; 2]>,
    pub(super) degree: Vec<u8>,
}

/// Reads the vertex count line `<#vertices> [2] [<#attributes>] [<#boundary markers>]`;
/// returns its line, the count, the attribute count and the marker count.
fn read_vertex_header(
    records: &mut Records<'_>,
) -> Result<(usize, usize, usize, usize), BoardError> {
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
    if let Some(dim) = fields.next().filter(|&dim| dim != "2") {
        return Err(parse_error(
            line,
            format!("dimension {}: only 2 is supported", Quoted(dim)),
        ));
    }
    let attributes = fields
        .next()
        .map_or(Ok(0), |f| parse_count(f, line, "attribute count"))?;
    let markers = fields
        .next()
        .map_or(Ok(0), |f| parse_marker_count(f, line))?;
    let record = "<#vertices> <dimension> <#attributes> <#boundary markers>";
    extra_field(line, fields.next(), record)?;
    Ok((line, count, attributes, markers))
}

/// The line of record `i` (from 0) of a section of `count` records whose count is on line
/// `header_line`; `what` names a record ("vertex", "segment"). A missing line, or one that
/// `ends_section` says is not a record (`id`: the id the record must have, if any, and `shape`
/// what it looks like), is blamed on the count.
fn section_record<'a>(
    records: &mut Records<'a>,
    (what, count, header_line): (&str, usize, usize),
    i: usize,
    (id, shape): (Option<i64>, &str),
) -> Result<Line<'a>, BoardError> {
    let Some(record) = records.next()? else {
        return Err(if i == 0 {
            records.end_of_input(&format!("{what} 1 of {count}"))
        } else {
            let detail = format!("the input ends after {i} {what} lines");
            count_error(header_line, what, count, detail)
        });
    };
    if i > 0 && ends_section(&record, id) {
        let detail = format!(
            "only {i} {what} lines follow: line {} ({}) is not {shape}",
            record.number,
            Quoted(record.content.trim())
        );
        return Err(count_error(header_line, what, count, detail));
    }
    Ok(record)
}

/// Checks the id of vertex record `i` (the first sets the numbering: 0 or 1) and adds its
/// point to `vertices`.
fn add_vertex(vertices: &mut Vertices, record: &Line<'_>, i: usize) -> Result<(), BoardError> {
    let mut fields = record.fields();
    let mut next = || fields.next().unwrap_or_default();
    let (id, x, y) = (next(), next(), next());
    let id = parse_id(id, record.number, "vertex id")?;
    let expected = vertices.base + i as i64;
    if i == 0 && id != 0 && id != 1 {
        let message = format!("the first vertex id is {id}: it must be 0 or 1");
        return Err(parse_error(record.number, message));
    } else if i == 0 {
        vertices.base = id;
    } else if id != expected {
        let message = format!("vertex id {id} is out of sequence: expected {expected}");
        return Err(parse_error(record.number, message));
    }
    let x = parse_coordinate(x).map_err(|m| parse_error(record.number, m))?;
    let y = parse_coordinate(y).map_err(|m| parse_error(record.number, m))?;
    vertices.points.push([x, y]);
    vertices.lines.push(record.number);
    Ok(())
}

/// Reads the vertex section: its count line and the vertex records.
pub(super) fn read_vertices(records: &mut Records<'_>) -> Result<Vertices, BoardError> {
    let (line, count, attributes, markers) = read_vertex_header(records)?;
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
        let shape = format!("vertex {next_id}");
        let section = ("vertex", count, line);
        let record = section_record(records, section, i, (Some(next_id), &shape))?;
        check_fields(&record, attributes, markers, &wanted)?;
        add_vertex(&mut vertices, &record, i)?;
    }
    Ok(vertices)
}

/// Reads the segment count line `<#segments> [<#boundary markers>]`, first checking that it
/// does not continue the vertices; returns its line, the count and the marker count.
fn read_segment_header(
    records: &mut Records<'_>,
    vertices: &Vertices,
) -> Result<(usize, usize, usize), BoardError> {
    let next_id = vertices.base + vertices.points.len() as i64;
    let header = records.expect("the segment count line `<#segments> [<#boundary markers>]`")?;
    let line = header.number;
    if continues(&header, vertices.fields, Some(next_id)) {
        let detail = format!("line {line} continues the vertices (vertex id {next_id})");
        let count = vertices.points.len();
        return Err(count_error(vertices.header_line, "vertex", count, detail));
    }
    let mut fields = header.fields();
    let count = parse_count(first_field(&header), line, "segment count")?;
    fields.next();
    let markers = fields
        .next()
        .map_or(Ok(0), |f| parse_marker_count(f, line))?;
    extra_field(line, fields.next(), "<#segments> <#boundary markers>")?;
    Ok((line, count, markers))
}

/// The vertex (from 0) that segment endpoint `field` on line `line` names.
fn endpoint(field: &str, line: usize, vertices: &Vertices) -> Result<usize, BoardError> {
    let (base, vertex_count) = (vertices.base, vertices.points.len());
    let v = parse_id(field, line, "segment endpoint")?;
    let index = v.checked_sub(base).and_then(|i| usize::try_from(i).ok());
    index.filter(|&i| i < vertex_count).ok_or_else(|| {
        let last = base + vertex_count as i64 - 1;
        let message =
            format!("segment endpoint {v} is not a vertex id (ids run from {base} to {last})");
        parse_error(line, message)
    })
}

/// Adds segment `s`, from `ends[0]` to `ends[1]` on line `line`, refusing a vertex's third.
fn add_segment(
    segments: &mut Segments,
    s: usize,
    ends: [usize; 2],
    (line, base): (usize, i64),
) -> Result<(), BoardError> {
    for v in ends {
        let degree = segments.degree[v];
        if degree == 2 {
            let message = format!(
                "vertex {} is the end of a third segment; each vertex must join exactly two \
                 segments of one loop",
                v as i64 + base
            );
            return Err(parse_error(line, message));
        }
        segments.at[v][usize::from(degree)] = s;
        segments.degree[v] = degree + 1;
    }
    segments.ends.push((ends[0], ends[1], line));
    Ok(())
}

/// Reads the segment section: its count line and the segment records.
pub(super) fn read_segments(
    records: &mut Records<'_>,
    vertices: &Vertices,
) -> Result<Segments, BoardError> {
    let vertex_count = vertices.points.len();
    let (line, count, markers) = read_segment_header(records, vertices)?;
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
    let shape = (None, "a segment line `<id> <v1> <v2>`");
    for s in 0..count {
        let record = section_record(records, ("segment", count, line), s, shape)?;
        check_fields(&record, 0, markers, &wanted)?;
        let mut fields = record.fields();
        let id = fields.next().unwrap_or_default();
        parse_id(id, record.number, "segment id")?;
        let mut ends = [0usize; 2];
        for (end, field) in ends.iter_mut().zip(fields) {
            *end = endpoint(field, record.number, vertices)?;
        }
        add_segment(&mut segments, s, ends, (record.number, vertices.base))?;
    }
    Ok(segments)
}

/// The optional hole and regional attribute counts, which must be 0, and nothing after them.
pub(super) fn read_holes_and_regions(
    records: &mut Records<'_>,
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
    let count = single_count(&holes, "hole count", "<#holes>")?;
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
        "<#regional attributes>",
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
