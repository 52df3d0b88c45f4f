//! `Tree::balance` (by levels) against the chapter's reference balance on random trees in 1 to 4
//! dimensions.

use orthtree::tree::{BalanceOptions, NodeId, Tree};
use orthtree::Connectivity;
use rand::{Rng, SeedableRng};

fn random_tree<const D: usize>(rng: &mut impl Rng, splits: usize, max_level: u8) -> Tree<D> {
    let mut t = Tree::<D>::new();
    for _ in 0..splits {
        let leaves: Vec<NodeId> = t.leaves().map(|(id, _)| id).collect();
        // prefer deep leaves so that the trees are unbalanced
        let deepest = leaves.iter().map(|&l| t.level(l)).max().unwrap_or(0);
        let pick = if rng.gen_bool(0.6) {
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

fn agrees_with_the_chapters_algorithm<const D: usize>(seed: u64, splits: usize) {
    let mut rng = rand::rngs::SmallRng::seed_from_u64(seed);
    for _ in 0..40 {
        let t = random_tree::<D>(&mut rng, splits, 7);
        for conn in Connectivity::ALL {
            for opts in [BalanceOptions::new(conn), BalanceOptions::new(conn).weak()] {
                assert_eq!(t.is_balanced(opts), t.is_balanced_chapter(opts));
                let (mut a, mut b) = (t.clone(), t.clone());
                let sa = a.balance(opts);
                let sb = b.balance_chapter(opts);
                assert_eq!(sa.len(), sb.len());
                let la: Vec<_> = a.leaves().map(|(_, c)| c).collect();
                let lb: Vec<_> = b.leaves().map(|(_, c)| c).collect();
                assert_eq!(la, lb);
                assert!(a.is_balanced(opts) && a.is_balanced_chapter(opts));
            }
        }
    }
}

#[test]
fn level_balance_equals_the_chapters_balance() {
    agrees_with_the_chapters_algorithm::<1>(1, 12);
    agrees_with_the_chapters_algorithm::<2>(2, 14);
    agrees_with_the_chapters_algorithm::<3>(3, 8);
    agrees_with_the_chapters_algorithm::<4>(4, 5);
}
