//! Every public operation of [`Tree`] in every dimension the crate supports, D = 1 to 8, on small
//! random trees: splits and merges (with [`Tree::validate`] after each), traversals, cell
//! location, neighbours in every direction, balance for every connectivity and level difference
//! (serial, reference, parallel and incremental) and the balance tests, each against brute force
//! over cell coordinates.
//!
//! One generic check per operation, instantiated for each D by `every_dimension!`. Trees stay
//! small (a split in 8-D makes 256 children) but reach depth 3 and more, where a child counter
//! in a `u8` (2^8 = 256 children) or a mask `1u8 << D` used to break the 8-D balance test and
//! balance.

use crate::common;

use common::*;
use orthtree::{geom::Direction, tree::BalanceOptions, tree::NodeId, Cell, Connectivity, Tree};
use rand::rngs::SmallRng;
use rand::Rng;
use std::collections::BTreeSet;

/// Splits `splits` random leaves below `max_level`, half of them children of the previous split
/// (so the tree gets deep), validating after each split.
fn grow<const D: usize>(rng: &mut SmallRng, t: &mut Tree<D>, splits: usize, max_level: u8) {
    let mut last: Option<NodeId> = None;
    for _ in 0..splits {
        let pick = match last {
            Some(v) if rng.gen_bool(0.5) && t.level(v) + 1 < max_level => {
                t.child(v, rng.gen_range(0..1usize << D)).unwrap()
            }
            _ => {
                let leaves: Vec<NodeId> = leaf_ids(t)
                    .into_iter()
                    .filter(|&v| t.level(v) < max_level)
                    .collect();
                leaves[rng.gen_range(0..leaves.len())]
            }
        };
        if t.is_leaf(pick) {
            t.split(pick);
            last = Some(pick);
            t.validate().unwrap();
        }
    }
}

/// A small random tree of depth at least 3: a chain of splits to level 3, then random splits,
/// none from 6-D on. From 5-D on, the chain's level-2 cell lies on the inner side of its parent
/// along two axes only (one from 6-D on), so that a corner balance splits 3 level-1 leaves (or
/// 1), not up to 255: the corner balance of a random 8-D tree of depth 3 easily has 70000
/// leaves, too many for the brute-force fixpoint over 6560 directions.
fn sample_tree<const D: usize>(rng: &mut SmallRng) -> Tree<D> {
    let mut t = if D >= 5 {
        let c = rng.gen_range(0..1usize << D);
        let mut inner = 0usize;
        while inner.count_ones() < if D >= 6 { 1 } else { 2 } {
            inner |= 1 << rng.gen_range(0..D);
        }
        chain_tree::<D>(3, |level| [c, c ^ inner][level as usize])
    } else {
        random_point_chain::<D>(rng, 3)
    };
    t.validate().unwrap();
    let splits = if D >= 6 { 0 } else { 12 / D };
    grow(rng, &mut t, splits, 5.min(Cell::<D>::MAX_LEVEL));
    assert!(t.depth() >= 3);
    t
}

/// Directions to test from a node: every one up to 4-D, else every face direction and a random
/// sample of the others (3^8 - 1 = 6560 in 8-D).
fn some_directions<const D: usize>(rng: &mut SmallRng) -> Vec<Direction> {
    let all = directions::<D>(Connectivity::Corner);
    if D <= 4 {
        return all;
    }
    all.into_iter()
        .filter(|d| d.axes_moved() == 1 || rng.gen_bool(0.02))
        .collect()
}

/// Some nodes to test from: all of them in small trees, else a random sample with the root and
/// the deepest node.
fn some_nodes<const D: usize>(rng: &mut SmallRng, t: &Tree<D>) -> Vec<(NodeId, Cell<D>)> {
    let nodes: Vec<(NodeId, Cell<D>)> = t.pre_order().collect();
    if nodes.len() <= 40 {
        return nodes;
    }
    let deepest = *nodes.iter().max_by_key(|(_, c)| c.level()).unwrap();
    let mut pick = vec![nodes[0], deepest];
    pick.extend((0..30).map(|_| nodes[rng.gen_range(0..nodes.len())]));
    pick
}

/// The deepest node whose cell contains `target`: the answer of both `locate_cell` and, for the
/// shifted cell, `neighbor` (the nodes containing a cell form a chain).
fn brute_deepest<const D: usize>(nodes: &[(NodeId, Cell<D>)], target: &Cell<D>) -> NodeId {
    nodes
        .iter()
        .filter(|(_, c)| contains(c, target))
        .max_by_key(|(_, c)| c.level())
        .map(|&(id, _)| id)
        .expect("the root contains every cell")
}

/// The leaves touching `cell` across the side, edge or corner `d`: those that hold points just
/// beyond it in direction `d`, that is, on every axis `d` moves up (down) along their interval
/// holds a stretch just above (below) `cell`'s, and on the others their intervals overlap.
fn brute_leaf_neighbors<const D: usize>(
    leaves: &[(NodeId, Cell<D>)],
    cell: &Cell<D>,
    d: Direction,
) -> Vec<NodeId> {
    leaves
        .iter()
        .filter(|(_, m)| {
            (0..D).all(|a| {
                let ((lo, hi), (mlo, mhi)) = (interval(cell, a), interval(m, a));
                match d.component(a) {
                    1 => mlo <= hi && hi < mhi,
                    -1 => mlo < lo && lo <= mhi,
                    _ => lo.max(mlo) < hi.min(mhi),
                }
            })
        })
        .map(|&(id, _)| id)
        .collect()
}

/// Traversals, cells, levels, parents and `locate_cell` against the leaves' coordinates.
fn check_topology<const D: usize>(rng: &mut SmallRng, t: &Tree<D>) {
    t.validate().unwrap();
    let nodes: Vec<(NodeId, Cell<D>)> = t.pre_order().collect();
    let leaves: Vec<Cell<D>> = t.leaves().map(|(_, c)| c).collect();
    assert_eq!(leaves.len(), t.leaf_count());
    assert!(tiles_root(&leaves), "the leaves tile the root");
    assert!(leaves.windows(2).all(|w| w[0] < w[1]), "Morton order");
    assert_eq!(nodes.iter().map(|(_, c)| c.level()).max(), Some(t.depth()));
    for &(id, cell) in &nodes {
        assert_eq!((t.cell(id), t.level(id)), (cell, cell.level()));
        assert_eq!(t.locate_cell(&cell), id);
        if let Some(p) = t.parent(id) {
            assert_eq!(t.child(p, t.child_index(id)), Some(id));
            assert_eq!(t.cell(p), cell.parent().unwrap());
        }
        assert_eq!(t.children(id).len(), if t.is_leaf(id) { 0 } else { 1 << D });
        let below: Vec<Cell<D>> = t.walk_from(id, true).map(|(_, c)| c).collect();
        let want: Vec<Cell<D>> = leaves
            .iter()
            .copied()
            .filter(|l| contains(&cell, l))
            .collect();
        assert_eq!(below, want);
    }
    for _ in 0..20 {
        let level = rng.gen_range(0..=Cell::<D>::MAX_LEVEL);
        let coords = core::array::from_fn(|_| rng.gen_range(0..1u64 << level) as u32);
        let target = Cell::new(level, coords).unwrap();
        assert_eq!(t.locate_cell(&target), brute_deepest(&nodes, &target));
    }
}

/// `neighbor`, `leaf_neighbors` and `adjacent_leaves` against brute force.
fn check_neighbors<const D: usize>(rng: &mut SmallRng, t: &Tree<D>) {
    let nodes: Vec<(NodeId, Cell<D>)> = t.pre_order().collect();
    let leaves: Vec<(NodeId, Cell<D>)> = t.leaves().collect();
    let dirs = some_directions::<D>(rng);
    for (id, cell) in some_nodes(rng, t) {
        for &d in &dirs {
            let want = shifted(&cell, d.offset::<D>()).map(|target| brute_deepest(&nodes, &target));
            assert_eq!(t.neighbor(id, d), want, "D = {D}, {cell:?} toward {d:?}");
            let mut got = Vec::new();
            t.leaf_neighbors(id, d, &mut got);
            assert_eq!(
                got,
                brute_leaf_neighbors(&leaves, &cell, d),
                "{cell:?} {d:?}"
            );
        }
        for conn in Connectivity::ALL {
            let mut got = Vec::new();
            t.adjacent_leaves(id, conn, &mut got);
            let got: BTreeSet<NodeId> = got.into_iter().collect();
            let want: BTreeSet<NodeId> = leaves
                .iter()
                .filter(|(_, m)| contact(&cell, m).is_some_and(|k| allowed(conn, k)))
                .map(|&(v, _)| v)
                .collect();
            assert_eq!(
                got, want,
                "D = {D}, leaves adjacent to {cell:?} under {conn:?}"
            );
        }
    }
}

/// Every balance option, including a level difference of 3.
fn options() -> Vec<BalanceOptions> {
    let mut v = all_options();
    v.push(
        BalanceOptions::new(Connectivity::Face)
            .with_max_level_difference(3)
            .unwrap(),
    );
    v
}

/// A balance of the crate, returning the leaves it split.
type Balancer<const D: usize> = fn(&mut Tree<D>, BalanceOptions) -> Vec<NodeId>;

/// The balance tests and every balance against the brute-force fixpoint, and the incremental
/// balanced splits.
fn check_balance<const D: usize>(t: &Tree<D>) {
    let leaves = leaf_cells(t);
    for opts in options() {
        let want = fast_balance(&leaves, opts);
        let balanced = want == leaves;
        if leaves.len() <= 600 {
            assert_eq!(brute_is_balanced(&leaves, opts), balanced);
        }
        assert_eq!(t.is_balanced(opts), balanced, "D = {D}, {opts:?}");
        assert_eq!(t.is_balanced_chapter(opts), balanced, "D = {D}, {opts:?}");
        #[cfg(feature = "rayon")]
        assert_eq!(t.par_is_balanced(opts), balanced, "D = {D}, {opts:?}");
        let runs: [(&str, Balancer<D>); 2 + cfg!(feature = "rayon") as usize] = [
            ("balance", |t, o| t.balance(o)),
            ("balance_chapter", |t, o| t.balance_chapter(o)),
            #[cfg(feature = "rayon")]
            ("par_balance", |t, o| t.par_balance(o)),
        ];
        for (name, run) in runs {
            let mut b = t.clone();
            let split = run(&mut b, opts);
            b.validate().unwrap();
            let got = leaf_cells(&b);
            assert_cells_eq(&got, &want, &format!("D = {D}, {name} with {opts:?}"));
            assert_eq!(got.len(), leaves.len() + split.len() * ((1 << D) - 1));
            assert!(b.is_balanced(opts) && b.is_balanced_chapter(opts));
        }
    }
}

/// Replays the splits of `t` (parents first) with `split_balanced`: the balanced tree of `t`.
fn check_split_balanced<const D: usize>(t: &Tree<D>) {
    let internal: Vec<Cell<D>> = t
        .pre_order()
        .filter(|&(id, _)| !t.is_leaf(id))
        .map(|(_, c)| c)
        .collect();
    for opts in options() {
        let mut built = Tree::<D>::new();
        for cell in &internal {
            let id = built.locate_cell(cell);
            if built.level(id) == cell.level() && built.is_leaf(id) {
                built.split_balanced(id, opts, |_, _| {});
                built.validate().unwrap();
                assert!(built.is_balanced(opts));
            }
        }
        let want = fast_balance(&leaf_cells(t), opts);
        assert_cells_eq(
            &leaf_cells(&built),
            &want,
            &format!("split_balanced {opts:?}"),
        );
    }
}

/// Merges random subtrees (validating), checks the leaves, then splits again into freed blocks.
fn check_merge<const D: usize>(rng: &mut SmallRng, t: &Tree<D>) {
    let mut t = t.clone();
    for _ in 0..3 {
        let internal: Vec<(NodeId, Cell<D>)> =
            t.pre_order().filter(|&(id, _)| !t.is_leaf(id)).collect();
        let (v, cell) = internal[rng.gen_range(0..internal.len())];
        let before = leaf_cells(&t);
        let blocks = t.merge_subtree(v);
        assert!(blocks >= 1);
        t.validate().unwrap();
        let mut want: Vec<Cell<D>> = before.into_iter().filter(|l| !contains(&cell, l)).collect();
        want.push(cell);
        want.sort();
        assert_eq!(leaf_cells(&t), want);
        assert!(t.is_leaf(v) && t.merge(v).is_err());
        let slots = t.node_count();
        let leaves = leaf_ids(&t);
        let pick = leaves[rng.gen_range(0..leaves.len())];
        if t.level(pick) < Cell::<D>::MAX_LEVEL {
            t.split(pick);
            assert_eq!(t.node_count(), slots, "a freed block is reused");
            t.validate().unwrap();
        }
        check_balance_consistency(&t);
    }
}

/// After merges (freed blocks, ids out of order) the fast test agrees with the reference one.
fn check_balance_consistency<const D: usize>(t: &Tree<D>) {
    for opts in all_options() {
        assert_eq!(t.is_balanced(opts), t.is_balanced_chapter(opts));
    }
}

/// A chain down to the deepest level: splitting stops there with an error; the corner chain is
/// balanced, the centre chain is not, whatever the dimension.
fn check_deepest_level<const D: usize>() {
    let t = corner_chain::<D>(Cell::<D>::MAX_LEVEL);
    t.validate().unwrap();
    let deepest = t
        .leaves()
        .map(|(id, _)| id)
        .find(|&v| t.level(v) == Cell::<D>::MAX_LEVEL);
    let deepest = deepest.unwrap();
    assert!(t.clone().try_split(deepest).is_err());
    for opts in all_options() {
        assert!(t.is_balanced(opts), "D = {D}: a corner chain is balanced");
    }
    let centre = centre_chain::<D>(3.min(Cell::<D>::MAX_LEVEL));
    if D >= 2 {
        assert!(!centre.is_balanced(Connectivity::Face));
    }
    let mut b = centre.clone();
    b.balance(Connectivity::Corner);
    b.validate().unwrap();
    assert!(b.is_balanced(Connectivity::Corner));
}

fn run<const D: usize>(seed: u64, trees: usize) {
    let mut r = rng(seed);
    check_deepest_level::<D>();
    for _ in 0..trees {
        let t = sample_tree::<D>(&mut r);
        check_topology(&mut r, &t);
        check_neighbors(&mut r, &t);
        check_balance(&t);
        check_split_balanced(&t);
        check_merge(&mut r, &t);
    }
}

macro_rules! every_dimension {
    ($($name:ident: $d:literal, $trees:literal;)*) => {
        $(
            #[test]
            fn $name() {
                run::<$d>(1000 + $d, $trees);
            }
        )*
    };
}

every_dimension! {
    tree_in_1d: 1, 12;
    tree_in_2d: 2, 12;
    tree_in_3d: 3, 8;
    tree_in_4d: 4, 5;
    tree_in_5d: 5, 3;
    tree_in_6d: 6, 2;
    tree_in_7d: 7, 2;
    tree_in_8d: 8, 2;
}
