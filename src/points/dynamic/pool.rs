//! [`Pool`]: the array a [`DynamicPointTree`](super::DynamicPointTree)'s leaves keep their
//! points in, each leaf a *chunk* (a contiguous block with slack), and the allocator of chunks.
//!
//! A buddy-free segregated fit: chunks are handed out in powers of two, a freed chunk goes to
//! the free list of its size (a chunk of another length, as compaction lays them, is cut into
//! its binary digits' powers of two first), and a request no list can serve grows the array.
//! Every operation is O(1) but the cut (O(log n)) and the growth (amortised O(1) per entry).
//! Freed space is reused, never returned; the tree compacts the pool (`compact` in
//! `update.rs`) once the free space exceeds the live space, which keeps the array within about
//! twice the live chunks and costs amortised O(1) per update.

/// The slot of an entry that belongs to no leaf.
pub(super) const GAP: u32 = u32::MAX;

/// The array of chunks: a point and the slot of its item per entry.
#[derive(Clone, Debug, Default)]
pub(super) struct Pool<S, const D: usize> {
    /// The points, leaf by leaf; gaps hold copies of some point, never read.
    pub(super) points: Vec<[S; D]>,
    /// The item slot of each entry, [`GAP`] for free space.
    pub(super) slots: Vec<u32>,
    /// `free[c]`: the starts of free chunks of `2^c` entries.
    free: Vec<Vec<u32>>,
    /// Entries in free chunks.
    free_len: usize,
}

impl<S: Copy + Default, const D: usize> Pool<S, D> {
    /// A pool holding `points` (slots `0..n`) in one run: the layout of a fresh build.
    pub(super) fn dense(points: Vec<[S; D]>) -> Self {
        let slots = (0..points.len() as u32).collect();
        Self::new(points, slots)
    }

    /// A pool of these entries, no space free.
    fn new(points: Vec<[S; D]>, slots: Vec<u32>) -> Self {
        Pool {
            points,
            slots,
            free: Vec::new(),
            free_len: 0,
        }
    }

    /// The number of entries, free or not.
    pub(super) fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether the free space exceeds the live space by more than a few pages: time to compact.
    pub(super) fn wants_compaction(&self) -> bool {
        self.free_len > self.points.len() - self.free_len + 4096
    }

    /// A chunk of `cap` entries (a power of two, or 0 for none); returns its start. New entries
    /// hold a copy of the first point (never read: a gap).
    pub(super) fn alloc(&mut self, cap: u32) -> u32 {
        if cap == 0 {
            return 0;
        }
        debug_assert!(cap.is_power_of_two());
        let class = cap.trailing_zeros() as usize;
        if let Some(start) = self.free.get_mut(class).and_then(Vec::pop) {
            self.free_len -= cap as usize;
            return start;
        }
        let start = self.points.len();
        let filler = self.points.first().copied().unwrap_or([S::default(); D]);
        self.points.resize(start + cap as usize, filler);
        self.slots.resize(start + cap as usize, GAP);
        start as u32
    }

    /// Gives back the chunk of `cap` entries (any length) at `start`.
    pub(super) fn free(&mut self, start: u32, cap: u32) {
        self.slots[start as usize..(start + cap) as usize].fill(GAP);
        self.free_len += cap as usize;
        let mut at = start;
        let mut rest = cap;
        while rest != 0 {
            let class = rest.trailing_zeros();
            if self.free.len() <= class as usize {
                self.free.resize(class as usize + 1, Vec::new());
            }
            self.free[class as usize].push(at);
            at += 1 << class;
            rest &= rest - 1;
        }
    }

    /// The pool of a tree read back from its arrays: `owned[e]` tells whether entry `e` lies in
    /// a leaf's chunk; every maximal run of other entries becomes free space (cut into powers of
    /// two as [`Pool::free`] does), and every entry a query never reads (free or beyond its
    /// chunk's count, `live[e]` false) gets `filler` as its point. The free lists may cut the
    /// space differently from the written tree's, which only changes where later chunks go.
    /// O(n log n) at worst.
    #[cfg(feature = "serde")]
    pub(super) fn restore(
        mut points: Vec<[S; D]>,
        slots: Vec<u32>,
        owned: &[bool],
        live: &[bool],
    ) -> Self {
        let filler = (0..points.len())
            .find(|&e| live[e])
            .map_or([S::default(); D], |e| points[e]);
        for (p, _) in points.iter_mut().zip(live).filter(|&(_, &l)| !l) {
            *p = filler;
        }
        let mut pool = Self::new(points, slots);
        let mut start = 0;
        for run in owned.chunk_by(|a, b| a == b) {
            if !run[0] {
                pool.free(start as u32, run.len() as u32);
            }
            start += run.len();
        }
        pool
    }

    /// An empty pool with room for `n` entries.
    pub(super) fn with_capacity(n: usize) -> Self {
        Self::new(Vec::with_capacity(n), Vec::with_capacity(n))
    }

    /// Bytes of heap memory held.
    pub(super) fn heap_bytes(&self) -> usize {
        self.points.capacity() * core::mem::size_of::<[S; D]>()
            + self.slots.capacity() * 4
            + self.free.iter().map(|f| f.capacity() * 4).sum::<usize>()
    }
}

/// The chunk size for a leaf of `len` entries: the next power of two, at least [`MIN_CAP`].
pub(super) fn cap_for(len: u32) -> u32 {
    len.next_power_of_two().max(MIN_CAP)
}

/// The smallest chunk handed out.
pub(super) const MIN_CAP: u32 = 4;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn freed_chunks_are_reused_by_size() {
        let mut p = Pool::<f64, 2>::dense(vec![[0.0; 2]; 7]);
        assert_eq!(p.len(), 7);
        // the build's chunk of 7 entries is cut into 1 + 2 + 4
        p.free(0, 7);
        assert_eq!(p.slots, [GAP; 7]);
        assert_eq!(p.alloc(4), 3);
        assert_eq!(p.alloc(2), 1);
        assert_eq!(p.alloc(1), 0);
        // nothing free of 8: the array grows
        assert_eq!(p.alloc(8), 7);
        assert_eq!(p.len(), 15);
        assert_eq!(p.alloc(0), 0);
        assert!(!p.wants_compaction());
        assert_eq!(cap_for(0), MIN_CAP);
        assert_eq!(cap_for(5), 8);
    }
}
