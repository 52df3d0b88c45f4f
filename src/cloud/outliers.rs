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

use super::{Cloud, CloudError};
use crate::geom::Scalar;
use crate::points::PointTree;
use crate::query::{Joins, PointSet};

/// The scores and the verdict of [`statistical`], per slot of the point set.
#[derive(Clone, Debug, PartialEq)]
pub struct Outliers {
    /// Each slot's mean distance to its `k` nearest other points (fewer when the set has at
    /// most `k` points; 0 for a set of one point).
    pub mean_distances: Vec<f64>,
    /// The threshold: mean of the scores plus `std_ratio` deviations.
    pub threshold: f64,
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
/// That of [`Joins::k_nearest_self`], about O(n (log n + k)); memory: the scores and
/// verdicts (9 bytes per point), no neighbour table ([`Joins::map_k_nearest_self`]).
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
/// ```
pub fn statistical<P: Joins<D>, const D: usize>(
    set: &P,
    k: usize,
    std_ratio: f64,
) -> Result<Outliers, CloudError> {
    check(k, std_ratio)?;
    Ok(verdict(set.map_k_nearest_self(k, mean_distance), std_ratio))
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
    Ok(verdict(
        set.par_map_k_nearest_self(k, mean_distance),
        std_ratio,
    ))
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

/// A point's score: the mean of the square roots of its neighbours' squared distances (0
/// without neighbours).
fn mean_distance(_: usize, _: &[usize], d2: &[f64]) -> f64 {
    if d2.is_empty() {
        0.0
    } else {
        d2.iter().map(|d| d.sqrt()).sum::<f64>() / d2.len() as f64
    }
}

/// The threshold and verdicts of the scores `mean_distances`.
fn verdict(mean_distances: Vec<f64>, std_ratio: f64) -> Outliers {
    let n = mean_distances.len() as f64;
    let mean = mean_distances.iter().sum::<f64>() / n.max(1.0);
    let var = if mean_distances.len() > 1 {
        mean_distances
            .iter()
            .map(|d| (d - mean).powi(2))
            .sum::<f64>()
            / (n - 1.0)
    } else {
        0.0
    };
    let threshold = mean + std_ratio * var.sqrt();
    let keep = mean_distances.iter().map(|&d| d <= threshold).collect();
    Outliers {
        mean_distances,
        threshold,
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
