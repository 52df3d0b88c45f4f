//! Statistical outlier removal (Rusu et al., "Towards 3D point cloud based object maps for
//! household environments", 2008; PCL's `StatisticalOutlierRemoval`, Open3D's
//! `remove_statistical_outlier`): a point's score is its mean distance to its `k` nearest
//! other points; a point is kept when its score is at most the cloud's mean score plus
//! `std_ratio` times their standard deviation (the sample deviation, `n - 1`, as Open3D).
//!
//! The neighbours come from the k-nearest self-join ([`Joins::map_k_nearest_self`]), one
//! dual-tree traversal for the whole cloud, each point's mean taken as its group is searched,
//! so no neighbour table is held. Unlike Open3D, a point is not its own neighbour (Open3D
//! counts it among its `k`, at distance 0), and a point whose neighbours all coincide with it
//! is kept (Open3D drops points whose mean is exactly 0).
//!
//! The verdict is the one exact arithmetic gives, up to rounding, for every cloud of finite
//! points, however far apart or close together. The join ranks by squared distances, which
//! overflow to infinity (and tie) for points more than about 1.3e154 apart and lose their bits
//! to underflow for points less than about 1e-154 apart; a point whose `k`-th squared distance
//! lies in either range is searched again ([`PointSet::k_nearest_by`]) under the squared
//! distance of its coordinates scaled by a power of two (exact) that brings its neighbours
//! into range, and its distances are then measured from the coordinates as `hypot` does (the
//! offsets scaled by a power of two before they are squared). The scores are kept as a
//! mantissa and a power of two until the largest is known, and the mean, the deviation and the
//! comparison are taken in units of a power of two of it ([`Outliers::scale`]), so that
//! nothing overflows: not even the distance `2 * f64::MAX` of points at `-f64::MAX` and
//! `f64::MAX`. On clouds whose squared distances all lie in range, the common case, the scores
//! are the square roots of the join's squared distances, with no second search.

use super::wide::{distance, exponent, scale_by, Wide};
use super::{Cloud, CloudError};
use crate::geom::{Aabb, Scalar};
use crate::points::PointTree;
use crate::query::{Joins, Metric, PointSet};
use std::sync::{Mutex, PoisonError};

/// The scores that `f64` cannot hold (beyond `f64::MAX` or below its normal range), by slot,
/// aside from the others until the scale is known: rare, so kept in a list that the serial and
/// parallel joins alike fill through a lock.
type Beyond = Mutex<Vec<(usize, Wide)>>;

/// The scores and the verdict of [`statistical`], per slot of the point set.
#[derive(Clone, Debug, PartialEq)]
pub struct Outliers {
    /// Each slot's mean distance to its `k` nearest other points (fewer when the set has at
    /// most `k` points; 0 for a set of one point), in units of `2^scale` ([`Outliers::scale`]).
    pub mean_distances: Vec<f64>,
    /// The threshold: mean of the scores plus `std_ratio` deviations, in the same units as the
    /// scores (never NaN: a cloud whose scores are all equal has the threshold of their mean,
    /// whatever the ratio).
    pub threshold: f64,
    /// The power of two the scores and the threshold are counted in: a score `s` is the mean
    /// distance `s * 2^scale`. 0 (plain distances) unless the largest score lies outside
    /// `[2^-500, 2^501)`; then the exponent of the largest score, which lies in `[1, 2)`.
    pub scale: i32,
    /// `true` for the slots kept (score at most the threshold).
    pub keep: Vec<bool>,
}

/// Scores every point of `set` by its mean distance (Euclidean) to its `k` nearest other
/// points and marks those above the mean score plus `std_ratio` deviations.
///
/// # Errors
/// [`CloudError::ZeroNeighbors`] for `k == 0`; [`CloudError::InvalidStdRatio`] for a NaN ratio.
///
/// # Complexity
/// That of [`Joins::k_nearest_self`], about O(n (log n + k)), and one k-nearest search for
/// each point whose squared distances leave `f64`'s range (see the module doc); memory: the
/// scores and verdicts (9 bytes per point), no neighbour table
/// ([`Joins::map_k_nearest_self`]).
///
/// ```
/// use orthtree::cloud::outliers;
/// use orthtree::{PointSet, PointTree};
/// let mut pts: Vec<([f64; 3], usize)> = (0..27).map(|i| ([(i % 3) as f64, (i / 3 % 3) as f64, (i / 9) as f64], i)).collect();
/// pts.push(([30.0, 30.0, 30.0], 27)); // far from the lattice
/// let tree = PointTree::new(&pts).unwrap();
/// let o = outliers::statistical(&tree, 4, 1.0).unwrap();
/// let dropped: Vec<usize> = (0..28).filter(|&s| !o.keep[s]).map(|s| tree.items()[s]).collect();
/// assert_eq!(dropped, [27]);
/// assert_eq!(o.scale, 0); // plain distances
/// // the same cloud 1e200 times larger: the same verdict, the scores in units of 2^scale
/// let far: Vec<([f64; 3], usize)> = pts.iter().map(|&(p, i)| (p.map(|x| x * 1e200), i)).collect();
/// let tree = PointTree::new(&far).unwrap();
/// let o = outliers::statistical(&tree, 4, 1.0).unwrap();
/// let dropped: Vec<usize> = (0..28).filter(|&s| !o.keep[s]).map(|s| tree.items()[s]).collect();
/// assert_eq!(dropped, [27]);
/// assert!(o.scale > 600);
/// ```
pub fn statistical<P: Joins<D>, const D: usize>(
    set: &P,
    k: usize,
    std_ratio: f64,
) -> Result<Outliers, CloudError> {
    check(k, std_ratio)?;
    let beyond = Mutex::new(Vec::new());
    let scores = set.map_k_nearest_self(k, |s, near, d2| score(set, k, s, near, d2, &beyond));
    Ok(verdict(scores, beyond, std_ratio))
}

/// [`statistical`] with the self-join on rayon's threads (feature `rayon`): the same scores
/// and verdicts.
///
/// # Errors
/// As [`statistical`].
///
/// # Complexity
/// That of [`statistical`], shared among the threads.
///
/// ```
/// use orthtree::cloud::outliers;
/// use orthtree::PointTree;
/// let pts: Vec<([f64; 3], usize)> = (0..1000).map(|i| ([(i % 10) as f64, (i / 10 % 10) as f64, (i / 100) as f64 * 1.5], i)).collect();
/// let tree = PointTree::new(&pts).unwrap();
/// assert_eq!(outliers::par_statistical(&tree, 6, 0.5), outliers::statistical(&tree, 6, 0.5));
/// ```
#[cfg(feature = "rayon")]
pub fn par_statistical<P: crate::query::ParallelJoins<D>, const D: usize>(
    set: &P,
    k: usize,
    std_ratio: f64,
) -> Result<Outliers, CloudError> {
    check(k, std_ratio)?;
    let beyond = Mutex::new(Vec::new());
    let scores = set.par_map_k_nearest_self(k, |s, near, d2| score(set, k, s, near, d2, &beyond));
    Ok(verdict(scores, beyond, std_ratio))
}

/// The parameter checks of [`statistical`].
fn check(k: usize, std_ratio: f64) -> Result<(), CloudError> {
    if k == 0 {
        return Err(CloudError::ZeroNeighbors);
    }
    if std_ratio.is_nan() {
        return Err(CloudError::InvalidStdRatio(std_ratio));
    }
    Ok(())
}

/// The smallest squared distance the join ranks and measures by as it is: from here up to
/// `f64::MAX`, a sum of squared offsets carries a relative error of a few roundings. Below,
/// the squares of the offsets round to multiples of `2^-1074` (or to 0), so that distances of
/// less than about 1e-154 lose their order and their value.
const IN_RANGE: f64 = f64::from_bits((1023 - 960) << 52); // 2^-960

/// `true` when the join's squared distance `d2` ranks and measures as it is.
#[inline(always)]
fn in_range(d2: f64) -> bool {
    (IN_RANGE..f64::INFINITY).contains(&d2)
}

/// The coordinates of slot `s` as `f64`.
#[inline]
fn coordinates<P: PointSet<D>, const D: usize>(set: &P, s: usize) -> [f64; D] {
    set.point(s).map(Scalar::to_f64)
}

/// The mean distance from `p` to the points of `near` (slots of `set`), measured from their
/// coordinates ([`distance`]).
fn mean_from_coordinates<P: PointSet<D>, const D: usize>(
    set: &P,
    p: &[f64; D],
    near: &[usize],
) -> Wide {
    let distances: Vec<Wide> = near
        .iter()
        .map(|&t| distance(p, &coordinates(set, t)))
        .collect();
    let Some(top) = distances.iter().filter_map(|d| d.exponent()).max() else {
        return Wide::ZERO;
    };
    // in units of 2^top: each term at most about 2 sqrt(D), the smallest underflowing only
    // when negligible beside the largest
    let sum: f64 = distances
        .iter()
        .filter(|d| d.m > 0.0)
        .map(|d| scale_by(d.m, d.e - top))
        .sum();
    Wide {
        m: sum / near.len() as f64,
        e: top,
    }
}

/// Slot `s`'s score: the mean of the square roots of its neighbours' squared distances (0
/// without neighbours) when all of them are in range or those of coinciding points; otherwise
/// measured from the coordinates ([`wide_score`]), and put in `beyond` (0 returned in its
/// place) when `f64` cannot hold it.
fn score<P: PointSet<D>, const D: usize>(
    set: &P,
    k: usize,
    s: usize,
    near: &[usize],
    d2: &[f64],
    beyond: &Beyond,
) -> f64 {
    if d2.iter().all(|&d| in_range(d)) {
        // (0 without neighbours: 0 / 1)
        return d2.iter().map(|d| d.sqrt()).sum::<f64>() / d2.len().max(1) as f64;
    }
    let score = wide_score(set, k, s, near, d2);
    score.plain().unwrap_or_else(|| {
        beyond
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .push((s, score));
        0.0
    })
}

/// Slot `s`'s score when a squared distance of its neighbours is out of range: the plain mean
/// when those are all of coinciding points (at 0 exactly), the mean of the distances measured
/// from the coordinates otherwise, after a second search when the join's ranking itself is in
/// doubt (its `k`-th squared distance out of range).
fn wide_score<P: PointSet<D>, const D: usize>(
    set: &P,
    k: usize,
    s: usize,
    near: &[usize],
    d2: &[f64],
) -> Wide {
    let p = coordinates(set, s);
    let same = |t: usize| coordinates(set, t) == p;
    if d2
        .iter()
        .zip(near)
        .all(|(&d, &t)| in_range(d) || (d == 0.0 && same(t)))
    {
        // coinciding points are at 0 exactly: the plain mean, as above
        return Wide {
            m: d2.iter().map(|d| d.sqrt()).sum::<f64>() / d2.len() as f64,
            e: 0,
        };
    }
    let last = d2.iter().fold(0.0f64, |m, &d| m.max(d));
    if in_range(last) {
        // every point nearer than the k-th is in, whatever its squared distance: only the
        // distances of the small ones need measuring again
        return mean_from_coordinates(set, &p, near);
    }
    let again = search_again(set, k, s, &p, near, last);
    mean_from_coordinates(set, &p, &again)
}

/// The `k` nearest other points of slot `s` (at `p`) under squared distances of scaled
/// coordinates that keep them in range, when the join's `k`-th squared distance `last` of its
/// neighbours `near` was out of range: infinite (the coordinates scaled down so that no
/// squared distance of finite points overflows) or below [`IN_RANGE`] (the offsets scaled up
/// to bring the farthest of `near` to about 1, again while the new `k`-th is still below).
fn search_again<P: PointSet<D>, const D: usize>(
    set: &P,
    k: usize,
    s: usize,
    p: &[f64; D],
    near: &[usize],
    last: f64,
) -> Vec<usize> {
    // scaled by 2^-(514 + c), coordinates below 2^1024 lie below 2^(510 - c), less than
    // 2^(511 - c) apart per axis, and D (at most 4^c) squares of that sum to less than 2^1022
    let c = (usize::BITS - (D.max(1) - 1).leading_zeros()).div_ceil(2) as i32;
    let farthest = |near: &[usize]| {
        near.iter()
            .filter_map(|&t| distance(p, &coordinates(set, t)).exponent())
            .max()
    };
    let mut shift = if last.is_infinite() {
        -(514 + c)
    } else {
        match farthest(near) {
            Some(e) => (-e).min(1023),
            None => return near.to_vec(),
        }
    };
    let mut best = near.to_vec();
    // a round whose k-th is still below range raises the scale by about 2^480 (that k-th is
    // so much nearer than the farthest of the round before), so the third round at most
    // reaches the cap of 2^1023, where distinct points are at least 2^-51 apart
    for _ in 0..4 {
        let metric = Scaled::new(shift);
        let Ok(found) = set.k_nearest_by(set.point(s), k + 1, f64::INFINITY, &metric) else {
            return best;
        };
        let mut pairs: Vec<(usize, f64)> = found.iter().map(|n| (n.index, n.distance)).collect();
        match pairs.iter().position(|&(t, _)| t == s) {
            Some(i) => {
                pairs.remove(i);
            }
            None => pairs.truncate(k),
        }
        best = pairs.iter().map(|&(t, _)| t).collect();
        let last = pairs.iter().fold(0.0f64, |m, &(_, d)| m.max(d));
        if in_range(last) || best.iter().all(|&t| coordinates(set, t) == *p) {
            return best;
        }
        match farthest(&best) {
            Some(e) if (-e).min(1023) > shift => shift = (-e).min(1023),
            _ => return best,
        }
    }
    best
}

/// The squared Euclidean distance of coordinates scaled by `2^shift`: each offset scaled after
/// the subtraction when `shift > 0` (the difference of two floats is exact when it is small,
/// and the far ones may overflow: they are not among the neighbours), the coordinates scaled
/// before it when `shift <= 0` (so that no offset overflows). Box bounds scale the nearest
/// point's offset the same way: rounding is monotone, so they never exceed a point's distance.
struct Scaled {
    factor: f64,
    before: bool,
}

impl Scaled {
    fn new(shift: i32) -> Self {
        Scaled {
            factor: scale_by(1.0, shift),
            before: shift <= 0,
        }
    }

    /// The scaled offset from `q` to the nearest point of `[lo, hi]` (0 inside).
    #[inline(always)]
    fn gap(&self, q: f64, lo: f64, hi: f64) -> f64 {
        let f = self.factor;
        let (q, lo, hi, after) = if self.before {
            (q * f, lo * f, hi * f, 1.0)
        } else {
            (q, lo, hi, f)
        };
        let gap = if q < lo {
            lo - q
        } else if q > hi {
            q - hi
        } else {
            0.0
        };
        gap * after
    }
}

impl<const D: usize> Metric<D> for Scaled {
    fn distance(&self, a: &[f64; D], b: &[f64; D]) -> f64 {
        (0..D).map(|i| self.gap(a[i], b[i], b[i]).powi(2)).sum()
    }
    fn box_distance(&self, q: &[f64; D], b: &Aabb<f64, D>) -> f64 {
        (0..D)
            .map(|i| self.gap(q[i], b.min[i], b.max[i]).powi(2))
            .sum()
    }
    fn scale_distance(&self, d: f64, factor: f64) -> f64 {
        d * (factor * factor)
    }
}

/// The threshold and verdicts of the scores (by slot, those of `beyond` in their place): taken
/// in units of `2^scale`, the deviations of the scores from their mean in units of a power of
/// two of the largest, so that neither the sum of the scores nor that of their squared
/// deviations overflows.
fn verdict(scores: Vec<f64>, beyond: Beyond, std_ratio: f64) -> Outliers {
    let beyond = beyond.into_inner().unwrap_or_else(PoisonError::into_inner);
    let top = scores
        .iter()
        .filter(|&&x| x > 0.0)
        .map(|&x| exponent(x))
        .chain(beyond.iter().filter_map(|(_, w)| w.exponent()))
        .max();
    let scale = match top {
        Some(t) if !(-500..=500).contains(&t) => t,
        _ => 0,
    };
    let mut mean_distances = scores;
    if scale != 0 {
        for x in &mut mean_distances {
            *x = scale_by(*x, -scale);
        }
    }
    for (s, w) in beyond {
        mean_distances[s] = scale_by(w.m, w.e - scale);
    }
    let n = mean_distances.len() as f64;
    let mean = mean_distances.iter().sum::<f64>() / n.max(1.0);
    // the largest score lies in [2^t, 2^(t + 1)) in these units: the deviations, at most
    // that, are scaled to below 2 (exactly: powers of two), their squares to below 4
    let t = top.map_or(0, |t| t - scale);
    let std = if mean_distances.len() > 1 {
        let var = mean_distances
            .iter()
            .map(|d| scale_by(d - mean, -t).powi(2))
            .sum::<f64>()
            / (n - 1.0);
        scale_by(var.sqrt(), t)
    } else {
        0.0
    };
    // `std_ratio * 0` is NaN for an infinite ratio: equal scores keep their mean
    let threshold = if std > 0.0 {
        mean + std_ratio * std
    } else {
        mean
    };
    let keep = mean_distances.iter().map(|&d| d <= threshold).collect();
    Outliers {
        mean_distances,
        threshold,
        scale,
        keep,
    }
}

/// The cloud without its statistical outliers ([`statistical`] on its world coordinates),
/// in the input order, and the indices of the points kept.
///
/// # Errors
/// As [`statistical`]; [`CloudError::ColumnLength`] and [`CloudError::Tree`] for a cloud whose
/// columns or coordinates are refused.
///
/// # Complexity
/// The tree's build and [`statistical`].
pub fn remove_statistical<S: Scalar>(
    cloud: &Cloud<S>,
    k: usize,
    std_ratio: f64,
) -> Result<(Cloud<S>, Vec<usize>), CloudError> {
    remove_by(cloud, |entries| {
        let tree = PointTree::new(entries)?;
        let verdict = statistical(&tree, k, std_ratio)?;
        Ok((tree, verdict))
    })
}

/// [`remove_statistical`] with the tree's build ([`PointTreeBuilder::par_build`]) and the
/// self-join on rayon's threads (feature `rayon`): the same cloud and indices.
///
/// # Errors
/// As [`remove_statistical`].
///
/// # Complexity
/// That of [`remove_statistical`], shared among the threads.
///
/// [`PointTreeBuilder::par_build`]: crate::points::PointTreeBuilder::par_build
#[cfg(feature = "rayon")]
pub fn par_remove_statistical<S: Scalar + Send + Sync>(
    cloud: &Cloud<S>,
    k: usize,
    std_ratio: f64,
) -> Result<(Cloud<S>, Vec<usize>), CloudError> {
    remove_by(cloud, |entries| {
        let tree = PointTree::builder().par_build(entries)?;
        let verdict = par_statistical(&tree, k, std_ratio)?;
        Ok((tree, verdict))
    })
}

/// The cloud of the points that `score` (a tree of the world coordinates, items the input
/// indices, and its verdicts) keeps, in the input order, and their indices.
fn remove_by<S: Scalar>(
    cloud: &Cloud<S>,
    score: impl FnOnce(&[([f64; 3], u32)]) -> Result<(PointTree<f64, u32, 3>, Outliers), CloudError>,
) -> Result<(Cloud<S>, Vec<usize>), CloudError> {
    cloud.attributes.check(cloud.len())?;
    let world = Cloud::from_points(cloud.world_points());
    let (tree, verdict) = score(&world.entries()?)?;
    let mut kept: Vec<usize> = (0..tree.len())
        .filter(|&s| verdict.keep[s])
        .map(|s| tree.items()[s] as usize)
        .collect();
    kept.sort_unstable();
    Ok((cloud.select(&kept), kept))
}
