//! Which children of a box split at its middle a search can leave out together: those in a half
//! of the box (either side of a split line) that holds no point the search wants. A search
//! states its test once ([`Halves`]); an index asks it for the children it may leave out
//! without bounding them one by one (`SpatialIndex::for_each_child_unless`).
//!
//! Any `Fn(&Aabb) -> bool` is such a test, asked of the 2 D half boxes. A test that is a sum
//! over the axes of a term of the box's interval on that axis (a ball's or the Euclidean
//! metric's nearest squared distance) can do the same with a term per half and axis
//! (`halves_by_terms`): a half box differs from the box on one axis only, so its sum is the
//! box's with one term changed. The sums are still taken term by term in axis order, so each
//! answers exactly as the test of the half box would.

use super::Aabb;

/// The children of a box `bbox` split at `mid` that no half of it rules out, as `(mask, want)`:
/// child `i` (bit `a` set: the upper half along axis `a`) is kept when `i & mask == want`;
/// `None` when both halves along some axis are out, so every child is.
pub type Kept = Option<(usize, usize)>;

/// A search's test of the halves of a box: which children of `bbox` split at `mid` it keeps.
///
/// Implemented by every `Fn(&Aabb<f64, D>) -> bool` that says whether a box holds no wanted
/// point (asked of the 2 D half boxes), and by the query engines' own tests, which answer the
/// same with fewer operations.
///
/// ```
/// use orthtree::geom::Halves;
/// use orthtree::Aabb;
/// let b = Aabb::new([0.0, 0.0], [2.0, 2.0]).unwrap();
/// // nothing wanted left of x = 1: the children of the upper half along x (bit 0 set)
/// let out = |h: &Aabb<f64, 2>| h.max[0] <= 1.0;
/// assert_eq!(out.kept(&b, &[1.0, 1.0]), Some((0b01, 0b01)));
/// ```
pub trait Halves<const D: usize> {
    /// The children of `bbox` split at `mid` outside every half this test rules out.
    fn kept(&self, bbox: &Aabb<f64, D>, mid: &[f64; D]) -> Kept;
}

impl<F: Fn(&Aabb<f64, D>) -> bool, const D: usize> Halves<D> for F {
    #[inline(always)]
    fn kept(&self, bbox: &Aabb<f64, D>, mid: &[f64; D]) -> Kept {
        let mut out = [(false, false); D];
        for (a, &m) in mid.iter().enumerate() {
            let (mut lower, mut upper) = (*bbox, *bbox);
            lower.max[a] = m;
            upper.min[a] = m;
            out[a] = (self(&lower), self(&upper));
        }
        kept_of(&out)
    }
}

/// [`Kept`] from whether the lower and upper half along each axis is out: every child when
/// both halves along an axis are, else those in no half that is (the upper along an axis whose
/// lower half is out, the lower along one whose upper half is). Bit operations only: which
/// halves a search rules out follows the query's place, so a branch per axis is mispredicted
/// often.
#[inline(always)]
fn kept_of<const D: usize>(out: &[(bool, bool); D]) -> Kept {
    let (mut lower, mut upper) = (0usize, 0usize);
    for (a, &(lo, up)) in out.iter().enumerate() {
        lower |= usize::from(lo) << a;
        upper |= usize::from(up) << a;
    }
    (lower & upper == 0).then_some((lower | upper, lower))
}

/// [`Halves::kept`] for a test "the sum over the axes `a`, in order from 0, of
/// `term(a, min_a, max_a)` exceeds `bound`": 3 D terms (the box's, each lower half's and each
/// upper half's) instead of the 2 D^2 of asking each half box, and one sum per half. Each sum
/// adds the same terms in the same order as the test of that half box would, so each answer is
/// the same.
#[inline(always)]
pub(crate) fn halves_by_terms<const D: usize>(
    bbox: &Aabb<f64, D>,
    mid: &[f64; D],
    term: impl Fn(usize, f64, f64) -> f64,
    bound: f64,
) -> Kept {
    let whole: [f64; D] = core::array::from_fn(|a| term(a, bbox.min[a], bbox.max[a]));
    let sum = |a: usize, t: f64| {
        let mut s = 0.0;
        for (b, &w) in whole.iter().enumerate() {
            s += if b == a { t } else { w };
        }
        s
    };
    // Every half's sum taken, even where its term equals the box's (the sum is then the
    // box's): a branch on it costs more in mispredictions than the few additions it saves.
    let half_out = |a: usize, t: f64| sum(a, t) > bound;
    let out: [(bool, bool); D] = core::array::from_fn(|a| {
        (
            half_out(a, term(a, bbox.min[a], mid[a])),
            half_out(a, term(a, mid[a], bbox.max[a])),
        )
    });
    kept_of(&out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The term-wise answer equals the half boxes' on boxes and bounds where sums tie.
    #[test]
    fn terms_answer_as_the_half_boxes_do() {
        let q = [0.25, 3.0, -1.0];
        let gap = |a: usize, lo: f64, hi: f64| {
            let d = if q[a] < lo {
                lo - q[a]
            } else if q[a] > hi {
                q[a] - hi
            } else {
                0.0
            };
            d * d
        };
        for bound in [0.0, 0.0625, 1.0, 1.5625, 4.0, 9.0, 100.0] {
            for lo in [-2.0, 0.0, 0.5] {
                for side in [0.5, 1.0, 4.0] {
                    let b = Aabb::new([lo; 3], [lo + side; 3]).unwrap();
                    let mid = [lo + side / 2.0; 3];
                    let by_boxes = |h: &Aabb<f64, 3>| {
                        (0..3)
                            .map(|a| gap(a, h.min[a], h.max[a]))
                            .fold(0.0, |s, t| s + t)
                            > bound
                    };
                    assert_eq!(
                        halves_by_terms(&b, &mid, gap, bound),
                        by_boxes.kept(&b, &mid),
                        "{b:?} bound {bound}"
                    );
                }
            }
        }
    }
}
