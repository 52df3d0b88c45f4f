//! [`SavedError`]: why bytes were refused as a saved tree, naming the field, its byte offset and
//! the limit or value expected.

use crate::error::ValidationError;
use core::fmt;

/// Why [`read_point_tree`](super::read_point_tree) or
/// [`read_point_tree_file`](super::read_point_tree_file) refused its input. Each variant names
/// what it concerns: a header field with its byte offset, the section the bytes end in, or the
/// invariant the arrays break.
///
/// ```
/// use orthtree::io::saved::{read_point_tree, SavedError};
/// let err = read_point_tree::<f64, u32, 2>(b"ORTHTREE").unwrap_err();
/// assert!(matches!(err, SavedError::Truncated { field: "version", offset: 8, .. }));
/// assert_eq!(
///     err.to_string(),
///     "saved tree: the bytes end inside `version` at byte 8: 10 bytes needed, 8 available"
/// );
/// ```
#[derive(Debug)]
#[non_exhaustive]
pub enum SavedError {
    /// The bytes end before the field or section `field`, which starts at byte `offset`: the
    /// header (or its counts) needs `needed` bytes in all, and only `available` are there.
    Truncated {
        /// The field or section cut short.
        field: &'static str,
        /// Its first byte.
        offset: u64,
        /// The bytes needed up to its end (for a section, up to the end of the whole file).
        needed: u64,
        /// The bytes there are.
        available: u64,
    },
    /// A header field does not hold what this reader expects: another magic, version, tree
    /// kind, dimension, scalar or item type than the one asked for, or a count or setting out of
    /// its range.
    Field {
        /// The field.
        field: &'static str,
        /// Its first byte.
        offset: u64,
        /// The value found.
        found: String,
        /// What was expected: the value, or the limit it broke.
        expected: String,
    },
    /// A padding or reserved byte is not zero.
    Padding {
        /// The byte.
        offset: u64,
    },
    /// Bytes follow the last section.
    Trailing {
        /// The first byte after the last section.
        offset: u64,
        /// How many bytes follow.
        extra: u64,
    },
    /// The arrays read break an invariant of the tree (its `validate`, or the settings' ranges).
    Invalid(ValidationError),
    /// The format is little-endian and this machine is not: nothing is read or written.
    BigEndianHost,
    /// Reading the file failed.
    Io(std::io::Error),
    /// A query through a memory map found `what` out of range at node (or section) `at`: the
    /// file was damaged after it was written (only the header is checked when it is mapped).
    Corrupt {
        /// What is out of range.
        what: &'static str,
        /// The node id or section number.
        at: u64,
    },
}

impl fmt::Display for SavedError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SavedError::Truncated {
                field,
                offset,
                needed,
                available,
            } => write!(
                f,
                "saved tree: the bytes end inside `{field}` at byte {offset}: \
                 {needed} bytes needed, {available} available"
            ),
            SavedError::Field {
                field,
                offset,
                found,
                expected,
            } => write!(
                f,
                "saved tree: `{field}` at byte {offset} is {found}, expected {expected}"
            ),
            SavedError::Padding { offset } => {
                write!(f, "saved tree: padding byte {offset} is not zero")
            }
            SavedError::Trailing { offset, extra } => write!(
                f,
                "saved tree: {extra} bytes follow the last section, from byte {offset}"
            ),
            SavedError::Invalid(e) => write!(f, "saved tree: {e}"),
            SavedError::BigEndianHost => write!(
                f,
                "saved tree: the format is little-endian and this machine is big-endian"
            ),
            SavedError::Io(e) => write!(f, "saved tree: {e}"),
            SavedError::Corrupt { what, at } => {
                write!(f, "saved tree: {what} out of range at node {at}")
            }
        }
    }
}

impl std::error::Error for SavedError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            SavedError::Invalid(e) => Some(e),
            SavedError::Io(e) => Some(e),
            _ => None,
        }
    }
}

impl From<ValidationError> for SavedError {
    fn from(e: ValidationError) -> Self {
        SavedError::Invalid(e)
    }
}
