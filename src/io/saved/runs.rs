//! The sorted runs of the out-of-core build ([`super::external`]): their records (key, point,
//! item, packed little-endian), the temporary files that hold them (removed when merged or when
//! the build ends, also on failure), and the merge of several runs by (key, run).

use super::external::ExternalError;
use bytemuck::Pod;
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::fs::File;
use std::io::{BufReader, Read, Write};
use std::path::{Path, PathBuf};

/// The error of a failed read or write of `path`.
pub(super) fn io(path: &Path) -> impl Fn(std::io::Error) -> ExternalError + '_ {
    move |source| ExternalError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Temporary run files, removed when merged or when the build ends (also on failure).
pub(super) struct Spill {
    pub dir: PathBuf,
    pub stem: String,
    pub next: u64,
    pub live: Vec<(PathBuf, u64)>,
    pub written: u64,
    pub peak: u64,
}

impl Spill {
    pub fn path(&mut self) -> PathBuf {
        self.next += 1;
        self.dir.join(format!("{}.run{}.tmp", self.stem, self.next))
    }

    pub fn add(&mut self, path: PathBuf, bytes: u64) {
        self.live.push((path, bytes));
        self.written += bytes;
        let now: u64 = self.live.iter().map(|l| l.1).sum();
        self.peak = self.peak.max(now);
    }

    pub fn remove(&mut self, path: &Path) {
        let _ = std::fs::remove_file(path);
        self.live.retain(|l| l.0 != path);
    }
}

impl Drop for Spill {
    fn drop(&mut self) {
        for (p, _) in &self.live {
            let _ = std::fs::remove_file(p);
        }
    }
}

/// One spilled record: key, point, item (little-endian, packed).
pub(super) struct Layout<S, T, const D: usize>(core::marker::PhantomData<(S, T)>);

impl<S: Pod, T: Pod, const D: usize> Layout<S, T, D> {
    pub const POINT: usize = core::mem::size_of::<[S; D]>();
    pub const ITEM: usize = core::mem::size_of::<T>();
    pub const RECORD: usize = 8 + Self::POINT + Self::ITEM;

    pub fn put(out: &mut impl Write, key: u64, p: &[S; D], item: &T) -> std::io::Result<()> {
        out.write_all(&key.to_le_bytes())?;
        out.write_all(bytemuck::bytes_of(p))?;
        out.write_all(super::bytes_of_items(core::slice::from_ref(item)))
    }
}

/// A sorted run being read in the merge.
struct RunReader {
    input: BufReader<File>,
    record: Vec<u8>,
    left: u64,
}

impl RunReader {
    /// The next record's key (the record in `self.record`), or `None` at the end.
    fn next(&mut self) -> std::io::Result<Option<u64>> {
        if self.left == 0 {
            return Ok(None);
        }
        self.left -= 1;
        self.input.read_exact(&mut self.record)?;
        Ok(Some(u64::from_le_bytes(
            self.record[..8].try_into().expect("8 bytes"),
        )))
    }
}

/// Merges the sorted `runs` (in input order) by (key, run), handing each record's key and
/// bytes to `emit` in order.
pub(super) fn merge<S: Pod, T: Pod, const D: usize>(
    runs: &[(PathBuf, u64)],
    buffer: usize,
    mut emit: impl FnMut(u64, &[u8]) -> std::io::Result<()>,
) -> Result<(), ExternalError> {
    let mut readers = Vec::with_capacity(runs.len());
    let mut heap = BinaryHeap::with_capacity(runs.len());
    for (r, (path, count)) in runs.iter().enumerate() {
        let file = File::open(path).map_err(io(path))?;
        let mut reader = RunReader {
            input: BufReader::with_capacity(buffer, file),
            record: vec![0; Layout::<S, T, D>::RECORD],
            left: *count,
        };
        if let Some(key) = reader.next().map_err(io(path))? {
            heap.push(Reverse((key, r)));
        }
        readers.push(reader);
    }
    while let Some(Reverse((key, r))) = heap.pop() {
        let path = &runs[r].0;
        emit(key, &readers[r].record).map_err(io(path))?;
        if let Some(next) = readers[r].next().map_err(io(path))? {
            heap.push(Reverse((next, r)));
        }
    }
    Ok(())
}
