//! [`Error`]: every way the crate refuses its caller's input, each naming the offending item.

use crate::geom::AabbError;

/// An input the crate refuses, naming the offending point, axis and value.
///
/// ```
/// use orthtree::{Error, Quadtree};
/// let err = Quadtree::new(&[([0.0, 0.0], 'a'), ([f64::NAN, 1.0], 'b')]).unwrap_err();
/// assert!(matches!(err, Error::NonFiniteCoordinate { index: 1, axis: 0, .. }));
/// assert_eq!(err.to_string(), "point 1: coordinate NaN on axis 0 is not finite");
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// Input point `index` has NaN or an infinity on `axis`.
    NonFiniteCoordinate {
        /// Position of the point in the input.
        index: usize,
        /// The axis holding the bad coordinate.
        axis: usize,
        /// The bad coordinate.
        value: f64,
    },
    /// Input point `index` has, on `axis`, an integer that `f64` cannot hold exactly (a 64-bit
    /// integer beyond 2^53 that is not a multiple of the `f64` spacing there; see
    /// [`crate::Scalar::converts_exactly`]).
    InexactCoordinate {
        /// Position of the point in the input.
        index: usize,
        /// The axis holding the bad coordinate.
        axis: usize,
        /// The coordinate.
        value: i128,
    },
    /// Input point `index` lies outside the root box on `axis`.
    OutsideRootBox {
        /// Position of the point in the input.
        index: usize,
        /// The first axis on which it lies outside.
        axis: usize,
        /// Its coordinate there.
        value: f64,
        /// The root box's interval on that axis.
        interval: (f64, f64),
    },
    /// A query point has NaN or an infinity on `axis`.
    QueryNotFinite {
        /// The axis holding the bad coordinate.
        axis: usize,
        /// The bad coordinate.
        value: f64,
    },
    /// A query point has, on `axis`, an integer that `f64` cannot hold exactly.
    QueryInexact {
        /// The axis holding the bad coordinate.
        axis: usize,
        /// The coordinate.
        value: i128,
    },
    /// A query point lies outside the root box on `axis`.
    QueryOutsideRootBox {
        /// The first axis on which it lies outside.
        axis: usize,
        /// Its coordinate there.
        value: f64,
        /// The root box's interval on that axis.
        interval: (f64, f64),
    },
    /// The root box given to the builder is not a valid box.
    InvalidRootBox(AabbError),
    /// The bucket size must be at least 1.
    ZeroBucketSize,
    /// The requested maximum depth exceeds what Morton keys of this dimension can address.
    MaxDepthTooLarge {
        /// The depth asked for.
        requested: u8,
        /// The largest depth possible, [`crate::Cell::MAX_LEVEL`].
        limit: u8,
    },
    /// More points than a `u32` can index.
    TooManyPoints {
        /// The number of points given.
        len: usize,
    },
}

/// The end of every message about an integer coordinate `f64` cannot hold.
pub(crate) const INEXACT: &str =
    "has no exact f64 (beyond 2^53 only multiples of the f64 spacing are exact)";

impl Error {
    /// The error for input point `index` failing the point check on `axis`.
    pub(crate) fn bad_input(index: usize, axis: usize, fault: crate::geom::Fault) -> Self {
        match fault {
            crate::geom::Fault::NotFinite(value) => {
                Error::NonFiniteCoordinate { index, axis, value }
            }
            crate::geom::Fault::Inexact(value) => Error::InexactCoordinate { index, axis, value },
        }
    }

    /// The error for a query point failing the point check on `axis`.
    pub(crate) fn bad_query(axis: usize, fault: crate::geom::Fault) -> Self {
        match fault {
            crate::geom::Fault::NotFinite(value) => Error::QueryNotFinite { axis, value },
            crate::geom::Fault::Inexact(value) => Error::QueryInexact { axis, value },
        }
    }
}

impl core::fmt::Display for Error {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Error::NonFiniteCoordinate { index, axis, value } => {
                write!(
                    f,
                    "point {index}: coordinate {value} on axis {axis} is not finite"
                )
            }
            Error::InexactCoordinate { index, axis, value } => write!(
                f,
                "point {index}: coordinate {value} on axis {axis} {INEXACT}"
            ),
            Error::OutsideRootBox {
                index,
                axis,
                value,
                interval: (lo, hi),
            } => write!(
                f,
                "point {index}: coordinate {value} on axis {axis} lies outside the root box's \
                 interval [{lo}, {hi}]"
            ),
            Error::QueryNotFinite { axis, value } => {
                write!(
                    f,
                    "query point: coordinate {value} on axis {axis} is not finite"
                )
            }
            Error::QueryInexact { axis, value } => {
                write!(
                    f,
                    "query point: coordinate {value} on axis {axis} {INEXACT}"
                )
            }
            Error::QueryOutsideRootBox {
                axis,
                value,
                interval: (lo, hi),
            } => write!(
                f,
                "query point: coordinate {value} on axis {axis} lies outside the root box's \
                 interval [{lo}, {hi}]"
            ),
            Error::InvalidRootBox(e) => write!(f, "invalid root box: {e}"),
            Error::ZeroBucketSize => write!(f, "the bucket size must be at least 1"),
            Error::MaxDepthTooLarge { requested, limit } => write!(
                f,
                "maximum depth {requested} exceeds {limit}, the deepest level of this dimension"
            ),
            Error::TooManyPoints { len } => {
                write!(
                    f,
                    "{len} points exceed the {} a tree can index",
                    u32::MAX - 1
                )
            }
        }
    }
}

impl std::error::Error for Error {}

impl From<AabbError> for Error {
    fn from(e: AabbError) -> Self {
        Error::InvalidRootBox(e)
    }
}

/// A broken invariant found by a tree's `validate` ([`PointSet::validate`](crate::query::PointSet::validate)).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ValidationError(pub String);

impl core::fmt::Display for ValidationError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ValidationError {}
