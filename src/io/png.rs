//! PNG images for 2D region trees, behind the `png` feature (the `png` crate of the image-rs
//! project decodes and encodes).
//!
//! Reading accepts every PNG colour type and bit depth: palettes are expanded, 16-bit samples cut
//! to 8, colour converted to luminance (Rec. 709 weights, `0.2126 R + 0.7152 G + 0.0722 B`),
//! alpha composited over white; a pixel is **black** (set) when its luminance is below 50%
//! (`< 128` of 255). Writing gives a grey PNG, black pixels 0 and white 255, at 1 bit per pixel
//! ([`PngDepth::One`]) or 8 ([`PngDepth::Eight`]).
//!
//! # Memory
//!
//! The header's size is checked against [`Limits`] before anything is allocated, the `png`
//! crate's own limit ([`Limits::max_bytes`]) stays in force for its buffers, and the rows are
//! decoded one at a time and streamed into a [`RowBuilder`]: memory is O(tree + one row), never
//! the dense image. An interlaced (Adam7) image cannot be streamed in row order; it is gathered
//! at 1 bit per pixel first, and that buffer counts against [`Limits::max_bytes`]. Writers stream
//! rows through a buffer to any [`Write`]; an image with a zero side, which a PNG cannot hold, is
//! refused ([`PngError::EmptyImage`]).
//!
//! ```
//! use orthtree::image::ImageTree;
//! use orthtree::io::png::{self, PngDepth};
//! let t = ImageTree::from_ball([37, 20], [18.0, 10.0], 8.0).unwrap();
//! for depth in [PngDepth::One, PngDepth::Eight] {
//!     let bytes = png::to_bytes(&t, depth).unwrap();
//!     assert_eq!(png::from_bytes(&bytes).unwrap(), t);
//! }
//! assert!(png::from_bytes(b"not a png").is_err());
//! ```

use super::limits::{LimitError, Limits};
use super::pbm::{nonempty_extent, packed_byte, unpack_row};
use crate::image::{ImageError, ImageTree, RowBuilder};
use core::fmt;
use std::io::{BufRead, BufReader, BufWriter, Cursor, Seek, Write};
use std::path::Path;

/// The bit depth of a written grey PNG.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PngDepth {
    /// 1 bit per pixel (the smallest files).
    One,
    /// 8 bits per pixel (0 or 255).
    Eight,
}

/// What went wrong reading or writing a PNG.
#[derive(Debug)]
#[non_exhaustive]
pub enum PngError {
    /// The file could not be read or written.
    Io(std::io::Error),
    /// The decoder rejected the data (its message names the chunk or what is wrong).
    Decode(::png::DecodingError),
    /// The encoder failed.
    Encode(::png::EncodingError),
    /// The image breaks a [`Limits`] limit.
    Limit(LimitError),
    /// The image is too large for a region tree, or building it broke the byte limit.
    Image(ImageError),
    /// Writing an image with a zero side, which a PNG file cannot hold.
    EmptyImage {
        /// The width.
        width: u32,
        /// The height.
        height: u32,
    },
}

impl fmt::Display for PngError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PngError::Io(e) => write!(f, "PNG: {e}"),
            PngError::Decode(e) => write!(f, "PNG: {e}"),
            PngError::Encode(e) => write!(f, "PNG: {e}"),
            PngError::Limit(e) => write!(f, "PNG: {e}"),
            PngError::Image(e) => write!(f, "PNG: {e}"),
            PngError::EmptyImage { width, height } => write!(
                f,
                "PNG: cannot write a {width} x {height} image, a PNG side is at least 1"
            ),
        }
    }
}

impl std::error::Error for PngError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            PngError::Io(e) => Some(e),
            PngError::Decode(e) => Some(e),
            PngError::Encode(e) => Some(e),
            PngError::Limit(e) => Some(e),
            PngError::Image(e) => Some(e),
            PngError::EmptyImage { .. } => None,
        }
    }
}

/// Reads a PNG image within [`Limits::default`], thresholded at 50% luminance (see the module
/// docs).
///
/// # Errors
/// [`PngError::Decode`] for data the decoder refuses, [`PngError::Limit`] past a limit.
pub fn from_bytes(bytes: &[u8]) -> Result<ImageTree, PngError> {
    from_bytes_with_limits(bytes, Limits::default())
}

/// Reads a PNG image within `limits`, thresholded at 50% luminance (see the module docs).
///
/// # Errors
/// [`PngError::Decode`] for data the decoder refuses, [`PngError::Limit`] past a limit.
///
/// # Complexity
/// O(pixels + n k) time for an n-node tree of depth k; O(n + width) memory (plus the 1-bit image
/// for interlaced files).
pub fn from_bytes_with_limits(bytes: &[u8], limits: Limits) -> Result<ImageTree, PngError> {
    limits
        .check_bytes("the file", bytes.len() as u64)
        .map_err(PngError::Limit)?;
    read_from(Cursor::new(bytes), limits)
}

/// Whether each pixel of a decoded row (8-bit samples, `channels` of them a pixel) is black;
/// sets bit `x` of `words` for black pixel `x`.
fn threshold(data: &[u8], channels: usize, words: &mut [u64]) {
    words.fill(0);
    for (x, p) in data.chunks_exact(channels).enumerate() {
        let black = match channels {
            1 => p[0] < 128,
            2 => over_white(f64::from(p[0]), f64::from(p[1])) < 128.0,
            _ => {
                let lum =
                    0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2]);
                // Opaque without an alpha channel (a pixel of 3 samples).
                let alpha = p.get(3).map_or(255.0, |&a| f64::from(a));
                over_white(lum, alpha) < 128.0
            }
        };
        words[x / 64] |= u64::from(black) << (x % 64);
    }
}

fn over_white(lum: f64, alpha: f64) -> f64 {
    (lum * alpha + 255.0 * (255.0 - alpha)) / 255.0
}

fn read_from<R: BufRead + Seek>(input: R, limits: Limits) -> Result<ImageTree, PngError> {
    let png_limits = ::png::Limits {
        bytes: usize::try_from(limits.max_bytes).unwrap_or(usize::MAX),
    };
    let mut decoder = ::png::Decoder::new_with_limits(input, png_limits);
    decoder.set_transformations(::png::Transformations::EXPAND | ::png::Transformations::STRIP_16);
    let mut reader = decoder.read_info().map_err(PngError::Decode)?;
    let (w, h) = reader.info().size();
    let interlaced = reader.info().interlaced;
    limits.check_pixels(w, h).map_err(PngError::Limit)?;
    ImageTree::depth_for([w, h]).map_err(PngError::Image)?;
    let channels = reader.output_color_type().0.samples();
    let line = reader.output_line_size(w).unwrap_or(usize::MAX) as u64;
    let row_words = 8 * (w as u64).div_ceil(64);
    // The 1-bit image gathered from the passes, for an interlaced image only.
    let gathered = u64::from(interlaced) * (w as u64).div_ceil(8) * u64::from(h);
    let mut used = 0u64;
    for (what, bytes) in [
        ("one decoded row", line),
        ("one bit-packed row", row_words),
        ("the deinterlaced 1-bit image", gathered),
    ] {
        used = used.saturating_add(bytes);
        limits.check_bytes(what, used).map_err(PngError::Limit)?;
    }
    let mut b = RowBuilder::new([w, h])
        .map_err(PngError::Image)?
        .max_bytes(limits.max_bytes - used);
    let mut words = vec![0u64; b.row_words()];
    if !interlaced {
        while let Some(row) = reader.next_row().map_err(PngError::Decode)? {
            threshold(row.data(), channels, &mut words);
            b.push_row(&words).map_err(PngError::Image)?;
        }
        return b.finish().map_err(PngError::Image);
    }
    let stride = (w as usize).div_ceil(8);
    let mut image = vec![0u8; gathered as usize];
    let mut bits = Vec::with_capacity(stride);
    while let Some(row) = reader.next_interlaced_row().map_err(PngError::Decode)? {
        let ::png::InterlaceInfo::Adam7(info) = *row.interlace() else {
            continue;
        };
        let data = row.data();
        threshold(data, channels, &mut words);
        let samples = data.len() / channels;
        bits.clear();
        bits.extend((0..samples.div_ceil(8)).map(|i| packed_byte(&words, i)));
        ::png::expand_interlaced_row(&mut image, stride, &bits, &info, 1);
    }
    for row in image.chunks_exact(stride) {
        unpack_row(row, &mut words);
        b.push_row(&words).map_err(PngError::Image)?;
    }
    b.finish().map_err(PngError::Image)
}

/// Writes a grey PNG of a region tree (cropped to its extent) to `out`, black pixels 0 and white
/// 255, row by row through a buffer.
///
/// # Errors
/// [`PngError::EmptyImage`] for a zero side (nothing is written then); [`PngError::Encode`].
///
/// # Complexity
/// O(pixels + n k) time, O(width + k) memory beyond the tree and the encoder's buffers.
pub fn write_to(tree: &ImageTree, depth: PngDepth, out: impl Write) -> Result<(), PngError> {
    let [w, h] = nonempty_extent(tree, |width, height| PngError::EmptyImage { width, height })?;
    let mut encoder = ::png::Encoder::new(BufWriter::new(out), w, h);
    encoder.set_color(::png::ColorType::Grayscale);
    encoder.set_depth(match depth {
        PngDepth::One => ::png::BitDepth::One,
        PngDepth::Eight => ::png::BitDepth::Eight,
    });
    let mut writer = encoder.write_header().map_err(PngError::Encode)?;
    let mut stream = writer.stream_writer().map_err(PngError::Encode)?;
    let mut line = Vec::new();
    tree.for_each_row(|_, words| -> Result<(), std::io::Error> {
        line.clear();
        match depth {
            PngDepth::One => {
                line.extend((0..(w as usize).div_ceil(8)).map(|i| !packed_byte(words, i)))
            }
            PngDepth::Eight => {
                line.extend((0..w as usize).map(|x| 255 * (!(words[x / 64] >> (x % 64)) & 1) as u8))
            }
        }
        stream.write_all(&line)
    })
    .map_err(PngError::Io)?;
    stream.finish().map_err(PngError::Encode)?;
    writer.finish().map_err(PngError::Encode)
}

/// A grey PNG of a region tree (cropped to its extent), in memory: [`write_to`] into a `Vec`.
///
/// # Errors
/// [`PngError::EmptyImage`] for a zero side; [`PngError::Encode`].
pub fn to_bytes(tree: &ImageTree, depth: PngDepth) -> Result<Vec<u8>, PngError> {
    let mut out = Vec::new();
    write_to(tree, depth, &mut out)?;
    Ok(out)
}

/// Reads a PNG file within [`Limits::default`], streaming it from the disk.
///
/// # Errors
/// As [`from_bytes`], and [`PngError::Io`].
pub fn read(path: impl AsRef<Path>) -> Result<ImageTree, PngError> {
    read_with_limits(path, Limits::default())
}

/// Reads a PNG file within `limits`, streaming it from the disk.
///
/// # Errors
/// As [`from_bytes_with_limits`], and [`PngError::Io`].
pub fn read_with_limits(path: impl AsRef<Path>, limits: Limits) -> Result<ImageTree, PngError> {
    let file = std::fs::File::open(path).map_err(PngError::Io)?;
    read_from(BufReader::new(file), limits)
}

/// Writes a grey PNG file (created only once the image is known to be writable).
///
/// # Errors
/// [`PngError::EmptyImage`] for a zero side; [`PngError::Io`], [`PngError::Encode`].
pub fn write(tree: &ImageTree, path: impl AsRef<Path>, depth: PngDepth) -> Result<(), PngError> {
    nonempty_extent(tree, |width, height| PngError::EmptyImage { width, height })?;
    write_to(
        tree,
        depth,
        std::fs::File::create(path).map_err(PngError::Io)?,
    )
}
