//! Surface normals by principal component analysis (Hoppe et al., "Surface reconstruction from
//! unorganized points", SIGGRAPH 1992): the normal at a point is the eigenvector of the
//! smallest eigenvalue of the covariance of the point and its `k` nearest neighbours (from
//! the k-nearest self-join). The 3x3 symmetric eigenproblem is solved by the cyclic Jacobi
//! method (Golub and Van Loan, *Matrix Computations*, section 8.5).
//!
//! Normals are oriented toward +z (toward +y when horizontal, then +x), the usual choice for
//! airborne scans; a neighbourhood on a line or a point has no unique normal, and gets one of
//! the eigenvectors of its smallest eigenvalue.

use super::{Cloud, CloudError};
use crate::geom::Scalar;
use crate::points::PointTree;
use crate::query::{Joins, PointSet};
use smallvec::SmallVec;

/// The eigenvalues of the symmetric matrix `a` in ascending order, with unit eigenvectors
/// (`vectors[i]` belongs to `values[i]`), by cyclic Jacobi rotations until the off-diagonal
/// part is below `1e-15` of the matrix's norm (at most 32 sweeps; 3x3 matrices take 4-6).
///
/// # Complexity
/// O(1).
///
/// ```
/// use orthtree::cloud::normals::symmetric_eigen;
/// let (values, vectors) = symmetric_eigen([[2.0, 1.0, 0.0], [1.0, 2.0, 0.0], [0.0, 0.0, 5.0]]);
/// assert!((values[0] - 1.0).abs() < 1e-12 && (values[1] - 3.0).abs() < 1e-12);
/// assert!((vectors[0][0] + vectors[0][1]).abs() < 1e-12); // (1, -1, 0) / sqrt 2
/// assert!((vectors[2][2].abs() - 1.0).abs() < 1e-12);
/// ```
pub fn symmetric_eigen(mut a: [[f64; 3]; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let norm: f64 = a.iter().flatten().map(|x| x * x).sum::<f64>().sqrt();
    for _ in 0..32 {
        let off = (a[0][1].powi(2) + a[0][2].powi(2) + a[1][2].powi(2)).sqrt();
        if off <= 1e-15 * norm || off == 0.0 {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            // The rotation that zeroes a[p][q] (Golub and Van Loan, algorithm 8.5.1).
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            // Columns p and q of `a` and of `v` turn alike; then rows p and q of `a`.
            for row in a.iter_mut().chain(v.iter_mut()) {
                let (x, y) = (row[p], row[q]);
                row[p] = c * x - s * y;
                row[q] = s * x + c * y;
            }
            let (row_p, row_q) = (a[p], a[q]);
            a[p] = core::array::from_fn(|j| c * row_p[j] - s * row_q[j]);
            a[q] = core::array::from_fn(|j| s * row_p[j] + c * row_q[j]);
        }
    }
    let mut order = [0usize, 1, 2];
    order.sort_by(|&i, &j| a[i][i].total_cmp(&a[j][j]));
    let values = order.map(|i| a[i][i]);
    let vectors = order.map(|i| [v[0][i], v[1][i], v[2][i]]);
    (values, vectors)
}

/// The unit normal of the points `neighbourhood` by PCA, oriented toward +z (then +y, +x).
/// `None` for an empty slice.
///
/// # Complexity
/// O(m) for m points.
pub fn pca_normal(neighbourhood: &[[f64; 3]]) -> Option<[f64; 3]> {
    if neighbourhood.is_empty() {
        return None;
    }
    let m = neighbourhood.len() as f64;
    let c: [f64; 3] = core::array::from_fn(|a| neighbourhood.iter().map(|p| p[a]).sum::<f64>() / m);
    let mut cov = [[0.0f64; 3]; 3];
    for p in neighbourhood {
        let d = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
        for i in 0..3 {
            for j in 0..3 {
                cov[i][j] += d[i] * d[j];
            }
        }
    }
    let (_, vectors) = symmetric_eigen(cov);
    let mut n = vectors[0];
    let flip = match (n[2], n[1]) {
        (z, _) if z != 0.0 => z < 0.0,
        (_, y) if y != 0.0 => y < 0.0,
        _ => n[0] < 0.0,
    };
    if flip {
        n = n.map(|x| -x);
    }
    Some(n)
}

/// The normal of every slot of `set` from the slot's point and its `k` nearest other points.
///
/// # Errors
/// [`CloudError::ZeroNeighbors`] for `k == 0`.
///
/// # Complexity
/// [`Joins::k_nearest_self`], then O(k) per point; memory: the normals, no neighbour table
/// ([`Joins::map_k_nearest_self`]).
pub fn normals<P: Joins<3>>(set: &P, k: usize) -> Result<Vec<[f64; 3]>, CloudError> {
    if k == 0 {
        return Err(CloudError::ZeroNeighbors);
    }
    Ok(set.map_k_nearest_self(k, |s, others, _| normal_of(set, s, others)))
}

/// [`normals`] with the self-join on rayon's threads (feature `rayon`): the same normals.
///
/// # Errors
/// As [`normals`].
///
/// # Complexity
/// That of [`normals`], shared among the threads.
///
/// ```
/// use orthtree::cloud::normals;
/// use orthtree::PointTree;
/// let pts: Vec<([f64; 3], usize)> = (0..400).map(|i| ([(i % 20) as f64, (i / 20) as f64, (i % 7) as f64 * 0.1], i)).collect();
/// let tree = PointTree::new(&pts).unwrap();
/// assert_eq!(normals::par_normals(&tree, 8), normals::normals(&tree, 8));
/// ```
#[cfg(feature = "rayon")]
pub fn par_normals<P: crate::query::ParallelJoins<3>>(
    set: &P,
    k: usize,
) -> Result<Vec<[f64; 3]>, CloudError> {
    if k == 0 {
        return Err(CloudError::ZeroNeighbors);
    }
    Ok(set.par_map_k_nearest_self(k, |s, others, _| normal_of(set, s, others)))
}

/// The normal of slot `s` of `set` from its point and those of the slots `others`, gathered
/// on the stack for up to 31 neighbours (no allocation per point).
fn normal_of<P: Joins<3>>(set: &P, s: usize, others: &[usize]) -> [f64; 3] {
    let hood: SmallVec<[[f64; 3]; 32]> = core::iter::once(s)
        .chain(others.iter().copied())
        .map(|t| set.point(t).map(Scalar::to_f64))
        .collect();
    pca_normal(&hood).expect("the neighbourhood holds the point")
}

/// Sets the cloud's normal column from its `k` nearest neighbours in world coordinates.
///
/// # Errors
/// As [`normals`]; [`CloudError::Tree`] for coordinates the tree refuses.
///
/// # Complexity
/// The tree's build and [`normals`].
///
/// ```
/// use orthtree::cloud::{normals, Cloud};
/// // a tilted plane z = x: normals (-1, 0, 1) / sqrt 2
/// let pts = (0..100).map(|i| [(i % 10) as f64, (i / 10) as f64, (i % 10) as f64]).collect();
/// let mut cloud = Cloud::from_points(pts);
/// normals::estimate(&mut cloud, 8).unwrap();
/// let n = cloud.attributes.normal.unwrap()[55];
/// assert!((n[0] + 0.70710677).abs() < 1e-5 && n[1].abs() < 1e-5 && (n[2] - 0.70710677).abs() < 1e-5);
/// ```
pub fn estimate<S: Scalar>(cloud: &mut Cloud<S>, k: usize) -> Result<(), CloudError> {
    let tree = PointTree::builder().build_indexed(&cloud.world_points())?;
    let by_slot = normals(&tree, k)?;
    let mut out = vec![[0f32; 3]; cloud.len()];
    for (s, n) in by_slot.iter().enumerate() {
        out[tree.items()[s] as usize] = n.map(|x| x as f32);
    }
    cloud.attributes.normal = Some(out);
    Ok(())
}
