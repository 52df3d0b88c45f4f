//! The leaves of a region tree as cells ([`Blocks`], in pre-order = Morton order), and the
//! conversions back to dense bitmaps, O(pixels + nodes): each black leaf fills its block.

use super::build::{pixel_count, row_major};
use super::{RegionTree, BLACK, INTERNAL};
use smallvec::SmallVec;

/// A leaf of a region tree: the cube `min .. min + side` on every axis, all one colour. Blocks
/// may reach into the padding beyond the extent (those are always white).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Block<const D: usize> {
    /// The lower corner, in pixels.
    pub min: [u32; D],
    /// The level in the tree (0 is the root).
    pub level: u8,
    /// The side in pixels, 2^(k - level).
    pub side: u32,
    /// Whether the block is black.
    pub black: bool,
}

/// Iterator returned by [`RegionTree::blocks`]: the leaves in pre-order (Morton order).
#[derive(Clone, Debug)]
pub struct Blocks<'a, const D: usize> {
    nodes: &'a [u8],
    depth: u8,
    pos: usize,
    /// the cell of the node at `pos`
    cur: ([u32; D], u8),
    /// (min, level, child being read) of each open internal node
    /// (the child counts in a `u16`: it reaches 2^D = 256 in 8-D)
    stack: SmallVec<[([u32; D], u8, u16); 32]>,
}

/// The lower corner of child `c` of the cell at `min` on `level`, in a tree of depth `depth`
/// (shared by the blocks, the builder and the validator).
#[inline]
pub(super) fn child<const D: usize>(min: [u32; D], level: u8, depth: u8, c: u16) -> [u32; D] {
    let half = 1u32 << (depth - level - 1);
    core::array::from_fn(|a| min[a] + ((c >> a) & 1) as u32 * half)
}

impl<const D: usize> Iterator for Blocks<'_, D> {
    type Item = Block<D>;

    fn next(&mut self) -> Option<Block<D>> {
        loop {
            let &x = self.nodes.get(self.pos)?;
            self.pos += 1;
            let (min, level) = self.cur;
            if x == INTERNAL {
                self.stack.push((min, level, 0));
                self.cur = (child(min, level, self.depth, 0), level + 1);
                continue;
            }
            let block = Block {
                min,
                level,
                side: 1 << (self.depth - level),
                black: x == BLACK,
            };
            while let Some(top) = self.stack.last_mut() {
                top.2 += 1;
                if usize::from(top.2) < 1 << D {
                    self.cur = (child(top.0, top.1, self.depth, top.2), top.1 + 1);
                    break;
                }
                self.stack.pop();
            }
            return Some(block);
        }
    }
}

impl<const D: usize> RegionTree<D> {
    /// The leaves as [`Block`]s, in pre-order (which is Morton order).
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// let t = ImageTree::from_boxes([4, 4], &[([2, 0], [4, 2])]).unwrap();
    /// let blocks: Vec<_> = t.blocks().collect();
    /// assert_eq!(blocks.len(), 4);
    /// assert!(blocks[1].black && blocks[1].min == [2, 0] && blocks[1].side == 2);
    /// assert_eq!(t.blocks().filter(|b| b.black).map(|b| b.side * b.side).sum::<u32>(), 4);
    /// ```
    pub fn blocks(&self) -> Blocks<'_, D> {
        Blocks {
            nodes: &self.nodes,
            depth: self.depth,
            pos: 0,
            cur: ([0; D], 0),
            stack: SmallVec::new(),
        }
    }

    /// Calls `fill(index, run)` for each run of black pixels along axis 0, `index` the row-major
    /// index (axis 0 fastest) of its first pixel within the extent.
    fn black_runs(&self, mut fill: impl FnMut(usize, usize)) {
        let ext = self.extent.map(|e| e as usize);
        for b in self.blocks().filter(|b| b.black) {
            let lo = b.min.map(|m| m as usize);
            let hi: [usize; D] = core::array::from_fn(|a| (lo[a] + b.side as usize).min(ext[a]));
            let run = hi[0] - lo[0];
            // odometer over axes 1..D
            let mut p = lo;
            loop {
                fill(row_major(p.map(|x| x as u32), self.extent), run);
                let mut a = 1;
                while a < D {
                    p[a] += 1;
                    if p[a] < hi[a] {
                        break;
                    }
                    p[a] = lo[a];
                    a += 1;
                }
                if a == D {
                    break;
                }
            }
        }
    }

    /// The image as row-major booleans (axis 0 fastest, `true` black), cropped to the extent.
    ///
    /// # Complexity
    /// O(pixels + nodes).
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// let bits = [true, false, false, true, true, true];
    /// let t = ImageTree::from_bools([3, 2], &bits).unwrap();
    /// assert_eq!(t.to_bools(), bits);
    /// ```
    pub fn to_bools(&self) -> Vec<bool> {
        let mut out = vec![false; pixel_count(self.extent)];
        self.black_runs(|i, run| out[i..i + run].fill(true));
        out
    }

    /// The image bit-packed: bit `i % 64` of word `i / 64` is the pixel of row-major index `i`
    /// (axis 0 fastest), cropped to the extent.
    ///
    /// # Complexity
    /// O(pixels / 64 + nodes + runs).
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// let t = ImageTree::from_boxes([10, 10], &[([0, 0], [10, 1])]).unwrap();
    /// assert_eq!(t.to_packed(), vec![0x3ff, 0]);
    /// ```
    pub fn to_packed(&self) -> Vec<u64> {
        let mut out = vec![0u64; pixel_count(self.extent).div_ceil(64)];
        self.black_runs(|i, run| set_bits(&mut out, i, i + run));
        out
    }
}

/// Sets bits `lo .. hi` of a packed bitmap (or row).
pub(super) fn set_bits(words: &mut [u64], lo: usize, hi: usize) {
    if lo >= hi {
        return;
    }
    let (wl, wh) = (lo / 64, (hi - 1) / 64);
    let first = !0u64 << (lo % 64);
    let last = !0u64 >> (63 - (hi - 1) % 64);
    if wl == wh {
        words[wl] |= first & last;
        return;
    }
    words[wl] |= first;
    words[wl + 1..wh].fill(!0);
    words[wh] |= last;
}
