//! Parallel bulk build (feature `rayon`): the Morton-sort build of [`PointTreeBuilder`] with its
//! data-parallel stages spread over rayon's threads.
//!
//! The stages are the serial build's (see `build.rs`): checking the points and finding their
//! bounds (in chunks, the first error in input order reported, as serially), computing the keys,
//! the radix sort (after the first byte that differs, its 256 runs in parallel), and gathering
//! points and items into key order. Cutting the sorted run into nodes stays serial: it is a small
//! part of the time. The result is the same tree as [`PointTreeBuilder::build`] gives.

use super::build::{index_bits, later_index, pack, scan, settle, unpack_index};
use super::{PointTree, PointTreeBuilder};
use crate::error::Error;
use crate::geom::{Aabb, Scalar};
use crate::prefetch::prefetch;
use rayon::prelude::*;

/// Points per parallel task when checking the input.
const CHUNK: usize = 1 << 16;

impl<S: Scalar + Send + Sync, const D: usize> PointTreeBuilder<S, D> {
    /// [`PointTreeBuilder::build`] on rayon's threads: the same tree, the same errors.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let pts: Vec<([f64; 2], usize)> = (0..10_000)
    ///     .map(|i| ([(i % 100) as f64, (i / 100) as f64], i))
    ///     .collect();
    /// let serial = Quadtree::builder().build(&pts).unwrap();
    /// let parallel = Quadtree::builder().par_build(&pts).unwrap();
    /// assert_eq!(parallel.items(), serial.items());
    /// assert_eq!(parallel.leaf_count(), serial.leaf_count());
    /// ```
    ///
    /// # Errors
    /// [`crate::Error::NonFiniteCoordinate`] or [`crate::Error::InexactCoordinate`] for a coordinate that is NaN,
    /// infinite or an integer `f64` cannot hold, [`crate::Error::OutsideRootBox`] for a point outside a
    /// given root box (each naming the point, axis and value), [`crate::Error::InvalidRootBox`],
    /// [`crate::Error::ZeroBucketSize`], [`crate::Error::MaxDepthTooLarge`], [`crate::Error::TooManyPoints`].
    pub fn par_build<T: Clone + Send + Sync>(
        &self,
        entries: &[([S; D], T)],
    ) -> Result<PointTree<S, T, D>, Error> {
        let n = entries.len();
        let root = self.check_settings(n)?;
        let point = |i: usize| &entries[i].0;
        let scans: Vec<Result<Aabb<f64, D>, Error>> = (0..n.div_ceil(CHUNK))
            .into_par_iter()
            .map(|c| scan(root.as_ref(), c * CHUNK..((c + 1) * CHUNK).min(n), &point))
            .collect();
        let mut bounds = Aabb::empty();
        for scan in scans {
            bounds.add_box(&scan?);
        }
        let (geometry, domain) = settle(root, bounds, n);
        let bits = index_bits(n);
        let mut packed = crate::huge_pages::zeros::<u64>(n);
        packed
            .par_chunks_mut(CHUNK)
            .enumerate()
            .for_each(|(c, out)| {
                let first = c * CHUNK;
                let point = |i: usize| &entries[first + i].0;
                geometry.keys_into(out.len(), point, |i, key| {
                    out[i] = pack(key, first + i, bits);
                });
            });
        super::radix::par_sort_keyed(&mut packed);
        let (mut points, mut items): (Vec<[S; D]>, Vec<T>) = (
            crate::huge_pages::with_capacity(n),
            crate::huge_pages::with_capacity(n),
        );
        packed
            .par_iter()
            .enumerate()
            .map(|(j, &k)| {
                prefetch(&entries[later_index(&packed, j, bits)]);
                entries[unpack_index(k, bits)].clone()
            })
            .unzip_into_vecs(&mut points, &mut items);
        Ok(self.assemble(geometry, domain, packed, bits, points, items))
    }
}
