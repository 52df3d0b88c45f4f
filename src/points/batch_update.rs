//! Batch updates of a [`PointTree`]: [`PointTree::extend_from_vec`] inserts many pairs and
//! [`PointTree::retain`] removes many, each in one linear pass over the stored points.
//!
//! A single [`PointTree::insert`](crate::query::PointSetMut::insert) or [`PointTree::remove`](crate::query::PointSetMut::remove) moves every point after its position
//! (one `memmove`: the points stay dense in Morton order, see `update.rs`). A batch of k updates
//! pays that once:
//!
//! - `extend_from_vec` sorts the k new (Morton key, batch index) pairs with the build's radix
//!   sort and merges them into the stored run (a new pair goes after the stored pairs with its
//!   key, and the batch keeps its order among equal keys, exactly where k single inserts would
//!   put them); `retain` keeps the pairs its predicate accepts, in order;
//! - then the tree is cut again from the root, as the bulk build cuts a sorted run.
//!
//! Time O(n + k log k) for the merge (O(n + k) with the radix sort on spread keys) and
//! O(m 2^D log n) for the cut, so O(depth) per updated point once k is at least n / depth. The
//! result is the canonical tree: the tree a fresh build of the same pairs gives, with the same
//! points in the same order as the single updates would leave.

use super::{PointTree, Runs};
use crate::error::Error;
use crate::geom::Scalar;
use crate::query::PointSet;
use crate::tree::{NodeId, Tree};

impl<S: Scalar, T, const D: usize> PointTree<S, T, D> {
    /// Inserts every (point, item) of `entries`: the tree [`PointTree::insert`](crate::query::PointSetMut::insert) called on each in
    /// turn would give, in one merge instead of one `memmove` per pair. See the module doc for
    /// the cost.
    ///
    /// A non-empty batch drops a [`PointTree::balance`] refinement, as an insert does.
    ///
    /// Errors (and then the tree is unchanged): a coordinate that is NaN, infinite or outside
    /// [`PointTree::domain`](crate::query::PointSet::domain) (`index` is the pair's position in `entries` plus
    /// [`PointTree::len`](crate::query::PointSet::len)); more points than a `u32` can index.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{Aabb, Quadtree};
    /// let root = Aabb::new([0.0, 0.0], [1.0, 1.0]).unwrap();
    /// let mut t = Quadtree::builder().root_box(root).bucket_size(2).build(&[([0.5, 0.5], 0)]).unwrap();
    /// t.extend_from_vec((1..100).map(|i| ([i as f64 / 100.0, 0.25], i)).collect()).unwrap();
    /// assert_eq!(t.len(), 100);
    /// t.validate().unwrap();
    /// assert!(t.extend_from_vec(vec![([0.5, 2.0], 7)]).is_err()); // outside the root box
    /// assert_eq!(t.len(), 100);
    /// ```
    ///
    /// # Errors
    /// As [`PointSetMut::insert`](crate::query::PointSetMut::insert), naming the first refused
    /// entry by its future index; the tree is unchanged then.
    pub fn extend_from_vec(&mut self, entries: Vec<([S; D], T)>) -> Result<(), Error> {
        let n = self.len();
        if entries.is_empty() {
            return Ok(()); // as no insert: a balanced tree stays balanced
        }
        for (i, (p, _)) in entries.iter().enumerate() {
            self.check_insertable(p, n + i)?;
        }
        Error::check_count(n + entries.len())?;
        let mut keyed: Vec<u128> = entries
            .iter()
            .enumerate()
            .map(|(i, (p, _))| super::build::key_pair(&self.geometry, p, i))
            .collect();
        super::radix::sort_keyed(&mut keyed);
        let mut new: Vec<Option<([S; D], T)>> = entries.into_iter().map(Some).collect();
        let total = n + keyed.len();
        let mut points = Vec::with_capacity(total);
        let mut items = Vec::with_capacity(total);
        let mut keys = Vec::with_capacity(total);
        let geometry = self.geometry;
        let mut old = core::mem::take(&mut self.points)
            .into_iter()
            .zip(core::mem::take(&mut self.items))
            .map(|(p, t)| (geometry.scalar_key(&p), p, t))
            .peekable();
        let mut pending = keyed
            .iter()
            .map(|&k| ((k >> 32) as u64, k as u32))
            .peekable();
        loop {
            // A new pair goes first only with a smaller key: equal keys keep the stored first.
            let new_first = match (old.peek(), pending.peek()) {
                (None, None) => break,
                (Some(&(stored, ..)), Some(&(key, _))) => key < stored,
                (stored, _) => stored.is_none(),
            };
            let (key, p, t) = match pending.next_if(|_| new_first) {
                Some((key, i)) => {
                    let (p, t) = new[i as usize].take().expect("each pair is taken once");
                    (key, p, t)
                }
                None => old.next().expect("a stored pair is left"),
            };
            points.push(p);
            items.push(t);
            keys.push(key);
        }
        self.points = points;
        self.items = items;
        self.recut(|_, i, _| keys[i]);
        Ok(())
    }

    /// Keeps only the pairs for which `keep(point, item)` is `true` (called once per pair, in
    /// storage order) and merges the nodes left holding at most the bucket size: the tree a
    /// fresh build of the kept pairs gives (so a [`PointTree::balance`] refinement is dropped).
    /// O(n) plus the cut (module doc).
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let pts: Vec<([f64; 2], u32)> = (0..1000).map(|i| ([i as f64, (i * 7 % 1000) as f64], i)).collect();
    /// let mut t = Quadtree::builder().bucket_size(4).build(&pts).unwrap();
    /// t.retain(|_, &i| i % 10 == 0);
    /// assert_eq!(t.len(), 100);
    /// assert!(t.items().iter().all(|i| i % 10 == 0));
    /// t.validate().unwrap();
    /// ```
    pub fn retain(&mut self, mut keep: impl FnMut(&[S; D], &T) -> bool) {
        let kept: Vec<bool> = self.iter().map(|(p, t)| keep(p, t)).collect();
        let mut flags = kept.iter();
        self.points
            .retain(|_| *flags.next().expect("one flag per point"));
        let mut flags = kept.iter();
        self.items
            .retain(|_| *flags.next().expect("one flag per item"));
        self.rebuild_canonical();
    }

    /// Drops every node (and any balance refinement) and cuts the stored run, which is in Morton
    /// order, from the root down; `key(points, i, level)` is point `i`'s Morton key (as for
    /// `subdivide`).
    pub(super) fn recut(&mut self, key: impl Fn(&[[S; D]], usize, u8) -> u64) {
        self.tree = Tree::new();
        self.runs = Runs::new(self.points.len());
        self.balanced = None;
        self.subdivide(NodeId::ROOT, key);
    }
}
