//! The claims of a LAS header that the `las` and `laz` crates trust, checked against the file's
//! length before the `las` crate reads past the fixed header: the end of the point records (the
//! crate multiplies the count by the record length, which can overflow), the record length of
//! the first EVLR (allocated before it is read) and, in a LAZ file, the LASzip items (the
//! decoder is built from them), the chunk table's place and count (that many entries are
//! reserved and decoded) and the byte count of every layer of a layered chunk (allocated before
//! the layer is read); and the frame of scale factors and offsets that gives the points their
//! world coordinates. Each is refused with the field, its byte offset and the limit it broke,
//! so a lying header costs neither a panic nor memory beyond the file's bytes.

use super::{las_error, LasError};
use crate::cloud::Frame;
use ::las::raw;
use std::io::{Read, Seek, SeekFrom};

/// Byte offset of the legacy point count (`u32`).
const LEGACY_POINT_COUNT_AT: u64 = 107;
/// Byte offset of the LAS 1.4 point count (`u64`).
const POINT_COUNT_AT: u64 = 247;
/// Byte offset of the start of the first EVLR (`u64`).
const FIRST_EVLR_AT: u64 = 235;
/// Bytes of an EVLR's header, whose record length (`u64`) is at byte 20.
const EVLR_HEADER: u64 = 60;
/// Bytes of a VLR's header, whose record length (`u16`) is at byte 20.
const VLR_HEADER: u64 = 54;
/// The user id and record id of the LASzip VLR, which describes a LAZ file's compression.
const LASZIP_USER_ID: &[u8] = b"laszip encoded";
const LASZIP_RECORD_ID: u16 = 22204;
/// LASzip's compressor without chunks (and without a chunk table).
const POINT_WISE: u16 = 1;

fn field(name: &'static str, offset: u64, found: impl ToString, expected: String) -> LasError {
    LasError::Field {
        field: name,
        offset,
        found: found.to_string(),
        expected,
    }
}

/// `N` bytes at `at`, or `None` when the file ends before them.
fn bytes_at<const N: usize, R: Read + Seek>(
    input: &mut R,
    at: u64,
    length: u64,
) -> Result<Option<[u8; N]>, LasError> {
    if at.checked_add(N as u64).is_none_or(|end| end > length) {
        return Ok(None);
    }
    input.seek(SeekFrom::Start(at))?;
    let mut b = [0u8; N];
    input.read_exact(&mut b)?;
    Ok(Some(b))
}

/// Reads the raw header of the `length` bytes of `input` and checks the claims the `las` and
/// `laz` crates trust (see the module doc); `input`'s position is left anywhere.
///
/// # Errors
/// [`LasError::Las`] for a header the `las` crate refuses, [`LasError::Field`] for a point
/// count whose records end beyond 2^64 bytes, a scale factor that is 0 or not finite, an
/// offset that is not finite, a first EVLR that starts or ends beyond the file,
/// LASzip items other than the point format's, a LAZ chunk table outside the file or claiming
/// more chunks than there are bytes of compressed points, or a layer longer than the bytes left;
/// [`LasError::Io`] when reading fails.
pub(super) fn checked_header<R: Read + Seek>(
    input: &mut R,
    length: u64,
) -> Result<raw::Header, LasError> {
    input.seek(SeekFrom::Start(0))?;
    let header = raw::Header::read_from(&mut *input).map_err(las_error(None))?;
    // Where the `las` crate reads the VLRs from: after the fields of the header's version and
    // its declared size, whatever that size says.
    let vlrs = input.stream_position()?;
    let start = u64::from(header.offset_to_point_data);
    let record = u64::from(header.point_data_record_length);
    // The count the `las` crate uses: the legacy one unless it is 0.
    let (count, count_at) = match header.large_file {
        Some(large) if header.number_of_point_records == 0 => {
            (large.number_of_point_records, POINT_COUNT_AT)
        }
        _ => (
            u64::from(header.number_of_point_records),
            LEGACY_POINT_COUNT_AT,
        ),
    };
    if count
        .checked_mul(record)
        .and_then(|bytes| bytes.checked_add(start))
        .is_none()
    {
        return Err(field(
            "number of point records",
            count_at,
            count,
            format!(
                "at most {} records of {record} bytes",
                (u64::MAX - start) / record
            ),
        ));
    }
    check_frame(&frame_of(&header))?;
    if let Some(evlr) = header.evlr {
        let at = evlr.start_of_first_evlr;
        let Some(len) = bytes_at::<8, R>(input, at.saturating_add(20), length)?
            .filter(|_| at + EVLR_HEADER <= length)
        else {
            return Err(field(
                "start of first EVLR",
                FIRST_EVLR_AT,
                at,
                format!("an EVLR header of {EVLR_HEADER} bytes within the file's {length}"),
            ));
        };
        let len = u64::from_le_bytes(len);
        let room = length - (at + EVLR_HEADER);
        if len > room {
            return Err(field(
                "EVLR record length",
                at + 20,
                len,
                format!("at most the {room} bytes after its header"),
            ));
        }
    }
    if let Ok(format) = ::las::point::Format::new(header.point_data_record_format)
        && format.is_compressed
    {
        check_laz(input, &header, vlrs, format, count, length)?;
    }
    Ok(header)
}

/// Byte offset of the x scale factor (`f64`); y and z follow, then the three offsets.
const SCALE_AT: u64 = 131;

/// The frame that turns the records' integers into world coordinates: each scale factor finite
/// and not zero (a zero collapses an axis, a NaN or an infinity gives no coordinate at all),
/// each offset finite. The writer checks a cloud's frame by the same rule, so that no file it
/// writes is one the readers refuse.
pub(super) fn check_frame(frame: &Frame) -> Result<(), LasError> {
    for (a, name) in ["x", "y", "z"].into_iter().enumerate() {
        let scale = frame.scale[a];
        if !scale.is_finite() || scale == 0.0 {
            return Err(field(
                ["x scale factor", "y scale factor", "z scale factor"][a],
                SCALE_AT + 8 * a as u64,
                scale,
                format!("a finite {name} scale other than 0"),
            ));
        }
        if !frame.offset[a].is_finite() {
            return Err(field(
                ["x offset", "y offset", "z offset"][a],
                SCALE_AT + 24 + 8 * a as u64,
                frame.offset[a],
                format!("a finite {name} offset"),
            ));
        }
    }
    Ok(())
}

/// The frame of a header's scale factors and offsets.
pub(super) fn frame_of(h: &raw::Header) -> Frame {
    Frame {
        scale: [h.x_scale_factor, h.y_scale_factor, h.z_scale_factor],
        offset: [h.x_offset, h.y_offset, h.z_offset],
    }
}

/// The fields of a LASzip VLR this reader checks (see [`check_laz`]).
struct Laszip {
    /// The byte offset of the VLR's data.
    at: u64,
    compressor: u16,
    /// Points per chunk (u32::MAX: each chunk's count is in the chunk table).
    chunk_size: u32,
    /// The items: type, size and version.
    items: Vec<[u16; 3]>,
}

/// The file's LASzip VLR, if the VLRs the header declares (from byte `at`) hold one within the
/// file (the `las` crate reports VLRs that do not fit, and a LAZ file without the VLR).
fn laszip_vlr<R: Read + Seek>(
    input: &mut R,
    header: &raw::Header,
    mut at: u64,
    length: u64,
) -> Result<Option<Laszip>, LasError> {
    // Each VLR takes at least its header, so the walk ends within length / 54 steps.
    for _ in 0..header.number_of_variable_length_records {
        let Some(vlr) = bytes_at::<{ VLR_HEADER as usize }, R>(input, at, length)? else {
            return Ok(None);
        };
        let user_id = &vlr[2..18];
        let record_id = u16::from_le_bytes([vlr[18], vlr[19]]);
        let len = u64::from(u16::from_le_bytes([vlr[20], vlr[21]]));
        at += VLR_HEADER;
        // The user id up to its first zero, as the `las` crate compares it.
        let user_id = &user_id[..user_id.iter().position(|&b| b == 0).unwrap_or(16)];
        if user_id == LASZIP_USER_ID && record_id == LASZIP_RECORD_ID {
            if at + len > length || len < 34 {
                return Ok(None);
            }
            let mut data = vec![0u8; len as usize];
            input.seek(SeekFrom::Start(at))?;
            input.read_exact(&mut data)?;
            let word = |i: usize| u16::from_le_bytes([data[i], data[i + 1]]);
            let count = usize::from(word(32));
            let items = (0..count)
                .map_while(|k| {
                    let i = 34 + 6 * k;
                    (i + 6 <= data.len()).then(|| [word(i), word(i + 2), word(i + 4)])
                })
                .collect();
            return Ok(Some(Laszip {
                at,
                compressor: word(0),
                chunk_size: u32::from_le_bytes([data[12], data[13], data[14], data[15]]),
                items,
            }));
        }
        at += len;
    }
    Ok(None)
}

/// LASzip item types (the `laz` crate's codes) and their sizes.
const POINT10: [u16; 2] = [6, 20];
const GPS_TIME: [u16; 2] = [7, 8];
const RGB12: [u16; 2] = [8, 6];
const WAVE_PACKET13: [u16; 2] = [9, 29];
const POINT14: [u16; 2] = [10, 30];
const RGB14: [u16; 2] = [11, 6];
const RGBNIR14: [u16; 2] = [12, 8];
const WAVE_PACKET14: [u16; 2] = [13, 29];
const BYTE: u16 = 0;
const BYTE14: u16 = 14;
/// The layers of a layered chunk per item type: `Point14` 9, `RGBNIR14` 2 (colour and NIR),
/// one per byte for extra bytes, 1 for the others.
fn layers(item: [u16; 2]) -> u64 {
    match item {
        POINT14 => 9,
        RGBNIR14 => 2,
        [BYTE14, n] => u64::from(n),
        _ => 1,
    }
}

/// The optional LASzip items in the order LASzip writes them, each with the point formats that
/// carry it.
const OPTIONAL_ITEMS: [(&[u8], [u16; 2]); 6] = [
    (&[1, 3, 4, 5], GPS_TIME),
    (&[2, 3, 5], RGB12),
    (&[4, 5], WAVE_PACKET13),
    (&[7], RGB14),
    (&[8, 10], RGBNIR14),
    (&[9, 10], WAVE_PACKET14),
];

/// The LASzip items of a point format with `extra` extra bytes (as LASzip writes them), each
/// with the versions the `laz` crate decodes.
fn items_of(format: u8, extra: u16) -> (Vec<[u16; 2]>, [u16; 2]) {
    let legacy = format <= 5;
    let mut items = vec![if legacy { POINT10 } else { POINT14 }];
    let optional = OPTIONAL_ITEMS
        .iter()
        .filter(|(formats, _)| formats.contains(&format));
    items.extend(optional.map(|&(_, item)| item));
    if extra > 0 {
        items.push([if legacy { BYTE } else { BYTE14 }, extra]);
    }
    (items, if legacy { [1, 2] } else { [3, 4] })
}

/// Checks what the `laz` crate trusts in a LAZ file: its LASzip items are those of the point
/// format (the decoder is built from them and has no checks of its own: no items at all panics
/// in it); the chunk table's count ([`check_chunk_count`]); and, for the layered chunks of
/// formats 6-10, that every layer's byte count, which the decoder allocates before reading the
/// layer, fits the bytes left in the file ([`check_layers`]). `count` is the header's points.
fn check_laz<R: Read + Seek>(
    input: &mut R,
    header: &raw::Header,
    vlrs: u64,
    format: ::las::point::Format,
    count: u64,
    length: u64,
) -> Result<(), LasError> {
    let Some(vlr) = laszip_vlr(input, header, vlrs, length)? else {
        return Ok(());
    };
    let id = header.point_data_record_format & 0x3f;
    let record = header.point_data_record_length;
    let (want, versions) = items_of(id, record.saturating_sub(format.len()));
    let found: Vec<[u16; 2]> = vlr.items.iter().map(|&[t, s, _]| [t, s]).collect();
    if found != want || vlr.items.iter().any(|&[_, _, v]| !versions.contains(&v)) {
        return Err(field(
            "LASzip items",
            vlr.at + 32,
            // At most 8 items: the VLR can claim thousands.
            match vlr.items.len() {
                n if n > 8 => format!("{:?}... ({n} items; type, size, version)", &vlr.items[..8]),
                _ => format!("{:?} (type, size, version)", vlr.items),
            },
            format!(
                "the items of point format {id} with records of {record} bytes: {want:?} \
                 (type, size), version {} or {}",
                versions[0], versions[1]
            ),
        ));
    }
    let start = u64::from(header.offset_to_point_data);
    // A point-wise file is one chunk without a table; the others start with the table's
    // offset, and their chunks hold `chunk_size` points (or the table's counts when that is
    // u32::MAX, so the decoder reads at most the table's chunks).
    let (first, chunks) = if vlr.compressor == POINT_WISE {
        (start, 1)
    } else {
        let table = check_chunk_count(input, start, length)?;
        let chunks = match vlr.chunk_size {
            0 => 1,
            u32::MAX => u64::from(table.1),
            size => count.div_ceil(u64::from(size)),
        };
        (start + 8, chunks)
    };
    // The decoder is layered when the items are (formats 6-10), whatever the compressor says.
    if id >= 6 {
        let layers: u64 = want.iter().map(|&item| layers(item)).sum();
        check_layers(input, first, chunks, length, u64::from(record), layers)?;
    }
    Ok(())
}

/// Walks the `chunks` layered chunks from `at`, as the decoder reads them: each is the first
/// record (`record` bytes), a point count, `layers` byte counts and the layers, and each
/// layer's byte count must fit the bytes left in the file's `length`. A chunk whose counts the
/// file cuts short ends the walk (the decoder reports the missing bytes without allocating
/// them).
fn check_layers<R: Read + Seek>(
    input: &mut R,
    mut at: u64,
    chunks: u64,
    length: u64,
    record: u64,
    layers: u64,
) -> Result<(), LasError> {
    let sizes_len = 4 * layers;
    // Each chunk takes its record, count and layer sizes: at most length / 48 steps.
    for _ in 0..chunks {
        let sizes_at = at + record + 4;
        let Some(data) = sizes_at.checked_add(sizes_len).filter(|&e| e <= length) else {
            return Ok(());
        };
        let mut sizes = vec![0u8; sizes_len as usize];
        input.seek(SeekFrom::Start(sizes_at))?;
        input.read_exact(&mut sizes)?;
        let mut next = data;
        for (i, size) in sizes.chunks_exact(4).enumerate() {
            let size = u64::from(u32::from_le_bytes(size.try_into().expect("4 bytes")));
            if size > length - next {
                return Err(field(
                    "LAZ layer size",
                    sizes_at + 4 * i as u64,
                    size,
                    format!("at most the {} bytes left in the file", length - next),
                ));
            }
            next += size;
        }
        at = next;
    }
    Ok(())
}

/// Finds a LAZ file's chunk table as the `laz` crate does (its offset in the first 8 bytes of
/// the point data, or else in the file's last 8 bytes) and checks its chunk count: every chunk
/// but one holds at least one byte of the compressed points between those 8 bytes and the
/// table. The table must lie within the file: when the crate cannot read it, where it goes on
/// reading points depends on how far its failed seeks moved the input. The table's offset and
/// count.
fn check_chunk_count<R: Read + Seek>(
    input: &mut R,
    data_start: u64,
    length: u64,
) -> Result<(u64, u32), LasError> {
    let missing = |found: String| {
        field(
            "offset to the LAZ chunk table",
            data_start,
            found,
            format!(
                "a table after the point data's first 8 bytes and within the file's {length} \
                 (or its offset in the file's last 8 bytes)"
            ),
        )
    };
    let Some(offset) = bytes_at::<8, R>(input, data_start, length)? else {
        return Err(missing("beyond the file's end".into()));
    };
    let mut table = i64::from_le_bytes(offset);
    if table <= data_start as i64 {
        let last = bytes_at::<8, R>(input, length.saturating_sub(8), length)?;
        table = last.map_or(-1, i64::from_le_bytes);
    }
    let chunks = (table > data_start as i64)
        .then(|| bytes_at::<4, R>(input, (table as u64).saturating_add(4), length))
        .transpose()?
        .flatten();
    let Some(chunks) = chunks else {
        return Err(missing(table.to_string()));
    };
    let table = table as u64;
    let chunks = u32::from_le_bytes(chunks);
    let room = table.saturating_sub(data_start + 8);
    if u64::from(chunks) > room + 1 {
        return Err(field(
            "LAZ chunk count",
            table + 4,
            chunks,
            format!(
                "at most {}: one chunk per byte of the {room} bytes of compressed points, and one",
                room + 1
            ),
        ));
    }
    Ok((table, chunks))
}
