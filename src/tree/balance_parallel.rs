//! Parallel 2:1 balance and balance test (feature `rayon`): the level-by-level balance of
//! `balance.rs` with each level's neighbour searches spread over threads, and the top-down test of
//! `balance_check.rs` with its subtrees spread over threads.
//!
//! Balance. Within one level, the searches that decide which splits are forced only read the
//! tree, and splits made for one node never undo another's finding: a search that ends deep
//! enough still does after any split (splits only deepen the tree), and a split for a node at
//! level l creates internal nodes above level l only (see `balance.rs`). So each level runs in two
//! phases: every (node, outward direction) pair is searched in parallel, keeping, in node order,
//! the leaf where each search that ends too shallow stops and the steps still to take below it;
//! then those descents are made one after another with the serial repair, splitting leaves (a
//! leaf an earlier descent already split is simply walked through). The
//! result is the same tree as [`Tree::balance`] (the coarsest balanced refinement is unique);
//! node ids may differ, since splits happen in another order.

use super::balance::{outward_directions, Descent, Levels};
use super::{BalanceOptions, NodeId, Tree};
use rayon::prelude::*;

/// Nodes per parallel task in [`Tree::par_balance`].
const CHUNK: usize = 4096;

impl<const D: usize> Tree<D> {
    /// [`Tree::balance`] with each level's neighbour searches spread over rayon's threads (see
    /// the module doc); gives the same leaves. Returns the leaves split, each after its parent.
    ///
    /// ```
    /// use orthtree::{Connectivity, tree::NodeId, Tree};
    /// let mut t = Tree::<2>::new();
    /// let mut v = t.split(NodeId::ROOT);
    /// for _ in 0..6 {
    ///     t.split(v);
    ///     v = t.child(v, 3).unwrap();
    /// }
    /// let mut serial = t.clone();
    /// let split = t.par_balance(Connectivity::Face);
    /// assert_eq!(split.len(), serial.balance(Connectivity::Face).len());
    /// assert!(t.par_is_balanced(Connectivity::Face));
    /// assert!(t.leaves().map(|(_, c)| c).eq(serial.leaves().map(|(_, c)| c)));
    /// ```
    pub fn par_balance(&mut self, options: impl Into<BalanceOptions>) -> Vec<NodeId> {
        let options = options.into();
        let outward = outward_directions::<D>(options.connectivity);
        let mut levels = Levels::new(self, options);
        while let Some((nodes, min_level)) = levels.next_level() {
            let tree = &*self;
            let short: Vec<Descent> = nodes
                .par_chunks(CHUNK)
                .flat_map_iter(|chunk| {
                    chunk.iter().flat_map(|&c| {
                        let level = tree.level(c);
                        outward[tree.child_index(c)]
                            .iter()
                            .filter_map(move |&d| tree.shortfall(c, level, d, min_level))
                    })
                })
                .collect();
            for from in short {
                levels.descend(self, from, min_level);
            }
        }
        levels.split
    }
}
