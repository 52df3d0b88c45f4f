//! The pieces the forest's balance and ghost layer share: which ranks own which Morton keys
//! ([`KeyRanges`], from the replicated partition table), which ranks a leaf's insulation layer
//! meets (Isaac, Burstedde and Ghattas 2012, "Low-cost parallel algorithms for 2:1 octree
//! balance", section 3: the 3^D - 1 same-size cells around a leaf, those the connectivity
//! counts), and the all-to-all exchange of cells (two words each: aligned key and level).
//!
//! Why the insulation layer is enough: when a leaf `b` touches a leaf `a` across a face, edge or
//! corner, the same-size neighbour of the smaller one in that direction lies inside the larger
//! one (dyadic cells are nested or disjoint, and the contact is a whole face, edge or corner of
//! the smaller cell). So each of two adjacent leaves on different ranks is either sent to the
//! other's rank or contains a cell of the other's insulation layer, and every rank sending its
//! leaves to the ranks their insulation layers meet tells each rank of every remote leaf
//! adjacent to one of its own, with some more that a check of contact removes.

use super::comm;
use super::forest::{root_end, span};
use super::{DistError, Partition};
use crate::geom::{Cell, Connectivity, Direction};
use mpi::traits::Communicator;

/// The Morton keys each non-empty rank owns: consecutive, from 0 to the root's end.
pub(crate) struct KeyRanges {
    begin: Vec<u128>,
    end: Vec<u128>,
    rank: Vec<usize>,
}

impl KeyRanges {
    /// The ranges of a forest's partition: a non-empty rank owns the keys from its first key up
    /// to the next non-empty rank's.
    pub(crate) fn new<const D: usize>(partition: &Partition) -> Self {
        let rank = partition.nonempty_ranks();
        let begin: Vec<u128> = rank
            .iter()
            .map(|&r| partition.first_keys()[r] as u128)
            .collect();
        let end = begin
            .iter()
            .skip(1)
            .copied()
            .chain([root_end::<D>()])
            .collect();
        KeyRanges { begin, end, rank }
    }

    /// The keys rank `r` owns (empty for an empty rank).
    pub(crate) fn of(&self, r: usize) -> (u128, u128) {
        (self.rank.binary_search(&r)).map_or((0, 0), |i| (self.begin[i], self.end[i]))
    }

    /// Calls `visit` with every rank owning a key in `lo..hi`, in rank order.
    #[inline]
    pub(crate) fn meeting(&self, lo: u128, hi: u128, mut visit: impl FnMut(usize)) {
        let mut i = self.end.partition_point(|&e| e <= lo);
        while i < self.begin.len() && self.begin[i] < hi {
            visit(self.rank[i]);
            i += 1;
        }
    }
}

/// The directions of a leaf's insulation layer that `connectivity` counts.
pub(crate) fn layer_directions<const D: usize>(connectivity: Connectivity) -> Vec<Direction> {
    Direction::all::<D>(connectivity).collect()
}

/// For each of the `size` ranks, the positions in `cells` of those whose insulation layer (the
/// same-size cells in `directions`) meets its range, in order; none for `me`.
pub(crate) fn layer_sends<const D: usize>(
    cells: &[Cell<D>],
    directions: &[Direction],
    ranges: &KeyRanges,
    me: usize,
    size: usize,
) -> Vec<Vec<usize>> {
    let mine = ranges.of(me);
    let mut sends = vec![Vec::new(); size];
    for (i, cell) in cells.iter().enumerate() {
        // Fast path: the smallest ancestor holding the whole layer lies in this rank's range.
        let (lo, hi) = span(&layer_ancestor(cell));
        if lo >= mine.0 && hi <= mine.1 {
            continue;
        }
        for &d in directions {
            let Some(n) = cell.neighbor(d) else { continue };
            let (lo, hi) = span(&n);
            if lo >= mine.0 && hi <= mine.1 {
                continue;
            }
            ranges.meeting(lo, hi, |r| {
                if r != me && sends[r].last() != Some(&i) {
                    sends[r].push(i);
                }
            });
        }
    }
    sends
}

/// The smallest ancestor of `cell` (the root at most) whose cell holds every
/// same-size neighbour of `cell` inside the root cube.
#[inline]
pub(crate) fn layer_ancestor<const D: usize>(cell: &Cell<D>) -> Cell<D> {
    let level = cell.level();
    let top = (1u64 << level) - 1;
    let mut up = 0u32;
    for c in cell.coords() {
        let c = c as u64;
        let (a, b) = (c.saturating_sub(1), (c + 1).min(top));
        up = up.max(64 - (a ^ b).leading_zeros());
    }
    cell.ancestor(level.saturating_sub(up.min(level as u32) as u8))
}

/// Sends `cells[i]` for each `i` of `sends[r]` to rank r (collective) and returns the cells
/// received, from rank 0 first, with how many came from each rank.
///
/// # Errors
/// [`DistError::MessageTooLarge`].
pub(crate) fn exchange_cells<const D: usize>(
    comm: &impl Communicator,
    cells: &[Cell<D>],
    sends: &[Vec<usize>],
) -> Result<(Vec<Cell<D>>, Vec<usize>), DistError> {
    let words: Vec<u64> = (sends.iter().flatten())
        .flat_map(|&i| [cells[i].aligned_key(), cells[i].level() as u64])
        .collect();
    let counts: Vec<usize> = sends.iter().map(|c| 2 * c.len()).collect();
    let (recv, recv_counts) = comm::exchange(comm, &words, &counts)?;
    let cells = recv
        .chunks_exact(2)
        .map(|w| Cell::from_aligned_key(w[0], w[1] as u8))
        .collect();
    Ok((cells, recv_counts.iter().map(|c| c / 2).collect()))
}
