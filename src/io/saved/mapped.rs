//! A saved tree queried in place through a memory map (feature `mmap`): the operating system
//! pages in the parts of the file a query touches, so a tree larger than memory (the output of
//! [`super::external`]) answers box queries with resident memory bounded by what the queries
//! read.
//!
//! The map is the one `unsafe` call here: `memmap2::Mmap::map`, which is unsafe because
//! another process could change the file while it is mapped (the slices would then change
//! under us). Opening a file that nothing else writes is the contract, stated on
//! [`MappedTree::open`]. Everything after the map is safe: the header is checked as
//! [`read_point_tree`](super::read_point_tree) checks it (counts against the file's length
//! before anything is read), and the sections are borrowed from the map by `bytemuck`'s checked
//! casts (the format aligns every section to 16 bytes, the map to a page).
//!
//! Two ways to query. [`MappedTree::view`] checks the node structure and every point (as
//! [`PointTreeView::open`]: one pass over the points, which pages in the whole points section)
//! and hands out a [`PointTreeView`] borrowing the map, with every query of the crate and
//! answers equal to a scan of the file's points whatever its bytes. [`MappedTree::query_box`]
//! reads nothing up front (`open` is O(1)) and walks the arrays a query touches, checking every
//! index it follows ([`SavedError::Corrupt`] rather than a panic on a damaged file) and testing
//! every point it reports, so it never reports a point outside the box; on a file damaged after
//! it was written it may miss points lying outside their leaf's cell, which only the view's
//! check rules out. [`MappedTree::to_tree`] copies into an owned tree with the loader's full
//! check.

use super::header::Header;
use super::{read_header, PointTreeView, SavedError, SavedScalar};
use crate::geom::{Aabb, Cell, Dim, RootGeometry};
use crate::{PointTree, Scalar};
use bytemuck::Pod;
use memmap2::Mmap;
use std::path::Path;

/// A saved point tree mapped into memory (see the module doc).
///
/// ```
/// use orthtree::io::saved::{mapped::MappedTree, write_point_tree};
/// use orthtree::{Aabb, Octree, PointSet};
/// let pts: Vec<([f64; 3], u32)> = (0..4000u32)
///     .map(|i| ([(i % 16) as f64, (i / 16 % 16) as f64, (i / 256) as f64], i)).collect();
/// let tree = Octree::new(&pts).unwrap();
/// let file = std::env::temp_dir().join(format!("orthtree-doc-mapped-{}.tree", std::process::id()));
/// write_point_tree(&tree, std::fs::File::create(&file).unwrap()).unwrap();
/// let mapped = MappedTree::<f64, u32, 3>::open(&file).unwrap();
/// let query = Aabb::new([2.0, 3.0, 0.5], [5.0, 3.0, 7.0]).unwrap();
/// let mut found = Vec::new();
/// mapped.query_box(&query, |_, &item| found.push(item)).unwrap();
/// found.sort_unstable();
/// let mut want: Vec<u32> = tree.query(&query).unwrap().map(|(_, &i)| i).collect();
/// want.sort_unstable();
/// assert_eq!(found, want);
/// assert_eq!(mapped.to_tree().unwrap().points(), tree.points());
/// // every query, after the check of the whole file
/// let view = mapped.view().unwrap();
/// assert_eq!(view.k_nearest(&[3.5, 2.0, 9.0], 4).unwrap(), tree.k_nearest(&[3.5, 2.0, 9.0], 4).unwrap());
/// drop(view);
/// std::fs::remove_file(&file).unwrap();
/// ```
pub struct MappedTree<S, T, const D: usize> {
    map: Mmap,
    header: Header<D>,
    /// Byte offsets of the sections: points, items, run ends, first children, levels.
    at: [usize; 5],
    geometry: RootGeometry<D>,
    _types: core::marker::PhantomData<(S, T)>,
}

impl<S: SavedScalar, T: Pod, const D: usize> MappedTree<S, T, D> {
    /// Maps the saved tree at `path` and checks its header against the file's length.
    ///
    /// The file must not be changed by anyone while the tree is open (the map would change
    /// under the queries: the one `unsafe` contract of `memmap2`).
    ///
    /// # Errors
    /// [`SavedError::Io`] when the file cannot be opened or mapped; the header errors of
    /// [`read_point_tree`](super::read_point_tree) ([`SavedError::Truncated`],
    /// [`SavedError::Field`], [`SavedError::Padding`], [`SavedError::Trailing`]).
    ///
    /// # Complexity
    /// O(1): only the header is read.
    pub fn open(path: impl AsRef<Path>) -> Result<Self, SavedError> {
        let file = std::fs::File::open(path).map_err(SavedError::Io)?;
        // SAFETY: the map is read-only and private to this value; the caller promises (see
        // above) that no one writes the file while it is open. Every read through the map
        // goes through checked slices.
        #[allow(unsafe_code)]
        let map = unsafe { Mmap::map(&file) }.map_err(SavedError::Io)?;
        let header = read_header::<S, T, D>(&map, map.len() as u64)?;
        let (spans, _) = header.spans::<S>();
        let at = core::array::from_fn(|k| spans[k].0 as usize);
        let geometry = RootGeometry::try_from_halves(header.half_lo, header.half_side)
            .map_err(|_| corrupt("root geometry", 0))?;
        Ok(MappedTree {
            map,
            header,
            at,
            geometry,
            _types: core::marker::PhantomData,
        })
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        self.header.points as usize
    }

    /// The box the points lie in (the root cube, or the root box the tree was built with).
    pub fn domain(&self) -> Aabb<f64, D> {
        self.header.domain
    }

    /// `true` for a tree without points.
    pub fn is_empty(&self) -> bool {
        self.header.points == 0
    }

    /// The section `k` as a slice of `len` values of `V`.
    fn section<V: Pod>(&self, k: usize, len: usize) -> Result<&[V], SavedError> {
        let bytes = len * core::mem::size_of::<V>();
        let raw = &self.map[self.at[k]..self.at[k] + bytes];
        bytemuck::try_cast_slice(raw).map_err(|_| corrupt("section alignment", k as u64))
    }

    /// The points in Morton order, borrowed from the map.
    ///
    /// # Errors
    /// [`SavedError::Corrupt`] if the section is not aligned for `S` (a map always is).
    pub fn points(&self) -> Result<&[[S; D]], SavedError> {
        self.section(0, self.len())
    }

    /// The item of each point, borrowed from the map (items of size 0 have no bytes: use
    /// [`MappedTree::to_tree`] for those).
    ///
    /// # Errors
    /// [`SavedError::Corrupt`] for items of size 0 or a misaligned section.
    pub fn items(&self) -> Result<&[T], SavedError> {
        if core::mem::size_of::<T>() == 0 {
            return Err(corrupt("items of size 0", 0));
        }
        self.section(1, self.len())
    }

    /// Calls `visit(point, item)` for every point in the closed box `query`; returns how many.
    /// Nodes outside the box are skipped and the points of the others tested exactly (so a
    /// point outside the box is never reported, and none twice; see the module doc for what a
    /// damaged file can still do, and [`MappedTree::view`] for the checked queries).
    ///
    /// # Errors
    /// [`SavedError::Corrupt`] naming the node whose links or runs leave the arrays, whose
    /// children's runs do not partition its own, or that the walk reaches twice (a file damaged
    /// after it was written; [`MappedTree::to_tree`] checks every invariant).
    ///
    /// # Complexity
    /// That of a box query on the tree, O(depth + nodes cut + k) for k points found, and never
    /// more than O(m + n) for m node slots whatever the file's links; memory O(2^D depth)
    /// besides the pages read.
    pub fn query_box(
        &self,
        query: &Aabb<f64, D>,
        mut visit: impl FnMut(&[S; D], &T),
    ) -> Result<usize, SavedError> {
        let n = self.len();
        let slots = self.header.slots as usize;
        let points = self.points()?;
        let zst = [T::zeroed()];
        let items: &[T] = if core::mem::size_of::<T>() == 0 {
            &zst
        } else {
            self.items()?
        };
        let item = |i: usize| &items[if items.len() == 1 { 0 } else { i }];
        let run_ends: &[u32] = self.section(2, slots)?;
        let first_child: &[u32] = self.section(3, slots)?;
        let mut found = 0usize;
        let mut stack: Vec<(u32, Cell<D>, usize, usize)> = vec![(0, Cell::root(), 0, n)];
        // A tree reaches each of its node slots at most once: more visits mean first children
        // that link back into the tree (a damaged file), whose walk would grow with 2^(D level).
        let mut visits = 0usize;
        while let Some((v, cell, s, e)) = stack.pop() {
            visits += 1;
            if visits > slots {
                return Err(corrupt("node reached twice", u64::from(v)));
            }
            if e > n || s > e {
                return Err(corrupt("node run", u64::from(v)));
            }
            let bbox = self.geometry.cell_box(&cell);
            if !bbox.intersects(query) {
                continue;
            }
            let inside = (0..D).all(|a| query.min[a] <= bbox.min[a] && bbox.max[a] <= query.max[a]);
            let first = *first_child
                .get(v as usize)
                .ok_or(corrupt("node id", u64::from(v)))?;
            if inside || first == u32::MAX {
                for (i, p) in points[s..e].iter().enumerate() {
                    let i = s + i;
                    if query.contains(&p.map(Scalar::to_f64)) {
                        visit(p, item(i));
                        found += 1;
                    }
                }
                continue;
            }
            if cell.level() >= Cell::<D>::MAX_LEVEL {
                return Err(corrupt("node level", u64::from(v)));
            }
            let first = first as usize;
            let ends = run_ends
                .get(first..first + Dim::<D>::CHILDREN)
                .ok_or(corrupt("first child", u64::from(v)))?;
            // The children's runs must partition the node's: one that reached past it would
            // report the points of another node a second time.
            if ends.last().is_some_and(|&end| s + end as usize != e) {
                return Err(corrupt("child runs", u64::from(v)));
            }
            let mut lo = s;
            for (c, &end) in ends.iter().enumerate() {
                let hi = s + end as usize;
                stack.push(((first + c) as u32, cell.child(c), lo, hi));
                lo = hi;
            }
        }
        Ok(found)
    }

    /// A [`PointTreeView`] borrowing the map, after the check of [`PointTreeView::open`] (the
    /// structure and every point, on rayon's threads with feature `rayon`): every query of the
    /// crate, on the mapped file.
    ///
    /// # Errors
    /// Those of [`PointTreeView::open`].
    ///
    /// # Complexity
    /// O(n D + m) for n points and m node slots: the points and node sections are read once
    /// (paged in); the items are paged in as queries read them.
    pub fn view(&self) -> Result<PointTreeView<'_, S, T, D>, SavedError> {
        PointTreeView::open(&self.map)
    }

    /// The tree copied out of the map into an owned [`PointTree`], with every check of
    /// [`read_point_tree`](super::read_point_tree).
    ///
    /// # Errors
    /// As [`read_point_tree`](super::read_point_tree).
    ///
    /// # Complexity
    /// O(n + m depth); memory for the whole tree.
    pub fn to_tree(&self) -> Result<PointTree<S, T, D>, SavedError> {
        super::read_point_tree(&self.map)
    }
}

fn corrupt(what: &'static str, at: u64) -> SavedError {
    SavedError::Corrupt { what, at }
}
