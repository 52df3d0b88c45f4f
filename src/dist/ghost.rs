//! The ghost layer of a [`DistForest`] (p4est's `p4est_ghost_new`, Burstedde, Wilcox and Ghattas
//! 2011, section 3.2): for each rank, the remote leaves adjacent to one of its own under a
//! connectivity (the ghosts), and which of its own leaves the other ranks see (the mirrors).
//!
//! One all-to-all exchange: each rank sends every leaf whose insulation layer meets another
//! rank's range to that rank (`exchange.rs` says why this reaches every adjacent pair). The
//! receiver keeps the cells that touch one of its leaves (exact integer contact tests of the
//! cells near each one, found by binary search in Morton order); and since adjacency is symmetric
//! and every remote leaf adjacent to an own leaf arrived, an own leaf sent to rank r is a mirror
//! for r exactly when it touches one of the cells that came from r. No second exchange.

use super::comm;
use super::exchange::{exchange_cells, layer_directions, layer_sends, KeyRanges};
use super::forest::span;
use super::{DistError, DistForest};
use crate::geom::{Cell, Connectivity, Direction};
use mpi::traits::Communicator;

/// The ghost layer of one rank: the remote leaves adjacent to its own, by owner, and its own
/// leaves adjacent to remote ones (the mirrors), by the rank that sees them.
///
/// ```
/// use orthtree::{dist::DistForest, Cell, Connectivity};
/// let universe = mpi::initialize().unwrap();
/// let world = universe.world();
/// let leaves = if mpi::traits::Communicator::rank(&world) == 0 {
///     (0..4).map(|c| Cell::<2>::root().child(c)).collect()
/// } else {
///     Vec::new()
/// };
/// let forest = DistForest::new(&world, leaves).unwrap();
/// let ghost = forest.ghost(&world, Connectivity::Corner).unwrap();
/// assert!(ghost.ghosts().is_empty()); // every leaf on one rank
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GhostLayer<const D: usize> {
    ghosts: Vec<Cell<D>>,
    ghost_first: Vec<usize>,
    mirrors: Vec<usize>,
    mirror_lists: Vec<usize>,
    mirror_first: Vec<usize>,
}

impl<const D: usize> GhostLayer<D> {
    /// Every ghost, in Morton order (which is owner order).
    pub fn ghosts(&self) -> &[Cell<D>] {
        &self.ghosts
    }

    /// The ghosts owned by rank `rank`, in Morton order.
    ///
    /// # Panics
    /// When `rank` is not a rank of the communicator.
    pub fn ghosts_of(&self, rank: usize) -> &[Cell<D>] {
        &self.ghosts[self.ghost_first[rank]..self.ghost_first[rank + 1]]
    }

    /// The rank owning ghost `index`.
    ///
    /// # Panics
    /// When `index` is not below the number of ghosts.
    pub fn owner(&self, index: usize) -> usize {
        assert!(index < self.ghosts.len(), "ghost index out of range");
        self.ghost_first.partition_point(|&f| f <= index) - 1
    }

    /// The positions (in [`DistForest::leaves`]) of this rank's leaves some other rank sees,
    /// increasing.
    pub fn mirrors(&self) -> &[usize] {
        &self.mirrors
    }

    /// The positions of this rank's leaves that rank `rank` sees, increasing.
    ///
    /// # Panics
    /// When `rank` is not a rank of the communicator.
    pub fn mirrors_for(&self, rank: usize) -> &[usize] {
        &self.mirror_lists[self.mirror_first[rank]..self.mirror_first[rank + 1]]
    }
}

impl<const D: usize> DistForest<D> {
    /// The ghost layer under `connectivity` (collective; see the module doc).
    ///
    /// # Errors
    /// [`DistError::SettingsDiffer`] when the ranks pass different connectivities;
    /// [`DistError::MessageTooLarge`].
    ///
    /// # Complexity
    /// O(n (3^D - 1)) per rank to choose what to send, one all-to-all of two words per leaf
    /// sent, and per cell received or sent a binary search and the contact tests of the cells
    /// in its insulation layer.
    ///
    /// # Panics
    /// When called on a communicator other than the forest's (its size differs).
    pub fn ghost(
        &self,
        comm: &impl Communicator,
        connectivity: Connectivity,
    ) -> Result<GhostLayer<D>, DistError> {
        let (me, size) = comm::rank_size(comm);
        assert_eq!(size, self.partition.ranks(), "the forest's communicator");
        super::balance::agree_options(comm, connectivity.into())?;
        let ranges = KeyRanges::new::<D>(&self.partition);
        let directions = layer_directions::<D>(connectivity);
        let sent_index = layer_sends(&self.leaves, &directions, &ranges, me, size);
        let (cells, counts) = exchange_cells(comm, &self.leaves, &sent_index)?;
        let mut ghosts = Vec::new();
        let mut ghost_first = vec![0];
        let mut mirror_lists = Vec::new();
        let mut mirror_first = vec![0];
        let mut at = 0;
        for (r, &n) in counts.iter().enumerate() {
            let from = &cells[at..at + n];
            at += n;
            ghosts.extend(
                from.iter()
                    .filter(|g| touches_any(g, &self.leaves, &directions, connectivity)),
            );
            ghost_first.push(ghosts.len());
            mirror_lists.extend(
                sent_index[r]
                    .iter()
                    .copied()
                    .filter(|&i| touches_any(&self.leaves[i], from, &directions, connectivity)),
            );
            mirror_first.push(mirror_lists.len());
        }
        let mut mirrors = mirror_lists.clone();
        mirrors.sort_unstable();
        mirrors.dedup();
        Ok(GhostLayer {
            ghosts,
            ghost_first,
            mirrors,
            mirror_lists,
            mirror_first,
        })
    }
}

/// Whether `cell` touches one of `cells` (disjoint, in Morton order) across a face, edge or
/// corner that `connectivity` counts.
fn touches_any<const D: usize>(
    cell: &Cell<D>,
    cells: &[Cell<D>],
    directions: &[Direction],
    connectivity: Connectivity,
) -> bool {
    directions
        .iter()
        .filter_map(|&d| cell.neighbor(d))
        .any(|n| {
            let (lo, hi) = span(&n);
            let start = cells.partition_point(|c| span(c).1 <= lo);
            cells[start..]
                .iter()
                .take_while(|c| (c.aligned_key() as u128) < hi)
                .any(|c| cell.contact(c).is_some_and(|k| connectivity.allows(k)))
        })
}
