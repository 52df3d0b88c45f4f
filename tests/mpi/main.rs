//! The distributed point tree, the distributed forest and their partition, run under `mpirun
//! -np P` (P = 1 to 4 in CI): partition invariants, the distributed tree and its batch queries
//! against a single-process tree over the union of every rank's input, the forest's balance
//! against the serial balance and its ghost layer against brute force, repartition keeping
//! sibling families together against a scan, and bad input on one rank.
//!
//! A plain `main` (no test harness): every rank runs every check in the same order, since
//! each one is collective. A failed check panics, and the panic hook aborts the whole job, so
//! no rank is left waiting in a collective. Rank 0 prints one line per check and the closing
//! count.

mod bad_input;
mod families;
mod forest;
mod forest_bad;
mod partition;
mod points;

use mpi::topology::SimpleCommunicator;
use mpi::traits::*;

/// A named check, run by every rank.
type Check = (&'static str, fn(&SimpleCommunicator));

fn main() {
    let universe = mpi::initialize().expect("MPI initialises once");
    let world = universe.world();
    let rank = world.rank();
    let default_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        default_hook(info);
        eprintln!("rank {rank}: a check failed; aborting every rank");
        SimpleCommunicator::world().abort(1);
    }));
    let filter: Option<String> = std::env::args().skip(1).find(|a| !a.starts_with('-'));
    let checks: Vec<Check> = partition::CHECKS
        .iter()
        .chain(points::CHECKS)
        .chain(bad_input::CHECKS)
        .chain(forest::CHECKS)
        .chain(forest_bad::CHECKS)
        .chain(families::CHECKS)
        .copied()
        .filter(|(name, _)| filter.as_ref().is_none_or(|f| name.contains(f.as_str())))
        .collect();
    for (name, check) in &checks {
        check(&world);
        world.barrier();
        if rank == 0 {
            println!("test {name} ... ok (np {})", world.size());
        }
    }
    if rank == 0 {
        println!("{} passed, 0 failed", checks.len());
    }
}
