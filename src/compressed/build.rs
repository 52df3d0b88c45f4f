//! [`CompressedTreeBuilder`]: bulk construction of a [`CompressedTree`] in O(n log n) from the
//! Morton-sorted points, without the uncompressed tree (exercise 14.5, second part).
//!
//! 1. Check the points and choose the root cube exactly as [`PointTreeBuilder`] does (the same
//!    code: a point tree with one bucket holding everything, which is only the validation, the
//!    root cube and the Morton sort), so both trees have the same cells.
//! 2. Key every point again at 64 levels ([`RootGeometry::deep_key`](crate::geom::RootGeometry::deep_key)).
//!    The deep boundaries refine the point tree's, so step 1's order is already the deep Morton
//!    order except among points sharing a finest [`Cell`](crate::Cell): one O(n) pass checks it,
//!    and only when it fails does a stable merge sort of slot numbers put them in order (Rust's
//!    sort, near-linear on such presorted runs; the radix sort of step 1 is not run again).
//! 3. Walk the sorted keys once with a stack holding the rightmost path of the tree built so far
//!    ([`Topology::from_sorted`](super::topology::Topology::from_sorted)): consecutive keys part
//!    at the level of their longest common prefix, and that cell is the only node the new key
//!    can need besides its leaf. Every node is pushed and popped once: O(n).
//!
//! The plain tree's build costs O((d + 1) n) for depth d, which the spread of the points bounds
//! but their number does not; this one costs O(n log n) whatever the spread.
//!
//! Conversions between [`PointTree`] and [`CompressedTree`] live here too. Both share
//! [`RootGeometry`](crate::geom::RootGeometry), so every point keeps its cell and its Morton key: the
//! compressed tree of a point tree is exercise 14.5's compression of it, carried on below the
//! point tree's deepest level to 64 levels (step 2 above), and the point tree of a compressed
//! tree is the fresh build of the same points over the same root cube, a compressed node deeper
//! than its maximum depth lying in one of its deepest leaves
//! ([`DeepCell::to_cell`](crate::geom::DeepCell::to_cell)). The point tree's order among points
//! sharing a finest [`Cell`](crate::Cell) is its input order, the compressed tree's their deep
//! Morton order. Both directions run over the points in Morton order without a full sort.

use super::CompressedTree;
use crate::error::Error;
use crate::geom::{Aabb, Scalar};
use crate::points::{PointTree, PointTreeBuilder};
use crate::query::PointSet;
use crate::query::SpatialIndex;

/// Settings for building a [`CompressedTree`]: the root box (the smallest enclosing cube of the
/// points unless given).
///
/// ```
/// use orthtree::prelude::*;
/// use orthtree::{Aabb, compressed::CompressedTreeBuilder};
/// let root = Aabb::new([0.0, 0.0], [1.0, 1.0]).unwrap();
/// let mut t = CompressedTreeBuilder::new().root_box(root).build(&[([0.5, 0.5], 'a')]).unwrap();
/// t.insert([1.0, 1.0], 'b').unwrap();
/// assert_eq!(t.node_count(), 3); // the root and two leaves
/// assert!(t.insert([2.0, 0.0], 'c').is_err()); // outside the root box
/// ```
#[derive(Clone, Copy, Debug)]
pub struct CompressedTreeBuilder<S, const D: usize> {
    points: PointTreeBuilder<S, D>,
}

impl<S: Scalar, const D: usize> Default for CompressedTreeBuilder<S, D> {
    fn default() -> Self {
        Self::new()
    }
}

impl<S: Scalar, const D: usize> CompressedTreeBuilder<S, D> {
    /// The smallest enclosing cube of the points as root.
    pub fn new() -> Self {
        CompressedTreeBuilder {
            points: PointTreeBuilder::new().bucket_size(usize::MAX),
        }
    }

    /// Every point (built or inserted) must lie in this closed box; the tree subdivides the cube
    /// with the same lower corner and the box's largest extent as side.
    pub fn root_box(mut self, root: Aabb<S, D>) -> Self {
        self.points = self.points.root_box(root);
        self
    }

    /// Builds from (point, item) pairs, cloning the items.
    ///
    /// # Errors
    /// A NaN, infinite or inexact coordinate (an integer `f64` cannot hold), a point outside the root box (naming the point,
    /// axis and value), an invalid root box, too many points.
    pub fn build<T: Clone>(
        &self,
        entries: &[([S; D], T)],
    ) -> Result<CompressedTree<S, T, D>, Error> {
        Ok(self.points.build(entries)?.into())
    }

    /// Builds from owned (point, item) pairs, moving the items.
    ///
    /// # Errors
    /// [`crate::Error::NonFiniteCoordinate`] or [`crate::Error::InexactCoordinate`] for a coordinate that is NaN,
    /// infinite or an integer `f64` cannot hold, [`crate::Error::OutsideRootBox`] for a point outside a
    /// given root box (each naming the point, axis and value), [`crate::Error::InvalidRootBox`],
    /// [`crate::Error::ZeroBucketSize`], [`crate::Error::MaxDepthTooLarge`], [`crate::Error::TooManyPoints`].
    pub fn build_from_vec<T>(
        &self,
        entries: Vec<([S; D], T)>,
    ) -> Result<CompressedTree<S, T, D>, Error> {
        Ok(self.points.build_from_vec(entries)?.into())
    }
}

impl<S: Scalar, T, const D: usize> From<PointTree<S, T, D>> for CompressedTree<S, T, D> {
    /// The compressed tree of the same points over the same root cube, moving the items; O(n).
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{CompressedTree, Quadtree};
    /// let t = Quadtree::new(&[([0.0, 0.0], 'a'), ([1.0, 1.0], 'b')]).unwrap();
    /// let c = CompressedTree::from(t.clone());
    /// assert_eq!((c.len(), c.geometry()), (2, t.geometry()));
    /// ```
    fn from(tree: PointTree<S, T, D>) -> Self {
        let (geometry, domain, points, items) = tree.into_parts();
        CompressedTree::from_sorted(geometry, domain, points, items)
    }
}

impl<S: Scalar, T: Clone, const D: usize> From<&PointTree<S, T, D>> for CompressedTree<S, T, D> {
    /// The compressed tree of the same points over the same root cube, cloning the items.
    fn from(tree: &PointTree<S, T, D>) -> Self {
        CompressedTree::from_sorted(
            *tree.geometry(),
            *tree.domain(),
            tree.points().to_vec(),
            tree.items().to_vec(),
        )
    }
}

/// [`CompressedTree::to_point_tree`].
pub(super) fn to_point_tree<S: Scalar, T: Clone, const D: usize>(
    tree: &CompressedTree<S, T, D>,
    bucket_size: usize,
    max_depth: u8,
) -> Result<PointTree<S, T, D>, Error> {
    // the builder's checks of the same settings, with the same errors
    (PointTreeBuilder::<S, D>::new().bucket_size(bucket_size))
        .max_depth(max_depth)
        .check_settings(0)?;
    let index = tree.index();
    let points = index.points().to_vec();
    let items = index
        .payloads()
        .iter()
        .map(|&s| tree.items()[s as usize].clone())
        .collect();
    let parts = (*tree.geometry(), *tree.domain(), points, items);
    Ok(PointTree::from_sorted_parts(parts, bucket_size, max_depth))
}
