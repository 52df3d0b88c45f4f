//! The coordinates alone of an uncompressed LAS file, in world units, paired with their record
//! numbers: the input of a point tree (`PointTreeBuilder::build` or `par_build`), read
//! in one pass at the speed of the disk cache ([`read_entries`]), or streamed block by block
//! for files larger than memory ([`LasEntries`]).
//!
//! The header is the `las` crate's; the point records are then read in blocks straight from
//! the file, and the three 32-bit integers at the start of each record (every point format
//! begins with X, Y, Z) are scaled and offset ([`Frame::to_world`], the same arithmetic as
//! [`read`](super::read) followed by [`crate::cloud::Cloud::world_points`]). With the `rayon`
//! feature a block is converted on all threads while the next one is read. Reading every field
//! ([`read`](super::read)) costs about ten times more per point.

use super::header::{checked_header, frame_of};
use super::{las_error, LasError, BATCH_BYTES};
use crate::cloud::Frame;
use ::las::raw;
use std::io::{Read, Seek, SeekFrom};
use std::path::Path;

/// Record `index`'s world coordinates, from the record's first 12 bytes.
#[inline]
fn entry(record: &[u8], frame: &Frame, index: usize) -> ([f64; 3], u32) {
    let axis = |a: usize| i32::from_le_bytes(record[4 * a..4 * a + 4].try_into().expect("4 bytes"));
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

/// An uncompressed LAS file positioned at its first point record, with the layout of its
/// records as its header declares them (checked against the file's length).
#[derive(Debug)]
struct Records {
    file: std::fs::File,
    /// Bytes of one record.
    record: usize,
    /// Records the header declares (all present in the file).
    count: usize,
    frame: Frame,
}

impl Records {
    /// Opens `path`, reads and checks its header, and seeks to the first record.
    fn open(path: &Path) -> Result<Records, LasError> {
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
        // The claims the `las` crate trusts, then its checks of the whole header (the version's
        // point formats, the VLRs between the header and the records), so that this reader
        // refuses what `read` refuses rather than taking the header's bytes for points.
        checked_header(&mut file, length)?;
        file.seek(SeekFrom::Start(0))?;
        ::las::Header::new(&mut file).map_err(las_error(None))?;
        let start = u64::from(header.offset_to_point_data);
        let whole = length.saturating_sub(start) / record as u64;
        if whole < count {
            return Err(LasError::Truncated {
                point: whole,
                count,
                length,
            });
        }
        file.seek(SeekFrom::Start(start))?;
        Ok(Records {
            file,
            record,
            count: count as usize,
            frame: frame_of(&header),
        })
    }
}

/// Reads the world coordinates of every point of the uncompressed LAS file at `path`, each
/// paired with its record number (0, 1, ...), in file order.
///
/// ```no_run
/// use orthtree::io::las;
/// use orthtree::points::PointTreeBuilder;
/// use orthtree::PointSet;
/// let entries = las::read_entries("scan.las").unwrap();
/// let tree = PointTreeBuilder::new().build(&entries).unwrap();
/// assert_eq!(tree.len(), entries.len());
/// ```
///
/// # Errors
/// [`LasError::Las`] for a header the `las` crate refuses, or a point count of 2^32 - 1 or more;
/// [`LasError::Field`] for a header field claiming more than the file holds;
/// [`LasError::UnsupportedFormat`] for compressed (LAZ) and waveform formats (read them with
/// [`read`](super::read)); [`LasError::Truncated`] when the file is shorter than the records the
/// header declares (checked before anything is allocated); [`LasError::Io`] when reading fails.
///
/// # Complexity
/// O(n) time; memory the entries (32 bytes a point) and two blocks of at most 4 MiB.
pub fn read_entries(path: impl AsRef<Path>) -> Result<Vec<([f64; 3], u32)>, LasError> {
    let Records {
        mut file,
        record,
        count,
        frame,
    } = Records::open(path.as_ref())?;
    let per_block = (BATCH_BYTES / record).max(1);
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

/// The world coordinates of the points of an uncompressed LAS file, each paired with its
/// record number, read block by block: a stream for inputs larger than memory, such as the
/// out-of-core build (`io::saved::external::ExternalBuild::write`, feature `saved`, which
/// reads its source twice: open one stream per pass). The same entries, in the same order, as
/// [`read_entries`].
///
/// ```no_run
/// use orthtree::iter::LasEntries;
/// let mut n = 0;
/// for entry in LasEntries::open("scan.las")? {
///     let (_position, record) = entry?;
///     assert_eq!(record, n);
///     n += 1;
/// }
/// # Ok::<(), orthtree::io::las::LasError>(())
/// ```
///
/// # Complexity
/// O(n) time over the whole stream; memory one block of at most 4 MiB of records and its
/// entries, whatever the file's size.
#[derive(Debug)]
pub struct LasEntries {
    records: Records,
    /// The bytes of the block being converted.
    block: Vec<u8>,
    /// The current block's entries and the next one to hand out.
    entries: Vec<([f64; 3], u32)>,
    at: usize,
    /// Records read so far.
    read: usize,
    /// Set after an error: the stream has ended.
    failed: bool,
}

impl LasEntries {
    /// Opens the file at `path` and checks its header; no point is read yet.
    ///
    /// # Errors
    /// As [`read_entries`]: a header the `las` crate refuses, too many points, a compressed or
    /// waveform format, a file shorter than its records, or failing I/O.
    pub fn open(path: impl AsRef<Path>) -> Result<LasEntries, LasError> {
        let records = Records::open(path.as_ref())?;
        Ok(LasEntries {
            records,
            block: Vec::new(),
            entries: Vec::new(),
            at: 0,
            read: 0,
            failed: false,
        })
    }

    /// The number of points the file holds (the header's count, checked against its length).
    pub fn point_count(&self) -> usize {
        self.records.count
    }

    /// Reads and converts the next block; `false` at the end of the records.
    fn refill(&mut self) -> Result<bool, LasError> {
        let Records {
            file,
            record,
            count,
            frame,
        } = &mut self.records;
        let here = (*count - self.read).min((BATCH_BYTES / *record).max(1));
        if here == 0 {
            return Ok(false);
        }
        self.block.resize(here * *record, 0);
        file.read_exact(&mut self.block)?;
        self.entries.clear();
        self.at = 0;
        convert(&self.block, *record, frame, self.read, &mut self.entries);
        self.read += here;
        Ok(true)
    }
}

impl Iterator for LasEntries {
    type Item = Result<([f64; 3], u32), LasError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.at == self.entries.len() {
            if self.failed {
                return None;
            }
            match self.refill() {
                Ok(true) => {}
                Ok(false) => return None,
                Err(e) => {
                    self.failed = true;
                    return Some(Err(e));
                }
            }
        }
        self.at += 1;
        Some(Ok(self.entries[self.at - 1]))
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.entries.len() - self.at + (self.records.count - self.read);
        (0, Some(left))
    }
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
