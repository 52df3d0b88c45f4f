//! The PLY header: `ply`, the format line, comments, elements with their properties and
//! `end_header`, read line by line within [`MAX_HEADER_BYTES`].

use super::{Encoding, Kind, PlyError, FORMATS, MAX_HEADER_BYTES};
use crate::cloud::Frame;
use std::io::{BufRead, Read};

/// What the header says about the vertices.
#[derive(Debug)]
pub(super) struct Header {
    pub encoding: Encoding,
    /// The vertices declared (not trusted for allocation).
    pub count: u64,
    /// The vertex properties, in order.
    pub properties: Vec<(String, Kind)>,
    /// The frame of a `comment orthtree frame` line.
    pub frame: Option<Frame>,
    /// The header's length in bytes (where the body starts).
    pub bytes: u64,
    /// The header's number of lines.
    pub lines: usize,
}

/// The comment line that carries a frame: `comment orthtree frame sx sy sz ox oy oz`.
pub(super) const FRAME_COMMENT: &str = "orthtree frame";

fn error(line: usize, message: impl Into<String>) -> PlyError {
    PlyError::Header {
        line,
        message: message.into(),
    }
}

/// Reads the header from `reader`, leaving it at the first byte of the body.
pub(super) fn read_header(reader: &mut impl BufRead) -> Result<Header, PlyError> {
    let mut bytes = 0u64;
    let mut line_no = 0usize;
    let mut buf = Vec::new();
    let mut next_line = |reader: &mut dyn BufRead| -> Result<Option<String>, PlyError> {
        buf.clear();
        let left = (MAX_HEADER_BYTES as u64).saturating_sub(bytes);
        bytes += reader.take(left).read_until(b'\n', &mut buf)? as u64;
        // A line cut short: by the end of the input, or by the limit.
        if buf.last() != Some(&b'\n') {
            if bytes < MAX_HEADER_BYTES as u64 {
                return Ok(None);
            }
            return Err(PlyError::HeaderTooLong {
                limit: MAX_HEADER_BYTES,
            });
        }
        line_no += 1;
        buf.pop();
        if buf.last() == Some(&b'\r') {
            buf.pop();
        }
        String::from_utf8(buf.clone())
            .map(Some)
            .map_err(|_| error(line_no, "the line is not ASCII text"))
    };
    let missing_end = |line| error(line, "the file ends before end_header");

    let first = next_line(reader)?.ok_or_else(|| missing_end(1))?;
    if first != "ply" {
        return Err(error(1, format!("expected 'ply', found {}", quote(&first))));
    }
    let mut encoding = None;
    let mut vertex: Option<(u64, Vec<(String, Kind)>)> = None;
    // The element whose properties are being declared: true for `vertex`.
    let mut in_vertex = false;
    let mut frame = None;
    let mut current = 1;
    loop {
        let line = next_line(reader)?.ok_or_else(|| missing_end(current + 1))?;
        current += 1;
        let words: Vec<&str> = line.split_ascii_whitespace().collect();
        match words.as_slice() {
            ["end_header"] => break,
            ["format", format, "1.0"] => {
                if encoding.is_some() {
                    return Err(error(current, "a second format line"));
                }
                let (found, _) = FORMATS
                    .iter()
                    .find(|f| f.1 == *format)
                    .ok_or_else(|| error(current, format!("unknown format {}", quote(format))))?;
                encoding = Some(*found);
            }
            ["comment", ..] | ["obj_info", ..] => {
                let rest = line.trim_start().strip_prefix("comment").map(str::trim);
                if let Some(values) = rest.and_then(|r| r.strip_prefix(FRAME_COMMENT)) {
                    frame = Some(parse_frame(values, current)?);
                }
            }
            ["element", name, count] => {
                let count: u64 = count
                    .parse()
                    .map_err(|_| error(current, format!("bad element count {}", quote(count))))?;
                in_vertex = *name == "vertex";
                if in_vertex {
                    if vertex.is_some() {
                        return Err(error(current, "a second vertex element"));
                    }
                    vertex = Some((count, Vec::new()));
                } else if count > 0 {
                    return Err(error(
                        current,
                        format!(
                            "element {} has {count} entries; only vertices are read",
                            quote(name)
                        ),
                    ));
                }
            }
            ["property", "list", ..] if in_vertex => {
                return Err(error(
                    current,
                    "list properties of vertices are not supported",
                ));
            }
            ["property", kind, name] => {
                let kind = Kind::from_name(kind)
                    .ok_or_else(|| error(current, format!("unknown type {}", quote(kind))))?;
                if in_vertex {
                    let props = &mut vertex.as_mut().expect("in_vertex implies vertex").1;
                    if props.iter().any(|(n, _)| n == name) {
                        return Err(error(current, format!("property {} twice", quote(name))));
                    }
                    props.push((name.to_string(), kind));
                }
            }
            ["property", "list", _, _, _] => {}
            _ => return Err(error(current, format!("unexpected line {}", quote(&line)))),
        }
    }
    let encoding = encoding.ok_or_else(|| error(2, "no format line"))?;
    let (count, properties) = vertex.ok_or_else(|| error(current, "no vertex element"))?;
    let has = |name: &str| properties.iter().any(|(n, _)| n == name);
    if let Some(name) = ["x", "y", "z"].into_iter().find(|name| !has(name)) {
        return Err(PlyError::MissingProperty { name });
    }
    Ok(Header {
        encoding,
        count,
        properties,
        frame,
        bytes,
        lines: current,
    })
}

fn parse_frame(values: &str, line: usize) -> Result<Frame, PlyError> {
    let v: Vec<f64> = values
        .split_ascii_whitespace()
        .map(str::parse)
        .collect::<Result<_, _>>()
        .map_err(|_| error(line, "a frame comment needs six numbers"))?;
    if v.len() != 6 || v.iter().any(|x| !x.is_finite()) {
        return Err(error(line, "a frame comment needs six finite numbers"));
    }
    Ok(Frame {
        scale: [v[0], v[1], v[2]],
        offset: [v[3], v[4], v[5]],
    })
}

/// A field quoted for a message, cut after 32 characters.
pub(super) fn quote(s: &str) -> String {
    let cut: String = s.chars().take(32).collect();
    if cut.len() < s.len() {
        format!("{:?}...", cut)
    } else {
        format!("{cut:?}")
    }
}
