//! [`BalanceWorkload`]: p4est's fractal refined over every rank, then the distributed 2:1
//! balance ([`DistForest::balance`], Isaac, Burstedde and Ghattas 2012), optionally the ghost
//! layer and a serial check; [`BalanceReport`] holds what rank 0 prints.

use super::fractal::{fractal_part, fractal_tree, uniform_cells};
use super::{max_over, median, phase_list, slowest, sum_over, timed, WorkloadError};
use crate::dist::{DistError, DistForest, Partition};
use crate::geom::Cell;
use crate::Connectivity;
use mpi::traits::*;

/// The fractal balance workload's settings (the same on every rank).
///
/// ```no_run
/// use orthtree::dist::workload::BalanceWorkload;
/// let universe = mpi::initialize().unwrap();
/// let world = universe.world();
/// let work = BalanceWorkload { level: 6, ..BalanceWorkload::default() };
/// let report = work.run(&world).unwrap();
/// assert_eq!(report.before, 5_632);
/// print!("{report}");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BalanceWorkload {
    /// The dimension: 2, 3 or 4.
    pub dim: usize,
    /// The fractal's refinement level, at most the tree's deepest level.
    pub level: u8,
    /// The balance's connectivity.
    pub connect: Connectivity,
    /// Balance runs, 1 to 100; the median time is reported.
    pub reps: usize,
    /// Also build the ghost layer of the balanced forest.
    pub ghost: bool,
    /// Rank 0 also balances the whole fractal serially and compares.
    pub check: bool,
}

impl Default for BalanceWorkload {
    /// 2D, level 8, face connectivity, one run, no ghost layer, no check.
    fn default() -> Self {
        BalanceWorkload {
            dim: 2,
            level: 8,
            connect: Connectivity::Face,
            reps: 1,
            ghost: false,
            check: false,
        }
    }
}

/// Peak bytes per leaf of the fractal before balance, over all ranks: the leaves (before and
/// after balance, 2 to 2.2 times as many), each rank's local tree and the copy of the refined
/// forest kept for repeated runs; measured 60-80 B at levels 10-12 in 2D and 7-8 in 3D, with a
/// margin.
const PEAK_BYTES_PER_LEAF: f64 = 120.0;

/// What a [`BalanceWorkload`] did, the same on every rank.
#[derive(Clone, Debug, PartialEq)]
pub struct BalanceReport {
    /// The settings.
    pub work: BalanceWorkload,
    /// The number of ranks.
    pub ranks: usize,
    /// Leaves before balance.
    pub before: u64,
    /// Leaves after balance.
    pub after: u64,
    /// The most leaves one rank holds after balance.
    pub most: u64,
    /// FNV-1a over (level, coordinates) of every leaf in Morton order, as `orthtree balance`
    /// computes it.
    pub checksum: u64,
    /// Seconds to refine the fractal (maximum over ranks).
    pub refine_s: f64,
    /// Seconds of balance (maximum over ranks, median over the runs).
    pub balance_s: f64,
    /// Seconds of each phase of balance (maximum over ranks, median over the runs).
    pub phases: Vec<(&'static str, f64)>,
    /// Exchange rounds that moved cells.
    pub rounds: usize,
    /// Cells sent over all ranks and rounds.
    pub sent: u64,
    /// Ghosts and mirrors over all ranks and the seconds to build the layer, with `ghost`.
    pub ghost: Option<(u64, u64, f64)>,
    /// The serial balance's leaf count and whether it equals the distributed one, with
    /// `check`.
    pub serial: Option<(u64, bool)>,
}

impl BalanceWorkload {
    /// The number of leaves before balance.
    pub fn leaves_before(&self) -> f64 {
        super::fractal_leaves(self.dim, self.level)
    }

    /// The estimated peak memory over all ranks, in bytes, for a caller to check against the
    /// memory it may use before [`BalanceWorkload::run`].
    pub fn estimated_bytes(&self) -> f64 {
        let check = if self.check { 1.5 } else { 1.0 };
        self.leaves_before() * PEAK_BYTES_PER_LEAF * check
    }

    /// Checks the settings: the dimension (2, 3, 4), the level against the dimension's
    /// deepest level, the runs (1 to 100).
    ///
    /// # Errors
    /// The [`WorkloadError`] naming the first bad setting and its limit.
    pub fn validate(&self) -> Result<(), WorkloadError> {
        let deepest = match self.dim {
            2 => Cell::<2>::MAX_LEVEL,
            3 => Cell::<3>::MAX_LEVEL,
            4 => Cell::<4>::MAX_LEVEL,
            dim => return Err(WorkloadError::Dimension { dim }),
        };
        if self.level > deepest {
            return Err(WorkloadError::Level {
                level: self.level,
                dim: self.dim,
                deepest,
            });
        }
        super::check_count("reps", self.reps as u64, 1, 100)
    }

    /// Runs the workload (collective: every rank calls it with the same settings).
    ///
    /// # Errors
    /// [`DistError::Workload`] for settings [`BalanceWorkload::validate`] refuses; the errors
    /// of [`DistForest::new`], [`DistForest::balance`] and [`DistForest::ghost`].
    pub fn run(&self, comm: &impl Communicator) -> Result<BalanceReport, DistError> {
        self.validate().map_err(DistError::Workload)?;
        match self.dim {
            2 => self.run_in::<2>(comm),
            3 => self.run_in::<3>(comm),
            _ => self.run_in::<4>(comm),
        }
    }

    fn run_in<const D: usize>(&self, comm: &impl Communicator) -> Result<BalanceReport, DistError> {
        let (rank, size) = (comm.rank() as usize, comm.size() as usize);
        let (refined, refine_s) = timed(comm, || {
            let cells = Partition::uniform(uniform_cells::<D>(self.level), size);
            DistForest::new(
                comm,
                fractal_part::<D>(self.level, cells[rank], cells[rank + 1]),
            )
        });
        let refined = refined?;
        let mut totals = Vec::new();
        let mut runs: Vec<Vec<(&'static str, f64)>> = Vec::new();
        let mut forest = refined.clone();
        let mut stats = None;
        for _ in 0..self.reps {
            forest = refined.clone();
            let (s, total) = timed(comm, || forest.balance(comm, self.connect));
            let s = s?;
            totals.push(total);
            runs.push(slowest(comm, &s.phases));
            stats = Some(s);
        }
        let stats = stats.expect("validated: at least one run");
        let phases = (0..runs[0].len())
            .map(|i| (runs[0][i].0, median(runs.iter().map(|p| p[i].1).collect())))
            .collect();
        let sent = sum_over(comm, stats.sent);
        let mine = forest.leaves().len() as u64;
        let most = max_over(comm, mine);
        let checksum = checksum(comm, forest.leaves());
        let ghost = if self.ghost {
            let (layer, ghost_s) = timed(comm, || forest.ghost(comm, self.connect));
            let layer = layer?;
            Some((
                sum_over(comm, layer.ghosts().len() as u64),
                sum_over(comm, layer.mirrors().len() as u64),
                ghost_s,
            ))
        } else {
            None
        };
        let after = sum_over(comm, mine);
        let serial = self.check.then(|| {
            let mut verdict = vec![0u64, 0];
            if rank == 0 {
                let mut tree = fractal_tree::<D>(self.level);
                tree.balance(self.connect);
                let leaves: Vec<Cell<D>> = tree.leaves().map(|(_, c)| c).collect();
                let same = fnv(FNV_BASIS, &leaves) == checksum && leaves.len() as u64 == after;
                verdict = vec![leaves.len() as u64, same as u64];
            }
            super::super::comm::broadcast(comm, 0, &mut verdict);
            (verdict[0], verdict[1] == 1)
        });
        Ok(BalanceReport {
            work: *self,
            ranks: size,
            before: refined.len(),
            after,
            most,
            checksum,
            refine_s,
            balance_s: median(totals),
            phases,
            rounds: stats.rounds,
            sent,
            ghost,
            serial,
        })
    }
}

impl core::fmt::Display for BalanceReport {
    /// The lines `dist_balance` prints: counts, checksum, times, exchange, ghost layer and check.
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let w = &self.work;
        writeln!(
            f,
            "dist_balance: dim {}, level {}, {:?}, {} ranks",
            w.dim, w.level, w.connect, self.ranks
        )?;
        writeln!(f, "leaves before balance: {}", self.before)?;
        writeln!(
            f,
            "leaves after balance:  {} (most on one rank {})",
            self.after, self.most
        )?;
        writeln!(f, "checksum:              {:016x}", self.checksum)?;
        writeln!(f, "refine time:           {:.4} s", self.refine_s)?;
        writeln!(
            f,
            "balance time:          {:.4} s (median of {}; {})",
            self.balance_s,
            w.reps,
            phase_list(&self.phases, 4)
        )?;
        writeln!(
            f,
            "exchange:              {} rounds, {} cells sent in all",
            self.rounds, self.sent
        )?;
        if let Some((ghosts, mirrors, s)) = self.ghost {
            writeln!(
                f,
                "ghost layer:           {ghosts} ghosts, {mirrors} mirrors, {s:.4} s"
            )?;
        }
        if let Some((leaves, same)) = self.serial {
            writeln!(f, "serial balance:        {leaves} leaves, same: {same}")?;
        }
        Ok(())
    }
}

/// FNV-1a's offset basis.
const FNV_BASIS: u64 = 0xcbf2_9ce4_8422_2325;

/// FNV-1a over (level, coordinates) of `cells`, continuing from `h` (`orthtree balance`'s
/// checksum when run over every leaf in Morton order from the offset basis).
fn fnv<const D: usize>(mut h: u64, cells: &[Cell<D>]) -> u64 {
    for cell in cells {
        for x in std::iter::once(cell.level() as u32).chain(cell.coords()) {
            for b in x.to_le_bytes() {
                h = (h ^ b as u64).wrapping_mul(0x0100_0000_01b3);
            }
        }
    }
    h
}

/// The checksum of every rank's leaves in rank order (collective): each rank continues the hash
/// of the ranks before it (a chain of messages), and the last rank's hash goes to every rank.
fn checksum<const D: usize>(comm: &impl Communicator, leaves: &[Cell<D>]) -> u64 {
    let (rank, size) = (comm.rank(), comm.size());
    let mut h = FNV_BASIS;
    if rank > 0 {
        (h, _) = comm.process_at_rank(rank - 1).receive::<u64>();
    }
    h = fnv(h, leaves);
    if rank + 1 < size {
        comm.process_at_rank(rank + 1).send(&h);
    }
    comm.process_at_rank(size - 1).broadcast_into(&mut h);
    h
}
