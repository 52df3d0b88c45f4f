//! [`PointTree`]: the chapter's point quadtree (section 14.2) in D dimensions, with bucketed
//! leaves, built by Morton sort ([`PointTreeBuilder`]); point location; balance that moves the
//! points into the new leaves; and an invariant checker.
//!
//! Points are stored sorted by Morton key, so every node owns one contiguous run of them: a query
//! streams through memory, and a node wholly inside a region yields its run untested.

mod batch_update;
mod build;
#[cfg(test)]
mod dispatch_tests;
mod dynamic;
mod index;
pub(crate) mod leaf_bounds;
pub(crate) mod leaves;
#[cfg(feature = "rayon")]
mod parallel;
mod radix;
#[cfg(any(feature = "saved", feature = "serde"))]
mod raw;
pub(crate) mod run_walk;
mod runs;
mod update;

pub(crate) use build::splits;
pub use build::{PointTreeBuilder, DEFAULT_BUCKET_SIZE};
pub use dynamic::{DynamicIndex, DynamicNode, DynamicPointTree};
pub use index::PointNode;
#[cfg(feature = "saved")]
pub(crate) use index::{point_index, PointArrays};
pub use leaves::Leaf;

use crate::error::{Error, ValidationError};
pub(crate) use crate::geom::digit;
use crate::geom::{Aabb, Dim, RootGeometry, Scalar};
use crate::query::{Location, PointSet, QueryError};
use crate::tree::{BalanceOptions, NodeId, Tree};
#[cfg(any(feature = "saved", feature = "mpi"))]
pub(crate) use build::settle;
pub(crate) use build::{scan, visit_by_cell};
#[cfg(feature = "serde")]
pub(crate) use dynamic::DynamicParts;
#[cfg(feature = "serde")]
pub(crate) use raw::check_bucket;
#[cfg(any(feature = "saved", feature = "serde"))]
pub(crate) use raw::checked_root;
#[cfg(feature = "saved")]
pub(crate) use raw::PointTreeArrays;
#[cfg(any(feature = "saved", feature = "serde"))]
pub(crate) use raw::PointTreeParts;
pub(crate) use runs::Runs;
#[cfg(feature = "mpi")]
pub(crate) use {
    build::{index_bits, order_by_full_keys, pack},
    radix::sort_keyed,
};

/// A point quadtree (D = 2), octree (D = 3) or 2^D-tree storing (point, item) pairs.
///
/// Split convention (the chapter's): a coordinate equal to a split value goes to the lower child.
/// A leaf holds at most the bucket size of points unless it is at the maximum depth.
///
/// ```
/// use orthtree::prelude::*;
/// use orthtree::{Connectivity, Quadtree};
/// let pts: Vec<([f64; 2], usize)> = (0..100).map(|i| ([i as f64, (i * i % 100) as f64], i)).collect();
/// let mut t = Quadtree::new(&pts).unwrap();
/// assert_eq!(t.len(), 100);
/// let leaf = t.locate(&[42.0, 64.0]).unwrap().inside().unwrap();
/// assert!(t.node_items(leaf).contains(&42));
/// t.balance(Connectivity::Face);
/// assert!(t.tree().is_balanced(Connectivity::Face));
/// t.validate().unwrap();
/// ```
#[derive(Clone, Debug)]
pub struct PointTree<S, T, const D: usize> {
    tree: Tree<D>,
    geometry: RootGeometry<D>,
    domain: Aabb<f64, D>,
    points: Vec<[S; D]>,
    items: Vec<T>,
    runs: Runs,
    bucket_size: usize,
    max_depth: u8,
    balanced: Option<BalanceOptions>,
}

impl<S: Scalar, const D: usize> PointTree<S, (), D> {
    /// A builder for other settings; the item type comes from what it builds.
    pub fn builder() -> PointTreeBuilder<S, D> {
        PointTreeBuilder::new()
    }
}

/// A point quadtree over `f64` coordinates.
pub type Quadtree<T> = PointTree<f64, T, 2>;
/// A point octree over `f64` coordinates.
pub type Octree<T> = PointTree<f64, T, 3>;

impl<S: Scalar, T, const D: usize> PointTree<S, T, D> {
    /// Builds with the default settings ([`PointTreeBuilder::new`]), cloning the items.
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
        PointTreeBuilder::new().build(entries)
    }

    /// The points in Morton order.
    pub fn points(&self) -> &[[S; D]] {
        &self.points
    }

    /// The topology.
    pub fn tree(&self) -> &Tree<D> {
        &self.tree
    }

    /// The depth of the tree (0 for a single leaf).
    pub fn depth(&self) -> u8 {
        self.tree.depth()
    }

    /// The number of node slots ([`Tree::node_count`]): the nodes, plus slots freed by removals
    /// and not yet reused by later splits.
    pub fn node_count(&self) -> usize {
        self.tree.node_count()
    }

    /// The number of leaves.
    pub fn leaf_count(&self) -> usize {
        self.tree.leaf_count()
    }

    /// The bucket size it was built with.
    pub fn bucket_size(&self) -> usize {
        self.bucket_size
    }

    /// The maximum depth it was built with.
    pub fn max_depth(&self) -> u8 {
        self.max_depth
    }

    /// Where the cells lie in space.
    pub fn geometry(&self) -> &RootGeometry<D> {
        &self.geometry
    }

    /// The closed box of a node's cell.
    pub fn cell_box(&self, id: NodeId) -> Aabb<f64, D> {
        self.geometry.cell_box(&self.tree.cell(id))
    }

    /// The points in the cell of node `id` (all of its subtree's), in Morton order. O(depth):
    /// a node records its run relative to its parent's (`runs.rs`); [`PointTree::leaves`] and
    /// the queries carry the runs down instead.
    pub fn node_points(&self, id: NodeId) -> &[[S; D]] {
        &self.points[self.node_run(id)]
    }

    /// The items of [`PointTree::node_points`]. O(depth).
    pub fn node_items(&self, id: NodeId) -> &[T] {
        &self.items[self.node_run(id)]
    }

    /// The indices of the points of node `id`. O(depth).
    pub fn node_run(&self, id: NodeId) -> core::ops::Range<usize> {
        let (s, e) = self.runs.run(&self.tree, id);
        s as usize..e as usize
    }

    /// The node runs (see `runs.rs`).
    #[inline]
    pub(crate) fn runs(&self) -> &Runs {
        &self.runs
    }

    /// Geometry, domain, and the points and items in Morton order (the compressed tree's
    /// conversion and build take them).
    pub(crate) fn into_parts(self) -> (RootGeometry<D>, Aabb<f64, D>, Vec<[S; D]>, Vec<T>) {
        (self.geometry, self.domain, self.points, self.items)
    }

    /// A tree over `geometry` and `domain` from points in Morton order (checked by the caller),
    /// without sorting: the compressed tree's conversion back, so both trees share cells.
    pub(crate) fn from_sorted_parts(
        parts: (RootGeometry<D>, Aabb<f64, D>, Vec<[S; D]>, Vec<T>),
        bucket_size: usize,
        max_depth: u8,
    ) -> Self {
        let (geometry, domain, points, items) = parts;
        let mut tree = PointTree {
            tree: Tree::new(),
            geometry,
            domain,
            runs: Runs::new(points.len()),
            points,
            items,
            bucket_size,
            max_depth,
            balanced: None,
        };
        tree.subdivide(NodeId::ROOT, |p, i, _| geometry.scalar_key(&p[i]));
        tree
    }

    /// Heap bytes used: points, items, node runs and topology.
    pub fn heap_bytes(&self) -> usize {
        self.points.capacity() * core::mem::size_of::<[S; D]>()
            + self.items.capacity() * core::mem::size_of::<T>()
            + self.runs.heap_bytes()
            + self.tree.heap_bytes()
    }

    /// The leaf whose cell holds `point` under the split convention, or
    /// [`Location::Outside`] for a point outside [`PointTree::domain`](crate::query::PointSet::domain).
    ///
    /// # Errors
    /// [`QueryError::NotFinite`] or [`QueryError::Inexact`] for a coordinate that is NaN,
    /// infinite or an integer `f64` cannot hold, naming its axis.
    ///
    /// # Complexity
    /// O(depth).
    pub fn locate(&self, point: &[S; D]) -> Result<Location<NodeId>, QueryError> {
        Ok(crate::query::place_point(point, &self.domain)?.map(|p| {
            let key = self.geometry.key(&p);
            let mut v = NodeId::ROOT;
            while let Some(first) = self.tree.child(v, 0) {
                let c = digit::<D>(key, self.tree.level(v));
                v = NodeId(first.0 + c as u32);
            }
            v
        }))
    }

    /// Refines the tree to the coarsest balanced tree containing it ([`Tree::balance`]) and moves
    /// the points of every split leaf into its new children. Returns the leaves split.
    pub fn balance(&mut self, options: impl Into<BalanceOptions>) -> Vec<NodeId> {
        let options = options.into();
        let split = self.tree.balance(options);
        let geometry = self.geometry;
        let points = &self.points;
        // Parents first, so that each split leaf's run is known when its points are moved.
        let mut order = split.clone();
        order.sort_by_key(|&v| self.tree.level(v));
        for leaf in order {
            let (s, e) = self.runs.run(&self.tree, leaf);
            partition_children(&self.tree, &mut self.runs, leaf, (s, e), |i| {
                geometry.scalar_key(&points[i])
            });
        }
        self.balanced = Some(options);
        split
    }

    /// Splits below `start` while a node holds more than the bucket size and is above the
    /// maximum depth; `key(points, i, level)` is the Morton key of point `i`, or any value with
    /// the same digits down to level `level + 1` (the digit that splits a node at `level`).
    fn subdivide(&mut self, start: NodeId, key: impl Fn(&[[S; D]], usize, u8) -> u64) {
        let (tree, runs, points) = (&mut self.tree, &mut self.runs, &self.points);
        let mut stack = vec![(start, runs.run(tree, start))];
        while let Some((v, (s, e))) = stack.pop() {
            if !splits(
                (e - s) as usize,
                tree.level(v),
                self.bucket_size,
                self.max_depth,
            ) {
                continue;
            }
            tree.split(v);
            let level = tree.level(v);
            partition_children(tree, runs, v, (s, e), |i| key(points, i, level));
            let block = runs.block::<D>(tree.child(v, 0).expect("just split"));
            let mut lo = s;
            for (child, &end) in tree.children(v).zip(block) {
                stack.push((child, (lo, s + end)));
                lo = s + end;
            }
            // Children in child order: pop the first first.
            let top = stack.len() - Dim::<D>::CHILDREN;
            stack[top..].reverse();
        }
    }
}

/// Runs up to this long are partitioned in one pass over their digits, longer ones by a binary
/// search per child. The pass is branch-free and reads the run in order.
const LINEAR_PARTITION: u32 = 512;

/// Gives each child of the just-split node `v` its part of `v`'s run `(s, e)`, which is sorted
/// by key.
pub(crate) fn partition_children<const D: usize>(
    tree: &Tree<D>,
    runs: &mut Runs,
    v: NodeId,
    (s, e): (u32, u32),
    key: impl Fn(usize) -> u64,
) {
    let level = tree.level(v);
    if e - s <= LINEAR_PARTITION {
        // Short runs: one pass in which each point sets the end of its digit's part to just
        // after itself. The digits are sorted, so the last write is the part's end; plain stores
        // (2^D <= 256 children), where counting would chain each increment to the one before.
        let mut ends = [s; 256];
        for i in s..e {
            ends[digit::<D>(key(i as usize), level)] = i + 1;
        }
        // A child without points ends where the one before it does.
        let mut at = s;
        let ends = ends[..Dim::<D>::CHILDREN].iter().map(|&end| {
            at = at.max(end);
            at
        });
        runs.set_children(tree, v, s, ends);
        return;
    }
    let mut lo = s;
    let ends = (0..Dim::<D>::CHILDREN).map(|c| {
        // First index in lo..e whose digit exceeds c.
        let (mut a, mut b) = (lo, e);
        while a < b {
            let mid = a + (b - a) / 2;
            if digit::<D>(key(mid as usize), level) <= c {
                a = mid + 1;
            } else {
                b = mid;
            }
        }
        lo = a;
        a
    });
    runs.set_children(tree, v, s, ends);
}

impl<S: Scalar, T, const D: usize> PointTree<S, T, D> {
    /// [`PointSet::validate`](crate::query::PointSet::validate): checks every invariant and
    /// names the first one broken: the arena's ([`Tree::validate`]); node runs nest and
    /// partition their parent's; every point lies in its leaf's cell under the split convention
    /// and inside the domain, with coordinates `f64` holds exactly; within each leaf the points
    /// are in Morton order (with the cells in pre-order, that is Morton order throughout); a
    /// leaf holds more than the bucket size only at the maximum depth; an internal node holds
    /// more than the bucket size unless balance split it, and then the tree is balanced.
    fn check_invariants(&self) -> Result<(), ValidationError> {
        use crate::error::Invariant as I;
        (self.tree.validate())
            .map_err(|e| ValidationError::new(I::Topology).detail(e.to_string()))?;
        self.check_points_and_runs()
    }

    /// [`PointTree::check_invariants`] after [`Tree::validate`]: the run walk
    /// (`run_walk.rs`), the per-leaf bound check (`leaf_bounds.rs`, no keys), the Morton order
    /// within each leaf and balance. Both point passes run on rayon's threads with feature
    /// `rayon`.
    pub(crate) fn check_points_and_runs(&self) -> Result<(), ValidationError> {
        use crate::error::Invariant as I;
        if self.runs.len() != self.tree.node_count() || self.items.len() != self.len() {
            return Err(ValidationError::new(I::Lengths).detail(format!(
                "{} runs for {} nodes, {} items for {} points",
                self.runs.len(),
                self.tree.node_count(),
                self.items.len(),
                self.len()
            )));
        }
        let (first_child, level, block_parent) = self.tree.link_arrays();
        let arrays = run_walk::RunArrays {
            first_child,
            level,
            block_parent,
            run_ends: self.runs.ends(),
        };
        let sizes = run_walk::Sizes {
            points: self.points.len(),
            bucket_size: self.bucket_size,
            max_depth: self.max_depth,
            balanced: self.balanced.is_some(),
        };
        let leaves = run_walk::walk_runs::<D>(arrays, sizes)?;
        leaf_bounds::check_leaves(&self.geometry, &self.domain, &self.points, &leaves, true)?;
        leaf_bounds::check_leaf_order(&self.geometry, &self.points, &leaves, true)?;
        if let Some(options) = self.balanced
            && !self.tree.is_balanced(options)
        {
            return Err(ValidationError::new(I::Balanced));
        }
        Ok(())
    }
}
