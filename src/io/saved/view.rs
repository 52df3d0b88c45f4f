//! [`PointTreeView`]: a saved point tree queried in place, borrowed from any byte slice (a file
//! read into memory, a memory map) without copying or rebuilding anything, with every query of
//! [`PointSet`](crate::PointSet): the saved arrays walked as the owned tree walks its own
//! (`points/index.rs`, written once for both), slots being positions in the saved points.
//!
//! Opening checks, in this order: the header as [`read_point_tree`](super::read_point_tree)
//! does (counts against the bytes available, before anything else); the sections' zero padding;
//! the settings (the root cube finite, the domain a finite box inside it); the node structure
//! by one walk from the root (links in range, each child block entered from the one parent it
//! records, levels, runs that nest and partition, leaf and node sizes: O(node slots)); then
//! every point inside its leaf's cell under the split convention and inside the domain, with
//! coordinates `f64` holds exactly, by two comparisons per axis and point against per-leaf
//! bounds (O(n) reads, no Morton keys; on rayon's threads with feature `rayon`). Those are
//! exactly what the queries rely on (the [`SpatialIndex`](crate::query::SpatialIndex) contract:
//! each node's run is its children's, every point of a run lies in the node's closed box), so a
//! view that opens answers every query as a scan of its own points would, and corrupt or
//! hostile bytes give a [`SavedError`] naming what is wrong, never a panic.
//!
//! What the view does not check, because no query reads it: the item bytes (any bytes are a
//! `Pod` value), the levels and free list of blocks the walk does not reach (freed by removals),
//! the recorded depth and live-block counts, balance, and the Morton order of the points
//! within a leaf. [`PointTreeView::to_tree`] copies into an owned [`PointTree`] with all of
//! those checks, which its updates need.
//!
//! The sections are borrowed with `bytemuck`'s checked casts. The format aligns each section to
//! 16 bytes from the start of the file, so a slice that starts at a multiple of 16 (a memory
//! map, a `Vec` of 16-byte values) is borrowed whole; from a slice whose start is not aligned
//! for the coordinate or item type, that section is copied instead
//! ([`PointTreeView::is_borrowed`] tells).

use super::header::{padded, zero_padding, Header};
use super::{read_header, SavedError, SavedScalar};
use crate::error::{Invariant, ValidationError};
use crate::geom::{Aabb, RootGeometry};
use crate::points::checked_root;
use crate::points::leaf_bounds::{self, LeafRun};
use crate::points::run_walk::{walk_runs, RunArrays, Sizes};
use crate::points::{point_index, PointArrays};
use crate::PointTree;
use bytemuck::Pod;
use std::borrow::Cow;

/// A saved point tree borrowed from bytes, with every query (see the module doc).
///
/// ```
/// use orthtree::io::saved::{write_point_tree, PointTreeView};
/// use orthtree::prelude::*;
/// use orthtree::{Aabb, Octree};
/// let pts: Vec<([f64; 3], u32)> = (0..4000u32)
///     .map(|i| ([(i % 16) as f64, (i / 16 % 16) as f64, (i / 256) as f64], i)).collect();
/// let tree = Octree::new(&pts).unwrap();
/// let mut bytes = Vec::new();
/// write_point_tree(&tree, &mut bytes).unwrap();
/// let view = PointTreeView::<f64, u32, 3>::open(&bytes).unwrap();
/// assert_eq!(view.len(), 4000);
/// let q = [3.2, 4.9, 7.5];
/// assert_eq!(view.k_nearest(&q, 5).unwrap(), tree.k_nearest(&q, 5).unwrap());
/// let b = Aabb::new([2.0, 3.0, 0.5], [5.0, 3.0, 7.0]).unwrap();
/// assert_eq!(view.query_count(&b).unwrap(), tree.query_count(&b).unwrap());
/// // the points start after the 240 bytes of a 3D header: point 100's x, its exponent changed
/// // by 64, leaves its leaf's cell and is refused
/// bytes[240 + 24 * 100 + 7] ^= 0x04;
/// assert!(PointTreeView::<f64, u32, 3>::open(&bytes).is_err());
/// ```
#[derive(Clone, Debug)]
pub struct PointTreeView<'a, S: Clone, T: Clone, const D: usize> {
    pub(super) points: Cow<'a, [[S; D]]>,
    pub(super) items: Cow<'a, [T]>,
    pub(super) run_ends: Cow<'a, [u32]>,
    pub(super) first_child: Cow<'a, [u32]>,
    pub(super) geometry: RootGeometry<D>,
    pub(super) domain: Aabb<f64, D>,
    bucket_size: usize,
    max_depth: u8,
    depth: u8,
    leaves: usize,
    bytes: &'a [u8],
}

/// A section of `bytes` as a slice of `V`: borrowed when aligned, else copied.
fn cast<V: Pod>(bytes: &[u8]) -> Cow<'_, [V]> {
    if core::mem::size_of::<V>() == 0 {
        return Cow::Owned(Vec::new());
    }
    match bytemuck::try_cast_slice(bytes) {
        Ok(s) => Cow::Borrowed(s),
        Err(_) => Cow::Owned(bytemuck::pod_collect_to_vec(bytes)),
    }
}

impl<'a, S: SavedScalar, T: Pod, const D: usize> PointTreeView<'a, S, T, D> {
    /// The tree saved in `bytes` (by [`write_point_tree`](super::write_point_tree)), checked
    /// (see the module doc): the points on rayon's threads with feature `rayon`.
    ///
    /// # Errors
    /// The header's, as [`read_point_tree`](super::read_point_tree)'s:
    /// [`SavedError::Truncated`], [`SavedError::Field`], [`SavedError::Padding`],
    /// [`SavedError::Trailing`] naming the field and byte offset; [`SavedError::Invalid`] naming
    /// the node or point and the invariant it breaks; [`SavedError::BigEndianHost`].
    ///
    /// # Complexity
    /// O(n D + m) for n points and m node slots, no recursion; memory O(leaves) during the
    /// check, then nothing but the view (unless a section had to be copied).
    pub fn open(bytes: &'a [u8]) -> Result<Self, SavedError> {
        Self::open_with(bytes, true)
    }

    /// [`PointTreeView::open`] with the points checked on the calling thread only.
    ///
    /// # Errors
    /// Those of [`PointTreeView::open`].
    ///
    /// # Complexity
    /// That of [`PointTreeView::open`].
    pub fn open_serial(bytes: &'a [u8]) -> Result<Self, SavedError> {
        Self::open_with(bytes, false)
    }

    /// [`PointTreeView::open`] with the structure checked but the points not: O(node slots),
    /// touching only the header and node sections. Only for bytes this process wrote or
    /// checked before (a point outside its leaf's cell would make queries miss it).
    pub(super) fn open_unchecked(bytes: &'a [u8]) -> Result<(Self, Vec<LeafRun<D>>), SavedError> {
        let header = read_header::<S, T, D>(bytes, bytes.len() as u64)?;
        let sections = sections::<S, D>(&header, bytes)?;
        let domain = header.domain;
        let geometry = checked_root(header.half_lo, header.half_side, &domain)?;
        let n = header.points as usize;
        let items = if core::mem::size_of::<T>() == 0 {
            Cow::Owned(vec![T::zeroed(); n])
        } else {
            cast(sections[1])
        };
        let view = PointTreeView {
            points: cast(sections[0]),
            items,
            run_ends: cast(sections[2]),
            first_child: cast(sections[3]),
            geometry,
            domain,
            bucket_size: header.bucket_size as usize,
            max_depth: header.max_depth,
            depth: header.depth,
            leaves: 0,
            bytes,
        };
        let block_parent: Cow<'_, [u32]> = cast(sections[5]);
        let arrays = RunArrays {
            first_child: &view.first_child,
            level: sections[4],
            block_parent: &block_parent,
            run_ends: &view.run_ends,
        };
        let sizes = Sizes {
            points: n,
            bucket_size: view.bucket_size,
            max_depth: view.max_depth,
            balanced: header.balanced.is_some(),
        };
        let leaves = walk_runs::<D>(arrays, sizes)?;
        let view = PointTreeView {
            leaves: leaves.len(),
            ..view
        };
        Ok((view, leaves))
    }

    fn open_with(bytes: &'a [u8], parallel: bool) -> Result<Self, SavedError> {
        let (view, leaves) = Self::open_unchecked(bytes)?;
        view.check_points(&leaves, parallel)?;
        Ok(view)
    }

    /// The arrays the queries walk (their indices were checked when the view was opened).
    #[inline(always)]
    pub(crate) fn arrays(&self) -> PointArrays<'_, S, T, D> {
        PointArrays {
            points: &self.points,
            items: &self.items,
            first_child: &self.first_child,
            run_ends: &self.run_ends,
            geometry: &self.geometry,
        }
    }

    /// The check of [`PointTreeView::open`] again, the structure and every point (the view's
    /// [`PointSet::validate`](crate::PointSet::validate)).
    fn check(&self) -> Result<(), ValidationError> {
        match Self::open_unchecked(self.bytes()) {
            Ok((_, leaves)) => self.check_points(&leaves, true),
            Err(SavedError::Invalid(e)) => Err(e),
            Err(e) => Err(ValidationError::new(Invariant::Settings).detail(e.to_string())),
        }
    }

    /// The per-leaf bound check of every point (see the module doc).
    fn check_points(&self, leaves: &[LeafRun<D>], parallel: bool) -> Result<(), ValidationError> {
        leaf_bounds::check_leaves(&self.geometry, &self.domain, &self.points, leaves, parallel)
    }

    /// The bytes the view was opened from.
    pub fn bytes(&self) -> &'a [u8] {
        self.bytes
    }

    /// The points in Morton order (by leaf; within a leaf, as saved).
    pub fn points(&self) -> &[[S; D]] {
        &self.points
    }

    /// Where the cells lie in space.
    pub fn geometry(&self) -> &RootGeometry<D> {
        &self.geometry
    }

    /// The bucket size the tree was built with.
    pub fn bucket_size(&self) -> usize {
        self.bucket_size
    }

    /// The maximum depth the tree was built with.
    pub fn max_depth(&self) -> u8 {
        self.max_depth
    }

    /// The depth recorded in the file (not checked: no query reads it).
    pub fn depth(&self) -> u8 {
        self.depth
    }

    /// The number of leaves.
    pub fn leaf_count(&self) -> usize {
        self.leaves
    }

    /// The number of node slots.
    pub fn node_count(&self) -> usize {
        self.first_child.len()
    }

    /// `true` when every section is borrowed from the bytes (none had to be copied because the
    /// slice's start is not aligned for the coordinate or item type).
    pub fn is_borrowed(&self) -> bool {
        matches!(self.points, Cow::Borrowed(_))
            && (core::mem::size_of::<T>() == 0 || matches!(self.items, Cow::Borrowed(_)))
            && matches!(self.run_ends, Cow::Borrowed(_))
            && matches!(self.first_child, Cow::Borrowed(_))
    }

    /// Heap bytes the view owns: none when every section is borrowed, else the copied ones.
    pub fn heap_bytes(&self) -> usize {
        owned_bytes(&self.points)
            + owned_bytes(&self.items)
            + owned_bytes(&self.run_ends)
            + owned_bytes(&self.first_child)
    }

    /// The tree copied into an owned [`PointTree`] with every check of
    /// [`read_point_tree`](super::read_point_tree) (which the owned tree's updates need).
    ///
    /// # Errors
    /// As [`read_point_tree`](super::read_point_tree).
    ///
    /// # Complexity
    /// O(n + m); memory for the whole tree.
    pub fn to_tree(&self) -> Result<PointTree<S, T, D>, SavedError> {
        super::read_point_tree(self.bytes)
    }
}

point_index!(
    impl[S: SavedScalar, T: Pod, const D: usize] PointTreeView<'_, S, T, D>,
    /// The check of [`PointTreeView::open`] again (the structure and every point), on rayon's
    /// threads with feature `rayon`.
    check
);

/// The heap bytes of a section: none when borrowed (the variant tells, hence the `Cow`).
#[allow(clippy::ptr_arg)]
fn owned_bytes<V: Clone>(section: &Cow<'_, [V]>) -> usize {
    match section {
        Cow::Borrowed(_) => 0,
        Cow::Owned(v) => v.capacity() * core::mem::size_of::<V>(),
    }
}

/// The seven sections of `bytes` (lengths checked by `read_header`), their padding checked.
fn sections<'b, S: SavedScalar, const D: usize>(
    header: &Header<D>,
    bytes: &'b [u8],
) -> Result<[&'b [u8]; 7], SavedError> {
    let (spans, _) = header.spans::<S>();
    for &(_, stop) in &spans {
        let end = padded(stop).expect("checked");
        zero_padding(&bytes[stop as usize..end as usize], stop)?;
    }
    Ok(spans.map(|(start, stop)| &bytes[start as usize..stop as usize]))
}
