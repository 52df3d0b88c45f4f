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
    if k == 0 {
        return Err(CloudError::ZeroNeighbors);
    }
    if std_ratio.is_nan() {
        return Err(CloudError::InvalidStdRatio(std_ratio));
    }
    let mean_distances = set.map_k_nearest_self(k, |_, _, d2| {
        if d2.is_empty() {
            0.0
        } else {
            d2.iter().map(|d| d.sqrt()).sum::<f64>() / d2.len() as f64
        }
    });
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
    Ok(Outliers {
        mean_distances,
        threshold,
        keep,
    })
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
    cloud.attributes.check(cloud.len())?;
    let world = Cloud::from_points(cloud.world_points());
    let tree = PointTree::new(&world.entries()?)?;
    let verdict = statistical(&tree, k, std_ratio)?;
    let mut kept: Vec<usize> = (0..tree.len())
        .filter(|&s| verdict.keep[s])
        .map(|s| tree.items()[s] as usize)
        .collect();
    kept.sort_unstable();
    Ok((cloud.select(&kept), kept))
}
