//! Region quadtrees and octrees for binary images and voxel grids (exercises 14.11 and 14.12 of
//! de Berg, Cheong, van Kreveld and Overmars, *Computational Geometry*, chapter 14).
//!
//! A [`RegionTree<D>`] covers a cube of side 2^k pixels (voxels in 3D); a cell is split into its
//! 2^D children while its pixels are not all of one colour. The tree is kept in **canonical
//! form**: no internal node has 2^D children that are leaves of one colour, so two trees of the
//! same extent are equal as values (`==`, derived) exactly when their images are equal.
//!
//! # Representation: a linear pre-order form, one byte per node
//!
//! The tree is not stored on the shared arena ([`Tree`](crate::Tree)) but as its **pre-order
//! sequence of node kinds**, one `u8` per node: white leaf, black leaf or internal node. The
//! children of a node are the 2^D subtrees that follow it, in child order (bit `i` of the child
//! index is the upper half along axis `i`, as everywhere in the crate), so the sequence of leaves
//! is the Morton (z-) order of their cells. The cell of a node is implied by its position; a
//! [`Block`] iterator ([`RegionTree::blocks`]) recovers the cells when needed.
//!
//! Why: the Boolean operations of exercise 14.12 are simultaneous traversals of two trees, and on
//! this form they are a **linear merge of two byte strings** (see `ops.rs`): no pointer chasing,
//! subtrees copied or complemented with one pass over a contiguous slice, and the result written
//! sequentially, collapsing on the fly. Memory is **1 byte per node** (plus 4 bytes per axis for
//! the extent), where an arena node with parent, first-child and payload takes 12-16 bytes.
//! What the form does not give is random access: [`RegionTree::contains`] is a scan, O(n).
//!
//! # Sizes that are not powers of two
//!
//! An image of extent `w x h` (any positive sizes; `[u32; D]` in general) is padded to the cube of
//! side 2^k, k the smallest with 2^k >= max(w, h), with **background (white)**; every operation
//! keeps the padding white (the complement is taken within the extent only), and conversions back
//! to bitmaps crop to the extent. Two operands must have the same extent: otherwise the `try_`
//! methods return [`ImageError::SizeMismatch`] and the operators panic. The depth is at most
//! [`RegionTree::MAX_DEPTH`] = min(31, 63 / D) so that every pixel count fits a `u64`.
//!
//! # Size bound (exercise 14.11)
//!
//! Let the black pixels of a 2^k x 2^k image be those whose centres lie in a plane region whose
//! boundary consists of `c` closed curves of total length `P` (in pixel units). An internal node
//! at level `l` (cell side `s = 2^(k-l) >= 2`) holds pixel centres of both colours, so the segment
//! joining two of them, which lies in the open cell, crosses the boundary: the boundary meets the
//! **open** cell. Cut each curve into pieces of length at most `s` (at most `P_i / s + 1` pieces
//! for a curve of length `P_i`); a piece has width and height at most `s`, so it meets at most
//! 2 open columns and 2 open rows of cells of side `s`, that is at most 4 cells. Hence level `l`
//! has at most `4 (P / s + c)` internal nodes and, summing over `s = 2^k, ..., 2`,
//! `I <= 4 P (1/2 + 1/4 + ...) + 4 c k < 4 P + 4 c k`. Every node but the root is one of the 4
//! children of an internal node, so the tree has
//!
//! **n = 4 I + 1 <= 16 P + 16 c k + 1 nodes**
//!
//! (the quadtree analogue of Theorem 14.2's count of nodes per level). The test
//! `tests/library/image/image_bounds.rs` checks it on random discs (`P = 2 pi r`) and random
//! star-shaped polygons.
//!
//! ```
//! use orthtree::image::{ImageTree, RegionTree};
//! // a 5 x 3 image (padded to 8 x 8), row-major, x fastest
//! let a = ImageTree::from_bools([5, 3], &[
//!     true, true, false, false, false,
//!     true, true, false, false, false,
//!     false, false, false, false, true,
//! ]).unwrap();
//! let b = ImageTree::from_boxes([5, 3], &[([0, 0], [5, 1])]).unwrap(); // the first row
//! assert_eq!((&a | &b).len(), 5 + 2 + 1);
//! assert_eq!((&a & &b).len(), 2);
//! assert_eq!(a.intersection_len(&b), 2); // the same, building nothing
//! assert_eq!((!&a).len(), 15 - 5); // complement within the 5 x 3 extent
//! assert_eq!(&a - &b, &a & &!&b);
//! assert!((&a ^ &b).is_canonical());
//! assert_eq!((&a | &b).to_bools()[..5], [true; 5]);
//! ```

mod budget;
mod build;
mod count;
pub(crate) mod iter;
mod operators;
mod ops;
mod rows;
mod validate;

pub use budget::DEFAULT_MAX_NODES;
pub use build::Coverage;
pub use iter::Block;
pub use ops::BoolOp;
pub use rows::RowBuilder;
pub use validate::Malformation;

use core::fmt;

/// Node kind: a leaf whose pixels are all white (background).
pub(crate) const WHITE: u8 = 0;
/// Node kind: a leaf whose pixels are all black (foreground).
pub(crate) const BLACK: u8 = 1;
/// Node kind: an internal node, followed by its 2^D subtrees.
pub(crate) const INTERNAL: u8 = 2;

/// A region quadtree (D = 2), octree (D = 3) or 2^D-tree of a binary image of extent `[u32; D]`,
/// in canonical form, stored as its pre-order sequence of node kinds (see the [module
/// docs](self)).
///
/// ```
/// use orthtree::image::VoxelTree;
/// let v = VoxelTree::from_boxes([4, 4, 4], &[([0, 0, 0], [2, 2, 2])]).unwrap();
/// assert_eq!(v.len(), 8);
/// assert_eq!(v.node_count(), 9); // the root and its 8 children
/// assert!(v.contains([1, 1, 1]) && !v.contains([2, 1, 1]));
/// ```
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct RegionTree<const D: usize> {
    extent: [u32; D],
    depth: u8,
    nodes: Vec<u8>,
}

/// A region quadtree of a 2D binary image.
pub type ImageTree = RegionTree<2>;

/// A region octree of a 3D voxel grid.
pub type VoxelTree = RegionTree<3>;

/// What can go wrong when building or combining region trees.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum ImageError {
    /// The two operands of a Boolean operation have different extents.
    SizeMismatch {
        /// The left operand's extent.
        left: Vec<u32>,
        /// The right operand's extent.
        right: Vec<u32>,
    },
    /// An extent needs a depth beyond [`RegionTree::MAX_DEPTH`].
    TooLarge {
        /// The extent asked for.
        extent: Vec<u32>,
        /// The largest depth allowed in this dimension.
        max_depth: u8,
    },
    /// A dense bitmap has the wrong length for its extent.
    BitmapLength {
        /// The length the extent asks for (pixels, or `u64` words for packed bitmaps).
        expected: usize,
        /// The length given.
        found: usize,
    },
    /// A node sequence that is not a canonical region tree (from [`RegionTree::validate`] or
    /// [`RegionTree::from_nodes`]).
    Malformed {
        /// The index of the offending node in pre-order.
        position: usize,
        /// The invariant of the canonical form broken there.
        invariant: Malformation,
    },
    /// Building the tree would hold more bytes than the budget allows
    /// ([`RowBuilder::max_bytes`]).
    MemoryLimit {
        /// The bytes it would hold (at least).
        needed: u64,
        /// The budget.
        limit: u64,
    },
    /// A row was pushed into a [`RowBuilder`] past the image's height.
    TooManyRows {
        /// The height.
        height: u32,
    },
    /// A [`RowBuilder`] was finished before every row was pushed.
    MissingRows {
        /// The height.
        height: u32,
        /// The rows pushed.
        found: u32,
    },
    /// A ball's radius is NaN or negative.
    InvalidRadius {
        /// The radius given.
        radius: f64,
    },
    /// A ball's centre has a NaN or infinite coordinate.
    InvalidCentre {
        /// The axis.
        axis: usize,
        /// The coordinate given.
        value: f64,
    },
    /// A shape constructor would classify more cells than its limit
    /// ([`DEFAULT_MAX_NODES`] unless a `_with_limit` form sets another).
    TooManyNodes {
        /// The cells it needs: an estimate made before building, or the limit plus one when
        /// the count passed the limit while building.
        nodes: u64,
        /// The limit.
        limit: u64,
        /// Whether `nodes` is the estimate made before building.
        estimated: bool,
    },
    /// A box has `lo > hi` on an axis.
    InvertedBox {
        /// The index of the box in the list given.
        index: usize,
        /// The axis.
        axis: usize,
        /// The lower bound given.
        lo: u32,
        /// The upper bound given.
        hi: u32,
    },
}

impl fmt::Display for ImageError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ImageError::SizeMismatch { left, right } => {
                write!(f, "operands differ in size: {left:?} and {right:?}")
            }
            ImageError::TooLarge { extent, max_depth } => write!(
                f,
                "extent {extent:?} needs a depth beyond the limit {max_depth}"
            ),
            ImageError::BitmapLength { expected, found } => {
                write!(f, "bitmap has length {found}, expected {expected}")
            }
            ImageError::Malformed {
                position,
                invariant,
            } => write!(f, "malformed region tree at node {position}: {invariant}"),
            ImageError::MemoryLimit { needed, limit } => write!(
                f,
                "building the region tree needs more than {needed} bytes; the limit is {limit}"
            ),
            ImageError::TooManyRows { height } => {
                write!(f, "row pushed past the image's height {height}")
            }
            ImageError::MissingRows { height, found } => {
                write!(f, "image has {found} rows of its height {height}")
            }
            ImageError::InvalidRadius { radius } => {
                write!(f, "ball radius {radius} is not a non-negative number")
            }
            ImageError::InvalidCentre { axis, value } => {
                write!(
                    f,
                    "ball centre has {value} on axis {axis}, expected a finite number"
                )
            }
            ImageError::TooManyNodes {
                nodes,
                limit,
                estimated: true,
            } => write!(
                f,
                "this shape needs about {nodes} cells (estimated before building); the limit \
                 is {limit}"
            ),
            ImageError::TooManyNodes { limit, .. } => write!(
                f,
                "this shape needs more than {limit} cells (counted while building); the limit \
                 is {limit}"
            ),
            ImageError::InvertedBox {
                index,
                axis,
                lo,
                hi,
            } => write!(f, "box {index} has lo {lo} above hi {hi} on axis {axis}"),
        }
    }
}

impl std::error::Error for ImageError {}

impl<const D: usize> fmt::Debug for RegionTree<D> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("RegionTree")
            .field("extent", &self.extent)
            .field("depth", &self.depth)
            .field("nodes", &self.nodes.len())
            .field("len", &self.len())
            .finish()
    }
}

impl<const D: usize> RegionTree<D> {
    /// The deepest tree allowed: min(31, 63 / D) (31 in 2D, 21 in 3D), so that a side fits a
    /// `u32` and a pixel count a `u64`.
    pub const MAX_DEPTH: u8 = if 63 / D > 31 { 31 } else { (63 / D) as u8 };

    /// The depth k of an image of this extent: the smallest k with 2^k >= every side, or
    /// [`ImageError::TooLarge`].
    ///
    /// # Errors
    /// [`ImageError::TooLarge`] for an extent beyond [`RegionTree::MAX_DEPTH`].
    ///
    /// # Complexity
    /// O(D).
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// assert_eq!(ImageTree::depth_for([5, 3]), Ok(3));
    /// assert_eq!(ImageTree::depth_for([1, 1]), Ok(0));
    /// assert!(ImageTree::depth_for([u32::MAX, 1]).is_err());
    /// ```
    pub fn depth_for(extent: [u32; D]) -> Result<u8, ImageError> {
        let max = extent.iter().copied().max().unwrap_or(0).max(1);
        let depth = (32 - (max - 1).leading_zeros()) as u8;
        if depth > Self::MAX_DEPTH {
            return Err(ImageError::TooLarge {
                extent: extent.to_vec(),
                max_depth: Self::MAX_DEPTH,
            });
        }
        Ok(depth)
    }

    /// The all-white image of this extent: one white leaf.
    ///
    /// # Errors
    /// [`ImageError::TooLarge`] for an extent beyond [`RegionTree::MAX_DEPTH`].
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// let e = ImageTree::empty([100, 7]).unwrap();
    /// assert!(e.is_empty() && e.node_count() == 1 && e.depth() == 7);
    /// ```
    pub fn empty(extent: [u32; D]) -> Result<Self, ImageError> {
        Self::from_nodes(extent, vec![WHITE])
    }

    /// The image whose pixels within the extent are all black (one black leaf when the extent is
    /// a power-of-two cube).
    ///
    /// # Errors
    /// [`ImageError::TooLarge`] for an extent beyond [`RegionTree::MAX_DEPTH`].
    ///
    /// # Complexity
    /// O(n) for the n nodes of the result, O(perimeter of the extent).
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// assert_eq!(ImageTree::full([3, 5]).unwrap().len(), 15);
    /// assert_eq!(ImageTree::full([8, 8]).unwrap().node_count(), 1);
    /// ```
    pub fn full(extent: [u32; D]) -> Result<Self, ImageError> {
        Self::from_boxes(extent, &[([0; D], extent)])
    }

    /// The extent (width, height, ...) of the image, as given when it was built.
    pub fn extent(&self) -> [u32; D] {
        self.extent
    }

    /// The depth k: the tree covers a cube of side 2^k.
    pub fn depth(&self) -> u8 {
        self.depth
    }

    /// The side 2^k of the cube the tree covers.
    pub fn side(&self) -> u32 {
        1 << self.depth
    }

    /// Whether the extent is the whole cube (no padding).
    pub fn is_cube(&self) -> bool {
        self.extent.iter().all(|&e| e == self.side())
    }

    /// The number of nodes, internal and leaves (one byte each).
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The number of leaves.
    pub fn leaf_count(&self) -> usize {
        self.nodes.iter().filter(|&&x| x != INTERNAL).count()
    }

    /// The pre-order node kinds: 0 white leaf, 1 black leaf, 2 internal node.
    ///
    /// ```
    /// use orthtree::image::ImageTree;
    /// let t = ImageTree::from_boxes([2, 2], &[([0, 0], [1, 1])]).unwrap();
    /// assert_eq!(t.nodes(), [2, 1, 0, 0, 0]);
    /// ```
    pub fn nodes(&self) -> &[u8] {
        &self.nodes
    }

    /// A tree from its pre-order node kinds (as [`RegionTree::nodes`] returns them), checked by
    /// [`RegionTree::validate`].
    ///
    /// # Errors
    /// [`ImageError::TooLarge`] for an extent beyond [`RegionTree::MAX_DEPTH`];
    /// [`ImageError::Malformed`] naming the first node that breaks the canonical form.
    ///
    /// # Complexity
    /// O(n) for n nodes (one pass of [`RegionTree::validate`]).
    ///
    /// ```
    /// use orthtree::image::{ImageError, ImageTree};
    /// let t = ImageTree::from_nodes([2, 2], vec![2, 1, 0, 0, 1]).unwrap();
    /// assert_eq!(t.len(), 2);
    /// let collapsible = ImageTree::from_nodes([2, 2], vec![2, 1, 1, 1, 1]);
    /// assert!(matches!(collapsible, Err(ImageError::Malformed { position: 0, .. })));
    /// ```
    pub fn from_nodes(extent: [u32; D], nodes: Vec<u8>) -> Result<Self, ImageError> {
        let t = RegionTree {
            extent,
            depth: Self::depth_for(extent)?,
            nodes,
        };
        t.validate().map(|()| t)
    }

    /// Whether the pixel at `p` is black. Pixels outside the extent are white.
    ///
    /// # Complexity
    /// O(n) for n nodes (a scan of the linear form).
    pub fn contains(&self, p: [u32; D]) -> bool {
        if p.iter().zip(&self.extent).any(|(c, e)| c >= e) {
            return false;
        }
        let mut i = 0;
        let mut level = 0;
        loop {
            match self.nodes[i] {
                INTERNAL => {
                    let shift = self.depth - level - 1;
                    let child = (0..D).fold(0, |acc, a| acc | (((p[a] >> shift) & 1) << a));
                    i += 1;
                    for _ in 0..child {
                        i = ops::subtree_end::<D>(&self.nodes, i);
                    }
                    level += 1;
                }
                x => return x == BLACK,
            }
        }
    }
}

/// Writes a tree's pre-order sequence, collapsing on the fly: when an internal node's 2^D
/// children turn out to be leaves of one colour, they and the node are replaced by one leaf.
/// Shared by the builders and the Boolean operations, which thus return canonical trees.
pub(crate) struct Writer<const D: usize> {
    pub(crate) out: Vec<u8>,
    /// (position of an open internal node, children still to come)
    open: Vec<(usize, u32)>,
}

impl<const D: usize> Writer<D> {
    pub(crate) fn with_capacity(capacity: usize) -> Self {
        Writer {
            out: Vec::with_capacity(capacity),
            open: Vec::with_capacity(32),
        }
    }

    /// Whether the root's subtree is complete.
    #[inline]
    pub(crate) fn done(&self) -> bool {
        self.open.is_empty()
    }

    /// Opens an internal node; its 2^D subtrees follow.
    #[inline]
    pub(crate) fn open(&mut self) {
        self.open.push((self.out.len(), 1 << D));
        self.out.push(INTERNAL);
    }

    /// Writes a leaf.
    #[inline]
    pub(crate) fn leaf(&mut self, colour: u8) {
        self.out.push(colour);
        self.close();
    }

    /// Writes a canonical subtree as it is.
    #[inline]
    pub(crate) fn copy(&mut self, subtree: &[u8]) {
        self.out.extend_from_slice(subtree);
        self.close();
    }

    /// Writes the complement of a canonical subtree (leaf colours swapped).
    #[inline]
    pub(crate) fn complement(&mut self, subtree: &[u8]) {
        // 0 -> 1, 1 -> 0, 2 -> 2
        self.out.extend(subtree.iter().map(|&x| x ^ ((x >> 1) ^ 1)));
        self.close();
    }

    /// A node was completed: count it in its parent, closing (and collapsing) every parent it
    /// completes.
    #[inline]
    fn close(&mut self) {
        while let Some(top) = self.open.last_mut() {
            top.1 -= 1;
            if top.1 > 0 {
                return;
            }
            let start = top.0;
            self.open.pop();
            if self.out.len() == start + 1 + (1 << D) {
                let first = self.out[start + 1];
                if first != INTERNAL && self.out[start + 2..].iter().all(|&y| y == first) {
                    self.out.truncate(start);
                    self.out.push(first);
                }
            }
        }
    }
}
