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
//! Cost: one bitmap lookup per child of an entered node, and rows only where they are needed: a
//! node is entered only when it has internal children; a node whose row holds no neighbour too
//! coarse for its children ("clean") lets those children pass without computing their rows; and
//! a neighbour's children are read (one array read per direction) only when some child needs a
//! row. Leaves are never entered, nothing recurses, and memory is one row per level of the
//! current path.

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
                let (plus, minus) = (d.plus_mask() & c, d.minus_mask() & !c);
                sources.push(if plus | minus == 0 {
                    Source::Sibling(index)
                } else {
                    Source::Parent {
                        direction: number(Direction::from_masks(plus, minus)),
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
        check.below(check.root())
    }

    /// [`Tree::is_balanced`] with the subtrees spread over rayon's threads: the top levels are
    /// expanded breadth-first until there are enough subtrees, which are then tested in parallel.
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
        let mut frontier = vec![check.root()];
        let wanted = 64 * rayon::current_num_threads();
        while !frontier.is_empty() && frontier.len() < wanted {
            let mut next = Vec::new();
            for top in &mut frontier {
                let mut row = check.empty_entry();
                for c in 0..Dim::<D>::CHILDREN {
                    match check.child(top, c, &mut row) {
                        Child::Unbalanced => return false,
                        Child::Enter => next.push(row.clone()),
                        Child::Done => {}
                    }
                }
            }
            frontier = next;
        }
        frontier.into_par_iter().all(|top| check.below(top))
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

/// An internal node with internal children, ready to have them tested: its first child, level,
/// neighbour row (for each allowed direction the neighbour search's result, a node id or
/// [`OUTSIDE`], and its level), and the first child of each neighbour at its own level (else
/// `NONE`).
#[derive(Clone)]
struct Entry {
    first: u32,
    level: u8,
    ids: SmallVec<[u32; 32]>,
    levels: SmallVec<[u8; 32]>,
    across: SmallVec<[u32; 32]>,
    /// `true` when no entry of the row is a leaf (or shallower node) too coarse for the node's
    /// internal children: they then pass the test without looking.
    clean: bool,
    /// `true` once `across` is filled (it is read only for children that need a row).
    across_ready: bool,
}

/// What [`Check::child`] found.
enum Child {
    /// The child is a leaf, or internal and fine with only leaves below it.
    Done,
    /// The child is internal, fine, and has internal children: its entry is filled.
    Enter,
    /// The child is internal and has a neighbour too coarse.
    Unbalanced,
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

    fn empty_entry(&self) -> Entry {
        let k = self.rule.directions;
        Entry {
            first: NONE,
            level: 0,
            ids: SmallVec::from_elem(OUTSIDE, k),
            levels: SmallVec::from_elem(0, k),
            across: SmallVec::from_elem(NONE, k),
            clean: true,
            across_ready: false,
        }
    }

    /// The root (internal), its neighbours all outside.
    fn root(&self) -> Entry {
        let mut root = self.empty_entry();
        root.first = self.tree.first_child[0];
        root
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

    /// Tests child `c` of `top` (the rule of the module doc) and, when it has internal children,
    /// fills `out` with its entry. Reads a neighbour's children (`top.across`) only for a child
    /// that needs a row, the first time one does.
    #[inline]
    fn child(&self, top: &mut Entry, c: usize, out: &mut Entry) -> Child {
        let child = top.first + c as u32;
        if !self.is_internal(child) {
            return Child::Done;
        }
        let first_child = &self.tree.first_child;
        let grandchildren = first_child[child as usize];
        let enter = self.any_internal(grandchildren);
        if top.clean && !enter {
            // no neighbour of `top` is too coarse for its children: nothing to test here
            return Child::Done;
        }
        if enter && !top.across_ready {
            for j in 0..self.rule.directions {
                let n = top.ids[j];
                top.across[j] = if self.internal_at(n, top.levels[j], top.level) {
                    first_child[n as usize]
                } else {
                    NONE
                };
            }
            top.across_ready = true;
        }
        let k = self.rule.directions;
        let level = top.level;
        let sources = &self.rule.sources[c * k..(c + 1) * k];
        for (j, &source) in sources.iter().enumerate() {
            let (id, l) = match source {
                Source::Sibling(i) => (top.first + i as u32, level + 1),
                Source::Parent { direction, index } => {
                    let d = direction as usize;
                    let (n, nl) = (top.ids[d], top.levels[d]);
                    if !self.internal_at(n, nl, level) {
                        (n, nl)
                    } else if enter {
                        (top.across[d] + index as u32, level + 1)
                    } else {
                        continue; // a same-level internal neighbour: fine, and no row needed
                    }
                }
            };
            // the child is internal: its neighbour here must not be too coarse
            if id != OUTSIDE && l + self.slack <= level {
                return Child::Unbalanced;
            }
            out.ids[j] = id;
            out.levels[j] = l;
        }
        if !enter {
            return Child::Done;
        }
        out.first = grandchildren;
        out.level = level + 1;
        out.across_ready = false;
        // clean: no neighbour that its children would see as too coarse
        out.clean = (0..k).all(|j| {
            let (n, l) = (out.ids[j], out.levels[j]);
            n == OUTSIDE || self.internal_at(n, l, level + 1) || l + self.slack > level + 1
        });
        Child::Enter
    }

    /// `true` when `n` (a neighbour row entry at level `l`) is an internal node at `level`.
    #[inline]
    fn internal_at(&self, n: u32, l: u8, level: u8) -> bool {
        n != OUTSIDE && l == level && self.is_internal(n)
    }

    /// Tests every internal node below `top`, depth first, one entry per level of the current
    /// path, each child's entry written in place (no recursion, no copies).
    fn below(&self, top: Entry) -> bool {
        let mut path = vec![top];
        let mut next = vec![0usize];
        let mut depth = 1;
        while depth > 0 {
            let r = depth - 1;
            let c = next[r];
            if c == Dim::<D>::CHILDREN {
                depth -= 1;
                continue;
            }
            next[r] += 1;
            if path.len() == depth {
                path.push(self.empty_entry());
                next.push(0);
            }
            let (upper, lower) = path.split_at_mut(depth);
            match self.child(&mut upper[r], c, &mut lower[0]) {
                Child::Unbalanced => return false,
                Child::Enter => {
                    next[depth] = 0;
                    depth += 1;
                }
                Child::Done => {}
            }
        }
        true
    }
}
