//! The 64-level quantisation of [`RootGeometry`] for [`DeepCell`]s: exact, O(1) per
//! coordinate, and equal to the point trees' cells down to level 32.
//!
//! Levels 0 to 32 are [`RootGeometry::boundary`]'s dyadic lines. Below level 32 there is no
//! arithmetic left to halve in: a level-32 cell `[L, R]` holds `K` `f64` values (counted by their
//! order, the bit patterns made monotone), and its `2^32` level-64 cells split those values
//! evenly: boundary `i` of the cell is the `f64` of order `ord(L) + floor(i K / 2^32)`. So:
//! - inside one binade (`f64`s evenly spaced) the split is the dyadic one, rounded down to the
//!   `f64` grid; every distinct value gets a cell of its own when `K <= 2^32`, which holds in
//!   every level-32 cell farther than `side / 4096` from zero;
//! - in the cells touching zero, which hold many binades, the split follows the binades (about
//!   `2^32 / 1000` cells per binade), so points near zero part by their order of magnitude;
//! - the boundaries are monotone, those of each level are among the next level's, and cells
//!   may be empty (`K < 2^32`, or one value spread over several cells) but never overlap.
//!
//! A point's coordinate is its level-32 cell (the exact search of [`RootGeometry::coordinate`])
//! and then `i = floor((d 2^32 - 1) / K)` for `d = ord(x) - ord(L)`: the last boundary below
//! `x`, so a point on a line goes to the lower cell at every level. A float estimate of the
//! quotient is corrected with two exact integer products: no search, whatever the box (an
//! inverse of the dyadic formula below level 32 would have to search where rounding makes it
//! flat, tens of steps in boxes far from the origin).

use super::root::RootGeometry;
use super::{Aabb, DeepCell, DeepKey};

/// The level down to which deep boundaries are dyadic.
const DYADIC: u8 = 32;
/// Level-64 indices inside one level-32 cell.
const SPAN: u64 = 1 << 32;

/// The order of a finite `f64` (or infinity) as an integer: monotone, -0 and +0 the same.
#[inline]
fn ord(x: f64) -> u64 {
    let bits = (x + 0.0).to_bits();
    if bits >> 63 == 1 {
        !bits
    } else {
        bits | (1 << 63)
    }
}

/// The inverse of [`ord`].
#[inline]
fn from_ord(o: u64) -> f64 {
    f64::from_bits(if o >> 63 == 1 { o & !(1 << 63) } else { !o })
}

/// `floor(i k / 2^32)`: how many of a cell's `k` values lie below its boundary `i`.
#[inline]
fn below(i: u64, k: u64) -> u64 {
    ((i as u128 * k as u128) >> 32) as u64
}

impl<const D: usize> RootGeometry<D> {
    /// The level-32 cell `j`'s sides along `axis` and how many `f64` values it spans.
    #[inline]
    fn span32(&self, axis: usize, j: u64) -> (u64, u64) {
        let lo = ord(self.boundary(axis, j, DYADIC));
        let hi = ord(self.boundary(axis, j + 1, DYADIC));
        (lo, hi.saturating_sub(lo))
    }

    /// The boundary number `j` (of `2^level + 1`, `level` at most 64) along `axis` for
    /// [`DeepCell`]s: [`RootGeometry::boundary`] down to level 32, then the even split of the
    /// level-32 cell's `f64` values (the module doc).
    ///
    /// ```
    /// use orthtree::geom::RootGeometry;
    /// let g = RootGeometry::<2>::new([0.0, 0.0], 1.0);
    /// assert_eq!(g.deep_boundary(0, 3, 2), g.boundary(0, 3, 2));
    /// assert_eq!(g.deep_boundary(0, (1 << 52) + 1, 53), 0.5 + (-53f64).exp2());
    /// assert_eq!(g.deep_boundary(0, 1 << 64, 64), 1.0);
    /// ```
    pub fn deep_boundary(&self, axis: usize, j: u128, level: u8) -> f64 {
        debug_assert!(level <= DeepCell::<D>::MAX_LEVEL && j <= 1 << level);
        if level <= DYADIC {
            return self.boundary(axis, j as u64, level);
        }
        let at = j << (64 - level);
        let (cell, i) = ((at >> 32) as u64, at as u64 & (SPAN - 1));
        if i == 0 {
            return self.boundary(axis, cell, DYADIC);
        }
        let (lo, k) = self.span32(axis, cell);
        from_ord(lo + below(i, k))
    }

    /// The closed box of a deep cell.
    pub fn deep_cell_box(&self, cell: &DeepCell<D>) -> Aabb<f64, D> {
        let (c, l) = (cell.coords(), cell.level());
        Aabb {
            min: core::array::from_fn(|a| self.deep_boundary(a, c[a] as u128, l)),
            max: core::array::from_fn(|a| self.deep_boundary(a, c[a] as u128 + 1, l)),
        }
    }

    /// The level-64 cell coordinate of `x` along `axis`: the `j` with `B(j) < x <= B(j + 1)`
    /// for `B(j) = deep_boundary(axis, j, 64)`, clamped to the root cube. Its top
    /// [`Cell::MAX_LEVEL`](crate::Cell::MAX_LEVEL) bits are [`RootGeometry::coordinate`]. O(1).
    ///
    /// ```
    /// use orthtree::geom::RootGeometry;
    /// let g = RootGeometry::<2>::new([0.0, 0.0], 1.0);
    /// assert_eq!(g.deep_coordinate(0, 0.5), (1 << 63) - 1); // on a split line: the lower cell
    /// assert_eq!(g.deep_coordinate(0, 0.5f64.next_up()), (1 << 63) + (1 << 11) - 1);
    /// assert_eq!(g.deep_coordinate(0, 1.0) >> 32, g.coordinate(0, 1.0) as u64);
    /// ```
    pub fn deep_coordinate(&self, axis: usize, x: f64) -> u64 {
        let cell = self.coordinate_at(axis, x, DYADIC);
        let (lo, k) = self.span32(axis, cell);
        let d = ord(x).saturating_sub(lo);
        let i = if d == 0 {
            0 // on the root's lower side
        } else if d > k {
            SPAN - 1 // beyond the root's upper side
        } else {
            // floor((d 2^32 - 1) / k) = ceil(d 2^32 / k) - 1: the float quotient is within
            // 2^-19 of d 2^32 / k, so its floor is off by at most one, and one exact product
            // either way corrects it.
            let num = ((d as u128) << 32) - 1;
            let q = ((d as f64 * SPAN as f64 / k as f64) as u64).min(SPAN - 1);
            let q = if q as u128 * k as u128 > num {
                q - 1
            } else if q + 1 < SPAN && (q + 1) as u128 * k as u128 <= num {
                q + 1
            } else {
                q
            };
            debug_assert!(q as u128 * k as u128 <= num && num < (q + 1) as u128 * k as u128);
            q
        };
        (cell << 32) | i
    }

    /// The deep key of `point`: its level-64 cell coordinates
    /// ([`RootGeometry::deep_coordinate`] per axis).
    #[inline]
    pub fn deep_key(&self, point: &[f64; D]) -> DeepKey<D> {
        core::array::from_fn(|a| self.deep_coordinate(a, point[a]))
    }

    /// The deep cell at `level` (at most 64) that holds `point` under the split convention.
    ///
    /// ```
    /// use orthtree::geom::RootGeometry;
    /// let g = RootGeometry::<2>::new([0.0, 0.0], 1.0);
    /// let (a, b) = (g.deep_cell_of(&[0.5, 0.5], 64), g.deep_cell_of(&[0.5f64.next_up(), 0.5], 64));
    /// assert_ne!(a, b);
    /// assert_eq!(a.ancestor(32).to_cell(), g.cell_of(&[0.5, 0.5], 32));
    /// ```
    pub fn deep_cell_of(&self, point: &[f64; D], level: u8) -> DeepCell<D> {
        DeepCell::of_key(&self.deep_key(point), level)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// `deep_coordinate` against its definition, and against `coordinate` on the top bits.
    fn check<const D: usize>(g: &RootGeometry<D>, x: f64) {
        let b = |j: u64| g.deep_boundary(0, j as u128, 64);
        let j = g.deep_coordinate(0, x);
        assert!(j == 0 || b(j) < x, "{g:?} {x}: {j} too high");
        assert!(j == u64::MAX || x <= b(j + 1), "{g:?} {x}: {j} too low");
        let finest = RootGeometry::<D>::FINEST;
        assert_eq!(j >> (64 - finest), g.coordinate(0, x) as u64, "{g:?} {x}");
    }

    #[test]
    fn deep_coordinates_follow_the_deep_boundaries() {
        let mut rng = rand::rngs::SmallRng::seed_from_u64(3);
        let boxes = [
            (0.0, 1.0),
            (-1.0, 3.0),
            (1e6, 1.0),
            (0.1, 3e-9),
            (-7.5, 1e300),
            (0.0, f64::MIN_POSITIVE),
            (3.0, 0.0),
        ];
        for (lo, side) in boxes {
            let g2 = RootGeometry::<2>::new([lo, lo], side);
            let g3 = RootGeometry::<3>::new([lo; 3], side);
            let r = g2.root_box();
            for _ in 0..3000 {
                let x = match rng.gen_range(0..4) {
                    0 => r.min[0] + rng.r#gen::<f64>() * (r.max[0] - r.min[0]),
                    1 => g2.deep_boundary(0, rng.r#gen::<u64>() as u128, 64),
                    2 => g2.deep_boundary(0, rng.gen_range(0..1u128 << 40), 40),
                    _ => r.max[0] - rng.gen_range(0..64) as f64 * r.max[0].abs() * f64::EPSILON,
                };
                for y in [x, x.next_up(), x.next_down(), r.min[0], r.max[0]] {
                    check(&g2, y);
                    check(&g3, y);
                }
            }
            for level in 0..=64u8 {
                let j = rng.gen_range(0..=1u128 << level);
                let b = g2.deep_boundary(1, j, level);
                if level <= 32 {
                    assert_eq!(b, g2.boundary(1, j as u64, level));
                }
                // the lines of a level are among the next level's
                if level < 64 {
                    assert_eq!(b, g2.deep_boundary(1, 2 * j, level + 1));
                }
                assert!(j == 0 || g2.deep_boundary(1, j - 1, level) <= b);
            }
        }
        // distinct f64s away from zero get distinct cells, and the binades near zero part
        let g = RootGeometry::<1>::new([0.0], 1.0);
        for k in 1..=53 {
            let x = 1.0 - (-(k as f64)).exp2();
            assert!(
                g.deep_coordinate(0, x) < g.deep_coordinate(0, x.next_up()),
                "{k}"
            );
        }
        for k in [40, 100, 300, 1000] {
            let x = (-(k as f64)).exp2();
            assert!(
                g.deep_coordinate(0, x / 2.0) < g.deep_coordinate(0, x),
                "{k}"
            );
        }
    }

    #[test]
    fn extreme_boxes_keep_deep_coordinates_exact() {
        let b = Aabb::around(&[[-f64::MAX, -1.0], [f64::MAX, 1.0]]);
        let g = RootGeometry::enclosing(&b);
        for x in [
            f64::MAX,
            -f64::MAX,
            0.0,
            -0.0,
            1.0,
            -1e300,
            f64::MIN_POSITIVE,
        ] {
            check(&g, x);
        }
        assert!(g.deep_cell_box(&DeepCell::finest([u64::MAX; 2])).max[0] >= f64::MAX);
    }
}
