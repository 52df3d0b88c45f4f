//! Queries on point trees: range queries over any [`Region`] (boxes, balls, half-spaces, your own
//! shapes), nearest and k-nearest neighbours under any [`Metric`], and a lazy best-first nearest
//! iterator; and the joins of two trees or of one with itself ([`Joins`]: all k-nearest
//! neighbours, pairs within a radius, counts over radii, sparse distance matrices).
//!
//! Algorithms: the range query of exercise 14.13 of de Berg, Cheong, van Kreveld and Overmars,
//! *Computational Geometry* (chapter 14): descend into the children of every node whose cell
//! crosses the region's boundary, report the whole run of a cell inside it untested, skip a cell
//! outside it (see [`range`] for the worst-case analysis). Nearest neighbours: depth-first
//! branch and bound with a bounded candidate list, children visited nearest box first (Arya and
//! Mount's priority search in its depth-first form); the iterator is Hjaltason and Samet's
//! best-first incremental search ("Distance browsing in spatial databases", 1999).
//!
//! Every engine works on a [`SpatialIndex`]: anything with a root, children, closed cell boxes and
//! a contiguous run of points per node. Every tree implements it next to its own code, and
//! [`PointSet`], whose provided methods are the queries users call, on top of it: the queries
//! are written once, in this module, for every tree.
//!
//! Coordinates are compared as `f64` ([`Scalar::to_f64`](crate::Scalar::to_f64)), exactly: a query
//! point, ball centre or box corner that `f64` cannot hold (a 64-bit integer such as 2^53 + 1) is
//! refused with [`QueryError::Inexact`], as the trees refuse such points. Every region's cell test
//! is computed so that it agrees with its point test: a query returns exactly the points its
//! region's [`Region::contains`] accepts. Distances are `f64` arithmetic and round; squared
//! Euclidean distances beyond `f64::MAX` (points more than about 1.3e154 apart) are infinite and
//! tie, broken by index.

#[cfg(feature = "rayon")]
mod batch;
mod best_within;
mod index;
mod join;
mod knn;
mod knn_images;
mod location;
mod metric;
mod nearest_iter;
mod ordered_batch;
mod periodic;
mod periodic_metric;
mod periodic_queries;
mod periodic_region;
pub(crate) mod point_set;
mod point_set_mut;
pub mod range;
mod region;

use crate::geom::FloatBits;
#[cfg(feature = "rayon")]
pub use batch::ParallelQueries;
pub(crate) use index::nearest_child_by_boxes;
#[cfg(test)]
pub(crate) use index::OneLeaf;
pub use index::SpatialIndex;
#[cfg(test)]
pub(crate) use join::assert_copies_agree;
pub use join::{Boundary, CsrDistances, Joins, KnnTable, PeriodicJoins, SparseDistances};
#[cfg(feature = "rayon")]
pub use join::{ParallelJoins, ParallelPeriodicJoins};
#[cfg(feature = "mpi")]
pub(crate) use knn::k_nearest;
pub use knn::Neighbor;
pub use location::Location;
pub use metric::{Chebyshev, Manhattan, Metric, SquaredEuclidean};
pub use ordered_batch::{BatchError, BatchQueries};
pub use periodic::{OutsidePoints, PeriodicError, Torus};
pub use periodic_metric::{AxisMetric, MinImage};
pub use periodic_queries::PeriodicQueries;
pub use periodic_region::{PeriodicBall, PeriodicBox};
pub use point_set::{Payload, PointSet, PositionSlots};
pub use point_set_mut::{InsertError, PointSetMut};
pub use range::QueryStats;
pub use region::{Ball, HalfSpace, Region, Relation};

/// A query the crate refuses, naming what is wrong with it.
///
/// ```
/// use orthtree::prelude::*;
/// use orthtree::{query::QueryError, Quadtree};
/// let t = Quadtree::new(&[([0.0, 0.0], 'a')]).unwrap();
/// assert_eq!(
///     t.nearest(&[f64::NAN, 0.0]).unwrap_err(),
///     QueryError::NotFinite { axis: 0, value: f64::NAN.into() }
/// );
/// assert!(matches!(t.in_ball(&[0.0, 0.0], -1.0), Err(QueryError::InvalidRadius { .. })));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum QueryError {
    /// A query point or ball centre has NaN or an infinity on `axis`.
    NotFinite {
        /// The axis holding the bad coordinate.
        axis: usize,
        /// The bad coordinate (compare its bits: NaN is not equal to itself).
        value: FloatBits,
    },
    /// A query point, ball centre or box corner has, on `axis`, an integer that `f64` cannot
    /// hold exactly ([`Scalar::converts_exactly`](crate::Scalar::converts_exactly)).
    Inexact {
        /// The axis holding the bad coordinate.
        axis: usize,
        /// The coordinate.
        value: i128,
    },
    /// A box bound on `axis` is NaN (infinite bounds are allowed).
    NanBound {
        /// The axis holding the bad bound.
        axis: usize,
    },
    /// A ball radius that is negative or NaN.
    InvalidRadius {
        /// The radius given.
        radius: FloatBits,
    },
    /// A maximum distance that is negative or NaN.
    InvalidMaxDistance {
        /// The maximum distance given.
        value: FloatBits,
    },
    /// A half-space normal with NaN or an infinity on `axis`.
    InvalidNormal {
        /// The axis holding the bad component.
        axis: usize,
    },
    /// A half-space offset that is NaN.
    NanOffset,
    /// An approximation factor `eps` (for a (1 + eps)-approximate search) that is negative or
    /// NaN.
    InvalidEpsilon {
        /// The `eps` given.
        value: FloatBits,
    },
    /// A list of radii that must be in non-decreasing order has `radii[index] < radii[index - 1]`.
    UnsortedRadii {
        /// The first position where the order breaks.
        index: usize,
    },
}

impl core::fmt::Display for QueryError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            QueryError::NotFinite { axis, value } => write!(
                f,
                "query coordinate {} on axis {axis} is not finite",
                value.get()
            ),
            QueryError::Inexact { axis, value } => write!(
                f,
                "query coordinate {value} on axis {axis} {}",
                crate::error::INEXACT
            ),
            QueryError::NanBound { axis } => write!(f, "box bound on axis {axis} is NaN"),
            QueryError::InvalidRadius { radius } => {
                write!(f, "radius {} is negative or NaN", radius.get())
            }
            QueryError::InvalidMaxDistance { value } => {
                write!(f, "maximum distance {} is negative or NaN", value.get())
            }
            QueryError::InvalidNormal { axis } => {
                write!(f, "half-space normal on axis {axis} is not finite")
            }
            QueryError::NanOffset => f.write_str("half-space offset is NaN"),
            QueryError::InvalidEpsilon { value } => {
                write!(f, "approximation eps {} is negative or NaN", value.get())
            }
            QueryError::UnsortedRadii { index } => {
                write!(f, "radius {index} is smaller than the radius before it")
            }
        }
    }
}

impl std::error::Error for QueryError {}

/// A query point (or ball centre) in `f64`, exactly: an error naming the first axis that fails
/// [`crate::geom::validate_point`].
#[inline]
pub(crate) fn query_point<S: crate::Scalar, const D: usize>(
    p: &[S; D],
) -> Result<[f64; D], QueryError> {
    crate::geom::exact_point(p).map_err(query_fault)
}

/// Where a point to locate lies against `domain` (in `f64`, exactly, when inside), or the error
/// naming the first axis that fails [`crate::geom::validate_point`]: the one check of every
/// tree's `locate`.
#[inline]
pub(crate) fn place_point<S: crate::Scalar, const D: usize>(
    p: &[S; D],
    domain: &crate::Aabb<f64, D>,
) -> Result<Location<[f64; D]>, QueryError> {
    let checked = crate::geom::check_point(p, domain).map_err(query_fault)?;
    Ok(match checked {
        crate::geom::Checked::Inside(p) => Location::Inside(p),
        crate::geom::Checked::Outside(axis, _) => Location::Outside { axis },
    })
}

/// The query error for a coordinate failing the point check on `axis`.
fn query_fault((axis, fault): (usize, crate::geom::Fault)) -> QueryError {
    match fault {
        crate::geom::Fault::NotFinite(v) => QueryError::NotFinite {
            axis,
            value: v.into(),
        },
        crate::geom::Fault::Inexact(value) => QueryError::Inexact { axis, value },
    }
}

/// A query box in `f64`: infinite float bounds pass (a NaN is refused by the box's
/// [`Region::validate`]), an integer `f64` cannot hold exactly is refused
/// ([`QueryError::Inexact`]), naming the first such axis.
pub(crate) fn query_box<S: crate::Scalar, const D: usize>(
    b: &crate::Aabb<S, D>,
) -> Result<crate::Aabb<f64, D>, QueryError> {
    for axis in 0..D {
        for c in [b.min[axis], b.max[axis]] {
            if let Some(value) = c.integer_value().filter(|_| !c.converts_exactly()) {
                return Err(QueryError::Inexact { axis, value });
            }
        }
    }
    Ok(b.to_f64())
}

/// `x` when it is neither negative nor NaN; otherwise the error `bad` makes of it, naming it.
pub(crate) fn non_negative(
    x: f64,
    bad: impl FnOnce(FloatBits) -> QueryError,
) -> Result<f64, QueryError> {
    if x >= 0.0 {
        Ok(x)
    } else {
        Err(bad(x.into()))
    }
}

/// Checks a maximum distance: not negative, not NaN (infinity means no limit, -0.0 is 0).
pub(crate) fn check_max(max: f64) -> Result<(), QueryError> {
    non_negative(max, |value| QueryError::InvalidMaxDistance { value }).map(drop)
}

/// A radius, checked: not negative, not NaN ([`QueryError::InvalidRadius`] otherwise).
pub(crate) fn check_radius(radius: f64) -> Result<f64, QueryError> {
    non_negative(radius, |radius| QueryError::InvalidRadius { radius })
}
