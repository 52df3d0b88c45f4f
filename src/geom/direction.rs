//! [`Direction`]s to a neighbouring cell and the [`Connectivity`] that says which of them count.
//!
//! A direction is an offset in {-1, 0, +1}^D, not all zero, stored as two bit masks (axes moving up,
//! axes moving down). A face direction moves along one axis (the chapter's north, east, south,
//! west), an edge direction along two, a corner direction along any number.

/// An offset of one cell in {-1, 0, +1}^D (not all zero), as bit masks over the axes.
///
/// ```
/// use orthtree::geom::Direction;
/// let ne = Direction::NORTH.combine(Direction::EAST).unwrap();
/// assert_eq!(ne.offset::<2>(), [1, 1]);
/// assert_eq!(ne.axes_moved(), 2);
/// assert_eq!(Direction::from_offset([0, -1]), Some(Direction::SOUTH));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Direction {
    plus: u8,
    minus: u8,
}

impl Direction {
    /// +y in 2D (the chapter's north).
    pub const NORTH: Direction = Direction::face(1, true);
    /// -y in 2D.
    pub const SOUTH: Direction = Direction::face(1, false);
    /// +x.
    pub const EAST: Direction = Direction::face(0, true);
    /// -x.
    pub const WEST: Direction = Direction::face(0, false);

    /// One step along `axis`, up if `positive`.
    ///
    /// # Panics
    /// If `axis >= 8`.
    pub const fn face(axis: usize, positive: bool) -> Direction {
        assert!(axis < 8, "axis out of range");
        Direction::from_masks((positive as u8) << axis, (!positive as u8) << axis)
    }

    /// From the masks of axes moving up and down (which must be disjoint and not both empty).
    pub(crate) const fn from_masks(plus: u8, minus: u8) -> Direction {
        debug_assert!(plus & minus == 0 && plus | minus != 0);
        Direction { plus, minus }
    }

    /// From an offset vector; `None` if it is all zero or has an entry outside {-1, 0, 1}.
    pub fn from_offset<const D: usize>(offset: [i8; D]) -> Option<Direction> {
        let (mut plus, mut minus) = (0u8, 0u8);
        for (a, &o) in offset.iter().enumerate() {
            match o {
                1 => plus |= 1 << a,
                -1 => minus |= 1 << a,
                0 => {}
                _ => return None,
            }
        }
        (plus | minus != 0).then_some(Direction { plus, minus })
    }

    /// The sum of two directions that move along disjoint axes (`None` if they share one).
    pub fn combine(self, other: Direction) -> Option<Direction> {
        (self.axes() & other.axes() == 0).then_some(Direction {
            plus: self.plus | other.plus,
            minus: self.minus | other.minus,
        })
    }

    /// The offset vector.
    pub fn offset<const D: usize>(self) -> [i8; D] {
        core::array::from_fn(|a| self.component(a))
    }

    /// The offset along one axis: -1, 0 or +1.
    #[inline]
    pub fn component(self, axis: usize) -> i8 {
        ((self.plus >> axis) & 1) as i8 - ((self.minus >> axis) & 1) as i8
    }

    /// Mask of the axes moving up.
    #[inline]
    pub const fn plus_mask(self) -> u8 {
        self.plus
    }

    /// Mask of the axes moving down.
    #[inline]
    pub const fn minus_mask(self) -> u8 {
        self.minus
    }

    /// Mask of the axes moved along.
    #[inline]
    pub const fn axes(self) -> u8 {
        self.plus | self.minus
    }

    /// How many axes the direction moves along: 1 for a face, 2 for an edge (in 3D), D for a corner.
    #[inline]
    pub const fn axes_moved(self) -> u32 {
        (self.plus | self.minus).count_ones()
    }

    /// The opposite direction.
    #[inline]
    pub const fn opposite(self) -> Direction {
        Direction {
            plus: self.minus,
            minus: self.plus,
        }
    }

    /// Every direction in D dimensions allowed by `connectivity`, in a fixed order.
    ///
    /// There are 2D face directions, and 3^D - 1 directions with corner connectivity.
    /// ```
    /// use orthtree::{Connectivity, geom::Direction};
    /// assert_eq!(Direction::all::<3>(Connectivity::Face).count(), 6);
    /// assert_eq!(Direction::all::<3>(Connectivity::Edge).count(), 18);
    /// assert_eq!(Direction::all::<3>(Connectivity::Corner).count(), 26);
    /// ```
    pub fn all<const D: usize>(connectivity: Connectivity) -> impl Iterator<Item = Direction> {
        // `code` moves along axis `a` by its base-3 digit `a`: 0 stays, 1 up, 2 down.
        (0..3usize.pow(D as u32)).filter_map(move |code| {
            let digit = |a: usize| [0, 1, -1][code / 3usize.pow(a as u32) % 3];
            Direction::from_offset::<D>(core::array::from_fn(digit))
                .filter(|d| connectivity.allows(d.axes_moved()))
        })
    }
}

/// Which neighbours count as adjacent, for balance and neighbour lists.
///
/// `Face`: cells sharing a (D-1)-dimensional face (the chapter's definition of neighbours). `Edge`:
/// also cells sharing a (D-2)-dimensional edge (in 2D the same as `Corner`). `Corner`: cells
/// sharing any boundary point (p4est's "full" balance).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Connectivity {
    /// Across (D-1)-dimensional faces only.
    Face,
    /// Across faces and (D-2)-dimensional edges.
    Edge,
    /// Across any shared boundary point.
    Corner,
}

impl Connectivity {
    /// Every connectivity, from the weakest.
    pub const ALL: [Connectivity; 3] =
        [Connectivity::Face, Connectivity::Edge, Connectivity::Corner];

    /// `true` when a direction moving along `axes_moved` axes counts.
    #[inline]
    pub const fn allows(self, axes_moved: u32) -> bool {
        match self {
            Connectivity::Face => axes_moved <= 1,
            Connectivity::Edge => axes_moved <= 2,
            Connectivity::Corner => true,
        }
    }
}
