//! Query regions: the [`Region`] trait (classify a closed cell box as outside, inside or crossing;
//! test a point) and its implementations for closed boxes ([`Aabb`]), closed balls ([`Ball`]) and
//! closed half-spaces ([`HalfSpace`], `a . x <= b`, exercise 14.13 of the chapter).
//!
//! Each cell test is computed with the same floating-point operations, in the same order, as the
//! point test, on the box corner that is extreme for them; rounding is monotone, so a cell called
//! `Inside` holds only points the point test accepts and a cell called `Outside` only points it
//! rejects. A query's answer therefore never depends on the tree's shape.

// Loops over axes index the point, the box's min and max together; an index reads best.
#![allow(clippy::needless_range_loop)]

// Axis loops index several arrays in one fixed order, the order the exactness argument needs.

use super::QueryError;
use crate::geom::Aabb;
use crate::geom::{halves_by_terms, Halves, Kept};

/// Where a closed cell box lies with respect to a region.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Relation {
    /// No point of the box is in the region.
    Outside,
    /// Every point of the box is in the region.
    Inside,
    /// Neither is known: the box may straddle the region's boundary.
    Crossing,
}

/// A query region in `f64` coordinates.
///
/// `classify` may answer [`Relation::Crossing`] when unsure, but must never call a box `Inside`
/// (or `Outside`) when one of its points fails (or passes) `contains`.
///
/// ```
/// use orthtree::prelude::*;
/// use orthtree::query::{Region, Relation};
/// use orthtree::{Aabb, Quadtree};
/// /// The points with x < y.
/// struct AboveDiagonal;
/// impl Region<2> for AboveDiagonal {
///     fn classify(&self, b: &Aabb<f64, 2>) -> Relation {
///         if b.max[0] < b.min[1] {
///             Relation::Inside
///         } else if b.min[0] >= b.max[1] {
///             Relation::Outside
///         } else {
///             Relation::Crossing
///         }
///     }
///     fn contains(&self, p: &[f64; 2]) -> bool {
///         p[0] < p[1]
///     }
/// }
/// let t = Quadtree::new(&[([0.0, 1.0], 'a'), ([1.0, 0.0], 'b'), ([2.0, 2.0], 'c')]).unwrap();
/// assert_eq!(t.query_count(AboveDiagonal).unwrap(), 1);
/// ```
pub trait Region<const D: usize> {
    /// Where the closed box `cell` lies with respect to the region.
    fn classify(&self, cell: &Aabb<f64, D>) -> Relation;
    /// `true` when `p` lies in the region.
    fn contains(&self, p: &[f64; D]) -> bool;
    /// `true` when `classify(cell)` is [`Relation::Outside`]; a region may answer it with less
    /// work (a ball needs only the box's nearest point). The engines ask it of the halves of a
    /// node, to leave their children out together.
    #[inline]
    fn excludes(&self, cell: &Aabb<f64, D>) -> bool {
        self.classify(cell) == Relation::Outside
    }
    /// The children of `cell` split at `mid` outside every half of it (either side of a split
    /// line) that the region [excludes](Region::excludes) ([`Kept`]). The default asks
    /// `excludes` of the 2 D half boxes; a [`Ball`] changes one term of the box's sum per half,
    /// with the same answers.
    #[inline]
    fn kept_children(&self, cell: &Aabb<f64, D>, mid: &[f64; D]) -> Kept {
        (|h: &Aabb<f64, D>| self.excludes(h)).kept(cell, mid)
    }
    /// Checks the region's parameters before a query; the default accepts everything.
    ///
    /// # Errors
    /// The region's own [`QueryError`] (a NaN radius, a non-finite normal, ...).
    fn validate(&self) -> Result<(), QueryError> {
        Ok(())
    }
}

impl<const D: usize, R: Region<D> + ?Sized> Region<D> for &R {
    #[inline]
    fn classify(&self, cell: &Aabb<f64, D>) -> Relation {
        (**self).classify(cell)
    }
    #[inline]
    fn contains(&self, p: &[f64; D]) -> bool {
        (**self).contains(p)
    }
    #[inline]
    fn excludes(&self, cell: &Aabb<f64, D>) -> bool {
        (**self).excludes(cell)
    }
    #[inline]
    fn kept_children(&self, cell: &Aabb<f64, D>, mid: &[f64; D]) -> Kept {
        (**self).kept_children(cell, mid)
    }
    fn validate(&self) -> Result<(), QueryError> {
        (**self).validate()
    }
}

/// The closed box: its boundary belongs to it. Bounds may be infinite; a box with `min > max` on
/// an axis is empty; a NaN bound is refused.
impl<const D: usize> Region<D> for Aabb<f64, D> {
    #[inline]
    fn classify(&self, cell: &Aabb<f64, D>) -> Relation {
        let mut inside = true;
        for a in 0..D {
            if cell.max[a] < self.min[a] || cell.min[a] > self.max[a] {
                return Relation::Outside;
            }
            inside &= self.min[a] <= cell.min[a] && cell.max[a] <= self.max[a];
        }
        if inside {
            Relation::Inside
        } else {
            Relation::Crossing
        }
    }
    #[inline]
    fn contains(&self, p: &[f64; D]) -> bool {
        // `&`, not `&&`: no branch per axis (see `range::contains_mask`).
        let mut inside = true;
        for a in 0..D {
            inside &= (self.min[a] <= p[a]) & (p[a] <= self.max[a]);
        }
        inside
    }
    fn validate(&self) -> Result<(), QueryError> {
        let nan = (0..D).find(|&a| self.min[a].is_nan() || self.max[a].is_nan());
        nan.map_or(Ok(()), |axis| Err(QueryError::NanBound { axis }))
    }
}

/// The closed ball of points at Euclidean distance at most `radius` from `center`.
///
/// Computed in `f64`, axis by axis in order, on offsets scaled by the power of two `s` that
/// brings the radius near 1: a point is in when `sum ((p_a - c_a) s)^2 <= (radius s)^2`. The
/// scaling is exact, so this is the plain squared comparison wherever that does not overflow or
/// underflow, and stays right where it would: a radius of `1e200` does not take in a point at
/// `1e201` (both squares would be infinite), and a radius of `1e-300` leaves out a point at
/// `1e-200` (both squares would be 0). An infinite radius holds everything, a radius of 0 (or
/// -0.0) only the centre; a NaN or negative radius and a non-finite centre are refused.
///
/// ```
/// use orthtree::query::{Ball, Region};
/// let b = Ball::new([0.0, 0.0], 5.0).unwrap();
/// assert!(b.contains(&[3.0, 4.0])); // on the sphere: closed
/// assert!(!b.contains(&[3.0, 4.5]));
/// assert!(Ball::new([0.0, 0.0], -1.0).is_err());
/// let huge = Ball::new([0.0, 0.0], 1e200).unwrap();
/// assert!(huge.contains(&[3e199, 4e199]) && !huge.contains(&[1e201, 0.0]));
/// let tiny = Ball::new([0.0, 0.0], 1e-300).unwrap();
/// assert!(tiny.contains(&[3e-301, 4e-301]) && !tiny.contains(&[1e-200, 0.0]));
/// assert!(Ball::new([0.0, 0.0], f64::INFINITY).unwrap().contains(&[f64::MAX, -f64::MAX]));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ball<const D: usize> {
    /// The centre.
    pub center: [f64; D],
    /// The radius, non-negative.
    pub radius: f64,
}

impl<const D: usize> Ball<D> {
    /// A ball; an error for a non-finite centre or a negative or NaN radius.
    ///
    /// # Errors
    /// [`QueryError::NotFinite`] for a non-finite centre (naming the axis),
    /// [`QueryError::InvalidRadius`] for a negative or NaN radius.
    pub fn new(center: [f64; D], radius: f64) -> Result<Self, QueryError> {
        let b = Ball { center, radius };
        b.validate()?;
        Ok(b)
    }

    /// The scale `s` (a power of two between 2^-1022 and 2^1022, exact to multiply by) and
    /// `(radius s)^2`: `s` puts a normal radius in [1, 2), and is 2^1022 for 0 and subnormal
    /// radii, so that no nonzero offset scales to 0.
    #[inline]
    fn scaled_radius(&self) -> (f64, f64) {
        let biased = ((self.radius.to_bits() >> 52) & 0x7ff).clamp(1, 2045);
        let s = f64::from_bits((2046 - biased) << 52);
        let r = self.radius * s;
        (s, r * r)
    }

    /// The offsets from the centre to the low and high sides of `cell` along axis `a`, as
    /// `p - c` rounds for a point there.
    #[inline(always)]
    fn offsets(&self, cell: &Aabb<f64, D>, a: usize) -> (f64, f64) {
        let c = self.center[a];
        (c - cell.min[a], cell.max[a] - c)
    }

    /// The squared nearest offset along axis `a` to the interval `[lo, hi]`, scaled by `s`:
    /// the term of [`Ball::classify`](Region::classify)'s nearest sum for that axis.
    #[inline(always)]
    fn near_term(&self, a: usize, lo: f64, hi: f64, s: f64) -> f64 {
        let c = self.center[a];
        let n = nearest_offset(c - lo, hi - c) * s;
        n * n
    }
}

/// The offset from a ball's centre to the nearest point of a box's interval along one axis,
/// given the offsets to its low (`dl`) and high (`dh`) sides: 0 when the centre lies in it.
#[inline(always)]
fn nearest_offset(dl: f64, dh: f64) -> f64 {
    // Selected without a branch on where the centre lies (see `metric::axis_gap`): the same
    // value as `if dl < 0 { -dl } else if dh < 0 { -dh } else { 0 }` for every input.
    let above = if dh < 0.0 { -dh } else { 0.0 };
    if dl < 0.0 {
        -dl
    } else {
        above
    }
}

impl<const D: usize> Region<D> for Ball<D> {
    #[inline]
    fn classify(&self, cell: &Aabb<f64, D>) -> Relation {
        if self.radius == f64::INFINITY {
            return Relation::Inside;
        }
        let (s, r2) = self.scaled_radius();
        let (mut near, mut far) = (0.0, 0.0);
        for a in 0..D {
            let (dl, dh) = self.offsets(cell, a);
            let f = dl.abs().max(dh.abs()) * s;
            let n = nearest_offset(dl, dh) * s;
            near += n * n;
            far += f * f;
        }
        range_relation(near, far, r2)
    }
    /// The nearest squared offset of [`Ball::classify`](Region::classify), summed in the
    /// same order: the same answer for half the work.
    #[inline]
    fn excludes(&self, cell: &Aabb<f64, D>) -> bool {
        if self.radius == f64::INFINITY {
            return false;
        }
        let (s, r2) = self.scaled_radius();
        let mut near = 0.0;
        for a in 0..D {
            near += self.near_term(a, cell.min[a], cell.max[a], s);
        }
        near > r2
    }
    /// The sums of [`Ball::excludes`](Region::excludes), one term changed per half.
    #[inline]
    fn kept_children(&self, cell: &Aabb<f64, D>, mid: &[f64; D]) -> Kept {
        if self.radius == f64::INFINITY {
            return Some((0, 0));
        }
        let (s, r2) = self.scaled_radius();
        halves_by_terms(cell, mid, |a, lo, hi| self.near_term(a, lo, hi, s), r2)
    }
    #[inline]
    fn contains(&self, p: &[f64; D]) -> bool {
        if self.radius == f64::INFINITY {
            return true;
        }
        let (s, r2) = self.scaled_radius();
        let mut d2 = 0.0;
        for a in 0..D {
            let d = (p[a] - self.center[a]) * s;
            d2 += d * d;
        }
        d2 <= r2
    }
    fn validate(&self) -> Result<(), QueryError> {
        super::query_point(&self.center)?;
        super::check_radius(self.radius).map(drop)
    }
}

/// The closed half-space `normal . x <= offset`.
///
/// Computed in `f64`, axis by axis in order, with the normal and the offset scaled by the power
/// of two `s` that puts `sum |normal_a| s` in [1/4, 1/2): a point is in when
/// `sum (normal_a s) x_a <= offset s`. Scaled so, no product or partial sum can overflow for
/// finite coordinates, so a normal such as `[1e300, -1e300]` or points near `f64::MAX` never
/// make `inf - inf`: the answer is the rounded dot product's, with rounding about 4 times
/// coarser than plain `f64` for products in the subnormal range. A zero normal gives
/// everything (offset >= 0) or nothing; an offset of `+inf` everything, `-inf` nothing.
///
/// ```
/// use orthtree::query::{HalfSpace, Region};
/// let left = HalfSpace::new([1.0, 0.0], 0.5).unwrap(); // x <= 0.5
/// assert!(left.contains(&[0.5, 7.0]));
/// assert!(!left.contains(&[0.6, 0.0]));
/// // x <= y, with a normal whose products would overflow unscaled
/// let below = HalfSpace::new([1e300, -1e300], 0.0).unwrap();
/// assert!(below.contains(&[1e10, 1e10]) && !below.contains(&[f64::MAX, 1.0]));
/// assert!(below.contains(&[f64::MAX, f64::MAX]));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HalfSpace<const D: usize> {
    /// The outward normal `a`.
    pub normal: [f64; D],
    /// The offset `b`.
    pub offset: f64,
}

impl<const D: usize> HalfSpace<D> {
    /// A half-space; an error for a non-finite normal or a NaN offset.
    ///
    /// # Errors
    /// [`QueryError::InvalidNormal`] for a non-finite normal (naming the axis),
    /// [`QueryError::NanOffset`] for a NaN offset.
    pub fn new(normal: [f64; D], offset: f64) -> Result<Self, QueryError> {
        let h = HalfSpace { normal, offset };
        h.validate()?;
        Ok(h)
    }

    /// The normal and offset scaled by `s` (see the type's doc): exact but in the subnormal
    /// range. A zero normal is left as it is.
    #[inline]
    fn scaled(&self) -> ([f64; D], f64) {
        // The sum of magnitudes, scaled down first so that it cannot overflow (D <= 8).
        let t: f64 = self.normal.iter().map(|n| n.abs() * (-16f64).exp2()).sum();
        if t == 0.0 || !t.is_finite() {
            return (self.normal, self.offset);
        }
        // t in [2^e, 2^(e+1)): the sum lies in [2^(e+16), 2^(e+17)), and s = 2^-(e+18).
        let e = ((t.to_bits() >> 52) & 0x7ff).max(1) as i32 - 1023;
        let s = pow2(-(e + 18));
        (self.normal.map(|n| n * s), self.offset * s)
    }
}

/// 2^k for k in -1074..=1023, exactly (subnormal below -1022).
#[inline]
fn pow2(k: i32) -> f64 {
    if k >= -1022 {
        f64::from_bits(((k + 1023) as u64) << 52)
    } else {
        f64::from_bits(1u64 << (k + 1074))
    }
}

impl<const D: usize> Region<D> for HalfSpace<D> {
    #[inline]
    fn classify(&self, cell: &Aabb<f64, D>) -> Relation {
        let (normal, offset) = self.scaled();
        let (mut low, mut high) = (0.0, 0.0);
        for a in 0..D {
            let n = normal[a];
            let (x, y) = (n * cell.min[a], n * cell.max[a]);
            // n * x is monotone in x for a fixed n, so the corners give the extremes (a NaN
            // from 0 * inf, at an infinite cell side, is skipped by min and max).
            low += x.min(y);
            high += x.max(y);
        }
        range_relation(low, high, offset)
    }
    #[inline]
    fn contains(&self, p: &[f64; D]) -> bool {
        let (normal, offset) = self.scaled();
        let mut s = 0.0;
        for a in 0..D {
            s += normal[a] * p[a];
        }
        s <= offset
    }
    fn validate(&self) -> Result<(), QueryError> {
        if let Some(axis) = self.normal.iter().position(|x| !x.is_finite()) {
            return Err(QueryError::InvalidNormal { axis });
        }
        if self.offset.is_nan() {
            return Err(QueryError::NanOffset);
        }
        Ok(())
    }
}

/// Where a box lies with respect to the region of the points whose value (a ball's squared
/// distance from its centre, a half-space's scaled dot product) is at most `bound`, given the
/// least (`low`) and greatest (`high`) value over the box.
#[inline]
pub(crate) fn range_relation(low: f64, high: f64, bound: f64) -> Relation {
    if low > bound {
        Relation::Outside
    } else if high <= bound {
        Relation::Inside
    } else {
        Relation::Crossing
    }
}

#[cfg(test)]
mod tests {
    use super::super::metric::tests::SPECIAL;
    use super::nearest_offset;

    /// `nearest_offset` selects what the three-way branch it replaced returned, bit for bit,
    /// on every pair of special values.
    #[test]
    fn nearest_offset_equals_the_branching_form() {
        let branching = |dl: f64, dh: f64| {
            if dl < 0.0 {
                -dl
            } else if dh < 0.0 {
                -dh
            } else {
                0.0
            }
        };
        for dl in SPECIAL {
            for dh in SPECIAL {
                let (got, want) = (nearest_offset(dl, dh), branching(dl, dh));
                assert!(
                    got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()),
                    "nearest_offset({dl}, {dh}) = {got}, the branching form {want}"
                );
            }
        }
    }
}
