//! What can be wrong with a PBM file and where ([`PbmError`], naming the byte offset and the
//! line), and how the bytes found are shown in a message (escaped, cut short).

use crate::image::ImageError;
use crate::io::limits::LimitError;
use core::fmt;

/// What is wrong with a PBM file, and where (`offset`: bytes from the start; `line`: 1-based).
#[derive(Debug)]
#[non_exhaustive]
pub enum PbmError {
    /// The file could not be read or written.
    Io(std::io::Error),
    /// The file does not start with `P1` or `P4`.
    BadMagic {
        /// The first bytes, escaped.
        found: String,
    },
    /// A header field (width or height) is missing or not a positive decimal number below 2^32.
    BadHeader {
        /// `"width"` or `"height"`.
        field: &'static str,
        /// Where it should start.
        offset: usize,
        /// The line.
        line: usize,
        /// The bytes found there, escaped and cut short.
        found: String,
    },
    /// No whitespace where the grammar asks for it (after the magic number, the width or the
    /// height).
    MissingWhitespace {
        /// `"magic number"`, `"width"` or `"height"`.
        after: &'static str,
        /// Where the whitespace should be.
        offset: usize,
        /// The line.
        line: usize,
        /// The bytes found there, escaped and cut short.
        found: String,
    },
    /// A `P1` pixel is neither `0` nor `1`.
    BadPixel {
        /// Its offset.
        offset: usize,
        /// The line.
        line: usize,
        /// The byte found.
        found: u8,
    },
    /// The raster ends early.
    Truncated {
        /// Where the file ends.
        offset: usize,
        /// The line there.
        line: usize,
        /// Pixels (for `P1`) or bytes (for `P4`) the header asks for.
        expected: u64,
        /// Pixels or bytes found.
        found: u64,
        /// `"pixels"` or `"bytes"`.
        unit: &'static str,
    },
    /// Data after the raster (a second image included).
    TrailingData {
        /// Where it starts.
        offset: usize,
        /// The line.
        line: usize,
        /// How many bytes follow the raster.
        bytes: usize,
        /// The first of them, escaped and cut short.
        found: String,
    },
    /// The image breaks a [`Limits`](crate::io::Limits) limit.
    Limit(LimitError),
    /// The image is too large for a region tree, or building it broke the byte limit.
    Image(ImageError),
    /// Writing an image with a zero side, which a PBM file cannot hold.
    EmptyImage {
        /// The width.
        width: u32,
        /// The height.
        height: u32,
    },
}

impl fmt::Display for PbmError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PbmError::Io(e) => write!(f, "PBM: {e}"),
            PbmError::BadMagic { found } => {
                write!(
                    f,
                    "PBM byte 0: starts with \"{found}\", expected \"P1\" or \"P4\""
                )
            }
            PbmError::BadHeader {
                field,
                offset,
                line,
                found,
            } => write!(
                f,
                "PBM line {line}, byte {offset}: {field} is \"{found}\", expected a positive \
                 decimal number of at most {}",
                u32::MAX
            ),
            PbmError::MissingWhitespace {
                after,
                offset,
                line,
                found,
            } => write!(
                f,
                "PBM line {line}, byte {offset}: expected whitespace after the {after}, found \
                 \"{found}\""
            ),
            PbmError::BadPixel {
                offset,
                line,
                found,
            } => write!(
                f,
                "PBM line {line}, byte {offset}: pixel is \"{}\", expected 0 or 1",
                shown(&[*found])
            ),
            PbmError::Truncated {
                offset,
                line,
                expected,
                found,
                unit,
            } => write!(
                f,
                "PBM line {line}, byte {offset}: the raster ends after {found} of {expected} \
                 {unit}"
            ),
            PbmError::TrailingData {
                offset,
                line,
                bytes,
                found,
            } => write!(
                f,
                "PBM line {line}, byte {offset}: {bytes} bytes after the raster (\"{found}\"); \
                 a file holds one image, and a P4 header ends with exactly one whitespace byte"
            ),
            PbmError::Limit(e) => write!(f, "PBM: {e}"),
            PbmError::Image(e) => write!(f, "PBM: {e}"),
            PbmError::EmptyImage { width, height } => write!(
                f,
                "PBM: cannot write a {width} x {height} image, a PBM side is at least 1"
            ),
        }
    }
}

impl std::error::Error for PbmError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            PbmError::Io(e) => Some(e),
            PbmError::Image(e) => Some(e),
            PbmError::Limit(e) => Some(e),
            _ => None,
        }
    }
}

impl From<std::io::Error> for PbmError {
    fn from(e: std::io::Error) -> Self {
        PbmError::Io(e)
    }
}

/// At most this many bytes are shown in a message.
pub(super) const SHOWN: usize = 16;

/// Bytes for a message: printable ASCII as is, everything else escaped, cut after [`SHOWN`].
pub(super) fn shown(bytes: &[u8]) -> String {
    let mut s = String::new();
    for &b in bytes.iter().take(SHOWN) {
        match b {
            b'\n' => s.push_str("\\n"),
            b'\r' => s.push_str("\\r"),
            b'\t' => s.push_str("\\t"),
            b'"' => s.push_str("\\\""),
            b'\\' => s.push_str("\\\\"),
            0x20..=0x7e => s.push(char::from(b)),
            _ => s.push_str(&format!("\\x{b:02x}")),
        }
    }
    if bytes.len() > SHOWN {
        s.push_str("...");
    }
    s
}
