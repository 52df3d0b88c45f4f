//! The joins on rayon's threads (feature `rayon`): the same answers as [`Joins`]' serial forms,
//! the work split into independent parts. The k-nearest joins hand the querying tree's groups
//! (see [`knn`](super::knn)) to the threads; the sparse distance matrix and the counts split the
//! top of the dual-tree traversal into independent node pairs ([`split_top`]) and traverse each
//! on a thread (the counts of the parts are summed). Results are put in the serial forms' order,
//! so they are equal to them.

use super::bounds::Euclid;
use super::knn::{group_knn, groups, table, width, write_rows, KnnTable};
use super::pairs::{CountWithin, PairsWithin};
use super::radius::{squared_radii, squared_radius, Boundary};
use super::scan::Block;
use super::sparse::SparseDistances;
use super::traverse::{roots, run, split_top};
use super::Joins;
use crate::query::{PointSet, QueryError};
use core::convert::Infallible;
use core::ops::ControlFlow;
use rayon::prelude::*;

/// Node pairs per thread that the top of a parallel traversal is split into: enough for the
/// threads to even out the uneven parts.
const PAIRS_PER_THREAD: usize = 16;

/// The parallel forms of [`Joins`], for every point set that can be shared between threads
/// (implemented for all of them; in the prelude under the `rayon` feature).
pub trait ParallelJoins<const D: usize>: Joins<D> + Sync {
    /// [`Joins::k_nearest_join`] on rayon's threads; the same table.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let pts: Vec<([f64; 2], ())> = (0..500).map(|i| ([(i % 25) as f64, (i / 25) as f64], ())).collect();
    /// let (a, b) = (Quadtree::new(&pts[..200]).unwrap(), Quadtree::new(&pts[100..]).unwrap());
    /// assert_eq!(a.par_k_nearest_join(&b, 3), a.k_nearest_join(&b, 3));
    /// ```
    fn par_k_nearest_join<B: PointSet<D> + Sync>(&self, other: &B, k: usize) -> KnnTable
    where
        Self: Sized,
    {
        par_knn(self, other, k, false)
    }

    /// [`Joins::k_nearest_self`] on rayon's threads; the same table.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let pts: Vec<([f64; 2], ())> = (0..500).map(|i| ([(i % 25) as f64, (i / 25) as f64], ())).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// assert_eq!(t.par_k_nearest_self(4), t.k_nearest_self(4));
    /// ```
    fn par_k_nearest_self(&self, k: usize) -> KnnTable
    where
        Self: Sized,
    {
        par_knn(self, self, k, true)
    }

    /// [`Joins::sparse_distance_matrix`] on rayon's threads; the same matrix.
    ///
    /// # Errors
    /// A negative or NaN `r` ([`QueryError::InvalidRadius`]).
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Boundary, Quadtree};
    /// let pts: Vec<([f64; 2], ())> = (0..500).map(|i| ([(i % 25) as f64, (i / 25) as f64], ())).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// let m = t.par_sparse_distance_matrix(&t, 1.5, Boundary::Inclusive).unwrap();
    /// assert_eq!(m, t.sparse_distance_matrix(&t, 1.5, Boundary::Inclusive).unwrap());
    /// ```
    fn par_sparse_distance_matrix<B: PointSet<D> + Sync>(
        &self,
        other: &B,
        r: f64,
        boundary: Boundary,
    ) -> Result<SparseDistances, QueryError>
    where
        Self: Sized,
    {
        let r2 = squared_radius(r)?;
        let (a, b) = (self, other);
        let collect = |triples: &mut Vec<(usize, usize, f64)>, start| {
            let mut v = PairsWithin {
                metric: &Euclid,
                unordered: false,
                a,
                b,
                r2,
                boundary,
                visit: |s, t, d| {
                    triples.push((s, t, d));
                    ControlFlow::<Infallible>::Continue(())
                },
                block: Block::boxed(),
            };
            let _ = run(a.index(), b.index(), &Euclid, start, &mut v);
        };
        let mut top = Vec::new();
        let frontier = {
            let mut v = PairsWithin {
                metric: &Euclid,
                unordered: false,
                a,
                b,
                r2,
                boundary,
                visit: |s, t, d| {
                    top.push((s, t, d));
                    ControlFlow::<Infallible>::Continue(())
                },
                block: Block::boxed(),
            };
            let want = rayon::current_num_threads() * PAIRS_PER_THREAD;
            let start = roots((a.index(), b.index(), &Euclid), false, (), &mut v);
            split_top(a.index(), b.index(), &Euclid, start, want, &mut v)
        };
        let parts: Vec<Vec<(usize, usize, f64)>> = frontier
            .into_par_iter()
            .map(|pair| {
                let mut triples = Vec::new();
                collect(&mut triples, vec![pair]);
                triples
            })
            .collect();
        for p in parts {
            top.extend(p);
        }
        Ok(SparseDistances::new((a.len(), b.len()), top))
    }

    /// [`Joins::count_pairs_within`] on rayon's threads; the same counts.
    ///
    /// # Errors
    /// Those of [`Joins::count_pairs_within`].
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Boundary, Quadtree};
    /// let pts: Vec<([f64; 2], ())> = (0..500).map(|i| ([(i % 25) as f64, (i / 25) as f64], ())).collect();
    /// let t = Quadtree::new(&pts).unwrap();
    /// let radii = [0.5, 1.0, 1.5, 10.0];
    /// let counts = t.par_count_pairs_within(&radii, Boundary::Inclusive).unwrap();
    /// assert_eq!(counts, t.count_pairs_within(&radii, Boundary::Inclusive).unwrap());
    /// assert_eq!(counts[1], 24 * 20 + 25 * 19); // the grid's horizontal and vertical edges
    /// ```
    fn par_count_pairs_within(
        &self,
        radii: &[f64],
        boundary: Boundary,
    ) -> Result<Vec<u64>, QueryError>
    where
        Self: Sized,
    {
        par_count(self, self, true, radii, boundary)
    }

    /// [`Joins::count_neighbors`] on rayon's threads; the same counts.
    ///
    /// # Errors
    /// Those of [`Joins::count_pairs_within`].
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::{query::Boundary, Quadtree};
    /// let pts: Vec<([f64; 2], ())> = (0..500).map(|i| ([(i % 25) as f64, (i / 25) as f64], ())).collect();
    /// let (a, b) = (Quadtree::new(&pts[..300]).unwrap(), Quadtree::new(&pts[200..]).unwrap());
    /// let radii = [0.0, 1.0, 3.0];
    /// let counts = a.par_count_neighbors(&b, &radii, Boundary::Exclusive).unwrap();
    /// assert_eq!(counts, a.count_neighbors(&b, &radii, Boundary::Exclusive).unwrap());
    /// assert_eq!(counts[1], 100); // the shared points, each with itself
    /// ```
    fn par_count_neighbors<B: PointSet<D> + Sync>(
        &self,
        other: &B,
        radii: &[f64],
        boundary: Boundary,
    ) -> Result<Vec<u64>, QueryError>
    where
        Self: Sized,
    {
        par_count(self, other, false, radii, boundary)
    }
}

impl<P: Joins<D> + Sync, const D: usize> ParallelJoins<D> for P {}

/// The k-nearest join of `a` in `b` (`same`: the self-join), the groups of `a` on rayon's
/// threads.
fn par_knn<A: PointSet<D> + Sync, B: PointSet<D> + Sync, const D: usize>(
    a: &A,
    b: &B,
    k: usize,
    same: bool,
) -> KnnTable {
    let w = width(k, b.len(), same);
    let mut t = table(a.len(), w);
    if w == 0 {
        return t;
    }
    let gs = groups(a.index());
    let lists: Vec<Vec<(f64, usize)>> = gs
        .par_iter()
        .map(|g| {
            let mut l = Vec::new();
            group_knn(a.index(), b.index(), &Euclid, g, w, same, &mut l);
            l
        })
        .collect();
    for (g, l) in gs.into_iter().zip(lists) {
        write_rows(a, b, g.0, &l, &mut t);
    }
    t
}

/// The counts within each of `radii` between `a` and `b` (`same`: `b` is `a`), the top of the
/// traversal split into node pairs counted on rayon's threads.
fn par_count<A: PointSet<D> + Sync, B: PointSet<D> + Sync, const D: usize>(
    a: &A,
    b: &B,
    same: bool,
    radii: &[f64],
    boundary: Boundary,
) -> Result<Vec<u64>, QueryError> {
    let r2 = squared_radii(radii)?;
    if r2.is_empty() {
        return Ok(Vec::new());
    }
    let counter = || CountWithin {
        metric: &Euclid,
        a,
        b,
        r2: &r2,
        boundary,
        diff: vec![0; r2.len() + 1],
        block: Block::boxed(),
    };
    let mut top = counter();
    let want = rayon::current_num_threads() * PAIRS_PER_THREAD;
    let start = roots(
        (a.index(), b.index(), &Euclid),
        same,
        (0, r2.len()),
        &mut top,
    );
    let frontier = split_top(a.index(), b.index(), &Euclid, start, want, &mut top);
    let parts: Vec<Vec<i128>> = frontier
        .into_par_iter()
        .map(|pair| {
            let mut c = counter();
            let _ = run(a.index(), b.index(), &Euclid, vec![pair], &mut c);
            c.diff
        })
        .collect();
    for part in parts {
        for (t, p) in top.diff.iter_mut().zip(part) {
            *t += p;
        }
    }
    Ok(top.counts())
}
