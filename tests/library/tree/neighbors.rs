//! Neighbour finding (`Tree::neighbor`, `Tree::leaf_neighbors`, `Tree::adjacent_leaves`) against
//! brute force over every node and every one of the 3^D - 1 directions, in 1 to 4 dimensions, on
//! random trees and on deep chains down to `Cell::MAX_LEVEL`.

use crate::common;

use common::*;
use orthtree::{geom::Direction, tree::NodeId, Cell, Connectivity, Tree};
use rand::Rng;
use std::collections::BTreeSet;

/// The chapter's contract, by brute force: the target is the same-size cell one step in the
/// direction (`None` outside the root); the answer is the node with exactly that cell if there is
/// one, else the deepest node whose cell contains it. (Both are "the deepest node containing the
/// target", since the nodes containing a cell form a chain and none is deeper than the cell.)
fn brute_neighbor<const D: usize>(
    nodes: &[(NodeId, Cell<D>)],
    cell: &Cell<D>,
    offset: [i8; D],
) -> Option<NodeId> {
    let target = shifted(cell, offset)?;
    let exact = nodes.iter().find(|(_, c)| *c == target).map(|(id, _)| *id);
    let deepest = nodes
        .iter()
        .filter(|(_, c)| contains(c, &target))
        .max_by_key(|(_, c)| c.level())
        .map(|(id, _)| *id);
    assert!(deepest.is_some(), "the root contains every cell");
    exact.or(deepest)
}

/// The leaves adjacent to `cell` across the face, edge or corner given by `offset`, by brute
/// force over all leaves with closed-interval geometry: a leaf L qualifies when, for every small
/// eps, L's interior meets the slab just outside `cell` on that side, i.e. on each axis a with
/// `cell = [l1, h1]`, `L = [l2, h2]`:
///   offset +1: l2 <= h1 < h2 (L starts at or before the upper side and reaches beyond it),
///   offset -1: l2 < l1 <= h2 (mirror image),
///   offset  0: l2 < h1 and l1 < h2 (the open intervals overlap: positive length in common).
/// For a face this is "shares a (D-1)-dimensional piece of the face"; for a 2D corner it is the
/// one leaf whose closed cell holds the corner point and lies diagonally beyond it (a leaf at
/// most as large touches `cell` exactly at that corner; a larger one contains the diagonal
/// same-size cell and may touch along a side as well).
fn brute_leaf_neighbors<const D: usize>(
    leaves: &[(NodeId, Cell<D>)],
    cell: &Cell<D>,
    offset: [i8; D],
) -> BTreeSet<NodeId> {
    leaves
        .iter()
        .filter(|(_, l)| {
            (0..D).all(|a| {
                let (l1, h1) = interval(cell, a);
                let (l2, h2) = interval(l, a);
                match offset[a] {
                    1 => l2 <= h1 && h1 < h2,
                    -1 => l2 < l1 && l1 <= h2,
                    _ => l2 < h1 && l1 < h2,
                }
            })
        })
        .map(|(id, _)| *id)
        .collect()
}

/// The chapter's NORTHNEIGHBOR, literally (recursive), generalised to the face direction
/// `positive` along `axis`.
fn chapter_face_neighbor<const D: usize>(
    t: &Tree<D>,
    v: NodeId,
    axis: usize,
    positive: bool,
) -> Option<NodeId> {
    let parent = t.parent(v)?; // v = root: nil
    let i = t.child_index(v);
    let bit = 1usize << axis;
    let stays_inside = if positive { i & bit == 0 } else { i & bit != 0 };
    if stays_inside {
        return t.child(parent, i ^ bit); // e.g. SW-child -> NW-child of parent(v)
    }
    let mu = chapter_face_neighbor(t, parent, axis, positive)?;
    if t.is_leaf(mu) {
        return Some(mu);
    }
    t.child(mu, i ^ bit) // e.g. NW-child -> SW-child of mu
}

/// Checks every node and every direction of `t` against the oracles.
fn check_tree<const D: usize>(t: &Tree<D>) {
    let nodes: Vec<(NodeId, Cell<D>)> = t.pre_order().collect();
    assert_eq!(nodes.len(), t.node_count());
    for (id, c) in &nodes {
        assert_eq!(t.cell(*id), *c);
        assert_eq!(t.level(*id), c.level());
    }
    let leaves: Vec<(NodeId, Cell<D>)> = t.leaves().collect();
    assert_eq!(leaves.len(), t.leaf_count());
    let leaf_cells: Vec<Cell<D>> = leaves.iter().map(|(_, c)| *c).collect();
    assert!(tiles_root(&leaf_cells), "the leaves tile the root");

    let dirs = directions::<D>(Connectivity::Corner);
    assert_eq!(dirs.len(), 3usize.pow(D as u32) - 1);
    let offsets: BTreeSet<[i8; D]> = dirs.iter().map(|d| d.offset::<D>()).collect();
    assert_eq!(offsets, all_offsets::<D>().into_iter().collect());

    let mut out = Vec::new();
    for (id, cell) in &nodes {
        for &d in &dirs {
            let off = d.offset::<D>();
            // neighbor
            let got = t.neighbor(*id, d);
            let want = brute_neighbor(&nodes, cell, off);
            assert_eq!(
                got,
                want,
                "neighbor of {cell:?} (node {}) toward {off:?}",
                id.index()
            );
            if let Some(n) = got {
                assert!(t.level(n) <= t.level(*id));
                if t.level(n) < t.level(*id) {
                    assert!(t.is_leaf(n), "a shallower neighbour is a leaf");
                }
            }
            if d.axes_moved() == 1 {
                let axis = (0..D).find(|&a| off[a] != 0).unwrap();
                assert_eq!(got, chapter_face_neighbor(t, *id, axis, off[axis] > 0));
            }
            // leaf_neighbors
            out.clear();
            out.push(NodeId::ROOT); // leaf_neighbors appends: keep what was there
            t.leaf_neighbors(*id, d, &mut out);
            assert_eq!(out[0], NodeId::ROOT);
            let reported = &out[1..];
            let want_leaves = brute_leaf_neighbors(&leaves, cell, off);
            let got_leaves: BTreeSet<NodeId> = reported.iter().copied().collect();
            assert_eq!(got_leaves.len(), reported.len(), "no leaf reported twice");
            assert_eq!(
                got_leaves, want_leaves,
                "leaf neighbours of {cell:?} toward {off:?}"
            );
            // in Morton order
            let cells: Vec<Cell<D>> = reported.iter().map(|&v| t.cell(v)).collect();
            assert!(cells.windows(2).all(|w| w[0] < w[1]), "Morton order");
        }
    }

    // adjacent_leaves of every leaf, for every connectivity
    for (id, cell) in &leaves {
        for conn in Connectivity::ALL {
            out.clear();
            t.adjacent_leaves(*id, conn, &mut out);
            // as a multiset: the brute-force leaf neighbours of each allowed direction
            let mut want: Vec<NodeId> = Vec::new();
            for off in all_offsets::<D>() {
                let k = off.iter().filter(|&&o| o != 0).count() as u32;
                if allowed(conn, k) {
                    want.extend(brute_leaf_neighbors(&leaves, cell, off));
                }
            }
            let mut got = out.clone();
            got.sort();
            want.sort();
            assert_eq!(got, want, "adjacent leaves of {cell:?} under {conn:?}");
            // as a set: every other leaf whose contact with it is allowed
            let got_set: BTreeSet<NodeId> = out.iter().copied().collect();
            let want_set: BTreeSet<NodeId> = leaves
                .iter()
                .filter(|(other, c)| {
                    other != id && contact(cell, c).is_some_and(|k| allowed(conn, k))
                })
                .map(|(other, _)| *other)
                .collect();
            assert_eq!(got_set, want_set);
        }
    }
}

fn random_trees<const D: usize>(seed: u64, count: usize, max_splits: usize, max_level: u8) {
    let mut r = rng(seed);
    for i in 0..count {
        let splits = if i == 0 {
            0
        } else {
            1 + (i * 7919) % max_splits
        };
        let bias = [0.0, 0.5, 0.8, 0.95][i % 4];
        let t = random_tree::<D>(&mut r, splits, max_level, bias);
        check_tree(&t);
    }
}

#[test]
fn neighbors_match_brute_force_1d() {
    random_trees::<1>(1, 60, 40, Cell::<1>::MAX_LEVEL);
}

#[test]
fn neighbors_match_brute_force_2d() {
    random_trees::<2>(2, 60, 50, 12);
}

#[test]
fn neighbors_match_brute_force_3d() {
    random_trees::<3>(3, 30, 25, 8);
}

#[test]
fn neighbors_match_brute_force_4d() {
    random_trees::<4>(4, 16, 10, 5);
}

/// Chains of splits down to the deepest level a cell may have, toward a corner, the centre, the
/// middle of a side and random points: the up-and-down walk crosses every level.
fn deep_chains<const D: usize>(seed: u64) {
    let depth = Cell::<D>::MAX_LEVEL;
    check_tree(&corner_chain::<D>(depth));
    check_tree(&centre_chain::<D>(depth));
    check_tree(&face_chain::<D>(depth));
    let mut r = rng(seed);
    for _ in 0..3 {
        check_tree(&random_point_chain::<D>(&mut r, depth));
    }
    // a chain at the deepest level next to random refinement elsewhere
    let mut t = centre_chain::<D>(depth);
    for _ in 0..4 {
        let leaves = leaf_ids(&t);
        let v = leaves[r.gen_range(0..leaves.len())];
        if t.level(v) < depth {
            t.split(v);
        }
    }
    check_tree(&t);
}

#[test]
fn neighbors_on_chains_to_the_deepest_level() {
    deep_chains::<1>(11);
    deep_chains::<2>(12);
    deep_chains::<3>(13);
    deep_chains::<4>(14);
}

#[test]
fn direction_sets_and_compass_names() {
    fn counts<const D: usize>() {
        let face = directions::<D>(Connectivity::Face);
        let edge = directions::<D>(Connectivity::Edge);
        let corner = directions::<D>(Connectivity::Corner);
        assert_eq!(face.len(), 2 * D);
        assert_eq!(edge.len(), 2 * D + 4 * D * (D - 1) / 2);
        assert_eq!(corner.len(), 3usize.pow(D as u32) - 1);
        for d in &corner {
            let off = d.offset::<D>();
            let moved = off.iter().filter(|&&o| o != 0).count() as u32;
            assert_eq!(d.axes_moved(), moved);
            assert_eq!(d.opposite().offset::<D>(), off.map(|o| -o));
            assert_eq!(face.contains(d), moved == 1);
            assert_eq!(edge.contains(d), moved <= 2);
        }
        for a in 0..D {
            let mut up = [0i8; D];
            up[a] = 1;
            assert_eq!(Direction::face(a, true).offset::<D>(), up);
            assert_eq!(Direction::face(a, false).offset::<D>(), up.map(|o| -o));
        }
    }
    counts::<1>();
    counts::<2>();
    counts::<3>();
    counts::<4>();
    assert_eq!(Direction::NORTH.offset::<2>(), [0, 1]);
    assert_eq!(Direction::SOUTH.offset::<2>(), [0, -1]);
    assert_eq!(Direction::EAST.offset::<2>(), [1, 0]);
    assert_eq!(Direction::WEST.offset::<2>(), [-1, 0]);
}

/// The chapter's figure-style example, by hand: children are SW = 0, SE = 1, NW = 2, NE = 3.
#[test]
fn chapter_north_neighbour_example() {
    let mut t = Tree::<2>::new();
    let sw = t.split(NodeId::ROOT);
    let nw = t.child(NodeId::ROOT, 2).unwrap();
    let ne = t.child(NodeId::ROOT, 3).unwrap();
    assert_eq!(t.cell(nw).coords(), [0, 1]);
    // SW-child: its north neighbour is the NW-child of the parent
    assert_eq!(t.neighbor(sw, Direction::NORTH), Some(nw));
    // on the root's boundary: nil
    assert_eq!(t.neighbor(nw, Direction::NORTH), None);
    assert_eq!(t.neighbor(NodeId::ROOT, Direction::NORTH), None);
    // split SW; its NW-child looks north into the leaf NW (shallower): reported as is
    t.split(sw);
    let sw_nw = t.child(sw, 2).unwrap();
    assert_eq!(t.neighbor(sw_nw, Direction::NORTH), Some(nw));
    // split NW; now the same-depth neighbour is NW's SW-child
    t.split(nw);
    assert_eq!(t.neighbor(sw_nw, Direction::NORTH), t.child(nw, 0));
    // north-east of SW's NE child (level 2, [1, 1]) lies the level-2 cell [2, 2], inside the
    // NE leaf
    let sw_ne = t.child(sw, 3).unwrap();
    let north_east = Direction::NORTH.combine(Direction::EAST).unwrap();
    assert_eq!(t.neighbor(sw_ne, north_east), Some(ne));
    let mut out = Vec::new();
    t.leaf_neighbors(sw, Direction::NORTH, &mut out);
    assert_eq!(out, [t.child(nw, 0).unwrap(), t.child(nw, 1).unwrap()]);
}
