//! [`Tree::is_balanced`]: one top-down pass over a compact table of the internal nodes that hands
//! every internal node its neighbours, with no neighbour search at all; or, for trees shallow
//! enough, the test of the same condition on a dense bitmap of internal cells
//! (`balance_check_dense.rs`), which is faster still (two sequential passes, no walk).
//!
//! The test. A tree is balanced (adjacent leaves differ by at most k levels under a connectivity)
//! exactly when, for every internal node C at level l and every direction δ allowed by the
//! connectivity, the neighbour search from C in δ ends at level l - (k - 1) or deeper (or leaves
//! the root cell). If it ends at a leaf N shallower than that, the child of C on N's side is (or
//! holds) a leaf at level l + 1 or deeper next to N: more than k levels apart. If it never does,
//! every leaf has its adjacent leaves within k levels (the argument of `balance.rs`'s module doc).
//!
//! The pass. A depth-first walk keeps, for the node at each level of the current path, the result
//! of the neighbour search in every allowed direction: the same-level neighbour when it is
//! internal, else the level of the leaf that covers its cell (or "outside"). A child's neighbours
//! follow from its parent's in O(1) each, the classic top-down neighbour rule (Samet, *The Design
//! and Analysis of Spatial Data Structures*, 1990, section 3.2): moving from child c in direction
//! δ stays in the parent along the axes where c is on the far side and leaves it along the
//! others, so the neighbour is the sibling c ^ axes(δ) when δ leaves the parent along no axis,
//! and otherwise the child c ^ axes(δ) of the parent's neighbour in the restriction of δ to the
//! leaving axes (or that neighbour itself, when it is a leaf).
//!
//! The walk reads only the table of internal nodes of `inner.rs` (records numbered in id order,
//! each with its children's masks and the number of its first internal child), never the
//! arena: a leaf has no record, and a row entry is either a record or the level of a leaf.
//!
//! Cost: O(1) per internal child of an entered node, and rows only where they are needed: a
//! node is entered only when it has internal children; a node whose row holds no leaf too coarse
//! for its children ("clean") lets those children pass without looking at them unless they have
//! internal children themselves. Nothing recurses; memory is one row per level of the current
//! path, plus the table (two words per internal node up to D = 4).

use super::balance_check_dense::Dense;
use super::inner::Inner;
use super::{BalanceOptions, NodeId, Tree};
use crate::geom::{Dim, Direction};

/// The neighbour rule of the module doc, tabulated for rows of `directions + 1` entries, the
/// last one the node itself (so that a sibling is a child of entry `directions`).
pub(super) struct Rule {
    directions: usize,
    /// `sources[c * directions + j]`: for child `c` and direction number `j`, the parent's row
    /// entry the neighbour comes from, and the child of that entry to take.
    sources: Vec<(u16, u8)>,
    /// `touch[touch_start[c]..touch_start[c + 1]]`: the parent's directions that child `c`
    /// inherits (where a leaf too coarse for `c` can come from).
    touch: Vec<u16>,
    touch_start: Vec<usize>,
    /// The directions of `touch`.
    steps: Vec<Direction>,
}

impl Rule {
    /// The rule for `options`.
    pub(super) fn new<const D: usize>(options: BalanceOptions) -> Rule {
        let directions: Vec<Direction> = Direction::all::<D>(options.connectivity).collect();
        let k = directions.len();
        // Direction numbers by base-3 code, so that finding one is O(1): 256 children times
        // 6560 directions in 8-D made a linear search take seconds.
        let code = |d: Direction| {
            (0..D).rev().fold(0usize, |code, a| {
                3 * code
                    + ((d.plus_mask() >> a) & 1) as usize
                    + 2 * ((d.minus_mask() >> a) & 1) as usize
            })
        };
        let mut numbers = vec![u16::MAX; 3usize.pow(D as u32)];
        for (j, &d) in directions.iter().enumerate() {
            numbers[code(d)] = u16::try_from(j).expect("3^D - 1 < 2^16 directions for D <= 8");
        }
        let number = |d: Direction| {
            let j = numbers[code(d)];
            debug_assert!(
                j != u16::MAX,
                "a restriction of an allowed direction is allowed"
            );
            j
        };
        let mut sources = Vec::with_capacity(Dim::<D>::CHILDREN * k);
        let (mut touch, mut touch_start, mut steps) = (Vec::new(), vec![0], Vec::new());
        // `touched[j]`: the last child (plus one) whose list holds direction j.
        let mut touched = vec![0usize; k];
        // `c` counts in `usize`: 2^D children is 256 in 8-D, one more than a `u8` holds.
        for c in 0..Dim::<D>::CHILDREN {
            let mark = c + 1;
            let c = u8::try_from(c).expect("a child index is below 2^D <= 256");
            for &d in &directions {
                let index = c ^ d.axes();
                let (plus, minus) = (d.plus_mask() & c, d.minus_mask() & !c);
                if plus | minus == 0 {
                    sources.push((k as u16, index));
                } else {
                    let from = number(Direction::from_masks(plus, minus));
                    sources.push((from, index));
                    if touched[from as usize] != mark {
                        touched[from as usize] = mark;
                        touch.push(from);
                        steps.push(directions[from as usize]);
                    }
                }
            }
            touch_start.push(touch.len());
        }
        Rule {
            directions: k,
            sources,
            touch,
            touch_start,
            steps,
        }
    }

    #[inline]
    fn sources(&self, c: usize) -> &[(u16, u8)] {
        &self.sources[c * self.directions..(c + 1) * self.directions]
    }

    #[inline]
    fn touch(&self, c: usize) -> &[u16] {
        &self.touch[self.touch_start[c]..self.touch_start[c + 1]]
    }

    /// The distinct directions in which child `c` leaves its parent's cell.
    #[inline]
    pub(super) fn steps(&self, c: usize) -> &[Direction] {
        &self.steps[self.touch_start[c]..self.touch_start[c + 1]]
    }
}

impl<const D: usize> Tree<D> {
    /// `true` when no two adjacent leaves (under `options`' connectivity) differ by more than
    /// `options.max_level_difference()` levels.
    ///
    /// One top-down pass over the internal nodes that carries each node's neighbours down from
    /// its parent (see the module doc): O(internal nodes × directions) array reads, no neighbour
    /// search; it stops at the first node in violation.
    ///
    /// ```
    /// use orthtree::{tree::BalanceOptions, Connectivity, tree::NodeId, Tree};
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
        match Plan::new(self, options.into(), true) {
            Plan::Leaf => true,
            Plan::Dense(dense, rule, k) => dense.balanced(&rule, k),
            Plan::Walk(check) => check.below(&check.root()),
        }
    }

    /// [`Tree::is_balanced`] by the walk, even where the dense test applies.
    #[cfg(test)]
    pub(super) fn is_balanced_walk(&self, options: BalanceOptions) -> bool {
        match Plan::new(self, options, false) {
            Plan::Walk(check) => check.below(&check.root()),
            _ => true,
        }
    }

    /// [`Tree::is_balanced`] by the dense test; `None` where it does not apply.
    #[cfg(test)]
    pub(super) fn is_balanced_dense(&self, options: BalanceOptions) -> Option<bool> {
        match Plan::new(self, options, true) {
            Plan::Dense(dense, rule, k) => Some(dense.balanced(&rule, k)),
            _ => None,
        }
    }

    /// [`Tree::is_balanced`] with the subtrees spread over rayon's threads: the top levels are
    /// expanded breadth-first until there are enough subtrees, which are then tested in parallel.
    ///
    /// ```
    /// use orthtree::{Connectivity, tree::NodeId, Tree};
    /// let mut t = Tree::<2>::new();
    /// let sw = t.split(NodeId::ROOT);
    /// let corner = t.split(sw); // level 2
    /// t.split(corner);
    /// assert!(t.par_is_balanced(Connectivity::Corner));
    /// t.split(t.child(corner, 3).unwrap()); // level-4 leaves next to a level-2 leaf
    /// assert!(!t.par_is_balanced(Connectivity::Face));
    /// ```
    #[cfg(feature = "rayon")]
    pub fn par_is_balanced(&self, options: impl Into<BalanceOptions>) -> bool {
        use rayon::prelude::*;
        let check = match Plan::new(self, options.into(), true) {
            Plan::Leaf => return true,
            Plan::Dense(dense, rule, k) => return dense.par_balanced(&rule, k),
            Plan::Walk(check) => check,
        };
        let mut frontier = vec![check.root()];
        let wanted = 64 * rayon::current_num_threads();
        while !frontier.is_empty() && frontier.len() < wanted {
            let mut next = Vec::new();
            for top in &frontier {
                let mut frame = top.frame;
                while let Some(c) = check.next_child(&mut frame) {
                    let mut row = vec![0; check.rule.directions + 1];
                    match check.child(frame, &top.row, c, &mut row) {
                        Child::Unbalanced => return false,
                        Child::Enter(frame) => next.push(Top { frame, row }),
                        Child::Done => {}
                    }
                }
            }
            frontier = next;
        }
        frontier.into_par_iter().all(|top| check.below(&top))
    }
}

/// How to test a tree: nothing to test (a single leaf), the dense test of `balance_check_dense.rs`
/// (with the rule and the allowed level difference) where it applies, else the walk.
enum Plan<const D: usize> {
    Leaf,
    Dense(Dense<D>, Rule, u8),
    Walk(Check<D>),
}

impl<const D: usize> Plan<D> {
    /// The test for `tree`: the dense one where it applies and `dense` allows it.
    fn new(tree: &Tree<D>, options: BalanceOptions, dense: bool) -> Self {
        let rule = Rule::new::<D>(options);
        if tree.is_leaf(NodeId::ROOT) {
            Plan::Leaf
        } else if let Some(dense) = Dense::new(tree).filter(|_| dense) {
            Plan::Dense(dense, rule, options.max_level_difference())
        } else {
            Plan::Walk(Check::new(tree, rule, options))
        }
    }
}

/// A leaf at level m in a neighbour row: `LEAF + m`; smaller values are records of internal
/// nodes at the row's own level.
const LEAF: u32 = u32::MAX - 255;

/// A direction that leaves the root cell: a leaf at level 255, never too coarse.
const OUTSIDE: u32 = u32::MAX;

/// One balance test: the table of internal nodes, the neighbour rule, the slack and the depth.
struct Check<const D: usize> {
    inner: Inner<D>,
    rule: Rule,
    slack: u32,
    depth: usize,
}

/// An internal node with internal children on the walk: its record, level, whether its row is
/// clean (no leaf too coarse for its internal children), and the children still to look at
/// (the set bits of `todo` in mask word `word`).
#[derive(Clone, Copy)]
struct Frame {
    record: u32,
    level: u8,
    clean: bool,
    word: u16,
    todo: u32,
}

/// A node to walk below, with its neighbour row: for each allowed direction the record of the
/// same-level internal neighbour, `LEAF + m` for a leaf at level m, or [`OUTSIDE`]; then the
/// node's own record.
struct Top {
    frame: Frame,
    row: Vec<u32>,
}

/// What [`Check::child`] found.
enum Child {
    /// The child is fine and has no internal children.
    Done,
    /// The child is fine and has internal children: its row is filled.
    Enter(Frame),
    /// The child has a neighbour too coarse.
    Unbalanced,
}

impl<const D: usize> Check<D> {
    /// The test of `tree`, whose root is internal.
    fn new(tree: &Tree<D>, rule: Rule, options: BalanceOptions) -> Self {
        Check {
            inner: Inner::new(tree).expect("the root is internal"),
            rule,
            slack: options.max_level_difference() as u32 - 1,
            depth: tree.depth() as usize,
        }
    }

    /// The root, its neighbours all outside.
    fn root(&self) -> Top {
        let mut row = vec![OUTSIDE; self.rule.directions + 1];
        row[self.rule.directions] = 0;
        Top {
            frame: self.frame(0, 0, true),
            row,
        }
    }

    /// The frame of record `record` at `level`, its first children to look at ready.
    #[inline]
    fn frame(&self, record: u32, level: u8, clean: bool) -> Frame {
        Frame {
            record,
            level,
            clean,
            word: 0,
            todo: self.todo(record, 0, clean),
        }
    }

    /// The children in mask word `w` of `record` that need a look: every internal child, or only
    /// those with internal children when the row is clean.
    #[inline]
    fn todo(&self, record: u32, w: usize, clean: bool) -> u32 {
        if clean {
            self.inner.grand_word(record, w)
        } else {
            self.inner.inner_word(record, w)
        }
    }

    /// The next child of `frame` to look at, taken off its list.
    #[inline]
    fn next_child(&self, frame: &mut Frame) -> Option<usize> {
        while frame.todo == 0 {
            frame.word += 1;
            if frame.word as usize >= Inner::<D>::WORDS {
                return None;
            }
            frame.todo = self.todo(frame.record, frame.word as usize, frame.clean);
        }
        let c = frame.word as usize * 32 + frame.todo.trailing_zeros() as usize;
        frame.todo &= frame.todo - 1;
        Some(c)
    }

    /// `true` when the row entry `e` is a leaf too coarse for an internal node at `level + 1`.
    #[inline]
    fn too_coarse(&self, e: u32, level: u8) -> bool {
        e.wrapping_sub(LEAF) + self.slack <= level as u32
    }

    /// Tests the internal child `c` of the node of `frame` with row `row` (the rule of the module
    /// doc) and, when it has internal children, fills `out` with its row.
    #[inline]
    fn child(&self, frame: Frame, row: &[u32], c: usize, out: &mut [u32]) -> Child {
        let level = frame.level;
        if !frame.clean
            && self
                .rule
                .touch(c)
                .iter()
                .any(|&d| self.too_coarse(row[d as usize], level))
        {
            return Child::Unbalanced;
        }
        if !self.inner.grand(frame.record, c) {
            return Child::Done;
        }
        let finer = LEAF + level as u32 + 1;
        for (o, &(d, i)) in out.iter_mut().zip(self.rule.sources(c)) {
            let e = row[d as usize];
            *o = if e < LEAF {
                self.inner.child_or(e, i as usize, finer)
            } else {
                e
            };
        }
        let k = self.rule.directions;
        let record = self.inner.child_or(frame.record, c, 0);
        out[k] = record;
        let clean = !out[..k].iter().any(|&e| self.too_coarse(e, level + 1));
        Child::Enter(self.frame(record, level + 1, clean))
    }

    /// Tests every internal node below `top`, depth first, one row per level of the current
    /// path, each child's row written in place (no recursion, no copies).
    fn below(&self, top: &Top) -> bool {
        let s = self.rule.directions + 1;
        let mut frames = Vec::with_capacity(self.depth + 1);
        frames.push(top.frame);
        let mut rows = vec![0; (self.depth + 1) * s];
        rows[..s].copy_from_slice(&top.row);
        while let Some(frame) = frames.last_mut() {
            let Some(c) = self.next_child(frame) else {
                frames.pop();
                continue;
            };
            let frame = *frame;
            let depth = frames.len();
            let (upper, lower) = rows.split_at_mut(depth * s);
            match self.child(frame, &upper[(depth - 1) * s..], c, &mut lower[..s]) {
                Child::Unbalanced => return false,
                Child::Enter(next) => frames.push(next),
                Child::Done => {}
            }
        }
        true
    }
}
