//! The sort and gather of the bulk build for many points: the records (point, item, packed key)
//! are distributed by the top bits of their packed keys into cache-sized buckets, reading the
//! input once in order; each bucket is then sorted by radix sort and put in order inside the
//! cache.
//!
//! This is one most-significant-digit radix pass over the whole records followed by a
//! cache-sized sort per bucket: the "MSD pass, then sort the buckets" scheme of radix sorts
//! for data larger than cache (Rahman and Raman, "Adapting radix sort to the memory
//! hierarchy", ACM Journal of Experimental Algorithmics 6, 2001). Gathering records in sorted
//! order straight from the input instead reads it at random: beyond a few million points each
//! read misses the cache and the address translation buffer, and the build's cost per point
//! grew with n (the gather alone, timed on a shared machine: 10 ns per point at 10^6 points,
//! 60 at 10^7, 205 at 10^8).
//!
//! Stages, each a sequential pass or a pass within one bucket:
//! 1. count the points of each bucket (per chunk of the input, so chunks can be scattered in
//!    parallel);
//! 2. scatter: read the input in order and write each point and packed key to the next free
//!    slot of its bucket (stable: a bucket holds its points in input order), each item to its
//!    bucket's vector;
//! 3. finish each bucket: sort its keys, with the low bits holding the position in the bucket
//!    instead of the input index (the same order: positions follow input indices in a bucket),
//!    then move its points and keys into that order through a copy and its items along the
//!    permutation's cycles.
//!
//! The result is exactly the order of sorting the packed keys ([`super::radix::sort_keyed`]).
//! Time O(n) for uniform points plus the buckets' sorts; memory besides the result: 8 bytes
//! per point for the bucketed keys (the input's keys are dropped after the scatter), the items
//! in their buckets until each is appended to the result, and a copy of the largest bucket's
//! points and keys.

use super::radix;

/// The number of points a bucket aims at: its keys and points (about 32 bytes a point in 3D)
/// then fit the second-level cache of current processors.
const BUCKET_TARGET: usize = 1 << 14;

/// The widest digit: a scatter into more than 2^11 buckets writes to too many places at once
/// for the caches and the address translation buffer.
const MAX_DIGIT_BITS: u32 = 11;

/// The bits of the packed keys the records are distributed by.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Digit {
    /// The lowest bit of the digit.
    shift: u32,
    /// The digit's width in bits (0: one bucket).
    width: u32,
    /// Bits at and above this one are equal in every key.
    top: u32,
}

impl Digit {
    /// The digit for `n` keys whose bits that differ are the ones set in `differ` (the
    /// bitwise AND of the keys xor their OR): the highest bits that differ, as many as give
    /// buckets of about [`BUCKET_TARGET`] points.
    pub(super) fn choose(n: usize, differ: u64) -> Digit {
        let wanted = n
            .div_ceil(BUCKET_TARGET)
            .next_power_of_two()
            .trailing_zeros();
        let top = u64::BITS - differ.leading_zeros();
        let width = wanted.min(MAX_DIGIT_BITS).min(top);
        Digit {
            shift: top - width,
            width,
            top,
        }
    }

    /// The number of buckets.
    pub(super) fn buckets(self) -> usize {
        1 << self.width
    }

    /// The bucket of `key`.
    #[inline]
    fn of(self, key: u64) -> usize {
        if self.width == 0 {
            0
        } else {
            ((key >> self.shift) & ((1u64 << self.width) - 1)) as usize
        }
    }

    /// The bit shift of the highest key byte that may differ, where a bucket's sort starts.
    fn first_byte(self) -> u32 {
        self.top.saturating_sub(1) / 8 * 8
    }
}

/// How many keys of `keys` fall in each bucket of `digit`.
pub(super) fn count(keys: &[u64], digit: Digit) -> Vec<usize> {
    let mut counts = vec![0usize; digit.buckets()];
    for &k in keys {
        counts[digit.of(k)] += 1;
    }
    counts
}

/// Where one chunk of the input writes in one bucket: the free slots of its points and keys,
/// and its items.
pub(super) struct Slot<'a, P, T> {
    points: core::slice::IterMut<'a, P>,
    keys: core::slice::IterMut<'a, u64>,
    items: Vec<T>,
}

/// The slots of every chunk (outer) in every bucket (inner) in `points` and `keys` (of the
/// total length of `counts`): chunk `c` gets `counts[c][b]` slots in bucket `b`, after those of
/// the chunks before it, so that a bucket holds its records in input order.
pub(super) fn slots<'a, P, T>(
    counts: &[Vec<usize>],
    mut points: &'a mut [P],
    mut keys: &'a mut [u64],
) -> Vec<Vec<Slot<'a, P, T>>> {
    let buckets = counts.first().map_or(0, Vec::len);
    let mut slots: Vec<Vec<Slot<'a, P, T>>> =
        counts.iter().map(|_| Vec::with_capacity(buckets)).collect();
    for b in 0..buckets {
        for (chunk, chunk_slots) in counts.iter().zip(&mut slots) {
            let (p, rest_points) = core::mem::take(&mut points).split_at_mut(chunk[b]);
            let (k, rest_keys) = core::mem::take(&mut keys).split_at_mut(chunk[b]);
            (points, keys) = (rest_points, rest_keys);
            chunk_slots.push(Slot {
                points: p.iter_mut(),
                keys: k.iter_mut(),
                items: Vec::with_capacity(chunk[b]),
            });
        }
    }
    slots
}

/// Scatters one chunk: `keys[j]` is the packed key of the record `take(j)` gives (called in
/// order), which goes to its bucket's slot.
///
/// # Panics
/// If a bucket's slots run out: `slots` was not made from this chunk's counts.
pub(super) fn scatter<P, T>(
    keys: &[u64],
    digit: Digit,
    slots: &mut [Slot<'_, P, T>],
    mut take: impl FnMut(usize) -> (P, T),
) {
    for (j, &key) in keys.iter().enumerate() {
        let (point, item) = take(j);
        let slot = &mut slots[digit.of(key)];
        *slot.points.next().expect("a slot counted for each record") = point;
        *slot.keys.next().expect("a slot counted for each record") = key;
        slot.items.push(item);
    }
}

/// The items of each bucket, gathered from the chunks' slots in chunk order (the points and
/// keys are already in place).
pub(super) fn bucket_items<P, T>(slots: Vec<Vec<Slot<'_, P, T>>>) -> Vec<Vec<T>> {
    let buckets = slots.first().map_or(0, Vec::len);
    let mut items: Vec<Vec<T>> = (0..buckets).map(|_| Vec::new()).collect();
    for chunk in slots {
        for (bucket, slot) in items.iter_mut().zip(chunk) {
            if bucket.is_empty() {
                *bucket = slot.items;
            } else {
                bucket.extend(slot.items);
            }
        }
    }
    items
}

/// Reused buffers for finishing buckets.
pub(super) struct Scratch<P> {
    order: Vec<u64>,
    buffer: Vec<u64>,
    keys: Vec<u64>,
    points: Vec<P>,
}

impl<P> Default for Scratch<P> {
    fn default() -> Self {
        Scratch {
            order: Vec::new(),
            buffer: Vec::new(),
            keys: Vec::new(),
            points: Vec::new(),
        }
    }
}

/// Puts one bucket in packed-key order: `points` and `keys` in place, `items` along the same
/// permutation; `bits` is the number of index bits of the packed keys.
pub(super) fn finish<P: Copy, T>(
    points: &mut [P],
    keys: &mut [u64],
    items: &mut [T],
    bits: u32,
    digit: Digit,
    scratch: &mut Scratch<P>,
) {
    let m = keys.len();
    debug_assert!(points.len() == m && items.len() == m && (m as u64) <= 1u64 << bits);
    if m <= 1 {
        return;
    }
    let mask = (1u64 << bits) - 1;
    // Positions in the bucket follow input indices: the order is the packed keys' order.
    scratch.order.clear();
    scratch.order.extend(
        keys.iter()
            .enumerate()
            .map(|(j, &k)| (k & !mask) | j as u64),
    );
    radix::sort_keyed_from(&mut scratch.order, &mut scratch.buffer, digit.first_byte());
    scratch.keys.clear();
    scratch.keys.extend_from_slice(keys);
    scratch.points.clear();
    scratch.points.extend_from_slice(points);
    for ((o, key), point) in scratch.order.iter_mut().zip(keys).zip(points) {
        *o &= mask;
        *key = scratch.keys[*o as usize];
        *point = scratch.points[*o as usize];
    }
    // Items move along the cycles of the permutation: position j takes the item at
    // `order[j]`; a finished position is marked by `order[j] = j`.
    let order = &mut scratch.order;
    for i in 0..m {
        let mut j = i;
        while order[j] as usize != i {
            let from = order[j] as usize;
            items.swap(j, from);
            order[j] = j as u64;
            j = from;
        }
        order[j] = j as u64;
    }
}

/// The whole sort and gather on one thread: `keys` (packed, in input order, see
/// `build::pack`) with `differ` their AND xor OR, `bits` their index bits, and `take(i)` giving
/// record `i` (called once each, in order). Returns the keys, points and items in packed-key
/// order.
pub(super) fn sort_gather<P: Copy, T>(
    keys: Vec<u64>,
    differ: u64,
    bits: u32,
    fill: P,
    take: impl FnMut(usize) -> (P, T),
) -> (Vec<u64>, Vec<P>, Vec<T>) {
    let n = keys.len();
    let digit = Digit::choose(n, differ);
    let counts = vec![count(&keys, digit)];
    let mut points = vec![fill; n];
    let mut sorted = vec![0u64; n];
    let mut slots = slots(&counts, &mut points, &mut sorted);
    scatter(&keys, digit, &mut slots[0], take);
    drop(keys);
    let buckets = bucket_items(slots);
    let mut items = Vec::with_capacity(n);
    let mut scratch = Scratch::default();
    let mut start = 0;
    for mut bucket in buckets {
        let end = start + bucket.len();
        finish(
            &mut points[start..end],
            &mut sorted[start..end],
            &mut bucket,
            bits,
            digit,
            &mut scratch,
        );
        items.append(&mut bucket);
        start = end;
    }
    (sorted, points, items)
}

/// [`sort_gather`] on rayon's threads: the input cut into chunks counted and scattered in
/// parallel (each chunk's slots in a bucket after those of the chunks before it, so the
/// buckets are the serial ones), then the buckets finished in parallel. `take(i)` may be
/// called in any order, once for each `i`.
#[cfg(feature = "rayon")]
pub(super) fn par_sort_gather<P: Copy + Send + Sync, T: Send>(
    keys: Vec<u64>,
    differ: u64,
    bits: u32,
    fill: P,
    take: impl Fn(usize) -> (P, T) + Sync,
) -> (Vec<u64>, Vec<P>, Vec<T>) {
    use rayon::prelude::*;
    let n = keys.len();
    let digit = Digit::choose(n, differ);
    // Several chunks a thread, so that a thread slowed by other work is helped.
    let chunk = n.div_ceil(4 * rayon::current_num_threads()).max(1);
    let counts: Vec<Vec<usize>> = keys.par_chunks(chunk).map(|k| count(k, digit)).collect();
    let mut points = vec![fill; n];
    let mut sorted = vec![0u64; n];
    let mut slots = slots(&counts, &mut points, &mut sorted);
    slots
        .par_iter_mut()
        .zip(keys.par_chunks(chunk))
        .enumerate()
        .for_each(|(c, (slots, keys))| scatter(keys, digit, slots, |j| take(c * chunk + j)));
    drop(keys);
    let buckets = bucket_items(slots);
    let mut work = Vec::with_capacity(buckets.len());
    let (mut rest_points, mut rest_keys) = (&mut points[..], &mut sorted[..]);
    for items in buckets {
        let (p, more_points) = core::mem::take(&mut rest_points).split_at_mut(items.len());
        let (k, more_keys) = core::mem::take(&mut rest_keys).split_at_mut(items.len());
        (rest_points, rest_keys) = (more_points, more_keys);
        work.push((p, k, items));
    }
    let finished: Vec<Vec<T>> = work
        .into_par_iter()
        .map_init(Scratch::default, |scratch, (p, k, mut items)| {
            finish(p, k, &mut items, bits, digit, scratch);
            items
        })
        .collect();
    let mut items = Vec::with_capacity(n);
    for mut bucket in finished {
        items.append(&mut bucket);
    }
    (sorted, points, items)
}

#[cfg(test)]
#[path = "distribute_tests.rs"]
mod tests;
