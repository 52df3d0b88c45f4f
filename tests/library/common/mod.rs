//! Shared helpers for the integration tests: seeded tree generators and brute-force oracles that
//! use nothing of the crate but cell addresses (level and integer coordinates).
//!
//! The oracles deliberately recompute everything from `Cell::level` and `Cell::coords` (intervals,
//! containment, contact, shifted cells) instead of calling the crate's own `Cell` helpers, so a
//! bug in those helpers cannot hide a bug in the code under test.
#![allow(dead_code)]

pub mod mutate;
pub mod points;
pub mod updates;

use orthtree::{geom::Direction, tree::BalanceOptions, tree::NodeId, Cell, Connectivity, Tree};
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};
use std::collections::{BTreeSet, HashSet};

/// A seeded small RNG.
pub fn rng(seed: u64) -> SmallRng {
    SmallRng::seed_from_u64(seed)
}

// ---------------------------------------------------------------------------------------------
// Cell arithmetic, recomputed from level and coordinates
// ---------------------------------------------------------------------------------------------

/// The closed interval `[lo, hi]` of `cell` on `axis`, in units of the finest level
/// (`Cell::<D>::MAX_LEVEL`).
pub fn interval<const D: usize>(cell: &Cell<D>, axis: usize) -> (u64, u64) {
    let shift = u32::from(Cell::<D>::MAX_LEVEL - cell.level());
    let lo = u64::from(cell.coords()[axis]) << shift;
    (lo, lo + (1u64 << shift))
}

/// `true` when `outer` is `inner` or one of its ancestors.
pub fn contains<const D: usize>(outer: &Cell<D>, inner: &Cell<D>) -> bool {
    if outer.level() > inner.level() {
        return false;
    }
    let shift = u32::from(inner.level() - outer.level());
    (0..D).all(|a| u64::from(inner.coords()[a]) >> shift == u64::from(outer.coords()[a]))
}

/// The same-level cell moved by `offset`; `None` outside the root cube.
pub fn shifted<const D: usize>(cell: &Cell<D>, offset: [i8; D]) -> Option<Cell<D>> {
    let side = 1i64 << cell.level();
    let mut coords = [0u32; D];
    for a in 0..D {
        let c = i64::from(cell.coords()[a]) + i64::from(offset[a]);
        if c < 0 || c >= side {
            return None;
        }
        coords[a] = c as u32;
    }
    Some(Cell::new(cell.level(), coords).expect("a valid cell"))
}

/// How two closed cells touch: `Some(k)` when their interiors are disjoint and their closures meet,
/// `k` being the number of axes on which they meet at an endpoint; `None` otherwise.
pub fn contact<const D: usize>(a: &Cell<D>, b: &Cell<D>) -> Option<u32> {
    let mut touching = 0;
    for axis in 0..D {
        let (l1, h1) = interval(a, axis);
        let (l2, h2) = interval(b, axis);
        if h1 < l2 || h2 < l1 {
            return None; // closures disjoint
        }
        if h1 == l2 || h2 == l1 {
            touching += 1; // intervals meet in one point
        }
    }
    (touching > 0).then_some(touching)
}

/// Whether a contact across `k` axes counts under `conn` (Face: 1, Edge: at most 2, Corner: any).
pub fn allowed(conn: Connectivity, k: u32) -> bool {
    match conn {
        Connectivity::Face => k == 1,
        Connectivity::Edge => k <= 2,
        Connectivity::Corner => true,
    }
}

/// Every offset in {-1, 0, 1}^D except zero, enumerated independently of `Direction::all`.
pub fn all_offsets<const D: usize>() -> Vec<[i8; D]> {
    let mut out = Vec::new();
    for code in 0..3usize.pow(D as u32) {
        let mut c = code;
        let mut off = [0i8; D];
        for o in off.iter_mut() {
            *o = (c % 3) as i8 - 1;
            c /= 3;
        }
        if off.iter().any(|&o| o != 0) {
            out.push(off);
        }
    }
    out
}

/// The volume of `cell` in cells of the finest level: side^D with side = 2^(MAX_LEVEL - level)
/// (D * MAX_LEVEL <= 64, so it fits in a `u128`).
pub fn volume<const D: usize>(cell: &Cell<D>) -> u128 {
    let side = 1u128 << (Cell::<D>::MAX_LEVEL - cell.level());
    (0..D).fold(1u128, |v, _| v * side)
}

/// `true` when the leaf cells tile the root cube: no cell contains another (so dyadic cells have
/// pairwise disjoint interiors) and their volumes add up to the root's. In Morton (pre-)order a
/// cell's descendants come right after it, so checking consecutive cells finds any nesting.
pub fn tiles_root<const D: usize>(leaves: &[Cell<D>]) -> bool {
    let mut sorted = leaves.to_vec();
    sorted.sort();
    let nested = sorted.windows(2).any(|w| contains(&w[0], &w[1]));
    let total: u128 = leaves.iter().map(volume).sum();
    !nested && total == volume(&Cell::<D>::root())
}

// ---------------------------------------------------------------------------------------------
// Tree generators
// ---------------------------------------------------------------------------------------------

/// The leaves of a tree, as ids.
pub fn leaf_ids<const D: usize>(t: &Tree<D>) -> Vec<NodeId> {
    t.leaves().map(|(id, _)| id).collect()
}

/// The leaf cells of a tree, sorted.
pub fn leaf_cells<const D: usize>(t: &Tree<D>) -> Vec<Cell<D>> {
    let mut v: Vec<Cell<D>> = t.leaves().map(|(_, c)| c).collect();
    v.sort();
    v
}

/// A random tree made of `splits` splits of random leaves above `max_level`. With probability
/// `deep_bias` the next split takes a child of the previous split (growing deep chains), otherwise
/// a uniformly random leaf.
pub fn random_tree<const D: usize>(
    rng: &mut SmallRng,
    splits: usize,
    max_level: u8,
    deep_bias: f64,
) -> Tree<D> {
    let mut t = Tree::<D>::new();
    let mut last: Option<NodeId> = None;
    for _ in 0..splits {
        let candidates: Vec<NodeId> = leaf_ids(&t)
            .into_iter()
            .filter(|&id| t.level(id) < max_level)
            .collect();
        if candidates.is_empty() {
            break;
        }
        let pick = match last {
            Some(parent) if rng.gen_bool(deep_bias) && t.level(parent) + 1 < max_level => {
                t.child(parent, rng.gen_range(0..1usize << D)).unwrap()
            }
            _ => candidates[rng.gen_range(0..candidates.len())],
        };
        if !t.is_leaf(pick) {
            continue;
        }
        t.split(pick);
        last = Some(pick);
    }
    t
}

/// A chain of splits: split the root, then at each level split the child chosen by `choose(level)`
/// of the node split last, down to `depth`.
pub fn chain_tree<const D: usize>(depth: u8, mut choose: impl FnMut(u8) -> usize) -> Tree<D> {
    let mut t = Tree::<D>::new();
    let mut v = NodeId::ROOT;
    for level in 0..depth {
        t.split(v);
        if level + 1 < depth {
            v = t.child(v, choose(level)).unwrap();
        }
    }
    t
}

/// A chain toward the lowest corner of the root: always child 0.
pub fn corner_chain<const D: usize>(depth: u8) -> Tree<D> {
    chain_tree::<D>(depth, |_| 0)
}

/// A chain toward the centre of the root: child 0 first, then always the last child, so that
/// refinement hugs the centre and the huge level-1 leaves next to it.
pub fn centre_chain<const D: usize>(depth: u8) -> Tree<D> {
    chain_tree::<D>(depth, |l| if l == 0 { 0 } else { (1 << D) - 1 })
}

/// A chain toward the point (1/2, 0, ..., 0), the midpoint of the root's lowest edge along axis 0
/// (in 2D the midpoint of the south side): child 0 first, then always child 1 (upper on axis 0,
/// lower on the others), so deep cells sit on the root's boundary next to the huge SE leaf.
pub fn face_chain<const D: usize>(depth: u8) -> Tree<D> {
    chain_tree::<D>(depth, |l| if l == 0 { 0 } else { 1 })
}

/// A chain toward a random point of the root.
pub fn random_point_chain<const D: usize>(rng: &mut SmallRng, depth: u8) -> Tree<D> {
    let target: [u64; D] = core::array::from_fn(|_| rng.r#gen::<u64>());
    chain_tree::<D>(depth, |l| {
        (0..D).fold(0, |i, a| {
            i | ((((target[a] >> (63 - l)) & 1) as usize) << a)
        })
    })
}

// ---------------------------------------------------------------------------------------------
// Balance oracles
// ---------------------------------------------------------------------------------------------

/// A violating pair (coarse leaf, fine leaf): adjacent under the connectivity and more than
/// `max_level_difference` levels apart. O(L^2).
pub fn brute_violation<const D: usize>(
    leaves: &[Cell<D>],
    opts: BalanceOptions,
) -> Option<(Cell<D>, Cell<D>)> {
    for l in leaves {
        for m in leaves {
            if m.level() <= l.level() + opts.max_level_difference() {
                continue;
            }
            if let Some(k) = contact(l, m)
                && allowed(opts.connectivity, k)
            {
                return Some((*l, *m));
            }
        }
    }
    None
}

/// `true` when no two adjacent leaves differ by more than the allowed number of levels. O(L^2).
pub fn brute_is_balanced<const D: usize>(leaves: &[Cell<D>], opts: BalanceOptions) -> bool {
    brute_violation(leaves, opts).is_none()
}

/// The children of a cell, computed from coordinates.
pub fn children<const D: usize>(cell: &Cell<D>) -> Vec<Cell<D>> {
    (0..1usize << D)
        .map(|i| {
            let coords: [u32; D] =
                core::array::from_fn(|a| (cell.coords()[a] << 1) | ((i >> a) & 1) as u32);
            Cell::new(cell.level() + 1, coords).unwrap()
        })
        .collect()
}

/// The brute-force balance fixpoint: while some leaf L has an adjacent leaf M (contact allowed by
/// the connectivity) with level(M) > level(L) + max_level_difference, split L. Every such split is
/// forced (it stays forced in every refinement), so the fixpoint is the unique coarsest balanced
/// refinement whatever the order. Each round splits every leaf violating at its start. O(L^2) per
/// round.
pub fn brute_balance<const D: usize>(leaves: &[Cell<D>], opts: BalanceOptions) -> Vec<Cell<D>> {
    let mut cur: Vec<Cell<D>> = leaves.to_vec();
    loop {
        let mut coarse: BTreeSet<Cell<D>> = BTreeSet::new();
        for l in &cur {
            let violates = cur.iter().any(|m| {
                m.level() > l.level() + opts.max_level_difference()
                    && contact(l, m).is_some_and(|k| allowed(opts.connectivity, k))
            });
            if violates {
                coarse.insert(*l);
            }
        }
        if coarse.is_empty() {
            cur.sort();
            return cur;
        }
        let mut next: Vec<Cell<D>> = cur.into_iter().filter(|c| !coarse.contains(c)).collect();
        for c in &coarse {
            next.extend(children(c));
        }
        cur = next;
    }
}

/// The leaf of `set` containing `cell` (walking up its ancestors), if any.
fn leaf_containing<const D: usize>(set: &HashSet<Cell<D>>, cell: &Cell<D>) -> Option<Cell<D>> {
    let mut c = *cell;
    loop {
        if set.contains(&c) {
            return Some(c);
        }
        c = c.parent()?;
    }
}

/// A faster, still independent oracle for larger trees: a leaf set in a hash set; every leaf M is
/// examined after it appears; for each allowed offset, the leaf L containing M's same-level
/// neighbour is split while it is more than `max_level_difference` levels coarser than M. (A leaf
/// L coarser than M is adjacent to M with an allowed contact exactly when it contains the
/// same-level neighbour of M in a direction moving along as many axes as their contact.)
pub fn fast_balance<const D: usize>(leaves: &[Cell<D>], opts: BalanceOptions) -> Vec<Cell<D>> {
    let offsets: Vec<[i8; D]> = all_offsets::<D>()
        .into_iter()
        .filter(|o| {
            allowed(
                opts.connectivity,
                o.iter().filter(|&&x| x != 0).count() as u32,
            )
        })
        .collect();
    let mut set: HashSet<Cell<D>> = leaves.iter().copied().collect();
    let mut work: Vec<Cell<D>> = leaves.to_vec();
    while let Some(m) = work.pop() {
        if !set.contains(&m) {
            continue;
        }
        for off in &offsets {
            let Some(n) = shifted(&m, *off) else {
                continue;
            };
            while let Some(l) = leaf_containing(&set, &n) {
                if l.level() + opts.max_level_difference() >= m.level() {
                    break;
                }
                set.remove(&l);
                for c in children(&l) {
                    set.insert(c);
                    work.push(c);
                }
            }
        }
    }
    let mut v: Vec<Cell<D>> = set.into_iter().collect();
    v.sort();
    v
}

/// Every balance option: each connectivity, 2:1 and weak (4:1).
pub fn all_options() -> Vec<BalanceOptions> {
    let mut v = Vec::new();
    for conn in Connectivity::ALL {
        v.push(BalanceOptions::new(conn));
        v.push(BalanceOptions::new(conn).weak());
    }
    v
}

/// The directions of a connectivity, as offsets.
pub fn directions<const D: usize>(conn: Connectivity) -> Vec<Direction> {
    Direction::all::<D>(conn).collect()
}

// ---------------------------------------------------------------------------------------------
// Point helpers
// ---------------------------------------------------------------------------------------------

/// Squared Euclidean distance.
pub fn dist2<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
    (0..D).map(|i| (a[i] - b[i]) * (a[i] - b[i])).sum()
}

/// The closest-pair distance by brute force (infinite for fewer than two points).
pub fn closest_pair<const D: usize>(pts: &[[f64; D]]) -> f64 {
    let mut best = f64::INFINITY;
    for i in 0..pts.len() {
        for j in i + 1..pts.len() {
            best = best.min(dist2(&pts[i], &pts[j]));
        }
    }
    best.sqrt()
}

/// Removes exact duplicates (bitwise), keeping the first.
pub fn dedup_points<const D: usize>(pts: Vec<[f64; D]>) -> Vec<[f64; D]> {
    let mut seen = HashSet::new();
    pts.into_iter()
        .filter(|p| seen.insert(p.map(f64::to_bits)))
        .collect()
}

/// Asserts two sorted cell lists are equal, reporting only a summary and the first differences.
pub fn assert_cells_eq<const D: usize>(got: &[Cell<D>], want: &[Cell<D>], context: &str) {
    if got == want {
        return;
    }
    let g: BTreeSet<Cell<D>> = got.iter().copied().collect();
    let w: BTreeSet<Cell<D>> = want.iter().copied().collect();
    let missing: Vec<(u8, [u32; D])> = w
        .difference(&g)
        .take(8)
        .map(|c| (c.level(), c.coords()))
        .collect();
    let extra: Vec<(u8, [u32; D])> = g
        .difference(&w)
        .take(8)
        .map(|c| (c.level(), c.coords()))
        .collect();
    panic!(
        "{context}: {} leaves, expected {}; first expected but missing (level, coords): \
         {missing:?}; first unexpected: {extra:?}",
        got.len(),
        want.len()
    );
}
