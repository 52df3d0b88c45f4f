//! Pixel counts, and count-only Boolean operations (roaring's `intersection_len` and siblings):
//! the same simultaneous traversal as `ops.rs`, summing cell volumes 2^(D (k - level)) instead of
//! writing nodes. O(n1 + n2) time, O(k) space, no allocation beyond a fixed stack.

use super::ops::{subtree_end, BoolOp, Unary};
use super::{ImageError, RegionTree, BLACK, INTERNAL};

/// The number of black pixels in the subtree starting at `start`, a node at `level` of a tree of
/// depth `depth`, and the subtree's end.
fn subtree_black<const D: usize>(s: &[u8], start: usize, level: u8, depth: u8) -> (usize, u64) {
    // remaining children of each open internal node (depth <= 31)
    let mut rem = [0u32; 33];
    let mut top = 0;
    let mut lvl = level;
    let mut count = 0u64;
    let mut i = start;
    loop {
        let x = s[i];
        i += 1;
        if x == INTERNAL {
            rem[top] = 1 << D;
            top += 1;
            lvl += 1;
            continue;
        }
        if x == BLACK {
            count += 1u64 << (D as u32 * u32::from(depth - lvl));
        }
        loop {
            if top == 0 {
                return (i, count);
            }
            rem[top - 1] -= 1;
            if rem[top - 1] > 0 {
                break;
            }
            top -= 1;
            lvl -= 1;
        }
    }
}

/// The number of black pixels of `op(a, b)`.
fn combine_len<const D: usize>(a: &[u8], b: &[u8], depth: u8, op: BoolOp) -> u64 {
    let volume = |level: u8| 1u64 << (D as u32 * u32::from(depth - level));
    let apply = |f: Unary, s: &[u8], at: usize, level: u8| -> (usize, u64) {
        match f {
            Unary::Const(c) => (subtree_end::<D>(s, at), u64::from(c) * volume(level)),
            Unary::Keep => subtree_black::<D>(s, at, level, depth),
            Unary::Flip => {
                let (end, black) = subtree_black::<D>(s, at, level, depth);
                (end, volume(level) - black)
            }
        }
    };
    let mut rem = [0u32; 33];
    let mut top = 0;
    let mut count = 0u64;
    let (mut i, mut j) = (0, 0);
    loop {
        let level = top as u8;
        let (x, y) = (a[i], b[j]);
        match (x == INTERNAL, y == INTERNAL) {
            (true, true) => {
                rem[top] = 1 << D;
                top += 1;
                i += 1;
                j += 1;
                continue;
            }
            (false, false) => {
                if op.apply(x == BLACK, y == BLACK) {
                    count += volume(level);
                }
                i += 1;
                j += 1;
            }
            (false, true) => {
                let (end, c) = apply(op.with_leaf(x, true), b, j, level);
                count += c;
                i += 1;
                j = end;
            }
            (true, false) => {
                let (end, c) = apply(op.with_leaf(y, false), a, i, level);
                count += c;
                i = end;
                j += 1;
            }
        }
        loop {
            if top == 0 {
                return count;
            }
            rem[top - 1] -= 1;
            if rem[top - 1] > 0 {
                break;
            }
            top -= 1;
        }
    }
}

impl<const D: usize> RegionTree<D> {
    /// The number of black pixels (voxels in 3D).
    ///
    /// # Complexity
    /// O(n) for n nodes.
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// let t = ImageTree::from_boxes([10, 10], &[([1, 2], [4, 7])]).unwrap();
    /// assert_eq!(t.len(), 15);
    /// ```
    pub fn len(&self) -> u64 {
        subtree_black::<D>(&self.nodes, 0, 0, self.depth).1
    }

    /// Whether no pixel is black (the tree is one white leaf). O(1).
    pub fn is_empty(&self) -> bool {
        self.nodes == [super::WHITE]
    }

    /// The number of black pixels of `op(self, other)`, building nothing.
    ///
    /// # Complexity
    /// O(n1 + n2) for trees of n1 and n2 nodes.
    ///
    /// # Panics
    /// If the extents differ.
    ///
    /// ```
    /// use orthtree::image::{BoolOp, ImageTree};
    /// let a = ImageTree::from_boxes([8, 8], &[([0, 0], [5, 5])]).unwrap();
    /// let b = ImageTree::from_boxes([8, 8], &[([3, 3], [8, 8])]).unwrap();
    /// for op in [BoolOp::And, BoolOp::Or, BoolOp::Xor, BoolOp::Sub] {
    ///     assert_eq!(a.combine_len(&b, op), a.try_combine(&b, op).unwrap().len());
    /// }
    /// ```
    pub fn combine_len(&self, other: &Self, op: BoolOp) -> u64 {
        self.try_combine_len(other, op)
            .unwrap_or_else(|e| panic!("{e}"))
    }

    /// The number of black pixels of `op(self, other)`, building nothing.
    ///
    /// # Complexity
    /// O(n1 + n2) for trees of n1 and n2 nodes.
    ///
    /// # Errors
    /// [`ImageError::SizeMismatch`] naming both extents if they differ.
    ///
    /// ```
    /// use orthtree::image::{BoolOp, ImageError, ImageTree};
    /// let a = ImageTree::full([8, 8]).unwrap();
    /// assert_eq!(a.try_combine_len(&a, BoolOp::And), Ok(64));
    /// let b = ImageTree::full([8, 9]).unwrap();
    /// let err = a.try_combine_len(&b, BoolOp::And).unwrap_err();
    /// assert_eq!(err, ImageError::SizeMismatch { left: vec![8, 8], right: vec![8, 9] });
    /// ```
    pub fn try_combine_len(&self, other: &Self, op: BoolOp) -> Result<u64, ImageError> {
        self.check_same_size(other)?;
        Ok(combine_len::<D>(&self.nodes, &other.nodes, self.depth, op))
    }

    /// [`RegionTree::intersection_len`], or [`ImageError::SizeMismatch`] if the extents differ.
    ///
    /// # Errors
    /// [`ImageError::SizeMismatch`] naming both extents.
    pub fn try_intersection_len(&self, other: &Self) -> Result<u64, ImageError> {
        self.try_combine_len(other, BoolOp::And)
    }

    /// [`RegionTree::union_len`], or [`ImageError::SizeMismatch`] if the extents differ.
    ///
    /// # Errors
    /// [`ImageError::SizeMismatch`] naming both extents.
    pub fn try_union_len(&self, other: &Self) -> Result<u64, ImageError> {
        self.try_combine_len(other, BoolOp::Or)
    }

    /// [`RegionTree::difference_len`], or [`ImageError::SizeMismatch`] if the extents differ.
    ///
    /// # Errors
    /// [`ImageError::SizeMismatch`] naming both extents.
    pub fn try_difference_len(&self, other: &Self) -> Result<u64, ImageError> {
        self.try_combine_len(other, BoolOp::Sub)
    }

    /// [`RegionTree::symmetric_difference_len`], or [`ImageError::SizeMismatch`] if the extents
    /// differ.
    ///
    /// # Errors
    /// [`ImageError::SizeMismatch`] naming both extents.
    pub fn try_symmetric_difference_len(&self, other: &Self) -> Result<u64, ImageError> {
        self.try_combine_len(other, BoolOp::Xor)
    }

    /// [`RegionTree::is_disjoint`], or [`ImageError::SizeMismatch`] if the extents differ.
    ///
    /// # Errors
    /// [`ImageError::SizeMismatch`] naming both extents.
    pub fn try_is_disjoint(&self, other: &Self) -> Result<bool, ImageError> {
        Ok(self.try_intersection_len(other)? == 0)
    }

    /// The number of black pixels of `self & other`, building nothing.
    ///
    /// # Panics
    /// If the extents differ.
    pub fn intersection_len(&self, other: &Self) -> u64 {
        self.combine_len(other, BoolOp::And)
    }

    /// The number of black pixels of `self | other`, building nothing.
    ///
    /// # Panics
    /// If the extents differ.
    pub fn union_len(&self, other: &Self) -> u64 {
        self.combine_len(other, BoolOp::Or)
    }

    /// The number of black pixels of `self - other`, building nothing.
    ///
    /// # Panics
    /// If the extents differ.
    pub fn difference_len(&self, other: &Self) -> u64 {
        self.combine_len(other, BoolOp::Sub)
    }

    /// The number of black pixels of `self ^ other`, building nothing.
    ///
    /// # Panics
    /// If the extents differ.
    pub fn symmetric_difference_len(&self, other: &Self) -> u64 {
        self.combine_len(other, BoolOp::Xor)
    }

    /// Whether `self` and `other` have no black pixel in common, building nothing.
    ///
    /// # Panics
    /// If the extents differ.
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// let a = ImageTree::from_boxes([8, 8], &[([0, 0], [4, 4])]).unwrap();
    /// let b = ImageTree::from_boxes([8, 8], &[([4, 4], [8, 8])]).unwrap();
    /// assert!(a.is_disjoint(&b) && !a.is_disjoint(&a));
    /// ```
    pub fn is_disjoint(&self, other: &Self) -> bool {
        self.intersection_len(other) == 0
    }
}
