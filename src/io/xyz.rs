//! Point clouds as XYZ / CSV text: one point a line (lines end in LF, CRLF or CR), fields
//! separated by commas, spaces or tabs, `#` starting a comment. A first line of names (`x,y,z,intensity,...`) says what each
//! column is, with the names of the PLY reader ([`crate::io::ply`]); without one, the first
//! three columns are `x y z` and the others extra columns `column4`, `column5`, ...
//!
//! Every line has the same number of fields; a field that is not a number, or a value that
//! does not fit its column exactly, is refused with its line, field and what the column holds. Memory grows with the
//! points read.
//!
//! ```
//! use orthtree::cloud::Cloud;
//! use orthtree::io::xyz;
//! let text = "x,y,z,intensity\n0.5,1,2,7\n# a comment\n3,4,5.25,9\n";
//! let cloud: Cloud<f64> = xyz::read(text.as_bytes()).unwrap();
//! assert_eq!(cloud.points, [[0.5, 1.0, 2.0], [3.0, 4.0, 5.25]]);
//! assert_eq!(cloud.attributes.intensity, Some(vec![7, 9]));
//! let mut out = Vec::new();
//! xyz::write(&cloud, &mut out).unwrap();
//! assert_eq!(xyz::read::<f64>(&out[..]).unwrap(), cloud);
//! let err = xyz::read::<f64>("1 2 3\n4 five 6\n".as_bytes()).unwrap_err();
//! assert_eq!(err.to_string(), "XYZ line 2, field 2: \"five\" is not a number");
//! ```

use crate::cloud::Cloud;
use crate::geom::Scalar;
use crate::io::columns::{attribute_names, row, Columns};
use core::fmt;
use std::io::{BufRead, BufReader, BufWriter, Read, Write};

/// The longest line read.
pub const MAX_LINE_BYTES: usize = 1 << 16;

/// Why an XYZ/CSV file was refused, naming the line (1-based) and field (1-based).
#[derive(Debug)]
#[non_exhaustive]
pub enum XyzError {
    /// Reading or writing failed.
    Io(std::io::Error),
    /// A field is not a number.
    NotANumber {
        /// The line.
        line: usize,
        /// The field.
        field: usize,
        /// The text (cut after 32 characters).
        text: String,
    },
    /// A line has another number of fields than the first.
    FieldCount {
        /// The line.
        line: usize,
        /// Its fields.
        found: usize,
        /// The fields of the first line.
        expected: usize,
    },
    /// The names lack `x`, `y` or `z`, or have fewer than three columns.
    MissingColumn {
        /// The column missing.
        name: &'static str,
    },
    /// A value does not fit its column exactly (a coordinate of an integer cloud with a
    /// fraction, an intensity above 65535, ...).
    Inexact {
        /// The line.
        line: usize,
        /// The field.
        field: usize,
        /// The column's name (cut after 32 characters).
        column: String,
        /// The field's text (cut after 32 characters).
        text: String,
        /// What the column holds ("an integer from 0 to 65535", ...).
        holds: String,
    },
    /// The line of names holds `name` twice: the later column would silently take the place
    /// of the earlier (two `x` columns, two intensities).
    DuplicateColumn {
        /// The line of names.
        line: usize,
        /// The field of the second occurrence.
        field: usize,
        /// The name (cut after 32 characters).
        name: String,
    },
    /// A line is longer than [`MAX_LINE_BYTES`] or not UTF-8.
    BadLine {
        /// The line.
        line: usize,
    },
}

impl fmt::Display for XyzError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            XyzError::Io(e) => write!(f, "XYZ: {e}"),
            XyzError::NotANumber { line, field, text } => {
                write!(
                    f,
                    "XYZ line {line}, field {field}: {text:?} is not a number"
                )
            }
            XyzError::FieldCount {
                line,
                found,
                expected,
            } => write!(
                f,
                "XYZ line {line}: {found} fields where the first line has {expected}"
            ),
            XyzError::MissingColumn { name } => write!(f, "XYZ: no column {name}"),
            XyzError::Inexact {
                line,
                field,
                column,
                text,
                holds,
            } => write!(
                f,
                "XYZ line {line}, field {field} ({column}): {text:?} is not {holds}"
            ),
            XyzError::DuplicateColumn { line, field, name } => write!(
                f,
                "XYZ line {line}, field {field}: column {name:?} is named twice"
            ),
            XyzError::BadLine { line } => write!(
                f,
                "XYZ line {line}: not UTF-8 or longer than {MAX_LINE_BYTES} bytes"
            ),
        }
    }
}

impl std::error::Error for XyzError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            XyzError::Io(e) => Some(e),
            _ => None,
        }
    }
}

impl From<std::io::Error> for XyzError {
    fn from(e: std::io::Error) -> Self {
        XyzError::Io(e)
    }
}

/// Reads the next line into `buf` (emptied first), without its end: LF, CRLF or a CR alone;
/// `false` at the end of the input. Stops reading once the line is longer than
/// [`MAX_LINE_BYTES`] (the caller refuses it), so a file without line ends is not held whole.
fn next_line(reader: &mut impl BufRead, buf: &mut Vec<u8>) -> std::io::Result<bool> {
    buf.clear();
    let mut any = false;
    loop {
        let chunk = reader.fill_buf()?;
        if chunk.is_empty() {
            return Ok(any);
        }
        any = true;
        let Some(end) = chunk.iter().position(|&b| b == b'\n' || b == b'\r') else {
            let len = chunk.len();
            buf.extend_from_slice(chunk);
            reader.consume(len);
            if buf.len() > MAX_LINE_BYTES {
                return Ok(true);
            }
            continue;
        };
        let cr = chunk[end] == b'\r';
        buf.extend_from_slice(&chunk[..end]);
        reader.consume(end + 1);
        if cr && reader.fill_buf()?.first() == Some(&b'\n') {
            reader.consume(1);
        }
        return Ok(true);
    }
}

fn fields(line: &str) -> impl Iterator<Item = &str> {
    line.split(|c: char| c == ',' || c.is_ascii_whitespace())
        .filter(|f| !f.is_empty())
}

/// Reads an XYZ/CSV cloud from `input` (buffered here), coordinates converted exactly to `S`.
///
/// # Errors
/// [`XyzError`] naming the line and field of a field that is not a number, a value that does
/// not fit its column, a line with another number of fields than the first, a missing `x`,
/// `y` or `z` name, a name given twice, or an I/O error.
///
/// # Complexity
/// O(n) time; memory grows with the points read.
pub fn read<S: Scalar>(input: impl Read) -> Result<Cloud<S>, XyzError> {
    let mut reader = BufReader::with_capacity(1 << 16, input);
    let mut buf = Vec::new();
    let mut line_no = 0;
    let mut layout: Option<Columns> = None;
    let mut cloud = Cloud::from_points(Vec::new());
    let mut values: Vec<f64> = Vec::new();
    while next_line(&mut reader, &mut buf)? {
        line_no += 1;
        if buf.len() > MAX_LINE_BYTES {
            return Err(XyzError::BadLine { line: line_no });
        }
        let text = core::str::from_utf8(&buf).map_err(|_| XyzError::BadLine { line: line_no })?;
        let text = text.split('#').next().unwrap_or("");
        if text.trim().is_empty() {
            continue;
        }
        if layout.is_none() {
            let first: Vec<&str> = fields(text).collect();
            // A first line of separators alone (",,") names no column: `x` is missing.
            let numeric = first
                .first()
                .is_some_and(|head| head.parse::<f64>().is_ok());
            let names: Vec<String> = if numeric {
                let name = |i: usize| ["x", "y", "z"].get(i).map(|n| n.to_string());
                (0..first.len())
                    .map(|i| name(i).unwrap_or_else(|| format!("column{}", i + 1)))
                    .collect()
            } else {
                first.iter().map(|s| s.to_string()).collect()
            };
            let names: Vec<&str> = names.iter().map(String::as_str).collect();
            if let Some(field) = (0..names.len()).find(|&f| names[..f].contains(&names[f])) {
                return Err(XyzError::DuplicateColumn {
                    line: line_no,
                    field: field + 1,
                    name: names[field].chars().take(32).collect(),
                });
            }
            if let Some(name) = ["x", "y", "z"].into_iter().find(|n| !names.contains(n)) {
                return Err(XyzError::MissingColumn { name });
            }
            let columns = Columns::new(&names);
            cloud.attributes = columns.attributes();
            values = vec![0.0; names.len()];
            layout = Some(columns);
            if !numeric {
                continue;
            }
        }
        let columns = layout.as_ref().expect("the first line sets the columns");
        push_line(text, line_no, &mut values, columns, &mut cloud)?;
    }
    Ok(cloud)
}

fn push_line<S: Scalar>(
    text: &str,
    line: usize,
    values: &mut [f64],
    columns: &Columns,
    cloud: &mut Cloud<S>,
) -> Result<(), XyzError> {
    let mut found = 0;
    for (i, word) in fields(text).enumerate() {
        found = i + 1;
        if i < values.len() {
            values[i] = word.parse().map_err(|_| XyzError::NotANumber {
                line,
                field: i + 1,
                text: word.chars().take(32).collect(),
            })?;
        }
    }
    if found != values.len() {
        return Err(XyzError::FieldCount {
            line,
            found,
            expected: values.len(),
        });
    }
    columns.push(values, cloud).map_err(|i| XyzError::Inexact {
        line,
        field: i + 1,
        column: columns.name(i),
        text: fields(text)
            .nth(i)
            .map(|w| w.chars().take(32).collect())
            .unwrap_or_default(),
        holds: columns.holds::<S>(i),
    })
}

/// Writes `cloud` as CSV to `out` (buffered here): a line of names (`x,y,z` and the present
/// attribute columns, named as [`read`] reads them), then one point a line, each value in the
/// shortest text that reads back to it. The frame is not written: write world coordinates
/// ([`Cloud::world_points`]) or use PLY to keep it.
///
/// # Errors
/// [`XyzError::Io`] when writing fails.
///
/// # Panics
/// When an attribute column is shorter than the points ([`Cloud::check`] tells first).
///
/// # Complexity
/// O(n) time, O(1) memory beyond the buffer.
pub fn write<S: Scalar>(cloud: &Cloud<S>, out: impl Write) -> Result<(), XyzError> {
    let mut w = BufWriter::with_capacity(1 << 16, out);
    write!(w, "x,y,z")?;
    for (name, _) in attribute_names(&cloud.attributes) {
        write!(w, ",{name}")?;
    }
    writeln!(w)?;
    let mut values = Vec::new();
    for i in 0..cloud.len() {
        row(cloud, i, &mut values);
        for (j, v) in values.iter().enumerate() {
            let end = if j + 1 == values.len() { '\n' } else { ',' };
            write!(w, "{v}{end}")?;
        }
    }
    Ok(w.flush()?)
}
