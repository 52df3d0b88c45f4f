//! Bad leaves on one rank are the same typed error on every rank, with no rank left waiting:
//! leaves out of Morton order, overlapping, leaving a gap, ranks' runs overlapping or in the
//! wrong order, the root cube not covered; and balance options that differ between ranks.

use super::Check;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use orthtree::dist::{DistError, DistForest, LeafProblem};
use orthtree::{Cell, Connectivity};

pub const CHECKS: &[Check] = &[
    ("forest_bad::bad_leaves_on_one_rank", bad_leaves),
    ("forest_bad::options_differ", options_differ),
];

/// The 4^3 cells of level 3 in Morton order, split evenly over the ranks.
fn level3(world: &SimpleCommunicator) -> (Vec<Cell<2>>, Vec<Cell<2>>) {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    let all: Vec<Cell<2>> = (0..64u64)
        .map(|i| Cell::from_aligned_key(i << (2 * (Cell::<2>::MAX_LEVEL - 3) as usize), 3))
        .collect();
    let first = orthtree::dist::Partition::uniform(64, size);
    let mine = all[first[rank] as usize..first[rank + 1] as usize].to_vec();
    (all, mine)
}

fn expect(
    world: &SimpleCommunicator,
    leaves: Vec<Cell<2>>,
    rank: usize,
    index: usize,
    problem: LeafProblem,
) {
    let got = DistForest::new(world, leaves).unwrap_err();
    assert_eq!(
        got,
        DistError::Leaves {
            rank,
            index,
            problem
        },
        "on rank {}",
        world.rank()
    );
}

fn bad_leaves(world: &SimpleCommunicator) {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    let (all, mine) = level3(world);
    let bad = size - 1;
    // two leaves swapped on the last rank (its run has 64 / size >= 16 leaves)
    let mut m = mine.clone();
    if rank == bad {
        m.swap(3, 4);
    }
    // leaf 4 now starts after leaf 3 ends: a gap there first
    expect(world, m, bad, 3, LeafProblem::Gap);
    // a leaf dropped on rank 0, and another on the last rank: the lowest rank is named
    let mut m = mine.clone();
    if rank == 0 || rank == bad {
        m.remove(5);
    }
    expect(world, m, 0, 5, LeafProblem::Gap);
    // a leaf that is a first child replaced by its parent: overlaps the next one
    let mut m = mine.clone();
    let start = orthtree::dist::Partition::uniform(64, size)[bad] as usize;
    let i = match (4 - start % 4) % 4 {
        0 => 4,
        i => i,
    };
    if rank == bad {
        m[i] = m[i].parent().unwrap();
    }
    expect(world, m, bad, i + 1, LeafProblem::Overlap);
    // the last leaf missing: the root cube is not covered after the last rank's run
    let mut m = mine.clone();
    if rank == bad {
        m.pop();
    }
    let bad_len = 64 - start - 1;
    expect(world, m, bad, bad_len, LeafProblem::Gap);
    if size > 1 {
        // rank 1 also holds rank 0's last leaf: the runs overlap
        let mut m = mine.clone();
        let first0 = orthtree::dist::Partition::uniform(64, size)[1] as usize;
        if rank == 1 {
            m.insert(0, all[first0 - 1]);
        }
        expect(world, m, 1, 0, LeafProblem::Overlap);
        // the ranks' runs in the wrong order
        let m = if rank == 0 {
            level3_of(world, size - 1)
        } else if rank == size - 1 {
            level3_of(world, 0)
        } else {
            mine.clone()
        };
        let got = DistForest::new(world, m).unwrap_err();
        assert!(
            matches!(
                got,
                DistError::Leaves {
                    rank: 0,
                    index: 0,
                    ..
                } | DistError::Leaves {
                    rank: 1,
                    index: 0,
                    ..
                }
            ),
            "{got:?}"
        );
    }
    // every rank empty: nothing covers the root cube
    expect(world, Vec::new(), 0, 0, LeafProblem::Gap);
    // and a good forest still works afterwards on every rank
    let forest = DistForest::new(world, mine).unwrap();
    assert_eq!(forest.len(), 64);
}

/// Rank `r`'s even share of the level-3 cells.
fn level3_of(world: &SimpleCommunicator, r: usize) -> Vec<Cell<2>> {
    let (all, _) = level3(world);
    let first = orthtree::dist::Partition::uniform(64, world.size() as usize);
    all[first[r] as usize..first[r + 1] as usize].to_vec()
}

fn options_differ(world: &SimpleCommunicator) {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    let (_, mine) = level3(world);
    let mut forest = DistForest::new(world, mine).unwrap();
    let c = if rank == size - 1 && size > 1 {
        Connectivity::Corner
    } else {
        Connectivity::Face
    };
    let got = forest.balance(world, c);
    if size > 1 {
        assert_eq!(
            got.unwrap_err(),
            DistError::SettingsDiffer { rank: size - 1 }
        );
        assert_eq!(
            forest.ghost(world, c).unwrap_err(),
            DistError::SettingsDiffer { rank: size - 1 }
        );
    } else {
        assert!(got.is_ok());
    }
    assert_eq!(forest.len(), 64);
}
