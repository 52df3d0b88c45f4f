//! The candidates of one query point of the k-nearest joins, and how the `k` first of them by
//! `(distance, position)` are picked and ordered without comparing pairs.
//!
//! Each candidate is stored twice: its entry (the bits of its squared distance, its position in
//! the other tree) at the next free place `i` of the buffer, and a one-word key at the same
//! place: the distance's bits with their low bits replaced by `i` (the bits of a non-negative
//! `f64` order it as its value, so the keys order the candidates by distance up to those low
//! bits, then by buffer place). Orderings and selections then work on plain `u64`s, which need
//! no branch per comparison; the keys are all distinct.
//!
//! - The final order of up to 32 candidates is a sorting network (Batcher's odd-even merge
//!   sort, "Sorting networks and their applications", 1968; the crate's `sort_network`, shared
//!   with the radix sort of the build) over the keys padded with `u64::MAX`: a fixed sequence of minimum-maximum exchanges, without branches on the data.
//!   More are first cut down to `k` by a selection.
//! - Two keys whose distances agree but for the low bits are ordered by buffer place, not by
//!   `(distance, position)`: one pass over the sorted keys re-orders each run of keys with equal
//!   high bits by their entries (almost every run holds one key, and the pass costs one
//!   comparison per key). Distances that differ in their high bits are ordered by them
//!   exactly, so the result is the exact order by `(distance, position)`.
//! - A selection ([`Cands::shrink`]) keeps the `k` first by key; it is exact unless a key left
//!   out shares its high bits with the `k`-th, which then sends the selection to an exact sort
//!   of the entries.
//! - Selections are mostly avoided by a guess: the candidates within a guessed distance (near)
//!   fill the buffer from its front, the others (far) from its back. Once `k` are near, the far
//!   ones are all farther than the `k`-th and are forgotten; if fewer than `k` end near, the far
//!   ones join them. Either way the `k` first are among those kept, so the guess only decides
//!   how many are ordered.

use crate::sort_network::{sort_by_network, WIDEST};

/// The sorting network's width: the most candidates ordered without a selection first.
const NET: usize = WIDEST;

/// The candidates of one query point: entries and keys (see the module doc), the near ones at
/// the front of the buffer, the far ones at its back. The default is an empty buffer.
#[derive(Default)]
pub(crate) struct Cands {
    keys: Vec<u64>,
    entries: Vec<(u64, usize)>,
    /// Room for the compaction of [`Cands::shrink`].
    spare: Vec<(u64, usize)>,
    /// The low bits of a key that hold its buffer place.
    low: u64,
    /// The near candidates: places `..front`.
    front: usize,
    /// The far candidates: places `back..room`.
    back: usize,
    /// The places of the buffer.
    room: usize,
    /// The candidates kept by a selection.
    k: usize,
}

impl Cands {
    /// Empties the buffer, for a point keeping `k` (at least 1) of up to `room - 1` candidates
    /// held at once.
    #[inline(always)]
    pub(crate) fn reset(&mut self, k: usize, room: usize) {
        if self.keys.len() < room {
            self.keys.resize(room, 0);
            self.entries.resize(room, (0, 0));
        }
        let bits = usize::BITS - (room.max(2) - 1).leading_zeros();
        self.low = (1u64 << bits) - 1;
        self.front = 0;
        self.back = room;
        self.room = room;
        self.k = k;
    }

    /// The candidates held, near and far.
    #[inline(always)]
    pub(crate) fn held(&self) -> usize {
        self.front + (self.room - self.back)
    }

    /// The near candidates held.
    #[inline(always)]
    pub(crate) fn near(&self) -> usize {
        self.front
    }

    /// Writes a candidate at distance bits `bits` and position `at` in the next free place of
    /// the front (`near`) or of the back, and keeps it unless `at` is `skip`; the buffer must
    /// have a free place. Without branches: it is written at both, and one end moves.
    #[inline(always)]
    pub(crate) fn push(&mut self, bits: u64, at: usize, skip: usize, near: bool) {
        let (i, j) = (self.front, self.back - 1);
        self.entries[j] = (bits, at);
        self.keys[j] = (bits & !self.low) | j as u64;
        self.entries[i] = (bits, at);
        self.keys[i] = (bits & !self.low) | i as u64;
        let keep = at != skip;
        self.front = i + usize::from(keep & near);
        self.back = j + 1 - usize::from(keep & !near);
    }

    /// Forgets the far candidates: at least `k` near ones are held, all of them nearer.
    #[inline(always)]
    pub(crate) fn drop_far(&mut self) {
        self.back = self.room;
    }

    /// Moves the far candidates after the near ones, all of them near now.
    #[inline(always)]
    fn merge_far(&mut self) {
        let low = self.low;
        for j in self.back..self.room {
            let (i, e) = (self.front, self.entries[j]);
            self.entries[i] = e;
            self.keys[i] = (e.0 & !low) | i as u64;
            self.front += 1;
        }
        self.back = self.room;
    }

    /// Keeps the `k` first candidates by `(distance, position)` (in no particular order) and
    /// returns the `k`-th distance; at least `k` must be held.
    #[inline(always)]
    pub(crate) fn shrink(&mut self) -> f64 {
        self.merge_far();
        self.select();
        let kth = self.entries[..self.k].iter().map(|e| e.0).max();
        f64::from_bits(kth.unwrap_or(0))
    }

    /// The highest position among the `k` candidates kept by the last [`Cands::shrink`]
    /// (call it right after).
    #[inline]
    pub(crate) fn kept_last_position(&self) -> usize {
        self.entries[..self.k]
            .iter()
            .map(|e| e.1)
            .max()
            .unwrap_or(0)
    }

    /// The `k` first candidates by `(distance, position)`, in that order, as (distance bits,
    /// position); at least `k` must be held.
    #[inline(always)]
    pub(crate) fn ordered(&mut self) -> impl Iterator<Item = (u64, usize)> + '_ {
        let k = self.k;
        if self.front >= k {
            self.drop_far();
        } else {
            self.merge_far();
        }
        let n = self.front;
        if n <= NET {
            sort_by_network(&mut self.keys[..n], u64::MAX);
            self.fix_runs(n);
        } else {
            self.select();
            let keys = &mut self.keys[..k];
            if k <= NET {
                sort_by_network(keys, u64::MAX);
            } else {
                keys.sort_unstable();
            }
            self.fix_runs(k);
        }
        let (keys, entries, low) = (&self.keys[..k], &self.entries, self.low);
        keys.iter().map(move |&key| entries[(key & low) as usize])
    }

    /// Re-orders the runs of keys with equal high bits among the sorted `keys[..len]` by their
    /// entries, an insertion sort that moves nothing across two runs.
    #[inline(always)]
    fn fix_runs(&mut self, len: usize) {
        let (keys, entries, low) = (&mut self.keys, &self.entries, self.low);
        for r in 1..len {
            let mut s = r;
            while s > 0
                && (keys[s] ^ keys[s - 1]) & !low == 0
                && entries[(keys[s] & low) as usize] < entries[(keys[s - 1] & low) as usize]
            {
                keys.swap(s, s - 1);
                s -= 1;
            }
        }
    }

    /// Keeps the `k` first near candidates by `(distance, position)` in the first `k` places of
    /// the buffer, entries and keys (in no particular order), and holds only them.
    #[inline(always)]
    fn select(&mut self) {
        let (k, n, low) = (self.k, self.front, self.low);
        let keys = &mut self.keys[..n];
        keys.select_nth_unstable(k - 1);
        let edge = keys[k - 1] & !low;
        if keys[k..].iter().any(|&key| key & !low == edge) {
            // A candidate left out may come before one kept: order the entries exactly.
            let entries = &mut self.entries[..n];
            entries.sort_unstable();
            for (i, (key, e)) in keys.iter_mut().zip(&*entries).enumerate().take(k) {
                *key = (e.0 & !low) | i as u64;
            }
        } else {
            self.spare.clear();
            self.spare.extend(
                keys[..k]
                    .iter()
                    .map(|&key| self.entries[(key & low) as usize]),
            );
            for (i, key) in keys[..k].iter_mut().enumerate() {
                *key = (*key & !low) | i as u64;
            }
            self.entries[..k].copy_from_slice(&self.spare);
        }
        self.front = k;
    }
}

#[cfg(test)]
mod tests {
    use super::Cands;
    use rand::{rngs::SmallRng, Rng, SeedableRng};

    /// Candidates whose distance bits often agree but for the low bits the keys replace (and
    /// often agree whole), with positions in any order, some of them the skipped one.
    fn offers(rng: &mut SmallRng, n: usize) -> Vec<(u64, usize)> {
        let base = 1.0f64.to_bits();
        (0..n)
            .map(|_| {
                let bits = match rng.gen_range(0..3) {
                    0 => base + rng.gen_range(0..4) * (1 << 20),
                    1 => base + rng.gen_range(0..300),
                    _ => rng.gen_range(0.0..2.0f64).to_bits(),
                };
                (bits, rng.gen_range(0..40))
            })
            .collect()
    }

    #[test]
    fn keys_order_exactly_as_the_entries() {
        let mut rng = SmallRng::seed_from_u64(7);
        let mut c = Cands::default();
        for round in 0..3000 {
            let k = [1, 3, 16, 17, 31, 32, 40][round % 7];
            let n = rng.gen_range(k..3 * k + 40);
            let skip = 5;
            let all = offers(&mut rng, n);
            let mut kept: Vec<(u64, usize)> = all.iter().copied().filter(|e| e.1 != skip).collect();
            kept.sort_unstable();
            if kept.len() < k {
                continue;
            }
            // Near: within a threshold that keeps fewer or more than `k`.
            let edge = kept[rng.gen_range(0..kept.len())].0;
            c.reset(k, n + 1);
            for &(bits, at) in &all {
                c.push(bits, at, skip, bits <= edge);
            }
            assert_eq!(c.held(), kept.len());
            assert_eq!(c.near(), kept.iter().filter(|e| e.0 <= edge).count());
            if round % 2 == 1 {
                let kth = c.shrink();
                assert_eq!(kth.to_bits(), kept[k - 1].0, "round {round}");
                assert_eq!(c.held(), k);
            }
            let got: Vec<(u64, usize)> = c.ordered().collect();
            assert_eq!(got, kept[..k], "round {round}: k {k}, n {n}");
        }
    }
}
