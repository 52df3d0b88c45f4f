//! The crate's error types for input and invariants: [`Error`], every way the crate refuses
//! its caller's input, each naming the offending item; [`ValidationError`] and [`Invariant`],
//! what a tree's `validate` found broken. (Queries refuse with
//! [`QueryError`](crate::QueryError).)

use crate::geom::{Aabb, AabbError, Checked, Fault, FloatBits};

/// An input the crate refuses (points to build or insert, builder settings), naming the
/// offending point, axis and value. Queries have their own error,
/// [`QueryError`](crate::QueryError); the two share no variant.
///
/// ```
/// use orthtree::{Error, Quadtree};
/// let err = Quadtree::new(&[([0.0, 0.0], 'a'), ([f64::NAN, 1.0], 'b')]).unwrap_err();
/// assert!(matches!(err, Error::NonFiniteCoordinate { index: 1, axis: 0, .. }));
/// assert_eq!(err, err.clone()); // a NaN payload is compared by its bits
/// assert_eq!(err.to_string(), "point 1: coordinate NaN on axis 0 is not finite");
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Error {
    /// Input point `index` has NaN or an infinity on `axis`.
    NonFiniteCoordinate {
        /// Position of the point in the input.
        index: usize,
        /// The axis holding the bad coordinate.
        axis: usize,
        /// The bad coordinate (compared by its bits: NaN equals itself here).
        value: FloatBits,
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
        value: FloatBits,
        /// The root box's interval on that axis.
        interval: (FloatBits, FloatBits),
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
    /// `Ok` when a tree can index `len` points (fewer than 2^32 - 1), else
    /// [`Error::TooManyPoints`] naming `len`.
    pub(crate) fn check_count(len: usize) -> Result<(), Error> {
        if len >= u32::MAX as usize {
            return Err(Error::TooManyPoints { len });
        }
        Ok(())
    }

    /// The point check of input point `index`: `point` in `f64` when it is finite, exact and
    /// (when `domain` is given) inside the closed box; else the error naming the first bad
    /// axis.
    pub(crate) fn check_input<S: crate::Scalar, const D: usize>(
        point: &[S; D],
        domain: Option<&Aabb<f64, D>>,
        index: usize,
    ) -> Result<[f64; D], Error> {
        let fault = |(axis, fault)| match fault {
            Fault::NotFinite(v) => Error::NonFiniteCoordinate {
                index,
                axis,
                value: v.into(),
            },
            Fault::Inexact(value) => Error::InexactCoordinate { index, axis, value },
        };
        let Some(domain) = domain else {
            return crate::geom::exact_point(point).map_err(fault);
        };
        match crate::geom::check_point(point, domain).map_err(fault)? {
            Checked::Inside(p) => Ok(p),
            Checked::Outside(axis, p) => Err(Error::OutsideRootBox {
                index,
                axis,
                value: p[axis].into(),
                interval: (domain.min[axis].into(), domain.max[axis].into()),
            }),
        }
    }
}

impl core::fmt::Display for Error {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Error::NonFiniteCoordinate { index, axis, value } => write!(
                f,
                "point {index}: coordinate {value} on axis {axis} is not finite"
            ),
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
            Error::InvalidRootBox(e) => write!(f, "invalid root box: {e}"),
            Error::ZeroBucketSize => write!(f, "the bucket size must be at least 1"),
            Error::MaxDepthTooLarge { requested, limit } => write!(
                f,
                "maximum depth {requested} exceeds {limit}, the deepest level of this dimension"
            ),
            Error::TooManyPoints { len } => write!(
                f,
                "{len} points exceed the {} a tree can index",
                u32::MAX - 1
            ),
        }
    }
}

impl std::error::Error for Error {}

impl From<AabbError> for Error {
    fn from(e: AabbError) -> Self {
        Error::InvalidRootBox(e)
    }
}

/// The invariants a point tree's `validate` checks, each named by a [`ValidationError`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Invariant {
    /// The node arena itself: links, cells, the free list ([`crate::Tree::validate`] and the
    /// compressed trees' arenas).
    Topology,
    /// The arrays kept side by side (points, items, keys, slots, runs) have equal lengths.
    Lengths,
    /// A node's count or run equals the sum of its children's; the root holds every point.
    Counts,
    /// Every point lies in the tree's domain, with coordinates `f64` holds exactly.
    InDomain,
    /// Every point lies in its leaf's cell, in Morton order where the tree keeps one.
    InLeaf,
    /// A leaf holds more than the bucket size only at the maximum depth.
    LeafSize,
    /// An internal node holds more than the bucket size (unless balance split it).
    SplitNeeded,
    /// A tree balance was asked for is still balanced.
    Balanced,
    /// Slot, chunk and leaf links point at each other and never at two owners.
    Links,
    /// A skip quadtree's level holds the sample of the level below and links down to it.
    SkipLevels,
    /// The settings a tree keeps are in range: bucket size at least 1, maximum depth at most
    /// [`crate::Cell::MAX_LEVEL`], a finite root cube holding a finite domain (checked when a
    /// tree is read back from bytes).
    Settings,
}

impl Invariant {
    fn describe(self) -> &'static str {
        match self {
            Invariant::Topology => "the node arena is broken",
            Invariant::Lengths => "arrays kept side by side differ in length",
            Invariant::Counts => "a count or run differs from its children's",
            Invariant::InDomain => "a point lies outside the domain",
            Invariant::InLeaf => "a point is out of place",
            Invariant::LeafSize => "a leaf above the maximum depth holds more than the bucket size",
            Invariant::SplitNeeded => "a node was split holding no more than the bucket size",
            Invariant::Balanced => "the tree is not balanced after balance()",
            Invariant::Links => "links do not point back",
            Invariant::SkipLevels => "a skip level does not match the level below",
            Invariant::Settings => "a setting is out of range",
        }
    }
}

/// A broken invariant found by a tree's `validate` ([`PointSet::validate`](crate::query::PointSet::validate)):
/// which invariant, at which node and point when one is to blame, with the figures found.
///
/// ```
/// use orthtree::error::{Invariant, ValidationError};
/// let e = ValidationError::new(Invariant::LeafSize).node(7u32).detail("holds 9");
/// assert_eq!((e.invariant, e.node, e.point), (Invariant::LeafSize, Some(7), None));
/// assert_eq!(
///     e.to_string(),
///     "a leaf above the maximum depth holds more than the bucket size (node 7): holds 9"
/// );
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ValidationError {
    /// The invariant broken.
    pub invariant: Invariant,
    /// The node to blame (the tree's own node number), when there is one.
    pub node: Option<u64>,
    /// The point to blame (its position in the tree's storage, or its slot), when there is one.
    pub point: Option<usize>,
    /// What was found, in words (counts, the level of a skip quadtree); may be empty.
    pub detail: String,
}

impl ValidationError {
    /// A broken `invariant`, with no node, point or detail yet.
    pub fn new(invariant: Invariant) -> Self {
        ValidationError {
            invariant,
            node: None,
            point: None,
            detail: String::new(),
        }
    }

    /// The same, blaming `node`.
    pub fn node(mut self, node: impl Into<u64>) -> Self {
        self.node = Some(node.into());
        self
    }

    /// The same, blaming `point`.
    pub fn point(mut self, point: usize) -> Self {
        self.point = Some(point);
        self
    }

    /// The same, with what was found.
    pub fn detail(mut self, detail: impl Into<String>) -> Self {
        self.detail = detail.into();
        self
    }
}

impl core::fmt::Display for ValidationError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.invariant.describe())?;
        match (self.node, self.point) {
            (Some(n), Some(p)) => write!(f, " (node {n}, point {p})")?,
            (Some(n), None) => write!(f, " (node {n})")?,
            (None, Some(p)) => write!(f, " (point {p})")?,
            (None, None) => {}
        }
        if !self.detail.is_empty() {
            write!(f, ": {}", self.detail)?;
        }
        Ok(())
    }
}

impl std::error::Error for ValidationError {}
