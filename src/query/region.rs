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
    /// Checks the region's parameters before a query; the default accepts everything.
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
        match (0..D).find(|&a| self.min[a].is_nan() || self.max[a].is_nan()) {
            Some(axis) => Err(QueryError::NanBound { axis }),
            None => Ok(()),
        }
    }
}

/// The closed ball of points whose squared Euclidean distance to `center` is at most
/// `radius * radius` (both computed in `f64`, axis by axis in order).
///
/// ```
/// use orthtree::query::{Ball, Region};
/// let b = Ball::new([0.0, 0.0], 5.0).unwrap();
/// assert!(b.contains(&[3.0, 4.0])); // on the sphere: closed
/// assert!(!b.contains(&[3.0, 4.5]));
/// assert!(Ball::new([0.0, 0.0], -1.0).is_err());
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
    pub fn new(center: [f64; D], radius: f64) -> Result<Self, QueryError> {
        let b = Ball { center, radius };
        b.validate()?;
        Ok(b)
    }
}

impl<const D: usize> Region<D> for Ball<D> {
    #[inline]
    fn classify(&self, cell: &Aabb<f64, D>) -> Relation {
        let r2 = self.radius * self.radius;
        let (mut near, mut far) = (0.0, 0.0);
        for a in 0..D {
            let c = self.center[a];
            let (dl, dh) = (c - cell.min[a], cell.max[a] - c);
            // Nearest and farthest offsets along this axis (0 when c lies in the interval).
            let n = if dl < 0.0 {
                -dl
            } else if dh < 0.0 {
                -dh
            } else {
                0.0
            };
            let f = dl.abs().max(dh.abs());
            near += n * n;
            far += f * f;
        }
        if near > r2 {
            Relation::Outside
        } else if far <= r2 {
            Relation::Inside
        } else {
            Relation::Crossing
        }
    }
    #[inline]
    fn contains(&self, p: &[f64; D]) -> bool {
        let mut d2 = 0.0;
        for a in 0..D {
            let d = p[a] - self.center[a];
            d2 += d * d;
        }
        d2 <= self.radius * self.radius
    }
    fn validate(&self) -> Result<(), QueryError> {
        super::check_point(&self.center)?;
        if self.radius >= 0.0 {
            Ok(())
        } else {
            Err(QueryError::InvalidRadius {
                radius: self.radius.into(),
            })
        }
    }
}

/// The closed half-space `normal . x <= offset` (the dot product computed in `f64`, axis by axis
/// in order). A zero normal gives everything (offset >= 0) or nothing.
///
/// ```
/// use orthtree::query::{HalfSpace, Region};
/// let left = HalfSpace::new([1.0, 0.0], 0.5).unwrap(); // x <= 0.5
/// assert!(left.contains(&[0.5, 7.0]));
/// assert!(!left.contains(&[0.6, 0.0]));
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
    pub fn new(normal: [f64; D], offset: f64) -> Result<Self, QueryError> {
        let h = HalfSpace { normal, offset };
        h.validate()?;
        Ok(h)
    }
}

impl<const D: usize> Region<D> for HalfSpace<D> {
    #[inline]
    fn classify(&self, cell: &Aabb<f64, D>) -> Relation {
        let (mut low, mut high) = (0.0, 0.0);
        for a in 0..D {
            let n = self.normal[a];
            let (x, y) = (n * cell.min[a], n * cell.max[a]);
            // n * x is monotone in x for a fixed n, so the corners give the extremes.
            low += x.min(y);
            high += x.max(y);
        }
        if low > self.offset {
            Relation::Outside
        } else if high <= self.offset {
            Relation::Inside
        } else {
            Relation::Crossing
        }
    }
    #[inline]
    fn contains(&self, p: &[f64; D]) -> bool {
        let mut s = 0.0;
        for a in 0..D {
            s += self.normal[a] * p[a];
        }
        s <= self.offset
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
