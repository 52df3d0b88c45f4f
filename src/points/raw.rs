//! A [`PointTree`]'s stored arrays and settings, for the saved-tree format and serde: a borrowed
//! view ([`PointTree::view`]) and the checked constructor that takes owned parts back
//! ([`PointTree::from_parts`]) without sorting or subdividing anything.
//!
//! The check is the settings' ranges, [`Tree::from_raw_parts`] for the topology, then the rest of
//! the tree's own `validate` (node runs nest and partition their parents', every point lies in
//! its leaf's cell and in the domain, Morton order within each leaf, leaf sizes, balance): linear in the points and nodes,
//! so a tree read from untrusted bytes answers every query as the tree that was written would, or
//! is refused.

use super::{PointTree, Runs};
use crate::error::{Invariant, ValidationError};
use crate::geom::{Aabb, Cell, RootGeometry, Scalar};
use crate::tree::raw::{OwnedRawTree, RawTree};
use crate::tree::{BalanceOptions, Tree};

/// Everything a [`PointTree`] stores: `Tr` its arena's arrays, then sequences of points, of
/// items and of run ends.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PointTreeFields<Tr, P, I, R, const D: usize> {
    pub tree: Tr,
    /// The root cube's lower corner halved (rounded down) and half its side.
    pub half_lo: [f64; D],
    pub half_side: f64,
    pub domain: Aabb<f64, D>,
    pub points: P,
    pub items: I,
    /// Per node slot, the end of its run relative to its parent's start (`runs.rs`).
    pub run_ends: R,
    pub bucket_size: usize,
    pub max_depth: u8,
    pub balanced: Option<BalanceOptions>,
}

/// Everything a [`PointTree`] stores, by reference.
pub(crate) type PointTreeArrays<'a, S, T, const D: usize> =
    PointTreeFields<RawTree<'a>, &'a [[S; D]], &'a [T], &'a [u32], D>;

/// The owned form of [`PointTreeArrays`], which [`PointTree::from_parts`] checks.
pub(crate) type PointTreeParts<S, T, const D: usize> =
    PointTreeFields<OwnedRawTree, Vec<[S; D]>, Vec<T>, Vec<u32>, D>;

/// The root cube of `half_lo` and `half_side` ([`RootGeometry::halves`]), checked with the
/// `domain` every point must lie in: both finite, the domain a box inside the cube. Shared by
/// every tree read back from its parts.
///
/// # Errors
/// [`Invariant::Settings`] naming the root cube's or the domain's fault, or the first axis on
/// which the domain leaves the cube.
pub(crate) fn checked_root<const D: usize>(
    half_lo: [f64; D],
    half_side: f64,
    domain: &Aabb<f64, D>,
) -> Result<RootGeometry<D>, ValidationError> {
    let settings = |detail: String| ValidationError::new(Invariant::Settings).detail(detail);
    let geometry = RootGeometry::try_from_halves(half_lo, half_side)
        .map_err(|e| settings(format!("the root cube: {e}")))?;
    Aabb::new(domain.min, domain.max).map_err(|e| settings(format!("the domain: {e}")))?;
    let root = geometry.root_box();
    if let Some(axis) = (0..D).find(|&a| domain.min[a] < root.min[a] || domain.max[a] > root.max[a])
    {
        return Err(settings(format!(
            "the domain [{}, {}] on axis {axis} is not inside the root cube's [{}, {}]",
            domain.min[axis], domain.max[axis], root.min[axis], root.max[axis]
        )));
    }
    Ok(geometry)
}

/// A stored bucket size and maximum depth, checked: the bucket size positive, the depth at
/// most [`Cell::MAX_LEVEL`]. Shared by the point trees read back from their parts.
///
/// # Errors
/// [`Invariant::Settings`] naming the zero bucket size, or the depth and its limit.
pub(crate) fn check_bucket<const D: usize>(
    bucket_size: usize,
    max_depth: u8,
) -> Result<(), ValidationError> {
    let settings = |detail: String| Err(ValidationError::new(Invariant::Settings).detail(detail));
    if bucket_size == 0 {
        return settings("the bucket size is 0".into());
    }
    if max_depth > Cell::<D>::MAX_LEVEL {
        let limit = Cell::<D>::MAX_LEVEL;
        return settings(format!(
            "the maximum depth {max_depth} exceeds the limit {limit}"
        ));
    }
    Ok(())
}

impl<S: Scalar, T, const D: usize> PointTree<S, T, D> {
    /// The stored arrays and settings.
    pub(crate) fn view(&self) -> PointTreeArrays<'_, S, T, D> {
        let (half_lo, half_side) = self.geometry.halves();
        PointTreeArrays {
            tree: self.tree.raw_parts(),
            half_lo,
            half_side,
            domain: self.domain,
            points: &self.points,
            items: &self.items,
            run_ends: self.runs.ends(),
            bucket_size: self.bucket_size,
            max_depth: self.max_depth,
            balanced: self.balanced,
        }
    }

    /// The tree of `parts`, checked (see the module doc); nothing is sorted or rebuilt.
    ///
    /// # Errors
    /// The first broken invariant: [`Invariant::Settings`] for a bucket size of 0, a maximum
    /// depth beyond [`Cell::MAX_LEVEL`], a root cube that is not finite or a domain that is not
    /// a finite box inside it; [`Invariant::Lengths`] for points and items of different counts;
    /// [`Invariant::Topology`] naming the [`crate::tree::TreeError`]; then whatever the tree's
    /// `validate` finds.
    ///
    /// # Complexity
    /// O(n + m depth) for n points and m node slots.
    pub(crate) fn from_parts(parts: PointTreeParts<S, T, D>) -> Result<Self, ValidationError> {
        check_bucket::<D>(parts.bucket_size, parts.max_depth)?;
        let geometry = checked_root(parts.half_lo, parts.half_side, &parts.domain)?;
        let domain = parts.domain;
        if parts.points.len() != parts.items.len() || parts.points.len() > u32::MAX as usize {
            return Err(ValidationError::new(Invariant::Lengths).detail(format!(
                "{} points, {} items (at most 2^32 - 1 of each)",
                parts.points.len(),
                parts.items.len()
            )));
        }
        let tree = Tree::from_raw_parts(parts.tree)
            .map_err(|e| ValidationError::new(Invariant::Topology).detail(e.to_string()))?;
        let tree = PointTree {
            tree,
            geometry,
            domain,
            points: parts.points,
            items: parts.items,
            runs: Runs::from_ends(parts.run_ends),
            bucket_size: parts.bucket_size,
            max_depth: parts.max_depth,
            balanced: parts.balanced,
        };
        // The arena was validated just above: the runs, points and balance remain.
        tree.check_points_and_runs()?;
        Ok(tree)
    }
}
