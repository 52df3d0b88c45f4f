//! PNG images for 2D region trees, behind the `png` feature (the `png` crate of the image-rs
//! project decodes and encodes).
//!
//! Reading accepts every PNG colour type and bit depth: palettes are expanded, 16-bit samples cut
//! to 8, colour converted to luminance (Rec. 709 weights, `0.2126 R + 0.7152 G + 0.0722 B`),
//! alpha composited over white; a pixel is **black** (set) when its luminance is below 50%
//! (`< 128` of 255). Writing gives a grey PNG, black pixels 0 and white 255, at 1 bit per pixel
//! ([`PngDepth::One`]) or 8 ([`PngDepth::Eight`]).
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

use crate::image::{ImageError, ImageTree};
use core::fmt;
use std::io::Cursor;
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
    /// The image is too large for a region tree.
    Image(ImageError),
}

impl fmt::Display for PngError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PngError::Io(e) => write!(f, "PNG: {e}"),
            PngError::Decode(e) => write!(f, "PNG: {e}"),
            PngError::Encode(e) => write!(f, "PNG: {e}"),
            PngError::Image(e) => write!(f, "PNG: {e}"),
        }
    }
}

impl std::error::Error for PngError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            PngError::Io(e) => Some(e),
            PngError::Decode(e) => Some(e),
            PngError::Encode(e) => Some(e),
            PngError::Image(e) => Some(e),
        }
    }
}

/// Reads a PNG image, thresholded at 50% luminance (see the module docs).
pub fn from_bytes(bytes: &[u8]) -> Result<ImageTree, PngError> {
    use ::png::ColorType;
    let mut decoder = ::png::Decoder::new(Cursor::new(bytes));
    decoder.set_transformations(::png::Transformations::EXPAND | ::png::Transformations::STRIP_16);
    let mut reader = decoder.read_info().map_err(PngError::Decode)?;
    let size = reader.output_buffer_size().ok_or_else(|| {
        PngError::Image(ImageError::TooLarge {
            extent: vec![reader.info().width, reader.info().height],
            max_depth: ImageTree::MAX_DEPTH,
        })
    })?;
    let mut buf = vec![0; size];
    let info = reader.next_frame(&mut buf).map_err(PngError::Decode)?;
    let (w, h) = (info.width as usize, info.height as usize);
    ImageTree::depth_for([info.width, info.height]).map_err(PngError::Image)?;
    let channels = match info.color_type {
        ColorType::Grayscale => 1,
        ColorType::GrayscaleAlpha => 2,
        ColorType::Rgb => 3,
        // palettes are expanded to RGB(A)
        ColorType::Rgba | ColorType::Indexed => 4,
    };
    let mut pixels = Vec::with_capacity(w * h);
    for y in 0..h {
        let row = &buf[y * info.line_size..];
        for x in 0..w {
            let p = &row[x * channels..(x + 1) * channels];
            let (lum, alpha) = match channels {
                1 => (f64::from(p[0]), 255.0),
                2 => (f64::from(p[0]), f64::from(p[1])),
                _ => (
                    0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2]),
                    if channels == 4 {
                        f64::from(p[3])
                    } else {
                        255.0
                    },
                ),
            };
            let over_white = (lum * alpha + 255.0 * (255.0 - alpha)) / 255.0;
            pixels.push(over_white < 128.0);
        }
    }
    ImageTree::from_bools([info.width, info.height], &pixels).map_err(PngError::Image)
}

/// A grey PNG of a region tree (cropped to its extent): black pixels 0, white 255.
pub fn to_bytes(tree: &ImageTree, depth: PngDepth) -> Result<Vec<u8>, PngError> {
    let [w, h] = tree.extent();
    let pixels = tree.to_bools();
    let mut data = Vec::new();
    for row in pixels.chunks((w as usize).max(1)) {
        match depth {
            PngDepth::One => data.extend(row.chunks(8).map(|byte| {
                byte.iter()
                    .enumerate()
                    .fold(0u8, |acc, (i, &p)| acc | (u8::from(!p) << (7 - i)))
            })),
            PngDepth::Eight => data.extend(row.iter().map(|&p| if p { 0 } else { 255 })),
        }
    }
    let mut out = Vec::new();
    {
        let mut encoder = ::png::Encoder::new(&mut out, w, h);
        encoder.set_color(::png::ColorType::Grayscale);
        encoder.set_depth(match depth {
            PngDepth::One => ::png::BitDepth::One,
            PngDepth::Eight => ::png::BitDepth::Eight,
        });
        let mut writer = encoder.write_header().map_err(PngError::Encode)?;
        writer.write_image_data(&data).map_err(PngError::Encode)?;
        writer.finish().map_err(PngError::Encode)?;
    }
    Ok(out)
}

/// Reads a PNG file.
pub fn read(path: impl AsRef<Path>) -> Result<ImageTree, PngError> {
    from_bytes(&std::fs::read(path).map_err(PngError::Io)?)
}

/// Writes a grey PNG file.
pub fn write(tree: &ImageTree, path: impl AsRef<Path>, depth: PngDepth) -> Result<(), PngError> {
    std::fs::write(path, to_bytes(tree, depth)?).map_err(PngError::Io)
}
