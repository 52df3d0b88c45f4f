//! [`Cell`]: the exact address of a dyadic cell (a level and integer coordinates), with its
//! Morton key, parent, children, same-size neighbours and contact tests, all in integers.

use super::morton;
use super::Direction;

/// Compile-time guard: the dimension of every tree is 1 to 8.
pub(crate) struct Dim<const D: usize>;

impl<const D: usize> Dim<D> {
    /// Evaluating this constant fails to compile unless 1 <= D <= 8.
    pub(crate) const CHECK: () = assert!(D >= 1 && D <= 8, "orthtree supports dimensions 1 to 8");
    /// The number of children of a node, 2^D.
    pub(crate) const CHILDREN: usize = 1 << D;
}

/// A dyadic cell: at `level` l the root cube is cut into 2^l parts along each axis and the cell is
/// the part with integer coordinates `coords` (each below 2^l).
///
/// Cells order by their Morton key aligned to [`Cell::MAX_LEVEL`] and then by level, which is the
/// pre-order of the tree: an ancestor comes right before its descendants.
///
/// ```
/// use orthtree::Cell;
/// let c = Cell::<2>::root().child(1).child(2); // SE child of the root, then its NW child
/// assert_eq!((c.level(), c.coords()), (2, [2, 1]));
/// assert_eq!(c.child_index(), 2);
/// assert_eq!(c.parent(), Some(Cell::root().child(1)));
/// assert!(Cell::root().child(1).contains(&c));
/// ```
///
/// A dimension outside 1..=8 does not compile:
/// ```compile_fail
/// let c = orthtree::Cell::<9>::root();
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Cell<const D: usize> {
    level: u8,
    coords: [u32; D],
}

impl<const D: usize> Cell<D> {
    /// The deepest level a cell (and so a tree) may have: min(32, 64 / D), so that an aligned
    /// Morton key fits in a `u64` (32 in 2D, 21 in 3D, 16 in 4D, 8 in 8D).
    pub const MAX_LEVEL: u8 = if 64 / D > 32 { 32 } else { (64 / D) as u8 };

    /// The root cell (level 0).
    #[inline]
    pub const fn root() -> Self {
        let () = Dim::<D>::CHECK;
        Cell {
            level: 0,
            coords: [0; D],
        }
    }

    /// A cell from its level and coordinates; `None` if the level exceeds [`Cell::MAX_LEVEL`] or a
    /// coordinate is not below 2^level.
    pub fn new(level: u8, coords: [u32; D]) -> Option<Self> {
        let () = Dim::<D>::CHECK;
        let ok = level <= Self::MAX_LEVEL && coords.iter().all(|&c| (c as u64) < (1u64 << level));
        ok.then_some(Cell { level, coords })
    }

    /// The level (depth below the root).
    #[inline]
    pub const fn level(&self) -> u8 {
        self.level
    }

    /// The integer coordinates, each in `0..2^level`.
    #[inline]
    pub const fn coords(&self) -> [u32; D] {
        self.coords
    }

    /// The `index`-th child: bit `a` of `index` set means the upper half along axis `a`.
    ///
    /// # Panics
    /// In debug builds, if the cell is at [`Cell::MAX_LEVEL`] or `index >= 2^D`.
    #[inline]
    pub fn child(&self, index: usize) -> Self {
        debug_assert!(self.level < Self::MAX_LEVEL && index < (1 << D));
        Cell {
            level: self.level + 1,
            coords: core::array::from_fn(|a| (self.coords[a] << 1) | ((index >> a) & 1) as u32),
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
        let shift = (self.level - level) as u32;
        Cell {
            level,
            coords: self.coords.map(|c| ((c as u64) >> shift) as u32),
        }
    }

    /// Which child of its parent the cell is (0 for the root).
    #[inline]
    pub fn child_index(&self) -> usize {
        // the root's coordinates are all 0
        self.coords
            .iter()
            .enumerate()
            .fold(0, |i, (a, &c)| i | (((c & 1) as usize) << a))
    }

    /// The Morton key of the coordinates at the cell's own level (`D * level` bits).
    #[inline]
    pub fn morton(&self) -> u64 {
        morton::interleave(self.coords, self.level as u32)
    }

    /// The cell at `level` whose Morton key at that level ([`Cell::morton`]) is `key`.
    ///
    /// ```
    /// use orthtree::geom::Cell;
    /// let c = Cell::<3>::new(4, [5, 0, 9]).unwrap();
    /// assert_eq!(Cell::<3>::from_morton(c.morton(), 4), c);
    /// assert_eq!(Cell::<2>::from_morton(0, 0), Cell::root());
    /// ```
    #[inline]
    pub fn from_morton(key: u64, level: u8) -> Self {
        Cell {
            level,
            coords: morton::deinterleave(key, u32::from(level)),
        }
    }

    /// The Morton key aligned to [`Cell::MAX_LEVEL`]: the key of the cell's lowest descendant
    /// there. Cells of one level sort by it in z-order.
    #[inline]
    pub fn aligned_key(&self) -> u64 {
        let shift = D as u32 * (Self::MAX_LEVEL - self.level) as u32;
        self.morton().checked_shl(shift).unwrap_or(0)
    }

    /// The cell at `level` whose aligned key's prefix is `key` (the inverse of
    /// [`Cell::aligned_key`] after truncating to `level`).
    #[inline]
    pub fn from_aligned_key(key: u64, level: u8) -> Self {
        // the key's first `level` digits, which the shift brings to the bottom
        let shift = D as u32 * u32::from(Self::MAX_LEVEL - level);
        Self::from_morton(key.checked_shr(shift).unwrap_or(0), level)
    }

    /// `true` when `other` is this cell or a descendant of it.
    #[inline]
    pub fn contains(&self, other: &Self) -> bool {
        other.level >= self.level && other.ancestor(self.level) == *self
    }

    /// The same-level cell one step in `direction`; `None` outside the root cube.
    pub fn neighbor(&self, direction: Direction) -> Option<Self> {
        let mut coords = self.coords;
        for (a, c) in coords.iter_mut().enumerate() {
            *c = c.checked_add_signed(direction.component(a).into())?;
        }
        // a step past the far side is refused here, below 2^level
        Self::new(self.level, coords)
    }

    /// The closed cell as integer intervals `[lo, hi]` per axis, in units of the finest level.
    #[inline]
    pub fn span(&self, axis: usize) -> (u64, u64) {
        let shift = (Self::MAX_LEVEL - self.level) as u32;
        let lo = (self.coords[axis] as u64) << shift;
        (lo, lo + (1u64 << shift))
    }

    /// How two cells with disjoint interiors touch: `Some(k)` when their closures meet in a
    /// (D - k)-dimensional piece (k = 1: a face, k = 2: an edge, k = D: a corner); `None` when
    /// they do not touch or their interiors overlap.
    ///
    /// ```
    /// use orthtree::Cell;
    /// let a = Cell::<2>::new(1, [0, 0]).unwrap();
    /// assert_eq!(a.contact(&Cell::new(1, [1, 0]).unwrap()), Some(1)); // share a side
    /// assert_eq!(a.contact(&Cell::new(2, [2, 2]).unwrap()), Some(2)); // share a corner
    /// assert_eq!(a.contact(&Cell::new(2, [3, 3]).unwrap()), None);
    /// ```
    pub fn contact(&self, other: &Self) -> Option<u32> {
        let mut touching_axes = 0;
        for a in 0..D {
            let (lo1, hi1) = self.span(a);
            let (lo2, hi2) = other.span(a);
            if hi1 < lo2 || hi2 < lo1 {
                return None;
            }
            if hi1 == lo2 || hi2 == lo1 {
                touching_axes += 1;
            }
        }
        (touching_axes > 0).then_some(touching_axes)
    }
}

impl<const D: usize> PartialOrd for Cell<D> {
    fn partial_cmp(&self, other: &Self) -> Option<core::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl<const D: usize> Ord for Cell<D> {
    fn cmp(&self, other: &Self) -> core::cmp::Ordering {
        (self.aligned_key(), self.level).cmp(&(other.aligned_key(), other.level))
    }
}

/// The child index, below a cell at `level`, of the cell at `level + 1` holding the point whose
/// Morton key at [`Cell::MAX_LEVEL`] is `key`: the key's digit `level + 1`.
#[inline]
pub(crate) fn digit<const D: usize>(key: u64, level: u8) -> usize {
    let shift = D as u32 * (Cell::<D>::MAX_LEVEL - level - 1) as u32;
    ((key >> shift) as usize) & (Dim::<D>::CHILDREN - 1)
}

/// Whether the points whose Morton keys at [`Cell::MAX_LEVEL`] are `a` and `b` lie in one cell
/// at `level` (the keys agree in their first `level` digits).
#[inline]
pub(crate) fn same_cell<const D: usize>(a: u64, b: u64, level: u8) -> bool {
    let shift = D as u32 * u32::from(Cell::<D>::MAX_LEVEL - level);
    shift >= 64 || (a >> shift) == (b >> shift)
}
