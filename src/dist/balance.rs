//! 2:1 balance of a [`DistForest`] (any connectivity, any allowed level difference), with the
//! same leaves as [`Tree::balance`] of the union: Isaac, Burstedde and Ghattas 2012, "Low-cost
//! parallel algorithms for 2:1 octree balance": balance on each rank first, then exchange only
//! the leaves whose insulation layer meets another rank, then a local fix-up.
//!
//! Each rank keeps one [`Tree`]: its own leaves, the remote leaves it has been sent, and the
//! coarsest cells filling the rest of the root cube (made by refining the root toward each
//! cell). The invariant: every split made anywhere is forced, since each rank's tree is coarser
//! than the union's (a filler holds only leaves at least as fine) and balance is monotone; so the
//! leaves are never finer than the serial result.
//!
//! The rounds: (1) balance the local tree; (2) send each own leaf new since the last exchange
//! to the ranks its insulation layer meets (`exchange.rs`); (3) refine the local tree to hold
//! the cells received and balance again, starting from the splits that made
//! (`Tree::balance_seeded`); repeat (2) and (3) until no rank has anything to send (agreed by a
//! sum over ranks). Then every rank's tree is balanced and holds, as nodes, all the remote leaves
//! whose insulation layers meet its range, so two adjacent leaves on different ranks are within
//! the allowed level difference (the finer one is a node of the coarser one's tree): the union is
//! balanced, and with only forced splits it is the coarsest balanced refinement, the serial
//! result. One fix-up round suffices unless a refinement crosses a rank boundary and comes back;
//! the loop has no depth and ends, since every round splits a leaf.

use super::comm;
use super::exchange::{exchange_cells, layer_ancestor, layer_directions, layer_sends, KeyRanges};
use super::forest::span;
use super::{DistError, DistForest};
use crate::geom::Cell;
use crate::tree::{BalanceOptions, NodeId};
use crate::Tree;
use mpi::traits::Communicator;
use smallvec::SmallVec;
use std::time::Instant;

/// What one [`DistForest::balance`] did on this rank.
#[derive(Clone, Debug, PartialEq)]
pub struct BalanceStats {
    /// Exchange rounds that moved cells (the same on every rank).
    pub rounds: usize,
    /// Cells this rank sent over all rounds.
    pub sent: u64,
    /// Cells this rank received over all rounds.
    pub received: u64,
    /// Seconds spent on this rank in each phase: building the local tree, the local balance,
    /// the exchanges (with the choice of what to send), the fix-up balances, and collecting the
    /// leaves.
    pub phases: Vec<(&'static str, f64)>,
}

impl<const D: usize> DistForest<D> {
    /// Refines the forest to the coarsest balanced forest containing it (collective): the
    /// leaves the serial [`Tree::balance`] gives on the union of every rank's leaves, each rank
    /// keeping those in its range of keys (see the module doc). The ranks' ranges do not move:
    /// [`DistForest::repartition`] evens the counts afterwards.
    ///
    /// # Errors
    /// [`DistError::SettingsDiffer`] when the ranks pass different options (nothing else moves);
    /// [`DistError::MessageTooLarge`].
    ///
    /// # Complexity
    /// Per rank, a local tree of its n leaves and O(depth 2^D) fillers, the serial balance of it,
    /// then per round O(s (3^D - 1) log P) to choose the s leaves to send and the balance from
    /// the cells received; one allreduce per round and one all-to-all per round that moves
    /// cells (two words each).
    ///
    /// # Panics
    /// When called on a communicator other than the forest's (its size differs).
    pub fn balance(
        &mut self,
        comm: &impl Communicator,
        options: impl Into<BalanceOptions>,
    ) -> Result<BalanceStats, DistError> {
        let options = options.into();
        let (me, size) = comm::rank_size(comm);
        assert_eq!(size, self.partition.ranks(), "the forest's communicator");
        agree_options(comm, options)?;
        let ranges = KeyRanges::new::<D>(&self.partition);
        let mine = ranges.of(me);
        let directions = layer_directions::<D>(options.connectivity);
        let mut phases: Vec<(&'static str, f64)> = Vec::new();
        let clock = Instant::now();

        let mut tree = Tree::<D>::new();
        tree.reserve_splits(self.leaves.len() / ((1 << D) - 1) + 64);
        tree.refine_to_sorted(&self.leaves);
        // The tree holds them now, as its own leaves with the build's nodes (ids below
        // `built`; balance only appends), and gives them back on an error below: their memory
        // goes back to the allocator before the balance asks for more.
        let built = u32::try_from(tree.node_count()).expect("node ids are u32");
        self.leaves = Vec::new();
        phases.push(("build", clock.elapsed().as_secs_f64()));
        let clock = Instant::now();
        tree.balance(options);
        phases.push(("local balance", clock.elapsed().as_secs_f64()));
        // The own leaves not yet sent: at first all of them near another rank's range.
        let mut fresh: Vec<Cell<D>> = boundary_leaves(&tree, mine);
        let (mut rounds, mut sent, mut received) = (0, 0u64, 0u64);
        let (mut exchange_s, mut fixup_s) = (0.0, 0.0);
        loop {
            let t = Instant::now();
            let sends = layer_sends(&fresh, &directions, &ranges, me, size);
            let count: usize = sends.iter().map(Vec::len).sum();
            if comm::all_sum(comm, &[count as u64])[0] == 0 {
                exchange_s += t.elapsed().as_secs_f64();
                break;
            }
            rounds += 1;
            sent += count as u64;
            let cells = match exchange_cells(comm, &fresh, &sends) {
                Ok((cells, _)) => cells,
                Err(e) => {
                    self.leaves = own_leaves(&tree, mine, built);
                    return Err(e);
                }
            };
            received += cells.len() as u64;
            exchange_s += t.elapsed().as_secs_f64();
            let t = Instant::now();
            let mut seeds: Vec<NodeId> = Vec::new();
            for c in &cells {
                tree.refine_to(c, |v| seeds.push(v));
            }
            let split = tree.balance_seeded(options, &seeds);
            fresh.clear();
            for &v in &split {
                let cell = tree.cell(v);
                if (mine.0..mine.1).contains(&(cell.aligned_key() as u128)) {
                    for (i, child) in tree.children(v).enumerate() {
                        if tree.is_leaf(child) {
                            fresh.push(cell.child(i));
                        }
                    }
                }
            }
            fixup_s += t.elapsed().as_secs_f64();
        }
        phases.push(("exchange", exchange_s));
        phases.push(("fix-up", fixup_s));
        let clock = Instant::now();
        self.leaves = own_leaves(&tree, mine, u32::MAX);
        let first_key = self.leaves.first().map(Cell::aligned_key);
        self.partition = super::Partition::gather(comm, self.leaves.len(), first_key)?;
        phases.push(("collect", clock.elapsed().as_secs_f64()));
        Ok(BalanceStats {
            rounds,
            sent,
            received,
            phases,
        })
    }
}

/// The own leaves (keys in `mine`) whose insulation layer may leave `mine`, in Morton order: the
/// walk skips every subtree outside the range, and every subtree whose cell and same-size
/// neighbours lie inside it (the layer of a leaf below lies among them).
fn boundary_leaves<const D: usize>(tree: &Tree<D>, mine: (u128, u128)) -> Vec<Cell<D>> {
    let mut out = Vec::new();
    let mut stack: SmallVec<[(NodeId, Cell<D>); 64]> = SmallVec::new();
    stack.push((NodeId::ROOT, Cell::root()));
    while let Some((v, cell)) = stack.pop() {
        let (lo, hi) = span(&cell);
        if hi <= mine.0 || lo >= mine.1 {
            continue;
        }
        let (lo, hi) = span(&layer_ancestor(&cell));
        if lo >= mine.0 && hi <= mine.1 {
            continue;
        }
        if tree.is_leaf(v) {
            out.push(cell);
            continue;
        }
        for (i, child) in tree.children(v).enumerate().rev() {
            stack.push((child, cell.child(i)));
        }
    }
    out
}

/// The leaves of `tree` whose keys lie in `mine`, in Morton order, as the tree was when it had
/// `before` nodes (`u32::MAX`: as it is). The walk skips every subtree outside the range and
/// lists every subtree inside it in one pass (the build made the nodes in Morton order, so the
/// arena is read mostly in order).
fn own_leaves<const D: usize>(tree: &Tree<D>, mine: (u128, u128), before: u32) -> Vec<Cell<D>> {
    // At most every leaf: the pages past the end are never touched, and given back below.
    let mut leaves = Vec::with_capacity(tree.leaf_count());
    let mut stack: SmallVec<[(NodeId, Cell<D>); 64]> = SmallVec::new();
    stack.push((NodeId::ROOT, Cell::root()));
    while let Some((v, cell)) = stack.pop() {
        let (lo, hi) = span(&cell);
        if hi <= mine.0 || lo >= mine.1 {
            continue;
        }
        if lo >= mine.0 && hi <= mine.1 {
            tree.leaf_cells_below(v, cell, before, &mut leaves);
            continue;
        }
        let Some(first) = tree.child(v, 0).filter(|f| f.0 < before) else {
            // Across an end of the range: its key decides, as for every own leaf.
            if lo >= mine.0 {
                leaves.push(cell);
            }
            continue;
        };
        for i in (0..1 << D).rev() {
            stack.push((NodeId(first.0 + i as u32), cell.child(i)));
        }
    }
    leaves.shrink_to_fit();
    leaves
}

/// Agrees that every rank passed rank 0's options.
pub(crate) fn agree_options(
    comm: &impl Communicator,
    options: BalanceOptions,
) -> Result<(), DistError> {
    let code = options.connectivity as u64 * 256 + options.max_level_difference() as u64;
    let all = comm::all_gather(comm, &[code]);
    (all.iter().position(|&c| c != all[0]))
        .map_or(Ok(()), |rank| Err(DistError::SettingsDiffer { rank }))
}
