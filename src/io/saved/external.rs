//! The out-of-core build: the saved file of a [`PointTree`](crate::PointTree) over more points
//! than fit in memory, by an external Morton sort within a memory budget.
//!
//! 1. A first pass over the points checks them and takes their bounds: the root cube, as the
//!    in-memory build chooses it.
//! 2. A second pass checks each point again against the first's count and bounds (a source
//!    that changed between passes is refused, never written), cuts the points into runs of as
//!    many as fit the budget, sorts each run by (Morton key, input index) and spills it to a
//!    temporary file.
//! 3. Runs are merged, at most [`FAN_IN`] at a time (the earlier run first among equal keys, so
//!    the order is the in-memory build's), until one pass can merge all of them into the saved
//!    file: the points and items stream into their sections while the node arrays are built
//!    from the keys (in the in-memory build's split order); the header and node arrays follow.
//!
//! The file is the one [`write_point_tree`](super::write_point_tree) writes for the in-memory
//! build of the same points, byte for byte, whatever the budget (tested, down to runs of one
//! point). Memory: the run being sorted (44 bytes a point for `f64` coordinates and `u32`
//! items) in seven eighths of the budget, then the merge's buffers (an eighth of the budget
//! shared among the streams) and the node arrays, about 13 bytes per node slot (0.13 bytes per
//! point at the default bucket size of 64 on a scan), which must fit what the runs left.
//! Disk: the runs (the points, items and keys, once) beside the output, removed as they are
//! merged.

use super::header::{padded, sections_start, write_section, Header};
use super::runs::{io, merge, Layout, Spill};
use super::SavedScalar;
use crate::geom::{Aabb, Cell, FloatBits, RootGeometry};
use crate::points::{PointTreeBuilder, DEFAULT_BUCKET_SIZE};
use crate::Error;
use bytemuck::Pod;
use core::fmt;
use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

/// The most runs merged at once.
pub const FAN_IN: usize = 16;

/// The settings of an out-of-core build: the memory budget and the tree's settings.
///
/// ```
/// use orthtree::io::saved::external::ExternalBuild;
/// let b = ExternalBuild::new(1 << 30).bucket_size(32).max_depth(12);
/// assert_eq!(b.budget(), 1 << 30);
/// ```
#[derive(Clone, Debug)]
pub struct ExternalBuild {
    budget: u64,
    bucket_size: usize,
    max_depth: Option<u8>,
    temp_dir: Option<PathBuf>,
}

/// What an out-of-core build did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ExternalReport {
    /// The points written.
    pub points: u64,
    /// The sorted runs spilled.
    pub runs: u64,
    /// Merge passes (the last writes the saved file).
    pub passes: u32,
    /// Bytes written to temporary files in all.
    pub spilled_bytes: u64,
    /// The most bytes of temporary files present at once.
    pub peak_temp_bytes: u64,
    /// The saved file's length.
    pub file_bytes: u64,
    /// The node slots of the tree.
    pub slots: u64,
}

/// Why an out-of-core build failed.
#[derive(Debug)]
#[non_exhaustive]
pub enum ExternalError {
    /// A point the tree refuses (not finite, not exact), or too many points: as the in-memory
    /// build says, naming the input index.
    Build(Error),
    /// The second pass over the points gave another number of points than the first.
    SourceChanged {
        /// Points in the first pass.
        first: u64,
        /// Points in the second.
        second: u64,
    },
    /// The second pass over the points gave point `index` outside the bounds the first pass
    /// found (the points' bounding box, from which the root cube and the domain written in the
    /// header were chosen): the points changed between passes.
    PointChanged {
        /// Position of the point in the sequence.
        index: usize,
        /// The first axis on which it lies outside the first pass's bounds.
        axis: usize,
        /// Its coordinate there, in `f64`.
        value: FloatBits,
        /// The first pass's bounds on that axis.
        bounds: (FloatBits, FloatBits),
    },
    /// Reading or writing `path` failed.
    Io {
        /// The file.
        path: PathBuf,
        /// What failed.
        source: std::io::Error,
    },
}

impl fmt::Display for ExternalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ExternalError::Build(e) => write!(f, "{e}"),
            ExternalError::SourceChanged { first, second } => write!(
                f,
                "the points changed between passes: {first} points, then {second}"
            ),
            ExternalError::PointChanged {
                index,
                axis,
                value,
                bounds: (lo, hi),
            } => write!(
                f,
                "the points changed between passes: point {index} has coordinate {value} on \
                 axis {axis}, outside the first pass's bounds [{lo}, {hi}]"
            ),
            ExternalError::Io { path, source } => write!(f, "{}: {source}", path.display()),
        }
    }
}

impl std::error::Error for ExternalError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            ExternalError::Build(e) => Some(e),
            ExternalError::Io { source, .. } => Some(source),
            ExternalError::SourceChanged { .. } | ExternalError::PointChanged { .. } => None,
        }
    }
}

impl ExternalBuild {
    /// A build within `budget` bytes of memory (runs of at least one point), the default
    /// bucket size and maximum depth, temporary files beside the output.
    pub fn new(budget: u64) -> Self {
        ExternalBuild {
            budget,
            bucket_size: DEFAULT_BUCKET_SIZE,
            max_depth: None,
            temp_dir: None,
        }
    }

    /// The memory budget in bytes.
    pub fn budget(&self) -> u64 {
        self.budget
    }

    /// Points per leaf (as [`PointTreeBuilder::bucket_size`](crate::points::PointTreeBuilder::bucket_size)).
    pub fn bucket_size(mut self, bucket_size: usize) -> Self {
        self.bucket_size = bucket_size;
        self
    }

    /// The deepest level split to (as [`PointTreeBuilder::max_depth`](crate::points::PointTreeBuilder::max_depth)).
    pub fn max_depth(mut self, max_depth: u8) -> Self {
        self.max_depth = Some(max_depth);
        self
    }

    /// The folder of the temporary run files (default: the output's).
    pub fn temp_dir(mut self, dir: impl Into<PathBuf>) -> Self {
        self.temp_dir = Some(dir.into());
        self
    }

    /// The points a run holds: seven eighths of the budget (the rest is for the program, the
    /// merge's buffers and the node arrays), at least one point.
    pub fn run_points<S: Pod, T: Pod, const D: usize>(&self) -> u64 {
        let per_point = core::mem::size_of::<([S; D], T)>() + 16;
        (self.budget / 8 * 7 / per_point as u64).max(1)
    }

    /// Writes the saved tree of the points `source()` yields (called twice: once for the
    /// bounds, once for the runs; both passes must yield the same points) to `out`, with each
    /// point's position in the sequence as input index.
    ///
    /// The second pass checks each point again against what the first found (the count, the
    /// bounds the root cube and domain were chosen from, finite and exact coordinates), so a
    /// source that changes between passes in a way the file would not survive gives an error,
    /// never a file [`read_point_tree`](super::read_point_tree) refuses. (A change that keeps
    /// every point within those bounds still gives a valid saved tree, of the second pass's
    /// points.) Every error but [`ExternalError::Io`] in the last merge comes before `out` is
    /// created: `out` is then left as it was (absent, or its old contents); the temporary runs
    /// are removed on every path.
    ///
    /// # Errors
    /// [`ExternalError::Build`] for a point the in-memory build refuses, in either pass (naming
    /// its index), or settings it refuses (bucket size 0, maximum depth too large, `u32::MAX`
    /// points or more); [`ExternalError::SourceChanged`] for another count in the second pass;
    /// [`ExternalError::PointChanged`] for a point of the second pass outside the first pass's
    /// bounds, naming its index and axis; [`ExternalError::Io`] naming the file.
    ///
    /// # Complexity
    /// O(n log n) time; two passes over the source, the runs written and read once per merge
    /// pass (one pass up to [`FAN_IN`] runs).
    ///
    /// ```
    /// use orthtree::io::saved::{external::ExternalBuild, read_point_tree, write_point_tree};
    /// use orthtree::{Octree, PointSet};
    /// let pts: Vec<([f64; 3], u32)> =
    ///     (0..1000u32).map(|i| ([(i % 10) as f64, (i / 10 % 10) as f64, (i / 100) as f64], i)).collect();
    /// let dir = std::env::temp_dir().join(format!("orthtree-doc-external-{}", std::process::id()));
    /// std::fs::create_dir_all(&dir).unwrap();
    /// let file = dir.join("cloud.tree");
    /// let report = ExternalBuild::new(4096).write(|| pts.iter().copied(), &file).unwrap();
    /// assert!(report.runs > 1);
    /// let mut bytes = Vec::new();
    /// write_point_tree(&Octree::new(&pts).unwrap(), &mut bytes).unwrap();
    /// assert_eq!(std::fs::read(&file).unwrap(), bytes); // the in-memory build's file
    /// std::fs::remove_dir_all(&dir).unwrap();
    /// ```
    pub fn write<S, T, I, const D: usize>(
        &self,
        mut source: impl FnMut() -> I,
        out: impl AsRef<Path>,
    ) -> Result<ExternalReport, ExternalError>
    where
        S: SavedScalar,
        T: Pod,
        I: IntoIterator<Item = ([S; D], T)>,
    {
        let out = out.as_ref();
        let max_depth = self.max_depth.unwrap_or(Cell::<D>::MAX_LEVEL);
        // The in-memory build's checks of the same settings, with the same errors.
        (PointTreeBuilder::<S, D>::new().bucket_size(self.bucket_size))
            .max_depth(max_depth)
            .check_settings(0)
            .map_err(ExternalError::Build)?;
        // Pass 1: the points' check and bounds.
        let mut bounds = Aabb::empty();
        let mut n = 0u64;
        for (index, (p, _)) in source().into_iter().enumerate() {
            let q = Error::check_input(&p, None, index).map_err(ExternalError::Build)?;
            bounds.add_point(&q);
            n += 1;
            if n >= u64::from(u32::MAX) {
                return Err(ExternalError::Build(Error::TooManyPoints {
                    len: n as usize,
                }));
            }
        }
        let (geometry, domain) = crate::points::settle(None, bounds, n as usize);
        let beside = out.parent().filter(|p| !p.as_os_str().is_empty());
        let beside = beside.map_or_else(|| PathBuf::from("."), Path::to_path_buf);
        let dir = self.temp_dir.clone().unwrap_or(beside);
        let stem = out
            .file_name()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "tree".into());
        let mut spill = Spill {
            dir,
            stem,
            next: 0,
            live: Vec::new(),
            written: 0,
            peak: 0,
        };
        // Pass 2: sorted runs.
        let runs = self.spill_runs::<S, T, I, D>(&mut source, &geometry, &bounds, n, &mut spill)?;
        let mut report = ExternalReport {
            points: n,
            runs: runs.len() as u64,
            ..ExternalReport::default()
        };
        // Merge passes until one can write the file.
        let mut runs = runs;
        let buffer = self.stream_buffer::<S, T, D>();
        while runs.len() > FAN_IN {
            report.passes += 1;
            let mut merged = Vec::new();
            for group in runs.chunks(FAN_IN) {
                let path = spill.path();
                let file = File::create(&path).map_err(io(&path))?;
                let mut w = BufWriter::with_capacity(buffer, file);
                let mut count = 0u64;
                merge::<S, T, D>(group, buffer, |_, record| {
                    count += 1;
                    w.write_all(record)
                })?;
                w.flush().map_err(io(&path))?;
                spill.add(path.clone(), count * Layout::<S, T, D>::RECORD as u64);
                for (p, _) in group {
                    spill.remove(p);
                }
                merged.push((path, count));
            }
            runs = merged;
        }
        report.passes += 1;
        let (file_bytes, slots) =
            self.write_file::<S, T, D>(&runs, &geometry, domain, n, max_depth, buffer, out)?;
        for (p, _) in &runs {
            spill.remove(p);
        }
        report.spilled_bytes = spill.written;
        report.peak_temp_bytes = spill.peak;
        report.file_bytes = file_bytes;
        report.slots = slots;
        Ok(report)
    }

    /// The buffer of each stream in a merge: an eighth of the budget shared among the inputs
    /// and outputs, at least one record, at most 1 MiB.
    fn stream_buffer<S: Pod, T: Pod, const D: usize>(&self) -> usize {
        let share = self.budget / 8 / (FAN_IN as u64 + 3);
        (share.min(1 << 20) as usize).max(Layout::<S, T, D>::RECORD)
    }

    /// Pass 2: the points in runs of [`ExternalBuild::run_points`], each sorted by (key,
    /// index) and spilled; returns the run files and their point counts, in input order.
    /// Each point is checked against pass 1's count and `bounds` (see [`ExternalBuild::write`]).
    fn spill_runs<S, T, I, const D: usize>(
        &self,
        source: &mut impl FnMut() -> I,
        geometry: &RootGeometry<D>,
        bounds: &Aabb<f64, D>,
        n: u64,
        spill: &mut Spill,
    ) -> Result<Vec<(PathBuf, u64)>, ExternalError>
    where
        S: SavedScalar,
        T: Pod,
        I: IntoIterator<Item = ([S; D], T)>,
    {
        let cap = self.run_points::<S, T, D>().min(n.max(1)) as usize;
        let mut entries: Vec<([S; D], T)> = Vec::with_capacity(cap);
        let mut order: Vec<(u64, u32)> = Vec::with_capacity(cap);
        let mut runs = Vec::new();
        let mut seen = 0u64;
        let changed = |second| ExternalError::SourceChanged { first: n, second };
        let mut flush = |entries: &mut Vec<([S; D], T)>,
                         order: &mut Vec<(u64, u32)>,
                         spill: &mut Spill|
         -> Result<(), ExternalError> {
            order.sort_unstable();
            let path = spill.path();
            let file = File::create(&path).map_err(io(&path))?;
            let mut w = BufWriter::with_capacity(1 << 16, file);
            for &(key, i) in order.iter() {
                let (p, item) = &entries[i as usize];
                Layout::<S, T, D>::put(&mut w, key, p, item).map_err(io(&path))?;
            }
            w.flush().map_err(io(&path))?;
            let count = entries.len() as u64;
            spill.add(path.clone(), count * Layout::<S, T, D>::RECORD as u64);
            runs.push((path, count));
            entries.clear();
            order.clear();
            Ok(())
        };
        for (p, item) in source() {
            seen += 1;
            if seen > n {
                return Err(changed(seen));
            }
            check_again(&p, bounds, (seen - 1) as usize)?;
            order.push((geometry.scalar_key(&p), entries.len() as u32));
            entries.push((p, item));
            if entries.len() == cap {
                flush(&mut entries, &mut order, spill)?;
            }
        }
        if seen != n {
            return Err(changed(seen));
        }
        if !entries.is_empty() {
            flush(&mut entries, &mut order, spill)?;
        }
        Ok(runs)
    }

    /// The last merge into the saved file at `out`; returns its length and node slots.
    #[allow(clippy::too_many_arguments)]
    fn write_file<S: SavedScalar, T: Pod, const D: usize>(
        &self,
        runs: &[(PathBuf, u64)],
        geometry: &RootGeometry<D>,
        domain: Aabb<f64, D>,
        n: u64,
        max_depth: u8,
        buffer: usize,
        out: &Path,
    ) -> Result<(u64, u64), ExternalError> {
        let fail = io(out);
        let head = sections_start::<D>();
        let point_bytes = n * Layout::<S, T, D>::POINT as u64;
        let items_at = padded(head + point_bytes).expect("in range");
        let item_bytes = n * Layout::<S, T, D>::ITEM as u64;
        let mut points = BufWriter::with_capacity(buffer, File::create(out).map_err(&fail)?);
        points.seek(SeekFrom::Start(head)).map_err(&fail)?;
        let second = OpenOptions::new().write(true).open(out).map_err(&fail)?;
        let mut items = BufWriter::with_capacity(buffer, second);
        items.seek(SeekFrom::Start(items_at)).map_err(&fail)?;
        let mut topology = super::topology::Topology::<D>::new(self.bucket_size, max_depth);
        let mut last = None;
        let (p_len, i_len) = (Layout::<S, T, D>::POINT, Layout::<S, T, D>::ITEM);
        merge::<S, T, D>(runs, buffer, |key, record| {
            topology.push(key, last);
            last = Some(key);
            points.write_all(&record[8..8 + p_len])?;
            items.write_all(&record[8 + p_len..8 + p_len + i_len])
        })?;
        topology.finish();
        let raw = topology.tree.raw_parts();
        write_section(&mut points, head + point_bytes, &[]).map_err(&fail)?;
        points.flush().map_err(&fail)?;
        let mut at = write_section(&mut items, items_at + item_bytes, &[]).map_err(&fail)?;
        let (half_lo, half_side) = geometry.halves();
        let header = Header::<D> {
            max_depth,
            depth: raw.depth,
            balanced: None,
            item_size: Layout::<S, T, D>::ITEM as u32,
            item_align: core::mem::align_of::<T>() as u32,
            points: n,
            slots: topology.slots(),
            free_blocks: 0,
            bucket_size: self.bucket_size as u64,
            half_side,
            half_lo,
            domain,
            live_blocks: raw.live_blocks.to_vec(),
        };
        let sections: [&[u8]; 5] = [
            bytemuck::cast_slice(topology.runs.ends()),
            bytemuck::cast_slice(raw.first_child),
            raw.level,
            bytemuck::cast_slice(raw.block_parent),
            &[],
        ];
        for s in sections {
            at = write_section(&mut items, at, s).map_err(&fail)?;
        }
        items.seek(SeekFrom::Start(0)).map_err(&fail)?;
        items.write_all(&header.encode::<S>()).map_err(&fail)?;
        items.flush().map_err(&fail)?;
        Ok((at, topology.slots()))
    }
}

/// Point `index` of pass 2 checked against pass 1's `bounds`: the root cube and the domain
/// written in the header were chosen from them, and the key is taken in that cube, so a point
/// outside them (or not finite, or not exact in `f64`) would give a file whose reader refuses
/// it ("a point lies outside the domain").
///
/// # Errors
/// [`ExternalError::PointChanged`] naming the point, axis, value and bounds;
/// [`ExternalError::Build`] for a coordinate that is not finite or has no exact `f64`.
fn check_again<S: SavedScalar, const D: usize>(
    p: &[S; D],
    bounds: &Aabb<f64, D>,
    index: usize,
) -> Result<(), ExternalError> {
    match Error::check_input(p, Some(bounds), index) {
        Ok(_) => Ok(()),
        Err(Error::OutsideRootBox {
            index,
            axis,
            value,
            interval,
        }) => Err(ExternalError::PointChanged {
            index,
            axis,
            value,
            bounds: interval,
        }),
        Err(e) => Err(ExternalError::Build(e)),
    }
}
