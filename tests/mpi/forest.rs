//! The distributed forest: 2:1 balance equal to the serial `Tree::balance` of the union for
//! D = 2 and 3, every connectivity and the weak balance, from leaves split over the ranks in
//! several ways (evenly, all on one rank, uneven with empty ranks); the ghost layer and its
//! mirrors against a brute-force contact search over every leaf; the partition table after
//! balance and repartition; the fractal's parts (cells below a run of the uniform level) equal
//! to the fractal refined as one tree.

use super::Check;
use mpi::datatype::PartitionMut;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use orthtree::dist::{DistForest, Partition};
use orthtree::tree::{fractal, BalanceOptions};
use orthtree::{Cell, Connectivity, Tree};
use rand::{rngs::SmallRng, Rng, SeedableRng};

pub const CHECKS: &[Check] = &[
    ("forest::balance_equals_serial_2d", balance_2d),
    ("forest::balance_equals_serial_3d", balance_3d),
    ("forest::ghost_layer_against_brute_force", ghost_layer),
    ("forest::repartition_keeps_the_leaves", repartition),
    ("forest::fractal_parts_equal_the_fractal", fractal_parts),
];

/// An unbalanced tree: the root refined toward `spikes` random cells, each at a random level up
/// to `depth`.
pub(crate) fn spiky<const D: usize>(seed: u64, spikes: usize, depth: u8) -> Tree<D> {
    let mut rng = SmallRng::seed_from_u64(seed);
    let mut tree = Tree::<D>::new();
    for _ in 0..spikes {
        let level = rng.gen_range(1..=depth);
        let coords = core::array::from_fn(|_| rng.gen_range(0..1u32 << level));
        let cell = Cell::<D>::new(level, coords).unwrap();
        let mut v = tree.locate_cell(&cell);
        while tree.level(v) < level {
            tree.split(v);
            v = tree.locate_cell(&cell);
        }
    }
    tree
}

/// The first positions of `n` leaves over `size` ranks in split `how`: 0 even, 1 all on rank 0,
/// 2 all on the last rank, 3 random cuts (some ranks empty).
pub(crate) fn cuts(n: u64, size: usize, how: usize, seed: u64) -> Vec<u64> {
    match how {
        0 => Partition::uniform(n, size),
        1 => (0..=size).map(|r| if r == 0 { 0 } else { n }).collect(),
        2 => (0..=size).map(|r| if r == size { n } else { 0 }).collect(),
        _ => {
            let mut rng = SmallRng::seed_from_u64(seed);
            let mut c: Vec<u64> = (0..size - 1).map(|_| rng.gen_range(0..=n)).collect();
            c.sort_unstable();
            std::iter::once(0).chain(c).chain([n]).collect()
        }
    }
}

/// Every rank's cells, in rank order (the union in Morton order).
pub(crate) fn gather<const D: usize>(world: &SimpleCommunicator, mine: &[Cell<D>]) -> Vec<Cell<D>> {
    let words: Vec<u64> = mine
        .iter()
        .flat_map(|c| [c.aligned_key(), c.level() as u64])
        .collect();
    let mut counts = vec![0i32; world.size() as usize];
    world.all_gather_into(&(words.len() as i32), &mut counts[..]);
    let displs: Vec<i32> = counts
        .iter()
        .scan(0, |at, &c| {
            let d = *at;
            *at += c;
            Some(d)
        })
        .collect();
    let mut all = vec![0u64; counts.iter().sum::<i32>() as usize];
    let mut part = PartitionMut::new(&mut all[..], &counts[..], &displs[..]);
    world.all_gather_varcount_into(&words[..], &mut part);
    all.chunks(2)
        .map(|w| Cell::from_aligned_key(w[0], w[1] as u8))
        .collect()
}

/// This rank's slice of `leaves` under `first`.
pub(crate) fn slice<const D: usize>(
    world: &SimpleCommunicator,
    leaves: &[Cell<D>],
    first: &[u64],
) -> Vec<Cell<D>> {
    let r = world.rank() as usize;
    leaves[first[r] as usize..first[r + 1] as usize].to_vec()
}

/// The distributed balance of the spiky trees of `seeds`, split every way, against the serial
/// balance, for every connectivity and the weak balance.
fn balance_equals_serial<const D: usize>(
    world: &SimpleCommunicator,
    seeds: &[u64],
    spikes: usize,
    depth: u8,
) {
    let size = world.size() as usize;
    for &seed in seeds {
        let tree = spiky::<D>(seed, spikes, depth);
        let leaves: Vec<Cell<D>> = tree.leaves().map(|(_, c)| c).collect();
        let mut options: Vec<BalanceOptions> =
            Connectivity::ALL.iter().map(|&c| c.into()).collect();
        options.push(BalanceOptions::new(Connectivity::Corner).weak());
        for &o in &options {
            let mut serial = tree.clone();
            serial.balance(o);
            let want: Vec<Cell<D>> = serial.leaves().map(|(_, c)| c).collect();
            for how in 0..4 {
                let first = cuts(leaves.len() as u64, size, how, seed + how as u64);
                let mut forest = DistForest::new(world, slice(world, &leaves, &first)).unwrap();
                assert_eq!(forest.len(), leaves.len() as u64);
                let stats = forest.balance(world, o).unwrap();
                let got = gather(world, forest.leaves());
                assert_eq!(
                    got.len(),
                    want.len(),
                    "seed {seed}, {o:?}, split {how}: leaf count ({} rounds)",
                    stats.rounds
                );
                assert!(got == want, "seed {seed}, {o:?}, split {how}: other leaves");
                check_table(world, &forest);
                // balancing again changes nothing and sends nothing new across
                let before = forest.clone();
                forest.balance(world, o).unwrap();
                assert_eq!(forest, before);
            }
        }
    }
}

/// The partition table agrees with every rank's leaves: counts, first positions, first keys.
pub(crate) fn check_table<const D: usize>(world: &SimpleCommunicator, forest: &DistForest<D>) {
    let p = forest.partition();
    let r = world.rank() as usize;
    assert_eq!(p.count(r), forest.leaves().len() as u64);
    let mut total = 0u64;
    world.all_reduce_into(
        &(forest.leaves().len() as u64),
        &mut total,
        mpi::collective::SystemOperation::sum(),
    );
    assert_eq!(p.len(), total);
    if let Some(c) = forest.leaves().first() {
        assert_eq!(p.first_keys()[r], c.aligned_key());
    }
    assert_eq!(forest.first_position(world), p.firsts()[r]);
    p.validate().unwrap();
}

fn balance_2d(world: &SimpleCommunicator) {
    balance_equals_serial::<2>(world, &[1, 2, 3], 40, 9);
}

fn balance_3d(world: &SimpleCommunicator) {
    balance_equals_serial::<3>(world, &[4, 5], 25, 6);
}

/// The ghost layer and mirrors of rank `me` against every pair of leaves in contact.
fn ghost_against_brute_force<const D: usize>(
    world: &SimpleCommunicator,
    forest: &DistForest<D>,
    connect: Connectivity,
) {
    let (me, size) = (world.rank() as usize, world.size() as usize);
    let all = gather(world, forest.leaves());
    let firsts = forest.partition().firsts().to_vec();
    let owner = |i: usize| firsts.partition_point(|&f| f <= i as u64) - 1;
    let touch = |a: &Cell<D>, b: &Cell<D>| a.contact(b).is_some_and(|k| connect.allows(k));
    let mine = forest.leaves();
    let ghost = forest.ghost(world, connect).unwrap();
    let want: Vec<Cell<D>> = all
        .iter()
        .enumerate()
        .filter(|&(i, g)| owner(i) != me && mine.iter().any(|o| touch(o, g)))
        .map(|(_, g)| *g)
        .collect();
    assert_eq!(ghost.ghosts(), &want[..], "{connect:?}: ghosts");
    for (i, g) in ghost.ghosts().iter().enumerate() {
        let at = all.binary_search(g).unwrap();
        assert_eq!(ghost.owner(i), owner(at));
    }
    let mut seen = vec![false; mine.len()];
    for r in 0..size {
        let theirs = &all[firsts[r] as usize..firsts[r + 1] as usize];
        let want_ghosts: Vec<Cell<D>> = want
            .iter()
            .filter(|g| theirs.contains(g))
            .copied()
            .collect();
        assert_eq!(ghost.ghosts_of(r), &want_ghosts[..]);
        let want_mirrors: Vec<usize> = if r == me {
            Vec::new()
        } else {
            (0..mine.len())
                .filter(|&i| theirs.iter().any(|g| touch(&mine[i], g)))
                .collect()
        };
        assert_eq!(
            ghost.mirrors_for(r),
            &want_mirrors[..],
            "{connect:?}: mirrors for {r}"
        );
        for &i in &want_mirrors {
            seen[i] = true;
        }
    }
    let want_all: Vec<usize> = (0..mine.len()).filter(|&i| seen[i]).collect();
    assert_eq!(ghost.mirrors(), &want_all[..]);
}

fn ghost_layer(world: &SimpleCommunicator) {
    let size = world.size() as usize;
    for (seed, how) in [(7u64, 0usize), (8, 3)] {
        let tree2 = spiky::<2>(seed, 30, 8);
        let tree3 = spiky::<3>(seed, 15, 5);
        let l2: Vec<Cell<2>> = tree2.leaves().map(|(_, c)| c).collect();
        let l3: Vec<Cell<3>> = tree3.leaves().map(|(_, c)| c).collect();
        for connect in Connectivity::ALL {
            let f2 = DistForest::new(
                world,
                slice(world, &l2, &cuts(l2.len() as u64, size, how, seed)),
            )
            .unwrap();
            ghost_against_brute_force(world, &f2, connect);
            let mut b2 = f2.clone();
            b2.balance(world, connect).unwrap();
            ghost_against_brute_force(world, &b2, connect);
            let mut f3 = DistForest::new(
                world,
                slice(world, &l3, &cuts(l3.len() as u64, size, how, seed)),
            )
            .unwrap();
            ghost_against_brute_force(world, &f3, connect);
            f3.balance(world, connect).unwrap();
            ghost_against_brute_force(world, &f3, connect);
        }
    }
}

/// Balance from all leaves on rank 0, then repartition: the same leaves, counts within one.
fn repartition(world: &SimpleCommunicator) {
    let size = world.size() as usize;
    let tree = spiky::<2>(11, 40, 9);
    let leaves: Vec<Cell<2>> = tree.leaves().map(|(_, c)| c).collect();
    let mut forest = DistForest::new(
        world,
        slice(world, &leaves, &cuts(leaves.len() as u64, size, 1, 0)),
    )
    .unwrap();
    forest.balance(world, Connectivity::Face).unwrap();
    let before = gather(world, forest.leaves());
    let even = forest.repartition(world).unwrap();
    assert_eq!(gather(world, even.leaves()), before);
    check_table(world, &even);
    let n = even.len();
    for r in 0..size {
        let c = even.partition().count(r);
        assert!(c == n / size as u64 || c == n / size as u64 + 1);
    }
    // the even forest balances and ghosts like the one it came from
    let mut again = even.clone();
    again.balance(world, Connectivity::Face).unwrap();
    assert_eq!(again, even);
    ghost_against_brute_force(world, &even, Connectivity::Corner);
}

/// Each rank's part of the fractal (a run of the uniform level's cells) is its run of the
/// serial fractal's leaves, and the parts tile the root cube.
fn fractal_parts(world: &SimpleCommunicator) {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    for level in [0u8, 3, 6] {
        let want: Vec<Cell<2>> = fractal::fractal::<2>(level)
            .leaves()
            .map(|(_, c)| c)
            .collect();
        let cells = Partition::uniform(fractal::uniform_cells::<2>(level), size);
        let part = fractal::fractal_part::<2>(level, cells[rank], cells[rank + 1]);
        let mut forest = DistForest::new(world, part).unwrap();
        assert_eq!(gather(world, forest.leaves()), want);
        let mut serial = fractal::fractal::<2>(level);
        serial.balance(Connectivity::Corner);
        forest.balance(world, Connectivity::Corner).unwrap();
        let want: Vec<Cell<2>> = serial.leaves().map(|(_, c)| c).collect();
        assert_eq!(gather(world, forest.leaves()), want);
    }
    let want: Vec<Cell<3>> = fractal::fractal::<3>(5).leaves().map(|(_, c)| c).collect();
    assert_eq!(
        fractal::fractal_part::<3>(5, 0, fractal::uniform_cells::<3>(5)),
        want
    );
    assert_eq!(fractal::fractal_leaves(3, 5), want.len() as f64);
}
