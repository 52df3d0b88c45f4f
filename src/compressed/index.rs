//! [`CompressedIndex`]: the points of a compressed quadtree with its nodes, and the
//! [`SpatialIndex`] through which every query engine of [`crate::query`] runs on it.
//!
//! # Layout, and why
//! Updates must cost O(depth), so the points cannot live in one array kept in Morton order (an
//! insert would shift half of it). They live in *slots* instead: `points[s]`, `keys[s]` and the
//! tree's `items[s]`, in no particular order; a new point takes the next slot and a removal moves
//! the last slot into the hole (O(1)). Each leaf (one Morton key) links its slots in a doubly
//! linked list, so duplicates are added and removed in O(1) too.
//!
//! The query engines want each node's points as one contiguous run of an array in Morton order.
//! That array is part of a *view*, built lazily on the first query after a change by two passes
//! over the pre-order (O(n), no sort: the tree's pre-order is Morton order) and dropped by the
//! next update. The view is a frozen copy of the tree for reading: the nodes renumbered in
//! pre-order (the [`SpatialIndex`] node handles), each with its run, its closed cell box and its
//! children as one contiguous range, and the points in Morton order with the slot each came from
//! (the index's payloads, which [`super::CompressedTree`] maps back to its items). Queries
//! then walk arrays in the order they are stored, as on the point tree.

use super::topology::{Topology, NIL};
use crate::geom::deep::morton_cmp;
use crate::geom::{Aabb, DeepKey, RootGeometry, Scalar};
use crate::query::SpatialIndex;
use core::ops::Range;
use std::sync::OnceLock;

/// The nodes and points of a compressed quadtree, as a [`SpatialIndex`] whose payloads are slot
/// numbers (positions in [`CompressedTree::items`](crate::query::PointSet::items)).
///
/// ```
/// use orthtree::prelude::*;
/// use orthtree::query::SpatialIndex;
/// use orthtree::CompressedTree;
/// let t = CompressedTree::new(&[([0.0, 0.0], 'a'), ([1.0, 1.0], 'b')]).unwrap();
/// let index = t.index();
/// let (root, _) = index.root().unwrap();
/// assert_eq!(index.run(root), 0..2);
/// let mut leaves = 0;
/// assert!(index.for_each_child(root, |_, _| leaves += 1));
/// assert_eq!(leaves, 2);
/// ```
#[derive(Debug)]
pub struct CompressedIndex<S, const D: usize> {
    pub(crate) geometry: RootGeometry<D>,
    pub(crate) domain: Aabb<f64, D>,
    pub(crate) topology: Topology<D>,
    pub(crate) points: Vec<[S; D]>,
    pub(crate) keys: Vec<DeepKey<D>>,
    /// The leaf of each slot, and its neighbours in the leaf's list.
    pub(crate) leaf: Vec<u32>,
    pub(crate) prev: Vec<u32>,
    pub(crate) next: Vec<u32>,
    view: OnceLock<View<S, D>>,
}

impl<S: Clone, const D: usize> Clone for CompressedIndex<S, D> {
    fn clone(&self) -> Self {
        CompressedIndex {
            geometry: self.geometry,
            domain: self.domain,
            topology: self.topology.clone(),
            points: self.points.clone(),
            keys: self.keys.clone(),
            leaf: self.leaf.clone(),
            prev: self.prev.clone(),
            next: self.next.clone(),
            view: OnceLock::new(),
        }
    }
}

/// The frozen form the queries read: the nodes renumbered in pre-order (Morton order) with
/// their runs, closed cell boxes and children as contiguous ranges, and the points in Morton
/// order with the slot each came from.
#[derive(Debug)]
struct View<S, const D: usize> {
    points: Vec<[S; D]>,
    slots: Vec<u32>,
    /// Per pre-order node: its run, its box, and its children `children[kids.0..kids.1]`
    /// (empty for a leaf).
    runs: Vec<(u32, u32)>,
    boxes: Vec<Aabb<f64, D>>,
    kids: Vec<(u32, u32)>,
    children: Vec<u32>,
}

impl<S: Scalar, const D: usize> CompressedIndex<S, D> {
    /// An index over `geometry` from points in any order, fastest when already in deep Morton
    /// order; equal keys share a leaf, in the order given. The slots are the positions given.
    ///
    /// Points in the Morton order of [`Cell`](crate::Cell) keys (a point tree's order) are in
    /// deep order except where several share a finest [`Cell`]: one pass checks the order, and
    /// only when it fails does a stable sort of slot numbers by deep key run (Rust's merge sort,
    /// near-linear on such nearly sorted runs).
    pub(crate) fn from_sorted(
        geometry: RootGeometry<D>,
        domain: Aabb<f64, D>,
        points: Vec<[S; D]>,
    ) -> Self {
        let keys: Vec<DeepKey<D>> = points
            .iter()
            .map(|p| geometry.deep_key(&p.map(Scalar::to_f64)))
            .collect();
        let order = deep_order(&keys);
        Self::from_keyed(geometry, domain, points, keys, order)
    }

    /// The index of `points` with their deep `keys`, taken in `order` (slot numbers; `None` for
    /// `0..n`), which must be a deep Morton order of the keys: equal keys share a leaf, listed
    /// in this order.
    pub(crate) fn from_keyed(
        geometry: RootGeometry<D>,
        domain: Aabb<f64, D>,
        points: Vec<[S; D]>,
        keys: Vec<DeepKey<D>>,
        order: Option<Vec<u32>>,
    ) -> Self {
        let slot = |i: usize| order.as_ref().map_or(i, |o| o[i] as usize);
        let n = keys.len();
        let starts: Vec<usize> = (0..n)
            .filter(|&i| i == 0 || keys[slot(i)] != keys[slot(i - 1)])
            .collect();
        let mut leaf = vec![NIL; n];
        let mut prev = vec![NIL; n];
        let mut next = vec![NIL; n];
        let leaves = starts.iter().map(|&i| keys[slot(i)]);
        let topology = Topology::from_sorted(leaves, |t, node, g| {
            let (s, e) = (starts[g], starts.get(g + 1).copied().unwrap_or(n));
            t.nodes[node as usize].head = slot(s) as u32;
            t.nodes[node as usize].tail = slot(e - 1) as u32;
            for i in s..e {
                let here = slot(i);
                leaf[here] = node;
                prev[here] = if i == s { NIL } else { slot(i - 1) as u32 };
                next[here] = if i + 1 == e { NIL } else { slot(i + 1) as u32 };
            }
        });
        CompressedIndex {
            geometry,
            domain,
            topology,
            points,
            keys,
            leaf,
            prev,
            next,
            view: OnceLock::new(),
        }
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// `true` when no point is stored.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Where the cells lie in space (the same map as [`crate::PointTree::geometry`]).
    pub fn geometry(&self) -> &RootGeometry<D> {
        &self.geometry
    }

    fn view(&self) -> &View<S, D> {
        self.view.get_or_init(|| self.build_view())
    }

    /// Drops the view (after any change).
    pub(crate) fn changed(&mut self) {
        self.view.take();
    }

    /// The frozen form: two passes over the pre-order (runs, boxes and children forward, the
    /// internal nodes' run ends backward). O(n).
    fn build_view(&self) -> View<S, D> {
        let t = &self.topology;
        let order: Vec<u32> = t.pre_order().collect();
        let mut rank = vec![NIL; t.nodes.len()];
        for (i, &v) in order.iter().enumerate() {
            rank[v as usize] = i as u32;
        }
        let m = order.len();
        let (mut runs, mut boxes) = (Vec::with_capacity(m), Vec::with_capacity(m));
        let (mut kids, mut children) = (Vec::with_capacity(m), Vec::with_capacity(m));
        let mut slots = Vec::with_capacity(self.len());
        for &v in &order {
            let start = slots.len() as u32;
            slots.extend(self.leaf_slots(v).map(|s| s as u32));
            runs.push((start, slots.len() as u32));
            boxes.push(self.geometry.deep_cell_box(&t.node(v).cell));
            let first = children.len() as u32;
            children.extend(t.children(v).map(|c| rank[c as usize]));
            kids.push((first, children.len() as u32));
        }
        for i in (0..m).rev() {
            let (first, end) = kids[i];
            if first < end {
                runs[i].1 = runs[children[end as usize - 1] as usize].1;
            }
        }
        let points = slots.iter().map(|&s| self.points[s as usize]).collect();
        View {
            points,
            slots,
            runs,
            boxes,
            kids,
            children,
        }
    }

    /// Stores `point` with finest key `key` in a new slot at the end of `leaf`'s list.
    pub(crate) fn push_slot(&mut self, point: [S; D], key: DeepKey<D>, leaf: u32) {
        let s = self.points.len() as u32;
        let tail = self.topology.node(leaf).tail;
        self.points.push(point);
        self.keys.push(key);
        self.leaf.push(leaf);
        self.prev.push(tail);
        self.next.push(NIL);
        self.link(leaf, tail, s, NIL, s);
        self.changed();
    }

    /// Takes slot `s` out of its leaf's list (removing the leaf from the tree if it empties, and
    /// returning it then, else NIL), then moves the last slot into `s`: call `swap_remove(s)` on
    /// any array parallel to the slots.
    pub(crate) fn remove_slot(&mut self, s: usize) -> u32 {
        let leaf = self.leaf[s];
        self.unlink(s);
        let removed = if self.topology.node(leaf).head == NIL {
            self.topology.remove_leaf(leaf);
            leaf
        } else {
            NIL
        };
        let last = self.points.len() - 1;
        if s != last {
            // Whatever pointed at `last` points at `s` now.
            let (lp, ln, ll) = (self.prev[last], self.next[last], self.leaf[last]);
            self.link(ll, lp, s as u32, ln, s as u32);
        }
        self.points.swap_remove(s);
        self.keys.swap_remove(s);
        self.leaf.swap_remove(s);
        self.prev.swap_remove(s);
        self.next.swap_remove(s);
        self.changed();
        removed
    }

    fn unlink(&mut self, s: usize) {
        let (p, x, leaf) = (self.prev[s], self.next[s], self.leaf[s]);
        self.link(leaf, p, x, x, p);
    }

    /// Relinks the list of `leaf` around a place between slots `p` and `x` (NIL for the list's
    /// ends): what follows `p` (the head when `p` is NIL) becomes `after`, what precedes `x` (the
    /// tail when `x` is NIL) becomes `before`.
    fn link(&mut self, leaf: u32, p: u32, after: u32, x: u32, before: u32) {
        match p {
            NIL => self.topology.nodes[leaf as usize].head = after,
            p => self.next[p as usize] = after,
        }
        match x {
            NIL => self.topology.nodes[leaf as usize].tail = before,
            x => self.prev[x as usize] = before,
        }
    }

    /// The slots of `leaf`, in list order (none for an inner node).
    pub(crate) fn leaf_slots(&self, leaf: u32) -> impl Iterator<Item = usize> + '_ {
        let mut s = self.topology.node(leaf).head;
        core::iter::from_fn(move || {
            (s != NIL).then(|| {
                let here = s as usize;
                s = self.next[here];
                here
            })
        })
    }
}

impl<S: Scalar, const D: usize> SpatialIndex<D> for CompressedIndex<S, D> {
    type Scalar = S;
    type Payload = u32;
    type Node = u32;

    #[inline]
    fn points(&self) -> &[[S; D]] {
        &self.view().points
    }

    #[inline]
    fn payloads(&self) -> &[u32] {
        &self.view().slots
    }

    fn root(&self) -> Option<(u32, Aabb<f64, D>)> {
        (!self.topology.is_empty()).then(|| (0, self.view().boxes[0]))
    }

    #[inline]
    fn run(&self, node: u32) -> Range<usize> {
        let (s, e) = self.view().runs[node as usize];
        s as usize..e as usize
    }

    #[inline]
    fn for_each_child(&self, node: u32, mut f: impl FnMut(u32, &Aabb<f64, D>)) -> bool {
        let view = self.view();
        let (first, end) = view.kids[node as usize];
        for &c in &view.children[first as usize..end as usize] {
            f(c, &view.boxes[c as usize]);
        }
        first < end
    }
}

/// `None` when `keys` are in Morton order, else the positions sorted by key (stable: equal keys
/// keep their order).
fn deep_order<const D: usize>(keys: &[DeepKey<D>]) -> Option<Vec<u32>> {
    if keys.windows(2).all(|w| morton_cmp(&w[0], &w[1]).is_le()) {
        return None;
    }
    let mut order: Vec<u32> = (0..keys.len() as u32).collect();
    order.sort_by(|&a, &b| morton_cmp(&keys[a as usize], &keys[b as usize]));
    Some(order)
}
