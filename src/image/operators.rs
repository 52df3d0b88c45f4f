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
use core::ops::{
    BitAnd, BitAndAssign, BitOr, BitOrAssign, BitXor, BitXorAssign, Not, Sub, SubAssign,
};

/// The intersection (`&`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> BitAnd<RegionTree<D>> for RegionTree<D> {
    type Output = RegionTree<D>;

    fn bitand(self, rhs: RegionTree<D>) -> RegionTree<D> {
        let (a, b): (&RegionTree<D>, &RegionTree<D>) = (&self, &rhs);
        a.try_combine(b, BoolOp::And)
            .unwrap_or_else(|e| panic!("{e}"))
    }
}

/// The intersection (`&`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> BitAnd<&RegionTree<D>> for RegionTree<D> {
    type Output = RegionTree<D>;

    fn bitand(self, rhs: &RegionTree<D>) -> RegionTree<D> {
        let (a, b): (&RegionTree<D>, &RegionTree<D>) = (&self, rhs);
        a.try_combine(b, BoolOp::And)
            .unwrap_or_else(|e| panic!("{e}"))
    }
}

/// The intersection (`&`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> BitAnd<RegionTree<D>> for &RegionTree<D> {
    type Output = RegionTree<D>;

    fn bitand(self, rhs: RegionTree<D>) -> RegionTree<D> {
        let (a, b): (&RegionTree<D>, &RegionTree<D>) = (self, &rhs);
        a.try_combine(b, BoolOp::And)
            .unwrap_or_else(|e| panic!("{e}"))
    }
}

/// The intersection (`&`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> BitAnd<&RegionTree<D>> for &RegionTree<D> {
    type Output = RegionTree<D>;

    fn bitand(self, rhs: &RegionTree<D>) -> RegionTree<D> {
        let (a, b): (&RegionTree<D>, &RegionTree<D>) = (self, rhs);
        a.try_combine(b, BoolOp::And)
            .unwrap_or_else(|e| panic!("{e}"))
    }
}

/// In-place intersection (`&=`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> BitAndAssign<RegionTree<D>> for RegionTree<D> {
    fn bitand_assign(&mut self, rhs: RegionTree<D>) {
        self.assign(&rhs, BoolOp::And);
    }
}

/// In-place intersection (`&=`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> BitAndAssign<&RegionTree<D>> for RegionTree<D> {
    fn bitand_assign(&mut self, rhs: &RegionTree<D>) {
        self.assign(rhs, BoolOp::And);
    }
}

/// The union (`|`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> BitOr<RegionTree<D>> for RegionTree<D> {
    type Output = RegionTree<D>;

    fn bitor(self, rhs: RegionTree<D>) -> RegionTree<D> {
        let (a, b): (&RegionTree<D>, &RegionTree<D>) = (&self, &rhs);
        a.try_combine(b, BoolOp::Or)
            .unwrap_or_else(|e| panic!("{e}"))
    }
}

/// The union (`|`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> BitOr<&RegionTree<D>> for RegionTree<D> {
    type Output = RegionTree<D>;

    fn bitor(self, rhs: &RegionTree<D>) -> RegionTree<D> {
        let (a, b): (&RegionTree<D>, &RegionTree<D>) = (&self, rhs);
        a.try_combine(b, BoolOp::Or)
            .unwrap_or_else(|e| panic!("{e}"))
    }
}

/// The union (`|`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> BitOr<RegionTree<D>> for &RegionTree<D> {
    type Output = RegionTree<D>;

    fn bitor(self, rhs: RegionTree<D>) -> RegionTree<D> {
        let (a, b): (&RegionTree<D>, &RegionTree<D>) = (self, &rhs);
        a.try_combine(b, BoolOp::Or)
            .unwrap_or_else(|e| panic!("{e}"))
    }
}

/// The union (`|`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> BitOr<&RegionTree<D>> for &RegionTree<D> {
    type Output = RegionTree<D>;

    fn bitor(self, rhs: &RegionTree<D>) -> RegionTree<D> {
        let (a, b): (&RegionTree<D>, &RegionTree<D>) = (self, rhs);
        a.try_combine(b, BoolOp::Or)
            .unwrap_or_else(|e| panic!("{e}"))
    }
}

/// In-place union (`|=`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> BitOrAssign<RegionTree<D>> for RegionTree<D> {
    fn bitor_assign(&mut self, rhs: RegionTree<D>) {
        self.assign(&rhs, BoolOp::Or);
    }
}

/// In-place union (`|=`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> BitOrAssign<&RegionTree<D>> for RegionTree<D> {
    fn bitor_assign(&mut self, rhs: &RegionTree<D>) {
        self.assign(rhs, BoolOp::Or);
    }
}

/// The symmetric difference (`^`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> BitXor<RegionTree<D>> for RegionTree<D> {
    type Output = RegionTree<D>;

    fn bitxor(self, rhs: RegionTree<D>) -> RegionTree<D> {
        let (a, b): (&RegionTree<D>, &RegionTree<D>) = (&self, &rhs);
        a.try_combine(b, BoolOp::Xor)
            .unwrap_or_else(|e| panic!("{e}"))
    }
}

/// The symmetric difference (`^`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> BitXor<&RegionTree<D>> for RegionTree<D> {
    type Output = RegionTree<D>;

    fn bitxor(self, rhs: &RegionTree<D>) -> RegionTree<D> {
        let (a, b): (&RegionTree<D>, &RegionTree<D>) = (&self, rhs);
        a.try_combine(b, BoolOp::Xor)
            .unwrap_or_else(|e| panic!("{e}"))
    }
}

/// The symmetric difference (`^`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> BitXor<RegionTree<D>> for &RegionTree<D> {
    type Output = RegionTree<D>;

    fn bitxor(self, rhs: RegionTree<D>) -> RegionTree<D> {
        let (a, b): (&RegionTree<D>, &RegionTree<D>) = (self, &rhs);
        a.try_combine(b, BoolOp::Xor)
            .unwrap_or_else(|e| panic!("{e}"))
    }
}

/// The symmetric difference (`^`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> BitXor<&RegionTree<D>> for &RegionTree<D> {
    type Output = RegionTree<D>;

    fn bitxor(self, rhs: &RegionTree<D>) -> RegionTree<D> {
        let (a, b): (&RegionTree<D>, &RegionTree<D>) = (self, rhs);
        a.try_combine(b, BoolOp::Xor)
            .unwrap_or_else(|e| panic!("{e}"))
    }
}

/// In-place symmetric difference (`^=`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> BitXorAssign<RegionTree<D>> for RegionTree<D> {
    fn bitxor_assign(&mut self, rhs: RegionTree<D>) {
        self.assign(&rhs, BoolOp::Xor);
    }
}

/// In-place symmetric difference (`^=`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> BitXorAssign<&RegionTree<D>> for RegionTree<D> {
    fn bitxor_assign(&mut self, rhs: &RegionTree<D>) {
        self.assign(rhs, BoolOp::Xor);
    }
}

/// The difference (`-`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> Sub<RegionTree<D>> for RegionTree<D> {
    type Output = RegionTree<D>;

    fn sub(self, rhs: RegionTree<D>) -> RegionTree<D> {
        let (a, b): (&RegionTree<D>, &RegionTree<D>) = (&self, &rhs);
        a.try_combine(b, BoolOp::Sub)
            .unwrap_or_else(|e| panic!("{e}"))
    }
}

/// The difference (`-`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> Sub<&RegionTree<D>> for RegionTree<D> {
    type Output = RegionTree<D>;

    fn sub(self, rhs: &RegionTree<D>) -> RegionTree<D> {
        let (a, b): (&RegionTree<D>, &RegionTree<D>) = (&self, rhs);
        a.try_combine(b, BoolOp::Sub)
            .unwrap_or_else(|e| panic!("{e}"))
    }
}

/// The difference (`-`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> Sub<RegionTree<D>> for &RegionTree<D> {
    type Output = RegionTree<D>;

    fn sub(self, rhs: RegionTree<D>) -> RegionTree<D> {
        let (a, b): (&RegionTree<D>, &RegionTree<D>) = (self, &rhs);
        a.try_combine(b, BoolOp::Sub)
            .unwrap_or_else(|e| panic!("{e}"))
    }
}

/// The difference (`-`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> Sub<&RegionTree<D>> for &RegionTree<D> {
    type Output = RegionTree<D>;

    fn sub(self, rhs: &RegionTree<D>) -> RegionTree<D> {
        let (a, b): (&RegionTree<D>, &RegionTree<D>) = (self, rhs);
        a.try_combine(b, BoolOp::Sub)
            .unwrap_or_else(|e| panic!("{e}"))
    }
}

/// In-place difference (`-=`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> SubAssign<RegionTree<D>> for RegionTree<D> {
    fn sub_assign(&mut self, rhs: RegionTree<D>) {
        self.assign(&rhs, BoolOp::Sub);
    }
}

/// In-place difference (`-=`).
///
/// # Panics
/// If the extents differ.
impl<const D: usize> SubAssign<&RegionTree<D>> for RegionTree<D> {
    fn sub_assign(&mut self, rhs: &RegionTree<D>) {
        self.assign(rhs, BoolOp::Sub);
    }
}

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
