//! [`Tree::is_balanced`] for trees shallow enough that a bitmap with one bit per possible internal
//! cell is small (at most one byte per node slot): two sequential passes over the block parents,
//! no walk at all.
//!
//! Keys. A cell at level l with Morton code m (coordinate bit j of axis a at bit j D + a) has the
//! key 2^(D l) + m: the top bit marks the level, and a child's key is its parent's key times 2^D
//! plus its child index. Every key of an internal cell is below 2^(D (depth - 1) + 1).
//!
//! Pass 1 gives every live child block the key of its parent (the parent's own block comes
//! earlier in the arena, so its key is known: a block is appended after its parent exists) and
//! sets the parent's bit in a bitmap of internal cells (by key) and one of internal nodes (by
//! id). A block placed before its parent's
//! block (a block freed by [`Tree::merge`] and reused) makes the pass give up, and the caller
//! walks instead (`balance_check.rs`).
//!
//! Pass 2 tests the condition of `balance_check.rs`'s module doc: for every internal node C at
//! level l >= k (k the allowed level difference) and every allowed direction δ, the neighbour
//! search from C ends at level l - (k - 1) or deeper, that is, the ancestor at level l - k of
//! the cell C + δ is internal (or C + δ is outside). That ancestor is the ancestor of P + δ',
//! with P the parent of C and δ' the restriction of δ to the axes where C lies on P's boundary
//! (P itself, internal, when δ' is empty). So the pass goes over the parents P instead, one
//! block at a time (the block's bits in the bitmap of internal nodes say which children are
//! internal), and makes one bit test per distinct δ' of P's internal children (at most
//! 3^D - 1). Neighbour keys come from dilated-integer arithmetic on the Morton code (one add or
//! subtract per axis moved), and the bitmap of cells (2^(D (depth - 1) + 1) bits, 1 MiB for
//! p4est's 2D fractal at level 12) mostly stays in cache. D <= 5, so that a block's bits fit
//! one word.

use super::balance_check::Rule;
use super::Tree;
use crate::geom::{Dim, Direction};
use core::ops::Range;

/// Keys of the blocks' parents and the bitmaps of internal nodes and cells (see the module doc).
pub(super) struct Dense<const D: usize> {
    /// The key of each block's parent; 0 for a freed block.
    keys: Vec<u32>,
    /// Bit n - 1 for every internal node n other than the root (block b at b * 2^D ..).
    inner: Vec<u32>,
    /// Bit `key` for the key of every internal cell.
    cells: Vec<u64>,
    /// `spread[a]`: the Morton code bits of axis `a`.
    spread: [u32; D],
}

/// One neighbour direction in Morton terms: for each axis a, two bits at 2a choosing to stay
/// (0), move down (1) or up (2) along it; and the moves it needs, bit 3a + choice.
#[derive(Clone, Copy)]
struct Step {
    choice: u32,
    needs: u32,
}

impl<const D: usize> Dense<D> {
    /// The children of one block in one mask word.
    const LOW: u32 = ((1u64 << (1 << if D <= 5 { D } else { 0 })) - 1) as u32;

    /// Pass 1; `None` when D > 5, when the bitmap of cells would be larger than one byte per
    /// node slot (or keys would not fit 32 bits), or when a block comes before its parent's
    /// block. The root must be internal.
    pub(super) fn new(tree: &Tree<D>) -> Option<Self> {
        let depth = tree.depth() as usize;
        let width = D * (depth - 1) + 1;
        if D > 5 || width > 32 || (1u64 << width) > 8 * tree.node_count() as u64 {
            return None;
        }
        let parents = tree.block_parents();
        let mut keys = vec![0u32; parents.len()];
        let mut inner = vec![0u32; (parents.len() << D).div_ceil(32)];
        let mut cells = vec![0u64; (1usize << width).div_ceil(64)];
        for (b, &p) in parents.iter().enumerate() {
            if !tree.block_is_live(b) {
                continue; // a freed block
            }
            let key = if p == 0 {
                1
            } else {
                let q = p as usize - 1;
                let block = q >> D;
                if block >= b {
                    return None;
                }
                inner[q >> 5] |= 1 << (q & 31);
                keys[block] << D | (q & (Dim::<D>::CHILDREN - 1)) as u32
            };
            keys[b] = key;
            cells[key as usize >> 6] |= 1 << (key & 63);
        }
        let mut spread = [0u32; D];
        for (a, s) in spread.iter_mut().enumerate() {
            for bit in (a..32).step_by(D) {
                *s |= 1 << bit;
            }
        }
        Some(Dense {
            keys,
            inner,
            cells,
            spread,
        })
    }

    /// Pass 2 over all blocks.
    pub(super) fn balanced(&self, rule: &Rule, max_level_difference: u8) -> bool {
        let steps = self.steps(rule);
        self.balanced_in(0..self.keys.len(), &steps, max_level_difference)
    }

    /// Pass 2, the blocks spread over rayon's threads.
    #[cfg(feature = "rayon")]
    pub(super) fn par_balanced(&self, rule: &Rule, max_level_difference: u8) -> bool {
        use rayon::prelude::*;
        let steps = self.steps(rule);
        let chunk = 1 << 14;
        (0..self.keys.len().div_ceil(chunk))
            .into_par_iter()
            .all(|i| {
                let range = i * chunk..((i + 1) * chunk).min(self.keys.len());
                self.balanced_in(range, &steps, max_level_difference)
            })
    }

    /// For every mask of internal children (D <= 3), or for every child (D > 3), the distinct
    /// directions in which those children leave the parent's cell.
    fn steps(&self, rule: &Rule) -> Vec<Vec<Step>> {
        let step = |d: &Direction| {
            let (plus, minus) = (d.plus_mask() as u32, d.minus_mask() as u32);
            let (mut choice, mut needs) = (0, 0);
            for a in 0..D {
                let c = ((minus >> a) & 1) | ((plus >> a) & 1) << 1;
                choice |= c << (2 * a);
                needs |= ((c != 0) as u32) << (3 * a + c as usize);
            }
            Step { choice, needs }
        };
        if D > 3 {
            return (0..Dim::<D>::CHILDREN)
                .map(|c| rule.steps(c).iter().map(step).collect())
                .collect();
        }
        (0..1usize << Dim::<D>::CHILDREN)
            .map(|mask| {
                let mut union: Vec<Direction> = Vec::new();
                for c in (0..Dim::<D>::CHILDREN).filter(|c| (mask >> c) & 1 != 0) {
                    for d in rule.steps(c) {
                        if !union.contains(d) {
                            union.push(*d);
                        }
                    }
                }
                union.iter().map(step).collect()
            })
            .collect()
    }

    fn balanced_in(&self, blocks: Range<usize>, steps: &[Vec<Step>], k: u8) -> bool {
        let k = k as usize;
        // Parents above level k - 1 have nothing to test.
        let first = 1u64 << (D * (k - 1)).min(63);
        let shift = (D * (k - 1)).min(31) as u32;
        for b in blocks {
            let q = b << D;
            let mask = (self.inner[q >> 5] >> (q & 31)) & Self::LOW;
            if mask == 0 {
                continue;
            }
            let parent = self.keys[b];
            if (parent as u64) < first {
                continue;
            }
            // The parent's code along each axis as it is, moved one step down and up, and the
            // moves that leave the root cell.
            let level = (31 - parent.leading_zeros()) / D as u32;
            let low = (1u32 << (D as u32 * level)) - 1;
            let (code, top) = (parent & low, parent & !low);
            let mut along = [[0u32; 4]; D];
            let mut outside = 0u32;
            for (a, moves) in along.iter_mut().enumerate() {
                let axis = self.spread[a] & low;
                let x = code & axis;
                *moves = [
                    x,
                    x.wrapping_sub(1 << a) & axis,
                    (x | !axis).wrapping_add(1 << a) & axis,
                    0,
                ];
                outside |= ((x == 0) as u32) << (3 * a + 1) | ((x == axis) as u32) << (3 * a + 2);
            }
            let mut test = |step: &Step| {
                if step.needs & outside != 0 {
                    return true;
                }
                let mut n = top;
                for (a, moves) in along.iter().enumerate() {
                    n |= moves[(step.choice >> (2 * a)) as usize & 3];
                }
                let n = n >> shift;
                (self.cells[n as usize >> 6] >> (n & 63)) & 1 != 0
            };
            let fine = if D > 3 {
                (0..Dim::<D>::CHILDREN)
                    .filter(|c| (mask >> c) & 1 != 0)
                    .all(|c| steps[c].iter().all(&mut test))
            } else {
                steps[mask as usize].iter().all(&mut test)
            };
            if !fine {
                return false;
            }
        }
        true
    }
}
