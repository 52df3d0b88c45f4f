//! [`DistPointTree`]: the point tree distributed over MPI ranks: this rank's local
//! [`PointTree`] over the global root box holding one contiguous run of the global Morton
//! order, the replicated [`Partition`] table, and every rank's bounding box of its points (to
//! route queries). Built by [`DistPointTreeBuilder`](super::DistPointTreeBuilder); queried
//! in batches (`queries.rs`).

use super::comm;
use super::Partition;
use crate::error::{Invariant, ValidationError};
use crate::geom::{Aabb, RootGeometry, Scalar};
use crate::query::PointSet;
use crate::PointTree;
use mpi::topology::SimpleCommunicator;

/// A point tree over the points of every rank of a communicator; each rank holds a
/// [`PointTree`] over one contiguous run of the global Morton order (see [`crate::dist`]).
///
/// Global slot `s` is the position of a point in the single-process tree over the union of
/// every rank's input (rank 0's input first): it sits on rank
/// [`Partition::owner`]`(s)`, at local slot `s - partition().firsts()[rank]`.
pub struct DistPointTree<S, T, const D: usize> {
    pub(super) comm: SimpleCommunicator,
    pub(super) local: PointTree<S, T, D>,
    pub(super) partition: Partition,
    /// Every rank's bounding box of its points (empty, min above max, for a rank without).
    pub(super) boxes: Vec<Aabb<f64, D>>,
    /// The build's phases and their seconds on this rank.
    pub(super) phases: Vec<(&'static str, f64)>,
}

impl<S: Scalar, T, const D: usize> core::fmt::Debug for DistPointTree<S, T, D> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("DistPointTree")
            .field("rank", &self.rank())
            .field("partition", &self.partition)
            .field("local_len", &self.local.len())
            .finish_non_exhaustive()
    }
}

impl<S: Scalar, T, const D: usize> DistPointTree<S, T, D> {
    /// This rank's tree: its run of the global order, over the global root box, with local
    /// slots (add `partition().firsts()[rank]` for global ones).
    pub fn local(&self) -> &PointTree<S, T, D> {
        &self.local
    }

    /// The replicated table of every rank's run.
    pub fn partition(&self) -> &Partition {
        &self.partition
    }

    /// Every rank's bounding box of its points (min above max for a rank without points).
    pub fn rank_boxes(&self) -> &[Aabb<f64, D>] {
        &self.boxes
    }

    /// This rank's number in the tree's communicator.
    pub fn rank(&self) -> usize {
        comm::rank_size(&self.comm).0
    }

    /// The tree's communicator (a duplicate of the one it was built on).
    pub fn comm(&self) -> &SimpleCommunicator {
        &self.comm
    }

    /// The number of points over all ranks.
    pub fn len(&self) -> u64 {
        self.partition.len()
    }

    /// Whether no rank holds a point.
    pub fn is_empty(&self) -> bool {
        self.partition.is_empty()
    }

    /// The global slot of this rank's first point.
    pub fn first_slot(&self) -> u64 {
        self.partition.firsts()[self.rank()]
    }

    /// The root geometry, the same on every rank.
    pub fn geometry(&self) -> &RootGeometry<D> {
        self.local.geometry()
    }

    /// The build's phases on this rank with their seconds (wall clock).
    pub fn build_phases(&self) -> &[(&'static str, f64)] {
        &self.phases
    }

    /// Checks every invariant (collective): this rank's tree ([`PointSet::validate`]), the
    /// partition table, that it agrees with this rank's points (count, first key), that the
    /// runs follow each other in Morton order across ranks, and the rank boxes. Every rank
    /// takes part even when its own check fails, and returns its own finding.
    ///
    /// # Errors
    /// The first invariant broken, as a [`ValidationError`].
    pub fn validate(&self) -> Result<(), ValidationError> {
        let local = self.local.validate();
        let g = self.local.geometry();
        let pts = self.local.points();
        let first = pts.first().map_or(u64::MAX, |p| g.scalar_key(p));
        let last = pts.last().map_or(0, |p| g.scalar_key(p));
        let all = comm::all_gather(&self.comm, &[pts.len() as u64, first, last]);
        local?;
        let fail = |detail: String| Err(ValidationError::new(Invariant::Counts).detail(detail));
        if let Err(e) = self.partition.validate() {
            return fail(format!("partition table: {e}"));
        }
        let rank = self.rank();
        let mut previous_last = 0u64;
        for (r, w) in all.chunks(3).enumerate() {
            if w[0] != self.partition.count(r) {
                return fail(format!(
                    "rank {r} holds {} points, the table says {}",
                    w[0],
                    self.partition.count(r)
                ));
            }
            if w[0] == 0 {
                continue;
            }
            if w[1] != self.partition.first_keys()[r] {
                return fail(format!("rank {r}'s first key differs from the table's"));
            }
            if w[1] < previous_last {
                return fail(format!(
                    "rank {r} starts below the last key of the rank before"
                ));
            }
            previous_last = w[2];
        }
        if !pts.is_empty() && Aabb::around(pts) != self.boxes[rank] {
            return fail(format!("rank {rank}'s box differs from its points' bounds"));
        }
        Ok(())
    }
}
