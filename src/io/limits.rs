//! Resource limits for the image readers ([`pbm`](super::pbm), and `png` behind its feature):
//! how many pixels an image may have and how many bytes a reader may hold, checked against the
//! header before anything is allocated, and while the region tree grows.
//!
//! ```
//! use orthtree::io::{pbm, Limits, LimitError};
//! let limits = Limits { max_pixels: 100, ..Limits::default() };
//! let err = pbm::from_bytes_with_limits(b"P4 20 20 ", limits).unwrap_err();
//! assert_eq!(err.to_string(), "PBM: the image has 400 pixels (20 x 20); the limit is 100 pixels");
//! ```

use core::fmt;

/// What a reader may use: checked against the header before any allocation, then against the
/// region tree as it is built. [`Limits::default`] reads any image of up to 2^32 pixels (65536 x
/// 65536) while holding at most 1 GiB.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Limits {
    /// The most pixels (width x height) an image may have.
    pub max_pixels: u64,
    /// The most bytes a reader may hold at once: the file when read whole, decoded rows (a
    /// whole 1-bit image for interlaced PNG), and the region tree under construction.
    pub max_bytes: u64,
}

impl Limits {
    /// The default number of pixels: 2^32.
    pub const DEFAULT_MAX_PIXELS: u64 = 1 << 32;
    /// The default number of bytes: 2^30 (1 GiB).
    pub const DEFAULT_MAX_BYTES: u64 = 1 << 30;

    /// No limits beyond the machine's.
    pub const NONE: Limits = Limits {
        max_pixels: u64::MAX,
        max_bytes: u64::MAX,
    };

    /// [`LimitError`] if a `width x height` image has more pixels than allowed.
    ///
    /// # Errors
    /// [`LimitError::Pixels`] naming the size and the limit.
    pub fn check_pixels(&self, width: u32, height: u32) -> Result<(), LimitError> {
        let pixels = u64::from(width) * u64::from(height);
        if pixels > self.max_pixels {
            return Err(LimitError::Pixels {
                width,
                height,
                limit: self.max_pixels,
            });
        }
        Ok(())
    }

    /// [`LimitError`] if holding `bytes` bytes for `what` exceeds the byte limit.
    ///
    /// # Errors
    /// [`LimitError::Bytes`] naming the size and the limit.
    pub fn check_bytes(&self, what: &'static str, bytes: u64) -> Result<(), LimitError> {
        if bytes > self.max_bytes {
            return Err(LimitError::Bytes {
                what,
                bytes,
                limit: self.max_bytes,
            });
        }
        Ok(())
    }
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_pixels: Self::DEFAULT_MAX_PIXELS,
            max_bytes: Self::DEFAULT_MAX_BYTES,
        }
    }
}

/// A limit of [`Limits`] that an input would break.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum LimitError {
    /// The image has more pixels than [`Limits::max_pixels`].
    Pixels {
        /// The width asked for.
        width: u32,
        /// The height asked for.
        height: u32,
        /// The limit.
        limit: u64,
    },
    /// Reading would hold more bytes than [`Limits::max_bytes`].
    Bytes {
        /// What the bytes are for (`"the file"`, `"decoded rows"`, `"the region tree"`).
        what: &'static str,
        /// The bytes asked for.
        bytes: u64,
        /// The limit.
        limit: u64,
    },
}

impl fmt::Display for LimitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LimitError::Pixels {
                width,
                height,
                limit,
            } => write!(
                f,
                "the image has {} pixels ({width} x {height}); the limit is {limit} pixels",
                u64::from(*width) * u64::from(*height)
            ),
            LimitError::Bytes { what, bytes, limit } => {
                write!(f, "{what} needs {bytes} bytes; the limit is {limit} bytes")
            }
        }
    }
}

impl std::error::Error for LimitError {}
