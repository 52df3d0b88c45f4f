//! The sections of a `.poly` file in order: vertices, segments, then the optional hole and
//! regional attribute counts.

use super::super::board_syntax::{parse_coordinate, parse_error, Quoted};
use super::records::{
    check_fields, continues, count_error, ends_section, first_field, parse_count, parse_id,
    parse_marker_count, single_count, Records,
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

pub(super) fn read_vertices(records: &mut Records<'_>) -> Result<Vertices, BoardError> {
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
                records.end_of_input(&format!("vertex 1 of {count}"))
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

pub(super) fn read_segments(
    records: &mut Records<'_>,
    vertices: &Vertices,
) -> Result<Segments, BoardError> {
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
                records.end_of_input(&format!("segment 1 of {count}"))
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
