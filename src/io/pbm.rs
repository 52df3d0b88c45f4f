//! Netpbm bitmaps (PBM) for 2D region trees, read and written with no dependency: `P1` (plain,
//! ASCII `0`/`1`) and `P4` (raw, rows packed 8 pixels a byte, most significant bit first, each
//! row padded to a whole byte). `1` is black, as in the format; the first row is the image's
//! row `y = 0`. Comments (`#` to the end of the line) are allowed in the header, and anywhere
//! in a `P1` body.
//!
//! A malformed file is a [`PbmError`] saying what is wrong and where: the line for `P1` and the
//! header, the byte offset for `P4` data.
//!
//! ```
//! use orthtree::image::ImageTree;
//! use orthtree::io::pbm::{self, PbmFormat};
//! let t = ImageTree::from_boxes([10, 3], &[([2, 0], [9, 2])]).unwrap();
//! for format in [PbmFormat::Plain, PbmFormat::Raw] {
//!     let bytes = pbm::to_bytes(&t, format);
//!     assert_eq!(pbm::from_bytes(&bytes).unwrap(), t);
//! }
//! assert!(pbm::to_bytes(&t, PbmFormat::Plain).starts_with(b"P1\n10 3\n0011111110\n"));
//! let err = pbm::from_bytes(b"P1\n2 2\n0 1\n1 x\n").unwrap_err();
//! assert_eq!(err.to_string(), "PBM line 4: pixel is 'x', expected 0 or 1");
//! ```

use crate::image::{ImageError, ImageTree};
use core::fmt;
use std::path::Path;

/// Which PBM variant to write.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PbmFormat {
    /// `P1`: ASCII `0` and `1`, at most 70 characters a line.
    Plain,
    /// `P4`: binary, 8 pixels a byte.
    Raw,
}

/// What is wrong with a PBM file, and where.
#[derive(Debug)]
#[non_exhaustive]
pub enum PbmError {
    /// The file could not be read or written.
    Io(std::io::Error),
    /// The file does not start with `P1` or `P4`.
    BadMagic {
        /// The first two bytes, lossily as text.
        found: String,
    },
    /// A header field (width or height) is missing or not a positive decimal number.
    BadHeader {
        /// `"width"` or `"height"`.
        field: &'static str,
        /// The line (1-based) where it should be.
        line: usize,
    },
    /// A `P1` pixel is neither `0` nor `1`.
    BadPixel {
        /// The line (1-based).
        line: usize,
        /// The character found.
        found: char,
    },
    /// The pixel data ends early.
    Truncated {
        /// Where it ends: the line for `P1`, the byte offset for `P4`.
        at: usize,
        /// Pixels (for `P1`) or bytes (for `P4`) expected in all.
        expected: usize,
        /// Pixels or bytes found.
        found: usize,
    },
    /// The image is too large for a region tree.
    Image(ImageError),
}

impl fmt::Display for PbmError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PbmError::Io(e) => write!(f, "PBM: {e}"),
            PbmError::BadMagic { found } => {
                write!(f, "PBM: starts with {found:?}, expected \"P1\" or \"P4\"")
            }
            PbmError::BadHeader { field, line } => {
                write!(
                    f,
                    "PBM line {line}: {field} missing or not a positive number"
                )
            }
            PbmError::BadPixel { line, found } => {
                write!(f, "PBM line {line}: pixel is {found:?}, expected 0 or 1")
            }
            PbmError::Truncated {
                at,
                expected,
                found,
            } => write!(
                f,
                "PBM: data ends at {at} (line or byte offset) after {found} of {expected}"
            ),
            PbmError::Image(e) => write!(f, "PBM: {e}"),
        }
    }
}

impl std::error::Error for PbmError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            PbmError::Io(e) => Some(e),
            PbmError::Image(e) => Some(e),
            _ => None,
        }
    }
}

impl From<std::io::Error> for PbmError {
    fn from(e: std::io::Error) -> Self {
        PbmError::Io(e)
    }
}

/// A cursor over the bytes that counts lines and skips whitespace and comments.
struct Cursor<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: usize,
}

impl Cursor<'_> {
    fn skip_space(&mut self) {
        while let Some(&c) = self.bytes.get(self.pos) {
            match c {
                b'\n' => self.line += 1,
                b'#' => {
                    while self.bytes.get(self.pos).is_some_and(|&c| c != b'\n') {
                        self.pos += 1;
                    }
                    continue;
                }
                c if c.is_ascii_whitespace() => {}
                _ => return,
            }
            self.pos += 1;
        }
    }

    fn number(&mut self, field: &'static str) -> Result<u32, PbmError> {
        self.skip_space();
        let start = self.pos;
        while self.bytes.get(self.pos).is_some_and(u8::is_ascii_digit) {
            self.pos += 1;
        }
        let bad = PbmError::BadHeader {
            field,
            line: self.line,
        };
        let text = core::str::from_utf8(&self.bytes[start..self.pos]).map_err(|_| bad)?;
        match text.parse::<u32>() {
            Ok(n) if n > 0 => Ok(n),
            _ => Err(PbmError::BadHeader {
                field,
                line: self.line,
            }),
        }
    }
}

/// Reads a PBM image (`P1` or `P4`) into a region tree.
pub fn from_bytes(bytes: &[u8]) -> Result<ImageTree, PbmError> {
    let magic = bytes.get(..2).unwrap_or(bytes);
    let raw = match magic {
        b"P1" => false,
        b"P4" => true,
        _ => {
            return Err(PbmError::BadMagic {
                found: String::from_utf8_lossy(magic).into_owned(),
            })
        }
    };
    let mut c = Cursor {
        bytes,
        pos: 2,
        line: 1,
    };
    let w = c.number("width")?;
    let h = c.number("height")?;
    ImageTree::depth_for([w, h]).map_err(PbmError::Image)?;
    let n = w as usize * h as usize;
    let mut pixels = vec![false; n];
    if raw {
        // exactly one whitespace byte after the height
        c.pos += 1;
        let row_bytes = (w as usize).div_ceil(8);
        let expected = row_bytes * h as usize;
        let data = &bytes[c.pos.min(bytes.len())..];
        if data.len() < expected {
            return Err(PbmError::Truncated {
                at: bytes.len(),
                expected,
                found: data.len(),
            });
        }
        for y in 0..h as usize {
            let row = &data[y * row_bytes..(y + 1) * row_bytes];
            for x in 0..w as usize {
                pixels[y * w as usize + x] = (row[x / 8] >> (7 - x % 8)) & 1 == 1;
            }
        }
    } else {
        for (i, p) in pixels.iter_mut().enumerate() {
            c.skip_space();
            match c.bytes.get(c.pos) {
                Some(b'0') => {}
                Some(b'1') => *p = true,
                Some(&other) => {
                    let found = char::from(other);
                    return Err(PbmError::BadPixel {
                        line: c.line,
                        found,
                    });
                }
                None => {
                    return Err(PbmError::Truncated {
                        at: c.line,
                        expected: n,
                        found: i,
                    })
                }
            }
            c.pos += 1;
        }
    }
    ImageTree::from_bools([w, h], &pixels).map_err(PbmError::Image)
}

/// The PBM file of a region tree (cropped to its extent).
pub fn to_bytes(tree: &ImageTree, format: PbmFormat) -> Vec<u8> {
    let [w, h] = tree.extent().map(|e| e as usize);
    let pixels = tree.to_bools();
    let mut out = Vec::with_capacity(16 + pixels.len() / 8 + h);
    let magic = if format == PbmFormat::Raw { "P4" } else { "P1" };
    out.extend_from_slice(format!("{magic}\n{w} {h}\n").as_bytes());
    for row in pixels.chunks(w.max(1)) {
        match format {
            PbmFormat::Raw => {
                for byte in row.chunks(8) {
                    let b = byte
                        .iter()
                        .enumerate()
                        .fold(0u8, |acc, (i, &p)| acc | (u8::from(p) << (7 - i)));
                    out.push(b);
                }
            }
            PbmFormat::Plain => {
                for line in row.chunks(70) {
                    out.extend(line.iter().map(|&p| if p { b'1' } else { b'0' }));
                    out.push(b'\n');
                }
            }
        }
    }
    out
}

/// Reads a PBM file.
pub fn read(path: impl AsRef<Path>) -> Result<ImageTree, PbmError> {
    from_bytes(&std::fs::read(path)?)
}

/// Writes a PBM file.
pub fn write(tree: &ImageTree, path: impl AsRef<Path>, format: PbmFormat) -> Result<(), PbmError> {
    std::fs::write(path, to_bytes(tree, format))?;
    Ok(())
}
