//! [`DeepCell`]: dyadic cells 64 levels deep on every axis, whatever D, and [`DeepKey`]s, the
//! finest of them; the cells of the compressed quadtree and the skip quadtree, whose nodes exist
//! only where points branch and so can afford cells as fine as `f64` coordinates tell apart (53
//! mantissa bits need at least 53 levels below a unit root box).
//!
//! A key is D coordinates of 64 bits, not their interleaving into one D * 64-bit Morton number:
//! every operation reads the coordinates directly, with the most-significant-differing-bit trick
//! of T. M. Chan ("Closest-point problems simplified on the RAM", SODA 2002):
//! - Morton order ([`morton_cmp`]): the axis whose XOR has the highest set bit decides (at equal
//!   bits the higher axis, whose bit is the more significant in a child index);
//! - the level at which two keys part ([`common_level`]): the fewest leading zeros of an XOR;
//! - the child of a cell holding a key: one bit per axis; the ancestor at a level: a mask.
//!
//! Each costs O(D) word operations and no bit spreading, where a `[u64; D]` Morton number would
//! need the interleaving on every key and a shift across words for every digit.
//!
//! Child numbering is [`Cell`]'s (bit `a` of the index set for the upper half along axis `a`),
//! and the first [`Cell::MAX_LEVEL`] levels are [`Cell`]'s: [`DeepCell::to_cell`] and
//! `From<Cell>` convert between them.

use super::cell::{Cell, Dim};
use core::cmp::Ordering;

/// The finest deep cell of a point: its coordinate at level 64 on every axis.
pub type DeepKey<const D: usize> = [u64; D];

/// Morton (z-order) comparison of two keys, without interleaving their bits.
///
/// ```
/// use orthtree::geom::deep::morton_cmp;
/// use std::cmp::Ordering;
/// // x = 0b01.., y = 0b00.. against x = 0b00.., y = 0b01..: the y bit is the higher digit bit
/// assert_eq!(morton_cmp(&[1 << 62, 0], &[0, 1 << 62]), Ordering::Less);
/// assert_eq!(morton_cmp(&[1 << 63, 0], &[0, 1 << 62]), Ordering::Greater);
/// assert_eq!(morton_cmp(&[5, 7], &[5, 7]), Ordering::Equal);
/// ```
#[inline]
pub fn morton_cmp<const D: usize>(a: &DeepKey<D>, b: &DeepKey<D>) -> Ordering {
    // The axis with the fewest leading zeros in its XOR; the later axis wins ties.
    let mut axis = 0;
    let mut zeros = u32::MAX;
    for i in 0..D {
        let z = (a[i] ^ b[i]).leading_zeros();
        if z <= zeros {
            (axis, zeros) = (i, z);
        }
    }
    a[axis].cmp(&b[axis])
}

/// The deepest level whose cell holds both keys (64 when they are equal).
///
/// ```
/// use orthtree::geom::deep::common_level;
/// assert_eq!(common_level(&[0, 0], &[1, 0]), 63);
/// assert_eq!(common_level(&[0, u64::MAX], &[0, 0]), 0);
/// assert_eq!(common_level(&[3; 3], &[3; 3]), 64);
/// ```
#[inline]
pub fn common_level<const D: usize>(a: &DeepKey<D>, b: &DeepKey<D>) -> u8 {
    (0..D)
        .map(|i| (a[i] ^ b[i]).leading_zeros())
        .fold(64, u32::min) as u8
}

/// The bits of a coordinate that a cell at `level` fixes.
#[inline]
fn mask(level: u8) -> u64 {
    u64::MAX.checked_shl(64 - u32::from(level)).unwrap_or(0)
}

/// A dyadic cell of a 64-level tree: at `level` l the root cube is cut into 2^l parts along each
/// axis. It is stored by its *anchor*, the key of its lowest finest descendant, so that testing
/// whether it holds a key is a mask per axis.
///
/// Cells order by anchor in Morton order and then by level: the pre-order of the tree.
///
/// ```
/// use orthtree::geom::DeepCell;
/// let c = DeepCell::<2>::root().child(1).child(2); // SE child of the root, then its NW child
/// assert_eq!((c.level(), c.coords()), (2, [2, 1]));
/// assert_eq!(c.anchor(), [2 << 62, 1 << 62]);
/// assert_eq!(c.parent(), Some(DeepCell::root().child(1)));
/// assert!(c.holds(&[(2 << 62) + 5, 1 << 62]));
/// let leaf = DeepCell::<2>::finest([u64::MAX, 7]);
/// assert_eq!((leaf.level(), leaf.ancestor(1).coords()), (64, [1, 0]));
/// assert_eq!(leaf.to_cell().level(), orthtree::Cell::<2>::MAX_LEVEL);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct DeepCell<const D: usize> {
    level: u8,
    anchor: DeepKey<D>,
}

impl<const D: usize> DeepCell<D> {
    /// The finest level, on every axis whatever D.
    pub const MAX_LEVEL: u8 = 64;

    /// The root cell (level 0).
    #[inline]
    pub const fn root() -> Self {
        let () = Dim::<D>::CHECK;
        DeepCell {
            level: 0,
            anchor: [0; D],
        }
    }

    /// A cell from its level and coordinates at that level; `None` if the level exceeds 64 or a
    /// coordinate is not below 2^level.
    pub fn new(level: u8, coords: [u64; D]) -> Option<Self> {
        let () = Dim::<D>::CHECK;
        let fits = |c: u64| level >= 64 || c >> level == 0;
        (level <= Self::MAX_LEVEL && coords.iter().all(|&c| fits(c))).then(|| DeepCell {
            level,
            anchor: coords.map(|c| if level == 0 { 0 } else { c << (64 - level) }),
        })
    }

    /// The finest cell of `key` (level 64).
    #[inline]
    pub const fn finest(key: DeepKey<D>) -> Self {
        let () = Dim::<D>::CHECK;
        DeepCell {
            level: Self::MAX_LEVEL,
            anchor: key,
        }
    }

    /// The cell at `level` holding `key`.
    ///
    /// # Panics
    /// In debug builds, if `level` exceeds 64.
    #[inline]
    pub fn of_key(key: &DeepKey<D>, level: u8) -> Self {
        debug_assert!(level <= Self::MAX_LEVEL);
        let m = mask(level);
        DeepCell {
            level,
            anchor: key.map(|c| c & m),
        }
    }

    /// The level (depth below the root).
    #[inline]
    pub const fn level(&self) -> u8 {
        self.level
    }

    /// The key of the cell's lowest finest descendant.
    #[inline]
    pub const fn anchor(&self) -> DeepKey<D> {
        self.anchor
    }

    /// The coordinates at the cell's own level, each in `0..2^level`.
    #[inline]
    pub fn coords(&self) -> [u64; D] {
        let shift = 64 - u32::from(self.level);
        self.anchor.map(|c| c.checked_shr(shift).unwrap_or(0))
    }

    /// `true` when the cell holds the finest cell `key`.
    #[inline]
    pub fn holds(&self, key: &DeepKey<D>) -> bool {
        let m = mask(self.level);
        (0..D).all(|i| (self.anchor[i] ^ key[i]) & m == 0)
    }

    /// `true` when `other` is this cell or a descendant of it.
    #[inline]
    pub fn contains(&self, other: &Self) -> bool {
        other.level >= self.level && self.holds(&other.anchor)
    }

    /// The index of the child that holds `key` (bit `a` set for the upper half along axis `a`);
    /// meaningful when the cell holds `key`.
    ///
    /// # Panics
    /// In debug builds, if the cell is at level 64.
    #[inline]
    pub fn child_digit(&self, key: &DeepKey<D>) -> usize {
        debug_assert!(self.level < Self::MAX_LEVEL);
        let s = 63 - self.level as u32;
        (0..D).fold(0, |d, i| d | ((((key[i] >> s) & 1) as usize) << i))
    }

    /// The `index`-th child: bit `a` of `index` set means the upper half along axis `a`.
    ///
    /// # Panics
    /// In debug builds, if the cell is at level 64 or `index >= 2^D`.
    #[inline]
    pub fn child(&self, index: usize) -> Self {
        debug_assert!(self.level < Self::MAX_LEVEL && index < Dim::<D>::CHILDREN);
        let s = 63 - self.level as u32;
        DeepCell {
            level: self.level + 1,
            anchor: core::array::from_fn(|a| self.anchor[a] | ((((index >> a) & 1) as u64) << s)),
        }
    }

    /// The parent cell; `None` for the root.
    #[inline]
    pub fn parent(&self) -> Option<Self> {
        (self.level > 0).then(|| self.ancestor(self.level - 1))
    }

    /// The ancestor at `level` (the cell itself if `level` is its own).
    ///
    /// # Panics
    /// In debug builds, if `level` is deeper than the cell.
    #[inline]
    pub fn ancestor(&self, level: u8) -> Self {
        debug_assert!(level <= self.level);
        Self::of_key(&self.anchor, level)
    }

    /// Which child of its parent the cell is (0 for the root).
    #[inline]
    pub fn child_index(&self) -> usize {
        self.parent().map_or(0, |p| p.child_digit(&self.anchor))
    }

    /// The [`Cell`] of this cell, or of its ancestor at [`Cell::MAX_LEVEL`] when it is deeper:
    /// where a [`PointTree`](crate::PointTree) over the same root cube keeps its points.
    ///
    /// # Panics
    /// Never: the ancestor's level is at most [`Cell::MAX_LEVEL`], so its coordinates fit.
    #[inline]
    pub fn to_cell(&self) -> Cell<D> {
        let level = self.level.min(Cell::<D>::MAX_LEVEL);
        let coords = self.ancestor(level).coords().map(|c| c as u32);
        Cell::new(level, coords).expect("coordinates below 2^level")
    }
}

impl<const D: usize> From<Cell<D>> for DeepCell<D> {
    /// The same cell, 64 levels available below the root.
    #[inline]
    fn from(cell: Cell<D>) -> Self {
        DeepCell::new(cell.level(), cell.coords().map(u64::from)).expect("a valid cell")
    }
}

impl<const D: usize> PartialOrd for DeepCell<D> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl<const D: usize> Ord for DeepCell<D> {
    fn cmp(&self, other: &Self) -> Ordering {
        morton_cmp(&self.anchor, &other.anchor).then(self.level.cmp(&other.level))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// The `D * 64`-bit Morton number of a key, most significant bit first.
    fn interleaved<const D: usize>(key: &DeepKey<D>) -> Vec<bool> {
        (0..64)
            .rev()
            .flat_map(|j| (0..D).rev().map(move |a| (key[a] >> j) & 1 == 1))
            .collect()
    }

    fn random_key<const D: usize>(rng: &mut impl Rng) -> DeepKey<D> {
        // Shared high bits now and then, so that keys part at every depth.
        let base: u64 = rng.r#gen();
        core::array::from_fn(|_| match rng.gen_range(0..3) {
            0 => rng.r#gen(),
            1 => base ^ (1u64 << rng.gen_range(0..64)),
            _ => base,
        })
    }

    fn check<const D: usize>(rng: &mut impl Rng) {
        for _ in 0..4000 {
            let (a, b) = (random_key::<D>(rng), random_key::<D>(rng));
            assert_eq!(morton_cmp(&a, &b), interleaved(&a).cmp(&interleaved(&b)));
            let l = common_level(&a, &b);
            let (ca, cb) = (DeepCell::of_key(&a, l), DeepCell::of_key(&b, l));
            assert_eq!(ca, cb);
            assert!(ca.holds(&a) && ca.holds(&b));
            if l < 64 {
                assert_ne!(ca.child_digit(&a), ca.child_digit(&b));
                assert!(!ca.child(ca.child_digit(&a)).holds(&b));
                assert!(ca.child(ca.child_digit(&a)).holds(&a));
            }
            let leaf = DeepCell::finest(a);
            let level = rng.gen_range(0..=64);
            let up = leaf.ancestor(level);
            assert!(up.contains(&leaf) && up <= leaf);
            assert_eq!(DeepCell::new(level, up.coords()), Some(up));
            if level < 64 {
                let c = up.child_digit(&a);
                assert_eq!(up.child(c).child_index(), c);
                assert_eq!(up.child(c).parent(), Some(up));
            }
        }
    }

    #[test]
    fn operations_agree_with_interleaved_morton_numbers() {
        let mut rng = rand::rngs::SmallRng::seed_from_u64(11);
        check::<1>(&mut rng);
        check::<2>(&mut rng);
        check::<3>(&mut rng);
        check::<5>(&mut rng);
        check::<8>(&mut rng);
    }

    #[test]
    fn conversions_and_limits() {
        assert_eq!(DeepCell::<2>::new(65, [0, 0]), None);
        assert_eq!(DeepCell::<2>::new(3, [8, 0]), None);
        assert!(DeepCell::<2>::new(64, [u64::MAX, 0]).is_some());
        let c = Cell::<3>::root().child(5).child(3);
        let d = DeepCell::from(c);
        assert_eq!((d.level(), d.coords()), (2, [3, 1, 2]));
        assert_eq!(d.to_cell(), c);
        assert_eq!(d.child(7).child_index(), 7);
        let deep = DeepCell::<3>::finest([u64::MAX; 3]);
        assert_eq!(deep.to_cell(), Cell::new(21, [(1 << 21) - 1; 3]).unwrap());
        let root = DeepCell::<2>::root();
        assert!(root < root.child(0) && root.child(0).child(3) < root.child(1));
        assert_eq!(root.child_index(), 0);
    }
}
