//! [`Tree::is_balanced`]: one top-down pass that hands every internal node its neighbours, with no
//! neighbour search at all.
//!
//! The test. A tree is balanced (adjacent leaves differ by at most k levels under a connectivity)
//! exactly when, for every internal node C at level l and every direction δ allowed by the
//! connectivity, the neighbour search from C in δ ends at level l - (k - 1) or deeper (or leaves
//! the root cell). If it ends at a leaf N shallower than that, the child of C on N's side is (or
//! holds) a leaf at level l + 1 or deeper next to N: more than k levels apart. If it never does,
//! every leaf has its adjacent leaves within k levels (the argument of `ripple.rs`'s module doc).
//!
//! The pass. A depth-first walk keeps, for the node at each level of the current path, the result
//! of the neighbour search in every allowed direction: the same-level neighbour when it exists,
//! else the leaf that covers its cell, else "outside". A child's neighbours follow from its
//! parent's in O(1) each, the classic top-down neighbour rule (Samet, *The Design and Analysis
//! of Spatial Data Structures*, 1990, section 3.2): moving from child c in direction δ stays in
//! the parent along the axes where c is on the far side and leaves it along the others, so the
//! neighbour is the sibling c ^ axes(δ) when δ leaves the parent along no axis, and otherwise the
//! child c ^ axes(δ) of the parent's neighbour in the restriction of δ to the leaving axes (or
//! that neighbour itself, when it is a leaf or shallower).
//!
//! Cost: one array read per internal node and direction that leaves the parent, no walk up the
//! tree and no allocation beyond (max level + 1) rows of neighbours; leaves are never entered.
//! Internal nodes are visited in pre-order with an explicit stack of one row per level.

use super::arena::NONE;
use super::{BalanceOptions, NodeId, Tree};
use crate::geom::{Dim, Direction};
use smallvec::SmallVec;

/// The search result for a direction that leaves the root cell.
const OUTSIDE: u32 = u32::MAX;

/// Where the neighbour of a child in one direction comes from.
#[derive(Clone, Copy, Debug)]
enum Source {
    /// The sibling with this child index.
    Sibling(u8),
    /// Child `index` of the parent's neighbour in direction number `direction`.
    Parent { direction: u16, index: u8 },
}

/// The neighbour rule of the module doc, tabulated: `rule[c * k + j]` for child `c` and
/// direction number `j` of the `k` allowed directions.
struct Rule {
    directions: usize,
    sources: Vec<Source>,
}

impl Rule {
    fn new<const D: usize>(options: BalanceOptions) -> Rule {
        let directions: Vec<Direction> = Direction::all::<D>(options.connectivity).collect();
        let number = |d: Direction| {
            directions
                .iter()
                .position(|&e| e == d)
                .expect("a restriction of an allowed direction is allowed") as u16
        };
        let mut sources = Vec::with_capacity(Dim::<D>::CHILDREN * directions.len());
        for c in 0..Dim::<D>::CHILDREN as u8 {
            for &d in &directions {
                let index = c ^ d.axes();
                let leaving = Direction::from_masks(d.plus_mask() & c, d.minus_mask() & !c);
                sources.push(if leaving.axes() == 0 {
                    Source::Sibling(index)
                } else {
                    Source::Parent {
                        direction: number(leaving),
                        index,
                    }
                });
            }
        }
        Rule {
            directions: directions.len(),
            sources,
        }
    }
}

impl<const D: usize> Tree<D> {
    /// `true` when no two adjacent leaves (under `options`' connectivity) differ by more than
    /// `options.max_level_difference` levels.
    ///
    /// One top-down pass over the internal nodes that carries each node's neighbours down from
    /// its parent (see the module doc): O(internal nodes × directions) array reads, no neighbour
    /// search; it stops at the first node in violation.
    ///
    /// # Panics
    /// If `options.max_level_difference` is 0.
    ///
    /// ```
    /// use orthtree::{BalanceOptions, Connectivity, NodeId, Tree};
    /// let mut t = Tree::<3>::new();
    /// let first = t.split(NodeId::ROOT);
    /// let g = t.split(first);
    /// t.split(g); // level-3 cells in the corner: still balanced (a corner chain)
    /// assert!(t.is_balanced(BalanceOptions::new(Connectivity::Corner)));
    /// let deep = t.child(g, 7).unwrap();
    /// t.split(deep); // level-4 leaves next to level-2 leaves: two levels apart
    /// assert!(!t.is_balanced(Connectivity::Face));
    /// assert!(t.is_balanced(BalanceOptions::new(Connectivity::Corner).weak()));
    /// ```
    pub fn is_balanced(&self, options: impl Into<BalanceOptions>) -> bool {
        let check = Check::new(self, options.into());
        if self.is_leaf(NodeId::ROOT) {
            return true;
        }
        let mut pending = check.root();
        while let Some(top) = pending.pop() {
            if !check.expand(&top, &mut pending) {
                return false;
            }
        }
        true
    }

    /// [`Tree::is_balanced`] with the subtrees spread over rayon's threads: the top levels are
    /// expanded until there are enough subtrees, which are then tested in parallel.
    ///
    /// ```
    /// use orthtree::{Connectivity, NodeId, Tree};
    /// let mut t = Tree::<2>::new();
    /// let sw = t.split(NodeId::ROOT);
    /// let corner = t.split(sw); // level 2
    /// t.split(corner);
    /// assert!(t.par_is_balanced(Connectivity::Corner));
    /// t.split(t.child(corner, 3).unwrap()); // level-4 leaves next to a level-2 leaf
    /// assert!(!t.par_is_balanced(Connectivity::Face));
    /// ```
    ///
    /// # Panics
    /// If `options.max_level_difference` is 0.
    #[cfg(feature = "rayon")]
    pub fn par_is_balanced(&self, options: impl Into<BalanceOptions>) -> bool {
        use rayon::prelude::*;
        let check = Check::new(self, options.into());
        if self.is_leaf(NodeId::ROOT) {
            return true;
        }
        let mut frontier = check.root();
        let wanted = 64 * rayon::current_num_threads();
        while !frontier.is_empty() && frontier.len() < wanted {
            let mut next = Pending::new(check.rule.directions);
            while let Some(top) = frontier.pop() {
                if !check.expand(&top, &mut next) {
                    return false;
                }
            }
            frontier = next;
        }
        (0..frontier.len()).into_par_iter().all(|e| {
            let mut pending = Pending::new(check.rule.directions);
            let mut top = Some(frontier.entry(e));
            while let Some(node) = top {
                if !check.expand(&node, &mut pending) {
                    return false;
                }
                top = pending.pop();
            }
            true
        })
    }
}

/// One balance test: the tree, the neighbour rule, and a bit per node slot telling internal
/// nodes from leaves (so that testing a node's children reads a bitmap that stays in cache, not
/// the children's own entries).
struct Check<'a, const D: usize> {
    tree: &'a Tree<D>,
    rule: Rule,
    internal: Vec<u64>,
    slack: u8,
}

impl<'a, const D: usize> Check<'a, D> {
    fn new(tree: &'a Tree<D>, options: BalanceOptions) -> Self {
        assert!(
            options.max_level_difference >= 1,
            "max_level_difference must be at least 1"
        );
        let internal = tree
            .first_child
            .chunks(64)
            .map(|chunk| {
                chunk
                    .iter()
                    .enumerate()
                    .fold(0u64, |w, (i, &f)| w | ((f != NONE) as u64) << i)
            })
            .collect();
        Check {
            tree,
            rule: Rule::new::<D>(options),
            internal,
            slack: options.max_level_difference - 1,
        }
    }

    /// The stack holding the root (internal) with its neighbours, all outside.
    fn root(&self) -> Pending {
        let mut pending = Pending::new(self.rule.directions);
        pending.push(self.tree.first_child[0], 0);
        pending.row_mut().0.fill(OUTSIDE);
        pending
    }

    #[inline]
    fn is_internal(&self, id: u32) -> bool {
        (self.internal[(id >> 6) as usize] >> (id & 63)) & 1 != 0
    }

    /// `true` when one of the 2^D children starting at `first` is internal.
    #[inline]
    fn any_internal(&self, first: u32) -> bool {
        let (start, end) = (first as usize, first as usize + Dim::<D>::CHILDREN);
        (start >> 6..=(end - 1) >> 6).any(|w| {
            let lo = start.max(w << 6) - (w << 6);
            let hi = end.min((w + 1) << 6) - (w << 6);
            let mask = if hi - lo == 64 {
                u64::MAX
            } else {
                ((1u64 << (hi - lo)) - 1) << lo
            };
            self.internal[w] & mask != 0
        })
    }

    /// Tests the internal children of the node `top` (internal, its row known): computes each
    /// one's neighbour row from `top`'s (the rule of the module doc), returns `false` at the first
    /// neighbour too coarse, and pushes onto `out` the children that have internal children.
    fn expand(&self, top: &Entry, out: &mut Pending) -> bool {
        let first_child = &self.tree.first_child;
        let k = self.rule.directions;
        let level = top.level;
        // the first child of each neighbour at `top`'s own level (else NONE)
        let mut across: SmallVec<[u32; 32]> = SmallVec::with_capacity(k);
        across.extend(top.ids.iter().zip(&top.levels).map(|(&n, &nl)| {
            if n != OUTSIDE && nl == level && self.is_internal(n) {
                first_child[n as usize]
            } else {
                NONE
            }
        }));
        let mut ids: SmallVec<[u32; 32]> = SmallVec::from_elem(0, k);
        let mut levels: SmallVec<[u8; 32]> = SmallVec::from_elem(0, k);
        for c in 0..Dim::<D>::CHILDREN {
            let child = top.first + c as u32;
            if !self.is_internal(child) {
                continue;
            }
            let sources = &self.rule.sources[c * k..(c + 1) * k];
            for (j, &source) in sources.iter().enumerate() {
                let (id, l) = match source {
                    Source::Sibling(i) => (top.first + i as u32, level + 1),
                    Source::Parent { direction, index } => {
                        let d = direction as usize;
                        match across[d] {
                            NONE => (top.ids[d], top.levels[d]),
                            nf => (nf + index as u32, level + 1),
                        }
                    }
                };
                // the child is internal: its neighbour here must not be too coarse
                if id != OUTSIDE && l + self.slack <= level {
                    return false;
                }
                ids[j] = id;
                levels[j] = l;
            }
            let grandchildren = first_child[child as usize];
            if self.any_internal(grandchildren) {
                out.push(grandchildren, level + 1);
                let (row_ids, row_levels) = out.row_mut();
                row_ids.copy_from_slice(&ids);
                row_levels.copy_from_slice(&levels);
            }
        }
        true
    }
}

/// An internal node taken off a [`Pending`] stack: its first child, level and neighbour row.
struct Entry {
    first: u32,
    level: u8,
    ids: SmallVec<[u32; 32]>,
    levels: SmallVec<[u8; 32]>,
}

/// A stack of internal nodes still to expand: each node's first child, level, and neighbour row
/// (for each allowed direction the neighbour search's result, a node id or [`OUTSIDE`], and its
/// level).
struct Pending {
    directions: usize,
    first: Vec<u32>,
    level: Vec<u8>,
    ids: Vec<u32>,
    levels: Vec<u8>,
}

impl Pending {
    fn new(directions: usize) -> Self {
        Pending {
            directions,
            first: Vec::new(),
            level: Vec::new(),
            ids: Vec::new(),
            levels: Vec::new(),
        }
    }

    fn len(&self) -> usize {
        self.first.len()
    }

    #[cfg(feature = "rayon")]
    fn is_empty(&self) -> bool {
        self.first.is_empty()
    }

    /// Pushes a node with a row to fill through [`Pending::row_mut`].
    fn push(&mut self, first: u32, level: u8) {
        self.first.push(first);
        self.level.push(level);
        self.ids.resize(self.ids.len() + self.directions, 0);
        self.levels.resize(self.levels.len() + self.directions, 0);
    }

    /// The row of the last node pushed.
    fn row_mut(&mut self) -> (&mut [u32], &mut [u8]) {
        let start = self.ids.len() - self.directions;
        (&mut self.ids[start..], &mut self.levels[start..])
    }

    /// A copy of entry `e`.
    fn entry(&self, e: usize) -> Entry {
        let r = e * self.directions..(e + 1) * self.directions;
        Entry {
            first: self.first[e],
            level: self.level[e],
            ids: SmallVec::from_slice(&self.ids[r.clone()]),
            levels: SmallVec::from_slice(&self.levels[r]),
        }
    }

    fn pop(&mut self) -> Option<Entry> {
        let e = self.len().checked_sub(1)?;
        let entry = self.entry(e);
        self.first.truncate(e);
        self.level.truncate(e);
        self.ids.truncate(e * self.directions);
        self.levels.truncate(e * self.directions);
        Some(entry)
    }
}
