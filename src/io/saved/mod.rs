//! A compact, versioned binary format for [`PointTree`]: the tree's own arrays (points, items,
//! node runs, topology) written as they are, read back without a sort or a rebuild (feature
//! `saved`).
//!
//! [`write_point_tree`] streams a tree to any [`Write`]. Three ways back:
//! - [`PointTreeView::open`] borrows the sections of a byte slice in place (a file read into
//!   memory, or a memory map: `mapped::MappedTree::view` with feature `mmap`) and answers every
//!   query of [`PointSet`](crate::PointSet) on them: no copy, one linear check;
//! - [`read_point_tree`] copies them from a byte slice into an owned tree, which also takes
//!   updates, [`read_point_tree_file`] from a file, reading each array straight into its place.
//!
//! Points and items are plain data cast to and from bytes by `bytemuck` ([`SavedScalar`] for
//! the coordinates, `bytemuck::Pod` for the items).
//!
//! # The check on load
//! Nothing in the input is trusted. The header's fields are checked first (magic, version, tree
//! kind, dimension, scalar, item size and alignment, each count against its range) and the
//! sections' lengths computed from the counts are compared with the bytes available before
//! anything is allocated. Then one walk of the nodes from the root checks the links, levels,
//! runs (they nest and partition their parents') and leaf sizes (`points/run_walk.rs`), and
//! every point is compared with its leaf cell's bounds under the split convention and the
//! domain's, its coordinates exact in `f64` (`points/leaf_bounds.rs`: two comparisons per axis
//! and point, no Morton keys, on rayon's threads with feature `rayon`). That is all the view
//! needs: its queries rely on nothing else. The owned tree also checks what its updates rely on:
//! the arena's free list and live-block counts ([`crate::Tree::validate`]), Morton order within
//! each leaf, balance. Corrupt or hostile bytes therefore give a [`SavedError`] naming the field
//! and byte offset, or the broken invariant with its node and point, never a panic, and a tree
//! or view that loads answers every query as the brute force over its points would. Item bytes
//! are not checked: any bytes are a valid `Pod` value.
//!
//! # Format, version 1 (little-endian)
//! | bytes | field |
//! | --- | --- |
//! | 0..8 | magic `ORTHTREE` |
//! | 8..10 | version (`u16`, 1) |
//! | 10 | tree kind (1: `PointTree`) |
//! | 11 | dimension D |
//! | 12 | scalar ([`SavedScalar::KIND`]) |
//! | 13, 14 | maximum depth, depth |
//! | 15, 16 | balance kept (0 none, 1 face, 2 edge, 3 corner) and its level difference |
//! | 17..20 | zero |
//! | 20..24, 24..28 | item size and alignment (`u32`) |
//! | 28..32 | zero |
//! | 32..40, 40..48, 48..56 | points n, node slots m, freed blocks f (`u64`) |
//! | 56..64 | bucket size (`u64`) |
//! | 64..72 | half the root cube's side (`f64`) |
//! | 72.. | the root cube's lower corner halved, the domain's minimum and maximum (`3 D f64`) |
//! | then | live child blocks per level 0..=`Cell::MAX_LEVEL` (`u32`) |
//!
//! then, each starting at a multiple of 16 bytes with zero padding between: the points
//! (`n [S; D]`), the items (`n T`), the node runs' relative ends (`m u32`), the first children
//! (`m u32`), the levels (`m u8`), the block parents (`(m - 1) / 2^D u32`) and the freed blocks
//! (`f u32`). The file ends with the last section's padding.
//!
//! ```
//! use orthtree::io::saved::{read_point_tree, write_point_tree};
//! use orthtree::prelude::*;
//! use orthtree::Quadtree;
//! let pts: Vec<([f64; 2], u32)> = (0..500).map(|i| ([(i % 37) as f64, (i / 37) as f64], i)).collect();
//! let tree = Quadtree::new(&pts).unwrap();
//! let mut bytes = Vec::new();
//! write_point_tree(&tree, &mut bytes).unwrap();
//! let back = read_point_tree::<f64, u32, 2>(&bytes).unwrap();
//! assert_eq!((back.points(), back.items()), (tree.points(), tree.items()));
//! assert_eq!(back.k_nearest(&[3.2, 4.9], 5).unwrap(), tree.k_nearest(&[3.2, 4.9], 5).unwrap());
//! bytes[200] ^= 0xff; // a point moved out of its leaf, or out of Morton order
//! assert!(read_point_tree::<f64, u32, 2>(&bytes).is_err());
//! ```

mod error;
pub mod external;
mod header;
#[cfg(feature = "mmap")]
pub mod mapped;
mod runs;
mod topology;
mod view;

pub use error::SavedError;
pub use header::{ALIGN, MAGIC, VERSION};
pub use view::PointTreeView;

use crate::points::{PointTreeArrays, PointTreeParts};
use crate::tree::raw::OwnedRawTree;
use crate::{PointTree, Scalar};
use bytemuck::Pod;
use header::{padded, sections_start, write_section, zero_padding, Header};
use std::io::{Read, Write};

/// A coordinate type the format stores: a [`Scalar`] that is plain data, with its code in the
/// header. Implemented for `f32`, `f64` and the primitive integers of 8 to 64 bits; sealed.
pub trait SavedScalar: Scalar + Pod + sealed::Sealed {
    /// The code written in the header (1 `f32`, 2 `f64`, 3-6 `i8`-`i64`, 7-10 `u8`-`u64`).
    const KIND: u8;
    /// The type's name, for error messages.
    const NAME: &'static str;
}

mod sealed {
    pub trait Sealed {}
}

macro_rules! saved_scalar {
    ($($t:ty => $k:expr),*) => {$(
        impl sealed::Sealed for $t {}
        impl SavedScalar for $t {
            const KIND: u8 = $k;
            const NAME: &'static str = stringify!($t);
        }
    )*};
}

saved_scalar!(f32 => 1, f64 => 2, i8 => 3, i16 => 4, i32 => 5, i64 => 6, u8 => 7, u16 => 8,
    u32 => 9, u64 => 10);

/// The header of `tree`.
fn header_of<S: SavedScalar, T: Pod, const D: usize>(
    v: &PointTreeArrays<'_, S, T, D>,
) -> Header<D> {
    Header {
        max_depth: v.max_depth,
        depth: v.tree.depth,
        balanced: v.balanced,
        item_size: core::mem::size_of::<T>() as u32,
        item_align: core::mem::align_of::<T>() as u32,
        points: v.points.len() as u64,
        slots: v.tree.first_child.len() as u64,
        free_blocks: v.tree.free_blocks.len() as u64,
        bucket_size: v.bucket_size as u64,
        half_side: v.half_side,
        half_lo: v.half_lo,
        domain: v.domain,
        live_blocks: v.tree.live_blocks.to_vec(),
    }
}

/// The number of bytes [`write_point_tree`] writes for `tree`.
///
/// ```
/// use orthtree::io::saved::{saved_len, write_point_tree};
/// let tree = orthtree::Quadtree::new(&[([0.0, 0.0], 1u8), ([1.0, 1.0], 2)]).unwrap();
/// let mut bytes = Vec::new();
/// write_point_tree(&tree, &mut bytes).unwrap();
/// assert_eq!(saved_len(&tree), bytes.len() as u64);
/// ```
pub fn saved_len<S: SavedScalar, T: Pod, const D: usize>(tree: &PointTree<S, T, D>) -> u64 {
    header_of(&tree.view()).spans::<S>().1
}

/// Writes `tree` in the saved format (see the module doc) to `out`, array by array.
///
/// # Errors
/// What `out` returns; [`std::io::ErrorKind::Unsupported`] on a big-endian machine and for an
/// item type aligned to more than [`ALIGN`] bytes.
///
/// # Complexity
/// O(n + m) for n points and m node slots; no memory beyond the header.
pub fn write_point_tree<S: SavedScalar, T: Pod, const D: usize>(
    tree: &PointTree<S, T, D>,
    mut out: impl Write,
) -> std::io::Result<()> {
    let unsupported = |what: String| std::io::Error::new(std::io::ErrorKind::Unsupported, what);
    if cfg!(target_endian = "big") {
        return Err(unsupported(SavedError::BigEndianHost.to_string()));
    }
    if core::mem::align_of::<T>() as u64 > ALIGN {
        return Err(unsupported(format!(
            "saved tree: items aligned to {} bytes, the format aligns to {ALIGN}",
            core::mem::align_of::<T>()
        )));
    }
    let v = tree.view();
    let head = header_of(&v).encode::<S>();
    out.write_all(&head)?;
    let mut at = head.len() as u64;
    let sections: [&[u8]; 7] = [
        bytemuck::cast_slice(v.points),
        bytes_of_items(v.items),
        bytemuck::cast_slice(v.run_ends),
        bytemuck::cast_slice(v.tree.first_child),
        v.tree.level,
        bytemuck::cast_slice(v.tree.block_parent),
        bytemuck::cast_slice(v.tree.free_blocks),
    ];
    for s in sections {
        at = write_section(&mut out, at, s)?;
    }
    Ok(())
}

/// The bytes of `items` (none for a zero-sized type, which `bytemuck` does not cast).
fn bytes_of_items<T: Pod>(items: &[T]) -> &[u8] {
    if core::mem::size_of::<T>() == 0 {
        &[]
    } else {
        bytemuck::cast_slice(items)
    }
}

/// Reads a tree saved by [`write_point_tree`] from `bytes`, without a rebuild: the arrays are
/// copied into place and checked (see the module doc).
///
/// # Errors
/// [`SavedError::Truncated`], [`SavedError::Field`], [`SavedError::Padding`] and
/// [`SavedError::Trailing`] naming the field and byte offset; [`SavedError::Invalid`] naming the
/// broken invariant; [`SavedError::BigEndianHost`].
///
/// # Complexity
/// O(n + m depth) for n points and m node slots; memory for the tree only (nothing is
/// allocated before the header's counts are checked against `bytes.len()`).
pub fn read_point_tree<S: SavedScalar, T: Pod, const D: usize>(
    bytes: &[u8],
) -> Result<PointTree<S, T, D>, SavedError> {
    let header = read_header::<S, T, D>(bytes, bytes.len() as u64)?;
    // The lengths were checked against the slice (`Header::check_length`).
    read_sections(header, &mut &bytes[sections_start::<D>() as usize..])
}

/// [`read_point_tree`] from the file at `path`, each array read straight into its place (no
/// copy of the whole file in memory).
///
/// # Errors
/// Those of [`read_point_tree`], with the file's length as the bytes available;
/// [`SavedError::Io`] when opening or reading fails.
///
/// # Complexity
/// That of [`read_point_tree`].
pub fn read_point_tree_file<S: SavedScalar, T: Pod, const D: usize>(
    path: impl AsRef<std::path::Path>,
) -> Result<PointTree<S, T, D>, SavedError> {
    let mut file = std::fs::File::open(path).map_err(SavedError::Io)?;
    let available = file.metadata().map_err(SavedError::Io)?.len();
    let mut head = vec![0u8; sections_start::<D>().min(available) as usize];
    file.read_exact(&mut head).map_err(SavedError::Io)?;
    let header = read_header::<S, T, D>(&head, available)?;
    read_sections(header, &mut std::io::BufReader::new(file))
}

/// The header, checked, and the file's length checked against `available`.
fn read_header<S: SavedScalar, T: Pod, const D: usize>(
    head: &[u8],
    available: u64,
) -> Result<Header<D>, SavedError> {
    if cfg!(target_endian = "big") {
        return Err(SavedError::BigEndianHost);
    }
    let size = core::mem::size_of::<T>();
    let header = Header::<D>::decode::<S>(head, available, size, core::mem::align_of::<T>())?;
    header.check_length::<S>(available)?;
    Ok(header)
}

/// Reads the sections after `header` (their lengths checked) from `src` (a slice or a file from
/// the first section on), then checks the tree.
fn read_sections<S: SavedScalar, T: Pod, const D: usize>(
    header: Header<D>,
    src: &mut impl Read,
) -> Result<PointTree<S, T, D>, SavedError> {
    let n = header.points as usize;
    let slots = header.slots as usize;
    let mut at = sections_start::<D>();
    let points = section(src, &mut at, n)?;
    let items = section(src, &mut at, n)?;
    let run_ends = section(src, &mut at, slots)?;
    let first_child = section(src, &mut at, slots)?;
    let level = section(src, &mut at, slots)?;
    let block_parent = section(src, &mut at, header.blocks() as usize)?;
    let free_blocks = section(src, &mut at, header.free_blocks as usize)?;
    let parts = PointTreeParts {
        tree: OwnedRawTree {
            first_child,
            level,
            block_parent,
            free_blocks,
            live_blocks: header.live_blocks,
            depth: header.depth,
        },
        half_lo: header.half_lo,
        half_side: header.half_side,
        domain: header.domain,
        points,
        items,
        run_ends,
        bucket_size: header.bucket_size as usize,
        max_depth: header.max_depth,
        balanced: header.balanced,
    };
    Ok(PointTree::from_parts(parts)?)
}

/// Reads one section, `len` values of `V`, and its padding, which must be zero; `at` is its
/// offset.
fn section<V: Pod>(src: &mut impl Read, at: &mut u64, len: usize) -> Result<Vec<V>, SavedError> {
    let mut values: Vec<V> = bytemuck::zeroed_vec(len);
    // Nothing to read for a zero-sized type (which `bytemuck` does not cast).
    let dst: &mut [u8] = match core::mem::size_of::<V>() {
        0 => &mut [],
        _ => bytemuck::cast_slice_mut(&mut values),
    };
    src.read_exact(dst).map_err(SavedError::Io)?;
    *at += dst.len() as u64;
    let pad = (padded(*at).expect("checked") - *at) as usize;
    let mut zeros = [0u8; ALIGN as usize];
    src.read_exact(&mut zeros[..pad]).map_err(SavedError::Io)?;
    zero_padding(&zeros[..pad], *at)?;
    *at += pad as u64;
    Ok(values)
}
