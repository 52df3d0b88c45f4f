//! [`RootGeometry`]: where the cells of a tree lie in space, and the exact quantisation of points
//! to Morton keys that agrees with the chapter's split convention.
//!
//! The boundary between cells `j - 1` and `j` at level `l` on axis `a` is
//! `b(t) = 2 * (lo_a / 2 + h * t)` with `t = j / 2^l` and `h` half the root cube's side, evaluated
//! in `f64` (`lo_a / 2` rounded down). Halving keeps every boundary strictly inside the points'
//! range finite for any finite coordinates (only the root cube's far side can overflow to
//! infinity, when one axis spans nearly all of `f64` and another sits near `f64::MAX`), and rounding is monotone,
//! so `b` is non-decreasing in `t`: the boundaries of every level are a subset of those of the
//! next, and a point lies in cell `j` (at the finest level) exactly when `b(j) < x <= b(j + 1)`.
//! A coordinate on a split line (`x == b(t)`) therefore goes to the lower cell, as in the chapter,
//! and a cell's points are exactly those whose key has the cell's key as prefix.
//!
//! The 64 levels of [`DeepCell`](crate::geom::DeepCell)s, for the compressed trees, continue these
//! lines below level 32 (`root_deep.rs`: [`RootGeometry::deep_coordinate`]).

use super::{Aabb, AabbError, Cell, Scalar};

/// How many points [`RootGeometry::keys_into`] quantises at a time.
const LANES: usize = 8;

/// The root cube of a tree and the map between coordinates and cells.
///
/// ```
/// use orthtree::{Cell, geom::RootGeometry};
/// let g = RootGeometry::<2>::new([0.0, 0.0], 16.0);
/// let c = Cell::new(1, [1, 0]).unwrap(); // the chapter's SE quadrant
/// assert_eq!(g.cell_box(&c).min, [8.0, 0.0]);
/// // on the vertical split line: the lower (western) side
/// assert_eq!(g.cell_of(&[8.0, 3.0], 1), Cell::new(1, [0, 0]).unwrap());
/// assert_eq!(g.cell_of(&[8.5, 3.0], 1), c);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RootGeometry<const D: usize> {
    half_lo: [f64; D],
    half_side: f64,
    /// 2^FINEST / half_side (0 for an empty cube): turns a coordinate into a first guess of its
    /// cell, which `coordinate` then checks exactly.
    scale: f64,
    /// Per axis, a bound on the rounding error of the guess plus that of the boundaries, in
    /// finest cells, doubled (above 1 where no bound is known): a guess whose fraction is
    /// farther than this from an integer is the exact cell (see [`RootGeometry::coordinate`]).
    margin: [f64; D],
}

impl<const D: usize> RootGeometry<D> {
    pub(super) const FINEST: u32 = Cell::<D>::MAX_LEVEL as u32;

    /// The cube with lower corner `min` and side `side` (finite, non-negative; `-0.0` is 0).
    /// Its far side may round to infinity (`min` near `f64::MAX`); the boundaries strictly
    /// inside stay finite.
    ///
    /// # Panics
    ///
    /// When a coordinate of `min` or `side` is not finite, or `side` is negative:
    /// [`RootGeometry::try_new`] returns the error instead.
    pub fn new(min: [f64; D], side: f64) -> Self {
        Self::try_new(min, side).unwrap_or_else(|e| panic!("RootGeometry::new: {e}"))
    }

    /// [`RootGeometry::new`], or an error.
    ///
    /// # Errors
    /// [`AabbError::NonFinite`] naming the first non-finite axis of `min`,
    /// [`AabbError::InvalidSide`] for a side that is NaN, infinite or negative.
    ///
    /// ```
    /// use orthtree::{geom::AabbError, geom::RootGeometry};
    /// assert!(RootGeometry::<2>::try_new([0.0, 1.0], 2.0).is_ok());
    /// assert_eq!(
    ///     RootGeometry::<2>::try_new([0.0, f64::NAN], 2.0),
    ///     Err(AabbError::NonFinite { axis: 1 })
    /// );
    /// assert!(matches!(
    ///     RootGeometry::<2>::try_new([0.0, 0.0], -1.0),
    ///     Err(AabbError::InvalidSide { .. })
    /// ));
    /// ```
    pub fn try_new(min: [f64; D], side: f64) -> Result<Self, AabbError> {
        check_corner_side(&min, side)?;
        // Half the side rounded up: halving an odd subnormal side rounds, and the cube must
        // not shrink below `side`.
        let half = side.abs() * 0.5;
        let half = if 2.0 * half < side {
            half.next_up()
        } else {
            half
        };
        Ok(Self::from_halves(min.map(half_down), half))
    }

    /// The two numbers that fix the geometry: the root cube's lower corner halved (rounded
    /// down) and half its side ([`RootGeometry::try_from_halves`] takes them back).
    #[cfg(any(feature = "saved", feature = "serde"))]
    pub(crate) fn halves(&self) -> ([f64; D], f64) {
        (self.half_lo, self.half_side)
    }

    /// The geometry of [`RootGeometry::halves`], for a saved tree: the derived figures are
    /// recomputed, so a geometry read back equals the one written.
    ///
    /// # Errors
    /// [`AabbError::NonFinite`] naming the first non-finite axis of `half_lo`,
    /// [`AabbError::InvalidSide`] for a half side that is NaN, infinite or negative.
    #[cfg(any(feature = "saved", feature = "serde"))]
    pub(crate) fn try_from_halves(half_lo: [f64; D], half_side: f64) -> Result<Self, AabbError> {
        check_corner_side(&half_lo, half_side)?;
        Ok(Self::from_halves(half_lo, half_side))
    }

    fn from_halves(half_lo: [f64; D], half_side: f64) -> Self {
        let finest = (1u64 << Self::FINEST) as f64;
        let scale = if half_side > 0.0 {
            finest / half_side
        } else {
            0.0
        };
        RootGeometry {
            half_lo,
            half_side,
            scale,
            margin: half_lo.map(|lo| guess_margin(lo, half_side, Self::FINEST)),
        }
    }

    /// The smallest cube with lower corner at the per-axis minimum of `bounds` that contains
    /// `bounds` (side 1 when `bounds` is a single point); for any finite `bounds`.
    pub fn enclosing(bounds: &Aabb<f64, D>) -> Self {
        let half_lo = bounds.min.map(half_down);
        let mut half_side = (0..D)
            .map(|a| bounds.max[a] * 0.5 - half_lo[a])
            .fold(0.0, f64::max);
        if half_side == 0.0 {
            half_side = 0.5;
        }
        let mut g = Self::from_halves(half_lo, half_side);
        // Rounding can leave the upper side a hair short: grow one ulp at a time, then
        // geometrically, so that this ends whatever the magnitudes.
        let mut tries = 0u32;
        while (0..D).any(|a| g.upper(a) < bounds.max[a]) {
            g.half_side = if tries < 8 {
                g.half_side.next_up()
            } else {
                g.half_side * (1.0 + f64::EPSILON * (1u64 << (tries - 8).min(52)) as f64)
            };
            tries += 1;
        }
        Self::from_halves(g.half_lo, g.half_side)
    }

    /// The boundary number `j` (of `2^level + 1`) along `axis` at `level`.
    #[inline]
    pub fn boundary(&self, axis: usize, j: u64, level: u8) -> f64 {
        // j / 2^level, exactly: a multiplication by a power of two.
        self.at(axis, (j as i64) as f64 * pow2(level))
    }

    /// The boundary at the fraction `t` of the root's side along `axis`: `2 * (lo / 2 + h * t)`.
    #[inline]
    fn at(&self, axis: usize, t: f64) -> f64 {
        2.0 * (self.half_lo[axis] + self.half_side * t)
    }

    #[inline]
    fn upper(&self, axis: usize) -> f64 {
        self.at(axis, 1.0)
    }

    /// The root cube.
    pub fn root_box(&self) -> Aabb<f64, D> {
        self.cell_box(&Cell::root())
    }

    /// The closed box of `cell`.
    pub fn cell_box(&self, cell: &Cell<D>) -> Aabb<f64, D> {
        let c = cell.coords();
        Aabb {
            min: core::array::from_fn(|a| self.boundary(a, c[a] as u64, cell.level())),
            max: core::array::from_fn(|a| self.boundary(a, c[a] as u64 + 1, cell.level())),
        }
    }

    /// The middle boundary of `cell` on every axis: the sides its children share.
    #[inline]
    pub(crate) fn mids(&self, cell: &Cell<D>) -> [f64; D] {
        let (level, c) = (cell.level() + 1, cell.coords());
        core::array::from_fn(|a| self.boundary(a, 2 * c[a] as u64 + 1, level))
    }

    /// The child of `cell` (closed box `bbox`) holding `q` under the split convention (a
    /// coordinate on a middle boundary goes to the lower child), with its closed box: one
    /// comparison per axis. `q` is taken to lie in `bbox`.
    #[inline]
    pub(crate) fn child_holding(
        &self,
        cell: &Cell<D>,
        bbox: &Aabb<f64, D>,
        q: &[f64; D],
    ) -> (usize, Aabb<f64, D>) {
        let mid = self.mids(cell);
        let mut child = *bbox;
        let mut i = 0;
        for a in 0..D {
            if q[a] > mid[a] {
                i |= 1 << a;
                child.min[a] = mid[a];
            } else {
                child.max[a] = mid[a];
            }
        }
        (i, child)
    }

    /// The finest-level cell coordinate of `x` along `axis`: the `j` with `b(j) < x <= b(j + 1)`,
    /// clamped to the root cube (the first cell includes its lower boundary).
    ///
    /// The guess `s = (x / 2 - lo / 2) * 2^FINEST / h` is within a few units in the last place
    /// of the exact position, and so is every boundary; when the fraction of `s` is farther
    /// from an integer than both errors together (`margin`, known from the cube alone), the
    /// guess is the answer. Otherwise the boundaries decide: the guess and its neighbours, then
    /// a binary search.
    #[inline]
    pub fn coordinate(&self, axis: usize, x: f64) -> u32 {
        self.coordinate_at(axis, x, Self::FINEST as u8) as u32
    }

    /// [`RootGeometry::coordinate`] at `level` (`Cell::MAX_LEVEL..=32`): the guess's shortcut
    /// (the margin grows with the cells' count, 2^level), else the boundaries.
    #[inline]
    pub(super) fn coordinate_at(&self, axis: usize, x: f64, level: u8) -> u64 {
        let finer = (1u64 << (level as u32 - Self::FINEST)) as f64;
        let scaled = (x * 0.5 - self.half_lo[axis]) * (self.scale * finer);
        // `as` truncates (and saturates; NaN gives 0); the fraction is exact below 2^52 and
        // fails the test for negative, huge or NaN guesses.
        let guess = scaled as i64;
        let fraction = scaled - guess as f64;
        let margin = self.margin[axis] * finer;
        if fraction > margin && fraction < 1.0 - margin && guess < (1i64 << level) {
            return guess as u64;
        }
        self.exact_coordinate(axis, x, scaled, level)
    }

    /// [`RootGeometry::coordinate_at`] from the boundaries alone; `scaled` is the guess.
    fn exact_coordinate(&self, axis: usize, x: f64, scaled: f64, level: u8) -> u64 {
        let last = (1u64 << level) - 1;
        let at = |j: u64| self.boundary(axis, j, level);
        let fits = |j: u64| (j == 0 || at(j) < x) && (j == last || x <= at(j + 1));
        // `as` saturates and maps NaN to 0.
        let guess = scaled.clamp(0.0, last as f64) as i64 as u64;
        for j in [guess, guess.saturating_sub(1), (guess + 1).min(last)] {
            if fits(j) {
                return j;
            }
        }
        // The first j in 0..=last with x <= b(j + 1) (the boundaries are monotone).
        let (mut lo, mut hi) = (0u64, last);
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            if x <= at(mid + 1) {
                hi = mid;
            } else {
                lo = mid + 1;
            }
        }
        lo
    }

    /// The Morton key of `point` at the finest level ([`Cell::MAX_LEVEL`]).
    #[inline]
    pub fn key(&self, point: &[f64; D]) -> u64 {
        let coords: [u32; D] = core::array::from_fn(|a| self.coordinate(a, point[a]));
        crate::geom::morton::interleave(coords, Self::FINEST)
    }

    /// [`RootGeometry::key`] of a point with coordinates of any [`Scalar`] (converted to `f64`).
    #[inline]
    pub(crate) fn scalar_key<S: Scalar>(&self, point: &[S; D]) -> u64 {
        self.key(&point.map(Scalar::to_f64))
    }

    /// [`RootGeometry::key`] of points `0..n` (`point(i)` reads point `i`), handed to
    /// `found(i, key)` in index order.
    ///
    /// The same guess and margin test as [`RootGeometry::coordinate`], written for [`LANES`]
    /// points at a time without a conversion to integer (which has no vector form before
    /// AVX-512): `floor` by rounding through 2^52, whose bits then hold the integer. The
    /// compiler turns the lanes into vector instructions, and a lane that fails the test takes
    /// the scalar path. On 10^6 uniform 2D points the keys cost about 20% less.
    pub(crate) fn keys_into<'p, S: Scalar + 'p>(
        &self,
        n: usize,
        point: impl Fn(usize) -> &'p [S; D],
        mut found: impl FnMut(usize, u64),
    ) {
        let full = n - n % LANES;
        for first in (0..full).step_by(LANES) {
            let lanes: [[f64; D]; LANES] =
                core::array::from_fn(|l| point(first + l).map(Scalar::to_f64));
            for (l, key) in self.lane_keys(&lanes).into_iter().enumerate() {
                found(first + l, key);
            }
        }
        for i in full..n {
            found(i, self.scalar_key(point(i)));
        }
    }

    /// The keys of [`LANES`] points: see [`RootGeometry::keys_into`].
    #[inline]
    fn lane_keys(&self, points: &[[f64; D]; LANES]) -> [u64; LANES] {
        // Adding 2^52 to a value in [0, 2^52) rounds it to an integer held in the low bits.
        const ROUND: f64 = 4_503_599_627_370_496.0;
        let cells = (1u64 << Self::FINEST) as f64;
        let mut fast = [true; LANES];
        let mut coords = [[0u64; LANES]; D];
        for (a, axis) in coords.iter_mut().enumerate() {
            let margin = self.margin[a];
            for (l, c) in axis.iter_mut().enumerate() {
                let scaled = (points[l][a] * 0.5 - self.half_lo[a]) * self.scale;
                let near = (scaled + ROUND) - ROUND;
                let floor = if near > scaled { near - 1.0 } else { near };
                let fraction = scaled - floor;
                fast[l] &= (scaled >= 0.0)
                    & (floor < cells)
                    & (fraction > margin)
                    & (fraction < 1.0 - margin);
                *c = (floor + ROUND).to_bits().wrapping_sub(ROUND.to_bits());
            }
        }
        // Plain loops over the lanes (not closures), so that the bit spreading vectorises too.
        let mut keys = [0u64; LANES];
        for (a, axis) in coords.iter().enumerate() {
            for (key, &c) in keys.iter_mut().zip(axis) {
                *key |= crate::geom::morton::spread::<D>(c) << a;
            }
        }
        for (l, key) in keys.iter_mut().enumerate() {
            if !fast[l] {
                *key = self.key(&points[l]);
            }
        }
        keys
    }

    /// The cell at `level` that holds `point` under the split convention.
    pub fn cell_of(&self, point: &[f64; D], level: u8) -> Cell<D> {
        Cell::from_aligned_key(self.key(point), level)
    }
}

/// The closed box of child `i` of a cell with closed box `bbox` and middle boundaries `mid`
/// ([`RootGeometry::mids`]): the parent's box gives the outer sides exactly
/// (`boundary(2c, l + 1) == boundary(c, l)`).
#[inline]
pub(crate) fn child_box<const D: usize>(
    bbox: &Aabb<f64, D>,
    mid: &[f64; D],
    i: usize,
) -> Aabb<f64, D> {
    Aabb {
        min: core::array::from_fn(|a| {
            if (i >> a) & 1 == 0 {
                bbox.min[a]
            } else {
                mid[a]
            }
        }),
        max: core::array::from_fn(|a| {
            if (i >> a) & 1 == 0 {
                mid[a]
            } else {
                bbox.max[a]
            }
        }),
    }
}

/// A cube's corner (or halved corner) and side (or half side), checked: every coordinate finite,
/// the side finite and not negative.
///
/// # Errors
/// [`AabbError::NonFinite`] naming the first non-finite axis, [`AabbError::InvalidSide`] for a
/// side that is NaN, infinite or negative.
fn check_corner_side<const D: usize>(lo: &[f64; D], side: f64) -> Result<(), AabbError> {
    if let Some(axis) = lo.iter().position(|x| !x.is_finite()) {
        return Err(AabbError::NonFinite { axis });
    }
    if !(side >= 0.0 && side.is_finite()) {
        return Err(AabbError::InvalidSide { side: side.into() });
    }
    Ok(())
}

/// The `margin` of [`RootGeometry::coordinate`] for an axis with `half_lo` and `half_side`,
/// in cells of level `finest`.
///
/// With u = 2^-53, a boundary `b(j) = 2 fl(lo/2 + fl(h t))` sits within u (2 + |lo/2| / h)
/// cells (plus u^2 terms) of its exact place `j` (doubling is exact), and the guess (three
/// rounded operations, `x / 2` exact for normal `x`) within 3u |s| <= 3u 2^finest of the exact
/// position of `x`. If the guess's fraction is more than the sum away from 0 and 1, `x` is
/// strictly above boundary `j` and at most boundary `j + 1`. The sum is doubled, with slack
/// for the u^2 terms; the bound is refused (2.0, never met) where subnormal or overflowing
/// values could break the relative error model.
fn guess_margin(half_lo: f64, half_side: f64, finest: u32) -> f64 {
    let safe = half_side >= (-960f64).exp2() && half_lo.abs() + 2.0 * half_side <= 1000f64.exp2();
    if !safe {
        return 2.0;
    }
    let u_cells = (finest as f64 - 53.0).exp2();
    let margin = 2.0 * u_cells * (5.01 + half_lo.abs() / half_side) + (-40f64).exp2();
    if margin < 0.25 {
        margin
    } else {
        2.0
    }
}

/// 2^-level, exactly.
#[inline]
fn pow2(level: u8) -> f64 {
    f64::from_bits((1023 - level as u64) << 52)
}

/// Half of `m`, rounded down: halving a subnormal can round up (to even), which would put the
/// root's lower side above the smallest point.
fn half_down(m: f64) -> f64 {
    let h = m * 0.5;
    if 2.0 * h > m {
        h.next_down()
    } else {
        h
    }
}

#[cfg(test)]
mod tests;
