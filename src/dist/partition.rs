//! [`Partition`]: elements in global Morton order split over the ranks, each rank one
//! contiguous range, with the replicated table of each rank's first position and first key
//! (p4est's `global_first_position`; Burstedde, Wilcox and Ghattas 2011, "p4est: Scalable
//! algorithms for parallel adaptive mesh refinement on forests of octrees", section 2.3), and
//! repartition: by counts ([`Partition::uniform`], p4est's uniform split floor(N r / P)) or by
//! weights ([`Partition::weighted`], p4est's `partition` with a weight callback), moving the
//! elements with one all-to-all exchange in which each rank sends contiguous runs.

use super::comm::{self, Words};
use super::DistError;
use crate::geom::FloatBits;
use bytemuck::Pod;
use mpi::traits::Communicator;

/// Which rank holds which run of a sequence in global order: every rank holds the same table.
///
/// Rank `r` holds positions `first[r]..first[r + 1]`, and its first element has Morton key
/// `first_key[r]` (an empty rank takes the next rank's, or `u64::MAX` after the last element,
/// as p4est does). Keys never decrease with the rank.
///
/// ```
/// use orthtree::dist::Partition;
/// let p = Partition::from_parts(vec![0, 3, 3, 7], vec![5, 9, 9]).unwrap();
/// assert_eq!((p.ranks(), p.len(), p.count(1)), (3, 7, 0));
/// assert_eq!(p.owner(3), Some(2));
/// assert_eq!(Partition::uniform(7, 3), [0, 2, 4, 7]);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Partition {
    first: Vec<u64>,
    first_key: Vec<u64>,
}

impl Partition {
    /// A table from its parts: `first` (one more entry than ranks, from 0, non-decreasing) and
    /// `first_key` (one per rank, non-decreasing).
    ///
    /// # Errors
    /// [`DistError::InvalidTargets`] naming the first entry of `first` or `first_key` (counted
    /// after `first`) that breaks the order or the lengths.
    pub fn from_parts(first: Vec<u64>, first_key: Vec<u64>) -> Result<Self, DistError> {
        check_targets(&first, first_key.len())?;
        if let Some(i) = (1..first_key.len()).find(|&i| first_key[i] < first_key[i - 1]) {
            return Err(DistError::InvalidTargets {
                index: first.len() + i,
            });
        }
        Ok(Partition { first, first_key })
    }

    /// Gathers the table from every rank's element count and first key (collective). The
    /// ranks' runs must follow each other in global order.
    ///
    /// # Errors
    /// [`DistError::InvalidTargets`] on every rank if the first keys decrease with the rank.
    pub fn gather(
        comm: &impl Communicator,
        len: usize,
        first_key: Option<u64>,
    ) -> Result<Self, DistError> {
        let all = comm::all_gather(comm, &[len as u64, first_key.unwrap_or(u64::MAX)]);
        let ranks = all.len() / 2;
        let mut first = Vec::with_capacity(ranks + 1);
        let mut at = 0u64;
        for r in 0..ranks {
            first.push(at);
            at += all[2 * r];
        }
        first.push(at);
        // An empty rank starts where the next non-empty one does.
        let mut keys = vec![u64::MAX; ranks];
        let mut next = u64::MAX;
        for r in (0..ranks).rev() {
            if all[2 * r] > 0 {
                next = all[2 * r + 1];
            }
            keys[r] = next;
        }
        Partition::from_parts(first, keys)
    }

    /// The number of ranks.
    pub fn ranks(&self) -> usize {
        self.first_key.len()
    }

    /// The number of elements over all ranks.
    pub fn len(&self) -> u64 {
        *self.first.last().expect("one entry per rank plus one")
    }

    /// Whether no rank holds an element.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The global positions rank `rank` holds.
    ///
    /// # Panics
    /// When `rank` is not below [`Partition::ranks`].
    pub fn range(&self, rank: usize) -> core::ops::Range<u64> {
        self.first[rank]..self.first[rank + 1]
    }

    /// The number of elements rank `rank` holds.
    ///
    /// # Panics
    /// When `rank` is not below [`Partition::ranks`].
    pub fn count(&self, rank: usize) -> u64 {
        self.first[rank + 1] - self.first[rank]
    }

    /// The ranks holding elements, in order.
    pub(crate) fn nonempty_ranks(&self) -> Vec<usize> {
        (0..self.ranks()).filter(|&r| self.count(r) > 0).collect()
    }

    /// Each rank's first global position, and the total last (p4est's
    /// `global_first_quadrant`).
    pub fn firsts(&self) -> &[u64] {
        &self.first
    }

    /// Each rank's first Morton key (p4est's `global_first_position`).
    pub fn first_keys(&self) -> &[u64] {
        &self.first_key
    }

    /// The rank holding global position `slot`, or `None` past the end.
    ///
    /// # Complexity
    /// O(log P).
    pub fn owner(&self, slot: u64) -> Option<usize> {
        (slot < self.len()).then(|| self.first.partition_point(|&f| f <= slot) - 1)
    }

    /// The ranks that may hold elements of Morton key `key`: rank `r` holds keys from
    /// `first_key[r]` up to `first_key[r + 1]` (inclusive: copies of one key may straddle a
    /// boundary). Empty ranks are left out only at the ends of the range.
    ///
    /// # Complexity
    /// O(log P).
    pub fn ranks_of_key(&self, key: u64) -> core::ops::Range<usize> {
        let lo = self
            .first_key
            .partition_point(|&k| k < key)
            .saturating_sub(1);
        let hi = self.first_key.partition_point(|&k| k <= key).max(lo + 1);
        let nonempty = |r: &usize| self.count(*r) > 0;
        let lo = (lo..hi).find(nonempty).unwrap_or(lo);
        let hi = (lo..hi).rev().find(nonempty).map_or(lo + 1, |r| r + 1);
        lo..hi
    }

    /// The first positions of the split of `len` elements over `ranks` ranks by counts: rank
    /// `r` starts at floor(len r / ranks) (p4est's uniform partition), so counts differ by at
    /// most one.
    pub fn uniform(len: u64, ranks: usize) -> Vec<u64> {
        (0..=ranks as u64)
            .map(|r| ((len as u128 * r as u128) / ranks.max(1) as u128) as u64)
            .collect()
    }

    /// The first positions of the split by weights (collective): every element has a
    /// `weights[i]` (this rank's elements, in order); rank `r` starts at the first element
    /// whose preceding weights sum to at least W r / P, W the total (p4est's weighted
    /// partition). With all weights zero it is [`Partition::uniform`].
    ///
    /// # Errors
    /// On every rank: [`DistError::WeightCount`] if a rank's weights are not one per element,
    /// [`DistError::InvalidWeight`] naming the first negative, NaN or infinite weight of the
    /// lowest rank that has one.
    pub fn weighted(
        &self,
        comm: &impl Communicator,
        weights: &[f64],
    ) -> Result<Vec<u64>, DistError> {
        let (rank, ranks) = comm::rank_size(comm);
        let elements = self.count(rank) as usize;
        if let Some(r) = comm::lowest_failing(comm, weights.len() != elements) {
            let mut w = vec![weights.len() as u64, elements as u64];
            comm::broadcast(comm, r, &mut w);
            return Err(DistError::WeightCount {
                rank: r,
                weights: w[0] as usize,
                elements: w[1] as usize,
            });
        }
        let bad = weights.iter().position(|w| !(w.is_finite() && *w >= 0.0));
        if let Some(r) = comm::lowest_failing(comm, bad.is_some()) {
            let i = bad.unwrap_or(0);
            let mut w = vec![i as u64, weights.get(i).map_or(0, |w| w.to_bits())];
            comm::broadcast(comm, r, &mut w);
            return Err(DistError::InvalidWeight {
                rank: r,
                index: w[0] as usize,
                value: FloatBits::from(f64::from_bits(w[1])),
            });
        }
        let sum: f64 = weights.iter().sum();
        let sums: Vec<f64> = comm::all_gather(comm, &[sum.to_bits()])
            .into_iter()
            .map(f64::from_bits)
            .collect();
        let total: f64 = sums.iter().sum();
        if total == 0.0 {
            return Ok(Partition::uniform(self.len(), ranks));
        }
        // For every target rank t, this rank's elements whose preceding weight (over all
        // ranks) is below its start W t / P; summed over ranks that is t's first position.
        let mut acc: f64 = sums[..rank].iter().sum();
        let mut i = 0usize;
        let mut counts = vec![0u64; ranks];
        for (t, count) in counts.iter_mut().enumerate().skip(1) {
            let start = total * t as f64 / ranks as f64;
            while i < weights.len() && acc < start {
                acc += weights[i];
                i += 1;
            }
            *count = i as u64;
        }
        let mut first = comm::all_sum(comm, &counts);
        first.push(self.len());
        Ok(first)
    }

    /// Moves this rank's elements `local` (in global order) so that rank `r` holds positions
    /// `targets[r]..targets[r + 1]` (collective, one all-to-all exchange in which every rank
    /// sends contiguous runs); returns the new table, with first keys by `key`, and this rank's
    /// new elements.
    ///
    /// # Errors
    /// [`DistError::InvalidTargets`] for targets that are not one entry per rank plus one,
    /// from 0 to [`Partition::len`], non-decreasing; [`DistError::MessageTooLarge`].
    ///
    /// # Panics
    /// When `local` is not this rank's count of elements.
    pub fn repartition<R: Pod>(
        &self,
        comm: &impl Communicator,
        local: &[R],
        targets: &[u64],
        key: impl Fn(&R) -> u64,
    ) -> Result<(Partition, Vec<R>), DistError> {
        let (rank, _) = comm::rank_size(comm);
        assert_eq!(
            local.len() as u64,
            self.count(rank),
            "one record per element"
        );
        let bytes = core::mem::size_of::<R>();
        let mut words = Words::with_records(local.len(), bytes);
        for (i, r) in local.iter().enumerate() {
            words.writer(i).put(r);
        }
        let words = self.move_words(comm, words, targets)?;
        let out: Vec<R> = (0..words.len()).map(|i| words.reader(i).get()).collect();
        let table = Partition::gather(comm, out.len(), out.first().map(&key))?;
        Ok((table, out))
    }

    /// [`Partition::repartition`] on records already packed as words.
    pub(crate) fn move_words(
        &self,
        comm: &impl Communicator,
        words: Words,
        targets: &[u64],
    ) -> Result<Words, DistError> {
        let (rank, ranks) = comm::rank_size(comm);
        check_targets(targets, ranks)?;
        if *targets.last().expect("checked") != self.len() {
            return Err(DistError::InvalidTargets { index: ranks });
        }
        let mine = self.range(rank);
        let counts: Vec<usize> = (0..ranks)
            .map(|r| {
                let lo = targets[r].max(mine.start);
                let hi = targets[r + 1].min(mine.end);
                hi.saturating_sub(lo) as usize
            })
            .collect();
        Ok(words.exchange(comm, &counts)?.0)
    }

    /// Checks the invariants: positions from 0, non-decreasing; keys non-decreasing.
    ///
    /// # Errors
    /// [`DistError::InvalidTargets`] naming the first entry that breaks them.
    pub fn validate(&self) -> Result<(), DistError> {
        Partition::from_parts(self.first.clone(), self.first_key.clone()).map(|_| ())
    }
}

/// Checks a table of first positions for `ranks` ranks: `ranks + 1` entries, from 0,
/// non-decreasing.
fn check_targets(first: &[u64], ranks: usize) -> Result<(), DistError> {
    if first.len() != ranks + 1 || ranks == 0 {
        return Err(DistError::InvalidTargets {
            index: first.len().min(ranks + 1),
        });
    }
    if first[0] != 0 {
        return Err(DistError::InvalidTargets { index: 0 });
    }
    (1..first.len())
        .find(|&i| first[i] < first[i - 1])
        .map_or(Ok(()), |index| Err(DistError::InvalidTargets { index }))
}
