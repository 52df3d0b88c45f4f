//! The operators `&`, `|`, `^`, `-` and `!` on region trees, for owned and borrowed operands,
//! and the `*Assign` forms (the shape of roaring's `bitmap/ops.rs`). Each is one call of the
//! simultaneous traversal in `ops.rs`, O(n1 + n2).
//!
//! # Panics
//! The binary operators panic when the two extents differ; the `try_` methods
//! ([`RegionTree::try_union`] and its siblings) return [`ImageError::SizeMismatch`](super::ImageError::SizeMismatch)
//! instead.
//!
//! ```
//! use orthtree::image::ImageTree;
//! let a = ImageTree::from_boxes([4, 4], &[([0, 0], [2, 4])]).unwrap();
//! let b = ImageTree::from_boxes([4, 4], &[([0, 0], [4, 2])]).unwrap();
//! let mut c = a.clone();
//! c |= &b;
//! assert_eq!(c, &a | &b);
//! c -= b.clone();
//! assert_eq!(c, a.clone() - b.clone());
//! c ^= &a; // (a - b) ^ a = a & b
//! assert_eq!(c, &a & &b);
//! c &= a.clone();
//! assert_eq!(c, &a & &b);
//! assert_eq!(!!a.clone(), a);
//! assert_eq!((a & b).len(), 4);
//! ```

use super::{BoolOp, RegionTree};
use core::borrow::Borrow;
use core::ops::{
    BitAnd, BitAndAssign, BitOr, BitOrAssign, BitXor, BitXorAssign, Not, Sub, SubAssign,
};

/// Implements `$op` for the four owned/borrowed operand pairs and `$assign` for an owned and a
/// borrowed right-hand side, each one call of the simultaneous traversal with `BoolOp::$bool`;
/// `$doc` and `$assign_doc` head their rustdoc.
macro_rules! bool_operator {
    (
        $op:ident $method:ident, $assign:ident $assign_method:ident, $bool:ident,
        $doc:literal, $assign_doc:literal
    ) => {
        bool_operator!(@binary $op $method, $bool, $doc, RegionTree<D>, RegionTree<D>);
        bool_operator!(@binary $op $method, $bool, $doc, RegionTree<D>, &RegionTree<D>);
        bool_operator!(@binary $op $method, $bool, $doc, &RegionTree<D>, RegionTree<D>);
        bool_operator!(@binary $op $method, $bool, $doc, &RegionTree<D>, &RegionTree<D>);
        bool_operator!(@assign $assign $assign_method, $bool, $assign_doc, RegionTree<D>);
        bool_operator!(@assign $assign $assign_method, $bool, $assign_doc, &RegionTree<D>);
    };
    (@binary $op:ident $method:ident, $bool:ident, $doc:literal, $lhs:ty, $rhs:ty) => {
        #[doc = $doc]
        ///
        /// # Panics
        /// If the extents differ.
        impl<const D: usize> $op<$rhs> for $lhs {
            type Output = RegionTree<D>;

            fn $method(self, rhs: $rhs) -> RegionTree<D> {
                let a: &RegionTree<D> = Borrow::borrow(&self);
                a.try_combine(Borrow::borrow(&rhs), BoolOp::$bool)
                    .unwrap_or_else(|e| panic!("{e}"))
            }
        }
    };
    (@assign $assign:ident $assign_method:ident, $bool:ident, $doc:literal, $rhs:ty) => {
        #[doc = $doc]
        ///
        /// # Panics
        /// If the extents differ.
        impl<const D: usize> $assign<$rhs> for RegionTree<D> {
            fn $assign_method(&mut self, rhs: $rhs) {
                self.assign(Borrow::borrow(&rhs), BoolOp::$bool);
            }
        }
    };
}

bool_operator!(
    BitAnd bitand, BitAndAssign bitand_assign, And,
    "The intersection (`&`).", "In-place intersection (`&=`)."
);
bool_operator!(
    BitOr bitor, BitOrAssign bitor_assign, Or,
    "The union (`|`).", "In-place union (`|=`)."
);
bool_operator!(
    BitXor bitxor, BitXorAssign bitxor_assign, Xor,
    "The symmetric difference (`^`).", "In-place symmetric difference (`^=`)."
);
bool_operator!(
    Sub sub, SubAssign sub_assign, Sub,
    "The difference (`-`).", "In-place difference (`-=`)."
);

/// The complement within the extent (`!`), see [`RegionTree::complement`].
impl<const D: usize> Not for RegionTree<D> {
    type Output = RegionTree<D>;

    fn not(self) -> RegionTree<D> {
        self.complement()
    }
}

/// The complement within the extent (`!`), see [`RegionTree::complement`].
impl<const D: usize> Not for &RegionTree<D> {
    type Output = RegionTree<D>;

    fn not(self) -> RegionTree<D> {
        self.complement()
    }
}
