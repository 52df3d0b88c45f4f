//! 2:1 and weak (4:1) balance (`Tree::balance`, level by level, and `Tree::balance_chapter`, the
//! chapter's worklist algorithm, with their `is_balanced` checks) against a brute-force fixpoint,
//! in 1 to 4 dimensions, for every connectivity; the split list they return; and the generalised
//! Theorem 14.4 bound on random and adversarial trees.

use crate::common;

use common::*;
use orthtree::{tree::BalanceOptions, tree::NodeId, Cell, Connectivity, Tree};
use std::collections::HashSet;

/// Largest expected result (in leaves) still checked against the O(L^2)-per-round brute force.
const BRUTE_LIMIT: usize = 700;

/// What `check_balance` learnt.
struct Outcome {
    splits: usize,
    brute_checked: bool,
}

/// The connectivity strength, for "weaker options are implied".
fn strength(c: Connectivity) -> u8 {
    match c {
        Connectivity::Face => 0,
        Connectivity::Edge => 1,
        Connectivity::Corner => 2,
    }
}

/// The two balancing algorithms: `Tree::balance` (level by level) and `Tree::balance_chapter`
/// (the chapter's BALANCEQUADTREE with a worklist), each with its `is_balanced` check.
#[derive(Clone, Copy, Debug)]
enum Algo {
    Levels,
    Chapter,
    /// `Tree::par_balance` and `Tree::par_is_balanced` (feature `rayon`).
    #[cfg(feature = "rayon")]
    Parallel,
}

impl Algo {
    #[cfg(not(feature = "rayon"))]
    const ALL: &'static [Algo] = &[Algo::Levels, Algo::Chapter];
    #[cfg(feature = "rayon")]
    const ALL: &'static [Algo] = &[Algo::Levels, Algo::Chapter, Algo::Parallel];

    fn balance<const D: usize>(self, t: &mut Tree<D>, opts: BalanceOptions) -> Vec<NodeId> {
        match self {
            Algo::Levels => t.balance(opts),
            Algo::Chapter => t.balance_chapter(opts),
            #[cfg(feature = "rayon")]
            Algo::Parallel => t.par_balance(opts),
        }
    }

    fn is_balanced<const D: usize>(self, t: &Tree<D>, opts: BalanceOptions) -> bool {
        match self {
            Algo::Levels => t.is_balanced(opts),
            Algo::Chapter => t.is_balanced_chapter(opts),
            #[cfg(feature = "rayon")]
            Algo::Parallel => t.par_is_balanced(opts),
        }
    }
}

/// Balances a clone of `original` with `opts`, with both algorithms, and checks everything against
/// the oracles.
fn check_balance<const D: usize>(original: &Tree<D>, opts: BalanceOptions) -> Outcome {
    let children = 1usize << D;
    let before = leaf_cells(original);
    assert!(tiles_root(&before));
    let m = original.node_count();

    // The expected result: the fast oracle always, the literal brute force when small enough;
    // both are fixpoints of forced splits and must agree.
    let expected = fast_balance(&before, opts);
    let brute_checked = expected.len() <= BRUTE_LIMIT;
    let balanced_before = expected.len() == before.len();
    if brute_checked {
        assert_cells_eq(&brute_balance(&before, opts), &expected, "the two oracles");
        assert_eq!(brute_is_balanced(&before, opts), balanced_before);
    }

    let mut splits = 0;
    for &algo in Algo::ALL {
        assert_eq!(
            algo.is_balanced(original, opts),
            balanced_before,
            "{algo:?} is_balanced before balance, {opts:?}"
        );
        let mut t = original.clone();
        let split = algo.balance(&mut t, opts);
        let after = leaf_cells(&t);
        assert_cells_eq(&after, &expected, &format!("{algo:?} with {opts:?}"));
        for &a in Algo::ALL {
            assert!(a.is_balanced(&t, opts), "{a:?} is_balanced after {algo:?}");
        }
        if brute_checked {
            assert!(brute_is_balanced(&after, opts));
        }

        // The split list: one entry per split, each a leaf when split, in the order of the
        // blocks of children appended to the arena (so each entry comes after its parent's).
        let growth = t.node_count() - m;
        assert_eq!(growth % children, 0);
        assert_eq!(split.len(), growth / children);
        assert_eq!(
            t.leaf_count(),
            original.leaf_count() + split.len() * (children - 1)
        );
        let mut seen = HashSet::new();
        for (i, &v) in split.iter().enumerate() {
            assert!(seen.insert(v), "a leaf is split once");
            let block = m + i * children;
            assert!(
                v.index() < block,
                "split entry {i} existed before its split"
            );
            assert_eq!(t.child(v, 0).map(NodeId::index), Some(block));
            if v.index() < m {
                assert!(
                    original.is_leaf(v),
                    "an original internal node is never split"
                );
            }
            assert!(!t.is_leaf(v));
        }
        // Nothing of the original tree moved.
        for (id, cell) in original.pre_order() {
            assert_eq!(t.cell(id), cell);
            for c in 0..children {
                if let Some(child) = original.child(id, c) {
                    assert_eq!(t.child(id, c), Some(child));
                }
            }
        }

        // Theorem 14.4 generalised: every split cell has an original cell among its 3^D - 1
        // same-size neighbours (the chapter's charging argument, 8 in 2D), and each original
        // cell is charged at most once per neighbour, so splits <= (3^D - 1) * m for a tree of
        // m nodes.
        let bound = (3usize.pow(D as u32) - 1) * m;
        assert!(split.len() <= bound, "{} splits > {bound}", split.len());

        // Idempotent, and every weaker notion of balance holds too.
        for &a in Algo::ALL {
            assert!(a.balance(&mut t.clone(), opts).is_empty());
        }
        for weaker in all_options() {
            if strength(weaker.connectivity) <= strength(opts.connectivity)
                && weaker.max_level_difference() >= opts.max_level_difference()
            {
                assert!(t.is_balanced(weaker), "{opts:?} implies {weaker:?}");
                assert!(t.is_balanced_chapter(weaker));
            }
        }
        splits = split.len();
    }
    Outcome {
        splits,
        brute_checked,
    }
}

fn random_balance<const D: usize>(seed: u64, count: usize, max_splits: usize, max_level: u8) {
    let mut r = rng(seed);
    let mut brute = 0;
    let mut total = 0;
    let mut any_split = false;
    for i in 0..count {
        let splits = 1 + (i * 31) % max_splits;
        let bias = [0.3, 0.6, 0.9][i % 3];
        let t = random_tree::<D>(&mut r, splits, max_level, bias);
        for opts in all_options() {
            let o = check_balance(&t, opts);
            total += 1;
            brute += usize::from(o.brute_checked);
            any_split |= o.splits > 0;
        }
    }
    // guard on the generator: the brute force really ran, on trees that needed balancing
    assert!(brute * 4 >= total * 3, "{brute} of {total} brute-checked");
    assert!(any_split);
}

#[test]
fn balance_matches_brute_force_fixpoint_1d() {
    random_balance::<1>(21, 80, 30, 16);
}

#[test]
fn balance_matches_brute_force_fixpoint_2d() {
    random_balance::<2>(22, 100, 30, 8);
}

#[test]
fn balance_matches_brute_force_fixpoint_3d() {
    random_balance::<3>(23, 60, 10, 5);
}

#[test]
fn balance_matches_brute_force_fixpoint_4d() {
    random_balance::<4>(24, 30, 5, 4);
}

#[test]
fn balance_matches_brute_force_fixpoint_5d() {
    random_balance::<5>(25, 12, 4, 3);
}

/// Adversarial trees: one deep chain of splits toward a corner, the centre (deep refinement next
/// to huge leaves on every side), the middle of a side, or random points.
fn adversarial<const D: usize>(seed: u64, depth: u8) {
    let mut r = rng(seed);
    let mut trees = vec![
        corner_chain::<D>(depth),
        centre_chain::<D>(depth),
        face_chain::<D>(depth),
    ];
    for _ in 0..2 {
        trees.push(random_point_chain::<D>(&mut r, depth));
    }
    // two chains side by side: refinement meeting from both sides of the centre
    let mut two = centre_chain::<D>(depth);
    let mut v = two.child(NodeId::ROOT, (1 << D) - 1).unwrap();
    for _ in 1..depth {
        two.split(v);
        v = two.child(v, 0).unwrap();
    }
    trees.push(two);
    for (i, t) in trees.iter().enumerate() {
        let mut splits = Vec::new();
        for opts in all_options() {
            splits.push(check_balance(t, opts).splits);
        }
        if i == 0 {
            // a chain toward a corner is already 2:1 balanced: every leaf of level l touches
            // only leaves of levels l - 1 to l + 1
            assert!(splits.iter().all(|&s| s == 0));
        }
        if i == 1 && depth >= 4 {
            // toward the centre, level-1 leaves touch level-`depth` leaves
            assert!(splits.iter().all(|&s| s > 0));
        }
    }
}

#[test]
fn balance_adversarial_chains() {
    adversarial::<1>(31, Cell::<1>::MAX_LEVEL);
    adversarial::<2>(32, Cell::<2>::MAX_LEVEL);
    adversarial::<3>(33, Cell::<3>::MAX_LEVEL);
    adversarial::<4>(34, 10);
    adversarial::<5>(35, 5);
}

/// Larger random trees, checked against the fast oracle only, for the split bound over many trees.
#[test]
fn balance_bound_on_larger_random_trees() {
    fn run<const D: usize>(seed: u64, count: usize, splits: usize, max_level: u8) {
        let mut r = rng(seed);
        for _ in 0..count {
            let t = random_tree::<D>(&mut r, splits, max_level, 0.9);
            for opts in [
                BalanceOptions::new(Connectivity::Face),
                BalanceOptions::new(Connectivity::Corner),
            ] {
                check_balance(&t, opts);
            }
        }
    }
    run::<2>(41, 20, 150, 16);
    run::<3>(42, 10, 60, 10);
}

/// The chapter's 2:1 balance with a larger allowed difference (3 levels) still reaches the
/// brute-force fixpoint.
#[test]
fn balance_with_three_levels_difference() {
    let mut r = rng(51);
    for i in 0..30 {
        let t = random_tree::<2>(&mut r, 5 + i % 20, 10, 0.9);
        for conn in Connectivity::ALL {
            let opts = BalanceOptions::new(conn)
                .with_max_level_difference(3)
                .unwrap();
            check_balance(&t, opts);
        }
    }
}

/// A level difference of 0 (no two adjacent leaves of different levels: only uniform trees) and
/// one above the deepest level cannot be built; every value in between can, and reads back.
#[test]
fn balance_options_refuse_level_differences_out_of_range() {
    for conn in Connectivity::ALL {
        let base = BalanceOptions::new(conn);
        for k in [0, BalanceOptions::MAX_LEVEL_DIFFERENCE + 1, 100, u8::MAX] {
            let err = base.with_max_level_difference(k).unwrap_err();
            assert_eq!(err.value, k);
            let message = err.to_string();
            assert!(message.contains(&k.to_string()), "{message}");
            assert!(message.contains("1..=32"), "{message}");
        }
        for k in 1..=BalanceOptions::MAX_LEVEL_DIFFERENCE {
            let opts = base.with_max_level_difference(k).unwrap();
            assert_eq!((opts.connectivity, opts.max_level_difference()), (conn, k));
        }
    }
}

/// The largest level difference accepted makes every tree balanced, even the deepest chains,
/// without overflowing the level arithmetic.
#[test]
fn the_largest_level_difference_accepts_every_tree() {
    let k = BalanceOptions::MAX_LEVEL_DIFFERENCE;
    let t = centre_chain::<2>(Cell::<2>::MAX_LEVEL);
    for conn in Connectivity::ALL {
        let opts = BalanceOptions::new(conn)
            .with_max_level_difference(k)
            .unwrap();
        for &algo in Algo::ALL {
            assert!(algo.is_balanced(&t, opts), "{algo:?} with {opts:?}");
        }
        assert!(t.clone().balance(opts).is_empty());
        assert!(t.clone().balance_chapter(opts).is_empty());
    }
}

/// Balance of a single leaf, and of uniform trees, changes nothing.
#[test]
fn balanced_trees_are_left_alone() {
    let mut t = Tree::<3>::new();
    for opts in all_options() {
        assert!(t.is_balanced(opts) && t.is_balanced_chapter(opts));
        assert!(t.clone().balance(opts).is_empty());
        assert!(t.clone().balance_chapter(opts).is_empty());
    }
    t.split(NodeId::ROOT);
    for v in leaf_ids(&t) {
        t.split(v);
    }
    for opts in all_options() {
        assert!(t.is_balanced(opts) && t.is_balanced_chapter(opts));
        assert!(t.clone().balance(opts).is_empty());
        assert!(t.clone().balance_chapter(opts).is_empty());
    }
}

/// The parallel balance and test on p4est's fractal, large enough that the top levels are
/// expanded and the subtrees shared out: the same leaves as the serial balance, both tests agree
/// before and after, and one extra split deep down is caught.
#[cfg(feature = "rayon")]
#[test]
fn parallel_balance_equals_serial_on_the_fractal() {
    use orthtree::tree::fractal;
    fn run<const D: usize>(level: u8) {
        for connectivity in Connectivity::ALL {
            let opts = BalanceOptions::new(connectivity);
            let refined = fractal::fractal::<D>(level);
            assert!(!refined.is_balanced(opts) && !refined.par_is_balanced(opts));
            let (mut serial, mut parallel) = (refined.clone(), refined.clone());
            let s = serial.balance(opts);
            let p = parallel.par_balance(opts);
            assert_eq!(s.len(), p.len());
            assert!(serial
                .leaves()
                .map(|(_, c)| c)
                .eq(parallel.leaves().map(|(_, c)| c)));
            assert!(parallel.is_balanced(opts) && parallel.par_is_balanced(opts));
            // split a deepest leaf off the root's lower sides twice more, at its lower corner:
            // two levels deeper than the leaves below it
            let depth = parallel.depth();
            let (leaf, _) = parallel
                .leaves()
                .find(|(_, c)| c.level() == depth && c.coords().iter().all(|&x| x > 0))
                .unwrap();
            let first = parallel.split(leaf);
            parallel.split(first);
            assert!(!parallel.is_balanced(opts) && !parallel.par_is_balanced(opts));
        }
    }
    run::<2>(9);
    run::<3>(6);
}
