//! A [`CompressedTree`] read back from what serde stores of it: the root cube, the domain, the
//! points and items in slot order, and the slots in the order the queries read them (deep
//! Morton order, each leaf's slots in its list order). The nodes are not stored: a compressed
//! tree is canonical (exercise 14.5: its nodes are exactly the root, the branching cells and the
//! stored keys' finest cells), so [`CompressedTree::from_slots`] rebuilds them from the keys in
//! O(n) with the stack construction of [`Topology::from_sorted`](super::topology::Topology),
//! after checking every input; the tree read back answers every query as the one written, ties
//! included.

use super::{CompressedIndex, CompressedTree};
use crate::error::{Error, Invariant, ValidationError};
use crate::geom::deep::morton_cmp;
use crate::geom::{Aabb, DeepKey, Scalar};
use crate::points::checked_root;
use crate::query::PointSet;

impl<S: Scalar, T, const D: usize> CompressedTree<S, T, D> {
    /// The tree over the root cube of `half_lo` and `half_side` (as
    /// [`RootGeometry::halves`](crate::geom::RootGeometry) gives them) and `domain`, holding
    /// `points` and `items` in slot order, with `order` the slots in deep Morton order (a leaf's
    /// duplicates in the order its list keeps them).
    ///
    /// # Errors
    /// [`Invariant::Settings`] for a root cube or domain that is not finite, or a domain outside
    /// the cube; [`Invariant::Lengths`] for points, items and `order` of different lengths (or
    /// 2^32 - 1 or more points); [`Invariant::InDomain`] naming the first point that is not
    /// finite, not exact or outside the domain, with its axis and value; [`Invariant::Links`]
    /// naming the position of `order` that repeats a slot, names none, or breaks the Morton
    /// order; then whatever the tree's `validate` finds.
    ///
    /// # Complexity
    /// O(n) for n points (the keys, the permutation check and the stack construction).
    pub(crate) fn from_slots(
        half_lo: [f64; D],
        half_side: f64,
        domain: Aabb<f64, D>,
        points: Vec<[S; D]>,
        items: Vec<T>,
        order: Vec<u32>,
    ) -> Result<Self, ValidationError> {
        let geometry = checked_root(half_lo, half_side, &domain)?;
        let n = points.len();
        if items.len() != n || order.len() != n || n >= u32::MAX as usize {
            return Err(ValidationError::new(Invariant::Lengths).detail(format!(
                "{n} points, {} items, {} slots in order (equal, and fewer than 2^32 - 1)",
                items.len(),
                order.len()
            )));
        }
        let mut keys: Vec<DeepKey<D>> = Vec::with_capacity(n);
        for (i, p) in points.iter().enumerate() {
            let q = Error::check_input(p, Some(&domain), i).map_err(|e| {
                ValidationError::new(Invariant::InDomain)
                    .point(i)
                    .detail(e.to_string())
            })?;
            keys.push(geometry.deep_key(&q));
        }
        let mut seen = vec![false; n];
        for (i, &s) in order.iter().enumerate() {
            let links = |d: String| ValidationError::new(Invariant::Links).point(i).detail(d);
            if s as usize >= n || std::mem::replace(&mut seen[s as usize], true) {
                return Err(links(format!(
                    "position {i} of the order holds slot {s}, out of range (of {n}) or repeated"
                )));
            }
            if i > 0 && morton_cmp(&keys[order[i - 1] as usize], &keys[s as usize]).is_gt() {
                return Err(links(format!(
                    "position {i} of the order holds slot {s}, whose point comes before slot {}'s \
                     in Morton order",
                    order[i - 1]
                )));
            }
        }
        let tree = CompressedTree {
            index: CompressedIndex::from_keyed(geometry, domain, points, keys, Some(order)),
            items,
        };
        tree.validate()?;
        Ok(tree)
    }
}
