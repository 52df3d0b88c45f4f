//! [`DistForest`]: the leaves of one 2^D-tree spread over MPI ranks in Morton order, each rank
//! holding one contiguous run of them, with the replicated [`Partition`] table of each rank's
//! first position and first key: p4est's linear forest (Burstedde, Wilcox and Ghattas 2011,
//! section 2), one tree. Built from any runs that tile the root cube, checked by an agreement
//! step; [`DistForest::repartition`] evens the counts (keeping families of siblings together
//! on request: `families.rs`). Balance is in `balance.rs`, the ghost
//! layer in `ghost.rs`, the key ranges and the exchange of cells in `exchange.rs`.

use super::comm;
use super::error::LeafProblem;
use super::{DistError, Partition, RepartitionOptions};
use crate::geom::Cell;
use mpi::traits::Communicator;

/// The leaves of one 2^D-tree over the ranks of a communicator: rank r holds the r-th run of
/// the leaves in Morton order, and every rank the table of each rank's first position and key.
///
/// ```
/// use orthtree::{dist::DistForest, Cell, Connectivity};
/// let universe = mpi::initialize().unwrap();
/// let world = universe.world();
/// let rank = mpi::traits::Communicator::rank(&world);
/// // the root split once, its first child split again: all of it on rank 0
/// let mut leaves = Vec::new();
/// if rank == 0 {
///     let first = Cell::<2>::root().child(0);
///     leaves.extend((0..4).map(|c| first.child(c)));
///     leaves.extend((1..4).map(|c| Cell::root().child(c)));
/// }
/// let mut forest = DistForest::new(&world, leaves).unwrap();
/// forest.balance(&world, Connectivity::Face).unwrap();
/// assert_eq!(forest.len(), 7); // already balanced
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct DistForest<const D: usize> {
    pub(super) leaves: Vec<Cell<D>>,
    pub(super) partition: Partition,
}

/// The Morton keys (aligned to [`Cell::MAX_LEVEL`]) a cell covers, `lo..hi`, in `u128` since the
/// root's end is 2^64 in 2D.
#[inline]
pub(crate) fn span<const D: usize>(cell: &Cell<D>) -> (u128, u128) {
    let lo = cell.aligned_key() as u128;
    (
        lo,
        lo + (1u128 << (D * (Cell::<D>::MAX_LEVEL - cell.level()) as usize)),
    )
}

/// The end of the root cube's keys.
#[inline]
pub(crate) fn root_end<const D: usize>() -> u128 {
    1u128 << (D * Cell::<D>::MAX_LEVEL as usize)
}

impl<const D: usize> DistForest<D> {
    /// The forest of every rank's `leaves` (collective). Each rank's leaves must follow each
    /// other in Morton order without gap or overlap, and the ranks' runs must follow each other
    /// in rank order and together tile the root cube (a rank may hold none).
    ///
    /// # Errors
    /// [`DistError::Leaves`] on every rank, naming the lowest rank and the leaf where the tiling
    /// breaks (checked on each rank first, then between ranks).
    ///
    /// # Complexity
    /// O(n) per rank for n leaves there, plus an allgather of three words per rank.
    pub fn new(comm: &impl Communicator, leaves: Vec<Cell<D>>) -> Result<Self, DistError> {
        let local = first_break(&leaves);
        if let Some(rank) = comm::lowest_failing(comm, local.is_some()) {
            let (index, problem) = local.unwrap_or((0, LeafProblem::Gap));
            let mut w = vec![index as u64, problem as u64];
            comm::broadcast(comm, rank, &mut w);
            return Err(DistError::Leaves {
                rank,
                index: w[0] as usize,
                problem: [LeafProblem::Overlap, LeafProblem::Gap][w[1] as usize],
            });
        }
        // Each rank's run: its count, first key, and last key covered (its end minus one).
        let ends = leaves
            .first()
            .zip(leaves.last())
            .map_or((0, 0), |(a, b)| (a.aligned_key(), (span(b).1 - 1) as u64));
        let all = comm::all_gather(comm, &[leaves.len() as u64, ends.0, ends.1]);
        let mut at = 0u128;
        let mut last = None;
        for (r, run) in all.chunks(3).enumerate() {
            if run[0] == 0 {
                continue;
            }
            if let Some(problem) = problem_at(run[1] as u128, at) {
                return Err(DistError::Leaves {
                    rank: r,
                    index: 0,
                    problem,
                });
            }
            at = run[2] as u128 + 1;
            last = Some((r, run[0] as usize));
        }
        if at != root_end::<D>() {
            let (rank, index) = last.unwrap_or((0, 0));
            return Err(DistError::Leaves {
                rank,
                index,
                problem: LeafProblem::Gap,
            });
        }
        let first_key = leaves.first().map(Cell::aligned_key);
        let partition = Partition::gather(comm, leaves.len(), first_key)?;
        Ok(DistForest { leaves, partition })
    }

    /// This rank's leaves, in Morton order.
    pub fn leaves(&self) -> &[Cell<D>] {
        &self.leaves
    }

    /// This rank's leaves, given up.
    pub fn into_leaves(self) -> Vec<Cell<D>> {
        self.leaves
    }

    /// The table of each rank's first position and first key.
    pub fn partition(&self) -> &Partition {
        &self.partition
    }

    /// The number of leaves over all ranks.
    pub fn len(&self) -> u64 {
        self.partition.len()
    }

    /// Whether the forest has no leaves (never: the leaves tile the root cube).
    pub fn is_empty(&self) -> bool {
        self.partition.is_empty()
    }

    /// The position of this rank's first leaf in the global Morton order.
    pub fn first_position(&self, comm: &impl Communicator) -> u64 {
        self.partition.firsts()[comm::rank_size(comm).0]
    }

    /// The same leaves with counts evened over the ranks (collective): rank r gets the leaves
    /// from position floor(N r / P) on (p4est's uniform partition), moved by one all-to-all
    /// exchange of contiguous runs. [`DistForest::repartition_with`] can keep families of
    /// sibling leaves together.
    ///
    /// # Errors
    /// [`DistError::MessageTooLarge`] when one rank would send or receive more than MPI counts.
    ///
    /// # Panics
    /// When called on a communicator other than the forest's (its size differs).
    pub fn repartition(&self, comm: &impl Communicator) -> Result<Self, DistError> {
        self.repartition_with(comm, RepartitionOptions::new())
    }

    /// [`DistForest::repartition`] with `options`: with
    /// [`RepartitionOptions::keep_families`], every boundary of the uniform split that falls
    /// inside a family of 2^D sibling leaves moves to the family's nearer end, so that no such
    /// family is split across ranks (p4est's `partition_for_coarsening`).
    ///
    /// # Errors
    /// [`DistError::MessageTooLarge`] when one rank would send or receive more than MPI counts.
    ///
    /// # Panics
    /// When called on a communicator other than the forest's (its size differs).
    ///
    /// # Complexity
    /// O(n) per rank for the n leaves it sends or receives, one all-to-all; keeping families
    /// adds an allgather of (2^(D+1) - 2) (P - 1) cells of three words.
    ///
    /// ```
    /// use orthtree::dist::{DistForest, RepartitionOptions};
    /// use orthtree::Cell;
    /// let universe = mpi::initialize().unwrap();
    /// let world = universe.world();
    /// let rank = mpi::traits::Communicator::rank(&world);
    /// let leaves = if rank == 0 { (0..4).map(|c| Cell::<2>::root().child(c)).collect() } else { vec![] };
    /// let forest = DistForest::new(&world, leaves).unwrap();
    /// let kept = forest
    ///     .repartition_with(&world, RepartitionOptions::new().keep_families(true))
    ///     .unwrap();
    /// // the root's four children are one family: on one rank whatever the rank count
    /// assert!(kept.leaves().is_empty() || kept.leaves().len() == 4);
    /// ```
    pub fn repartition_with(
        &self,
        comm: &impl Communicator,
        options: RepartitionOptions,
    ) -> Result<Self, DistError> {
        let (_, size) = comm::rank_size(comm);
        assert_eq!(size, self.partition.ranks(), "the forest's communicator");
        let mut targets = Partition::uniform(self.len(), size);
        if options.keeps_families() {
            targets = self.family_targets(comm, targets)?;
        }
        let records: Vec<[u64; 2]> = self
            .leaves
            .iter()
            .map(|c| [c.aligned_key(), c.level() as u64])
            .collect();
        let (partition, moved) = self
            .partition
            .repartition(comm, &records, &targets, |r| r[0])?;
        let leaves = moved
            .iter()
            .map(|r| Cell::from_aligned_key(r[0], r[1] as u8))
            .collect();
        Ok(DistForest { leaves, partition })
    }
}

/// The first leaf of a rank's run that does not start where the one before it ends.
fn first_break<const D: usize>(leaves: &[Cell<D>]) -> Option<(usize, LeafProblem)> {
    leaves.windows(2).enumerate().find_map(|(i, w)| {
        problem_at(w[1].aligned_key() as u128, span(&w[0]).1).map(|p| (i + 1, p))
    })
}

/// The problem of a leaf starting at key `start` after leaves ending at `end`: none when it
/// starts right there.
fn problem_at(start: u128, end: u128) -> Option<LeafProblem> {
    match start.cmp(&end) {
        core::cmp::Ordering::Less => Some(LeafProblem::Overlap),
        core::cmp::Ordering::Greater => Some(LeafProblem::Gap),
        core::cmp::Ordering::Equal => None,
    }
}
