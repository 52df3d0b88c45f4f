//! The walk that checks a point tree's node runs over its stored arrays (first children, levels,
//! block parents, relative run ends) and lists its leaves with their absolute runs, for the
//! per-leaf bound check (`leaf_bounds.rs`). Shared by [`super::PointTree`]'s `validate` and the
//! borrowed view of a saved tree ([`crate::io::saved::PointTreeView`]), which has no
//! [`crate::Tree`] to lean on: the walk therefore also checks every link it follows.
//!
//! One pre-order walk from the root with an explicit stack (no recursion), O(node slots). At
//! each node reached: its recorded level is its cell's; an internal node is above
//! [`Cell::MAX_LEVEL`], its first child starts a block inside the arrays and that block records
//! the node as its parent (so every block is entered from one node only, and no node is reached
//! twice: the walk ends); its children's relative ends do not decrease, stay inside its run and
//! the last one ends it (the runs nest and partition); a leaf holds at most the bucket size
//! unless at the maximum depth, and an internal node more than the bucket size unless balance
//! split it. The root's run is every point. Blocks the walk does not reach (freed by removals)
//! hold no points and are not looked at; [`crate::Tree::validate`] checks them for the owned tree.

use super::leaf_bounds::LeafRun;
use crate::error::{Invariant, ValidationError};
use crate::geom::{Cell, Dim};

/// The stored arrays the walk reads (one entry per node slot, block parents per block).
#[derive(Clone, Copy, Debug)]
pub(crate) struct RunArrays<'a> {
    pub first_child: &'a [u32],
    pub level: &'a [u8],
    pub block_parent: &'a [u32],
    pub run_ends: &'a [u32],
}

/// What the walk checks leaf and node sizes against.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Sizes {
    /// Points held.
    pub points: usize,
    pub bucket_size: usize,
    pub max_depth: u8,
    /// Whether balance may have split nodes holding no more than the bucket size.
    pub balanced: bool,
}

/// A leaf's marker in `first_child`.
const NONE: u32 = u32::MAX;

fn topology(node: u32, detail: String) -> ValidationError {
    ValidationError::new(Invariant::Topology)
        .node(node)
        .detail(detail)
}

fn counts(node: u32, detail: &str) -> ValidationError {
    ValidationError::new(Invariant::Counts)
        .node(node)
        .detail(detail)
}

/// Walks the tree of `arrays` from the root (see the module doc) and returns its leaves in
/// pre-order (Morton order), whose runs tile `0..sizes.points`.
///
/// # Errors
/// The first broken invariant, naming the node: [`Invariant::Lengths`] for arrays of different
/// lengths; [`Invariant::Topology`] for a level, first child or block parent that is wrong;
/// [`Invariant::Counts`] for runs that do not nest and partition; [`Invariant::LeafSize`] and
/// [`Invariant::SplitNeeded`].
///
/// # Complexity
/// O(m) for m node slots; memory O(2^D depth) for the stack and O(leaves) for the result.
pub(crate) fn walk_runs<const D: usize>(
    arrays: RunArrays<'_>,
    sizes: Sizes,
) -> Result<Vec<LeafRun<D>>, ValidationError> {
    let children = Dim::<D>::CHILDREN;
    let slots = arrays.first_child.len();
    let blocks = slots.saturating_sub(1) / children;
    if slots == 0
        || arrays.level.len() != slots
        || arrays.run_ends.len() != slots
        || arrays.block_parent.len() != blocks
        || !(slots - 1).is_multiple_of(children)
        || sizes.points > u32::MAX as usize
    {
        return Err(ValidationError::new(Invariant::Lengths).detail(format!(
            "{slots} first children, {} levels, {} run ends, {} block parents ({} blocks), {} points \
             (at most 2^32 - 1)",
            arrays.level.len(),
            arrays.run_ends.len(),
            arrays.block_parent.len(),
            blocks,
            sizes.points
        )));
    }
    let n = sizes.points as u32;
    if arrays.run_ends[0] != n {
        return Err(counts(0, "the root does not own every point"));
    }
    let mut leaves = Vec::new();
    let mut stack: Vec<(u32, Cell<D>, u32, u32)> = vec![(0, Cell::root(), 0, n)];
    while let Some((v, cell, s, e)) = stack.pop() {
        let at = v as usize;
        let level = cell.level();
        if arrays.level[at] != level {
            let found = arrays.level[at];
            return Err(topology(
                v,
                format!("its level is {found}, its depth {level}"),
            ));
        }
        let count = (e - s) as usize;
        let first = arrays.first_child[at];
        if first == NONE {
            if super::splits(count, level, sizes.bucket_size, sizes.max_depth) {
                return Err(ValidationError::new(Invariant::LeafSize)
                    .node(v)
                    .detail(format!("holds {count} points")));
            }
            leaves.push(LeafRun {
                node: v,
                cell,
                start: s,
                end: e,
            });
            continue;
        }
        if level >= Cell::<D>::MAX_LEVEL {
            return Err(topology(
                v,
                format!(
                    "has children below the deepest level {}",
                    Cell::<D>::MAX_LEVEL
                ),
            ));
        }
        let f = first as usize;
        if f == 0 || !(f - 1).is_multiple_of(children) || f + children > slots {
            return Err(topology(
                v,
                format!("its first child {first} does not start a block of the {slots} slots"),
            ));
        }
        let parent = arrays.block_parent[(f - 1) / children];
        if parent != v {
            return Err(topology(
                v,
                format!("its child block {first} records the parent {parent}"),
            ));
        }
        if count <= sizes.bucket_size && !sizes.balanced {
            return Err(ValidationError::new(Invariant::SplitNeeded)
                .node(v)
                .detail(format!("holds {count} points")));
        }
        let ends = &arrays.run_ends[f..f + children];
        if ends[children - 1] != e - s {
            return Err(counts(v, "its children do not cover its run"));
        }
        if ends.windows(2).any(|w| w[0] > w[1]) {
            return Err(counts(v, "its children do not partition its run"));
        }
        // Children last first, so that the first is walked first (pre-order).
        for c in (0..children).rev() {
            let lo = if c == 0 { 0 } else { ends[c - 1] };
            stack.push((first + c as u32, cell.child(c), s + lo, s + ends[c]));
        }
    }
    Ok(leaves)
}
