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

use super::budget::{ball_estimate, box_estimate, check_estimate, counted, DEFAULT_MAX_NODES};
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
    ///
    /// # Errors
    ///
    /// [`ImageError::TooLarge`] for an extent beyond [`RegionTree::MAX_DEPTH`];
    /// [`ImageError::TooManyNodes`] once more than [`DEFAULT_MAX_NODES`] cells are classified
    /// (see [`RegionTree::from_region_with_limit`]).
    pub fn from_region(
        extent: [u32; D],
        classify: impl FnMut([u32; D], u32) -> Coverage,
    ) -> Result<Self, ImageError> {
        Self::from_region_with_limit(extent, DEFAULT_MAX_NODES, classify)
    }

    /// [`RegionTree::from_region`] classifying at most `max_nodes` cells: the construction
    /// stops with an error as soon as it would classify one more. The nodes written are at most
    /// 2^D times the cells classified (cells wholly outside the extent are not classified).
    ///
    /// ```
    /// use orthtree::image::{Coverage, ImageError, ImageTree};
    /// let everywhere_partial = |_: [u32; 2], _: u32| Coverage::Partial;
    /// // a 4 x 4 image split down to pixels classifies 1 + 4 + 16 cells
    /// assert!(ImageTree::from_region_with_limit([4, 4], 21, everywhere_partial).is_ok());
    /// let err = ImageTree::from_region_with_limit([4, 4], 20, everywhere_partial).unwrap_err();
    /// assert!(matches!(err, ImageError::TooManyNodes { limit: 20, estimated: false, .. }));
    /// ```
    ///
    /// # Errors
    ///
    /// [`ImageError::TooLarge`] for an extent beyond [`RegionTree::MAX_DEPTH`];
    /// [`ImageError::TooManyNodes`] (not estimated) once more than `max_nodes` cells are
    /// classified.
    pub fn from_region_with_limit(
        extent: [u32; D],
        max_nodes: u64,
        mut classify: impl FnMut([u32; D], u32) -> Coverage,
    ) -> Result<Self, ImageError> {
        let depth = Self::depth_for(extent)?;
        let mut classified = 0u64;
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
                classified += 1;
                if classified > max_nodes {
                    return Err(counted(max_nodes));
                }
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
                    min = super::iter::child(top.0, top.1, depth, top.2);
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
    ///
    /// # Errors
    ///
    /// As [`RegionTree::from_fn_with_limit`] with [`DEFAULT_MAX_NODES`].
    pub fn from_fn(
        extent: [u32; D],
        pixel: impl FnMut([u32; D]) -> bool,
    ) -> Result<Self, ImageError> {
        Self::from_fn_with_limit(extent, DEFAULT_MAX_NODES, pixel)
    }

    /// [`RegionTree::from_fn`] classifying at most `max_nodes` cells. It classifies every cell
    /// within the extent, at least one per pixel, so an extent of more pixels than `max_nodes`
    /// is refused before `pixel` is called.
    ///
    /// ```
    /// use orthtree::image::{ImageError, ImageTree};
    /// let err = ImageTree::from_fn_with_limit([1 << 20, 1 << 20], 1 << 28, |_| true).unwrap_err();
    /// assert!(matches!(err, ImageError::TooManyNodes { estimated: true, .. }));
    /// ```
    ///
    /// # Errors
    ///
    /// [`ImageError::TooLarge`] for an extent beyond [`RegionTree::MAX_DEPTH`];
    /// [`ImageError::TooManyNodes`] (estimated) for more pixels than `max_nodes`, or (counted)
    /// once more than `max_nodes` cells are classified.
    pub fn from_fn_with_limit(
        extent: [u32; D],
        max_nodes: u64,
        mut pixel: impl FnMut([u32; D]) -> bool,
    ) -> Result<Self, ImageError> {
        Self::depth_for(extent)?;
        let pixels: f64 = extent.iter().map(|&e| f64::from(e)).product();
        check_estimate(pixels, max_nodes)?;
        let mut t = Self::from_region_with_limit(extent, max_nodes, |min, side| {
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
        check_length(pixel_count(extent), pixels.len())?;
        // Backed by the data: one bool per pixel is held already.
        Self::from_fn_with_limit(extent, u64::MAX, |p| pixels[row_major(p, extent)])
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
        check_length(pixel_count(extent).div_ceil(64), words.len())?;
        // Backed by the data: one bit per pixel is held already.
        Self::from_fn_with_limit(extent, u64::MAX, |p| {
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
    /// [`ImageError::TooLarge`] for an extent beyond [`RegionTree::MAX_DEPTH`];
    /// [`ImageError::TooManyNodes`] above [`DEFAULT_MAX_NODES`] cells classified (see
    /// [`RegionTree::from_boxes_with_limit`]).
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
        Self::from_boxes_with_limit(extent, boxes, DEFAULT_MAX_NODES)
    }

    /// [`RegionTree::from_boxes`] classifying at most `max_nodes` cells. A single box is
    /// refused before building when the cells its faces cut (a lower bound of the cells
    /// classified) pass the limit; several boxes are counted while building only (a box may
    /// hide another's faces).
    ///
    /// ```
    /// use orthtree::image::{ImageError, VoxelTree};
    /// let side = 1 << 21; // the deepest in 3-D
    /// // faces at odd coordinates cut cells at every level: about 2^40 cells
    /// let odd = ([1, 1, 1], [side - 1, side - 1, side - 1]);
    /// let err = VoxelTree::from_boxes([side; 3], &[odd]).unwrap_err();
    /// assert!(matches!(err, ImageError::TooManyNodes { estimated: true, .. }));
    /// // faces on the grid of the largest cells cost nothing
    /// let aligned = ([0, 0, 0], [side / 2, side, side]);
    /// assert_eq!(VoxelTree::from_boxes([side; 3], &[aligned]).unwrap().node_count(), 9);
    /// ```
    ///
    /// # Errors
    ///
    /// As [`RegionTree::from_boxes`], and [`ImageError::TooManyNodes`] above `max_nodes`.
    pub fn from_boxes_with_limit(
        extent: [u32; D],
        boxes: &[([u32; D], [u32; D])],
        max_nodes: u64,
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
        if let [single] = boxes {
            let depth = Self::depth_for(extent)?;
            check_estimate(box_estimate(extent, depth, *single), max_nodes)?;
        }
        Self::from_region_with_limit(extent, max_nodes, |min, side| {
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
    /// [`Ball::new`](crate::query::Ball::new) refuses them; [`ImageError::TooLarge`] for an
    /// extent beyond [`RegionTree::MAX_DEPTH`]; [`ImageError::TooManyNodes`] above
    /// [`DEFAULT_MAX_NODES`] cells classified (see [`RegionTree::from_ball_with_limit`]).
    pub fn from_ball(extent: [u32; D], centre: [f64; D], radius: f64) -> Result<Self, ImageError> {
        Self::from_ball_with_limit(extent, centre, radius, DEFAULT_MAX_NODES)
    }

    /// [`RegionTree::from_ball`] classifying at most `max_nodes` cells: refused before building
    /// when the sphere's surface within the extent, over 2 sqrt(D) (about the boundary pixels,
    /// each classified), passes the limit, and counted while building.
    ///
    /// ```
    /// use orthtree::image::{ImageError, VoxelTree};
    /// let side = 1 << 21; // the deepest in 3-D
    /// let half = f64::from(side / 2);
    /// // a sphere of radius 2^19 at depth 21: about 10^12 boundary voxels
    /// let err = VoxelTree::from_ball([side; 3], [half; 3], half / 2.0).unwrap_err();
    /// assert!(matches!(err, ImageError::TooManyNodes { estimated: true, .. }));
    /// assert!(err.to_string().contains("the limit is 268435456"));
    /// ```
    ///
    /// # Errors
    ///
    /// As [`RegionTree::from_ball`], and [`ImageError::TooManyNodes`] above `max_nodes`.
    pub fn from_ball_with_limit(
        extent: [u32; D],
        centre: [f64; D],
        radius: f64,
        max_nodes: u64,
    ) -> Result<Self, ImageError> {
        Self::depth_for(extent)?;
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
        check_estimate(ball_estimate(extent, centre, r2, scale), max_nodes)?;
        Self::from_region_with_limit(extent, max_nodes, |min, side| {
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

/// `Ok` when a bitmap (or a row) of `found` values has the `expected` length, else
/// [`ImageError::BitmapLength`] naming both.
pub(super) fn check_length(expected: usize, found: usize) -> Result<(), ImageError> {
    (found == expected)
        .then_some(())
        .ok_or(ImageError::BitmapLength { expected, found })
}

/// The number of pixels of an image of this extent.
pub(super) fn pixel_count<const D: usize>(extent: [u32; D]) -> usize {
    extent.iter().map(|&e| e as usize).product()
}

/// The index of pixel `p` in row-major order (axis 0 varying fastest).
#[inline]
pub(super) fn row_major<const D: usize>(p: [u32; D], extent: [u32; D]) -> usize {
    (0..D)
        .rev()
        .fold(0, |index, a| index * extent[a] as usize + p[a] as usize)
}
