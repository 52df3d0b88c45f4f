//! The few collectives [`crate::dist`] uses, over rsmpi, on 8-byte words: gather, reduce,
//! broadcast, the agreement on a failing rank, and the all-to-all exchange (`MPI_Alltoallv`)
//! whose sizes are agreed on before any data moves. Records of any `Pod` type travel as
//! words ([`Words`]): one message per destination, whatever the record holds.

use super::DistError;
use bytemuck::Pod;
use mpi::collective::SystemOperation;
use mpi::datatype::{Partition, PartitionMut};
use mpi::traits::*;
use mpi::Count;

/// The most words one rank sends or receives in one exchange: MPI counts and displacements
/// are `i32`.
pub(crate) const MAX_WORDS: u64 = i32::MAX as u64;

/// This rank and the number of ranks.
pub(crate) fn rank_size(comm: &impl Communicator) -> (usize, usize) {
    (comm.rank() as usize, comm.size() as usize)
}

/// Every rank's `mine` (the same length on every rank), in rank order.
pub(crate) fn all_gather(comm: &impl Communicator, mine: &[u64]) -> Vec<u64> {
    let mut out = vec![0u64; mine.len() * comm.size() as usize];
    comm.all_gather_into(mine, &mut out[..]);
    out
}

/// The sum over ranks of `mine`, element by element.
pub(crate) fn all_sum(comm: &impl Communicator, mine: &[u64]) -> Vec<u64> {
    let mut out = vec![0u64; mine.len()];
    comm.all_reduce_into(mine, &mut out[..], SystemOperation::sum());
    out
}

/// The lowest rank on which `failed` holds, agreed on by every rank.
pub(crate) fn lowest_failing(comm: &impl Communicator, failed: bool) -> Option<usize> {
    let (rank, size) = rank_size(comm);
    let mine = if failed { rank as u64 } else { size as u64 };
    let mut low = 0u64;
    comm.all_reduce_into(&mine, &mut low, SystemOperation::min());
    (low < size as u64).then_some(low as usize)
}

/// `words` as rank `root` has them, on every rank (any length: the length goes first).
pub(crate) fn broadcast(comm: &impl Communicator, root: usize, words: &mut Vec<u64>) {
    let process = comm.process_at_rank(root as i32);
    let mut len = words.len() as u64;
    process.broadcast_into(&mut len);
    words.resize(len as usize, 0);
    process.broadcast_into(&mut words[..]);
}

/// Every rank's `mine` (any length, at most [`MAX_WORDS`] in all), concatenated in rank order,
/// with each rank's length.
pub(crate) fn all_gather_var(comm: &impl Communicator, mine: &[u64]) -> (Vec<u64>, Vec<usize>) {
    let counts: Vec<usize> = all_gather(comm, &[mine.len() as u64])
        .into_iter()
        .map(|c| c as usize)
        .collect();
    let (c, d) = counts_displs(&counts);
    let mut out = vec![0u64; counts.iter().sum()];
    comm.all_gather_varcount_into(mine, &mut PartitionMut::new(&mut out[..], c, &d[..]));
    (out, counts)
}

/// MPI counts and displacements for parts of `counts` words (each sum checked by the caller).
fn counts_displs(counts: &[usize]) -> (Vec<Count>, Vec<Count>) {
    let mpi = |v: &[usize]| v.iter().map(|&c| c as Count).collect();
    (mpi(counts), mpi(&starts(counts)))
}

/// Where each of consecutive parts `counts` long starts (the sums of the counts before it).
pub(crate) fn starts(counts: &[usize]) -> Vec<usize> {
    counts
        .iter()
        .scan(0, |at, &c| {
            *at += c;
            Some(*at - c)
        })
        .collect()
}

/// The all-to-all exchange: `send` holds the words for rank 0, then rank 1, ..., `send_counts`
/// words each; returns the words received, from rank 0 first, and how many came from each
/// rank. The counts travel first; if any rank would send or receive more than [`MAX_WORDS`],
/// every rank returns [`DistError::MessageTooLarge`] naming the lowest such rank, and no data
/// moves.
///
/// # Errors
/// [`DistError::MessageTooLarge`].
pub(crate) fn exchange(
    comm: &impl Communicator,
    send: &[u64],
    send_counts: &[usize],
) -> Result<(Vec<u64>, Vec<usize>), DistError> {
    let size = comm.size() as usize;
    debug_assert_eq!(send_counts.len(), size);
    let out: Vec<u64> = send_counts.iter().map(|&c| c as u64).collect();
    let mut incoming = vec![0u64; size];
    comm.all_to_all_into(&out[..], &mut incoming[..]);
    let recv_counts: Vec<usize> = incoming.iter().map(|&c| c as usize).collect();
    let words = (send.len() as u64).max(incoming.iter().sum());
    if let Some(rank) = lowest_failing(comm, words > MAX_WORDS) {
        let mut w = vec![words];
        broadcast(comm, rank, &mut w);
        return Err(DistError::MessageTooLarge {
            rank,
            words: w[0],
            limit: MAX_WORDS,
        });
    }
    let (sc, sd) = counts_displs(send_counts);
    let (rc, rd) = counts_displs(&recv_counts);
    let mut recv = vec![0u64; recv_counts.iter().sum()];
    comm.all_to_all_varcount_into(
        &Partition::new(send, &sc[..], &sd[..]),
        &mut PartitionMut::new(&mut recv[..], &rc[..], &rd[..]),
    );
    Ok((recv, recv_counts))
}

/// Records packed into 8-byte words, a fixed number per record: each field's bytes in turn,
/// the record padded to whole words.
pub(crate) struct Words {
    /// The words of every record.
    pub(crate) words: Vec<u64>,
    /// Words per record.
    pub(crate) per: usize,
}

impl Words {
    /// Room for `n` records of `bytes` bytes each.
    pub(crate) fn with_records(n: usize, bytes: usize) -> Self {
        let per = bytes.div_ceil(8).max(1);
        Words {
            words: vec![0; n * per],
            per,
        }
    }

    /// The all-to-all exchange of records ([`exchange`]): `counts[r]` records, in order, go to
    /// rank r; returns the records received, from rank 0 first, and how many came from each
    /// rank. These records' memory is given back before the received ones are read.
    ///
    /// # Errors
    /// [`DistError::MessageTooLarge`].
    pub(crate) fn exchange(
        self,
        comm: &impl Communicator,
        counts: &[usize],
    ) -> Result<(Words, Vec<usize>), DistError> {
        let per = self.per;
        let counts: Vec<usize> = counts.iter().map(|c| c * per).collect();
        let (words, from) = exchange(comm, &self.words, &counts)?;
        Ok((Words { words, per }, from.iter().map(|w| w / per).collect()))
    }

    /// The number of records.
    pub(crate) fn len(&self) -> usize {
        self.words.len() / self.per
    }

    /// A writer into record `i`.
    pub(crate) fn writer(&mut self, i: usize) -> Writer<'_> {
        let per = self.per;
        Writer {
            bytes: bytemuck::cast_slice_mut(&mut self.words[i * per..(i + 1) * per]),
            at: 0,
        }
    }

    /// A reader of record `i`.
    pub(crate) fn reader(&self, i: usize) -> Reader<'_> {
        Reader {
            bytes: bytemuck::cast_slice(&self.words[i * self.per..(i + 1) * self.per]),
            at: 0,
        }
    }
}

/// Writes the fields of one record in turn.
pub(crate) struct Writer<'a> {
    bytes: &'a mut [u8],
    at: usize,
}

impl Writer<'_> {
    /// Appends `value`'s bytes (a point's: its coordinates in turn).
    #[inline]
    pub(crate) fn put<P: Pod>(&mut self, value: &P) -> &mut Self {
        let b = bytemuck::bytes_of(value);
        self.bytes[self.at..self.at + b.len()].copy_from_slice(b);
        self.at += b.len();
        self
    }
}

/// Reads the fields of one record in turn.
pub(crate) struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    /// The next field (a point: its coordinates in turn).
    #[inline]
    pub(crate) fn get<P: Pod>(&mut self) -> P {
        let n = core::mem::size_of::<P>();
        let v = bytemuck::pod_read_unaligned(&self.bytes[self.at..self.at + n]);
        self.at += n;
        v
    }
}

/// The bytes of a point of `D` coordinates of type `S`.
pub(crate) const fn point_bytes<S, const D: usize>() -> usize {
    D * core::mem::size_of::<S>()
}
