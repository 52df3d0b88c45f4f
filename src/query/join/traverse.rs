//! The dual-tree traversal over node pairs (Gray and Moore, "N-body problems in statistical
//! learning", NIPS 2001): the engine of the radius joins ([`pairs`](super::pairs), the counts
//! and the sparse distance matrix).
//!
//! Start from the pair of roots. Pop a node pair from an explicit stack and let the caller
//! classify it by the distance range between the two boxes ([`PairDistance::box_box`]) and its
//! number of point pairs: skip it (no pair of its points is left to look at: none qualifies, or
//! a count took every pair whole by multiplying the sizes), or split it. A pair is split on the side with more points (both sides at
//! once for a node paired with itself, into the unordered pairs of its children); a pair of two
//! leaves (or of nodes small enough to scan, whose runs are contiguous) is handed to the caller
//! with both runs. A self-join starts from the root paired with itself, so each unordered pair
//! of points lies in exactly one node pair handed over. The stack holds at most about
//! `2^(2D)` entries per level: its depth never grows with recursion.

use super::bounds::PairDistance;
use crate::geom::Aabb;
use crate::query::index::{scans_whole, SpatialIndex};
use core::ops::{ControlFlow, Range};
use smallvec::SmallVec;

/// A node whose contiguous run holds at most this many points is scanned as if it were a leaf.
pub(crate) const SCAN: usize = 32;

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

/// The children of a node with their boxes; empty for a node to scan (a leaf, or a node whose
/// contiguous run holds at most [`SCAN`] points).
pub(crate) fn children<I: SpatialIndex<D>, const D: usize>(
    index: &I,
    side: &Side<I::Node, D>,
) -> SmallVec<[Side<I::Node, D>; 8]> {
    let mut out = SmallVec::new();
    if !scans_whole(index, side.0, SCAN) {
        index.for_each_child_in(side.0, &side.1, |c, cb| out.push((c, *cb)));
    }
    out
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

/// Expands one node pair: either hands it to the visitor (skip, whole, leaves) or pushes its
/// children pairs on `stack`. `same`: `b` is `a`'s node paired with itself in the same tree.
pub(crate) fn step<A, B, T, V, P, const D: usize>(
    a: &A,
    b: &B,
    metric: &P,
    pair: Pair<A::Node, B::Node, T, D>,
    visitor: &mut V,
    stack: &mut Vec<Pair<A::Node, B::Node, T, D>>,
) -> ControlFlow<V::Break>
where
    A: SpatialIndex<D>,
    B: SpatialIndex<D>,
    T: Clone,
    V: PairVisitor<A, B, T, D>,
    P: PairDistance<D>,
{
    let (sa, sb, same, state) = pair;
    let (near, far) = metric.box_box(&sa.1, &sb.1);
    let (na, nb) = (a.count(sa.0) as u64, b.count(sb.0) as u64);
    let pairs = if same {
        na * na.saturating_sub(1) / 2
    } else {
        na * nb
    };
    let state = match visitor.classify(&state, near, far, pairs) {
        Step::Skip => return ControlFlow::Continue(()),
        Step::Split(s) => s,
    };
    let ca = children(a, &sa);
    if same {
        // One node with itself: the unordered pairs of its children, each child with itself.
        if ca.is_empty() {
            return visitor.leaves(&state, (a.run(sa.0), &sa.1), (b.run(sb.0), &sb.1), true);
        }
        // The same tree on both sides: the children's handles are both A's and B's.
        let cb = children(b, &sb);
        for i in (0..ca.len()).rev() {
            for j in (i..cb.len()).rev() {
                stack.push((ca[i], cb[j], i == j, state.clone()));
            }
        }
        return ControlFlow::Continue(());
    }
    let cb = children(b, &sb);
    match (ca.is_empty(), cb.is_empty()) {
        (true, true) => visitor.leaves(&state, (a.run(sa.0), &sa.1), (b.run(sb.0), &sb.1), false),
        (false, true) => {
            for c in ca.into_iter().rev() {
                stack.push((c, sb, false, state.clone()));
            }
            ControlFlow::Continue(())
        }
        (true, false) => {
            for c in cb.into_iter().rev() {
                stack.push((sa, c, false, state.clone()));
            }
            ControlFlow::Continue(())
        }
        (false, false) => {
            if na >= nb {
                for c in ca.into_iter().rev() {
                    stack.push((c, sb, false, state.clone()));
                }
            } else {
                for c in cb.into_iter().rev() {
                    stack.push((sa, c, false, state.clone()));
                }
            }
            ControlFlow::Continue(())
        }
    }
}

/// Runs the traversal from `start` to the end, or until the visitor breaks.
pub(crate) fn run<A, B, T, V, P, const D: usize>(
    a: &A,
    b: &B,
    metric: &P,
    start: Vec<Pair<A::Node, B::Node, T, D>>,
    visitor: &mut V,
) -> ControlFlow<V::Break>
where
    A: SpatialIndex<D>,
    B: SpatialIndex<D>,
    T: Clone,
    V: PairVisitor<A, B, T, D>,
    P: PairDistance<D>,
{
    let mut stack = start;
    stack.reverse();
    while let Some(pair) = stack.pop() {
        step(a, b, metric, pair, visitor, &mut stack)?;
    }
    ControlFlow::Continue(())
}

/// The root pair of `a` and `b` (`same`: `b` is `a`), or nothing when either is empty.
pub(crate) fn roots<A: SpatialIndex<D>, B: SpatialIndex<D>, T, const D: usize>(
    a: &A,
    b: &B,
    same: bool,
    state: T,
) -> Vec<Pair<A::Node, B::Node, T, D>> {
    match (a.root(), b.root()) {
        (Some(ra), Some(rb)) => vec![(ra, rb, same, state)],
        _ => Vec::new(),
    }
}

/// Splits the traversal's top into at least `want` independent node pairs (fewer when the trees
/// are small), in traversal order: the pairs a parallel join hands to separate threads. Pairs
/// the visitor skips, and leaf pairs met on the way, are given to `visitor`.
#[cfg(feature = "rayon")]
pub(crate) fn split_top<A, B, T, V, P, const D: usize>(
    a: &A,
    b: &B,
    metric: &P,
    start: Vec<Pair<A::Node, B::Node, T, D>>,
    want: usize,
    visitor: &mut V,
) -> Vec<Pair<A::Node, B::Node, T, D>>
where
    A: SpatialIndex<D>,
    B: SpatialIndex<D>,
    T: Clone,
    V: PairVisitor<A, B, T, D, Break = core::convert::Infallible>,
    P: PairDistance<D>,
{
    let mut frontier = start;
    while !frontier.is_empty() && frontier.len() < want {
        let mut next = Vec::new();
        for pair in frontier {
            let mut out = Vec::new();
            let _ = step(a, b, metric, pair, visitor, &mut out);
            out.reverse();
            next.extend(out);
        }
        if next.is_empty() {
            return next;
        }
        frontier = next;
    }
    frontier
}
