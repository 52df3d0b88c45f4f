//! The partition table and repartition: uniform splits, table invariants and look-ups
//! against a linear scan, repartition by counts and by weights against the definition
//! computed from every rank's input.

use super::Check;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use orthtree::dist::{DistError, Partition};
use rand::{rngs::SmallRng, Rng, SeedableRng};

pub const CHECKS: &[Check] = &[
    ("partition::uniform_counts", uniform_counts),
    ("partition::table_lookups", table_lookups),
    ("partition::bad_tables", bad_tables),
    ("partition::repartition_by_counts", repartition_by_counts),
    ("partition::repartition_by_weights", repartition_by_weights),
    ("partition::bad_weights", bad_weights),
];

/// Rank r's element count in case `seed` (known to every rank): some ranks empty.
fn count_of(seed: u64, r: usize) -> usize {
    let mut rng = SmallRng::seed_from_u64(seed * 1000 + r as u64);
    if rng.gen_bool(0.3) {
        0
    } else {
        rng.gen_range(0..200)
    }
}

fn uniform_counts(_: &SimpleCommunicator) {
    for len in [0u64, 1, 2, 7, 100, 1001] {
        for ranks in 1..=9 {
            let f = Partition::uniform(len, ranks);
            assert_eq!((f.len(), f[0], f[ranks]), (ranks + 1, 0, len));
            let counts: Vec<u64> = f.windows(2).map(|w| w[1] - w[0]).collect();
            let (lo, hi) = (counts.iter().min().unwrap(), counts.iter().max().unwrap());
            assert!(hi - lo <= 1, "{len} over {ranks}: {counts:?}");
        }
    }
}

fn table_lookups(world: &SimpleCommunicator) {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    for seed in 0..20u64 {
        let counts: Vec<usize> = (0..size).map(|r| count_of(seed, r)).collect();
        // Keys: element i of the union has key i / 3 (copies straddle rank boundaries).
        let before: usize = counts[..rank].iter().sum();
        let first_key = (counts[rank] > 0).then_some((before / 3) as u64);
        let p = Partition::gather(world, counts[rank], first_key).unwrap();
        p.validate().unwrap();
        let total: usize = counts.iter().sum();
        assert_eq!((p.ranks(), p.len()), (size, total as u64));
        let owner_of = |slot: usize| {
            let mut at = 0;
            (0..size).find(|&r| {
                at += counts[r];
                slot < at
            })
        };
        for slot in 0..total + 2 {
            assert_eq!(p.owner(slot as u64), owner_of(slot), "slot {slot}");
        }
        for key in 0..(total / 3 + 2) as u64 {
            let holders: Vec<usize> = (0..size)
                .filter(|&r| {
                    let s: usize = counts[..r].iter().sum();
                    (s..s + counts[r]).any(|i| (i / 3) as u64 == key)
                })
                .collect();
            let found = p.ranks_of_key(key);
            for h in &holders {
                assert!(found.contains(h), "key {key}: rank {h} not in {found:?}");
            }
            // The table cannot tell whether the rank before a boundary holds copies of the
            // next rank's first key: only the first rank of the range may be extra.
            assert!(
                (found.start + 1..found.end).all(|r| counts[r] == 0 || holders.contains(&r)),
                "key {key}: {found:?} for holders {holders:?}"
            );
        }
    }
}

fn bad_tables(_: &SimpleCommunicator) {
    assert_eq!(
        Partition::from_parts(vec![0, 5, 3], vec![0, 1]),
        Err(DistError::InvalidTargets { index: 2 })
    );
    assert_eq!(
        Partition::from_parts(vec![1, 5], vec![0]),
        Err(DistError::InvalidTargets { index: 0 })
    );
    assert_eq!(
        Partition::from_parts(vec![0, 1, 2], vec![4, 3]),
        Err(DistError::InvalidTargets { index: 4 })
    );
    assert!(Partition::from_parts(vec![0, 1], vec![0, 0]).is_err());
}

fn repartition_by_counts(world: &SimpleCommunicator) {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    for seed in 0..20u64 {
        let counts: Vec<usize> = (0..size).map(|r| count_of(seed, r)).collect();
        let before: u64 = counts[..rank].iter().sum::<usize>() as u64;
        let mine: Vec<u64> = (before..before + counts[rank] as u64).collect();
        let p = Partition::gather(world, mine.len(), mine.first().copied()).unwrap();
        let total = p.len();
        let targets = Partition::uniform(total, size);
        let (q, moved) = p.repartition(world, &mine, &targets, |&v| v).unwrap();
        q.validate().unwrap();
        assert_eq!(q.firsts(), &targets[..]);
        let want: Vec<u64> = (targets[rank]..targets[rank + 1]).collect();
        assert_eq!(moved, want, "seed {seed}");
        // Back to where they were.
        let (back, original) = q.repartition(world, &moved, p.firsts(), |&v| v).unwrap();
        assert_eq!((back.firsts(), original), (p.firsts(), mine));
    }
}

fn repartition_by_weights(world: &SimpleCommunicator) {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    for seed in 0..20u64 {
        let counts: Vec<usize> = (0..size).map(|r| count_of(seed, r)).collect();
        // Integer weights (sums exact in f64), every rank's known to all.
        let weights_of = |r: usize| -> Vec<f64> {
            let mut rng = SmallRng::seed_from_u64(seed * 77 + r as u64);
            (0..counts[r]).map(|_| rng.gen_range(0..5) as f64).collect()
        };
        let all: Vec<f64> = (0..size).flat_map(weights_of).collect();
        let before: u64 = counts[..rank].iter().sum::<usize>() as u64;
        let mine: Vec<u64> = (before..before + counts[rank] as u64).collect();
        let p = Partition::gather(world, mine.len(), mine.first().copied()).unwrap();
        let targets = p.weighted(world, &weights_of(rank)).unwrap();
        // The definition: rank t starts at the first element whose preceding weight reaches
        // W t / P.
        let total: f64 = all.iter().sum();
        let want: Vec<u64> = if total == 0.0 {
            Partition::uniform(all.len() as u64, size)
        } else {
            (0..=size)
                .map(|t| {
                    if t == size {
                        return all.len() as u64;
                    }
                    let start = total * t as f64 / size as f64;
                    let mut acc = 0.0;
                    all.iter()
                        .take_while(|&&w| {
                            let below = acc < start;
                            acc += w;
                            below
                        })
                        .count() as u64
                })
                .collect()
        };
        assert_eq!(targets, want, "seed {seed}");
        let (q, moved) = p.repartition(world, &mine, &targets, |&v| v).unwrap();
        q.validate().unwrap();
        assert_eq!(moved, (want[rank]..want[rank + 1]).collect::<Vec<u64>>());
        // Each rank's weight is at most the ideal share plus the largest weight.
        let share: f64 = all[want[rank] as usize..want[rank + 1] as usize]
            .iter()
            .sum();
        assert!(
            share <= total / size as f64 + 4.0,
            "seed {seed}: {share} of {total}"
        );
    }
}

fn bad_weights(world: &SimpleCommunicator) {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    let mine: Vec<u64> = vec![0; 10];
    let p = Partition::gather(world, mine.len(), Some(0)).unwrap();
    let mut w = vec![1.0; 10];
    if rank == size - 1 {
        w[4] = f64::NAN;
    }
    match p.weighted(world, &w) {
        Err(DistError::InvalidWeight {
            rank: r,
            index: 4,
            value,
        }) => {
            assert_eq!((r, value.get().is_nan()), (size - 1, true));
        }
        other => panic!("rank {rank}: {other:?}"),
    }
    let short = if rank == 0 {
        vec![1.0; 3]
    } else {
        vec![1.0; 10]
    };
    assert_eq!(
        p.weighted(world, &short),
        Err(DistError::WeightCount {
            rank: 0,
            weights: 3,
            elements: 10
        })
    );
}
