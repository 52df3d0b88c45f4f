//! Conversions between [`PointTree`] and [`CompressedTree`]. Both share
//! [`RootGeometry`](crate::RootGeometry), so every point keeps its cell and its Morton key: the compressed tree
//! of a point tree is exercise 14.5's compression of it (with its leaves at the finest cells),
//! and the point tree of a compressed tree is the fresh build of the same points over the same
//! root cube. Both directions run over the points in Morton order without sorting.

use super::CompressedTree;
use crate::error::Error;
use crate::geom::{Cell, Scalar};
use crate::points::PointTree;
use crate::query::SpatialIndex;

impl<S: Scalar, T, const D: usize> From<PointTree<S, T, D>> for CompressedTree<S, T, D> {
    /// The compressed tree of the same points over the same root cube, moving the items; O(n).
    ///
    /// ```
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
        let g = *tree.geometry();
        CompressedTree::from_sorted(
            g,
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
    if bucket_size == 0 {
        return Err(Error::ZeroBucketSize);
    }
    if max_depth > Cell::<D>::MAX_LEVEL {
        return Err(Error::MaxDepthTooLarge {
            requested: max_depth,
            limit: Cell::<D>::MAX_LEVEL,
        });
    }
    let index = tree.index();
    let points = index.points().to_vec();
    let items = index
        .items()
        .iter()
        .map(|&s| tree.items()[s as usize].clone())
        .collect();
    let parts = (*tree.geometry(), *tree.domain(), points, items);
    Ok(PointTree::from_sorted_parts(parts, bucket_size, max_depth))
}
