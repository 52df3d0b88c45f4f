//! The queries of [`crate::query`] on a [`CompressedTree`]: range (box, ball, half-space, any
//! [`Region`](crate::Region)), nearest, k-nearest and the nearest iterator, with the names and
//! meanings of [`PointTree`](crate::PointTree)'s, written by
//! [`slot_queries!`](crate::slot_queries) (shared with [`crate::DynamicPointTree`]): each runs
//! the shared engine on the tree's [`CompressedIndex`] and maps the slots the index reports back
//! to the tree's items.
//!
//! Indices in [`Neighbor::index`](crate::Neighbor::index) are positions in
//! `self.index().points()` (Morton order), which break ties as in the point tree; on a freshly
//! built tree they equal the point tree's, except among points sharing one of its finest cells,
//! which the compressed tree orders by their 64-level keys.

use super::{CompressedIndex, CompressedTree};

crate::slot_queries!(
    CompressedTree,
    CompressedIndex,
    false,
    CompressedRegionIter,
    CompressedNearestIter
);
