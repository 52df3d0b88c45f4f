//! Property tests of [`Tree::is_balanced`]'s two paths, the walk over the table of internal
//! nodes (`balance_check.rs`, `inner.rs`) and the dense bitmap test (`balance_check_dense.rs`), against
//! the chapter's neighbour-search check ([`Tree::is_balanced_chapter`]), on random trees with
//! splits and merges (so that blocks are reused, some before their parents), in 1 to 4
//! dimensions, every connectivity and allowed level difference 1 to 3; and on their balanced
//! versions, with and without one more split.

use super::{BalanceOptions, NodeId, Tree};
use crate::geom::Connectivity;
use proptest::prelude::*;
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

/// Random splits (deep leaves preferred, so that the tree is unbalanced) with merges of random
/// nodes whose children are all leaves mixed in (`merge_percent` of the steps).
fn random_tree<const D: usize>(seed: u64, steps: usize, merge_percent: u32) -> Tree<D> {
    let mut rng = SmallRng::seed_from_u64(seed);
    let max_level = rng.gen_range(2..=8u8);
    let mut t = Tree::<D>::new();
    for _ in 0..steps {
        if rng.gen_range(0..100) < merge_percent {
            let mergeable: Vec<NodeId> = t
                .pre_order()
                .map(|(id, _)| id)
                .filter(|&id| !t.is_leaf(id) && t.children(id).all(|c| t.is_leaf(c)))
                .collect();
            if !mergeable.is_empty() {
                let v = mergeable[rng.gen_range(0..mergeable.len())];
                t.merge(v).expect("its children are leaves");
            }
            continue;
        }
        let leaves: Vec<NodeId> = t.leaves().map(|(id, _)| id).collect();
        let deepest = leaves.iter().map(|&l| t.level(l)).max().unwrap_or(0);
        let pick = if rng.gen_bool(0.5) {
            *leaves.iter().rfind(|&&l| t.level(l) == deepest).unwrap()
        } else {
            leaves[rng.gen_range(0..leaves.len())]
        };
        if t.level(pick) < max_level {
            t.split(pick);
        }
    }
    t
}

/// Every path agrees with the chapter's check on `t`; returns how many of the tests the dense
/// path took.
fn paths_agree<const D: usize>(t: &Tree<D>, opts: BalanceOptions) -> usize {
    let expected = t.is_balanced_chapter(opts);
    assert_eq!(t.is_balanced(opts), expected, "is_balanced, {opts:?}");
    assert_eq!(t.is_balanced_walk(opts), expected, "the walk, {opts:?}");
    #[cfg(feature = "rayon")]
    assert_eq!(
        t.par_is_balanced(opts),
        expected,
        "par_is_balanced, {opts:?}"
    );
    match t.is_balanced_dense(opts) {
        Some(dense) => {
            assert_eq!(dense, expected, "the dense test, {opts:?}");
            1
        }
        None => 0,
    }
}

/// The checks on a random tree, its balanced versions and one more split of each.
fn check<const D: usize>(seed: u64, steps: usize, merge_percent: u32) -> usize {
    let t = random_tree::<D>(seed, steps, merge_percent);
    let mut dense = 0;
    for connectivity in Connectivity::ALL {
        for max_level_difference in 1..=3 {
            let opts = BalanceOptions::new(connectivity)
                .with_max_level_difference(max_level_difference)
                .unwrap();
            dense += paths_agree(&t, opts);
            let mut b = t.clone();
            b.balance(opts);
            assert!(b.is_balanced_chapter(opts));
            dense += paths_agree(&b, opts);
            let leaves: Vec<NodeId> = b.leaves().map(|(id, _)| id).collect();
            let deep = leaves
                .iter()
                .copied()
                .max_by_key(|&l| (b.level(l), l.index()));
            if let Some(leaf) = deep.filter(|&l| b.level(l) < 9) {
                b.split(leaf);
                dense += paths_agree(&b, opts);
            }
        }
    }
    dense
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn paths_agree_1d(seed in any::<u64>(), steps in 0usize..60, merges in 0u32..40) {
        check::<1>(seed, steps, merges);
    }

    #[test]
    fn paths_agree_2d(seed in any::<u64>(), steps in 0usize..80, merges in 0u32..40) {
        check::<2>(seed, steps, merges);
    }

    #[test]
    fn paths_agree_3d(seed in any::<u64>(), steps in 0usize..40, merges in 0u32..40) {
        check::<3>(seed, steps, merges);
    }

    #[test]
    fn paths_agree_4d(seed in any::<u64>(), steps in 0usize..12, merges in 0u32..40) {
        check::<4>(seed, steps, merges);
    }
}

/// Both paths are taken: the dense one on shallow bushy trees, the walk on deep thin ones and
/// where merges put a block before its parent's.
#[test]
fn both_paths_are_exercised() {
    let (mut dense, mut total) = (0, 0);
    for seed in 0..40 {
        dense += check::<2>(seed, 60, if seed % 2 == 0 { 0 } else { 30 });
        total += 3 * 3 * 3;
    }
    assert!(dense > total / 10, "dense path taken {dense} of {total}");
    assert!(
        dense < total * 9 / 10,
        "dense path taken {dense} of {total}"
    );
}
