//! [`SkipQuadtree`]: Eppstein, Goodrich and Sun, "The skip quadtree: a simple dynamic data
//! structure for multidimensional data" (SoCG 2005), cited in the notes of chapter 14.
//!
//! Level 0 is a [`CompressedTree`] over all points. Level `i + 1` is a compressed quadtree over
//! a random half of level `i`'s distinct finest cells (a key is in levels `0..=h`, with
//! `P(h >= i) = 2^-i`, as in a skip list). A branching cell of a sample also branches in every
//! larger sample, so every node of level `i + 1` has a node with the same cell in level `i`, and
//! keeps a `down` link to it.
//!
//! - Point location: walk down the top level to the deepest node whose cell holds the query,
//!   follow `down`, continue in the level below, and so on. Each level adds O(1) expected steps
//!   (between two consecutive nodes of level `i + 1` on the query's path, the nodes of level `i`
//!   form a geometric run), so a location costs expected O(log n) nodes, whatever the depth.
//! - Insert: locate, recording the deepest node holding the key on every level; insert into
//!   levels `0..=h` bottom-up (O(1) per level below the recorded node, [`Topology::insert`]),
//!   linking each new node to its copy one level down (found by walking up from that level's
//!   new leaf). Expected O(log n).
//! - Delete: locate, remove the point from level 0; if its cell emptied, remove its leaf from
//!   every level holding it (splicing out parents left with one child). Expected O(log n).
//! - (1 + eps)-approximate nearest neighbour: best-first search (Arya and Mount's priority
//!   search) on level 0, stopped once no box left can hold a point closer than the best found
//!   divided by (1 + eps). The approximation is guaranteed; the running time is that of the
//!   priority search, not the O(eps^(1-d) log n) of the paper's level-by-level search.
//!
//! The sample is drawn by hashing each key with a seed ([`SkipQuadtree::with_seed`]): a key's
//! height is the number of trailing zero bits of its SplitMix64 hash (chained over its D
//! coordinates, starting from the seed). The
//! expectations hold for any input chosen without knowledge of the seed, and the structure is
//! a function of the stored keys and the seed alone, so it equals a fresh build after updates.

use super::topology::{Inserted, Topology, NIL};
use super::CompressedIndex;
use super::{CompressedTree, Located};
use crate::error::Error;
use crate::error::ValidationError;
use crate::geom::{Aabb, DeepCell, DeepKey, Scalar};
use crate::hash::splitmix64;
use crate::query::{InsertError, Location};
use crate::query::{
    Metric, Neighbor, PointSet, PointSetMut, PositionSlots, QueryError, SpatialIndex,
    SquaredEuclidean,
};
use smallvec::SmallVec;
use std::cmp::Ordering;
use std::collections::{BinaryHeap, HashSet};

/// The deepest node holding a key on every level, level 0 first.
type Path = SmallVec<[u32; 48]>;

/// The seed used unless one is given.
const DEFAULT_SEED: u64 = 0x5851_f42d_4c95_7f2d;
/// No key climbs above this many levels (probability 2^-48 per key).
const MAX_HEIGHT: u32 = 48;

/// A skip quadtree: a [`CompressedTree`] (level 0, which answers every query of
/// [`crate::query`] through [`SkipQuadtree::base`]) and compressed quadtrees over nested random
/// samples above it, for expected O(log n) point location, insert and delete.
///
/// ```
/// use orthtree::prelude::*;
/// use orthtree::compressed::SkipQuadtree;
/// let pts: Vec<([f64; 2], usize)> = (0..1000).map(|i| ([(i % 37) as f64, (i / 37) as f64], i)).collect();
/// let mut t = SkipQuadtree::new(&pts).unwrap();
/// let at = t.locate(&[5.0, 3.0]).unwrap().inside().unwrap();
/// assert!(at.leaf);
/// t.insert([5.5, 3.0], 1000).unwrap();
/// assert_eq!(t.remove_point(&[5.0, 3.0]), Some(5 + 3 * 37));
/// let (near, _) = t.approx_nearest(&[5.4, 3.1], 0.5).unwrap();
/// assert_eq!(*near.unwrap().item, 1000);
/// t.validate().unwrap();
/// ```
#[derive(Clone, Debug)]
pub struct SkipQuadtree<S, T, const D: usize> {
    base: CompressedTree<S, T, D>,
    /// `levels[i]` is level `i + 1`; its `down` links point into level `i`.
    levels: Vec<Topology<D>>,
    seed: u64,
}

impl<S: Scalar, T, const D: usize> SkipQuadtree<S, T, D> {
    /// Builds over the smallest enclosing cube of the points, cloning the items.
    ///
    /// # Errors
    /// Those of [`CompressedTree::new`].
    pub fn new(entries: &[([S; D], T)]) -> Result<Self, Error>
    where
        T: Clone,
    {
        Ok(Self::with_seed(CompressedTree::new(entries)?, DEFAULT_SEED))
    }

    /// The skip quadtree over `base` (its level 0), sampling with `seed`. O(n) expected after
    /// the base is built.
    pub fn with_seed(base: CompressedTree<S, T, D>, seed: u64) -> Self {
        let t = &base.index.topology;
        let mut sample: Vec<DeepKey<D>> = t
            .pre_order()
            .filter(|&v| t.is_leaf(v))
            .map(|v| t.node(v).cell.anchor())
            .collect();
        let mut skip = SkipQuadtree {
            base,
            levels: Vec::new(),
            seed,
        };
        for i in 1.. {
            sample.retain(|k| skip.height(k) >= i);
            if sample.is_empty() {
                break;
            }
            let mut level = Topology::from_sorted(sample.iter().copied(), |_, _, _| {});
            let below = skip.level(i as usize - 1);
            // Both pre-orders are Morton orders, and the upper cells are among the lower ones.
            let mut lower = below.pre_order();
            let ids: Vec<u32> = level.pre_order().collect();
            for v in ids {
                let cell = level.node(v).cell;
                let copy = lower.find(|&w| below.node(w).cell == cell);
                level.nodes[v as usize].down = copy.unwrap_or(NIL);
            }
            skip.levels.push(level);
        }
        skip
    }

    /// The height of a key: its levels are `0..=height`.
    fn height(&self, key: &DeepKey<D>) -> u32 {
        let hash = key.iter().fold(self.seed, |h, &k| splitmix64(h ^ k));
        hash.trailing_zeros().min(MAX_HEIGHT)
    }

    /// Level `i` (0 is the base's tree).
    fn level(&self, i: usize) -> &Topology<D> {
        (i.checked_sub(1)).map_or(&self.base.index.topology, |i| &self.levels[i])
    }

    /// The seed the sample is drawn with ([`SkipQuadtree::with_seed`]).
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// Level 0: every point, and every query of [`CompressedTree`].
    pub fn base(&self) -> &CompressedTree<S, T, D> {
        &self.base
    }

    /// The number of levels, level 0 included (1 for an empty tree).
    pub fn level_count(&self) -> usize {
        self.levels.len() + 1
    }

    /// The nodes of every level (O(n) expected: about twice level 0's).
    pub fn node_count(&self) -> usize {
        self.base.node_count() + self.levels.iter().map(Topology::len).sum::<usize>()
    }

    /// The cell of every node of level `i` (0 is the base) in pre-order, with `true` for a
    /// leaf; nothing for a level above the top.
    pub fn level_cells(&self, i: usize) -> impl Iterator<Item = (DeepCell<D>, bool)> + '_ {
        let level = (i <= self.levels.len()).then(|| self.level(i));
        let nodes = level
            .into_iter()
            .flat_map(|t| t.pre_order().map(move |v| (t, v)));
        nodes.map(|(t, v)| (t.node(v).cell, t.is_leaf(v)))
    }

    /// The deepest node holding `key` on every level, counting the nodes visited.
    fn search(&self, key: &DeepKey<D>, touched: &mut usize) -> Path {
        let mut path: Path = SmallVec::from_elem(0, self.levels.len() + 1);
        let mut v = 0;
        for i in (0..=self.levels.len()).rev() {
            let level = self.level(i);
            v = level.descend(v, key, |_| *touched += 1);
            path[i] = v;
            v = level.node(v).down;
        }
        path
    }

    /// The deepest node of level 0 whose cell holds `point`, found from the top level down, or
    /// [`Location::Outside`] for a point outside the domain.
    ///
    /// # Errors
    /// [`QueryError::NotFinite`] or [`QueryError::Inexact`] for a coordinate that is NaN,
    /// infinite or an integer `f64` cannot hold, naming its axis.
    ///
    /// # Complexity
    /// Expected O(log n) nodes visited ([`Located::touched`]).
    pub fn locate(&self, point: &[S; D]) -> Result<Location<Located<D>>, QueryError> {
        Ok(self.base.query_key(point)?.map(|key| {
            let mut touched = 0;
            let path = self.search(&key, &mut touched);
            self.base.located(path[0], touched)
        }))
    }

    /// Sets the `down` links of the nodes an insert created on level `i`, `below` being what
    /// it did on level `i - 1`.
    fn link_down(&mut self, i: usize, done: Inserted, below: Inserted) {
        self.levels[i - 1].nodes[done.leaf as usize].down = below.leaf;
        if done.branch == NIL {
            return;
        }
        let cell = self.levels[i - 1].node(done.branch).cell;
        let lower = self.level(i - 1);
        let mut w = below.leaf;
        while w != NIL && lower.node(w).cell != cell {
            w = lower.node(w).parent;
        }
        self.levels[i - 1].nodes[done.branch as usize].down = w;
    }

    /// A point whose distance to `p` is at most `(1 + eps)` times the nearest's (Euclidean), and
    /// the number of nodes the search visited; `None` for an empty tree. `eps = 0` gives the
    /// exact nearest point (and so does `-0.0`); an infinite or huge `eps` (for which
    /// `(1 + eps)^2` overflows) accepts any point, the first found.
    ///
    /// # Errors
    /// A non-finite `p` or an integer coordinate `f64` cannot hold; `eps` negative or
    /// NaN ([`QueryError::InvalidEpsilon`]).
    pub fn approx_nearest(
        &self,
        p: &[S; D],
        eps: f64,
    ) -> Result<(Option<Neighbor<'_, S, T, D>>, usize), QueryError> {
        let q = crate::query::query_point(p)?;
        if eps.is_nan() || eps < 0.0 {
            return Err(QueryError::InvalidEpsilon { value: eps.into() });
        }
        // A box is searched while its distance is at most best / (1 + eps)^2. The factor is 0
        // for an eps so large (above about 1.3e154, or infinite) that (1 + eps)^2 overflows:
        // then any point will do, and the bound is 0 once one is found. While none is found the
        // bound is infinite, never `infinity * 0`.
        let shrink = 1.0 / ((1.0 + eps) * (1.0 + eps));
        let bound = |best: f64| {
            if best == f64::INFINITY {
                best
            } else {
                best * shrink
            }
        };
        let index = self.base.index();
        let (points, slots) = (index.points(), index.payloads());
        let m = SquaredEuclidean;
        let mut best = (f64::INFINITY, usize::MAX);
        let mut visited = 0;
        let mut heap = BinaryHeap::new();
        if let Some((root, b)) = index.root() {
            heap.push(Pending(m.box_distance(&q, &b), root, b));
        }
        while let Some(Pending(d, v, b)) = heap.pop() {
            if d > bound(best.0) {
                break;
            }
            visited += 1;
            let leaf = !index.for_each_child_in(v, &b, |c, cb| {
                let cd = m.box_distance(&q, cb);
                if cd <= bound(best.0) {
                    heap.push(Pending(cd, c, *cb));
                }
            });
            if leaf {
                for i in index.run(v) {
                    let di = m.distance(&q, &points[i].map(Scalar::to_f64));
                    if (di, i) < best {
                        best = (di, i);
                    }
                }
            }
        }
        let found = (best.1 != usize::MAX).then(|| Neighbor {
            point: &points[best.1],
            item: &self.base.items()[slots[best.1] as usize],
            distance: best.0,
            index: slots[best.1] as usize,
        });
        Ok((found, visited))
    }
}

/// A node waiting in the best-first search, nearest box on top.
struct Pending<const D: usize>(f64, u32, Aabb<f64, D>);

impl<const D: usize> PartialEq for Pending<D> {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl<const D: usize> Eq for Pending<D> {}

impl<const D: usize> PartialOrd for Pending<D> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl<const D: usize> Ord for Pending<D> {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}

impl<S: Scalar, T, const D: usize> PointSet<D> for SkipQuadtree<S, T, D> {
    type Scalar = S;
    type Item = T;
    type Index = CompressedIndex<S, D>;

    #[inline]
    fn index(&self) -> &CompressedIndex<S, D> {
        self.base.index()
    }

    #[inline(always)]
    fn item_of<'a>(&'a self, payload: &'a u32) -> &'a T {
        self.base.item_of(payload)
    }

    #[inline(always)]
    fn slot_of(&self, position: usize, payload: &u32) -> usize {
        self.base.slot_of(position, payload)
    }

    #[inline]
    fn position_slots(&self) -> PositionSlots<'_> {
        self.base.position_slots()
    }

    #[inline]
    fn items(&self) -> &[T] {
        self.base.items()
    }

    #[inline]
    fn point(&self, slot: usize) -> &[S; D] {
        self.base.point(slot)
    }

    /// The closed box every point lies in.
    fn domain(&self) -> &Aabb<f64, D> {
        self.base.domain()
    }

    /// Checks level 0 ([`CompressedTree::validate`](crate::query::PointSet::validate)) and every level above: a valid canonical
    /// compressed quadtree over exactly the keys of the level below whose height reaches it,
    /// each node linked down to the node with its cell; no empty level on top.
    fn validate(&self) -> Result<(), ValidationError> {
        self.base.validate()?;
        use crate::error::Invariant as I;
        for i in 1..=self.levels.len() {
            let (level, below) = (self.level(i), self.level(i - 1));
            if let Err(e) = level.validate() {
                return Err(ValidationError::new(I::Topology).detail(format!("level {i}: {e}")));
            }
            let keys = |t: &Topology<D>| -> Vec<DeepKey<D>> {
                let leaves = t.pre_order().filter(|&v| t.is_leaf(v));
                leaves.map(|v| t.node(v).cell.anchor()).collect()
            };
            let mut want = keys(below);
            want.retain(|k| self.height(k) >= i as u32);
            if keys(level) != want || want.is_empty() {
                return Err(ValidationError::new(I::SkipLevels)
                    .detail(format!("level {i} does not hold its sample")));
            }
            let live: HashSet<u32> = below.pre_order().collect();
            for v in level.pre_order() {
                let w = level.node(v).down;
                if !live.contains(&w) || below.node(w).cell != level.node(v).cell {
                    return Err(ValidationError::new(I::SkipLevels)
                        .node(v)
                        .detail(format!("level {i}: badly linked down")));
                }
            }
        }
        Ok(())
    }
}

impl<S: Scalar, T, const D: usize> PointSetMut<D> for SkipQuadtree<S, T, D> {
    /// Inserts `item` at `point`. Expected O(log n).
    ///
    /// # Errors
    /// Those of [`CompressedTree::insert`](crate::query::PointSetMut::insert).
    fn insert(&mut self, point: [S; D], item: T) -> Result<(), InsertError<T>> {
        let key = match self.base.checked_insert_key(&point) {
            Ok(key) => key,
            Err(error) => return Err(InsertError { error, item }),
        };
        let path = self.search(&key, &mut 0);
        let mut below = self.base.insert_below(path[0], point, key, item);
        if !below.created {
            return Ok(());
        }
        for i in 1..=self.height(&key) as usize {
            if self.levels.len() < i {
                let mut fresh = Topology::new();
                fresh.nodes[0].down = 0;
                self.levels.push(fresh);
            }
            let start = path.get(i).copied().unwrap_or(0);
            let done = self.levels[i - 1].insert(start, &key);
            self.link_down(i, done, below);
            below = done;
        }
        Ok(())
    }

    /// Removes the first item stored at `point` that `wanted` accepts and returns it; `None` if
    /// there is none. Expected O(log n).
    fn remove_where(&mut self, point: &[S; D], wanted: impl Fn(&T) -> bool) -> Option<T> {
        let key = self.base.query_key(point).ok()?.inside()?;
        let path = self.search(&key, &mut 0);
        let (item, removed) = self.base.remove_in_leaf(path[0], &key, point, wanted)?;
        if removed != NIL {
            for (level, &v) in self.levels.iter_mut().zip(&path[1..]) {
                if level.is_leaf(v) && level.node(v).cell.anchor() == key {
                    level.remove_leaf(v);
                }
            }
            while self.levels.last().is_some_and(Topology::is_empty) {
                self.levels.pop();
            }
        }
        Some(item)
    }
}
