//! The PLY body: vertices read one at a time (a line of ASCII or one binary record) into the
//! cloud's columns, each value converted exactly or refused.

use super::header::{quote, read_header, Header};
use super::{Encoding, Kind, PlyError};
use crate::cloud::{Cloud, Frame};
use crate::geom::Scalar;
use crate::io::columns::Columns;
use crate::io::read_full;
use std::io::{BufRead, BufReader, Read};

/// The longest ASCII vertex line read.
const MAX_LINE_BYTES: usize = 1 << 16;

/// Reads a PLY point cloud from `input` (buffered here), its positions converted exactly to
/// `S`.
///
/// # Errors
/// [`PlyError`]: a header that breaks the grammar (naming the line), a missing `x`, `y` or
/// `z`, a malformed value (line and field), a truncated body or data after it (byte offset),
/// a value that does not fit `S` or its attribute column exactly (vertex and property), or an
/// I/O error.
///
/// # Complexity
/// O(n) time; memory grows with the vertices read, never with the count the header claims.
pub fn read<S: Scalar>(input: impl Read) -> Result<Cloud<S>, PlyError> {
    let mut reader = BufReader::with_capacity(1 << 16, input);
    let header = read_header(&mut reader)?;
    let names: Vec<&str> = header.properties.iter().map(|(n, _)| n.as_str()).collect();
    let columns = Columns::new(&names);
    let mut cloud = Cloud {
        points: Vec::new(),
        attributes: columns.attributes(),
        frame: header.frame.unwrap_or(Frame::IDENTITY),
    };
    let mut values = vec![0.0f64; header.properties.len()];
    let ascii = header.encoding == Encoding::Ascii;
    // A binary record's bytes, or an ASCII line (each read clears and refills it).
    let stride: usize = header.properties.iter().map(|(_, k)| k.size()).sum();
    let mut buf = vec![0u8; if ascii { 0 } else { stride }];
    let mut offset = header.bytes;
    for vertex in 0..header.count {
        let at = (vertex, offset);
        offset += if ascii {
            read_line(&mut reader, &header, at, &mut buf, &mut values)?
        } else {
            read_record(&mut reader, &header, at, &mut buf, &mut values)?
        };
        columns
            .push(&values, &mut cloud)
            .map_err(|i| PlyError::Inexact {
                vertex,
                property: header.properties[i].0.clone(),
                value: values[i],
                holds: columns.holds::<S>(i),
            })?;
    }
    // Only white space may follow an ASCII body, nothing a binary one.
    loop {
        let rest = reader.fill_buf()?;
        if rest.is_empty() {
            return Ok(cloud);
        }
        if let Some(p) = rest
            .iter()
            .position(|b| !(ascii && b.is_ascii_whitespace()))
        {
            return Err(PlyError::TrailingData {
                offset: offset + p as u64,
            });
        }
        let n = rest.len();
        offset += n as u64;
        reader.consume(n);
    }
}

/// Reads vertex `vertex`'s ASCII line, which starts at byte `offset`, into `values`; the
/// bytes read.
fn read_line(
    reader: &mut impl BufRead,
    header: &Header,
    (vertex, offset): (u64, u64),
    line: &mut Vec<u8>,
    values: &mut [f64],
) -> Result<u64, PlyError> {
    line.clear();
    let n = reader
        .by_ref()
        .take(MAX_LINE_BYTES as u64)
        .read_until(b'\n', line)?;
    let line_no = header.lines + 1 + vertex as usize;
    if n == 0 {
        return Err(PlyError::Truncated {
            vertex,
            count: header.count,
            offset,
        });
    }
    // A line that cannot be split into fields, blamed on its first.
    let whole_line = |text: &str| PlyError::BadValue {
        line: line_no,
        field: 1,
        property: header.properties[0].0.clone(),
        text: text.into(),
    };
    if n == MAX_LINE_BYTES && line.last() != Some(&b'\n') {
        return Err(whole_line(&format!(
            "(a line longer than {MAX_LINE_BYTES} bytes)"
        )));
    }
    let text = core::str::from_utf8(line).map_err(|_| whole_line("(not ASCII)"))?;
    let mut found = 0;
    for (field, word) in text.split_ascii_whitespace().enumerate() {
        found = field + 1;
        if field >= values.len() {
            continue;
        }
        let (name, kind) = &header.properties[field];
        values[field] = parse(word, *kind).ok_or_else(|| PlyError::BadValue {
            line: line_no,
            field: field + 1,
            property: name.clone(),
            text: quote(word),
        })?;
    }
    if found != values.len() {
        return Err(PlyError::FieldCount {
            line: line_no,
            found,
            expected: values.len(),
        });
    }
    Ok(n as u64)
}

/// An ASCII value of type `kind`, or `None` when malformed or out of range.
fn parse(word: &str, kind: Kind) -> Option<f64> {
    match kind {
        Kind::F32 => word.parse::<f32>().ok().map(f64::from),
        Kind::F64 => word.parse::<f64>().ok(),
        _ => {
            let v: i64 = word.parse().ok()?;
            // The integer kind's range: its bits, one of them the sign's if it has one.
            let signed = matches!(kind, Kind::I8 | Kind::I16 | Kind::I32);
            let hi = (1i64 << (8 * kind.size() as u32 - u32::from(signed))) - 1;
            let lo = if signed { -hi - 1 } else { 0 };
            (lo..=hi).contains(&v).then_some(v as f64)
        }
    }
}

/// Reads vertex `vertex`'s binary record, which starts at byte `offset` and is as long as
/// `record`, into `values`; the bytes read.
fn read_record(
    reader: &mut impl BufRead,
    header: &Header,
    (vertex, offset): (u64, u64),
    record: &mut [u8],
    values: &mut [f64],
) -> Result<u64, PlyError> {
    let stride = record.len();
    let got = read_full(reader, record)?;
    if got < stride {
        return Err(PlyError::Truncated {
            vertex,
            count: header.count,
            offset: offset + got as u64,
        });
    }
    let little = header.encoding == Encoding::BinaryLittleEndian;
    let mut at = 0;
    for (i, (_, kind)) in header.properties.iter().enumerate() {
        values[i] = decode(&record[at..at + kind.size()], *kind, little);
        at += kind.size();
    }
    Ok(stride as u64)
}

/// A binary value of type `kind` from its bytes.
fn decode(b: &[u8], kind: Kind, little: bool) -> f64 {
    macro_rules! num {
        ($t:ty, $n:expr) => {{
            let a: [u8; $n] = b.try_into().expect("the record is cut by the kinds' sizes");
            (if little {
                <$t>::from_le_bytes(a)
            } else {
                <$t>::from_be_bytes(a)
            }) as f64
        }};
    }
    match kind {
        Kind::I8 => num!(i8, 1),
        Kind::U8 => num!(u8, 1),
        Kind::I16 => num!(i16, 2),
        Kind::U16 => num!(u16, 2),
        Kind::I32 => num!(i32, 4),
        Kind::U32 => num!(u32, 4),
        Kind::F32 => num!(f32, 4),
        Kind::F64 => num!(f64, 8),
    }
}
