//! Updates of a [`PointTree`]: [`PointTree::insert`](crate::query::PointSetMut::insert), [`PointTree::remove`](crate::query::PointSetMut::remove) and
//! [`PointTree::remove_point`](crate::query::PointSetMut::remove_point), keeping the tree *canonical*: after any sequence of updates it has
//! exactly the leaves (cells) and the points per leaf of a tree freshly built from the same
//! (point, item) pairs with the same root box, bucket size and maximum depth. A node is split
//! exactly when it holds more than the bucket size and is above the maximum depth, so:
//!
//! - insert descends to the leaf of the point, adds it there, and splits that leaf while it (then
//!   each child) is over the bucket size and above the maximum depth;
//! - remove takes the point out of its leaf, then merges the shallowest ancestor left holding at
//!   most the bucket size back into a leaf ([`Tree::merge_subtree`]), freeing its child blocks
//!   for reuse by later splits.
//!
//! # Layout and cost
//! The storage is the bulk build's, unchanged: points and items in one `Vec` each, sorted by
//! Morton key, each node owning a contiguous run (so `points()`, `node_points` and the runs the
//! queries read keep their meaning after updates). The tree work of an update is O(depth) node
//! visits plus, for the split or merge it may cause, O(bucket size + 2^D depth). The node runs
//! change in O(2^D depth): each node records its run's end relative to
//! its parent's start (`runs.rs`), so only the path and its later siblings move. Keeping the
//! points contiguous adds one `memmove` of the points and items after the update's position:
//! O(n) bytes moved, with a small constant, but not O(depth): about 15 us per update at
//! n = 10^5 and 300 us at 10^6 (2D uniform, `u64` items). Many updates at once go through
//! [`PointTree::extend_from_vec`] and [`PointTree::retain`] (`batch_update.rs`): one merge or
//! filter pass for the whole batch, 0.6 us per inserted point for 10^5 points into 10^6.
//!
//! That term cannot be O(depth) while `points()` and `items()` are dense slices in Morton order:
//! an adversary inserting at the front moves every point each time. With gaps, keeping n items
//! in key order in an array of O(n) slots costs Θ(log² n) amortised moves per insert (a packed
//! memory array meets it; Bulánek, Koucký and Saks, "Tight lower bounds for the online labeling
//! problem", STOC 2012, show no array layout does better), and a gap needs a placeholder item,
//! which a generic `T` (no `Default`, no `unsafe`) does not have. For single updates between
//! queries, convert to a [`crate::DynamicPointTree`] (`DynamicPointTree::from(tree)`): the same
//! shape and queries, its leaves in chunks with slack and its items apart in slots, so that an
//! update costs amortised O(depth) (0.4-0.6 us per insert and remove together at 10^6 points,
//! `examples/compare.rs`).
//!
//! # Rules
//! - The root box is fixed at build time: the given root box, or the enclosing cube of the first
//!   points. A point outside it (or with a NaN or infinite coordinate) is refused with
//!   [`Error::OutsideRootBox`] (or [`Error::NonFiniteCoordinate`]) naming the axis and value;
//!   `index` there is [`PointTree::len`](crate::query::PointSet::len) at the time of the call. Build with
//!   [`super::PointTreeBuilder::root_box`] to make a tree for points not yet known.
//! - Within a leaf, an inserted point goes after the points with the same Morton key.
//! - Remove with several stored copies of the same point and item removes the first copy in
//!   storage order (Morton order; among equal keys, build order, then insertion order).
//! - A removal of a point that is not stored (or not finite, or outside the root box) changes
//!   nothing and returns `false` / `None`.
//! - After [`PointTree::balance`], the first update drops the balance refinement (it rebuilds the
//!   canonical tree from the stored points, O(n log n)): an updated tree is never balanced; call
//!   `balance` again if needed.

use super::PointTree;
use crate::error::Error;
use crate::geom::Scalar;
use crate::query::{InsertError, PointSet, PointSetMut};
use crate::tree::NodeId;
use smallvec::SmallVec;

type Path = SmallVec<[NodeId; 40]>;

impl<S: Scalar, T, const D: usize> PointTree<S, T, D> {
    /// Refuses a point that is not finite or lies outside the domain; `index` names it in the
    /// error.
    pub(super) fn check_insertable(&self, point: &[S; D], index: usize) -> Result<(), Error> {
        Error::check_input(point, Some(&self.domain), index).map(|_| ())
    }

    /// The Morton key of stored point `i`.
    #[inline]
    fn key_of(&self, i: usize) -> u64 {
        self.geometry.scalar_key(&self.points[i])
    }

    /// The nodes from the root to the leaf holding Morton key `key`, and the leaf's run.
    fn path(&self, key: u64) -> (Path, (u32, u32)) {
        let mut path = Path::new();
        let mut v = NodeId::ROOT;
        let (mut s, mut e) = (0, self.runs.total());
        path.push(v);
        while let Some(first) = self.tree.child(v, 0) {
            let c = super::digit::<D>(key, self.tree.level(v));
            let ends = self.runs.block::<D>(first);
            (s, e) = (s + if c == 0 { 0 } else { ends[c - 1] }, s + ends[c]);
            v = NodeId(first.0 + c as u32);
            path.push(v);
        }
        (path, (s, e))
    }

    /// Splits below `start` as a fresh build would, recomputing the points' keys.
    fn split_down(&mut self, start: NodeId) {
        let geometry = self.geometry;
        self.subdivide(start, |points, i, _| geometry.scalar_key(&points[i]));
    }

    /// Drops every split (balance's too) and splits again from the root: the tree a fresh build
    /// of the stored points gives. The points keep their order.
    pub(super) fn rebuild_canonical(&mut self) {
        let geometry = self.geometry;
        self.recut(|points, i, _| geometry.scalar_key(&points[i]));
    }
}

impl<S: Scalar, T, const D: usize> PointSetMut<D> for PointTree<S, T, D> {
    /// Inserts `item` at `point`, splitting the point's leaf while it holds more than the bucket
    /// size and is above the maximum depth. See the module doc for the cost.
    ///
    /// # Errors
    /// A coordinate that is NaN or infinite, or outside [`PointTree::domain`](crate::query::PointSet::domain); more points
    /// than a `u32` can index.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{Aabb, Quadtree};
    /// let root = Aabb::new([0.0, 0.0], [1.0, 1.0]).unwrap();
    /// let mut t = Quadtree::builder().root_box(root).bucket_size(1).build(&[]).unwrap();
    /// t.insert([0.25, 0.25], 'a').unwrap();
    /// t.insert([0.75, 0.75], 'b').unwrap();
    /// assert_eq!(t.leaf_count(), 4);
    /// assert!(t.insert([2.0, 0.0], 'c').is_err()); // outside the root box
    /// assert!(t.remove(&[0.75, 0.75], &'b'));
    /// assert_eq!(t.leaf_count(), 1); // merged back: as if built from 'a' alone
    /// t.validate().unwrap();
    /// ```
    fn insert(&mut self, point: [S; D], item: T) -> Result<(), InsertError<T>> {
        let index = self.len();
        let checked =
            (self.check_insertable(&point, index)).and_then(|()| Error::check_count(index + 1));
        if let Err(error) = checked {
            return Err(InsertError { error, item });
        }
        let p = point.map(Scalar::to_f64);
        if self.balanced.is_some() {
            self.rebuild_canonical();
        }
        let key = self.geometry.key(&p);
        let (path, (s, e)) = self.path(key);
        let leaf = *path.last().expect("the path holds the root");
        // After every point of the leaf whose key is at most `key`.
        let a = s as usize
            + self.points[s as usize..e as usize]
                .partition_point(|p| self.geometry.scalar_key(p) <= key);
        self.points.insert(a, point);
        self.items.insert(a, item);
        self.runs.shift::<D>(&path, 1);
        self.split_down(leaf);
        Ok(())
    }

    /// Removes the first item (in storage order) stored at exactly `point` that `wanted`
    /// accepts and returns it; `None` (and nothing changed) when there is none.
    fn remove_where(&mut self, point: &[S; D], wanted: impl Fn(&T) -> bool) -> Option<T> {
        let p = crate::query::place_point(point, &self.domain)
            .ok()?
            .inside()?;
        let key = self.geometry.key(&p);
        let (_, (s, e)) = self.path(key);
        // The first point of the leaf with this key, then scan the equal keys.
        let a = s as usize
            + self.points[s as usize..e as usize]
                .partition_point(|p| self.geometry.scalar_key(p) < key);
        let i = (a..e as usize)
            .take_while(|&i| self.key_of(i) == key)
            .find(|&i| self.points[i] == *point && wanted(&self.items[i]))?;
        if self.balanced.is_some() {
            // Rebuilding keeps the points' order, so `i` stays valid.
            self.rebuild_canonical();
        }
        let (path, _) = self.path(key);
        self.points.remove(i);
        let item = self.items.remove(i);
        self.runs.shift::<D>(&path, -1);
        // The shallowest node on the path now holding at most the bucket size becomes a leaf.
        if let Some(&top) = path.iter().find(|&&v| {
            !self.tree.is_leaf(v) && self.runs.count::<D>(v) as usize <= self.bucket_size
        }) {
            self.tree.merge_subtree(top);
        }
        Some(item)
    }
}
