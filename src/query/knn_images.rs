//! The image search of the k-nearest engines on a periodic domain: the k nearest points under
//! a minimum-image metric ([`MinImage`](super::MinImage)) found by ordinary searches from the
//! query's images, as particle codes do with periodic images of a cell list (Allen and
//! Tildesley, *Computer Simulation of Liquids*, section 5.3), instead of bounding every box by
//! its nearest image.
//!
//! The query is wrapped into the period box (its home image) and searched as in ordinary space
//! ([`seeded`]: the walk down to the node around it, the backtracking that stops once the
//! bound's ball lies inside the box walked through), every point measured by the minimum-image
//! distance itself. Then each other image, the home one shifted by `-1` or `+1` period along
//! some wrapping axes, whose distance to the root box is within the `k`-th distance found so
//! far, is searched from the root ([`descend`]) into the same candidate list, nearest image
//! first. Most queries lie farther than their `k`-th distance from every face and search the
//! home image only.
//!
//! Exactness: a point's minimum-image distance is realised, axis by axis, by one image of the
//! query within half a period of it; that image is among those searched (the root box holds
//! the point), and every box on the way to the point is bounded from that image by its
//! unwrapped offsets lowered by a margin of a few roundings of the coordinates involved
//! ([`Metric::unwrapped_box_distance`]), never above the point's computed distance. So every
//! point within the final `k`-th distance is offered, with the one distance the metric gives it
//! (the same from every image): a point offered again is the same candidate and is kept once,
//! and ties are broken by index as in the ordinary search. When the root box reaches beyond
//! one period on either side of the home image (tree points far outside the period box), the
//! engines fall back to bounding boxes by their nearest image.

// Loops over axes index the point, the box's min and max together; an index reads best.
#![allow(clippy::needless_range_loop)]

use super::index::SpatialIndex;
use super::knn::{descend, seeded, Best};
use super::metric::{axis_gap, Metric};
use super::periodic::Torus;
use crate::geom::Aabb;
use smallvec::SmallVec;

/// The images of one query worth searching.
pub(super) struct Images<const D: usize> {
    /// The query wrapped into the period box along the wrapping axes.
    home: [f64; D],
    /// Per axis, the rounding margin of the unwrapped bounds (0 on ordinary axes).
    margin: [f64; D],
    /// Per axis, the period (0 on ordinary axes).
    period: [f64; D],
    /// Per axis, the shifts of the home image that can be a point's nearest: bit 0 for one
    /// period down, bit 1 for one period up.
    shifts: [u8; D],
    /// An unwrapped distance from the query below which no offset along a wrapping axis
    /// exceeds half its period: the distance of half a period along one wrapping axis, the
    /// least over them (infinity without a wrapping axis); minus infinity when the query is not
    /// its home image (it lies outside the period box).
    below: f64,
}

impl<const D: usize> Images<D> {
    /// The images of query `q` on `torus` over an index whose root box is `root`; `None` when
    /// a point of the root box may have its nearest image more than one period from the home
    /// one (or the margins overflow): the caller then bounds boxes by their nearest image.
    pub(super) fn new<M: Metric<D>>(
        torus: &Torus<D>,
        metric: &M,
        q: &[f64; D],
        root: &Aabb<f64, D>,
    ) -> Option<Self> {
        let mut images = Images {
            home: *q,
            margin: [0.0; D],
            period: [0.0; D],
            shifts: [0; D],
            below: f64::INFINITY,
        };
        for a in (0..D).filter(|&a| torus.wraps()[a]) {
            let l = torus.period(a);
            let h = torus.wrap_axis(a, q[a]);
            let (rlo, rhi) = (root.min[a], root.max[a]);
            let m = 16.0
                * f64::EPSILON
                * (q[a].abs()
                    + torus.lo()[a].abs()
                    + torus.hi()[a].abs()
                    + l
                    + rlo.abs().max(rhi.abs()));
            if !m.is_finite() {
                return None;
            }
            // A point's nearest image lies within half a period of it (and the margin).
            let reach = |n: f64| axis_gap(h + n * l, rlo, rhi) - m <= l / 2.0;
            if reach(-2.0) || reach(2.0) || !(reach(-1.0) || reach(0.0) || reach(1.0)) {
                return None;
            }
            images.home[a] = h;
            images.margin[a] = m;
            images.period[a] = l;
            images.shifts[a] = u8::from(reach(-1.0)) | u8::from(reach(1.0)) << 1;
            let mut half = [0.0; D];
            half[a] = l / 2.0;
            let at_half = metric.unwrapped_distance(&[0.0; D], &half);
            images.below = if h == q[a] {
                images.below.min(at_half)
            } else {
                f64::NEG_INFINITY
            };
        }
        Some(images)
    }

    /// The `k` nearest points to `q` under `metric` (whose torus made `self`) into `best`:
    /// the home image, then the other images within the bound, nearest first.
    #[inline(never)]
    pub(super) fn search<I: SpatialIndex<D>, M: Metric<D>>(
        &self,
        index: &I,
        q: &[f64; D],
        metric: &M,
        best: &mut Best,
        (root, b): (I::Node, Aabb<f64, D>),
        cut: &impl Fn(f64) -> f64,
    ) {
        let bounds = Unwrapped {
            metric,
            margin: &self.margin,
        };
        let home = Home {
            metric,
            below: self.below,
        };
        let from_home = ((q, &home), (&self.home, &bounds));
        seeded(index, from_home, best, (root, b), cut);
        if self.shifts == [0; D] {
            return;
        }
        // Per axis, the shifts whose image is within the bound on that axis alone.
        let prune = best.prune(cut);
        let mut options = [[0.0f64; 3]; D];
        let mut counts = [1usize; D];
        let mut any = false;
        for a in 0..D {
            for (bit, n) in [(1u8, -1.0), (2u8, 1.0)] {
                if self.shifts[a] & bit == 0 {
                    continue;
                }
                let x = self.home[a] + n * self.period[a];
                let mut slab = Aabb {
                    min: [f64::NEG_INFINITY; D],
                    max: [f64::INFINITY; D],
                };
                (slab.min[a], slab.max[a]) = (b.min[a], b.max[a]);
                let mut at = self.home;
                at[a] = x;
                if metric.unwrapped_box_distance(&at, &slab, &self.margin) <= prune {
                    options[a][counts[a]] = x;
                    counts[a] += 1;
                    any = true;
                }
            }
            options[a][0] = self.home[a];
        }
        if !any {
            return;
        }
        // Every combination of the axes' options but the home image, with its bound.
        let mut found: SmallVec<[(f64, [f64; D]); 8]> = SmallVec::new();
        let mut pick = [0usize; D];
        loop {
            // The next combination, as an odometer over the axes.
            let mut a = 0;
            while a < D && pick[a] + 1 == counts[a] {
                pick[a] = 0;
                a += 1;
            }
            if a == D {
                break;
            }
            pick[a] += 1;
            let image: [f64; D] = core::array::from_fn(|i| options[i][pick[i]]);
            let lower = metric.unwrapped_box_distance(&image, &b, &self.margin);
            if lower <= prune {
                found.push((lower, image));
            }
        }
        found.sort_by(|x, y| x.0.total_cmp(&y.0));
        for (lower, image) in &found {
            if *lower <= best.prune(cut) {
                descend(index, ((q, metric), (image, &bounds)), best, (root, b), cut);
            }
        }
    }
}

/// The distance of points from the home image: the unwrapped distance where it is below
/// `below` (then no wrapping offset exceeds half a period, so it is the minimum-image distance,
/// bit for bit, the query being its home image), the minimum-image distance elsewhere.
struct Home<'a, M> {
    metric: &'a M,
    below: f64,
}

impl<M: Metric<D>, const D: usize> Metric<D> for Home<'_, M> {
    #[inline(always)]
    fn distance(&self, a: &[f64; D], b: &[f64; D]) -> f64 {
        let u = self.metric.unwrapped_distance(a, b);
        if u < self.below {
            u
        } else {
            self.metric.distance(a, b)
        }
    }
    #[inline(always)]
    fn box_distance(&self, q: &[f64; D], b: &Aabb<f64, D>) -> f64 {
        self.metric.box_distance(q, b)
    }
}

/// The bound of boxes seen from one image of the query: [`Metric::unwrapped_box_distance`] with
/// the query's margins.
struct Unwrapped<'a, M, const D: usize> {
    metric: &'a M,
    margin: &'a [f64; D],
}

impl<M: Metric<D>, const D: usize> Metric<D> for Unwrapped<'_, M, D> {
    #[inline(always)]
    fn distance(&self, a: &[f64; D], b: &[f64; D]) -> f64 {
        self.box_distance(a, &Aabb { min: *b, max: *b })
    }
    #[inline(always)]
    fn box_distance(&self, q: &[f64; D], b: &Aabb<f64, D>) -> f64 {
        self.metric.unwrapped_box_distance(q, b, self.margin)
    }
    #[inline(always)]
    fn scale_distance(&self, d: f64, factor: f64) -> f64 {
        self.metric.scale_distance(d, factor)
    }
}
