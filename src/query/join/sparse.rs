//! The sparse distance matrix between two sets: every pair within a radius with its distance,
//! in coordinate (COO) form, sorted by row then column, and its compressed sparse row (CSR)
//! form, as scipy's `cKDTree.sparse_distance_matrix` and `scipy.sparse` give them.

/// The pairs within a radius of the points of set `a` (rows, by slot) and of set `b` (columns,
/// by slot), with their squared Euclidean distances, in coordinate form sorted by row then
/// column (see [`Joins::sparse_distance_matrix`](super::Joins::sparse_distance_matrix)).
///
/// ```
/// use orthtree::prelude::*;
/// use orthtree::{query::Boundary, Quadtree};
/// let a = Quadtree::new(&[([0.0, 0.0], 'a'), ([5.0, 0.0], 'b')]).unwrap();
/// let b = Quadtree::new(&[([1.0, 0.0], 'x'), ([9.0, 0.0], 'y'), ([4.0, 0.0], 'z')]).unwrap();
/// let m = a.sparse_distance_matrix(&b, 1.0, Boundary::Inclusive).unwrap();
/// assert_eq!((m.rows(), m.cols(), m.len()), (2, 3, 2));
/// let named: Vec<(char, char, f64)> =
///     m.iter().map(|(r, c, d)| (a.items()[r], b.items()[c], d)).collect();
/// assert!(named.contains(&('a', 'x', 1.0)) && named.contains(&('b', 'z', 1.0)));
/// let csr = m.to_csr();
/// assert_eq!((csr.indptr(), csr.data()), (&[0, 1, 2][..], &[1.0, 1.0][..]));
/// assert_eq!(csr.indices(), m.col_indices());
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SparseDistances {
    shape: (usize, usize),
    row: Vec<usize>,
    col: Vec<usize>,
    distance: Vec<f64>,
}

impl SparseDistances {
    /// The matrix of `triples` (row, column, distance), sorted here.
    pub(crate) fn new(shape: (usize, usize), mut triples: Vec<(usize, usize, f64)>) -> Self {
        triples.sort_unstable_by_key(|&(r, c, _)| (r, c));
        let ((row, col), distance) = triples.into_iter().map(|(r, c, d)| ((r, c), d)).unzip();
        SparseDistances {
            shape,
            row,
            col,
            distance,
        }
    }
    /// The number of rows: the points of the first set.
    pub fn rows(&self) -> usize {
        self.shape.0
    }
    /// The number of columns: the points of the second set.
    pub fn cols(&self) -> usize {
        self.shape.1
    }
    /// The number of pairs stored.
    pub fn len(&self) -> usize {
        self.row.len()
    }
    /// `true` when no pair is within the radius.
    pub fn is_empty(&self) -> bool {
        self.row.is_empty()
    }
    /// Each pair's row: its slot in the first set.
    pub fn row_indices(&self) -> &[usize] {
        &self.row
    }
    /// Each pair's column: its slot in the second set.
    pub fn col_indices(&self) -> &[usize] {
        &self.col
    }
    /// Each pair's squared distance.
    pub fn distances(&self) -> &[f64] {
        &self.distance
    }
    /// Every pair as (row, column, squared distance), sorted by row then column.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = (usize, usize, f64)> + '_ {
        (0..self.len()).map(|i| (self.row[i], self.col[i], self.distance[i]))
    }
    /// The same matrix in compressed sparse row form.
    ///
    /// # Complexity
    /// `O(rows + pairs)`.
    pub fn to_csr(&self) -> CsrDistances {
        let mut indptr = vec![0; self.shape.0 + 1];
        for &r in &self.row {
            indptr[r + 1] += 1;
        }
        for r in 0..self.shape.0 {
            indptr[r + 1] += indptr[r];
        }
        CsrDistances {
            shape: self.shape,
            indptr,
            indices: self.col.clone(),
            data: self.distance.clone(),
        }
    }
}

/// A sparse distance matrix in compressed sparse row form: row `r`'s pairs are
/// `indptr[r]..indptr[r + 1]` of `indices` (columns, ascending) and `data` (squared distances).
/// Made by [`SparseDistances::to_csr`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CsrDistances {
    shape: (usize, usize),
    indptr: Vec<usize>,
    indices: Vec<usize>,
    data: Vec<f64>,
}

impl CsrDistances {
    /// (rows, columns).
    pub fn shape(&self) -> (usize, usize) {
        self.shape
    }
    /// Where each row starts in [`CsrDistances::indices`] and [`CsrDistances::data`], and the
    /// end (`rows + 1` entries).
    pub fn indptr(&self) -> &[usize] {
        &self.indptr
    }
    /// The columns of the pairs, row after row, ascending within a row.
    pub fn indices(&self) -> &[usize] {
        &self.indices
    }
    /// The squared distances of the pairs, in the order of [`CsrDistances::indices`].
    pub fn data(&self) -> &[f64] {
        &self.data
    }
    /// The columns and squared distances of row `r`.
    ///
    /// # Panics
    /// When `r >= rows`.
    pub fn row(&self, r: usize) -> (&[usize], &[f64]) {
        let at = self.indptr[r]..self.indptr[r + 1];
        (&self.indices[at.clone()], &self.data[at])
    }
}
