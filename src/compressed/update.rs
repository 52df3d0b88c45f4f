//! Updates of a [`CompressedTree`]: [`CompressedTree::insert`](crate::query::PointSetMut::insert), [`CompressedTree::remove`](crate::query::PointSetMut::remove) and
//! [`CompressedTree::remove_point`](crate::query::PointSetMut::remove_point) in O(depth), keeping the tree canonical (equal to a fresh
//! build over the same points and root box).
//!
//! - Insert: walk down from the root to the deepest node whose cell holds the point's finest
//!   cell (O(depth) nodes, O(2^D) each); there, either the point's leaf exists (a duplicate: one
//!   more slot in its list), or its quadrant is empty (one new leaf), or the quadrant holds a
//!   node the point parts from (one new branching node at their common cell, and the leaf).
//! - Remove: walk down to the point's leaf, unlink the slot; an emptied leaf is removed, and a
//!   parent left with one child (other than the root) is spliced out. O(depth).
//!
//! The points live in slots ([`super::CompressedIndex`]'s module doc): a new point takes the
//! last slot, a removal moves the last slot into the hole, so no array is shifted. Queries after
//! an update rebuild the Morton-order view once, in O(n).
//!
//! Rules as in [`PointTree`](crate::PointTree)'s updates: the root box is fixed at build time;
//! a point outside it, or not finite, is refused with an error naming the axis and value
//! (`index` there is [`CompressedTree::len`](crate::query::PointSet::len) at the call); a removal of a point not stored
//! changes nothing; among equal points the first stored (list order) is removed.

use super::topology::NIL;
use super::CompressedTree;
use crate::error::Error;
use crate::geom::{DeepKey, Scalar};
use crate::query::{InsertError, PointSet, PointSetMut};

impl<S: Scalar, T, const D: usize> CompressedTree<S, T, D> {
    /// The finest key of a point to insert, checked (room for one more; then finiteness and
    /// domain, like the build's input, as number `len()`).
    pub(crate) fn checked_insert_key(&self, point: &[S; D]) -> Result<DeepKey<D>, Error> {
        let n = self.len();
        Error::check_count(n + 1)?;
        let p = Error::check_input(point, Some(self.domain()), n)?;
        Ok(self.geometry().deep_key(&p))
    }

    /// Stores the point below `at`, the deepest node holding `key`; returns what the tree did.
    pub(crate) fn insert_below(
        &mut self,
        at: u32,
        point: [S; D],
        key: DeepKey<D>,
        item: T,
    ) -> super::topology::Inserted {
        let done = self.index.topology.insert(at, &key);
        self.index.push_slot(point, key, done.leaf);
        self.items.push(item);
        done
    }

    /// Removes the first item at `point` accepted by `accept` below `leaf`, the deepest node
    /// holding `key`; returns it with the leaf removed from the tree (NIL if the leaf stays).
    pub(crate) fn remove_in_leaf(
        &mut self,
        leaf: u32,
        key: &DeepKey<D>,
        point: &[S; D],
        accept: impl Fn(&T) -> bool,
    ) -> Option<(T, u32)> {
        let t = &self.index.topology;
        if !t.is_leaf(leaf) || t.node(leaf).cell.anchor() != *key {
            return None;
        }
        let s = self
            .index
            .leaf_slots(leaf)
            .find(|&s| self.index.points[s] == *point && accept(&self.items[s]))?;
        let removed = self.index.remove_slot(s);
        let item = self.items.swap_remove(s);
        Some((item, if removed == NIL { NIL } else { leaf }))
    }
}

impl<S: Scalar, T, const D: usize> PointSetMut<D> for CompressedTree<S, T, D> {
    /// Inserts `item` at `point`. O(depth).
    ///
    /// # Errors
    /// A NaN or infinite coordinate, or one outside [`CompressedTree::domain`](crate::query::PointSet::domain); more
    /// points than a `u32` can index.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{Aabb, CompressedTree};
    /// let root = Aabb::new([0.0, 0.0], [1.0, 1.0]).unwrap();
    /// let mut t = CompressedTree::builder().root_box(root).build(&[]).unwrap();
    /// t.insert([0.25, 0.25], 'a').unwrap();
    /// t.insert([0.25 + 1e-9, 0.25], 'b').unwrap();
    /// assert_eq!(t.node_count(), 4); // root, their common cell, two leaves
    /// assert!(t.remove(&[0.25, 0.25], &'a'));
    /// assert_eq!(t.node_count(), 2);
    /// t.validate().unwrap();
    /// ```
    fn insert(&mut self, point: [S; D], item: T) -> Result<(), InsertError<T>> {
        let key = match self.checked_insert_key(&point) {
            Ok(key) => key,
            Err(error) => return Err(InsertError { error, item }),
        };
        let at = self.index.topology.descend(0, &key, |_| {});
        self.insert_below(at, point, key, item);
        Ok(())
    }

    /// Removes the first item stored at `point` that `wanted` accepts and returns it; `None` if
    /// there is none. O(depth + copies of the point).
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::CompressedTree;
    /// let mut t = CompressedTree::new(&[([0.0, 0.0], 'a'), ([0.0, 0.0], 'b'), ([1.0, 1.0], 'c')]).unwrap();
    /// assert_eq!(t.remove_point(&[0.0, 0.0]), Some('a'));
    /// assert_eq!(t.remove_point(&[0.5, 0.5]), None);
    /// assert_eq!(t.len(), 2);
    /// ```
    fn remove_where(&mut self, point: &[S; D], wanted: impl Fn(&T) -> bool) -> Option<T> {
        let key = self.query_key(point).ok()?.inside()?;
        let leaf = self.index.topology.descend(0, &key, |_| {});
        self.remove_in_leaf(leaf, &key, point, wanted)
            .map(|(item, _)| item)
    }
}
