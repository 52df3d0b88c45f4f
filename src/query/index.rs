//! [`SpatialIndex`]: the little a query engine needs from a tree (a root, children with their
//! closed boxes, and one contiguous run of points per node).
//!
//! The engines of this module ([`range`](super::range), nearest neighbours, the nearest
//! iterator) are written against this trait only, so any hierarchy of boxes over a point array
//! gets every query by implementing five methods. Each tree implements it where the tree is
//! defined, and reaches the engines through [`PointSet`](super::PointSet), whose provided
//! methods are the user-facing queries.

use super::metric::Metric;
use crate::geom::Halves;
use crate::geom::{Aabb, Scalar};
use core::ops::Range;

/// A tree of closed boxes over one array of points, each node owning a contiguous run of it.
///
/// Contract: the run of a node is the union of its children's runs; every point of a node's run
/// lies in the node's closed box (as `f64`); a node without children is a leaf. An index whose
/// leaves keep their points apart (a [`crate::DynamicPointTree`]'s leaves are blocks with
/// slack, anywhere in its array) sets [`SpatialIndex::NESTED_RUNS`] to `false`: then only
/// leaves have runs (an inner node's is empty) and [`SpatialIndex::count`] counts a node's
/// points.
///
/// ```
/// use orthtree::query::SpatialIndex;
/// use orthtree::Quadtree;
/// let t = Quadtree::new(&[([0.0, 0.0], 'a'), ([1.0, 1.0], 'b')]).unwrap();
/// let (root, bbox) = t.root().unwrap();
/// assert_eq!(t.run(root), 0..2);
/// assert!(bbox.contains(&[1.0, 1.0]));
/// let mut children = 0;
/// let internal = t.for_each_child(root, |_, _| children += 1);
/// assert_eq!((internal, children), (false, 0)); // two points fit one bucket
/// ```
pub trait SpatialIndex<const D: usize> {
    /// The coordinate type of the points.
    type Scalar: Scalar;
    /// What the index stores with each point (see [`SpatialIndex::payloads`]).
    type Payload;
    /// A handle on a node, small and cheap to copy (and to hand to another thread: the
    /// parallel joins split a traversal into node pairs).
    type Node: Copy + PartialEq + Send + Sync;

    /// `true` when every node owns one contiguous run, the union of its children's (the
    /// engines then scan a small inner node's run without descending, and report an inside
    /// node's run whole); `false` when only leaves have runs (the engines then descend to the
    /// leaves). Decided at compile time: the engines' other branch is not generated.
    const NESTED_RUNS: bool = true;

    /// `true` when [`SpatialIndex::for_each_child_unless`] leaves out the children in the halves
    /// that are out (not every child handed, as the default does): the k-nearest search and the
    /// region queries then ask it even of a node they scan whole, and scan only the children
    /// left (from 6D up). Decided at
    /// compile time, like [`SpatialIndex::NESTED_RUNS`].
    const LEAVES_OUT_HALVES: bool = false;

    /// Every point, in the order the runs index.
    fn points(&self) -> &[[Self::Scalar; D]];
    /// What the index stores with each point, in the order of [`SpatialIndex::points`]: the
    /// items themselves, or the numbers of the tree's slots holding them
    /// ([`PointSet::item_of`](super::PointSet::item_of) maps one to its item).
    fn payloads(&self) -> &[Self::Payload];
    /// The root and its closed box; `None` when the index holds no point.
    fn root(&self) -> Option<(Self::Node, Aabb<f64, D>)>;
    /// The indices of the node's points (of a leaf's only, when not
    /// [`SpatialIndex::NESTED_RUNS`]: an inner node's run is then empty).
    fn run(&self, node: Self::Node) -> Range<usize>;

    /// The number of points in the node's subtree; the default is its run's length.
    #[inline]
    fn count(&self, node: Self::Node) -> usize {
        self.run(node).len()
    }
    /// Calls `f` with every child whose run is not empty, and its closed box; returns `false`
    /// (calling nothing) for a leaf.
    fn for_each_child(&self, node: Self::Node, f: impl FnMut(Self::Node, &Aabb<f64, D>)) -> bool;

    /// [`SpatialIndex::for_each_child`] for a node whose closed box `bbox` the caller already
    /// holds (from [`SpatialIndex::root`] or an earlier call), so that an index can build the
    /// children's boxes from it. The default ignores `bbox`.
    #[inline]
    fn for_each_child_in(
        &self,
        node: Self::Node,
        bbox: &Aabb<f64, D>,
        f: impl FnMut(Self::Node, &Aabb<f64, D>),
    ) -> bool {
        let _ = bbox;
        self.for_each_child(node, f)
    }

    /// [`SpatialIndex::for_each_child_in`] for a search that wants no point of the halves of
    /// `bbox` (either side of a split line) that `out` rules out ([`Halves`]; any
    /// `Fn(&Aabb) -> bool` saying a box holds no wanted point is one): an index may leave out
    /// the children in them without bounding them one by one. The default hands every child.
    #[inline(always)]
    fn for_each_child_unless(
        &self,
        node: Self::Node,
        bbox: &Aabb<f64, D>,
        out: impl Halves<D>,
        f: impl FnMut(Self::Node, &Aabb<f64, D>),
    ) -> bool {
        let _ = out;
        self.for_each_child_in(node, bbox, f)
    }

    /// The child of `node` (whose closed box `bbox` the caller holds) to search first for
    /// points near `q`: the non-empty child whose box is nearest under `metric`, the first of
    /// equals, with its box; `None` for a leaf. The nearest-neighbour engines walk these down
    /// from the root to seed their bound. The default bounds every child; an index that can
    /// tell the child holding `q` directly may override it, returning the same child.
    #[inline]
    fn nearest_child<M: Metric<D>>(
        &self,
        node: Self::Node,
        bbox: &Aabb<f64, D>,
        q: &[f64; D],
        metric: &M,
    ) -> Option<(Self::Node, Aabb<f64, D>)> {
        nearest_child_by_boxes(self, node, bbox, q, metric)
    }
}

/// The most points a node's contiguous run may hold for an engine to scan it whole rather than
/// descend: the engine's own `base` (measured in 2D and 3D) below 6D, and from 6D up at least
/// 4 per child (4 × 2^D). There a node has up to 2^D children, each of which costs D operations
/// to bound and a place on the engine's stack, as much as measuring a point: a node of 4 points
/// per child is scanned at about the cost of looking at its children. Measured with kiddo's
/// k-nearest queries beside (10^6 uniform points, k = 10): 6D 1.8x, 8D 1.7x faster than with the
/// base limits; 4D and 5D were slower with it, so they keep theirs.
#[inline(always)]
pub(crate) const fn scan_limit<const D: usize>(base: usize) -> usize {
    if D < 6 {
        return base;
    }
    let per_children = 4usize << (if D < 16 { D } else { 16 });
    if per_children > base {
        per_children
    } else {
        base
    }
}

/// Whether the engines scan `node`'s run whole rather than descend: its run is contiguous
/// ([`SpatialIndex::NESTED_RUNS`]) and holds at most `limit` points. (A leaf is scanned
/// either way.)
#[inline(always)]
pub(crate) fn scans_whole<I: SpatialIndex<D>, const D: usize>(
    index: &I,
    node: I::Node,
    limit: usize,
) -> bool {
    I::NESTED_RUNS && index.count(node) <= limit
}

/// The fewest points per child (on average) for which the engines ask for the halves of a node
/// they scan whole ([`for_each_kept_run`]): below it the halves' tests and the walk over the
/// children cost more than the points they spare (6D, 20 tight clusters, 10^5 10-NN queries:
/// 4-10% slower than scanning whole from 1 point per child, 2-5% from 2).
const HALVES_MIN: usize = 2;

/// The runs of points of a node the engines scan whole: in 2D-5D never more than one, and
/// from 6D up at most 2^(D-1) (every other child kept), inline up to 8D so that no query
/// allocates for them.
pub(crate) type Runs = smallvec::SmallVec<[Range<usize>; 128]>;

/// For a node (`node`, box `b`) small enough to be scanned whole: from 6D up, when the index
/// [leaves out halves](SpatialIndex::LEAVES_OUT_HALVES) and the node holds at least
/// [`HALVES_MIN`] points per child, hands `keep` the runs of the children outside the halves of
/// `b` that `out` rules out ([`SpatialIndex::for_each_child_unless`]), adjacent runs joined, and
/// returns `true`; otherwise (a leaf, fewer dimensions, fewer points) hands nothing and returns
/// `false`: the caller scans the node's whole run.
///
/// In 6D such a node holds up to 256 points in 64 children, of which a query's ball reaches a
/// fraction. 10^6 uniform points, 2 x 10^5 1-NN queries, alternated: 1880-1979 -> 1630-1672
/// ms. In 4D and 5D no gain was measured for the k-nearest search (nodes of at most 48
/// points); the region queries' 128-point nodes there were not tried with it.
#[inline(always)]
pub(crate) fn for_each_kept_run<I: SpatialIndex<D>, const D: usize>(
    index: &I,
    node: I::Node,
    b: &Aabb<f64, D>,
    out: impl Halves<D>,
    mut keep: impl FnMut(Range<usize>),
) -> bool {
    if !(I::LEAVES_OUT_HALVES && D >= 6 && index.count(node) >= HALVES_MIN << D) {
        return false;
    }
    let mut open = 0..0;
    let inner = index.for_each_child_unless(node, b, out, |child, _| {
        let next = index.run(child);
        if open.end == next.start {
            open.end = next.end;
        } else {
            let done = core::mem::replace(&mut open, next);
            if !done.is_empty() {
                keep(done);
            }
        }
    });
    if inner && !open.is_empty() {
        keep(open);
    }
    inner
}

/// [`SpatialIndex::nearest_child`] by bounding every child: the first child whose box is nearest.
#[inline]
pub(crate) fn nearest_child_by_boxes<I: SpatialIndex<D> + ?Sized, M: Metric<D>, const D: usize>(
    index: &I,
    node: I::Node,
    bbox: &Aabb<f64, D>,
    q: &[f64; D],
    metric: &M,
) -> Option<(I::Node, Aabb<f64, D>)> {
    let mut next: Option<(f64, I::Node, Aabb<f64, D>)> = None;
    index.for_each_child_in(node, bbox, |child, cb| {
        let d = metric.box_distance(q, cb);
        if next.as_ref().is_none_or(|n| d < n.0) {
            next = Some((d, child, *cb));
        }
    });
    next.map(|(_, child, cb)| (child, cb))
}

/// An index of one leaf holding every point (what a tree keeps at the maximum depth), for the
/// unit tests of the engines on copies of one point.
#[cfg(test)]
pub(crate) struct OneLeaf(pub(crate) Vec<[f64; 3]>);

#[cfg(test)]
impl SpatialIndex<3> for OneLeaf {
    type Scalar = f64;
    type Payload = [f64; 3];
    type Node = ();
    fn points(&self) -> &[[f64; 3]] {
        &self.0
    }
    fn payloads(&self) -> &[[f64; 3]] {
        &self.0
    }
    fn root(&self) -> Option<((), Aabb<f64, 3>)> {
        Some(((), Aabb::around(&self.0)))
    }
    fn run(&self, (): ()) -> Range<usize> {
        0..self.0.len()
    }
    fn for_each_child(&self, (): (), _: impl FnMut((), &Aabb<f64, 3>)) -> bool {
        false
    }
}
