//! Point clouds as PLY files (Turk's Polygon File Format, as documented by Paul Bourke):
//! ASCII, binary little-endian and binary big-endian, read and written by hand.
//!
//! Read: a `vertex` element of scalar properties. `x y z` (any PLY type, converted exactly to
//! the cloud's coordinate type) are the position; `intensity`, `classification`, `red green
//! blue`, `gps_time` and `nx ny nz` fill their [`Attributes`](crate::cloud::Attributes)
//! columns; every other property becomes an extra [`Column`](crate::cloud::Column). Nothing is
//! dropped: another element with points in it (a mesh's `face`), a list property, or bytes
//! after the last vertex are refused. A `comment orthtree frame ...` line written by
//! [`write()`] restores a LAS [`Frame`](crate::cloud::Frame).
//!
//! Hostile input: errors name the line (header, ASCII body) or the byte offset (binary body)
//! and what was expected; the header is at most [`MAX_HEADER_BYTES`]; nothing is allocated by
//! the element count before the data backs it (points are pushed as they are read).
//!
//! ```
//! use orthtree::cloud::Cloud;
//! use orthtree::io::ply::{self, Encoding};
//! let mut cloud = Cloud::from_points(vec![[0.5, 1.0, 2.0], [3.0, 4.0, 5.25]]);
//! cloud.attributes.intensity = Some(vec![7, 9]);
//! let mut bytes = Vec::new();
//! ply::write(&cloud, Encoding::BinaryLittleEndian, &mut bytes).unwrap();
//! let back: Cloud<f64> = ply::read(&bytes[..]).unwrap();
//! assert_eq!(back, cloud);
//! let err = ply::read::<f64>(&bytes[..bytes.len() - 1]).unwrap_err();
//! assert!(err.to_string().contains("byte offset"));
//! ```

mod header;
mod read;
mod write;

pub use read::read;
pub use write::write;

use core::fmt;

/// The most bytes a PLY header may take.
pub const MAX_HEADER_BYTES: usize = 1 << 16;

/// How the body of a PLY file is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Encoding {
    /// `format ascii 1.0`: one vertex a line.
    Ascii,
    /// `format binary_little_endian 1.0`.
    BinaryLittleEndian,
    /// `format binary_big_endian 1.0`.
    BinaryBigEndian,
}

/// A PLY scalar type.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    /// `char` / `int8`.
    I8,
    /// `uchar` / `uint8`.
    U8,
    /// `short` / `int16`.
    I16,
    /// `ushort` / `uint16`.
    U16,
    /// `int` / `int32`.
    I32,
    /// `uint` / `uint32`.
    U32,
    /// `float` / `float32`.
    F32,
    /// `double` / `float64`.
    F64,
}

/// Each encoding with its name on the `format` line, in the order of [`Encoding`].
const FORMATS: [(Encoding, &str); 3] = [
    (Encoding::Ascii, "ascii"),
    (Encoding::BinaryLittleEndian, "binary_little_endian"),
    (Encoding::BinaryBigEndian, "binary_big_endian"),
];

/// Each kind with its classic and its sized PLY name and its bytes per value, in the order of
/// [`Kind`].
const KINDS: [(Kind, &str, &str, usize); 8] = [
    (Kind::I8, "char", "int8", 1),
    (Kind::U8, "uchar", "uint8", 1),
    (Kind::I16, "short", "int16", 2),
    (Kind::U16, "ushort", "uint16", 2),
    (Kind::I32, "int", "int32", 4),
    (Kind::U32, "uint", "uint32", 4),
    (Kind::F32, "float", "float32", 4),
    (Kind::F64, "double", "float64", 8),
];

impl Kind {
    /// The type of a PLY name (both spellings).
    pub fn from_name(name: &str) -> Option<Kind> {
        KINDS
            .iter()
            .find(|k| k.1 == name || k.2 == name)
            .map(|k| k.0)
    }

    /// The classic PLY name.
    pub fn name(self) -> &'static str {
        KINDS[self as usize].1
    }

    /// Bytes per value in a binary body.
    pub fn size(self) -> usize {
        KINDS[self as usize].3
    }

    /// `true` for `float` and `double`.
    pub fn is_float(self) -> bool {
        matches!(self, Kind::F32 | Kind::F64)
    }
}

/// Why a PLY file was refused. Header errors name the line, ASCII body errors the line and
/// field, binary body errors the byte offset.
#[derive(Debug)]
#[non_exhaustive]
pub enum PlyError {
    /// Reading or writing failed.
    Io(std::io::Error),
    /// The header breaks the grammar at `line`.
    Header {
        /// The 1-based line.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// The header is longer than [`MAX_HEADER_BYTES`].
    HeaderTooLong {
        /// The limit.
        limit: usize,
    },
    /// The `vertex` element lacks property `name` (`x`, `y` or `z`).
    MissingProperty {
        /// The property.
        name: &'static str,
    },
    /// A value of the ASCII body is malformed or out of its type's range.
    BadValue {
        /// The 1-based line.
        line: usize,
        /// The 1-based field on the line.
        field: usize,
        /// The property.
        property: String,
        /// The text found, quoted (cut after 32 characters).
        text: String,
    },
    /// An ASCII vertex line has another number of fields than the header's properties.
    FieldCount {
        /// The 1-based line.
        line: usize,
        /// The fields found.
        found: usize,
        /// The properties declared.
        expected: usize,
    },
    /// The file ends inside vertex `vertex` of the `count` the header declares.
    Truncated {
        /// The vertex (0-based) that is incomplete or missing.
        vertex: u64,
        /// The vertices declared.
        count: u64,
        /// The byte offset where the data ends.
        offset: u64,
    },
    /// Bytes or lines follow the last vertex.
    TrailingData {
        /// The byte offset of the first extra byte.
        offset: u64,
    },
    /// A value does not fit its attribute column or the coordinate type exactly.
    Inexact {
        /// The vertex.
        vertex: u64,
        /// The property.
        property: String,
        /// The value.
        value: f64,
        /// What the column holds ("an integer from 0 to 65535", ...).
        holds: String,
    },
}

impl fmt::Display for PlyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PlyError::Io(e) => write!(f, "PLY: {e}"),
            PlyError::Header { line, message } => write!(f, "PLY header, line {line}: {message}"),
            PlyError::HeaderTooLong { limit } => {
                write!(f, "PLY: the header is longer than {limit} bytes")
            }
            PlyError::MissingProperty { name } => {
                write!(f, "PLY: the vertex element has no property {name}")
            }
            PlyError::BadValue {
                line,
                field,
                property,
                text,
            } => write!(
                f,
                "PLY line {line}, field {field} ({property}): {text} is not a valid value"
            ),
            PlyError::FieldCount {
                line,
                found,
                expected,
            } => write!(
                f,
                "PLY line {line}: {found} fields where the header declares {expected} properties"
            ),
            PlyError::Truncated {
                vertex,
                count,
                offset,
            } => write!(
                f,
                "PLY: the data ends at byte offset {offset} in vertex {vertex} of the {count} declared"
            ),
            PlyError::TrailingData { offset } => {
                write!(f, "PLY: data after the last vertex at byte offset {offset}")
            }
            PlyError::Inexact {
                vertex,
                property,
                value,
                holds,
            } => write!(f, "PLY vertex {vertex}: {property} = {value} is not {holds}"),
        }
    }
}

impl std::error::Error for PlyError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            PlyError::Io(e) => Some(e),
            _ => None,
        }
    }
}

impl From<std::io::Error> for PlyError {
    fn from(e: std::io::Error) -> Self {
        PlyError::Io(e)
    }
}
