//! [`DynamicPointTree`]: the point tree for interleaved updates and queries, with insert and
//! remove in amortised O(depth) and every query of [`PointTree`].
//!
//! [`PointTree`] keeps its points in one dense array in Morton order, so every node owns one
//! contiguous run; that is what makes its build and its queries fast, and what makes a single
//! update move O(n) bytes (see `points/update.rs`). This tree trades the runs of inner nodes for
//! O(depth) updates, as a pointer-based quadtree does:
//!
//! - each leaf keeps its points in a *chunk* of a shared array (`pool.rs`), a block with slack
//!   that grows and shrinks by doubling and halving, anywhere in the array;
//! - the items sit apart in *slot* order (insertion order, a removal moving the last slot into
//!   the hole), each chunk entry holding its item's slot, and each slot its entry's position;
//! - every node counts the points below it, which decides splits and merges.
//!
//! The shape is the point tree's rule, so after any sequence of updates the tree has exactly
//! the leaves (cells), and the points per leaf, of a [`PointTree`] freshly built from the same
//! (point, item) pairs with the same root box, bucket size and maximum depth: a node is split
//! exactly when it holds more than the bucket size and is above the maximum depth.
//!
//! # Cost
//! With the bucket size B and the dimension D fixed, every update costs amortised O(depth):
//! - an insert descends to its leaf (O(depth), counting) and appends to the leaf's chunk: O(1),
//!   or, when the chunk is full, a move to one twice its size (amortised O(1), as in a growing
//!   `Vec`). A leaf then over B splits, its B + 1 entries going to chunks of its children, and
//!   again below while they all fall in one child: O(B + 2^D depth) at worst;
//! - a remove descends, finds the entry in its leaf's chunk (O(B), but O(m) in a leaf at the
//!   maximum depth holding m copies of one point, which no split parts: removing all of them
//!   one at a time is O(m^2)), takes it out (the chunk's last entry fills the hole; a chunk
//!   under a quarter full moves to a smaller one, amortised O(1)), and merges the shallowest
//!   ancestor left with B points into one leaf: O(B + 2^D depth) at worst;
//! - freed chunks are reused by size; once the free space exceeds the live space, the whole
//!   array is laid out again leaf by leaf in Morton order (O(n), after Ω(n) freed entries:
//!   amortised O(1)).
//!
//! The shape cannot lag behind (it must be a fresh build's at every step), so inserting and
//! removing one point at a cell holding B points splits and merges each time: O(B) per update,
//! independent of n.
//!
//! # Queries
//! The index ([`DynamicIndex`]) is a [`SpatialIndex`] without nested runs
//! ([`SpatialIndex::NESTED_RUNS`] is `false`): the shared engines descend to the leaves and scan
//! their chunks, so every query of [`PointSet`] is here with its name and meaning.
//! [`Neighbor::index`](crate::Neighbor::index) is the item's slot (its position in
//! [`PointSet::items`]); k-nearest ties go by position in the chunk array
//! (Morton order after a build or a compaction; deterministic for a given sequence of calls).
//!
//! Memory, per point: the point and a 4-byte slot per chunk entry, and a 4-byte position. A
//! build (and a compaction) leaves one entry per point; updates leave chunks between a quarter
//! full and full (at most twice the entries once they have grown by inserts) and at most as
//! many free entries as live ones. Per node: 12 bytes (count, chunk start and size) beside the
//! topology.

mod index;
#[cfg(feature = "serde")]
mod parts;
mod pool;
mod update;

pub use index::{DynamicIndex, DynamicNode};
#[cfg(feature = "serde")]
pub(crate) use parts::DynamicParts;

use super::{splits, PointTree};
use crate::error::{Error, ValidationError};
use crate::geom::RootGeometry;
use crate::geom::{Aabb, Cell, Scalar};
use crate::query::{PointSet, PositionSlots};
use crate::tree::Tree;
use pool::{Pool, GAP};

/// What a node of a [`DynamicIndex`] records beside the topology.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct NodeData {
    /// The number of points below the node (for a leaf, the entries of its chunk).
    count: u32,
    /// A leaf's chunk: its first entry in the pool.
    start: u32,
    /// A leaf's chunk: its number of entries (0 for none).
    cap: u32,
}

/// A point tree whose single inserts and removes cost amortised O(depth); see the module doc.
///
/// ```
/// use orthtree::prelude::*;
/// use orthtree::{Aabb, DynamicPointTree, Quadtree};
/// let root = Aabb::new([0.0, 0.0], [1.0, 1.0]).unwrap();
/// let built = Quadtree::builder().root_box(root).bucket_size(1).build(&[]).unwrap();
/// let mut t = DynamicPointTree::from(built);
/// t.insert([0.25, 0.25], 'a').unwrap();
/// t.insert([0.75, 0.75], 'b').unwrap();
/// assert_eq!(t.leaf_count(), 4);
/// assert_eq!(*t.nearest(&[0.7, 0.9]).unwrap().unwrap().item, 'b');
/// assert!(t.insert([2.0, 0.0], 'c').is_err()); // outside the root box
/// assert!(t.remove(&[0.75, 0.75], &'b'));
/// assert_eq!(t.leaf_count(), 1); // merged back: as if built from 'a' alone
/// t.validate().unwrap();
/// ```
#[derive(Clone, Debug)]
pub struct DynamicPointTree<S, T, const D: usize> {
    index: DynamicIndex<S, D>,
    /// The items in slot order.
    items: Vec<T>,
    /// The pool position of each slot's entry.
    pos: Vec<u32>,
    domain: Aabb<f64, D>,
    bucket_size: usize,
    max_depth: u8,
}

impl<S: Scalar, T, const D: usize> From<PointTree<S, T, D>> for DynamicPointTree<S, T, D> {
    /// The dynamic form of a built tree, in O(n + nodes): the same leaves, each leaf's run
    /// becoming its chunk (a balanced tree's refinement is dropped first, as its first update
    /// would). Build with [`PointTree::builder`] to choose the root box, bucket size and
    /// maximum depth.
    fn from(mut t: PointTree<S, T, D>) -> Self {
        if t.balanced.is_some() {
            t.rebuild_canonical();
        }
        let mut nodes = vec![NodeData::default(); t.tree.node_count()];
        let mut starts = vec![0u32; t.tree.node_count()];
        for (id, _) in t.tree.pre_order() {
            let start = starts[id.index()];
            let count = t.runs.count::<D>(id);
            nodes[id.index()] = NodeData {
                count,
                start: 0,
                cap: 0,
            };
            if let Some(first) = t.tree.child(id, 0) {
                let mut s = start;
                for (i, &end) in t.runs.block::<D>(first).iter().enumerate() {
                    starts[first.index() + i] = s;
                    s = start + end;
                }
            } else if count != 0 {
                nodes[id.index()].start = start;
                nodes[id.index()].cap = count;
            }
        }
        let n = t.points.len() as u32;
        DynamicPointTree {
            index: DynamicIndex {
                tree: t.tree,
                geometry: t.geometry,
                nodes,
                pool: Pool::dense(t.points),
            },
            items: t.items,
            pos: (0..n).collect(),
            domain: t.domain,
            bucket_size: t.bucket_size,
            max_depth: t.max_depth,
        }
    }
}

impl<S: Scalar, T, const D: usize> DynamicPointTree<S, T, D> {
    /// Builds with [`PointTree::new`]'s defaults (the root box the enclosing cube of the points),
    /// cloning the items.
    ///
    /// # Errors
    /// [`Error::NonFiniteCoordinate`] or [`Error::InexactCoordinate`] for a coordinate that is NaN,
    /// infinite or an integer `f64` cannot hold, [`Error::OutsideRootBox`] for a point outside a
    /// given root box (each naming the point, axis and value), [`Error::InvalidRootBox`],
    /// [`Error::ZeroBucketSize`], [`Error::MaxDepthTooLarge`], [`Error::TooManyPoints`].
    pub fn new(entries: &[([S; D], T)]) -> Result<Self, Error>
    where
        T: Clone,
    {
        PointTree::new(entries).map(Self::from)
    }

    /// The topology.
    pub fn tree(&self) -> &Tree<D> {
        &self.index.tree
    }

    /// Where the cells lie in space.
    pub fn geometry(&self) -> &RootGeometry<D> {
        &self.index.geometry
    }

    /// The bucket size it was built with.
    pub fn bucket_size(&self) -> usize {
        self.bucket_size
    }

    /// The maximum depth it was built with.
    pub fn max_depth(&self) -> u8 {
        self.max_depth
    }

    /// The number of leaves.
    pub fn leaf_count(&self) -> usize {
        self.index.tree.leaf_count()
    }

    /// The leaves in Morton order, each with its cell and the slots of its points (in chunk
    /// order).
    ///
    /// ```
    /// use orthtree::DynamicPointTree;
    /// let t = DynamicPointTree::new(&[([0.0, 0.0], 'a'), ([1.0, 1.0], 'b')]).unwrap();
    /// let leaves: Vec<_> = t.leaves().collect();
    /// assert_eq!(leaves.len(), 1);
    /// assert_eq!(leaves[0].1, [0, 1]);
    /// ```
    pub fn leaves(&self) -> impl Iterator<Item = (Cell<D>, &[u32])> + '_ {
        self.index.tree.leaves().map(|(id, cell)| {
            let d = self.index.nodes[id.index()];
            let s = d.start as usize;
            (cell, &self.index.pool.slots[s..s + d.count as usize])
        })
    }

    /// Bytes of heap memory held, items included.
    pub fn heap_bytes(&self) -> usize {
        self.index.tree.heap_bytes()
            + self.index.nodes.capacity() * core::mem::size_of::<NodeData>()
            + self.index.pool.heap_bytes()
            + self.items.capacity() * core::mem::size_of::<T>()
            + self.pos.capacity() * 4
    }
}

impl<S: Scalar, T, const D: usize> PointSet<D> for DynamicPointTree<S, T, D> {
    type Scalar = S;
    type Item = T;
    type Index = DynamicIndex<S, D>;

    #[inline(always)]
    fn item_of<'a>(&'a self, payload: &'a u32) -> &'a T {
        &self.items[*payload as usize]
    }

    #[inline(always)]
    fn slot_of(&self, _: usize, payload: &u32) -> usize {
        *payload as usize
    }

    #[inline]
    fn position_slots(&self) -> PositionSlots<'_> {
        PositionSlots::Table(crate::query::SpatialIndex::payloads(&self.index))
    }

    /// The index the queries run on.
    fn index(&self) -> &DynamicIndex<S, D> {
        &self.index
    }

    /// The items in slot order: insertion order, except that a removal moves the last item
    /// into the removed one's place.
    fn items(&self) -> &[T] {
        &self.items
    }

    /// The point of the item in `slot`.
    ///
    /// # Panics
    /// If `slot >= len()`.
    fn point(&self, slot: usize) -> &[S; D] {
        &self.index.pool.points[self.pos[slot] as usize]
    }

    /// The box points may be inserted in.
    fn domain(&self) -> &Aabb<f64, D> {
        &self.domain
    }

    /// Checks every invariant: counts add up; a leaf over the bucket size only at the maximum
    /// depth and an inner node only over it (the canonical shape); every point in its leaf's
    /// cell and the domain; chunks inside the pool and disjoint; slots and positions inverse.
    fn validate(&self) -> Result<(), ValidationError> {
        use crate::error::Invariant as I;
        let ix = &self.index;
        (ix.tree.validate())
            .map_err(|e| ValidationError::new(I::Topology).detail(e.to_string()))?;
        if ix.nodes.len() < ix.tree.node_count() || self.pos.len() != self.items.len() {
            return Err(ValidationError::new(I::Lengths)
                .detail("one record per node and one position per item"));
        }
        if ix.nodes[0].count as usize != self.len() {
            return Err(
                ValidationError::new(I::Counts).detail("the root does not count every point")
            );
        }
        let mut owned = vec![false; ix.pool.len()];
        for (id, cell) in ix.tree.pre_order() {
            let d = ix.nodes[id.index()];
            if let Some(first) = ix.tree.child(id, 0) {
                let sum: u32 = (0..1 << D).map(|i| ix.nodes[first.index() + i].count).sum();
                if sum != d.count {
                    return Err(ValidationError::new(I::Counts)
                        .node(id.0)
                        .detail(format!("its children count {sum} of {}", d.count)));
                }
                if d.count as usize <= self.bucket_size {
                    return Err(ValidationError::new(I::SplitNeeded)
                        .node(id.0)
                        .detail(format!("holds {} points", d.count)));
                }
                continue;
            }
            if splits(
                d.count as usize,
                cell.level(),
                self.bucket_size,
                self.max_depth,
            ) {
                return Err(ValidationError::new(I::LeafSize)
                    .node(id.0)
                    .detail(format!("holds {} points", d.count)));
            }
            if d.count > d.cap || (d.start + d.cap) as usize > ix.pool.len() {
                return Err(ValidationError::new(I::Links)
                    .node(id.0)
                    .detail("its chunk is too small or outside the pool"));
            }
            for e in d.start..d.start + d.cap {
                if std::mem::replace(&mut owned[e as usize], true) {
                    return Err(ValidationError::new(I::Links)
                        .node(id.0)
                        .detail(format!("entry {e} belongs to two chunks")));
                }
                let slot = ix.pool.slots[e as usize];
                if e >= d.start + d.count {
                    continue;
                }
                if slot as usize >= self.len() || self.pos[slot as usize] != e {
                    return Err(ValidationError::new(I::Links)
                        .point(slot as usize)
                        .detail(format!("entry {e} and its slot disagree")));
                }
                let p = ix.pool.points[e as usize].map(Scalar::to_f64);
                if !self.domain.contains(&p) {
                    return Err(ValidationError::new(I::InDomain).point(slot as usize));
                }
                let key = ix.geometry.key(&p);
                if Cell::from_aligned_key(key, cell.level()) != cell {
                    return Err(ValidationError::new(I::InLeaf)
                        .node(id.0)
                        .point(slot as usize));
                }
            }
        }
        if let Some(e) = (0..ix.pool.len()).find(|&e| !owned[e] && ix.pool.slots[e] != GAP) {
            return Err(
                ValidationError::new(I::Links).detail(format!("free entry {e} holds a slot"))
            );
        }
        Ok(())
    }

    /// Every (point, item) in slot order.
    fn iter(&self) -> impl ExactSizeIterator<Item = (&[S; D], &T)> + '_ {
        self.pos
            .iter()
            .zip(&self.items)
            .map(|(&p, t)| (&self.index.pool.points[p as usize], t))
    }
}
