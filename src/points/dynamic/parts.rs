//! A [`DynamicPointTree`]'s stored arrays and settings, for serde: a borrowed view
//! ([`DynamicPointTree::view`]) and the checked constructor that takes owned parts back
//! ([`DynamicPointTree::from_parts`]) without sorting, splitting or moving any point.
//!
//! What is kept is what the queries and updates read: the topology, the root cube, the domain,
//! the settings, per node its count and chunk (start, size), the chunk array (points and the
//! slot of each entry) and the items in slot order. Each slot's position is derived (the entry
//! holding it), and so are the free lists (every run of entries outside the chunks), so a tree
//! read back answers every query exactly as the one written, ties included.
//!
//! The check: the settings' ranges and the root cube ([`checked_root`]), the topology
//! ([`Tree::from_raw_parts`]), then, in 64-bit arithmetic so that no claimed count or chunk can
//! overflow, every node's count against its children's and every leaf's chunk against the
//! array; then the tree's own `validate` (every point in the domain and its leaf's cell, the
//! canonical shape, chunks disjoint, slots and positions inverse). Linear in the entries and
//! nodes.

use super::pool::Pool;
use super::{DynamicIndex, DynamicPointTree, NodeData};
use crate::error::{Invariant, ValidationError};
use crate::geom::{Aabb, Scalar};
use crate::points::{check_bucket, checked_root};
use crate::query::PointSet;
use crate::tree::raw::{OwnedRawTree, RawTree};
use crate::tree::Tree;

/// Everything a [`DynamicPointTree`] stores: `Tr` its arena's arrays, then sequences of
/// points, of slots and of items.
#[derive(Clone, Debug)]
pub(crate) struct DynamicFields<Tr, P, U, I, const D: usize> {
    pub tree: Tr,
    /// The root cube's lower corner halved (rounded down) and half its side.
    pub half_lo: [f64; D],
    pub half_side: f64,
    pub domain: Aabb<f64, D>,
    pub bucket_size: usize,
    pub max_depth: u8,
    /// Per node of the arena: its count of points, its chunk's start and size.
    pub nodes: Vec<[u32; 3]>,
    /// The chunk array: a point and its item's slot per entry (`u32::MAX` for free space).
    pub points: P,
    pub slots: U,
    /// The items in slot order.
    pub items: I,
}

/// Everything a [`DynamicPointTree`] stores, by reference (the node records copied).
pub(crate) type DynamicView<'a, S, T, const D: usize> =
    DynamicFields<RawTree<'a>, &'a [[S; D]], &'a [u32], &'a [T], D>;

/// The owned form of [`DynamicView`], which [`DynamicPointTree::from_parts`] checks.
pub(crate) type DynamicParts<S, T, const D: usize> =
    DynamicFields<OwnedRawTree, Vec<[S; D]>, Vec<u32>, Vec<T>, D>;

impl<S: Scalar, T, const D: usize> DynamicPointTree<S, T, D> {
    /// The stored arrays and settings.
    pub(crate) fn view(&self) -> DynamicView<'_, S, T, D> {
        let ix = &self.index;
        let (half_lo, half_side) = ix.geometry.halves();
        let nodes = ix.nodes[..ix.tree.node_count()]
            .iter()
            .map(|d| [d.count, d.start, d.cap])
            .collect();
        DynamicView {
            tree: ix.tree.raw_parts(),
            half_lo,
            half_side,
            domain: self.domain,
            bucket_size: self.bucket_size,
            max_depth: self.max_depth,
            nodes,
            points: &ix.pool.points,
            slots: &ix.pool.slots,
            items: &self.items,
        }
    }

    /// The tree of `parts`, checked (see the module doc); nothing is sorted or moved.
    ///
    /// # Errors
    /// The first broken invariant: [`Invariant::Settings`] for a bucket size of 0, a maximum
    /// depth beyond [`Cell::MAX_LEVEL`](crate::Cell::MAX_LEVEL), a root cube or domain that is
    /// not finite, or a domain outside the cube; [`Invariant::Lengths`] for arrays of the wrong
    /// lengths;
    /// [`Invariant::Topology`] naming the [`crate::tree::TreeError`]; [`Invariant::Counts`] or
    /// [`Invariant::Links`] naming the node whose count or chunk is wrong, or the entry whose
    /// slot is out of range; then whatever the tree's `validate` finds.
    ///
    /// # Complexity
    /// O(e + m log e) for e entries in the chunk array and m node slots.
    pub(crate) fn from_parts(parts: DynamicParts<S, T, D>) -> Result<Self, ValidationError> {
        let lengths = |detail: String| ValidationError::new(Invariant::Lengths).detail(detail);
        check_bucket::<D>(parts.bucket_size, parts.max_depth)?;
        let geometry = checked_root(parts.half_lo, parts.half_side, &parts.domain)?;
        let (entries, n) = (parts.points.len(), parts.items.len());
        if parts.slots.len() != entries || entries >= u32::MAX as usize || n > entries {
            return Err(lengths(format!(
                "{entries} points, {} slots and {n} items in the chunk array (one slot per \
                 point, fewer than 2^32 - 1 entries, at most one item per entry)",
                parts.slots.len()
            )));
        }
        let tree = Tree::from_raw_parts(parts.tree)
            .map_err(|e| ValidationError::new(Invariant::Topology).detail(e.to_string()))?;
        if parts.nodes.len() != tree.node_count() {
            return Err(lengths(format!(
                "{} node records for {} node slots",
                parts.nodes.len(),
                tree.node_count()
            )));
        }
        let Entries { owned, live, pos } =
            check_nodes(&tree, &parts.nodes, &parts.slots, n, parts.max_depth)?;
        let mut nodes = vec![NodeData::default(); tree.node_count()];
        for (id, _) in tree.pre_order() {
            let [count, start, cap] = parts.nodes[id.index()];
            nodes[id.index()] = NodeData { count, start, cap };
        }
        let t = DynamicPointTree {
            index: DynamicIndex {
                tree,
                geometry,
                nodes,
                pool: Pool::restore(parts.points, parts.slots, &owned, &live),
            },
            items: parts.items,
            pos,
            domain: parts.domain,
            bucket_size: parts.bucket_size,
            max_depth: parts.max_depth,
        };
        t.validate()?;
        Ok(t)
    }
}

/// What [`check_nodes`] finds of the chunk array: which entries lie in a chunk, which are live,
/// and each slot's entry.
struct Entries {
    owned: Vec<bool>,
    live: Vec<bool>,
    pos: Vec<u32>,
}

/// Checks every live node's record against `tree` and the chunk array (`slots`, for `n` items)
/// in 64-bit arithmetic: a leaf's count within its chunk and its chunk within the array, an
/// inner node above `max_depth`, without a chunk and counting what its children count, the
/// root counting `n`, and
/// every live entry's slot below `n`. Returns which entries lie in a chunk, which are live, and
/// each slot's entry (`u32::MAX` where none claims it, which `validate` then refuses).
fn check_nodes<const D: usize>(
    tree: &Tree<D>,
    nodes: &[[u32; 3]],
    slots: &[u32],
    n: usize,
    max_depth: u8,
) -> Result<Entries, ValidationError> {
    let links = |id: u32, detail: String| {
        Err(ValidationError::new(Invariant::Links)
            .node(id)
            .detail(detail))
    };
    if nodes[0][0] as usize != n {
        return Err(ValidationError::new(Invariant::Counts)
            .node(0u32)
            .detail(format!("the root counts {} points of {n}", nodes[0][0])));
    }
    let (mut owned, mut live) = (vec![false; slots.len()], vec![false; slots.len()]);
    let mut pos = vec![u32::MAX; n];
    for (id, cell) in tree.pre_order() {
        let [count, start, cap] = nodes[id.index()];
        if let Some(first) = tree.child(id, 0) {
            if cell.level() >= max_depth {
                return Err(ValidationError::new(Invariant::Topology)
                    .node(id.0)
                    .detail(format!(
                        "split at level {}, the maximum depth being {max_depth}",
                        cell.level()
                    )));
            }
            let sum: u64 = (0..1 << D)
                .map(|i| u64::from(nodes[first.index() + i][0]))
                .sum();
            if sum != u64::from(count) {
                return Err(ValidationError::new(Invariant::Counts)
                    .node(id.0)
                    .detail(format!("its children count {sum} of {count}")));
            }
            if cap != 0 {
                return links(id.0, format!("an inner node with a chunk of {cap} entries"));
            }
            continue;
        }
        let end = u64::from(start) + u64::from(cap);
        if count > cap || end > slots.len() as u64 {
            return links(
                id.0,
                format!(
                    "{count} points in the chunk of {cap} entries at {start}, in an array of {}",
                    slots.len()
                ),
            );
        }
        owned[start as usize..end as usize].fill(true);
        for e in start..start + count {
            let slot = slots[e as usize];
            if slot as usize >= n {
                return links(id.0, format!("entry {e} holds slot {slot}, of {n} items"));
            }
            live[e as usize] = true;
            pos[slot as usize] = e;
        }
    }
    Ok(Entries { owned, live, pos })
}
