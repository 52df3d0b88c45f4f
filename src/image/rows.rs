//! Streaming 2D region trees row by row, in both directions, never holding the dense image.
//!
//! [`RowBuilder`] takes the rows of an image one at a time, bit-packed, and merges as it goes: a
//! row is a *band* of cells of side 1; two complete bands of side 2^j (rows `2m 2^j ..` and
//! `(2m + 1) 2^j ..`) merge into one band of side 2^(j+1), whose cell `x` is uniform when its
//! four children are uniform of one colour and otherwise an internal node followed by the
//! children's subtrees. A band stores two bitmaps (mixed, black; one bit per cell) and the
//! subtrees of its mixed cells, so at most one band per level waits for its partner. Memory is
//! O(n + w) for a tree of n nodes and a width of w pixels (the subtrees waiting are parts of the
//! final tree, and a band of side 2^j has w / 2^j cells), time O(pixels / 64 + n k) (bitmaps
//! merged 64 cells at a time; a subtree is copied once per level above it).
//!
//! [`RegionTree::for_each_row`] goes the other way: it hands out the rows of a 2D tree one at a
//! time, bit-packed, with O(w + k) memory beyond the tree: for each level it keeps the internal
//! nodes and the black leaves of that level crossing the current row.

use super::iter::set_bits;
use super::ops::subtree_end;
use super::{ImageError, ImageTree, RegionTree, BLACK, INTERNAL, WHITE};

/// One band of cells of side 2^j across the image.
#[derive(Default)]
struct Band {
    /// Bit `x` set: cell `x` holds both colours (its subtree is in `nodes`).
    mixed: Vec<u64>,
    /// Bit `x` set: cell `x` is all black.
    black: Vec<u64>,
    /// The subtrees of the mixed cells, in order of `x`.
    nodes: Vec<u8>,
    /// The end of each subtree in `nodes`.
    ends: Vec<usize>,
}

impl Band {
    fn bytes(&self) -> u64 {
        let words = self.mixed.len() + self.black.len() + self.ends.len();
        (self.nodes.len() + 8 * words) as u64
    }
}

/// Bits `0, 2, 4, ...` of `x` packed into the low 32 bits.
#[inline]
fn even_bits(mut x: u64) -> u64 {
    x &= 0x5555_5555_5555_5555;
    x = (x | (x >> 1)) & 0x3333_3333_3333_3333;
    x = (x | (x >> 2)) & 0x0f0f_0f0f_0f0f_0f0f;
    x = (x | (x >> 4)) & 0x00ff_00ff_00ff_00ff;
    x = (x | (x >> 8)) & 0x0000_ffff_0000_ffff;
    (x | (x >> 16)) & 0x0000_0000_ffff_ffff
}

/// For each pair of adjacent bits of `v` (two words, 128 cells), the OR and the AND of the pair,
/// as 64 bits.
#[inline]
fn pairs(v: &[u64], w: usize) -> (u64, u64) {
    let a0 = v.get(2 * w).copied().unwrap_or(0);
    let a1 = v.get(2 * w + 1).copied().unwrap_or(0);
    let or = even_bits(a0 | (a0 >> 1)) | (even_bits(a1 | (a1 >> 1)) << 32);
    let and = even_bits(a0 & (a0 >> 1)) | (even_bits(a1 & (a1 >> 1)) << 32);
    (or, and)
}

#[inline]
fn bit(v: &[u64], x: usize) -> bool {
    v.get(x / 64).is_some_and(|w| (w >> (x % 64)) & 1 == 1)
}

/// Reads the mixed subtrees of a band in order.
struct Subtrees<'a> {
    band: &'a Band,
    next: usize,
}

impl<'a> Subtrees<'a> {
    fn take(&mut self) -> &'a [u8] {
        let start = self.next.checked_sub(1).map_or(0, |i| self.band.ends[i]);
        let end = self.band.ends[self.next];
        self.next += 1;
        &self.band.nodes[start..end]
    }
}

/// Builds a 2D region tree from rows streamed in: O(n + width) memory for an n-node result,
/// never the dense image.
///
/// A row is a band of cells of side 1; two complete bands of side 2^j merge into one of side
/// 2^(j+1), whose cell is a leaf when its four children are leaves of one colour and otherwise an
/// internal node followed by the children's subtrees. At most one band per level waits for its
/// partner, each as two bitmaps (mixed, black) and the subtrees of its mixed cells, merged 64
/// cells at a time.
///
/// # Complexity
/// O(pixels / 64 + n k) time (a subtree is copied once per level above it), O(n + width)
/// memory.
///
/// ```
/// use orthtree::image::{ImageTree, RowBuilder};
/// let mut b = RowBuilder::new([70, 3]).unwrap();
/// b.push_row(&[u64::MAX, u64::MAX]).unwrap(); // a black first row (bits past 70: padding)
/// b.push_row(&[0, 0]).unwrap();
/// b.push_row(&[1, 0]).unwrap(); // the pixel (0, 2)
/// let t = b.finish().unwrap();
/// assert_eq!(t, ImageTree::from_fn([70, 3], |[x, y]| y == 0 || (x, y) == (0, 2)).unwrap());
/// ```
pub struct RowBuilder {
    extent: [u32; 2],
    depth: u8,
    /// Words per row.
    row_words: usize,
    /// Rows pushed so far.
    rows: u32,
    /// The band of each level waiting for its partner below it.
    pending: Vec<Option<Band>>,
    /// Bytes held in `pending`.
    held: u64,
    max_bytes: u64,
    root: Option<Vec<u8>>,
}

impl RowBuilder {
    /// A builder for an image of extent `[width, height]`, with no memory limit beyond the
    /// machine's (see [`RowBuilder::max_bytes`]).
    ///
    /// # Errors
    /// [`ImageError::TooLarge`] if the extent needs a depth beyond [`RegionTree::MAX_DEPTH`].
    pub fn new(extent: [u32; 2]) -> Result<Self, ImageError> {
        let depth = ImageTree::depth_for(extent)?;
        Ok(RowBuilder {
            extent,
            depth,
            row_words: (extent[0] as usize).div_ceil(64),
            rows: 0,
            pending: (0..=depth).map(|_| None).collect(),
            held: 0,
            max_bytes: u64::MAX,
            root: None,
        })
    }

    /// Refuses, with [`ImageError::MemoryLimit`], to hold more than `bytes` bytes of waiting
    /// bands (subtrees and bitmaps: about the size of the tree built so far).
    pub fn max_bytes(mut self, bytes: u64) -> Self {
        self.max_bytes = bytes;
        self
    }

    /// The number of `u64` words a row takes: `ceil(width / 64)`.
    pub fn row_words(&self) -> usize {
        self.row_words
    }

    /// The rows pushed so far.
    pub fn rows_pushed(&self) -> u32 {
        self.rows
    }

    /// Adds the next row (from `y = 0` down): bit `x % 64` of word `x / 64` is pixel `x`, set for
    /// black. Bits past the width are padding and are not read.
    ///
    /// # Errors
    /// [`ImageError::BitmapLength`] if `row` is not [`RowBuilder::row_words`] long;
    /// [`ImageError::TooManyRows`] past the height; [`ImageError::MemoryLimit`] past the budget.
    ///
    /// # Complexity
    /// O(width / 64) amortised, plus the merges it completes.
    pub fn push_row(&mut self, row: &[u64]) -> Result<(), ImageError> {
        super::build::check_length(self.row_words, row.len())?;
        if self.rows >= self.extent[1] {
            return Err(ImageError::TooManyRows {
                height: self.extent[1],
            });
        }
        let mut black = row.to_vec();
        let width = self.extent[0] as usize;
        if !width.is_multiple_of(64)
            && let Some(last) = black.last_mut()
        {
            *last &= (1u64 << (width % 64)) - 1;
        }
        let band = Band {
            black,
            ..Band::default()
        };
        let at = self.rows;
        self.rows += 1;
        self.carry(band, 0, u64::from(at))
    }

    /// The tree, once every row is in.
    ///
    /// # Errors
    /// [`ImageError::MissingRows`] if fewer rows than the height were pushed;
    /// [`ImageError::MemoryLimit`] past the budget.
    ///
    /// # Panics
    /// Never: once every row is in, the last band has reached the root.
    pub fn finish(mut self) -> Result<ImageTree, ImageError> {
        if self.rows != self.extent[1] {
            return Err(ImageError::MissingRows {
                height: self.extent[1],
                found: self.rows,
            });
        }
        // the rows below the height are white: add white bands of the largest aligned height
        let mut pos = u64::from(self.rows);
        let side = 1u64 << self.depth;
        while pos < side {
            let level = pos.trailing_zeros();
            self.carry(Band::default(), level as u8, pos >> level)?;
            pos += 1 << level;
        }
        let nodes = self.root.take().expect("the last band reached the root");
        Ok(RegionTree {
            extent: self.extent,
            depth: self.depth,
            nodes,
        })
    }

    /// A complete band `index` of `level`: waits for its partner, or merges with it and goes up.
    fn carry(&mut self, mut band: Band, mut level: u8, mut index: u64) -> Result<(), ImageError> {
        loop {
            if level == self.depth {
                let nodes = if bit(&band.mixed, 0) {
                    band.nodes
                } else {
                    vec![u8::from(bit(&band.black, 0))]
                };
                self.root = Some(nodes);
                return Ok(());
            }
            let slot = usize::from(level);
            if index.is_multiple_of(2) {
                self.held += band.bytes();
                self.check(0)?;
                self.pending[slot] = Some(band);
                return Ok(());
            }
            let upper = self.pending[slot]
                .take()
                .expect("an odd band follows its even partner");
            self.held -= upper.bytes();
            band = self.merge(&upper, &band, level + 1)?;
            level += 1;
            index /= 2;
        }
    }

    fn check(&self, extra: u64) -> Result<(), ImageError> {
        let needed = self.held + extra;
        if needed > self.max_bytes {
            return Err(ImageError::MemoryLimit {
                needed,
                limit: self.max_bytes,
            });
        }
        Ok(())
    }

    /// The band of `level` (cells of side 2^level) whose cells have the children `2x`, `2x + 1`
    /// in `upper` (children 0 and 1) and in `lower` (children 2 and 3).
    fn merge(&self, upper: &Band, lower: &Band, level: u8) -> Result<Band, ImageError> {
        let cells = (self.extent[0] as usize).div_ceil(1 << level);
        let words = cells.div_ceil(64);
        let mut out = Band {
            mixed: Vec::with_capacity(words),
            black: Vec::with_capacity(words),
            ..Band::default()
        };
        let mut from = [upper, lower].map(|band| Subtrees { band, next: 0 });
        for w in 0..words {
            let (um_or, _) = pairs(&upper.mixed, w);
            let (lm_or, _) = pairs(&lower.mixed, w);
            let (ub_or, ub_and) = pairs(&upper.black, w);
            let (lb_or, lb_and) = pairs(&lower.black, w);
            let any_mixed = um_or | lm_or;
            let all_black = ub_and & lb_and;
            let mixed = any_mixed | ((ub_or | lb_or) & !all_black);
            out.mixed.push(mixed);
            out.black.push(all_black & !any_mixed);
            let mut m = mixed;
            while m != 0 {
                let x = 64 * w + m.trailing_zeros() as usize;
                m &= m - 1;
                out.nodes.push(INTERNAL);
                for c in 0..4 {
                    let (band, child) = if c < 2 { (upper, 0) } else { (lower, 1) };
                    let cx = 2 * x + (c & 1);
                    if bit(&band.mixed, cx) {
                        let sub = from[child].take();
                        out.nodes.extend_from_slice(sub);
                    } else {
                        out.nodes
                            .push(if bit(&band.black, cx) { BLACK } else { WHITE });
                    }
                }
                out.ends.push(out.nodes.len());
            }
            self.check(out.bytes())?;
        }
        Ok(out)
    }
}

/// What one level of the tree contributes to the current row.
#[derive(Default)]
struct LevelRow {
    /// (lower x, first node) of each internal node of this level crossing the row.
    internal: Vec<(u32, usize)>,
    /// `lo .. hi` of each black leaf of this level crossing the row, cut to the width.
    black: Vec<(u32, u32)>,
}

impl RegionTree<2> {
    /// Calls `row(y, words)` for each row `y = 0 .. height` in order, `words` the row bit-packed
    /// (bit `x % 64` of word `x / 64` is pixel `x`, set for black; bits past the width clear).
    /// Stops at the first error `row` returns.
    ///
    /// # Errors
    /// The first error of `row`.
    ///
    /// # Complexity
    /// O(pixels / 64 + n k + the leaves crossing each row) time, O(width / 64 + k + the nodes
    /// crossing one row) memory beyond the tree: the dense image is never built.
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// let t = ImageTree::from_boxes([5, 3], &[([1, 1], [4, 2])]).unwrap();
    /// let mut rows = Vec::new();
    /// t.for_each_row(|y, words| -> Result<(), ()> { rows.push((y, words[0])); Ok(()) }).unwrap();
    /// assert_eq!(rows, [(0, 0), (1, 0b01110), (2, 0)]);
    /// ```
    pub fn for_each_row<E>(
        &self,
        mut row: impl FnMut(u32, &[u64]) -> Result<(), E>,
    ) -> Result<(), E> {
        let [width, height] = self.extent;
        let k = self.depth;
        let mut levels: Vec<LevelRow> = (0..=k).map(|_| LevelRow::default()).collect();
        let root = &mut levels[0];
        match self.nodes[0] {
            INTERNAL => root.internal.push((0, 0)),
            BLACK => root.black.push((0, width)),
            _ => {}
        }
        let mut words = vec![0u64; (width as usize).div_ceil(64)];
        for y in 0..height {
            // the levels whose band starts at this row: side 2^(k - l) divides y
            let first = if y == 0 {
                1
            } else {
                k.saturating_sub(y.trailing_zeros() as u8).max(1)
            };
            for l in first..=k {
                let (parents, rest) = levels.split_at_mut(usize::from(l));
                let parent = &parents[usize::from(l) - 1];
                let here = &mut rest[0];
                here.internal.clear();
                here.black.clear();
                let side = 1u32 << (k - l);
                let lower = (y >> (k - l)) & 1 == 1;
                for &(x, start) in &parent.internal {
                    let c0 = start + 1;
                    let c1 = subtree_end::<2>(&self.nodes, c0);
                    let (a, b) = if lower {
                        let c2 = subtree_end::<2>(&self.nodes, c1);
                        (c2, subtree_end::<2>(&self.nodes, c2))
                    } else {
                        (c0, c1)
                    };
                    for (cx, at) in [(x, a), (x + side, b)] {
                        match self.nodes[at] {
                            INTERNAL => here.internal.push((cx, at)),
                            BLACK if cx < width => {
                                here.black.push((cx, (cx + side).min(width)));
                            }
                            _ => {}
                        }
                    }
                }
            }
            words.fill(0);
            for level in &levels {
                for &(lo, hi) in &level.black {
                    set_bits(&mut words, lo as usize, hi as usize);
                }
            }
            row(y, &words)?;
        }
        Ok(())
    }
}
