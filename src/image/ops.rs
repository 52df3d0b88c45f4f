//! Boolean operations by simultaneous traversal (exercise 14.12), on the linear pre-order form.
//!
//! The two node sequences are read in lockstep, one node pair at a time, which visits the pairs
//! of cells the two trees share (Hunter and Steiglitz's merge of quadtrees, "Operations on images
//! using quad trees", IEEE PAMI 1(2), 1979; Samet, *The Design and Analysis of Spatial Data
//! Structures*, section 5.1):
//!
//! - two leaves: one leaf, the operation of the two colours;
//! - a leaf of colour `c` against a subtree `S` of the other tree: the result in that cell is
//!   `op(c, S)`, which is a constant (one leaf), `S` itself (copied as one slice) or the
//!   complement of `S` (copied with the colours swapped); the other cursor skips `S`;
//! - two internal nodes: an internal node, then the 2^D child pairs.
//!
//! The result is written by the shared writer, which replaces an internal node whose 2^D
//! children came out as leaves of one colour by one leaf as soon as its last child is written, so
//! the result is canonical (copied and complemented subtrees of canonical inputs are canonical).
//! Each input node is read once or twice (once in the lockstep walk or the skip, once when copied),
//! so the cost is **O(n1 + n2)** time and O(k) extra space (the writer's stack of open nodes).

use super::{ImageError, RegionTree, Writer, BLACK, INTERNAL, WHITE};

/// A binary Boolean operation on pixels; those that map (white, white) to white, so the padding
/// outside the extent stays white.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BoolOp {
    /// Black where both are black (`&`).
    And,
    /// Black where either is black (`|`).
    Or,
    /// Black where exactly one is black (`^`).
    Xor,
    /// Black where the left is black and the right white (`-`).
    Sub,
}

impl BoolOp {
    /// The truth table: bit `2 a + b` is `op(a, b)`.
    #[inline]
    const fn table(self) -> u8 {
        match self {
            BoolOp::And => 0b1000,
            BoolOp::Or => 0b1110,
            BoolOp::Xor => 0b0110,
            BoolOp::Sub => 0b0100,
        }
    }

    /// The colour `op(a, b)` of two leaf colours.
    ///
    /// ```
    /// use orthtree::image::BoolOp;
    /// assert!(BoolOp::Sub.apply(true, false) && !BoolOp::Sub.apply(true, true));
    /// assert!(BoolOp::Xor.apply(false, true) && !BoolOp::And.apply(false, true));
    /// ```
    #[inline]
    pub const fn apply(self, a: bool, b: bool) -> bool {
        (self.table() >> (2 * a as u8 + b as u8)) & 1 == 1
    }

    /// What `op(c, x)` (left leaf `c`) or `op(x, c)` (right leaf `c`) does to `x`.
    #[inline]
    pub(crate) fn with_leaf(self, c: u8, leaf_on_left: bool) -> Unary {
        let c = c == BLACK;
        let (f0, f1) = if leaf_on_left {
            (self.apply(c, false), self.apply(c, true))
        } else {
            (self.apply(false, c), self.apply(true, c))
        };
        match (f0, f1) {
            (false, false) => Unary::Const(WHITE),
            (true, true) => Unary::Const(BLACK),
            (false, true) => Unary::Keep,
            (true, false) => Unary::Flip,
        }
    }
}

/// A Boolean function of one pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Unary {
    Const(u8),
    Keep,
    Flip,
}

/// The end of the subtree starting at `i` (one past its last node): O(size of the subtree).
#[inline]
pub(crate) fn subtree_end<const D: usize>(s: &[u8], mut i: usize) -> usize {
    let mut need = 1usize;
    while need > 0 {
        // internal (2): 2^D more nodes to read; leaf (0, 1): one fewer
        need += ((s[i] >> 1) as usize) << D;
        need -= 1;
        i += 1;
    }
    i
}

/// The merge of two canonical node sequences of the same depth.
pub(crate) fn combine<const D: usize>(a: &[u8], b: &[u8], op: BoolOp) -> Vec<u8> {
    let mut w = Writer::<D>::with_capacity(a.len().max(b.len()));
    let (mut i, mut j) = (0, 0);
    loop {
        let (x, y) = (a[i], b[j]);
        match (x == INTERNAL, y == INTERNAL) {
            (true, true) => {
                w.open();
                i += 1;
                j += 1;
                continue;
            }
            (false, false) => {
                w.leaf(op.apply(x == BLACK, y == BLACK) as u8);
                i += 1;
                j += 1;
            }
            (false, true) => {
                let end = subtree_end::<D>(b, j);
                emit(&mut w, op.with_leaf(x, true), &b[j..end]);
                i += 1;
                j = end;
            }
            (true, false) => {
                let end = subtree_end::<D>(a, i);
                emit(&mut w, op.with_leaf(y, false), &a[i..end]);
                i = end;
                j += 1;
            }
        }
        if w.done() {
            debug_assert!(i == a.len() && j == b.len());
            return w.out;
        }
    }
}

#[inline]
fn emit<const D: usize>(w: &mut Writer<D>, f: Unary, subtree: &[u8]) {
    match f {
        Unary::Const(c) => w.leaf(c),
        Unary::Keep => w.copy(subtree),
        Unary::Flip => w.complement(subtree),
    }
}

impl<const D: usize> RegionTree<D> {
    pub(crate) fn check_same_size(&self, other: &Self) -> Result<(), ImageError> {
        if self.extent != other.extent {
            return Err(ImageError::SizeMismatch {
                left: self.extent.to_vec(),
                right: other.extent.to_vec(),
            });
        }
        Ok(())
    }

    /// `op` applied pixel by pixel, by simultaneous traversal: O(n1 + n2) time, canonical
    /// result; [`ImageError::SizeMismatch`] if the extents differ.
    ///
    /// # Errors
    /// [`ImageError::SizeMismatch`] naming both extents if they differ.
    ///
    /// ```
    /// use orthtree::image::{BoolOp, ImageTree};
    /// let a = ImageTree::from_boxes([4, 4], &[([0, 0], [2, 4])]).unwrap();
    /// let b = ImageTree::from_boxes([4, 4], &[([0, 0], [4, 2])]).unwrap();
    /// assert_eq!(a.try_combine(&b, BoolOp::Xor).unwrap().len(), 8);
    /// let c = ImageTree::empty([4, 5]).unwrap();
    /// assert!(a.try_combine(&c, BoolOp::Or).is_err());
    /// ```
    pub fn try_combine(&self, other: &Self, op: BoolOp) -> Result<Self, ImageError> {
        self.check_same_size(other)?;
        Ok(RegionTree {
            nodes: combine::<D>(&self.nodes, &other.nodes, op),
            ..*self
        })
    }

    /// The union (`|`); [`ImageError::SizeMismatch`] if the extents differ.
    ///
    /// # Errors
    /// [`ImageError::SizeMismatch`] naming both extents if they differ.
    ///
    /// # Complexity
    /// O(n1 + n2) for trees of n1 and n2 nodes.
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// let a = ImageTree::from_boxes([4, 4], &[([0, 0], [2, 2])]).unwrap();
    /// let b = ImageTree::from_boxes([4, 4], &[([2, 2], [4, 4])]).unwrap();
    /// assert_eq!(a.try_union(&b).unwrap().len(), 8);
    /// ```
    pub fn try_union(&self, other: &Self) -> Result<Self, ImageError> {
        self.try_combine(other, BoolOp::Or)
    }

    /// The intersection (`&`); [`ImageError::SizeMismatch`] if the extents differ.
    ///
    /// # Errors
    /// [`ImageError::SizeMismatch`] naming both extents if they differ.
    ///
    /// # Complexity
    /// O(n1 + n2) for trees of n1 and n2 nodes.
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// let a = ImageTree::from_boxes([4, 4], &[([0, 0], [3, 3])]).unwrap();
    /// let b = ImageTree::from_boxes([4, 4], &[([2, 2], [4, 4])]).unwrap();
    /// assert_eq!(a.try_intersection(&b).unwrap().len(), 1);
    /// ```
    pub fn try_intersection(&self, other: &Self) -> Result<Self, ImageError> {
        self.try_combine(other, BoolOp::And)
    }

    /// The difference `self - other` (`-`); [`ImageError::SizeMismatch`] if the extents differ.
    ///
    /// # Errors
    /// [`ImageError::SizeMismatch`] naming both extents if they differ.
    ///
    /// # Complexity
    /// O(n1 + n2) for trees of n1 and n2 nodes.
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// let a = ImageTree::full([4, 4]).unwrap();
    /// let b = ImageTree::from_boxes([4, 4], &[([1, 1], [3, 3])]).unwrap();
    /// assert_eq!(a.try_difference(&b).unwrap().len(), 12);
    /// ```
    pub fn try_difference(&self, other: &Self) -> Result<Self, ImageError> {
        self.try_combine(other, BoolOp::Sub)
    }

    /// The symmetric difference (`^`); [`ImageError::SizeMismatch`] if the extents differ.
    ///
    /// # Errors
    /// [`ImageError::SizeMismatch`] naming both extents if they differ.
    ///
    /// # Complexity
    /// O(n1 + n2) for trees of n1 and n2 nodes.
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// let a = ImageTree::from_boxes([4, 4], &[([0, 0], [2, 2])]).unwrap();
    /// assert!(a.try_symmetric_difference(&a).unwrap().is_empty());
    /// ```
    pub fn try_symmetric_difference(&self, other: &Self) -> Result<Self, ImageError> {
        self.try_combine(other, BoolOp::Xor)
    }

    /// The union (`|`).
    ///
    /// # Panics
    /// If the extents differ (see [`RegionTree::try_union`]).
    pub fn union(&self, other: &Self) -> Self {
        self.try_union(other).unwrap_or_else(|e| panic!("{e}"))
    }

    /// The intersection (`&`).
    ///
    /// # Panics
    /// If the extents differ (see [`RegionTree::try_intersection`]).
    pub fn intersection(&self, other: &Self) -> Self {
        self.try_intersection(other)
            .unwrap_or_else(|e| panic!("{e}"))
    }

    /// The difference `self - other` (`-`).
    ///
    /// # Panics
    /// If the extents differ (see [`RegionTree::try_difference`]).
    pub fn difference(&self, other: &Self) -> Self {
        self.try_difference(other).unwrap_or_else(|e| panic!("{e}"))
    }

    /// The symmetric difference (`^`).
    ///
    /// # Panics
    /// If the extents differ (see [`RegionTree::try_symmetric_difference`]).
    pub fn symmetric_difference(&self, other: &Self) -> Self {
        self.try_symmetric_difference(other)
            .unwrap_or_else(|e| panic!("{e}"))
    }

    /// The complement within the extent (`!`): pixels outside the extent stay white. For a
    /// power-of-two cube this swaps the leaf colours, O(n); otherwise it is the symmetric
    /// difference with [`RegionTree::full`], O(n + the size of the full image's tree, which is
    /// O(perimeter of the extent)).
    ///
    /// # Panics
    /// Never: the extent was accepted when `self` was built, so its full image exists.
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// let a = ImageTree::from_boxes([6, 5], &[([0, 0], [2, 2])]).unwrap();
    /// assert_eq!(a.complement().len(), 30 - 4);
    /// assert_eq!(a.complement().complement(), a);
    /// ```
    pub fn complement(&self) -> Self {
        if self.is_cube() {
            let mut nodes = self.nodes.clone();
            nodes.iter_mut().for_each(|x| *x ^= (*x >> 1) ^ 1);
            return RegionTree { nodes, ..*self };
        }
        let full = Self::full(self.extent).expect("the extent was accepted before");
        RegionTree {
            nodes: combine::<D>(&self.nodes, &full.nodes, BoolOp::Xor),
            ..*self
        }
    }

    /// Replaces `self` by `op(self, other)` (the fallible form of `&=`, `|=`, `^=`, `-=`);
    /// `self` is unchanged on error.
    ///
    /// # Errors
    /// [`ImageError::SizeMismatch`] naming both extents if they differ.
    ///
    /// ```
    /// use orthtree::image::{BoolOp, ImageTree};
    /// let mut a = ImageTree::from_boxes([4, 4], &[([0, 0], [2, 2])]).unwrap();
    /// a.try_combine_assign(&ImageTree::full([4, 4]).unwrap(), BoolOp::Xor).unwrap();
    /// assert_eq!(a.len(), 12);
    /// assert!(a.try_combine_assign(&ImageTree::full([4, 3]).unwrap(), BoolOp::Or).is_err());
    /// assert_eq!(a.len(), 12);
    /// ```
    pub fn try_combine_assign(&mut self, other: &Self, op: BoolOp) -> Result<(), ImageError> {
        self.check_same_size(other)?;
        self.nodes = combine::<D>(&self.nodes, &other.nodes, op);
        Ok(())
    }

    /// Replaces `self` by `op(self, other)`.
    pub(crate) fn assign(&mut self, other: &Self, op: BoolOp) {
        self.try_combine_assign(other, op)
            .unwrap_or_else(|e| panic!("{e}"));
    }
}
