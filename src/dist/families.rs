//! Repartition that keeps families of sibling leaves together (p4est's
//! `partition_for_coarsening`; Burstedde, Wilcox and Ghattas 2011, section 3.3): after the
//! uniform split by counts, every rank boundary that falls strictly inside a family of 2^D
//! sibling leaves moves to the nearer end of that family (the lower one on a tie), so that a
//! later coarsening finds each family on one rank.
//!
//! Each boundary's window of 2^(D+1) - 2 positions around it is gathered by every rank (an
//! allgather of three words per cell); each rank then adjusts every boundary the same way.
//! A family [s, s + 2^D) of leaves is recognised by its ends alone: the leaf at s is child 0
//! and the leaf at s + 2^D - 1 the last child of the same parent; since the leaves tile the
//! root cube in Morton order, the 2^D - 2 leaves between them are then exactly the other
//! children.

use super::comm;
use super::forest::DistForest;
use super::DistError;
use crate::geom::Cell;
use mpi::traits::Communicator;

/// How [`DistForest::repartition_with`] splits the leaves.
///
/// ```
/// use orthtree::dist::RepartitionOptions;
/// let options = RepartitionOptions::new().keep_families(true);
/// assert!(options.keeps_families());
/// assert!(!RepartitionOptions::default().keeps_families());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RepartitionOptions {
    families: bool,
}

impl RepartitionOptions {
    /// The uniform split by counts (p4est's `partition`).
    pub fn new() -> Self {
        Self::default()
    }

    /// With `true`, no family of 2^D sibling leaves is split across ranks: each boundary of the
    /// uniform split inside a family moves to the family's nearer end, so counts differ from
    /// the uniform split's by at most 2^(D-1) per boundary (p4est's
    /// `partition_for_coarsening`).
    pub fn keep_families(mut self, keep: bool) -> Self {
        self.families = keep;
        self
    }

    /// Whether families of sibling leaves are kept on one rank.
    pub fn keeps_families(&self) -> bool {
        self.families
    }
}

impl<const D: usize> DistForest<D> {
    /// The first positions of the uniform split with every boundary inside a family of
    /// sibling leaves moved to the family's nearer end (collective): see the module doc.
    pub(super) fn family_targets(
        &self,
        comm: &impl Communicator,
        mut targets: Vec<u64>,
    ) -> Result<Vec<u64>, DistError> {
        let (me, ranks) = comm::rank_size(comm);
        let n = 1u64 << D;
        let mine = self.partition.range(me);
        // This rank's cells in any boundary's window, once each, in order.
        let mut words = Vec::new();
        let mut next = mine.start;
        for &b in &targets[1..ranks] {
            let lo = b.saturating_sub(n - 1).max(next);
            let hi = (b + n - 1).min(mine.end);
            for p in lo..hi {
                let cell = &self.leaves[(p - mine.start) as usize];
                words.extend([p, cell.aligned_key(), cell.level() as u64]);
            }
            next = next.max(hi);
        }
        let (all, _) = comm::all_gather_var(comm, &words);
        let window: Vec<(u64, Cell<D>)> = all
            .chunks_exact(3)
            .map(|w| (w[0], Cell::from_aligned_key(w[1], w[2] as u8)))
            .collect();
        let at = |p: u64| -> Option<Cell<D>> {
            window
                .binary_search_by_key(&p, |e| e.0)
                .ok()
                .map(|i| window[i].1)
        };
        for b in targets[1..ranks].iter_mut() {
            let Some(cell) = at(*b) else { continue };
            let c = cell.child_index() as u64;
            if cell.level() == 0 || c == 0 || *b < c {
                continue;
            }
            let s = *b - c;
            let (first, last) = (at(s), at(s + n - 1));
            let family = matches!((first, last), (Some(f), Some(l))
                if f.level() == cell.level() && f.child_index() == 0
                    && l.child_index() as u64 == n - 1 && f.parent() == l.parent()
                    && f.parent() == cell.parent());
            if family {
                *b = if *b - s <= s + n - *b { s } else { s + n };
            }
        }
        // Moved boundaries stay in order (families are disjoint); kept non-decreasing anyway.
        for r in 1..=ranks {
            targets[r] = targets[r].max(targets[r - 1]);
        }
        Ok(targets)
    }
}
