//! [`PointTreeBuilder`]: bulk construction of a [`PointTree`] by Morton sort.
//!
//! 1. Check every point (finite; inside the root box when one is given) and find the root cube
//!    (given, or the smallest enclosing cube: the chapter's linear scan of the extreme points),
//!    a block of 1024 points at a time without a branch per point, asking for the input 32
//!    points ahead (the processor's own prefetcher stops at each 4 KiB page: 15 -> 4.5
//!    ns/point for 3-D points at 10^6 and at 10^8).
//! 2. Quantise each point to its Morton key at the finest level ([`RootGeometry::key`]), which
//!    agrees exactly with the split convention; replace the key's low ceil(log2 n) bits by the
//!    point's input index ([`pack`]) and radix-sort these `u64`s; gather points and items in
//!    that order, asking the cache for the record 24 ahead, both its lines (`prefetch.rs`); put
//!    the rare runs whose keys agree above the index bits but differ below them in full key
//!    order ([`order_by_full_keys`]). The result is the (key, input index) order.
//!    Moving 8 bytes per point instead of a 16-byte (key, index) pair made the build 1.2x (2D)
//!    to 1.6x (3D) faster on 10^6 uniform points.
//! 3. Cut the sorted run into nodes top-down with an explicit stack: a node holding more than the
//!    bucket size splits, unless it is at the maximum depth; its children's runs are found by
//!    binary search on the next key digit. With bucket size 1 this is exactly the chapter's
//!    quadtree (section 14.2), all 2^D children of a split node present.
//!
//! Time O(n log n) for the sort plus O(m 2^D log n) for m nodes. Memory during the build: 16
//! bytes per point for the packed keys and the sort's buffer; after it, the points and
//! items plus 9 bytes per node (first child, level, run end) and 4 per child block (the arrays
//! are shrunk to fit). With [`PointTreeBuilder::map_pages_ahead`] a second thread maps these
//! fresh buffers while the build fills them (`huge_pages.rs`).

use super::PointTree;
use crate::error::Error;
use crate::geom::RootGeometry;
use crate::geom::{Aabb, Cell, Dim, Scalar};
use crate::huge_pages;
use crate::prefetch::{prefetch, LOOKAHEAD};
use crate::tree::{NodeId, Tree};

/// The bucket size used unless one is set: a leaf holds up to 64 points before it splits.
///
/// Chosen by measurement (`examples/compare`, 10^6 points, 2D and 3D, uniform, clustered,
/// duplicated and lattice points): against 16, the queries are as fast or faster (1-NN up to
/// 1.6x, since fewer and larger leaves stay in cache), and the nodes cost 0.60 (2D) and 0.51
/// (3D) bytes per point instead of 2.55 and 4.03; 128 measured the same within noise.
pub const DEFAULT_BUCKET_SIZE: usize = 64;

/// The build's split rule: a node at `level` holding `count` points splits when it holds more
/// than the bucket size and lies above the maximum depth (so duplicates never loop).
#[inline]
pub(crate) fn splits(count: usize, level: u8, bucket_size: usize, max_depth: u8) -> bool {
    count > bucket_size && level < max_depth
}

/// Settings for building a [`PointTree`]: root box, bucket size and maximum depth.
///
/// ```
/// use orthtree::prelude::*;
/// use orthtree::{Aabb, points::PointTreeBuilder};
/// let pts = [([1.0, 1.0], 'a'), ([3.0, 3.0], 'b'), ([3.5, 3.5], 'c')];
/// let t = PointTreeBuilder::new()
///     .root_box(Aabb::new([0.0, 0.0], [4.0, 4.0]).unwrap())
///     .bucket_size(1) // the chapter's quadtree
///     .build(&pts)
///     .unwrap();
/// assert_eq!(t.len(), 3);
/// // (3, 3) lies on the level-2 split line x = y = 3, so it goes to the lower child and
/// // parts from (3.5, 3.5) at level 2
/// assert_eq!(t.depth(), 2);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct PointTreeBuilder<S, const D: usize> {
    root: Option<Aabb<S, D>>,
    bucket_size: usize,
    max_depth: Option<u8>,
    map_ahead: bool,
}

impl<S: Scalar, const D: usize> Default for PointTreeBuilder<S, D> {
    fn default() -> Self {
        Self::new()
    }
}

impl<S: Scalar, const D: usize> PointTreeBuilder<S, D> {
    /// Defaults: the smallest enclosing cube, [`DEFAULT_BUCKET_SIZE`], depth up to
    /// [`Cell::MAX_LEVEL`].
    pub fn new() -> Self {
        let () = Dim::<D>::CHECK;
        PointTreeBuilder {
            root: None,
            bucket_size: DEFAULT_BUCKET_SIZE,
            max_depth: None,
            map_ahead: false,
        }
    }

    /// Every point must lie in this closed box; the tree subdivides the cube with the same lower
    /// corner and the box's largest extent as side.
    pub fn root_box(mut self, root: Aabb<S, D>) -> Self {
        self.root = Some(root);
        self
    }

    /// A leaf with more points than this splits (unless at the maximum depth). 1 gives the
    /// chapter's quadtree; 0 is refused by `build`.
    pub fn bucket_size(mut self, bucket_size: usize) -> Self {
        self.bucket_size = bucket_size;
        self
    }

    /// No leaf is split below this level; a leaf there keeps every point it gets, so duplicates
    /// never loop. At most [`Cell::MAX_LEVEL`] (32 in 2D, 21 in 3D).
    pub fn max_depth(mut self, max_depth: u8) -> Self {
        self.max_depth = Some(max_depth);
        self
    }

    /// With `true`, the serial builds ([`build`](Self::build), [`build_indexed`](Self::build_indexed),
    /// [`build_from_vec`](Self::build_from_vec)) start a second thread that asks the system to
    /// map their fresh buffers (the sort's keys and buffer, then the tree's points and items,
    /// about 44 bytes per point in 3-D with `u32` items) while this thread fills them, so that
    /// the first write to each page does not wait for the kernel to zero it. Off by default:
    /// the serial builds use one thread unless asked. It pays only for large inputs on a
    /// machine with a second core free; below 64 MiB of buffers, with one core, off Linux or
    /// without the feature `huge-pages` it changes nothing. The tree is the same either way.
    /// `par_build` keeps both cores busy and ignores it.
    ///
    /// Measured on a 2-core virtual machine (`examples/build_scale --runs 1`, three alternated
    /// cold builds of 10^8 uniform 3-D points): 69.1-77.3 ns/point against 118.4-133.9 without
    /// (the kernel's share of the time moves to the second thread), the same peak memory; at
    /// 10^7, 63.4-66.4 against 67.9-69.7.
    ///
    /// ```
    /// use orthtree::{points::PointTreeBuilder, PointSet};
    /// let pts: Vec<[f64; 3]> = (0..1000).map(|i| [i as f64, (i % 7) as f64, 0.5]).collect();
    /// let plain = PointTreeBuilder::new().build_indexed(&pts).unwrap();
    /// let ahead = PointTreeBuilder::new().map_pages_ahead(true).build_indexed(&pts).unwrap();
    /// assert_eq!(plain.items(), ahead.items());
    /// ```
    pub fn map_pages_ahead(mut self, on: bool) -> Self {
        self.map_ahead = on;
        self
    }

    /// The fresh buffers of `stages` to map ahead while a build fills them (see
    /// `huge_pages::while_populating`): all of them with
    /// [`map_pages_ahead`](Self::map_pages_ahead) on, none with it off.
    fn ahead<'r, 's>(
        &self,
        stages: &'s [&'r [core::ops::Range<usize>]],
    ) -> &'s [&'r [core::ops::Range<usize>]] {
        if self.map_ahead {
            stages
        } else {
            &[]
        }
    }

    /// The root box, bucket size and maximum depth set (the distributed build reads them).
    #[cfg(feature = "mpi")]
    pub(crate) fn settings(&self) -> (Option<Aabb<S, D>>, usize, Option<u8>) {
        (self.root, self.bucket_size, self.max_depth)
    }

    /// Builds from a slice of (point, item) pairs, cloning the items.
    ///
    /// # Errors
    /// [`Error::NonFiniteCoordinate`] or [`Error::InexactCoordinate`] for a coordinate that is NaN,
    /// infinite or an integer `f64` cannot hold, [`Error::OutsideRootBox`] for a point outside a
    /// given root box (each naming the point, axis and value), [`Error::InvalidRootBox`],
    /// [`Error::ZeroBucketSize`], [`Error::MaxDepthTooLarge`], [`Error::TooManyPoints`].
    pub fn build<T: Clone>(&self, entries: &[([S; D], T)]) -> Result<PointTree<S, T, D>, Error> {
        self.build_with(
            entries.len(),
            |i| &entries[i].0,
            |i, later| {
                prefetch(&entries[later]);
                entries[i].clone()
            },
        )
    }

    /// Builds from points alone, each point's item its position in `points` (as `u32`, which
    /// every tree's size fits), without copying the input into (point, item) pairs first.
    ///
    /// # Errors
    /// As [`PointTreeBuilder::build`].
    ///
    /// ```
    /// use orthtree::{PointSet, PointTree};
    /// let t = PointTree::builder().build_indexed(&[[3.0, 0.0], [1.0, 0.0], [1.0, 0.0]]).unwrap();
    /// assert_eq!(t.items(), [1, 2, 0]); // Morton order, equal points in input order
    /// assert_eq!(*t.point(2), [3.0, 0.0]);
    /// ```
    pub fn build_indexed(&self, points: &[[S; D]]) -> Result<PointTree<S, u32, D>, Error> {
        self.build_with(
            points.len(),
            |i| &points[i],
            |i, later| {
                prefetch(&points[later]);
                // `check_settings` refuses `u32::MAX` points or more: the position fits.
                (points[i], i as u32)
            },
        )
    }

    /// Builds from owned (point, item) pairs, moving the items.
    ///
    /// # Errors
    /// [`Error::NonFiniteCoordinate`] or [`Error::InexactCoordinate`] for a coordinate that is NaN,
    /// infinite or an integer `f64` cannot hold, [`Error::OutsideRootBox`] for a point outside a
    /// given root box (each naming the point, axis and value), [`Error::InvalidRootBox`],
    /// [`Error::ZeroBucketSize`], [`Error::MaxDepthTooLarge`], [`Error::TooManyPoints`].
    pub fn build_from_vec<T>(
        &self,
        entries: Vec<([S; D], T)>,
    ) -> Result<PointTree<S, T, D>, Error> {
        let (points, mut items): (Vec<[S; D]>, Vec<Option<T>>) =
            entries.into_iter().map(|(p, item)| (p, Some(item))).unzip();
        self.build_with(
            points.len(),
            |i| &points[i],
            |i, later| {
                prefetch(&points[later]);
                prefetch(&items[later]);
                (
                    points[i],
                    items[i].take().expect("each input index is taken once"),
                )
            },
        )
    }

    /// The build over `n` points: `point(i)` reads point `i`; `take(i, later)` moves or clones
    /// entry `i` out, and may [`prefetch`] entry `later`, the one it will be asked for
    /// [`LOOKAHEAD`] calls from now.
    fn build_with<'p, T>(
        &self,
        n: usize,
        point: impl Fn(usize) -> &'p [S; D],
        mut take: impl FnMut(usize, usize) -> ([S; D], T),
    ) -> Result<PointTree<S, T, D>, Error>
    where
        S: 'p,
    {
        let root = self.check_settings(n)?;
        // With `map_pages_ahead`, fresh buffers are mapped on another core while this one
        // fills them, each before its first write: the keys while the input is checked, the
        // sort's buffer while the keys are made, then the points and items while they are
        // gathered.
        let mut packed: Vec<u64> = huge_pages::with_capacity(n);
        let mut buffer = super::radix::sort_buffer(n);
        let (keys, scratch) = (
            [huge_pages::allocation(&packed)],
            [huge_pages::allocation(&buffer)],
        );
        let (geometry, domain, bits) =
            huge_pages::while_populating(self.ahead(&[&keys, &scratch]), || {
                let bounds = scan(root.as_ref(), 0..n, &point)?;
                let (geometry, domain) = settle(root, bounds, n);
                let bits = index_bits(n);
                geometry.keys_into(n, &point, |i, key| packed.push(pack(key, i, bits)));
                super::radix::sort_keyed_in(&mut packed, &mut buffer);
                Ok::<_, Error>((geometry, domain, bits))
            })?;
        drop(buffer);
        let mut points = huge_pages::with_capacity(n);
        let mut items = huge_pages::with_capacity(n);
        let fresh = [
            huge_pages::allocation(&points),
            huge_pages::allocation(&items),
        ];
        // The gather reads the input in Morton order, at random for scattered points: ask for
        // the records ahead so that their cache misses overlap.
        huge_pages::while_populating(self.ahead(&[&fresh]), || {
            for (j, &k) in packed.iter().enumerate() {
                let (p, item) = take(unpack_index(k, bits), later_index(&packed, j, bits));
                points.push(p);
                items.push(item);
            }
        });
        Ok(self.assemble(geometry, domain, packed, bits, points, items))
    }

    /// The tree over points and items gathered in the order of `packed` (sorted, see [`pack`]):
    /// puts points whose keys agree above the index bits in full key order
    /// ([`order_by_full_keys`]), then subdivides the root down to the buckets.
    pub(super) fn assemble<T>(
        &self,
        geometry: RootGeometry<D>,
        domain: Aabb<f64, D>,
        mut packed: Vec<u64>,
        bits: u32,
        mut points: Vec<[S; D]>,
        mut items: Vec<T>,
    ) -> PointTree<S, T, D> {
        order_by_full_keys(&geometry, &mut packed, bits, &mut points, &mut items);
        let n = points.len();
        let mut tree = PointTree {
            tree: Tree::new(),
            geometry,
            domain,
            points,
            items,
            runs: super::Runs::new(n),
            bucket_size: self.bucket_size,
            max_depth: self.max_depth.unwrap_or(Cell::<D>::MAX_LEVEL),
            balanced: None,
        };
        // A digit below the index bits needs the full key (only in cells deeper than
        // (64 - bits) / D levels).
        tree.subdivide(NodeId::ROOT, |points, i, level| {
            if D as u32 * u32::from(Cell::<D>::MAX_LEVEL - level - 1) >= bits {
                packed[i]
            } else {
                geometry.scalar_key(&points[i])
            }
        });
        // The node arrays grew by doubling: up to half their memory is spare.
        tree.tree.shrink_to_fit();
        tree.runs.shrink_to_fit();
        tree
    }

    /// Checks the settings for `n` points; returns the root box given, if any, as `f64`.
    pub(crate) fn check_settings(&self, n: usize) -> Result<Option<Aabb<f64, D>>, Error> {
        if self.bucket_size == 0 {
            return Err(Error::ZeroBucketSize);
        }
        if let Some(requested) = self.max_depth
            && requested > Cell::<D>::MAX_LEVEL
        {
            return Err(Error::MaxDepthTooLarge {
                requested,
                limit: Cell::<D>::MAX_LEVEL,
            });
        }
        if n >= u32::MAX as usize {
            return Err(Error::TooManyPoints { len: n });
        }
        (self.root.as_ref())
            .map(|root| Ok(Aabb::new(root.min, root.max)?.to_exact_f64()?))
            .transpose()
    }
}

/// Checks the points with indices in `range` (finite, inside `root` when given) and returns
/// their bounding box (min above max for an empty range).
///
/// A block of points at a time: its bounds and one flag for all its checks, without a
/// branch per point; only a block whose flag is down is checked again point by point, for
/// the error naming its first bad point (the one a point-by-point scan would report).
pub(crate) fn scan<'p, S: Scalar + 'p, const D: usize>(
    root: Option<&Aabb<f64, D>>,
    range: core::ops::Range<usize>,
    point: &impl Fn(usize) -> &'p [S; D],
) -> Result<Aabb<f64, D>, Error> {
    const BLOCK: usize = 1024;
    const SCAN_AHEAD: usize = 32;
    let mut bounds = Aabb::empty();
    let (lower, upper) = root.map_or(([f64::MIN; D], [f64::MAX; D]), |r| (r.min, r.max));
    for start in range.clone().step_by(BLOCK) {
        let block = start..(start + BLOCK).min(range.end);
        let mut fine = true;
        let mut block_bounds = Aabb::<f64, D>::empty();
        for index in block.clone() {
            prefetch(point((index + SCAN_AHEAD).min(range.end - 1)));
            let p = point(index);
            for a in 0..D {
                let x = p[a].to_f64();
                fine &= p[a].converts_exactly() & (lower[a] <= x) & (x <= upper[a]);
                block_bounds.min[a] = block_bounds.min[a].min(x);
                block_bounds.max[a] = block_bounds.max[a].max(x);
            }
        }
        if !fine {
            for index in block {
                Error::check_input(point(index), root, index)?;
            }
        }
        bounds.add_box(&block_bounds);
    }
    Ok(bounds)
}

/// Hands each point of `points` to `visit`, with its input index and the Morton key of its
/// cell at `level` ([`Cell::morton`]), grouped by cell in Morton order: the build's keys and
/// radix sort, for work on the cells of one level (voxels) that needs no tree (no points or
/// items gathered, no nodes). The points must lie in the geometry's cube (checked by
/// [`scan`]); the order within a cell is not promised. With `read` (`visit` reads the points)
/// the point [`LOOKAHEAD`] ahead in key order is asked for, as the gather does; without it no
/// point is touched after the keys.
///
/// Memory: 16 bytes per point (an 8-byte (key, index) pair and the sort's buffer) while the
/// index fits below the level's digits, else 32.
pub(crate) fn visit_by_cell<S: Scalar, const D: usize>(
    geometry: &RootGeometry<D>,
    points: &[[S; D]],
    level: u8,
    read: bool,
    visit: impl FnMut(u64, usize, &[S; D]),
) {
    let n = points.len();
    let below = D as u32 * u32::from(Cell::<D>::MAX_LEVEL - level);
    let cell = move |key: u64| key.checked_shr(below).unwrap_or(0);
    let bits = index_bits(n);
    if bits <= below {
        let pair = |key, i| pack(key, i, bits);
        let split = |p: u64| (cell(p), unpack_index(p, bits));
        visit_sorted(geometry, points, read, pair, split, visit);
    } else {
        let pair = |key, i| u128::from(key) << 32 | i as u128;
        let split = |p: u128| (cell((p >> 32) as u64), p as u32 as usize);
        visit_sorted(geometry, points, read, pair, split, visit);
    }
}

/// [`visit_by_cell`] with `pair(key, index)` a point's packed pair and `split` the (cell,
/// index) of a pair.
fn visit_sorted<P: super::radix::Packed, S: Scalar, const D: usize>(
    geometry: &RootGeometry<D>,
    points: &[[S; D]],
    read: bool,
    pair: impl Fn(u64, usize) -> P,
    split: impl Fn(P) -> (u64, usize),
    mut visit: impl FnMut(u64, usize, &[S; D]),
) {
    let mut pairs = huge_pages::with_capacity(points.len());
    geometry.keys_into(
        points.len(),
        |i| &points[i],
        |i, key| pairs.push(pair(key, i)),
    );
    super::radix::sort_keyed(&mut pairs);
    for (j, &p) in pairs.iter().enumerate() {
        if read {
            let later = pairs.get(j + LOOKAHEAD).unwrap_or(&p);
            prefetch(&points[split(*later).1]);
        }
        let (cell, index) = split(p);
        visit(cell, index, &points[index]);
    }
}

/// The number of low key bits [`pack`] gives to the index for `n` points: enough for `n - 1`.
#[inline]
pub(crate) fn index_bits(n: usize) -> u32 {
    (usize::BITS - n.saturating_sub(1).leading_zeros()).max(1)
}

/// Morton key `key` with its low `bits` bits replaced by `index`: sorting these sorts the points
/// by their keys' high bits, then by input index (8 bytes per point; a `u128` pair moves 16).
/// Points whose keys differ only in the low bits are put in order after the gather
/// ([`order_by_full_keys`]): with 2^bits >= n they are rare unless the points crowd into cells
/// deeper than (64 - bits) / D levels.
#[inline]
pub(crate) fn pack(key: u64, index: usize, bits: u32) -> u64 {
    (key >> bits << bits) | index as u64
}

/// The input index the gather reads [`LOOKAHEAD`] steps after step `j` (its own at the end),
/// for it to [`prefetch`].
#[inline]
pub(super) fn later_index(packed: &[u64], j: usize, bits: u32) -> usize {
    let later = packed.get(j + LOOKAHEAD).unwrap_or(&packed[j]);
    unpack_index(*later, bits)
}

/// The input index of a [`pack`]ed key.
#[inline]
pub(crate) fn unpack_index(packed: u64, bits: u32) -> usize {
    (packed & ((1u64 << bits) - 1)) as usize
}

/// Puts each run of `points` (with `items` and `packed`) whose packed keys agree above the
/// index bits into (full key, input index) order; a run of copies of one point, the common
/// case, is already in input order and is only compared. O(n) plus O(r log r) per run of r
/// distinct points.
pub(crate) fn order_by_full_keys<S: Scalar, T, const D: usize>(
    geometry: &RootGeometry<D>,
    packed: &mut [u64],
    bits: u32,
    points: &mut [[S; D]],
    items: &mut [T],
) {
    let mut start = 0;
    while start + 1 < packed.len() {
        // Most neighbours differ above the index bits: skip them without a branch per point.
        let Some(at) = packed[start..]
            .windows(2)
            .position(|w| (w[0] ^ w[1]) >> bits == 0)
        else {
            return;
        };
        start += at;
        let high = packed[start] >> bits;
        let end = start
            + packed[start..]
                .iter()
                .take_while(|&&k| k >> bits == high)
                .count();
        if points[start + 1..end].iter().any(|p| *p != points[start]) {
            let mut order: Vec<(u64, u64, usize)> = (start..end)
                .map(|i| (geometry.scalar_key(&points[i]), packed[i], i))
                .collect();
            order.sort_unstable();
            // Old position `order[j].2` goes to `j`: move each along its cycle by swaps.
            let mut dest = vec![0; order.len()];
            for (j, o) in order.iter().enumerate() {
                dest[o.2 - start] = j;
            }
            for i in 0..dest.len() {
                while dest[i] != i {
                    let d = dest[i];
                    points.swap(start + i, start + d);
                    items.swap(start + i, start + d);
                    packed.swap(start + i, start + d);
                    dest.swap(i, d);
                }
            }
        }
        start = end;
    }
}

/// The pair `key << 32 | index` of point `p` with input index `index`: sorting the pairs sorts
/// by (key, index), faster than sorting tuples.
#[inline]
pub(super) fn key_pair<S: Scalar, const D: usize>(
    geometry: &RootGeometry<D>,
    p: &[S; D],
    index: usize,
) -> u128 {
    ((geometry.scalar_key(p) as u128) << 32) | index as u128
}

/// The root geometry and the domain points must lie in: the root box given, or the smallest
/// enclosing cube of the points' `bounds` (the unit box when there are no points: the chapter's
/// linear scan of the extreme points gives `bounds`).
///
/// The cube's far side rounds to infinity on the axes where its side exceeds `f64::MAX`
/// minus the lower corner (points spanning more than `f64::MAX` on some axis, or near it on
/// one axis and far apart on another); its lower side never does. There the domain stops at
/// `f64::MAX`: it holds every finite point the cube holds, so insertions, locations and checks
/// answer as the cube's box would, and it stays a box of finite corners ([`Aabb::new`]'s),
/// which the saved format, serde (JSON has no infinities) and every tree read back require.
pub(crate) fn settle<const D: usize>(
    root: Option<Aabb<f64, D>>,
    bounds: Aabb<f64, D>,
    n: usize,
) -> (RootGeometry<D>, Aabb<f64, D>) {
    match root {
        Some(root) => (RootGeometry::enclosing(&root), root),
        None => {
            let bounds = if n == 0 {
                Aabb::around(&[[0.0; D], [1.0; D]])
            } else {
                bounds
            };
            let geometry = RootGeometry::enclosing(&bounds);
            let mut domain = geometry.root_box();
            domain.max = domain.max.map(|x| x.min(f64::MAX));
            (geometry, domain)
        }
    }
}
