//! Updates of a [`DynamicPointTree`]: [`DynamicPointTree::insert`](crate::query::PointSetMut::insert),
//! [`DynamicPointTree::remove`](crate::query::PointSetMut::remove) and [`DynamicPointTree::remove_point`](crate::query::PointSetMut::remove_point), each amortised O(depth)
//! (see the module doc of `dynamic`), keeping the canonical shape: splits below an insert's
//! leaf while it is over the bucket size, a merge of the shallowest ancestor of a removal left
//! with at most the bucket size; and the compaction of the chunk array.
//!
//! Rules, as [`PointTree`](crate::PointTree)'s updates: the root box is fixed at build time
//! (a point outside it, or not finite, is refused with an error naming the axis and value, its
//! `index` the slot it would have taken); a removal of a point not stored changes nothing and
//! returns `false` / `None`; with several stored copies of the same point and item, remove
//! takes the first in its leaf's chunk.

use super::pool::{cap_for, MIN_CAP};
use super::{DynamicPointTree, NodeData, GAP};
use crate::error::Error;
use crate::geom::Scalar;
use crate::points::{digit, splits};
use crate::query::{InsertError, Location, PointSet, PointSetMut, QueryError};
use crate::tree::NodeId;
use smallvec::SmallVec;

/// The nodes from the root to a leaf.
type Path = SmallVec<[NodeId; 40]>;

impl<S: Scalar, T, const D: usize> DynamicPointTree<S, T, D> {
    /// The leaf whose cell holds `point` under the split convention, or
    /// [`Location::Outside`] for a point outside the domain (as
    /// [`PointTree::locate`](crate::PointTree::locate)).
    ///
    /// # Errors
    /// [`QueryError::NotFinite`](crate::QueryError::NotFinite) or
    /// [`QueryError::Inexact`](crate::QueryError::Inexact) for a coordinate that is NaN,
    /// infinite or an integer `f64` cannot hold, naming its axis.
    ///
    /// # Complexity
    /// O(depth).
    ///
    /// ```
    /// use orthtree::query::Location;
    /// use orthtree::{tree::NodeId, DynamicPointTree};
    /// let t = DynamicPointTree::new(&[([0.0, 0.0], 'a'), ([1.0, 1.0], 'b')]).unwrap();
    /// assert_eq!(t.locate(&[0.5, 0.5]), Ok(Location::Inside(NodeId::ROOT)));
    /// assert_eq!(t.locate(&[-1.0, 0.5]), Ok(Location::Outside { axis: 0 }));
    /// ```
    pub fn locate(&self, point: &[S; D]) -> Result<Location<NodeId>, QueryError> {
        Ok(crate::query::place_point(point, &self.domain)?
            .map(|_| *self.path(point).last().expect("the path holds the root")))
    }

    /// The nodes from the root to the leaf whose cell holds `point`.
    fn path(&self, point: &[S; D]) -> Path {
        let ix = &self.index;
        let key = ix.geometry.scalar_key(point);
        let mut path = Path::new();
        let mut v = NodeId::ROOT;
        path.push(v);
        while let Some(first) = ix.tree.child(v, 0) {
            v = NodeId(first.0 + digit::<D>(key, ix.tree.level(v)) as u32);
            path.push(v);
        }
        path
    }

    /// Moves the entry at pool position `from` to `to` (its slot's position follows).
    fn move_entry(&mut self, from: u32, to: u32) {
        let pool = &mut self.index.pool;
        let slot = pool.slots[from as usize];
        pool.points[to as usize] = pool.points[from as usize];
        pool.slots[to as usize] = slot;
        self.pos[slot as usize] = to;
    }

    /// Moves the first `keep` entries of leaf `v`'s chunk to a new chunk of `cap` entries (0:
    /// none) and frees the old one.
    fn relocate(&mut self, v: NodeId, cap: u32, keep: u32) {
        let d = self.index.nodes[v.index()];
        let start = self.index.pool.alloc(cap);
        for j in 0..keep {
            self.move_entry(d.start + j, start + j);
        }
        if d.cap != 0 {
            self.index.pool.free(d.start, d.cap);
        }
        let n = &mut self.index.nodes[v.index()];
        (n.start, n.cap) = (start, cap);
    }

    /// Splits leaf `v`, then each child, while it holds more than the bucket size and is above
    /// the maximum depth: a fresh build's shape below `v`.
    fn split_down(&mut self, v: NodeId) {
        let mut stack: SmallVec<[NodeId; 8]> = SmallVec::new();
        stack.push(v);
        while let Some(v) = stack.pop() {
            let d = self.index.nodes[v.index()];
            let level = self.index.tree.level(v);
            if !splits(d.count as usize, level, self.bucket_size, self.max_depth) {
                continue;
            }
            let first = self.index.tree.split(v);
            let ix = &mut self.index;
            if ix.nodes.len() < ix.tree.node_count() {
                ix.nodes.resize(ix.tree.node_count(), Default::default());
            }
            let entries = d.start..d.start + d.count;
            let child_of = |e: u32| {
                let key = ix.geometry.scalar_key(&ix.pool.points[e as usize]);
                digit::<D>(key, level)
            };
            let mut counts = [0u32; 256];
            let children: SmallVec<[u8; 64]> = entries
                .clone()
                .map(|e| {
                    let c = child_of(e);
                    counts[c] += 1;
                    c as u8
                })
                .collect();
            for (i, &count) in counts[..1 << D].iter().enumerate() {
                let cap = if count == 0 { 0 } else { cap_for(count) };
                let start = ix.pool.alloc(cap);
                ix.nodes[first.index() + i] = NodeData { count, start, cap };
            }
            let mut filled = [0u32; 256];
            for (e, &c) in entries.zip(&children) {
                let to = self.index.nodes[first.index() + c as usize].start + filled[c as usize];
                filled[c as usize] += 1;
                self.move_entry(e, to);
            }
            self.index.pool.free(d.start, d.cap);
            let n = &mut self.index.nodes[v.index()];
            (n.start, n.cap) = (0, 0);
            stack.extend((0..1 << D).map(|i| NodeId(first.0 + i as u32)));
        }
    }

    /// Makes inner node `top` (holding at most the bucket size) a leaf again: its leaves'
    /// entries go to one chunk, their chunks and child blocks are freed.
    fn merge(&mut self, top: NodeId) {
        let count = self.index.nodes[top.index()].count;
        let cap = if count == 0 { 0 } else { cap_for(count) };
        let start = self.index.pool.alloc(cap);
        let mut at = start;
        let leaves: SmallVec<[NodeId; 64]> = self
            .index
            .tree
            .walk_from(top, true)
            .map(|(id, _)| id)
            .collect();
        for leaf in leaves {
            let d = self.index.nodes[leaf.index()];
            for j in 0..d.count {
                self.move_entry(d.start + j, at);
                at += 1;
            }
            if d.cap != 0 {
                self.index.pool.free(d.start, d.cap);
            }
        }
        self.index.tree.merge_subtree(top);
        let n = &mut self.index.nodes[top.index()];
        (n.start, n.cap) = (start, cap);
    }

    /// Lays the chunk array out again, leaf by leaf in Morton order with no slack, once its
    /// free space exceeds its live space.
    fn compact_if_sparse(&mut self) {
        if self.index.pool.wants_compaction() {
            self.compact();
        }
    }

    /// Lays the chunk array out again, leaf by leaf in Morton order, each chunk exactly its
    /// leaf's size: O(n + nodes).
    pub fn compact(&mut self) {
        let old = core::mem::take(&mut self.index.pool);
        let mut pool = super::Pool::with_capacity(self.len());
        for (id, _) in self.index.tree.leaves() {
            let d = &mut self.index.nodes[id.index()];
            let start = pool.points.len() as u32;
            for e in d.start..d.start + d.count {
                let slot = old.slots[e as usize];
                pool.points.push(old.points[e as usize]);
                pool.slots.push(slot);
                self.pos[slot as usize] = start + (e - d.start);
            }
            (d.start, d.cap) = (if d.count == 0 { 0 } else { start }, d.count);
        }
        self.index.pool = pool;
    }
}

impl<S: Scalar, T, const D: usize> PointSetMut<D> for DynamicPointTree<S, T, D> {
    /// Inserts `item` at `point` in amortised O(depth).
    ///
    /// # Errors
    /// A coordinate that is NaN or infinite, or outside [`DynamicPointTree::domain`](crate::query::PointSet::domain);
    /// more points than a `u32` can index.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{Aabb, DynamicPointTree, Octree};
    /// let root = Aabb::new([0.0; 3], [1.0; 3]).unwrap();
    /// let mut t = DynamicPointTree::from(Octree::builder().root_box(root).bucket_size(2).build(&[]).unwrap());
    /// for i in 0..100 {
    ///     t.insert([i as f64 / 100.0, 0.5, 0.5], i).unwrap();
    /// }
    /// assert_eq!(t.len(), 100);
    /// assert_eq!(t.in_box(&Aabb::new([0.0; 3], [0.095, 1.0, 1.0]).unwrap()).unwrap().count(), 10);
    /// assert!(t.insert([f64::NAN, 0.0, 0.0], 100).is_err());
    /// t.validate().unwrap();
    /// ```
    fn insert(&mut self, point: [S; D], item: T) -> Result<(), InsertError<T>> {
        let slot = self.len();
        let checked = Error::check_input(&point, Some(&self.domain), slot)
            .and_then(|_| Error::check_count(slot + 1));
        if let Err(error) = checked {
            return Err(InsertError { error, item });
        }
        let path = self.path(&point);
        for &u in &path {
            self.index.nodes[u.index()].count += 1;
        }
        let v = *path.last().expect("the path holds the root");
        // The count already includes the new entry: make room for it, then write it.
        let d = self.index.nodes[v.index()];
        if d.count > d.cap {
            self.relocate(v, cap_for(d.count), d.count - 1);
        }
        let d = self.index.nodes[v.index()];
        let at = d.start + d.count - 1;
        self.index.pool.points[at as usize] = point;
        self.index.pool.slots[at as usize] = slot as u32;
        self.items.push(item);
        self.pos.push(at);
        self.split_down(v);
        self.compact_if_sparse();
        Ok(())
    }

    /// Removes an item stored at exactly `point` that `wanted` accepts (the first in its leaf's
    /// chunk), in amortised O(depth + m) for the m points of that leaf (at most the bucket size,
    /// but every copy of a point at the maximum depth), and returns it; `None` (and nothing
    /// changed) when there is none.
    fn remove_where(&mut self, point: &[S; D], wanted: impl Fn(&T) -> bool) -> Option<T> {
        self.locate(point).ok()?.inside()?;
        let path = self.path(point);
        let v = *path.last().expect("the path holds the root");
        let ix = &self.index;
        let d = ix.nodes[v.index()];
        let (points, slots) = (&ix.pool.points, &ix.pool.slots);
        let at = (d.start..d.start + d.count).find(|&e| {
            points[e as usize] == *point && wanted(&self.items[slots[e as usize] as usize])
        })?;
        // The chunk's last entry fills the hole.
        let last = d.start + d.count - 1;
        let slot = self.index.pool.slots[at as usize];
        self.move_entry(last, at);
        self.index.pool.slots[last as usize] = GAP;
        for &u in &path {
            self.index.nodes[u.index()].count -= 1;
        }
        // The last slot fills the item's.
        let item = self.items.swap_remove(slot as usize);
        self.pos.swap_remove(slot as usize);
        if let Some(&e) = self.pos.get(slot as usize) {
            self.index.pool.slots[e as usize] = slot;
        }
        let ix = &self.index;
        if let Some(&top) = path.iter().find(|&&u| {
            !ix.tree.is_leaf(u) && ix.nodes[u.index()].count as usize <= self.bucket_size
        }) {
            self.merge(top);
        } else {
            let d = self.index.nodes[v.index()];
            if d.count == 0 {
                self.relocate(v, 0, 0);
            } else if d.cap > MIN_CAP && d.count * 4 < d.cap {
                self.relocate(v, cap_for(d.count), d.count);
            }
        }
        self.compact_if_sparse();
        Some(item)
    }
}
