//! Building region trees: top-down from a cell classifier ([`RegionTree::from_region`]: boxes,
//! balls, any shape that can say whether a cell is empty, full or partly covered), and from dense
//! bitmaps in time linear in the pixels.
//!
//! Both walk the cells depth first in pre-order with an explicit stack (depth at most k) and
//! write the node sequence through the shared writer, which merges 2^D equal leaves into their
//! parent as soon as the last of them is written: the bottom-up merge per Morton block of the
//! classical linear-time construction (Samet, *The Design and Analysis of Spatial Data
//! Structures*, section 4.2.1), done while reading the pixels in Morton order, with no per-pixel
//! descent from the root. A dense bitmap of N pixels costs O(N) time (every cell of the full tree
//! is visited once, and there are fewer than N (1 + 1 / (2^D - 1)) of them; cells wholly in the
//! padding are skipped) and O(k 2^D + n) memory for n output nodes. A classifier costs one call
//! per visited cell: O(n) calls for an n-node result, which is how shapes on a 65536^2 image are
//! built without ever touching its 2^32 pixels.

use super::{ImageError, RegionTree, Writer, BLACK, INTERNAL, WHITE};

/// How a shape covers a cell, as told by the classifier of [`RegionTree::from_region`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Coverage {
    /// No pixel of the cell is black.
    Empty,
    /// Every pixel of the cell is black.
    Full,
    /// Some pixels are black and some are not (or the classifier cannot tell): split.
    Partial,
}

impl<const D: usize> RegionTree<D> {
    /// A tree from a cell classifier: `classify(min, side)` tells how the cube of pixels
    /// `min .. min + side` is covered. Cells wholly outside the extent are white without asking;
    /// a cell reaching beyond the extent that is `Full` is split further (the padding stays
    /// white); at the pixel level (`side == 1`), `Partial` counts as `Full`. O(n) calls for a
    /// result of n nodes.
    ///
    /// # Errors
    /// [`ImageError::TooLarge`] for an extent beyond [`RegionTree::MAX_DEPTH`].
    ///
    /// ```
    /// use orthtree::image::{Coverage, ImageTree};
    /// // the pixels with x < y, on a 64 x 64 image
    /// let t = ImageTree::from_region([64, 64], |[x, y], s| {
    ///     if x + s - 1 < y { Coverage::Full } else if x >= y + s - 1 { Coverage::Empty }
    ///     else { Coverage::Partial }
    /// }).unwrap();
    /// assert_eq!(t.len(), 64 * 63 / 2);
    /// assert!(t.is_canonical());
    /// ```
    pub fn from_region(
        extent: [u32; D],
        mut classify: impl FnMut([u32; D], u32) -> Coverage,
    ) -> Result<Self, ImageError> {
        let depth = Self::depth_for(extent)?;
        let mut w = Writer::<D>::with_capacity(64);
        // (min, level, child being visited) of each open cell; the child counts in a `u16`, as
        // it reaches 2^D = 256 in 8-D
        let mut stack: Vec<([u32; D], u8, u16)> = Vec::with_capacity(32);
        let (mut min, mut level) = ([0u32; D], 0u8);
        loop {
            let side = 1u32 << (depth - level);
            let outside = (0..D).any(|a| min[a] >= extent[a]);
            let inside =
                (0..D).all(|a| u64::from(min[a]) + u64::from(side) <= u64::from(extent[a]));
            let kind = if outside {
                WHITE
            } else {
                match classify(min, side) {
                    Coverage::Empty => WHITE,
                    Coverage::Full if inside => BLACK,
                    _ if side == 1 => BLACK,
                    _ => INTERNAL,
                }
            };
            if kind == INTERNAL {
                w.open();
                stack.push((min, level, 0));
                level += 1;
                continue;
            }
            w.leaf(kind);
            loop {
                let Some(top) = stack.last_mut() else {
                    return Ok(RegionTree {
                        extent,
                        depth,
                        nodes: w.out,
                    });
                };
                top.2 += 1;
                if usize::from(top.2) < 1 << D {
                    let (base, c) = (top.0, top.2);
                    let half = 1u32 << (depth - top.1 - 1);
                    min = core::array::from_fn(|a| base[a] + ((c >> a) & 1) as u32 * half);
                    level = top.1 + 1;
                    break;
                }
                stack.pop();
            }
        }
    }

    /// A tree from a pixel predicate, called once per pixel within the extent in Morton order.
    ///
    /// # Errors
    /// [`ImageError::TooLarge`] for an extent beyond [`RegionTree::MAX_DEPTH`].
    ///
    /// # Complexity
    /// O(pixels).
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// let t = ImageTree::from_fn([5, 5], |[x, y]| (x + y) % 2 == 0).unwrap();
    /// assert_eq!(t.len(), 13);
    /// ```
    pub fn from_fn(
        extent: [u32; D],
        mut pixel: impl FnMut([u32; D]) -> bool,
    ) -> Result<Self, ImageError> {
        let mut t = Self::from_region(extent, |min, side| {
            if side > 1 {
                Coverage::Partial
            } else if pixel(min) {
                Coverage::Full
            } else {
                Coverage::Empty
            }
        })?;
        t.nodes.shrink_to_fit();
        Ok(t)
    }

    /// A tree from row-major booleans (axis 0 fastest; `true` is black), `extent` the sides.
    ///
    /// # Errors
    /// [`ImageError::TooLarge`] for an extent beyond [`RegionTree::MAX_DEPTH`],
    /// [`ImageError::BitmapLength`] if `pixels` is not the product of the sides long.
    ///
    /// # Complexity
    /// O(pixels).
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// let t = ImageTree::from_bools([2, 2], &[true, true, true, true]).unwrap();
    /// assert_eq!(t.nodes(), [1]); // one black leaf
    /// assert!(ImageTree::from_bools([2, 2], &[true]).is_err());
    /// ```
    pub fn from_bools(extent: [u32; D], pixels: &[bool]) -> Result<Self, ImageError> {
        let n = pixel_count(extent);
        if pixels.len() != n {
            return Err(ImageError::BitmapLength {
                expected: n,
                found: pixels.len(),
            });
        }
        Self::from_fn(extent, |p| pixels[row_major(p, extent)])
    }

    /// A tree from a bit-packed bitmap as [`RegionTree::to_packed`] writes it: bit `i % 64` of
    /// word `i / 64` is the pixel of row-major index `i`.
    ///
    /// # Errors
    /// [`ImageError::TooLarge`] for an extent beyond [`RegionTree::MAX_DEPTH`],
    /// [`ImageError::BitmapLength`] if `words` is not the pixel count over 64, rounded up, long.
    ///
    /// # Complexity
    /// O(pixels).
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// let t = ImageTree::from_packed([8, 8], &[0xff]).unwrap(); // the first row
    /// assert_eq!(t.len(), 8);
    /// assert_eq!(t.to_packed(), [0xff]);
    /// ```
    pub fn from_packed(extent: [u32; D], words: &[u64]) -> Result<Self, ImageError> {
        let n = pixel_count(extent).div_ceil(64);
        if words.len() != n {
            return Err(ImageError::BitmapLength {
                expected: n,
                found: words.len(),
            });
        }
        Self::from_fn(extent, |p| {
            let i = row_major(p, extent);
            (words[i / 64] >> (i % 64)) & 1 == 1
        })
    }

    /// The union of boxes `lo .. hi` (half-open, in pixels; a box with `lo == hi` on an axis
    /// holds no pixel, parts beyond the extent are cut off). O(n b) for b boxes and an n-node
    /// result.
    ///
    /// # Errors
    /// [`ImageError::InvertedBox`] naming the box and axis where `lo > hi`;
    /// [`ImageError::TooLarge`] for an extent beyond [`RegionTree::MAX_DEPTH`].
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// let t = ImageTree::from_boxes([16, 16], &[([0, 0], [8, 8]), ([4, 4], [12, 12])]).unwrap();
    /// assert_eq!(t.len(), 64 + 64 - 16);
    /// assert!(ImageTree::from_boxes([16, 16], &[([0, 5], [8, 4])]).is_err()); // 5 > 4
    /// ```
    pub fn from_boxes(
        extent: [u32; D],
        boxes: &[([u32; D], [u32; D])],
    ) -> Result<Self, ImageError> {
        for (index, (lo, hi)) in boxes.iter().enumerate() {
            if let Some(axis) = (0..D).find(|&a| lo[a] > hi[a]) {
                return Err(ImageError::InvertedBox {
                    index,
                    axis,
                    lo: lo[axis],
                    hi: hi[axis],
                });
            }
        }
        Self::from_region(extent, |min, side| {
            let mut partial = false;
            for (lo, hi) in boxes {
                let cell_hi = |a: usize| u64::from(min[a]) + u64::from(side);
                if (0..D).all(|a| lo[a] <= min[a] && cell_hi(a) <= u64::from(hi[a])) {
                    return Coverage::Full;
                }
                partial |= (0..D).all(|a| u64::from(lo[a]) < cell_hi(a) && min[a] < hi[a]);
            }
            if partial {
                Coverage::Partial
            } else {
                Coverage::Empty
            }
        })
    }

    /// The pixels whose centres `p + 1/2` lie in the closed ball of `centre` and `radius` (a
    /// disc in 2D, in pixel units). Each cell is classified exactly by the nearest and farthest
    /// pixel centre it holds, so the result is the pixel-by-pixel rasterisation; O(n) for an
    /// n-node result (O(perimeter), see the module docs).
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// let t = ImageTree::from_ball([64, 64], [32.0, 32.0], 20.0).unwrap();
    /// let dense = ImageTree::from_fn([64, 64], |[x, y]| {
    ///     let (dx, dy) = (x as f64 + 0.5 - 32.0, y as f64 + 0.5 - 32.0);
    ///     dx * dx + dy * dy <= 400.0
    /// }).unwrap();
    /// assert_eq!(t, dense);
    /// assert!(ImageTree::from_ball([64, 64], [32.0, 32.0], f64::NAN).is_err());
    /// assert!(ImageTree::from_ball([64, 64], [32.0, 32.0], -1.0).is_err());
    /// assert_eq!(ImageTree::from_ball([8, 8], [0.0, 1e300], f64::INFINITY).unwrap().len(), 64);
    /// ```
    ///
    /// A radius of `+inf` covers every pixel; `-0.0` is `0`. Huge finite values do not overflow:
    /// the distances are computed scaled by a power of two (exactly), so a centre at `1e300` with
    /// a radius of `1e299` is still told apart from one with a radius of `2e300`.
    ///
    /// # Errors
    /// [`ImageError::InvalidCentre`] for a NaN or infinite coordinate (naming the axis),
    /// [`ImageError::InvalidRadius`] for a NaN or negative radius, as
    /// [`Ball::new`](crate::query::Ball::new) refuses them.
    pub fn from_ball(extent: [u32; D], centre: [f64; D], radius: f64) -> Result<Self, ImageError> {
        if let Some(axis) = (0..D).find(|&a| !centre[a].is_finite()) {
            return Err(ImageError::InvalidCentre {
                axis,
                value: centre[axis],
            });
        }
        if radius.is_nan() || radius < 0.0 {
            return Err(ImageError::InvalidRadius { radius });
        }
        // Scale every length by a power of two (exact) so that no square overflows: pixel
        // coordinates are below 2^32, and 2^500 squared times D is far below f64::MAX.
        let largest = centre
            .iter()
            .map(|c| c.abs())
            .chain(radius.is_finite().then_some(radius))
            .fold(f64::from(u32::MAX), f64::max);
        let scale = if largest > 2f64.powi(500) {
            2f64.powi(500 - largest.log2().ceil() as i32)
        } else {
            1.0
        };
        let centre = centre.map(|c| c * scale);
        let r2 = (radius * scale) * (radius * scale);
        Self::from_region(extent, |min, side| {
            let (mut near, mut far) = (0.0, 0.0);
            for a in 0..D {
                let lo = (f64::from(min[a]) + 0.5) * scale;
                let hi = (f64::from(min[a]) + f64::from(side) - 0.5) * scale;
                let (dlo, dhi) = ((lo - centre[a]).abs(), (hi - centre[a]).abs());
                let n = if centre[a] < lo || centre[a] > hi {
                    dlo.min(dhi)
                } else {
                    0.0
                };
                far += dlo.max(dhi) * dlo.max(dhi);
                near += n * n;
            }
            if far <= r2 {
                Coverage::Full
            } else if near > r2 {
                Coverage::Empty
            } else {
                Coverage::Partial
            }
        })
    }
}

fn pixel_count<const D: usize>(extent: [u32; D]) -> usize {
    extent.iter().map(|&e| e as usize).product()
}

#[inline]
fn row_major<const D: usize>(p: [u32; D], extent: [u32; D]) -> usize {
    let mut index = 0;
    for a in (0..D).rev() {
        index = index * extent[a] as usize + p[a] as usize;
    }
    index
}
