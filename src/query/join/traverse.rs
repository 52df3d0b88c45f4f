//! The dual-tree traversal over node pairs (Gray and Moore, "N-body problems in statistical
//! learning", NIPS 2001): the engine of the radius joins ([`pairs`](super::pairs), the counts
//! and the sparse distance matrix).
//!
//! Start from the pair of roots. Every node pair is classified by the caller when it is made,
//! from the distance range between the two boxes ([`PairDistance::box_box`]) and its number of
//! point pairs: skipped (no pair of its points is left to look at: none qualifies, or a count
//! took every pair whole by multiplying the sizes), or kept on an explicit stack to be split,
//! so that the stack holds only pairs left to look at. A kept pair is split on the side with
//! more points (both sides at once for a node paired with itself, into the unordered pairs of
//! its children); a pair of two
//! leaves (or of nodes small enough to scan, whose runs are contiguous) is handed to the caller
//! with both runs. A self-join starts from the root paired with itself, so each unordered pair
//! of points lies in exactly one node pair handed over. The stack holds at most about
//! `2^(2D)` entries per level: its depth never grows with recursion. The steps are the methods
//! of [`Dual`] (the two indices and their distance).

use super::bounds::PairDistance;
use crate::geom::Aabb;
use crate::query::index::{scan_limit, scans_whole, SpatialIndex};
use core::marker::PhantomData;
use core::ops::{ControlFlow, Range};
use smallvec::SmallVec;

/// A node whose contiguous run holds at most this many points is scanned as if it were a leaf
/// by the k-nearest joins.
pub(crate) const SCAN: usize = 32;

/// The same for the radius joins, whose leaf kernel filters each run by the other node's box.
pub(crate) const SCAN_RADIUS: usize = 128;

/// What to do with a node pair, decided from its boxes.
pub(crate) enum Step<T> {
    /// No pair of points of the two nodes is left to look at.
    Skip,
    /// Look closer, with this state handed to the node pair's descendants.
    Split(T),
}

/// One side of a node pair: the node and its closed box.
pub(crate) type Side<N, const D: usize> = (N, Aabb<f64, D>);

/// A pending node pair: both sides, whether it is a node paired with itself, the caller's state.
pub(crate) type Pair<A, B, T, const D: usize> = (Side<A, D>, Side<B, D>, bool, T);

/// The children of a node with their boxes.
pub(crate) type Kids<N, const D: usize> = SmallVec<[Side<N, D>; 8]>;

/// The children of a node with their boxes; empty for a node to scan (a leaf, or a node whose
/// contiguous run holds at most `scan` points, more from 6D up: [`scan_limit`]).
#[inline]
pub(crate) fn children<I: SpatialIndex<D>, const D: usize>(
    index: &I,
    side: &Side<I::Node, D>,
    scan: usize,
) -> Kids<I::Node, D> {
    let mut out = SmallVec::new();
    push_children(index, side, scan, |c| out.push(c));
    out
}

/// Hands the children of a node with their boxes to `push` ([`children`]); hands nothing for
/// a node to scan. Pushing onto a buffer the caller keeps saves the copy of a returned list,
/// which was a tenth of the radius joins' time (and a push per child, not `Extend` with a
/// one-item iterator, which reserved room on every call: a twentieth).
#[inline(always)]
pub(crate) fn push_children<I: SpatialIndex<D>, const D: usize>(
    index: &I,
    side: &Side<I::Node, D>,
    scan: usize,
    mut push: impl FnMut(Side<I::Node, D>),
) {
    if !scans_whole(index, side.0, scan_limit::<D>(scan)) {
        index.for_each_child_in(side.0, &side.1, |c, cb| push((c, *cb)));
    }
}

/// The callbacks of [`traverse`].
pub(crate) trait PairVisitor<A: SpatialIndex<D>, B: SpatialIndex<D>, T, const D: usize> {
    /// What the traversal stops with.
    type Break;
    /// Classifies a node pair from its boxes' distance range `(near, far)`; `pairs` is its
    /// number of point pairs (unordered, of distinct points, for a node with itself).
    fn classify(&mut self, state: &T, near: f64, far: f64, pairs: u64) -> Step<T>;
    /// A pair of scanned nodes: their runs and closed boxes (the same node when `same`).
    fn leaves(
        &mut self,
        state: &T,
        a: (Range<usize>, &Aabb<f64, D>),
        b: (Range<usize>, &Aabb<f64, D>),
        same: bool,
    ) -> ControlFlow<Self::Break>;
}

/// The node pairs a traversal's top is split into, or the visitor's break met on the way.
#[cfg(feature = "rayon")]
pub(crate) type Frontier<A, B, T, Br, const D: usize> = ControlFlow<Br, Vec<Pair<A, B, T, D>>>;

/// The two indices of a dual-tree traversal and the distance between their points: the
/// traversal's steps are its methods. The dimension is a parameter of the type (the last field
/// only marks it), so that their bounds are stated once.
pub(crate) struct Dual<'a, A, B, P, const D: usize>(&'a A, &'a B, &'a P, PhantomData<[(); D]>);

impl<A, B, P, const D: usize> Clone for Dual<'_, A, B, P, D> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<A, B, P, const D: usize> Copy for Dual<'_, A, B, P, D> {}

impl<'a, A: SpatialIndex<D>, B: SpatialIndex<D>, P: PairDistance<D>, const D: usize>
    Dual<'a, A, B, P, D>
{
    /// The traversal of `a` against `b` under `metric`.
    pub(crate) fn new(a: &'a A, b: &'a B, metric: &'a P) -> Self {
        Dual(a, b, metric, PhantomData)
    }

    /// Classifies the node pair of `sa` and `sb` (`same`: one node with itself) by its boxes'
    /// distance range and number of point pairs, and pushes it on `stack` unless the visitor
    /// skips it: only pairs left to look at are held.
    #[inline(always)]
    fn offer<T, V: PairVisitor<A, B, T, D>>(
        self,
        (sa, sb, same): (Side<A::Node, D>, Side<B::Node, D>, bool),
        state: &T,
        visitor: &mut V,
        stack: &mut Vec<Pair<A::Node, B::Node, T, D>>,
    ) {
        let Dual(a, b, metric, _) = self;
        let (near, far) = metric.box_box(&sa.1, &sb.1);
        let (na, nb) = (a.count(sa.0) as u64, b.count(sb.0) as u64);
        let pairs = if same {
            na * na.saturating_sub(1) / 2
        } else {
            na * nb
        };
        if let Step::Split(s) = visitor.classify(state, near, far, pairs) {
            stack.push((sa, sb, same, s));
        }
    }

    /// Expands one classified node pair: hands a pair of nodes to scan to the visitor, or
    /// classifies the pairs of its children ([`Dual::offer`]) and pushes those left to look at on
    /// `stack`. `same`: `b` is `a`'s node paired with itself in the same tree. `kids`: the buffers
    /// of both sides' children, kept by the caller from pair to pair.
    fn step<T, V: PairVisitor<A, B, T, D>>(
        self,
        (sa, sb, same, state): Pair<A::Node, B::Node, T, D>,
        visitor: &mut V,
        stack: &mut Vec<Pair<A::Node, B::Node, T, D>>,
        (ca, cb): &mut (Kids<A::Node, D>, Kids<B::Node, D>),
    ) -> ControlFlow<V::Break> {
        let Dual(a, b, ..) = self;
        ca.clear();
        cb.clear();
        push_children(a, &sa, SCAN_RADIUS, |c| ca.push(c));
        if same {
            // One node with itself: the unordered pairs of its children, each child with itself.
            if ca.is_empty() {
                return visitor.leaves(&state, (a.run(sa.0), &sa.1), (b.run(sb.0), &sb.1), true);
            }
            // The same tree on both sides: the children's handles are both A's and B's.
            push_children(b, &sb, SCAN_RADIUS, |c| cb.push(c));
            for i in (0..ca.len()).rev() {
                for j in (i..cb.len()).rev() {
                    self.offer((ca[i], cb[j], i == j), &state, visitor, stack);
                }
            }
            return ControlFlow::Continue(());
        }
        // Split the side with more points; look at `b`'s children only when they may be needed.
        if ca.is_empty() || a.count(sa.0) < b.count(sb.0) {
            push_children(b, &sb, SCAN_RADIUS, |c| cb.push(c));
            if !cb.is_empty() {
                for &c in cb.iter().rev() {
                    self.offer((sa, c, false), &state, visitor, stack);
                }
                return ControlFlow::Continue(());
            }
            if ca.is_empty() {
                return visitor.leaves(&state, (a.run(sa.0), &sa.1), (b.run(sb.0), &sb.1), false);
            }
        }
        for &c in ca.iter().rev() {
            self.offer((c, sb, false), &state, visitor, stack);
        }
        ControlFlow::Continue(())
    }

    /// Runs the traversal from the classified pairs `start` to the end, or until the visitor
    /// breaks.
    pub(crate) fn run<T, V: PairVisitor<A, B, T, D>>(
        self,
        start: Vec<Pair<A::Node, B::Node, T, D>>,
        visitor: &mut V,
    ) -> ControlFlow<V::Break> {
        let mut stack = start;
        stack.reverse();
        let mut kids = (SmallVec::new(), SmallVec::new());
        while let Some(pair) = stack.pop() {
            self.step(pair, visitor, &mut stack, &mut kids)?;
        }
        ControlFlow::Continue(())
    }

    /// The root pair of `a` and `b` (`same`: `b` is `a`) classified by `visitor` from `state`:
    /// nothing when either is empty or the visitor skips it.
    pub(crate) fn roots<T, V: PairVisitor<A, B, T, D>>(
        self,
        same: bool,
        state: T,
        visitor: &mut V,
    ) -> Vec<Pair<A::Node, B::Node, T, D>> {
        let mut out = Vec::new();
        if let (Some(ra), Some(rb)) = (self.0.root(), self.1.root()) {
            self.offer((ra, rb, same), &state, visitor, &mut out);
        }
        out
    }

    /// Splits the traversal's top into at least `want` independent node pairs (fewer when the trees
    /// are small), in traversal order: the pairs a parallel join hands to separate threads. Pairs
    /// the visitor skips, and leaf pairs met on the way, are given to `visitor`, whose break ends
    /// the split and is returned.
    #[cfg(feature = "rayon")]
    pub(crate) fn split_top<T, V: PairVisitor<A, B, T, D>>(
        self,
        start: Vec<Pair<A::Node, B::Node, T, D>>,
        want: usize,
        visitor: &mut V,
    ) -> Frontier<A::Node, B::Node, T, V::Break, D> {
        let mut frontier = start;
        let mut kids = (SmallVec::new(), SmallVec::new());
        while !frontier.is_empty() && frontier.len() < want {
            let mut next = Vec::new();
            for pair in frontier {
                let mut out = Vec::new();
                self.step(pair, visitor, &mut out, &mut kids)?;
                out.reverse();
                next.extend(out);
            }
            frontier = next;
        }
        ControlFlow::Continue(frontier)
    }
}
