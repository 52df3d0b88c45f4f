//! Level-by-level 2:1 balance: every split forced, each internal node examined once, no worklist
//! of leaves and no searches below neighbours.
//!
//! The test. A tree is balanced (adjacent leaves differ by at most k levels under a connectivity)
//! exactly when, for every internal node C at level l and every direction δ allowed by the
//! connectivity that leaves C's parent P on every axis it moves along, the neighbour search from C
//! ([`Tree::neighbor`]) ends at level l - (k - 1) or deeper. (Any leaf adjacent to a child of C is
//! found in such a direction; directions that stay inside P lead to siblings, which exist; and
//! directions that leave P on only some of their axes reach the same node as their restriction to
//! those axes.) Testing this costs one neighbour search per internal node and outward direction
//! ((2^D - 1) at most, D with face connectivity); [`Tree::is_balanced`] (`balance_check.rs`)
//! tests the same condition without searches.
//!
//! The repair. Internal nodes are taken by level, deepest first. For each outward direction whose
//! search ends too shallow, the search's path is followed down, splitting the leaf met at each
//! level, until level l - (k - 1) is reached. Those splits are forced: the node C is internal in
//! every refinement, so any balanced refinement has them. They create internal nodes only at
//! levels below l - k + 1 <= l, which are examined later, so once all levels are done the test
//! holds for every internal node: the result is the coarsest balanced refinement, whatever order
//! the nodes of one level are taken in.
//!
//! Cost: O(1) amortised per search on trees of bounded neighbour depth, O(d) worst case
//! (Theorem 14.3), for (2^D - 1)(m + 2^D s) searches with m nodes and s splits; memory 4 bytes per
//! internal node for the lists by level.

use super::{BalanceOptions, NodeId, Tree};
use crate::geom::{Cell, Connectivity, Dim, Direction};
use smallvec::SmallVec;

impl<const D: usize> Tree<D> {
    /// Refines the tree to the coarsest balanced tree containing it, level by level (see the
    /// module doc), and returns the leaves it split, each after its parent (a consumer moves its
    /// payload from each split leaf to the leaf's children, in this order).
    ///
    /// # Complexity
    /// At most (3^D - 1) m splits for a tree of m nodes (Theorem 14.4, generalised in the module
    /// doc of the reference balance, `balance_reference.rs`); O(d + 1) time per neighbour
    /// search, one search per internal node and outward direction.
    ///
    /// ```
    /// use orthtree::{Connectivity, tree::NodeId, Tree};
    /// let mut t = Tree::<2>::new();
    /// // refine towards the centre from the SW quadrant, down to level 4
    /// let mut v = t.split(NodeId::ROOT); // the SW child
    /// for _ in 0..3 {
    ///     t.split(v);
    ///     v = t.child(v, 3).unwrap(); // its NE child
    /// }
    /// assert!(!t.is_balanced(Connectivity::Face));
    /// let split = t.balance(Connectivity::Face);
    /// assert!(t.is_balanced(Connectivity::Face));
    /// // SE and NW (level 1) split, then their children next to the centre, and that
    /// // propagates: NE (level 1) now borders level-3 leaves and splits too
    /// assert_eq!(split.len(), 5);
    /// ```
    pub fn balance(&mut self, options: impl Into<BalanceOptions>) -> Vec<NodeId> {
        let options = options.into();
        let levels = Levels::new(self, options);
        self.balance_levels(levels, options.connectivity)
    }

    /// The repair of the module doc over the internal nodes listed in `levels`.
    pub(super) fn balance_levels(
        &mut self,
        mut levels: Levels,
        connectivity: Connectivity,
    ) -> Vec<NodeId> {
        let outward = outward_directions::<D>(connectivity);
        while let Some((nodes, min_level)) = levels.next_level() {
            for &c in &nodes {
                let level = self.level(c);
                for &d in &outward[self.child_index(c)] {
                    self.reach(c, level, d, min_level, |tree, leaf| {
                        levels.record(tree, leaf)
                    });
                }
            }
        }
        levels.split
    }

    /// Where the neighbour search from `id` (at `level`) in `direction` stops short: the leaf
    /// above `min_level` it ends at, as [`Tree::descend`] takes it; `None` when the search
    /// reaches `min_level` (nothing to split).
    #[cfg(feature = "rayon")]
    pub(super) fn shortfall(
        &self,
        id: NodeId,
        level: u8,
        direction: Direction,
        min_level: u8,
    ) -> Option<Descent> {
        let (v, path, steps) = self.neighbor_steps(id, direction)?;
        let (leaf, left) = self.follow(v, path, steps);
        let level = level - left;
        (level < min_level).then_some((leaf, level, path, left))
    }

    /// Follows the neighbour search from `id` (at `level`) in `direction`, splitting every leaf
    /// met above `min_level` on the way down (calling `on_split` after each split), until the
    /// path reaches `min_level` or its end.
    pub(super) fn reach(
        &mut self,
        id: NodeId,
        level: u8,
        direction: Direction,
        min_level: u8,
        on_split: impl FnMut(&Self, NodeId),
    ) {
        if let Some((v, path, steps)) = self.neighbor_steps(id, direction) {
            self.descend((v, level - steps, path, steps), min_level, on_split);
        }
    }

    /// The descent of [`Tree::reach`] from `v` at `level`, taking the last `steps` child indices
    /// of the packed `path` of [`Tree::neighbor_steps`]: the levels on the way down are counted,
    /// not read, so each step down reads one word of the arena.
    pub(super) fn descend(
        &mut self,
        (mut v, mut level, path, mut steps): Descent,
        min_level: u8,
        mut on_split: impl FnMut(&Self, NodeId),
    ) {
        let mask = (1u64 << D) - 1;
        while steps > 0 && level < min_level {
            steps -= 1;
            let mut first = self.first_child[v.index()];
            if first == super::arena::NONE {
                first = self.split(v).0;
                on_split(self, v);
            }
            v = NodeId(first + ((path >> (D * steps as usize)) & mask) as u32);
            level += 1;
        }
    }
}

/// Where a descent of [`Tree::descend`] starts: a node, its level, and the packed path of
/// [`Tree::neighbor_steps`] with the number of its steps still to take.
pub(super) type Descent = (NodeId, u8, u64, u8);

/// The state of one level-by-level balance (see the module doc): the internal nodes still to
/// examine, by level, and the splits made so far.
pub(super) struct Levels {
    slack: u8,
    by_level: Vec<Vec<NodeId>>,
    /// The next level to examine, plus one (0 when done).
    level: usize,
    /// The leaves split, each after its parent.
    pub(super) split: Vec<NodeId>,
}

impl Levels {
    /// Lists the internal nodes of `tree` by level.
    pub(super) fn new<const D: usize>(tree: &Tree<D>, options: BalanceOptions) -> Levels {
        Self::of_nodes(tree, options, (0..tree.node_count() as u32).map(NodeId))
    }

    /// The internal nodes among `seeds` by level (the nodes split since the tree was balanced).
    #[cfg(feature = "mpi")]
    pub(super) fn seeded<const D: usize>(
        tree: &Tree<D>,
        options: BalanceOptions,
        seeds: &[NodeId],
    ) -> Levels {
        Self::of_nodes(tree, options, seeds.iter().copied())
    }

    /// The internal nodes among `nodes`, by level.
    fn of_nodes<const D: usize>(
        tree: &Tree<D>,
        options: BalanceOptions,
        nodes: impl Iterator<Item = NodeId>,
    ) -> Levels {
        let mut by_level: Vec<Vec<NodeId>> = vec![Vec::new(); Cell::<D>::MAX_LEVEL as usize + 1];
        for id in nodes.filter(|&id| !tree.is_leaf(id)) {
            by_level[tree.level(id) as usize].push(id);
        }
        Levels {
            slack: options.max_level_difference() - 1,
            level: by_level.len(),
            by_level,
            split: Vec::new(),
        }
    }

    /// The internal nodes of the next level to examine (deepest first, the root's level never)
    /// and the level their neighbour searches must reach; `None` when every level is done.
    pub(super) fn next_level(&mut self) -> Option<(Vec<NodeId>, u8)> {
        while self.level > 1 {
            self.level -= 1;
            if let Some(min_level) = (self.level as u8).checked_sub(self.slack) {
                return Some((core::mem::take(&mut self.by_level[self.level]), min_level));
            }
        }
        None
    }

    /// [`Tree::descend`], recording each split and the new internal node's level.
    #[cfg(feature = "rayon")]
    pub(super) fn descend<const D: usize>(
        &mut self,
        tree: &mut Tree<D>,
        from: Descent,
        min_level: u8,
    ) {
        tree.descend(from, min_level, |tree, leaf| self.record(tree, leaf));
    }

    fn record<const D: usize>(&mut self, tree: &Tree<D>, leaf: NodeId) {
        self.split.push(leaf);
        self.by_level[tree.level(leaf) as usize].push(leaf);
    }
}

/// For each child index c, the directions allowed by `connectivity` that move outward (away from
/// the parent's centre) on every axis they use: one per non-empty subset of axes.
pub(super) fn outward_directions<const D: usize>(
    connectivity: Connectivity,
) -> Vec<SmallVec<[Direction; 8]>> {
    // Masks over the axes count in `usize`: `1u8 << D` overflows in 8-D.
    (0..Dim::<D>::CHILDREN)
        .map(|c| {
            (1..Dim::<D>::CHILDREN)
                .filter(|axes| connectivity.allows(axes.count_ones()))
                .map(|axes| {
                    let (plus, minus) = (axes & c, axes & !c);
                    Direction::from_masks(axis_mask(plus), axis_mask(minus))
                })
                .collect()
        })
        .collect()
}

/// A mask over the axes (below 2^D <= 256) as a [`Direction`]'s `u8` mask.
fn axis_mask(axes: usize) -> u8 {
    u8::try_from(axes).expect("a mask over at most 8 axes fits a u8")
}
