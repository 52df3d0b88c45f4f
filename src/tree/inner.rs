//! The internal nodes of a [`Tree`] as a compact table (for [`Tree::is_balanced`]), built from the
//! block parents alone: 4 bytes per child block are read, never the per-node arrays.
//!
//! Every internal node gets a number, its *record*: the root is record 0, the other internal
//! nodes follow in id order. Record r holds `base`, the record of its first internal child, and
//! two masks over its 2^D children: which are internal (`inner`) and which have internal
//! children of their own (`grand`). Child i, when internal, is record base + (the number of
//! internal children before i), a popcount. A walk down the table touches the internal nodes
//! only, each one record of two words up to D = 4 (inner bits 0 .. 2^D, grand bits 2^D ..
//! 2^(D+1) of one word), in a table 2^D / 2 times smaller than the arena.
//!
//! Built in three passes over the block parents: (1) mark every block's parent in a bitmap of
//! internal nodes, bit n - 1 for node n, so that block b's bits are b * 2^D .. (b + 1) * 2^D,
//! aligned in one 32-bit word or a run of whole words; (2) mark every block's parent again in a
//! bitmap of "has an internal child" when the block's own bits are not all zero; (3) write each
//! parent's record, the ranks read from per-word counts of the first bitmap. Blocks freed by
//! [`Tree::merge`] are skipped: their old parent no longer points to them.

use super::arena::NONE;
use super::Tree;

/// The table of internal nodes (see the module doc).
pub(super) struct Inner<const D: usize> {
    table: Vec<u32>,
}

/// Set bits of every byte: the masks of D <= 3 count with one look-up (the crate builds for
/// CPUs without a popcount instruction, where `count_ones` takes a dozen).
const ONES: [u8; 256] = {
    let mut t = [0u8; 256];
    let mut i = 0;
    while i < 256 {
        t[i] = (i as u32).count_ones() as u8;
        i += 1;
    }
    t
};

/// The set bits of `x`, which is below 256 when `small`.
#[inline]
fn ones(x: u32, small: bool) -> u32 {
    if small {
        ONES[x as usize & 255] as u32
    } else {
        x.count_ones()
    }
}

/// Sets bit `q` of a bitmap.
#[inline]
fn set(words: &mut [u32], q: usize) {
    words[q >> 5] |= 1 << (q & 31);
}

impl<const D: usize> Inner<D> {
    /// 32-bit words per mask (`inner` or `grand`) from D = 5 on; below, both share one word.
    pub(super) const WORDS: usize = if D >= 5 { 1 << (D - 5) } else { 1 };
    /// Words of both masks.
    const MASKS: usize = if D >= 5 { 2 << (D - 5) } else { 1 };
    const STRIDE: usize = 1 + Self::MASKS;
    /// The bits of one child block in a one-word mask (D < 5).
    const LOW: u32 = ((1u64 << (1 << if D < 5 { D } else { 0 })) - 1) as u32;

    /// The table of `tree`'s internal nodes; `None` when the root is a leaf.
    pub(super) fn new(tree: &Tree<D>) -> Option<Self> {
        if tree.first_child[0] == NONE {
            return None;
        }
        let parents = tree.block_parents();
        let words = (parents.len() << D).div_ceil(32);
        let mut inner = vec![0u32; words];
        for (b, &p) in parents.iter().enumerate() {
            if p != 0 && tree.block_is_live(b) {
                set(&mut inner, p as usize - 1);
            }
        }
        let mut grand = vec![0u32; words];
        for (b, &p) in parents.iter().enumerate() {
            if p != 0 && Self::any(&inner, b) && tree.block_is_live(b) {
                set(&mut grand, p as usize - 1);
            }
        }
        let mut before = Vec::with_capacity(words);
        let mut count = 1u32; // the root
        for w in &inner {
            before.push(count);
            count += w.count_ones();
        }
        let rank =
            |q: usize| before[q >> 5] + (inner[q >> 5] & ((1u32 << (q & 31)) - 1)).count_ones();
        let mut table = vec![0u32; count as usize * Self::STRIDE];
        // the record of the first internal node at or after block b (freed blocks have none)
        let mut base = 1;
        for (b, &p) in parents.iter().enumerate() {
            let first = base;
            let record = if D < 5 {
                let q = b << D;
                let (w, s) = (q >> 5, q & 31);
                let own = (inner[w] >> s) & Self::LOW;
                base += ones(own, D <= 3);
                own | ((grand[w] >> s) & Self::LOW) << (1 << D & 31)
            } else {
                base += Self::block(&inner, b)
                    .iter()
                    .map(|w| w.count_ones())
                    .sum::<u32>();
                0
            };
            if !tree.block_is_live(b) {
                continue;
            }
            let r = if p == 0 {
                0
            } else {
                rank(p as usize - 1) as usize
            };
            let out = &mut table[r * Self::STRIDE..(r + 1) * Self::STRIDE];
            out[0] = first;
            if D < 5 {
                out[1] = record;
            } else {
                let w = Self::WORDS;
                out[1..1 + w].copy_from_slice(Self::block(&inner, b));
                out[1 + w..].copy_from_slice(Self::block(&grand, b));
            }
        }
        Some(Inner { table })
    }

    /// `true` when block `b` has a bit set in `bits`.
    #[inline]
    fn any(bits: &[u32], b: usize) -> bool {
        if D < 5 {
            let q = b << D;
            (bits[q >> 5] >> (q & 31)) & Self::LOW != 0
        } else {
            Self::block(bits, b).iter().any(|&w| w != 0)
        }
    }

    /// The words of block `b` in `bits` (D >= 5, whole words).
    #[inline]
    fn block(bits: &[u32], b: usize) -> &[u32] {
        &bits[b * Self::WORDS..(b + 1) * Self::WORDS]
    }

    /// Word `w` (below [`Self::WORDS`]) of record `r`'s `inner` mask.
    #[inline]
    pub(super) fn inner_word(&self, r: u32, w: usize) -> u32 {
        let s = r as usize * Self::STRIDE + 1;
        if D < 5 {
            self.table[s] & Self::LOW
        } else {
            self.table[s + w]
        }
    }

    /// Word `w` (below [`Self::WORDS`]) of record `r`'s `grand` mask.
    #[inline]
    pub(super) fn grand_word(&self, r: u32, w: usize) -> u32 {
        let s = r as usize * Self::STRIDE + 1;
        if D < 5 {
            self.table[s] >> (1 << D & 31)
        } else {
            self.table[s + Self::WORDS + w]
        }
    }

    /// `true` when child `i` of record `r` has internal children.
    #[inline]
    pub(super) fn grand(&self, r: u32, i: usize) -> bool {
        let s = r as usize * Self::STRIDE + 1;
        if D < 5 {
            (self.table[s] >> ((1 << D) + i)) & 1 != 0
        } else {
            (self.table[s + Self::WORDS + (i >> 5)] >> (i & 31)) & 1 != 0
        }
    }

    /// The record of child `i` of record `r` when it is internal, else `otherwise`.
    #[inline]
    pub(super) fn child_or(&self, r: u32, i: usize, otherwise: u32) -> u32 {
        let s = r as usize * Self::STRIDE;
        let record = &self.table[s..s + Self::STRIDE];
        let word = record[1 + (i >> 5)];
        if (word >> (i & 31)) & 1 == 0 {
            return otherwise;
        }
        let whole: u32 = if D < 5 {
            0
        } else {
            record[1..1 + (i >> 5)].iter().map(|w| w.count_ones()).sum()
        };
        record[0] + whole + ones(word & ((1u32 << (i & 31)) - 1), D <= 3)
    }
}
