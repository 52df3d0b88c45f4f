//! Compressed quadtrees and the skip quadtree: linear size whatever the input, and O(log n)
//! expected point location, insert and delete.
//!
//! - [`CompressedTree`]: the point quadtree of exercise 14.5 of de Berg, Cheong, van Kreveld and
//!   Overmars, *Computational Geometry* (chapter 14, and its notes, after Aluru's survey): a node
//!   only where the points branch. Its nodes are the root cell, every cell whose points fall into
//!   at least two of its children, and one leaf per distinct point cell at the finest level
//!   (level 64 on every axis, [`DeepCell`]; equal points, or points closer than the finest
//!   cell, share a leaf).
//!   Every node but the root has at least two children, so **a tree over `m` distinct finest
//!   cells (`m <= n`) has at most `2m` nodes** (`m` leaves, at most `m - 1` branching nodes, and
//!   the root): O(n) for any input, where the plain tree has O((d + 1) n) for depth d.
//!   Built from the Morton-sorted points in O(n log n) without the uncompressed tree
//!   (a stack over the sorted keys, [`CompressedTreeBuilder`]); insert and delete in O(depth).
//! - Every query of [`crate::query`] runs on it through [`CompressedIndex`], the same engines as
//!   [`PointTree`]'s.
//! - [`SkipQuadtree`]: Eppstein, Goodrich and Sun, "The skip quadtree: a simple dynamic data
//!   structure for multidimensional data" (SoCG 2005): compressed quadtrees over nested random
//!   samples, for expected O(log n) point location, insert and delete, and (1 + eps)-approximate
//!   nearest neighbours.
//! - [`Subdivision`] and [`PointLocator`]: point location in a planar subdivision with a
//!   quadtree, exercise 14.10.
//!
//! # Cells 64 levels deep
//! A compressed tree has a node only where points branch, so its size does not grow with the
//! depth of its cells, and its cells can be as fine as `f64` coordinates tell apart: 53
//! mantissa bits need 53 levels below a unit root box, beyond the 32 (2D) or 21 (3D) levels of
//! [`Cell`](crate::Cell), whose Morton keys fit a `u64`. Its cells are [`DeepCell`]s instead: 64
//! levels on every axis whatever D, each point keyed by its level-64 coordinates
//! ([`RootGeometry::deep_key`], a [`DeepKey`] of D `u64`s, compared in Morton order without
//! interleaving). Their split lines are [`RootGeometry`]'s down to level 32, exactly, so a
//! [`PointTree`] over the same root cube has the same cells down to its maximum depth, and
//! converting between the two trees moves no point to another cell: a compressed node deeper
//! than the point tree's cells lies in the point tree's cell [`DeepCell::to_cell`]. Below level
//! 32 each level-32 cell's `f64` values are split evenly by their order (the dyadic split,
//! rounded, inside one binade), so distinct coordinates get distinct cells wherever a level-32
//! cell holds at most 2^32 values, and a point on a line goes to the lower cell at every level;
//! cells holding no `f64` stay empty.
//!
//! [`PointLocator`] keeps [`Cell`](crate::Cell)s: its leaves hold edges, and cells finer than 32
//! levels would only add squares along close edges.

mod build;
mod index;
mod locate;
#[cfg(feature = "serde")]
mod parts;
mod skip;
mod subdivision;
pub(crate) mod topology;
mod update;

pub use build::CompressedTreeBuilder;
pub use index::CompressedIndex;
pub use locate::PointLocator;
pub use skip::SkipQuadtree;
pub use subdivision::{FaceId, Subdivision, SubdivisionError};

use crate::error::Error;
use crate::error::ValidationError;
use crate::geom::RootGeometry;
use crate::geom::{Aabb, DeepCell, DeepKey, Scalar};
use crate::points::PointTree;
use crate::query::{Location, PointSet, PositionSlots, QueryError};
use topology::NIL;

/// A compressed quadtree (D = 2), octree (D = 3) or 2^D-tree storing (point, item) pairs: the
/// point quadtree with every node that has a single non-empty child removed (exercise 14.5).
///
/// ```
/// use orthtree::prelude::*;
/// use orthtree::{CompressedTree, Quadtree};
/// // 100 points 2^-30 apart in the unit square: the plain tree is 32 levels deep
/// let mut pts: Vec<([f64; 2], usize)> =
///     (0..100).map(|i| ([0.3 + i as f64 * (-30f64).exp2(), 0.7], i)).collect();
/// pts.extend([([0.0, 0.0], 100), ([1.0, 1.0], 101)]);
/// let c = CompressedTree::new(&pts).unwrap();
/// let plain = Quadtree::builder().bucket_size(1).build(&pts).unwrap();
/// assert!(c.node_count() <= 2 * pts.len());
/// assert!(plain.node_count() > 2 * c.node_count());
/// assert_eq!(*c.nearest(&[0.3, 0.7]).unwrap().unwrap().item, 0);
/// // 2^-50 apart: one leaf of the plain tree, 64-level cells tell them apart
/// let close = [([0.3, 0.7], 0), ([0.3 + (-50f64).exp2(), 0.7], 1), ([1.0, 1.0], 2)];
/// let c = CompressedTree::new(&close).unwrap();
/// assert_eq!((c.leaf_count(), c.node_count()), (3, 5));
/// c.validate().unwrap();
/// ```
#[derive(Clone, Debug)]
pub struct CompressedTree<S, T, const D: usize> {
    index: CompressedIndex<S, D>,
    items: Vec<T>,
}

/// The node holding a point inside a [`CompressedTree`]'s or [`SkipQuadtree`]'s domain (what
/// their `locate` gives in [`Location::Inside`]): the deepest node whose cell holds it, and the
/// work it took.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Located<const D: usize> {
    /// The node's id in the tree's arena (valid until the next update).
    pub node: u32,
    /// Its cell (down to level 64; [`DeepCell::to_cell`] gives the [`PointTree`] cell holding
    /// it).
    pub cell: DeepCell<D>,
    /// `true` when the node is a leaf, i.e. points with the query's finest cell are stored.
    pub leaf: bool,
    /// The nodes visited on the way (the start node of every level included).
    pub touched: usize,
}

impl<S: Scalar, const D: usize> CompressedTree<S, (), D> {
    /// A builder for a root box; the item type comes from what it builds.
    pub fn builder() -> CompressedTreeBuilder<S, D> {
        CompressedTreeBuilder::new()
    }
}

impl<S: Scalar, T, const D: usize> CompressedTree<S, T, D> {
    /// Builds over the smallest enclosing cube of the points, cloning the items.
    ///
    /// # Errors
    /// A NaN, infinite or inexact coordinate (an integer `f64` cannot hold) (naming the point and axis); too many points.
    pub fn new(entries: &[([S; D], T)]) -> Result<Self, Error>
    where
        T: Clone,
    {
        CompressedTreeBuilder::new().build(entries)
    }

    /// The tree over `geometry` from points and items in Morton order.
    pub(crate) fn from_sorted(
        geometry: RootGeometry<D>,
        domain: Aabb<f64, D>,
        points: Vec<[S; D]>,
        items: Vec<T>,
    ) -> Self {
        CompressedTree {
            index: CompressedIndex::from_sorted(geometry, domain, points),
            items,
        }
    }

    /// The nodes, the root included; 0 for an empty tree. At most `2m` for `m` distinct finest
    /// cells, so at most `2n`.
    pub fn node_count(&self) -> usize {
        if self.is_empty() {
            0
        } else {
            self.index.topology.len()
        }
    }

    /// The number of leaves: the distinct finest cells holding points.
    pub fn leaf_count(&self) -> usize {
        let t = &self.index.topology;
        t.pre_order().filter(|&v| t.is_leaf(v)).count()
    }

    /// The number of edges on the longest root-to-leaf path (0 for an empty tree).
    pub fn depth(&self) -> usize {
        let t = &self.index.topology;
        let mut deepest = 0;
        let mut stack = Vec::from_iter((!t.is_empty()).then_some((0u32, 0usize)));
        while let Some((v, d)) = stack.pop() {
            deepest = deepest.max(d);
            stack.extend(t.children(v).map(|c| (c, d + 1)));
        }
        deepest
    }

    /// Where the cells lie in space.
    pub fn geometry(&self) -> &RootGeometry<D> {
        &self.index.geometry
    }

    /// The points, in storage (slot) order: build order at first, then changed by updates.
    pub fn points(&self) -> &[[S; D]] {
        &self.index.points
    }

    /// The cell of every node in pre-order (Morton order, ancestors first), with `true` for a
    /// leaf.
    pub fn cells(&self) -> impl Iterator<Item = (DeepCell<D>, bool)> + '_ {
        let t = &self.index.topology;
        t.pre_order().map(move |v| (t.node(v).cell, t.is_leaf(v)))
    }

    /// The deepest node whose cell holds `point`, walking down from the root, or
    /// [`Location::Outside`] for a point outside [`CompressedTree::domain`](crate::query::PointSet::domain).
    ///
    /// # Errors
    /// [`QueryError::NotFinite`] or [`QueryError::Inexact`] for a coordinate that is NaN,
    /// infinite or an integer `f64` cannot hold, naming its axis.
    ///
    /// # Complexity
    /// O(depth).
    ///
    /// ```
    /// use orthtree::query::Location;
    /// use orthtree::CompressedTree;
    /// let t = CompressedTree::new(&[([0.0, 0.0], 'a'), ([1.0, 1.0], 'b')]).unwrap();
    /// assert!(t.locate(&[1.0, 1.0]).unwrap().inside().unwrap().leaf);
    /// let empty_spot = t.locate(&[0.9, 0.1]).unwrap().inside().unwrap();
    /// assert_eq!((empty_spot.leaf, empty_spot.cell.level(), empty_spot.touched), (false, 0, 1));
    /// assert_eq!(t.locate(&[0.5, 1.5]), Ok(Location::Outside { axis: 1 }));
    /// ```
    pub fn locate(&self, point: &[S; D]) -> Result<Location<Located<D>>, QueryError> {
        Ok(self.query_key(point)?.map(|key| {
            let mut touched = 0;
            let v = self.index.topology.descend(0, &key, |_| touched += 1);
            self.located(v, touched)
        }))
    }

    pub(crate) fn located(&self, v: u32, touched: usize) -> Located<D> {
        let t = &self.index.topology;
        Located {
            node: v,
            cell: t.node(v).cell,
            leaf: t.is_leaf(v),
            touched,
        }
    }

    /// The finest key of a point to locate, checked ([`crate::geom::validate_point`]) and
    /// placed against the domain.
    pub(crate) fn query_key(&self, point: &[S; D]) -> Result<Location<DeepKey<D>>, QueryError> {
        Ok(crate::query::place_point(point, self.domain())?.map(|p| self.geometry().deep_key(&p)))
    }

    /// The equivalent [`PointTree`] with the same root cube and cells, with `bucket_size` and
    /// `max_depth` (as [`crate::points::PointTreeBuilder`] takes them): the points in Morton order, no
    /// sort. O(n + nodes).
    ///
    /// # Errors
    /// A zero bucket size; a maximum depth beyond
    /// [`Cell::MAX_LEVEL`](crate::Cell::MAX_LEVEL).
    pub fn to_point_tree(
        &self,
        bucket_size: usize,
        max_depth: u8,
    ) -> Result<PointTree<S, T, D>, Error>
    where
        T: Clone,
    {
        build::to_point_tree(self, bucket_size, max_depth)
    }
}

impl<S: Scalar, T, const D: usize> PointSet<D> for CompressedTree<S, T, D> {
    type Scalar = S;
    type Item = T;
    type Index = CompressedIndex<S, D>;

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

    /// The index the query engines run on: nodes, cells, and the points in Morton order.
    fn index(&self) -> &CompressedIndex<S, D> {
        &self.index
    }

    /// The items, in the order of [`CompressedTree::points`].
    fn items(&self) -> &[T] {
        &self.items
    }

    /// The closed box every point lies in (given to the builder, or the root cube up to
    /// `f64::MAX`).
    fn domain(&self) -> &Aabb<f64, D> {
        &self.index.domain
    }

    /// Checks every invariant and names the first one broken: the node arena
    /// (canonical: every non-root internal node branches, leaves are finest cells), every
    /// point's key and leaf, the leaves' lists, every leaf non-empty, every point in the domain.
    fn validate(&self) -> Result<(), ValidationError> {
        use crate::error::Invariant as I;
        let ix = &self.index;
        let t = &ix.topology;
        t.validate()
            .map_err(|e| ValidationError::new(I::Topology).detail(e))?;
        let n = self.len();
        if [ix.points.len(), ix.keys.len(), ix.leaf.len(), ix.prev.len()] != [n; 4] {
            return Err(ValidationError::new(I::Lengths).detail("slot arrays"));
        }
        let mut listed = 0;
        for v in t.pre_order().filter(|&v| t.is_leaf(v)) {
            let mut previous = NIL;
            for s in ix.leaf_slots(v) {
                listed += 1;
                if listed > n || ix.leaf[s] != v || ix.prev[s] != previous {
                    return Err(ValidationError::new(I::Links).node(v).point(s));
                }
                previous = s as u32;
            }
            if previous == NIL || t.node(v).tail != previous {
                return Err(ValidationError::new(I::Links)
                    .node(v)
                    .detail("empty leaf or wrong tail"));
            }
        }
        if listed != n {
            return Err(ValidationError::new(I::Counts)
                .detail(format!("{listed} of {n} points are in leaves")));
        }
        for (s, p) in ix.points.iter().enumerate() {
            let q = p.map(Scalar::to_f64);
            if !self.domain().contains(&q) {
                return Err(ValidationError::new(I::InDomain).point(s));
            }
            let key = self.geometry().deep_key(&q);
            if key != ix.keys[s] || t.node(ix.leaf[s]).cell.anchor() != key {
                return Err(ValidationError::new(I::InLeaf).node(ix.leaf[s]).point(s));
            }
        }
        Ok(())
    }

    /// Every (point, item), in storage order.
    fn iter(&self) -> impl ExactSizeIterator<Item = (&[S; D], &T)> + '_ {
        self.index.points.iter().zip(&self.items)
    }

    #[inline]
    fn point(&self, slot: usize) -> &[S; D] {
        &self.index.points[slot]
    }
}
