//! `Tree::split_balanced`: replaying random splits with it builds the tree `balance` makes.

use orthtree::tree::{BalanceOptions, Tree};
use orthtree::Connectivity;
use rand::{Rng, SeedableRng};

/// Replaying random splits with `split_balanced` gives `balance` of the plain tree.
fn replay<const D: usize>(seed: u64) {
    let mut rng = rand::rngs::SmallRng::seed_from_u64(seed);
    for _ in 0..30 {
        let mut plain = Tree::<D>::new();
        let mut cells = Vec::new();
        for _ in 0..rng.gen_range(1..12) {
            let leaves: Vec<_> = plain.leaves().collect();
            let (id, cell) = leaves[rng.gen_range(0..leaves.len())];
            if cell.level() < 6 {
                plain.split(id);
                cells.push(cell);
            }
        }
        for conn in Connectivity::ALL {
            for opts in [BalanceOptions::new(conn), BalanceOptions::new(conn).weak()] {
                let mut expected = plain.clone();
                expected.balance(opts);
                let mut built = Tree::<D>::new();
                for cell in &cells {
                    let id = built.locate_cell(cell);
                    if built.level(id) == cell.level() && built.is_leaf(id) {
                        built.split_balanced(id, opts, |_, _| {});
                    }
                    assert!(built.is_balanced(opts));
                }
                let a: Vec<_> = built.leaves().map(|(_, c)| c).collect();
                let b: Vec<_> = expected.leaves().map(|(_, c)| c).collect();
                assert_eq!(a, b);
            }
        }
    }
}

#[test]
fn balanced_splits_build_the_balanced_tree() {
    replay::<1>(1);
    replay::<2>(2);
    replay::<3>(3);
}
