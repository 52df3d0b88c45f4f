//! [`DistPointTreeBuilder`]: the distributed build of a [`DistPointTree`] from points
//! scattered arbitrarily over the ranks.
//!
//! 1. Agreement: every rank's settings against rank 0's, then every rank's point check (finite,
//!    exact, inside a given root box) with one gathered word per rank; the lowest failing rank
//!    broadcasts its bad point and every rank rebuilds the same [`Error`] from it. The same
//!    gather carries each rank's count and bounding box: the global count, each rank's offset
//!    in the union and the root box (given, or the smallest enclosing cube of all points: the
//!    single-process build's, exactly).
//! 2. Keys: each point's Morton key over the global root box, packed with its index in the
//!    union (the single-process build's packed key, `points/build.rs`).
//! 3. Sample sort (Blelloch et al. 1991, "A comparison of sorting algorithms for the
//!    Connection Machine CM-2"; regular sampling as in Shi and Schaeffer 1992): each rank
//!    sends 64 P samples of its keys' high bits, weighted by its count; P - 1 splitters at
//!    the weighted quantiles; each point goes to the rank its high bits fall in, all points
//!    of equal high bits to one rank, with one all-to-all exchange (`MPI_Alltoallv`).
//! 4. Each rank radix-sorts what it received (received position in the low bits: within
//!    equal high bits that is the order of the index in the union), gathers, and puts equal
//!    high bits in full key order, as the single-process build does.
//! 5. Counts evened out ([`Partition::uniform`]): only the ends of the runs move, with a
//!    second exchange; then the local [`PointTree`] over the global root geometry.

use super::comm::{self, point_bytes, Words};
use super::{DistError, DistPointTree, Partition};
use crate::error::Error;
use crate::geom::{Aabb, Cell, Scalar};
use crate::points::{index_bits, order_by_full_keys, pack, settle, sort_keyed, PointTreeBuilder};
use crate::prefetch::{prefetch, LOOKAHEAD};
use crate::PointTree;
use bytemuck::Pod;
use mpi::traits::Communicator;

/// Samples per rank and splitter in the sample sort.
const OVERSAMPLE: usize = 64;

/// The most points a distributed tree holds in total: packed keys keep 16 bits of key above
/// the index.
pub const MAX_TOTAL: u64 = 1 << 48;

/// Settings for building a [`DistPointTree`]: those of [`PointTreeBuilder`], which must be
/// the same on every rank.
///
/// ```
/// use orthtree::{dist::DistPointTreeBuilder, Aabb};
/// let universe = mpi::initialize().unwrap();
/// let world = universe.world();
/// let t = DistPointTreeBuilder::new()
///     .root_box(Aabb::new([0.0, 0.0], [1.0, 1.0]).unwrap())
///     .bucket_size(16)
///     .build(&world, &[([0.5, 0.5], 7u32)])
///     .unwrap();
/// assert!(t.len() >= 1);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct DistPointTreeBuilder<S, const D: usize> {
    inner: PointTreeBuilder<S, D>,
}

impl<S: Scalar + Pod, const D: usize> Default for DistPointTreeBuilder<S, D> {
    fn default() -> Self {
        Self::new()
    }
}

impl<S: Scalar + Pod, const D: usize> DistPointTree<S, (), D> {
    /// A builder; the item type comes from what it builds.
    pub fn builder() -> DistPointTreeBuilder<S, D> {
        DistPointTreeBuilder::new()
    }
}

impl<S: Scalar + Pod, const D: usize> DistPointTreeBuilder<S, D> {
    /// The defaults of [`PointTreeBuilder::new`].
    pub fn new() -> Self {
        DistPointTreeBuilder {
            inner: PointTreeBuilder::new(),
        }
    }

    /// [`PointTreeBuilder::root_box`].
    pub fn root_box(mut self, root: Aabb<S, D>) -> Self {
        self.inner = self.inner.root_box(root);
        self
    }

    /// [`PointTreeBuilder::bucket_size`].
    pub fn bucket_size(mut self, bucket_size: usize) -> Self {
        self.inner = self.inner.bucket_size(bucket_size);
        self
    }

    /// [`PointTreeBuilder::max_depth`].
    pub fn max_depth(mut self, max_depth: u8) -> Self {
        self.inner = self.inner.max_depth(max_depth);
        self
    }

    /// [`DistPointTreeBuilder::build_from_vec`] from a slice.
    ///
    /// # Errors
    /// Those of [`DistPointTreeBuilder::build_from_vec`].
    pub fn build<T: Pod>(
        &self,
        comm: &impl Communicator,
        entries: &[([S; D], T)],
    ) -> Result<DistPointTree<S, T, D>, DistError> {
        self.build_from_vec(comm, entries.to_vec())
    }

    /// Builds from this rank's (point, item) pairs (collective: every rank calls it with its
    /// own points, any number, and the same settings). The tree equals the single-process
    /// tree over the union of the inputs in rank order, split over the ranks by counts.
    ///
    /// # Errors
    /// The same on every rank: [`DistError::SettingsDiffer`]; [`DistError::Input`] with what
    /// [`PointTreeBuilder::build`] refuses (a setting, or the first bad point of the lowest
    /// rank with one, by its index on that rank); [`DistError::TooManyPoints`] past
    /// [`MAX_TOTAL`] or when one rank's share would exceed a `u32` index;
    /// [`DistError::MessageTooLarge`].
    ///
    /// # Complexity
    /// O(n log n / P) work per rank for n points in all on P ranks with well-spread splitters,
    /// plus two all-to-all exchanges, the first moving about n (P - 1) / P points in all.
    pub fn build_from_vec<T: Pod>(
        &self,
        comm: &impl Communicator,
        entries: Vec<([S; D], T)>,
    ) -> Result<DistPointTree<S, T, D>, DistError> {
        let comm = comm.duplicate();
        let (rank, ranks) = comm::rank_size(&comm);
        let mut clock = Clock::new();
        let root = self.agree_settings(&comm)?;
        let (points, items): (Vec<[S; D]>, Vec<T>) = entries.into_iter().unzip();
        let n = points.len();
        let scan = crate::points::scan(root.as_ref(), 0..n, &|i| &points[i]);
        agree_points(&comm, &scan, &points, root.as_ref())?;
        let bounds = scan.expect("agreed: no rank failed");
        // Counts and bounds of every rank.
        let mut mine = vec![n as u64];
        mine.extend(bounds.min.iter().chain(&bounds.max).map(|x| x.to_bits()));
        let all = comm::all_gather(&comm, &mine);
        let per = 1 + 2 * D;
        let counts: Vec<u64> = all.chunks(per).map(|w| w[0]).collect();
        let total: u64 = counts.iter().sum();
        let share = total.div_ceil(ranks as u64);
        if total > MAX_TOTAL || share >= u64::from(u32::MAX) {
            let limit = MAX_TOTAL.min((u64::from(u32::MAX) - 1) * ranks as u64);
            return Err(DistError::TooManyPoints { len: total, limit });
        }
        let mut global = Aabb::empty();
        for w in all.chunks(per) {
            global.add_box(&box_from_words(&w[1..]));
        }
        let (geometry, domain) = settle(root, global, total as usize);
        let offset = counts[..rank].iter().sum::<u64>() as usize;
        clock.lap("agree");

        let bits = index_bits(total as usize);
        let mut packed = Vec::with_capacity(n);
        geometry.keys_into(
            n,
            |i| &points[i],
            |i, key| packed.push(pack(key, offset + i, bits)),
        );
        let splitters = splitters(&comm, &packed, bits, &counts);
        clock.lap("keys");

        // Bin by destination, stably (in input order within a destination).
        let dest = |p: u64| splitters.partition_point(|&s| s < p >> bits);
        let mut send_counts = vec![0usize; ranks];
        for &p in &packed {
            send_counts[dest(p)] += 1;
        }
        let bytes = 8 + point_bytes::<S, D>() + core::mem::size_of::<T>();
        let mut words = Words::with_records(n, bytes);
        let mut at = comm::starts(&send_counts);
        for (i, &p) in packed.iter().enumerate() {
            let d = dest(p);
            words.writer(at[d]).put(&p).put(&points[i]).put(&items[i]);
            at[d] += 1;
        }
        drop((points, items, packed));
        let (recv, _) = words.exchange(&comm, &send_counts)?;
        let per = recv.per;
        clock.lap("exchange");

        let m = recv.len();
        // Received position j in the low bits: within equal high bits, j follows the index in
        // the union (senders in rank order, each in input order).
        let mut local: Vec<u64> = (0..m)
            .map(|j| pack(recv.reader(j).get::<u64>(), j, bits))
            .collect();
        sort_keyed(&mut local);
        let mut points = Vec::with_capacity(m);
        let mut items = Vec::with_capacity(m);
        let mask = (1u64 << bits) - 1;
        for (i, &k) in local.iter().enumerate() {
            if let Some(&later) = local.get(i + LOOKAHEAD) {
                prefetch(&recv.words[(later & mask) as usize * per]);
            }
            let mut r = recv.reader((k & mask) as usize);
            let _: u64 = r.get();
            points.push(r.get::<[S; D]>());
            items.push(r.get::<T>());
        }
        drop(recv);
        order_by_full_keys(&geometry, &mut local, bits, &mut points, &mut items);
        drop(local);
        clock.lap("sort");

        let first_key = |p: &Vec<[S; D]>| p.first().map(|p| geometry.scalar_key(p));
        let sorted = Partition::gather(&comm, m, first_key(&points))?;
        let (points, items) = even_out(&comm, &sorted, points, items)?;
        clock.lap("even");

        let (_, bucket_size, max_depth) = self.inner.settings();
        let partition = Partition::gather(&comm, points.len(), first_key(&points))?;
        let b = Aabb::around(&points);
        let local = PointTree::from_sorted_parts(
            (geometry, domain, points, items),
            bucket_size,
            max_depth.unwrap_or(Cell::<D>::MAX_LEVEL),
        );
        let words: Vec<u64> = b.min.iter().chain(&b.max).map(|x| x.to_bits()).collect();
        let boxes = comm::all_gather(&comm, &words)
            .chunks(2 * D)
            .map(box_from_words)
            .collect();
        clock.lap("local tree");
        Ok(DistPointTree {
            comm,
            local,
            partition,
            boxes,
            phases: clock.phases,
        })
    }

    /// Checks that every rank has rank 0's settings, then the settings themselves (the same
    /// result on every rank); returns the root box, if given, in `f64`.
    fn agree_settings(&self, comm: &impl Communicator) -> Result<Option<Aabb<f64, D>>, DistError> {
        let (root, bucket_size, max_depth) = self.inner.settings();
        let mut mine = vec![
            bucket_size as u64,
            max_depth.map_or(u64::MAX, u64::from),
            u64::from(root.is_some()),
        ];
        for a in 0..D {
            let (lo, hi) = root.map_or((0.0, 0.0), |r| (r.min[a].to_f64(), r.max[a].to_f64()));
            mine.extend([lo.to_bits(), hi.to_bits()]);
        }
        let all = comm::all_gather(comm, &mine);
        // Every rank has every rank's settings: the lowest differing rank is the same on each.
        if let Some(rank) = all.chunks(mine.len()).position(|w| w != &all[..mine.len()]) {
            return Err(DistError::SettingsDiffer { rank });
        }
        self.inner
            .check_settings(0)
            .map_err(|error| DistError::Input { rank: 0, error })
    }
}

/// The agreement on the points: if a rank's scan failed, the lowest such rank sends its bad
/// point and index, and every rank returns the error the point check gives for it.
fn agree_points<S: Scalar + Pod, const D: usize>(
    comm: &impl Communicator,
    scan: &Result<Aabb<f64, D>, Error>,
    points: &[[S; D]],
    root: Option<&Aabb<f64, D>>,
) -> Result<(), DistError> {
    let Some(rank) = comm::lowest_failing(comm, scan.is_err()) else {
        return Ok(());
    };
    let mut w = Words::with_records(1, 8 + point_bytes::<S, D>());
    if let Err(e) = scan {
        let index = point_index(e);
        w.writer(0).put(&(index as u64)).put(&points[index]);
    }
    comm::broadcast(comm, rank, &mut w.words);
    let mut r = w.reader(0);
    let index = r.get::<u64>() as usize;
    let point: [S; D] = r.get();
    let error = Error::check_input(&point, root, index)
        .expect_err("the point check is the same on every rank");
    Err(DistError::Input { rank, error })
}

/// The point an error of the point check names.
fn point_index(e: &Error) -> usize {
    match e {
        Error::NonFiniteCoordinate { index, .. }
        | Error::InexactCoordinate { index, .. }
        | Error::OutsideRootBox { index, .. } => *index,
        _ => unreachable!("the point check names a point"),
    }
}

/// The sample sort's splitters (the same on every rank): `OVERSAMPLE * P` evenly spaced keys'
/// high bits from each rank, each weighted by its rank's count over its samples; splitter `t`
/// is the first sample at which the weight reaches total t / P.
fn splitters(comm: &impl Communicator, packed: &[u64], bits: u32, counts: &[u64]) -> Vec<u64> {
    let ranks = counts.len();
    if ranks == 1 {
        return Vec::new();
    }
    let n = packed.len();
    let s = n.min(OVERSAMPLE * ranks);
    let mut mine: Vec<u64> = (0..s).map(|j| packed[j * n / s] >> bits).collect();
    mine.sort_unstable();
    let (all, sizes) = comm::all_gather_var(comm, &mine);
    let mut weighted: Vec<(u64, f64)> = Vec::with_capacity(all.len());
    let mut at = 0;
    for (r, &size) in sizes.iter().enumerate() {
        let w = counts[r] as f64 / size.max(1) as f64;
        weighted.extend(all[at..at + size].iter().map(|&v| (v, w)));
        at += size;
    }
    weighted.sort_unstable_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let total: f64 = counts.iter().sum::<u64>() as f64;
    let mut out = Vec::with_capacity(ranks - 1);
    let mut acc = 0.0;
    let mut it = weighted.iter();
    for t in 1..ranks {
        let goal = total * t as f64 / ranks as f64;
        let mut v = out.last().copied().unwrap_or(0);
        while acc < goal {
            match it.next() {
                Some(&(value, w)) => {
                    acc += w;
                    v = value;
                }
                None => {
                    v = u64::MAX;
                    break;
                }
            }
        }
        out.push(v);
    }
    out
}

/// Moves the ends of the runs so that the counts follow [`Partition::uniform`] (one exchange;
/// the middle of each run stays in place).
fn even_out<S: Scalar + Pod, T: Pod, const D: usize>(
    comm: &impl Communicator,
    sorted: &Partition,
    points: Vec<[S; D]>,
    items: Vec<T>,
) -> Result<(Vec<[S; D]>, Vec<T>), DistError> {
    let (rank, ranks) = comm::rank_size(comm);
    let targets = Partition::uniform(sorted.len(), ranks);
    let mine = sorted.range(rank);
    // The part of this rank's run that rank r gets, in local positions.
    let part = |r: usize| {
        let lo = targets[r].clamp(mine.start, mine.end) - mine.start;
        let hi = targets[r + 1].clamp(mine.start, mine.end) - mine.start;
        lo as usize..hi as usize
    };
    let keep = part(rank);
    let bytes = point_bytes::<S, D>() + core::mem::size_of::<T>();
    let leaving = points.len() - keep.len();
    let mut words = Words::with_records(leaving, bytes);
    let mut counts = vec![0usize; ranks];
    let mut w = 0;
    for r in (0..ranks).filter(|&r| r != rank) {
        for i in part(r) {
            words.writer(w).put(&points[i]).put(&items[i]);
            w += 1;
        }
        counts[r] = part(r).len();
    }
    let (recv, from) = words.exchange(comm, &counts)?;
    let before: usize = from[..rank].iter().sum();
    let mut out_points = Vec::with_capacity(keep.len() + recv.len());
    let mut out_items = Vec::with_capacity(keep.len() + recv.len());
    let take = |js: core::ops::Range<usize>, points: &mut Vec<[S; D]>, items: &mut Vec<T>| {
        for j in js {
            let mut r = recv.reader(j);
            points.push(r.get::<[S; D]>());
            items.push(r.get::<T>());
        }
    };
    take(0..before, &mut out_points, &mut out_items);
    out_points.extend_from_slice(&points[keep.clone()]);
    out_items.extend_from_slice(&items[keep]);
    take(before..recv.len(), &mut out_points, &mut out_items);
    Ok((out_points, out_items))
}

/// The box whose corners' coordinates `words` holds as bits, the minimum corner's first.
fn box_from_words<const D: usize>(words: &[u64]) -> Aabb<f64, D> {
    Aabb {
        min: core::array::from_fn(|a| f64::from_bits(words[a])),
        max: core::array::from_fn(|a| f64::from_bits(words[D + a])),
    }
}

/// Wall-clock phase times.
struct Clock {
    start: f64,
    phases: Vec<(&'static str, f64)>,
}

impl Clock {
    fn new() -> Self {
        Clock {
            start: mpi::time(),
            phases: Vec::new(),
        }
    }

    fn lap(&mut self, name: &'static str) {
        let now = mpi::time();
        self.phases.push((name, now - self.start));
        self.start = now;
    }
}
