//! Repartition keeping families of sibling leaves together (p4est's
//! `partition_for_coarsening`) for D = 2 and 3, from leaves split over the ranks in several
//! ways: no family of 2^D sibling leaves is split across ranks, every boundary is within 2^D of
//! the uniform split's, the boundaries are exactly the uniform ones moved to the nearer end of
//! the family they cut (computed here by a scan of every leaf), and the leaves are unchanged.

use super::forest::{check_table, cuts, gather, slice, spiky};
use super::Check;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use orthtree::dist::{DistForest, Partition, RepartitionOptions};
use orthtree::{Cell, Connectivity, Tree};

pub const CHECKS: &[Check] = &[
    ("families::repartition_keeps_families_2d", families_2d),
    ("families::repartition_keeps_families_3d", families_3d),
];

/// Every family of sibling leaves in `leaves` (the union in Morton order): its first position.
/// A brute-force scan: 2^D consecutive leaves of one level with one parent.
fn families<const D: usize>(leaves: &[Cell<D>]) -> Vec<usize> {
    let n = 1usize << D;
    (0..leaves.len().saturating_sub(n - 1))
        .filter(|&s| {
            let run = &leaves[s..s + n];
            run[0].level() > 0
                && run
                    .iter()
                    .enumerate()
                    .all(|(i, c)| c.child_index() == i && c.parent() == run[0].parent())
        })
        .collect()
}

/// The uniform split's boundaries, each inside a family moved to its nearer end (lower on a
/// tie), from the whole list of leaves.
fn expected_targets<const D: usize>(leaves: &[Cell<D>], ranks: usize) -> Vec<u64> {
    let n = 1u64 << D;
    let starts = families(leaves);
    let mut t = Partition::uniform(leaves.len() as u64, ranks);
    for b in t[1..ranks].iter_mut() {
        if let Some(&s) = starts
            .iter()
            .find(|&&s| (s as u64) < *b && *b < s as u64 + n)
        {
            let s = s as u64;
            *b = if *b - s <= s + n - *b { s } else { s + n };
        }
    }
    t
}

/// Repartitions `tree`'s leaves, first split by `how` (see `cuts`), keeping families, and
/// checks the result against the scan; returns whether a boundary moved.
fn check<const D: usize>(
    world: &SimpleCommunicator,
    tree: &Tree<D>,
    how: usize,
    seed: u64,
) -> bool {
    let size = world.size() as usize;
    let leaves: Vec<Cell<D>> = tree.leaves().map(|(_, c)| c).collect();
    let start = cuts(leaves.len() as u64, size, how, seed);
    let forest = DistForest::new(world, slice(world, &leaves, &start)).unwrap();
    let kept = forest
        .repartition_with(world, RepartitionOptions::new().keep_families(true))
        .unwrap();
    // (iii) the leaves overall are unchanged, and the table is right
    let after = gather(world, kept.leaves());
    assert_eq!(after, leaves, "D = {D}, split {how}: the leaves moved");
    check_table(world, &kept);
    // (i) every family of leaves on one rank
    let table = kept.partition();
    let n = 1usize << D;
    for s in families(&leaves) {
        let (a, b) = (table.owner(s as u64), table.owner((s + n - 1) as u64));
        assert_eq!(a, b, "D = {D}, split {how}: family at {s} split over ranks");
    }
    // (ii) within 2^D of the uniform split at every boundary, and exactly the scan's
    let uniform = Partition::uniform(leaves.len() as u64, size);
    for (r, (&k, &u)) in table.firsts().iter().zip(&uniform).enumerate() {
        assert!(k.abs_diff(u) < n as u64, "boundary {r}: {k} against {u}");
    }
    assert_eq!(table.firsts(), expected_targets(&leaves, size), "D = {D}");
    // without the option: the uniform split
    let even = forest.repartition(world).unwrap();
    assert_eq!(even.partition().firsts(), uniform);
    table.firsts() != uniform
}

/// Forests of every kind of boundary: spiky random trees (few families), balanced ones (many),
/// uniform trees (every leaf in a family), a forest of the root alone and of its children.
fn forests<const D: usize>(depth: u8) -> Vec<Tree<D>> {
    let mut out = vec![Tree::<D>::new()];
    let mut split = Tree::<D>::new();
    split.split(orthtree::tree::NodeId::ROOT);
    out.push(split);
    let mut uniform = Tree::<D>::new();
    for _ in 0..2 {
        let leaves: Vec<_> = uniform.leaves().map(|(v, _)| v).collect();
        for v in leaves {
            uniform.split(v);
        }
    }
    out.push(uniform);
    for seed in 0..4 {
        let mut t = spiky::<D>(seed, 6 + 5 * seed as usize, depth);
        out.push(t.clone());
        t.balance(Connectivity::Corner);
        out.push(t);
    }
    out
}

fn families_2d(world: &SimpleCommunicator) {
    let mut moved = 0;
    for (i, tree) in forests::<2>(8).iter().enumerate() {
        for how in 0..4 {
            moved += check(world, tree, how, i as u64) as usize;
        }
    }
    // the forests put boundaries inside families: the option is exercised
    assert!(world.size() == 1 || moved > 0, "no boundary moved");
}

fn families_3d(world: &SimpleCommunicator) {
    let mut moved = 0;
    for (i, tree) in forests::<3>(5).iter().enumerate() {
        for how in 0..4 {
            moved += check(world, tree, how, 100 + i as u64) as usize;
        }
    }
    // the forests put boundaries inside families: the option is exercised
    assert!(world.size() == 1 || moved > 0, "no boundary moved");
}
