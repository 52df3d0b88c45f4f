//! The header of a saved point tree and the layout of the sections after it (see the format
//! table in the module doc of [`super`]): encoded in one pass, decoded field by field with each
//! field's byte offset, and the section layout computed with checked arithmetic so that every
//! count is compared with the bytes available before anything is allocated; then each section's
//! span for the readers, and a section written with its zero padding for the writers.

use super::{SavedError, SavedScalar};
use crate::geom::{Aabb, Cell, Connectivity, Dim};
use crate::tree::BalanceOptions;
use std::io::Write;

/// The first 8 bytes of every saved tree.
pub const MAGIC: [u8; 8] = *b"ORTHTREE";
/// The format version this crate writes and reads.
pub const VERSION: u16 = 1;
/// The tree kind of a [`PointTree`](crate::PointTree).
pub(super) const KIND_POINT_TREE: u8 = 1;
/// Every section starts at a multiple of this, so that a slice of any item type of alignment
/// up to 16 can be cast in place from a buffer aligned to 16 (a memory map is).
pub const ALIGN: u64 = 16;

/// Byte offsets of the fixed fields.
const FIXED: u64 = 72;

/// The header's fields, as written and as read (after the range checks of [`Header::decode`]).
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Header<const D: usize> {
    pub max_depth: u8,
    pub depth: u8,
    pub balanced: Option<BalanceOptions>,
    pub item_size: u32,
    pub item_align: u32,
    pub points: u64,
    pub slots: u64,
    pub free_blocks: u64,
    pub bucket_size: u64,
    pub half_side: f64,
    pub half_lo: [f64; D],
    pub domain: Aabb<f64, D>,
    pub live_blocks: Vec<u32>,
}

/// The number of live-block counts: one per level 0..=MAX_LEVEL.
pub(super) fn levels<const D: usize>() -> u64 {
    Cell::<D>::MAX_LEVEL as u64 + 1
}

/// The header's length before its padding.
pub(super) fn header_len<const D: usize>() -> u64 {
    FIXED + 24 * D as u64 + 4 * levels::<D>()
}

/// `x` rounded up to a multiple of [`ALIGN`] (`None` on overflow).
pub(super) fn padded(x: u64) -> Option<u64> {
    x.checked_add(ALIGN - 1).map(|y| y / ALIGN * ALIGN)
}

/// Where the first section starts: the header's length, padded.
pub(super) fn sections_start<const D: usize>() -> u64 {
    padded(header_len::<D>()).expect("a short header")
}

/// `Ok` when the padding `pad`, which starts at byte `at`, is all zero, else the
/// [`SavedError::Padding`] naming its first other byte.
pub(super) fn zero_padding(pad: &[u8], at: u64) -> Result<(), SavedError> {
    match pad.iter().position(|&b| b != 0) {
        Some(i) => Err(SavedError::Padding {
            offset: at + i as u64,
        }),
        None => Ok(()),
    }
}

/// Writes `bytes` at offset `at` of `out`, then zeros up to the next multiple of [`ALIGN`];
/// the offset after them.
pub(super) fn write_section(out: &mut impl Write, at: u64, bytes: &[u8]) -> std::io::Result<u64> {
    out.write_all(bytes)?;
    let end = at + bytes.len() as u64;
    let next = padded(end).expect("in range");
    out.write_all(&[0u8; ALIGN as usize][..(next - end) as usize])?;
    Ok(next)
}

/// The header's balance bytes: 0 and 0 without balance, else 1 + the connectivity's place in
/// [`Connectivity::ALL`] (face 1, edge 2, corner 3) and the level difference.
fn balance_code(b: Option<BalanceOptions>) -> (u8, u8) {
    b.map_or((0, 0), |o| {
        let place = Connectivity::ALL.iter().position(|&c| c == o.connectivity);
        (
            1 + place.expect("every connectivity") as u8,
            o.max_level_difference(),
        )
    })
}

impl<const D: usize> Header<D> {
    /// The header's bytes, padded to [`ALIGN`].
    pub(super) fn encode<S: SavedScalar>(&self) -> Vec<u8> {
        let mut b = Vec::with_capacity(header_len::<D>() as usize + ALIGN as usize);
        b.extend_from_slice(&MAGIC);
        b.extend_from_slice(&VERSION.to_le_bytes());
        let (code, difference) = balance_code(self.balanced);
        b.extend_from_slice(&[
            KIND_POINT_TREE,
            D as u8,
            S::KIND,
            self.max_depth,
            self.depth,
            code,
            difference,
        ]);
        b.extend_from_slice(&[0; 3]);
        b.extend_from_slice(&self.item_size.to_le_bytes());
        b.extend_from_slice(&self.item_align.to_le_bytes());
        b.extend_from_slice(&0u32.to_le_bytes());
        for x in [self.points, self.slots, self.free_blocks, self.bucket_size] {
            b.extend_from_slice(&x.to_le_bytes());
        }
        b.extend_from_slice(&self.half_side.to_le_bytes());
        for x in self
            .half_lo
            .iter()
            .chain(&self.domain.min)
            .chain(&self.domain.max)
        {
            b.extend_from_slice(&x.to_le_bytes());
        }
        for x in &self.live_blocks {
            b.extend_from_slice(&x.to_le_bytes());
        }
        debug_assert_eq!(b.len() as u64, header_len::<D>());
        b.resize(padded(b.len() as u64).expect("a short header") as usize, 0);
        b
    }

    /// The header of `bytes` (the file's first bytes, at most the padded header; `available`
    /// is the length of the whole input), for points of `S` and items of size `item_size` and
    /// alignment `item_align`.
    ///
    /// # Errors
    /// [`SavedError::Truncated`] naming the first field cut short, [`SavedError::Field`] for a
    /// field that is not what this reader expects or out of range, [`SavedError::Padding`].
    pub(super) fn decode<S: SavedScalar>(
        bytes: &[u8],
        available: u64,
        item_size: usize,
        item_align: usize,
    ) -> Result<Self, SavedError> {
        let mut r = Fields {
            bytes,
            at: 0,
            available,
        };
        let magic = r.take::<8>("magic")?;
        let (found, want) = (format!("{magic:?}"), format!("{MAGIC:?}"));
        ensure(magic == MAGIC, "magic", 0, found, want)?;
        let version = u16::from_le_bytes(r.take("version")?);
        ensure(version == VERSION, "version", 8, version, VERSION)?;
        let kind = r.byte("tree kind")?;
        if kind != KIND_POINT_TREE {
            return Err(field("tree kind", 10, kind, "1 (a point tree)"));
        }
        let dimension = r.byte("dimension")?;
        ensure(dimension as usize == D, "dimension", 11, dimension, D)?;
        let scalar = r.byte("scalar")?;
        let name = format!("{} ({})", S::KIND, S::NAME);
        ensure(scalar == S::KIND, "scalar", 12, scalar, name)?;
        let deepest = Cell::<D>::MAX_LEVEL;
        let limit = format!("at most {deepest}");
        let max_depth = r.byte("max depth")?;
        ensure(max_depth <= deepest, "max depth", 13, max_depth, &limit)?;
        let depth = r.byte("depth")?;
        ensure(depth <= deepest, "depth", 14, depth, &limit)?;
        let code = r.byte("balance")?;
        let difference = r.byte("level difference")?;
        let balanced = decode_balance(code, difference)?;
        for _ in 0..3 {
            r.zero("reserved")?;
        }
        let size = u32::from_le_bytes(r.take("item size")?);
        ensure(size as usize == item_size, "item size", 20, size, item_size)?;
        let align = u32::from_le_bytes(r.take("item alignment")?);
        if align as usize != item_align {
            return Err(field("item alignment", 24, align, item_align));
        }
        for _ in 0..4 {
            r.zero("reserved")?;
        }
        let points = u64::from_le_bytes(r.take("points")?);
        if points > u64::from(u32::MAX) {
            return Err(field("points", 32, points, "at most 2^32 - 1"));
        }
        let slots = u64::from_le_bytes(r.take("node slots")?);
        let children = Dim::<D>::CHILDREN as u64;
        if slots == 0 || slots > u64::from(u32::MAX) || (slots - 1) % children != 0 {
            let rule = format!("1 + a multiple of {children}, below 2^32");
            return Err(field("node slots", 40, slots, rule));
        }
        let free_blocks = u64::from_le_bytes(r.take("free blocks")?);
        if free_blocks > (slots - 1) / children {
            let limit = format!("at most the {} blocks", (slots - 1) / children);
            return Err(field("free blocks", 48, free_blocks, limit));
        }
        let bucket_size = u64::from_le_bytes(r.take("bucket size")?);
        if bucket_size == 0 || usize::try_from(bucket_size).is_err() {
            return Err(field("bucket size", 56, bucket_size, "at least 1, a usize"));
        }
        let half_side = f64::from_le_bytes(r.take("half side")?);
        let half_lo = r.floats::<D>("half lower corner")?;
        let min = r.floats::<D>("domain minimum")?;
        let max = r.floats::<D>("domain maximum")?;
        let mut live_blocks = Vec::with_capacity(levels::<D>() as usize);
        for _ in 0..levels::<D>() {
            live_blocks.push(u32::from_le_bytes(r.take("live blocks")?));
        }
        while r.at < sections_start::<D>() {
            r.zero("header padding")?;
        }
        Ok(Header {
            max_depth,
            depth,
            balanced,
            item_size: size,
            item_align: align,
            points,
            slots,
            free_blocks,
            bucket_size,
            half_side,
            half_lo,
            domain: Aabb { min, max },
            live_blocks,
        })
    }

    /// The number of child blocks.
    pub(super) fn blocks(&self) -> u64 {
        (self.slots - 1) / Dim::<D>::CHILDREN as u64
    }

    /// The sections after the header, in file order: name and byte length.
    pub(super) fn sections<S>(&self) -> [(&'static str, Option<u64>); 7] {
        let point = core::mem::size_of::<[S; D]>() as u64;
        [
            ("points", self.points.checked_mul(point)),
            ("items", self.points.checked_mul(u64::from(self.item_size))),
            ("run ends", Some(self.slots * 4)),
            ("first children", Some(self.slots * 4)),
            ("levels", Some(self.slots)),
            ("block parents", Some(self.blocks() * 4)),
            ("free blocks", Some(self.free_blocks * 4)),
        ]
    }

    /// Each section's start and the end of its bytes (before its padding), for lengths checked
    /// by [`Header::check_length`] or of a tree in memory; then the file's length.
    pub(super) fn spans<S>(&self) -> ([(u64, u64); 7], u64) {
        let mut end = sections_start::<D>();
        let spans = self.sections::<S>().map(|(_, len)| {
            let start = end;
            let stop = start + len.expect("checked against the length");
            end = padded(stop).expect("checked");
            (start, stop)
        });
        (spans, end)
    }

    /// The total length of a file with this header, checked against `available` bytes.
    ///
    /// # Errors
    /// [`SavedError::Truncated`] naming the first section the bytes end in (or whose length
    /// overflows), [`SavedError::Trailing`] when bytes follow the last.
    pub(super) fn check_length<S>(&self, available: u64) -> Result<u64, SavedError> {
        let mut end = sections_start::<D>();
        for (name, len) in self.sections::<S>() {
            let start = end;
            end = len
                .and_then(|l| start.checked_add(l))
                .and_then(padded)
                .filter(|&e| e <= available)
                .ok_or(SavedError::Truncated {
                    field: name,
                    offset: start,
                    needed: len.map_or(u64::MAX, |l| start.saturating_add(l)),
                    available,
                })?;
        }
        if available > end {
            return Err(SavedError::Trailing {
                offset: end,
                extra: available - end,
            });
        }
        Ok(end)
    }
}

fn decode_balance(code: u8, difference: u8) -> Result<Option<BalanceOptions>, SavedError> {
    let connectivity = match code {
        0 if difference == 0 => return Ok(None),
        0 => {
            return Err(field(
                "level difference",
                16,
                difference,
                "0 without balance",
            ))
        }
        1..=3 => Connectivity::ALL[usize::from(code) - 1],
        _ => return Err(field("balance", 15, code, "0 to 3")),
    };
    BalanceOptions::new(connectivity)
        .with_max_level_difference(difference)
        .map(Some)
        .map_err(|_| {
            let limit = format!("1 to {}", BalanceOptions::MAX_LEVEL_DIFFERENCE);
            field("level difference", 16, difference, limit)
        })
}

/// `Ok` when `ok`, else the [`SavedError::Field`] of the field `name` at byte `offset`.
fn ensure(
    ok: bool,
    name: &'static str,
    offset: u64,
    found: impl ToString,
    expected: impl ToString,
) -> Result<(), SavedError> {
    ok.then_some(())
        .ok_or_else(|| field(name, offset, found, expected))
}

fn field(
    name: &'static str,
    offset: u64,
    found: impl ToString,
    expected: impl ToString,
) -> SavedError {
    SavedError::Field {
        field: name,
        offset,
        found: found.to_string(),
        expected: expected.to_string(),
    }
}

/// A cursor over the header's bytes that names the field the bytes end in.
struct Fields<'a> {
    bytes: &'a [u8],
    at: u64,
    available: u64,
}

impl Fields<'_> {
    fn take<const N: usize>(&mut self, name: &'static str) -> Result<[u8; N], SavedError> {
        let start = self.at as usize;
        let got = self
            .bytes
            .get(start..start + N)
            .ok_or(SavedError::Truncated {
                field: name,
                offset: self.at,
                needed: self.at + N as u64,
                available: self.available,
            })?;
        self.at += N as u64;
        Ok(got.try_into().expect("N bytes"))
    }

    fn byte(&mut self, name: &'static str) -> Result<u8, SavedError> {
        Ok(self.take::<1>(name)?[0])
    }

    fn zero(&mut self, name: &'static str) -> Result<(), SavedError> {
        let offset = self.at;
        zero_padding(&[self.byte(name)?], offset)
    }

    fn floats<const D: usize>(&mut self, name: &'static str) -> Result<[f64; D], SavedError> {
        let mut out = [0.0; D];
        for x in &mut out {
            *x = f64::from_le_bytes(self.take(name)?);
        }
        Ok(out)
    }
}
