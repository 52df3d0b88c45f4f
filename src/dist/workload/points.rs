//! [`PointsWorkload`]: uniform and clustered points in the unit square, a
//! [`DistPointTree`] built over every rank and a batch of k-nearest queries; each point and
//! query drawn from its index alone by SplitMix64 (Steele, Lea and Flood 2014), so the union
//! and the checksums are the same at every rank count. [`PointsReport`] holds what rank 0
//! prints.

use super::{over, phase_list, slowest, sum_over, timed, WorkloadError};
use crate::dist::{DistError, DistPointTree, Partition, MAX_TOTAL};
use crate::query::PointSet;
use mpi::collective::SystemOperation;
use mpi::traits::*;

/// The point workload's settings (the same on every rank).
///
/// ```no_run
/// use orthtree::dist::workload::PointsWorkload;
/// let universe = mpi::initialize().unwrap();
/// let world = universe.world();
/// let work = PointsWorkload { n: 10_000, queries: 1_000, k: 4 };
/// let report = work.run(&world).unwrap();
/// assert_eq!(report.runs[0].found, 4_000);
/// print!("{report}");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PointsWorkload {
    /// Points in all, at least 1.
    pub n: u64,
    /// k-nearest queries in all.
    pub queries: u64,
    /// Neighbours per query, at least 1.
    pub k: usize,
}

impl Default for PointsWorkload {
    /// 10^6 points, 10^5 queries, k = 8.
    fn default() -> Self {
        PointsWorkload {
            n: 1_000_000,
            queries: 100_000,
            k: 8,
        }
    }
}

/// One data set's figures in a [`PointsReport`].
#[derive(Clone, Debug, PartialEq)]
pub struct PointsRun {
    /// `"uniform"` or `"clustered"`.
    pub kind: &'static str,
    /// Points in the tree.
    pub len: u64,
    /// XOR over the points of a hash of (global slot, item).
    pub build_sum: u64,
    /// Neighbours found over all queries.
    pub found: u64,
    /// XOR over the answers of a hash of (query, rank in the answer, slot, distance).
    pub knn_sum: u64,
    /// Seconds to build (maximum over ranks).
    pub build_s: f64,
    /// The build's phases (maximum over ranks).
    pub phases: Vec<(&'static str, f64)>,
    /// Seconds of the batch k-nearest (maximum over ranks).
    pub knn_s: f64,
}

/// What a [`PointsWorkload`] did, the same on every rank: the uniform run, then the clustered.
#[derive(Clone, Debug, PartialEq)]
pub struct PointsReport {
    /// The settings.
    pub work: PointsWorkload,
    /// The number of ranks.
    pub ranks: usize,
    /// The uniform and the clustered data set.
    pub runs: Vec<PointsRun>,
}

/// SplitMix64's finaliser: a well-mixed 64-bit value of `x`.
fn mix(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^ (x >> 31)
}

/// A number in [0, 1) from `x`.
fn unit(x: u64) -> f64 {
    (mix(x) >> 11) as f64 / (1u64 << 53) as f64
}

/// Point `i` of a data set: uniform, or near one of eight centres.
fn point(i: u64, clustered: bool) -> [f64; 2] {
    let (a, b) = (unit(2 * i), unit(2 * i + 1));
    if !clustered {
        return [a, b];
    }
    let c = mix(i ^ 0x5555) % 8;
    let centre = [0.1 + 0.1 * c as f64, 0.2 + 0.6 * unit(c + 1000)];
    [centre[0] + 0.02 * (a - 0.5), centre[1] + 0.02 * (b - 0.5)]
}

impl PointsWorkload {
    /// Checks the settings: 1 to [`MAX_TOTAL`] points, at most 2^40 queries, 1 to 2^20
    /// neighbours.
    ///
    /// # Errors
    /// The [`WorkloadError`] naming the first bad setting and its range.
    pub fn validate(&self) -> Result<(), WorkloadError> {
        super::check_count("n", self.n, 1, MAX_TOTAL)?;
        super::check_count("queries", self.queries, 0, 1 << 40)?;
        super::check_count("k", self.k as u64, 1, 1 << 20)
    }

    /// Runs the workload (collective: every rank calls it with the same settings).
    ///
    /// # Errors
    /// [`DistError::Workload`] for settings [`PointsWorkload::validate`] refuses; the errors of
    /// the build and of [`DistPointTree::k_nearest_batch`].
    pub fn run(&self, comm: &impl Communicator) -> Result<PointsReport, DistError> {
        self.validate().map_err(DistError::Workload)?;
        let (rank, size) = (comm.rank() as usize, comm.size() as usize);
        let mut runs = Vec::new();
        for clustered in [false, true] {
            let mine = Partition::uniform(self.n, size);
            let entries: Vec<([f64; 2], u64)> = (mine[rank]..mine[rank + 1])
                .map(|i| (point(i, clustered), i))
                .collect();
            let qs = Partition::uniform(self.queries, size);
            let queries: Vec<[f64; 2]> = (qs[rank]..qs[rank + 1])
                .map(|j| point(j + (1 << 50), clustered))
                .collect();
            let (tree, build_s) = timed(comm, || {
                DistPointTree::builder().build_from_vec(comm, entries)
            });
            let tree = tree?;
            let phases = slowest(comm, tree.build_phases());
            let first = tree.first_slot();
            let items = tree.local().items().iter().enumerate();
            let sum = items.fold(0, |x, (s, item)| x ^ mix((first + s as u64) ^ mix(*item)));
            let build_sum = over(comm, sum, SystemOperation::bitwise_xor());
            let (answers, knn_s) = timed(comm, || tree.k_nearest_batch(&queries, self.k));
            let answers = answers?;
            let mut sum = 0u64;
            let mut found = 0u64;
            for (j, a) in answers.iter().enumerate() {
                let q = qs[rank] + j as u64;
                for (t, n) in a.iter().enumerate() {
                    sum ^= mix(mix(q) ^ (n.slot << 8) ^ t as u64 ^ n.distance.to_bits());
                }
                found += a.len() as u64;
            }
            runs.push(PointsRun {
                kind: if clustered { "clustered" } else { "uniform" },
                len: tree.len(),
                build_sum,
                found: sum_over(comm, found),
                knn_sum: over(comm, sum, SystemOperation::bitwise_xor()),
                build_s,
                phases,
                knn_s,
            });
        }
        Ok(PointsReport {
            work: *self,
            ranks: size,
            runs,
        })
    }
}

impl core::fmt::Display for PointsReport {
    /// The lines `dist_points` prints: per data set the counts and checksums, then the times.
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let w = &self.work;
        writeln!(
            f,
            "dist_points: {} points, {} queries, k = {}, {} ranks",
            w.n, w.queries, w.k, self.ranks
        )?;
        for r in &self.runs {
            writeln!(
                f,
                "{:9}: {} points, build checksum {:016x}, {} neighbours, knn checksum {:016x}",
                r.kind, r.len, r.build_sum, r.found, r.knn_sum
            )?;
            writeln!(
                f,
                "           build {:.3} s ({}), batch k-nearest {:.3} s, total {:.3} s",
                r.build_s,
                phase_list(&r.phases, 3),
                r.knn_s,
                r.build_s + r.knn_s
            )?;
        }
        Ok(())
    }
}
