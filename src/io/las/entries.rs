//! The coordinates alone of an uncompressed LAS file, in world units, paired with their record
//! numbers: the input of a point tree (`PointTreeBuilder::build` or `par_build`), read
//! in one pass at the speed of the disk cache.
//!
//! The header is the `las` crate's; the point records are then read in blocks straight from
//! the file, and the three 32-bit integers at the start of each record (every point format
//! begins with X, Y, Z) are scaled and offset ([`Frame::to_world`], the same arithmetic as
//! [`read`](super::read) followed by [`crate::cloud::Cloud::world_points`]). With the `rayon`
//! feature a block is converted on all threads while the next one is read. Reading every field
//! ([`read`](super::read)) costs about ten times more per point.

use super::{las_error, LasError, BATCH_BYTES};
use crate::cloud::Frame;
use ::las::raw;
use std::io::{Read, Seek, SeekFrom};
use std::path::Path;

/// Record `index`'s world coordinates, from the record's first 12 bytes.
#[inline]
fn entry(record: &[u8], frame: &Frame, index: usize) -> ([f64; 3], u32) {
    let axis = |a: usize| {
        i32::from_le_bytes([
            record[4 * a],
            record[4 * a + 1],
            record[4 * a + 2],
            record[4 * a + 3],
        ])
    };
    (frame.to_world(&[axis(0), axis(1), axis(2)]), index as u32)
}

/// Appends the entries of the whole records in `block`, the first being record `first`.
fn convert(
    block: &[u8],
    record: usize,
    frame: &Frame,
    first: usize,
    out: &mut Vec<([f64; 3], u32)>,
) {
    #[cfg(feature = "rayon")]
    {
        use rayon::prelude::*;
        out.par_extend(
            block
                .par_chunks_exact(record)
                .enumerate()
                .map(|(j, r)| entry(r, frame, first + j)),
        );
    }
    #[cfg(not(feature = "rayon"))]
    out.extend(
        block
            .chunks_exact(record)
            .enumerate()
            .map(|(j, r)| entry(r, frame, first + j)),
    );
}

/// Reads the world coordinates of every point of the uncompressed LAS file at `path`, each
/// paired with its record number (0, 1, ...), in file order.
///
/// ```no_run
/// use orthtree::io::las;
/// use orthtree::points::PointTreeBuilder;
/// let entries = las::read_entries("scan.las").unwrap();
/// let tree = PointTreeBuilder::new().build(&entries).unwrap();
/// assert_eq!(tree.len(), entries.len());
/// ```
///
/// # Errors
/// [`LasError::Las`] for a header the `las` crate refuses, or a point count of 2^32 - 1 or more;
/// [`LasError::UnsupportedFormat`] for compressed (LAZ) and waveform formats (read them with
/// [`read`](super::read)); [`LasError::Truncated`] when the file is shorter than the records the
/// header declares (checked before anything is allocated); [`LasError::Io`] when reading fails.
///
/// # Complexity
/// O(n) time; memory the entries (32 bytes a point) and two blocks of at most 4 MiB.
pub fn read_entries(path: impl AsRef<Path>) -> Result<Vec<([f64; 3], u32)>, LasError> {
    let mut file = std::fs::File::open(path)?;
    let length = file.metadata()?.len();
    let header = raw::Header::read_from(&mut file).map_err(las_error(None))?;
    let id = header.point_data_record_format;
    let format = ::las::point::Format::new(id).map_err(las_error(None))?;
    if format.is_compressed || format.has_waveform {
        return Err(LasError::UnsupportedFormat(id));
    }
    let record = usize::from(header.point_data_record_length);
    if record < usize::from(format.len()) {
        return Err(LasError::Las {
            point: None,
            message: format!(
                "a record of {record} bytes is shorter than point format {id} ({} bytes)",
                format.len()
            ),
        });
    }
    let count = match header.large_file {
        Some(large) if header.number_of_point_records == 0 => large.number_of_point_records,
        _ => u64::from(header.number_of_point_records),
    };
    if count >= u64::from(u32::MAX) {
        return Err(LasError::Las {
            point: None,
            message: format!("{count} points: at most {} fit a point tree", u32::MAX - 1),
        });
    }
    let start = u64::from(header.offset_to_point_data);
    let whole = length.saturating_sub(start) / record as u64;
    if whole < count {
        return Err(LasError::Truncated {
            point: whole,
            count,
            length,
        });
    }
    let frame = Frame {
        scale: [
            header.x_scale_factor,
            header.y_scale_factor,
            header.z_scale_factor,
        ],
        offset: [header.x_offset, header.y_offset, header.z_offset],
    };
    file.seek(SeekFrom::Start(start))?;
    let per_block = (BATCH_BYTES / record).max(1);
    let count = count as usize;
    let mut entries = Vec::with_capacity(count);
    let mut block = vec![0u8; per_block.min(count) * record];
    let mut next = block.clone();
    file.read_exact(&mut block)?;
    let mut done = 0;
    while done < count {
        let here = (count - done).min(per_block);
        let later = (count - done - here).min(per_block);
        next.truncate(later * record);
        let (read, ()) = join(
            || file.read_exact(&mut next),
            || convert(&block[..here * record], record, &frame, done, &mut entries),
        );
        read?;
        core::mem::swap(&mut block, &mut next);
        done += here;
    }
    Ok(entries)
}

/// Runs both, in parallel with the `rayon` feature.
fn join<A, B>(a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B + Send) -> (A, B)
where
    A: Send,
    B: Send,
{
    #[cfg(feature = "rayon")]
    return rayon::join(a, b);
    #[cfg(not(feature = "rayon"))]
    (a(), b())
}
