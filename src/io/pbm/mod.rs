//! Netpbm bitmaps (PBM) for 2D region trees, read and written with no dependency: `P1` (plain,
//! ASCII `0`/`1`) and `P4` (raw, rows packed 8 pixels a byte, most significant bit first, each
//! row padded to a whole byte). `1` is black, as in the format; the first row is the image's
//! row `y = 0`.
//!
//! # The grammar read
//!
//! The Netpbm grammar, exactly: the magic number `P1` or `P4`; whitespace (space, tab, LF, VT,
//! FF, CR), at least one byte of it; the width in ASCII decimal; whitespace; the height. Comments
//! (`#` through the next LF or CR) may stand wherever header whitespace may, and end a number.
//! Then:
//! - `P4`: exactly **one** whitespace byte (or a comment, whose closing LF or CR is that byte),
//!   then exactly `ceil(width / 8) * height` bytes of raster, and nothing after it.
//! - `P1`: the pixels `0` and `1`, separated by any whitespace and comments; after the last
//!   pixel only whitespace and comments.
//!
//! One image a file: a second image, or any other data after the raster, is refused
//! ([`PbmError::TrailingData`]). Width and height are positive numbers below 2^32.
//!
//! A malformed file is a [`PbmError`] naming the **byte offset** (and the line) of what is
//! wrong, with the bytes found shown escaped and cut short. Sizes are checked against the data
//! and against [`Limits`] before anything is allocated, and the tree is built row by row
//! ([`RowBuilder`]), so memory is O(tree + one row), never the dense image.
//!
//! Writers stream rows to any [`Write`] through a buffer; an image with a zero side, which no
//! PBM can hold, is refused ([`PbmError::EmptyImage`]).
//!
//! ```
//! use orthtree::image::ImageTree;
//! use orthtree::io::pbm::{self, PbmFormat};
//! let t = ImageTree::from_boxes([10, 3], &[([2, 0], [9, 2])]).unwrap();
//! for format in [PbmFormat::Plain, PbmFormat::Raw] {
//!     let bytes = pbm::to_bytes(&t, format).unwrap();
//!     assert_eq!(pbm::from_bytes(&bytes).unwrap(), t);
//! }
//! assert!(pbm::to_bytes(&t, PbmFormat::Plain).unwrap().starts_with(b"P1\n10 3\n0011111110\n"));
//! let err = pbm::from_bytes(b"P1\n2 2\n0 1\n1 x\n").unwrap_err();
//! assert_eq!(err.to_string(), "PBM line 4, byte 13: pixel is \"x\", expected 0 or 1");
//! ```

mod error;

use super::limits::Limits;
use crate::image::{ImageTree, RowBuilder};
pub use error::PbmError;
use error::{shown, SHOWN};
use std::io::{BufWriter, Write};
use std::path::Path;

/// Which PBM variant to write.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PbmFormat {
    /// `P1`: ASCII `0` and `1`, at most 70 characters a line.
    Plain,
    /// `P4`: binary, 8 pixels a byte.
    Raw,
}

fn is_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\n' | b'\r' | 0x0b | 0x0c)
}

/// A cursor over the file that counts lines (LF, CR LF or a lone CR ends one).
struct Cursor<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: usize,
}

impl Cursor<'_> {
    fn peek(&self) -> Option<u8> {
        self.bytes.get(self.pos).copied()
    }

    /// Moves past one byte, counting line ends.
    fn bump(&mut self) {
        let b = self.bytes[self.pos];
        self.pos += 1;
        if b == b'\n' || (b == b'\r' && self.peek() != Some(b'\n')) {
            self.line += 1;
        }
    }

    /// Skips a comment starting here: `#` through the next LF or CR, inclusive.
    fn comment(&mut self) {
        while let Some(b) = self.peek() {
            self.bump();
            if b == b'\n' || b == b'\r' {
                return;
            }
        }
    }

    /// Skips whitespace and comments; the number of bytes skipped.
    fn skip_space(&mut self) -> usize {
        let start = self.pos;
        while let Some(b) = self.peek() {
            if b == b'#' {
                self.comment();
            } else if is_space(b) {
                self.bump();
            } else {
                break;
            }
        }
        self.pos - start
    }

    /// The bytes from here to the next whitespace, for a message.
    fn token(&self) -> String {
        let rest = &self.bytes[self.pos.min(self.bytes.len())..];
        let end = rest.iter().position(|&b| is_space(b)).unwrap_or(rest.len());
        shown(&rest[..end.clamp(1.min(rest.len()), SHOWN + 1)])
    }

    /// Whitespace (at least one byte) after `after`.
    fn separator(&mut self, after: &'static str) -> Result<(), PbmError> {
        if self.skip_space() == 0 {
            return Err(self.no_space(after));
        }
        Ok(())
    }

    /// The error for a byte here that is neither whitespace nor a comment, after `after`.
    fn no_space(&self, after: &'static str) -> PbmError {
        PbmError::MissingWhitespace {
            after,
            offset: self.pos,
            line: self.line,
            found: self.token(),
        }
    }

    fn number(&mut self, field: &'static str) -> Result<u32, PbmError> {
        let (offset, line) = (self.pos, self.line);
        let bad = |c: &Self| PbmError::BadHeader {
            field,
            offset,
            line,
            found: c.token(),
        };
        let mut value = 0u32;
        let mut digits = 0;
        while let Some(b) = self.peek().filter(u8::is_ascii_digit) {
            value = value
                .checked_mul(10)
                .and_then(|v| v.checked_add(u32::from(b - b'0')))
                .ok_or_else(|| bad(self))?;
            self.pos += 1;
            digits += 1;
        }
        if digits == 0 || value == 0 {
            self.pos = offset;
            return Err(bad(self));
        }
        Ok(value)
    }

    fn truncated(&self, expected: u64, found: u64, raw: bool) -> PbmError {
        PbmError::Truncated {
            offset: self.bytes.len(),
            line: self.line,
            expected,
            found,
            unit: if raw { "bytes" } else { "pixels" },
        }
    }

    fn trailing(&self) -> PbmError {
        PbmError::TrailingData {
            offset: self.pos,
            line: self.line,
            bytes: self.bytes.len() - self.pos,
            found: shown(&self.bytes[self.pos..]),
        }
    }
}

/// Reads a PBM image (`P1` or `P4`) into a region tree, within [`Limits::default`].
///
/// # Errors
/// A [`PbmError`] naming the byte offset of what is wrong, or the limit broken.
pub fn from_bytes(bytes: &[u8]) -> Result<ImageTree, PbmError> {
    from_bytes_with_limits(bytes, Limits::default())
}

/// Reads a PBM image (`P1` or `P4`) into a region tree, within `limits`.
///
/// # Errors
/// A [`PbmError`] naming the byte offset of what is wrong, or the limit broken.
///
/// # Complexity
/// O(file + n k) time for an n-node tree of depth k; O(n + width) memory.
///
/// ```
/// use orthtree::io::{pbm, Limits};
/// // 2000000000 x 2000000000 in a 30-byte file: refused before any allocation
/// let err = pbm::from_bytes_with_limits(b"P4\n2000000000 2000000000\n\0", Limits::NONE).unwrap_err();
/// assert!(err.to_string().contains("the raster ends after 1 of 500000000000000000 bytes"));
/// ```
pub fn from_bytes_with_limits(bytes: &[u8], limits: Limits) -> Result<ImageTree, PbmError> {
    limits
        .check_bytes("the file", bytes.len() as u64)
        .map_err(PbmError::Limit)?;
    let raw = match bytes.get(..2) {
        Some(b"P1") => false,
        Some(b"P4") => true,
        _ => {
            return Err(PbmError::BadMagic {
                found: shown(&bytes[..bytes.len().min(2)]),
            })
        }
    };
    let mut c = Cursor {
        bytes,
        pos: 2,
        line: 1,
    };
    c.separator("magic number")?;
    let w = c.number("width")?;
    c.separator("width")?;
    let h = c.number("height")?;
    limits.check_pixels(w, h).map_err(PbmError::Limit)?;
    ImageTree::depth_for([w, h]).map_err(PbmError::Image)?;
    let budget = limits.max_bytes.saturating_sub(bytes.len() as u64);
    // A P4 header ends with its one whitespace byte (or comment); a P1 raster may start after
    // any. At the end of the input the reader reports the raster missing.
    match c.peek() {
        Some(b'#') if raw => c.comment(),
        Some(b) if raw && is_space(b) => c.bump(),
        Some(b) if b != b'#' && !is_space(b) => return Err(c.no_space("height")),
        _ => {}
    }
    let read = if raw { read_raw } else { read_plain };
    read(&mut c, [w, h], budget)
}

fn builder(extent: [u32; 2], budget: u64) -> Result<RowBuilder, PbmError> {
    let limits = Limits {
        max_pixels: u64::MAX,
        max_bytes: budget,
    };
    let row_bytes = 8 * (extent[0] as u64).div_ceil(64);
    limits
        .check_bytes("one row", row_bytes)
        .map_err(PbmError::Limit)?;
    Ok(RowBuilder::new(extent)
        .map_err(PbmError::Image)?
        .max_bytes(budget - row_bytes))
}

fn read_raw(c: &mut Cursor<'_>, [w, h]: [u32; 2], budget: u64) -> Result<ImageTree, PbmError> {
    let row_bytes = (w as usize).div_ceil(8);
    let expected = row_bytes as u64 * u64::from(h);
    let raster = &c.bytes[c.pos..];
    if (raster.len() as u64) < expected {
        return Err(c.truncated(expected, raster.len() as u64, true));
    }
    if raster.len() as u64 > expected {
        c.pos += expected as usize;
        return Err(c.trailing());
    }
    let mut b = builder([w, h], budget)?;
    let mut words = vec![0u64; b.row_words()];
    for row in raster.chunks_exact(row_bytes) {
        unpack_row(row, &mut words);
        b.push_row(&words).map_err(PbmError::Image)?;
    }
    b.finish().map_err(PbmError::Image)
}

fn read_plain(c: &mut Cursor<'_>, [w, h]: [u32; 2], budget: u64) -> Result<ImageTree, PbmError> {
    let expected = u64::from(w) * u64::from(h);
    // every pixel takes a byte: refuse a header the data cannot back before allocating
    let rest = &c.bytes[c.pos..];
    if (rest.len() as u64) < expected {
        let found = rest.iter().filter(|&&b| b == b'0' || b == b'1').count();
        return Err(c.truncated(expected, found as u64, false));
    }
    let mut b = builder([w, h], budget)?;
    let mut words = vec![0u64; b.row_words()];
    let mut done = 0u64;
    for _ in 0..h {
        words.fill(0);
        for x in 0..w as usize {
            c.skip_space();
            match c.peek() {
                Some(b'0') => {}
                Some(b'1') => words[x / 64] |= 1 << (x % 64),
                Some(found) => {
                    return Err(PbmError::BadPixel {
                        offset: c.pos,
                        line: c.line,
                        found,
                    })
                }
                None => return Err(c.truncated(expected, done, false)),
            }
            c.pos += 1;
            done += 1;
        }
        b.push_row(&words).map_err(PbmError::Image)?;
    }
    c.skip_space();
    if c.pos < c.bytes.len() {
        return Err(c.trailing());
    }
    b.finish().map_err(PbmError::Image)
}

/// Writes the PBM file of a region tree (cropped to its extent) to `out`, row by row through a
/// buffer.
///
/// # Errors
/// [`PbmError::EmptyImage`] for a zero side (nothing is written then); [`PbmError::Io`].
///
/// # Complexity
/// O(pixels / 64 + n k) time, O(width + k) memory beyond the tree (see
/// [`ImageTree::for_each_row`]).
pub fn write_to(tree: &ImageTree, format: PbmFormat, out: impl Write) -> Result<(), PbmError> {
    let [w, h] = nonempty_extent(tree, |width, height| PbmError::EmptyImage { width, height })?;
    let mut out = BufWriter::new(out);
    let magic = if format == PbmFormat::Raw { "P4" } else { "P1" };
    write!(out, "{magic}\n{w} {h}\n")?;
    let mut line = Vec::with_capacity(71);
    tree.for_each_row(|_, words| -> Result<(), std::io::Error> {
        match format {
            PbmFormat::Raw => {
                for i in 0..(w as usize).div_ceil(8) {
                    out.write_all(&[packed_byte(words, i)])?;
                }
            }
            PbmFormat::Plain => {
                for start in (0..w as usize).step_by(70) {
                    line.clear();
                    let end = (start + 70).min(w as usize);
                    line.extend(
                        (start..end).map(|x| b'0' + ((words[x / 64] >> (x % 64)) & 1) as u8),
                    );
                    line.push(b'\n');
                    out.write_all(&line)?;
                }
            }
        }
        Ok(())
    })?;
    Ok(out.flush()?)
}

/// Sets `words` (bit `x` for pixel `x`) from `bytes` of 8 pixels each, the first in the most
/// significant bit, as a `P4` row and a 1-bit PNG row hold them.
pub(super) fn unpack_row(bytes: &[u8], words: &mut [u64]) {
    words.fill(0);
    for (i, &byte) in bytes.iter().enumerate() {
        words[i / 8] |= u64::from(byte.reverse_bits()) << (8 * (i % 8));
    }
}

/// Byte `i` of the row `words` packed as [`unpack_row`] reads it: pixels `8 i ..= 8 i + 7`, the
/// first in the most significant bit.
pub(super) fn packed_byte(words: &[u64], i: usize) -> u8 {
    ((words[i / 8] >> (8 * (i % 8))) as u8).reverse_bits()
}

/// The extent of an image to write, or `empty(width, height)` for a zero side, which neither a
/// PBM nor a PNG file can hold.
pub(super) fn nonempty_extent<E>(
    tree: &ImageTree,
    empty: impl FnOnce(u32, u32) -> E,
) -> Result<[u32; 2], E> {
    match tree.extent() {
        [w, h] if w == 0 || h == 0 => Err(empty(w, h)),
        extent => Ok(extent),
    }
}

/// The PBM file of a region tree (cropped to its extent), in memory: [`write_to`] into a `Vec`.
///
/// # Errors
/// [`PbmError::EmptyImage`] for a zero side.
pub fn to_bytes(tree: &ImageTree, format: PbmFormat) -> Result<Vec<u8>, PbmError> {
    let mut out = Vec::new();
    write_to(tree, format, &mut out)?;
    Ok(out)
}

/// Reads a PBM file within [`Limits::default`].
///
/// # Errors
/// As [`from_bytes`], and [`PbmError::Io`].
pub fn read(path: impl AsRef<Path>) -> Result<ImageTree, PbmError> {
    read_with_limits(path, Limits::default())
}

/// Reads a PBM file within `limits` (the file's size is checked before it is read).
///
/// # Errors
/// As [`from_bytes_with_limits`], and [`PbmError::Io`].
pub fn read_with_limits(path: impl AsRef<Path>, limits: Limits) -> Result<ImageTree, PbmError> {
    let path = path.as_ref();
    let size = std::fs::metadata(path)?.len();
    limits
        .check_bytes("the file", size)
        .map_err(PbmError::Limit)?;
    from_bytes_with_limits(&std::fs::read(path)?, limits)
}

/// Writes a PBM file (created only once the image is known to be writable).
///
/// # Errors
/// [`PbmError::EmptyImage`] for a zero side; [`PbmError::Io`].
pub fn write(tree: &ImageTree, path: impl AsRef<Path>, format: PbmFormat) -> Result<(), PbmError> {
    nonempty_extent(tree, |width, height| PbmError::EmptyImage { width, height })?;
    write_to(tree, format, std::fs::File::create(path)?)
}
