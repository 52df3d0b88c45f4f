//! The PLY writer: a header naming the cloud's columns, then one vertex a line (ASCII) or one
//! record (binary), streamed to any writer.

use super::header::FRAME_COMMENT;
use super::{Encoding, Kind, PlyError, FORMATS};
use crate::cloud::{Cloud, Frame};
use crate::geom::Scalar;
use crate::io::columns::{attribute_names, row};
use std::io::{BufWriter, Write};

/// The PLY type that holds every value of `S` exactly: `float`, `double`, or the integer type
/// of its size and sign (64-bit integers as `double`: a cloud holds only values `f64` holds).
fn kind_of<S: Scalar>() -> Kind {
    let half: Option<S> = num_traits::NumCast::from(0.5f64);
    let is_float = half.is_some_and(|h| h.to_f64() == 0.5);
    let signed = <S as num_traits::NumCast>::from(-1i32).is_some();
    match (is_float, core::mem::size_of::<S>(), signed) {
        (true, 4, _) => Kind::F32,
        (true, _, _) => Kind::F64,
        (false, 1, true) => Kind::I8,
        (false, 1, false) => Kind::U8,
        (false, 2, true) => Kind::I16,
        (false, 2, false) => Kind::U16,
        (false, 4, true) => Kind::I32,
        (false, 4, false) => Kind::U32,
        _ => Kind::F64,
    }
}

/// Writes `cloud` as PLY to `out` (buffered here): `x y z` in the type that holds `S`
/// exactly, then `intensity` (ushort), `classification` (uchar), `red green blue` (ushort),
/// `gps_time` (double), `nx ny nz` (float) where present and every extra column (double). A
/// frame other than [`Frame::IDENTITY`] is written as a `comment orthtree frame` line, which
/// [`read`](super::read) restores.
///
/// # Errors
/// [`PlyError::Io`] when writing fails; [`PlyError::Header`] (line 0) when the columns'
/// lengths differ from the points'.
///
/// # Complexity
/// O(n) time, O(1) memory beyond the buffer.
pub fn write<S: Scalar>(
    cloud: &Cloud<S>,
    encoding: Encoding,
    out: impl Write,
) -> Result<(), PlyError> {
    cloud
        .attributes
        .check(cloud.len())
        .map_err(|e| PlyError::Header {
            line: 0,
            message: e.to_string(),
        })?;
    let mut w = BufWriter::with_capacity(1 << 16, out);
    let pos = kind_of::<S>();
    let mut props: Vec<(String, Kind)> = ["x", "y", "z"].map(|n| (n.to_string(), pos)).into();
    props.extend(attribute_names(&cloud.attributes));
    writeln!(w, "ply\nformat {} 1.0", FORMATS[encoding as usize].1)?;
    if cloud.frame != Frame::IDENTITY {
        let (s, o) = (cloud.frame.scale, cloud.frame.offset);
        writeln!(
            w,
            "comment {FRAME_COMMENT} {} {} {} {} {} {}",
            s[0], s[1], s[2], o[0], o[1], o[2]
        )?;
    }
    writeln!(w, "element vertex {}", cloud.len())?;
    for (name, kind) in &props {
        writeln!(w, "property {} {name}", kind.name())?;
    }
    writeln!(w, "end_header")?;
    let mut values = Vec::with_capacity(props.len());
    let mut record = Vec::new();
    for i in 0..cloud.len() {
        row(cloud, i, &mut values);
        record.clear();
        for (v, (_, kind)) in values.iter().zip(&props) {
            encode(*v, *kind, encoding, &mut record);
        }
        if encoding == Encoding::Ascii {
            record.pop(); // the last separator
            record.push(b'\n');
        }
        w.write_all(&record)?;
    }
    Ok(w.flush()?)
}

/// Appends `v` (exact in `kind`) to `out`: text and a space, or its bytes.
fn encode(v: f64, kind: Kind, encoding: Encoding, out: &mut Vec<u8>) {
    use std::io::Write as _;
    macro_rules! bytes {
        ($x:expr) => {
            match encoding {
                Encoding::BinaryBigEndian => out.extend_from_slice(&$x.to_be_bytes()),
                _ => out.extend_from_slice(&$x.to_le_bytes()),
            }
        };
    }
    if encoding == Encoding::Ascii {
        let _ = match kind {
            Kind::F32 => write!(out, "{} ", v as f32),
            Kind::F64 => write!(out, "{v} "),
            _ => write!(out, "{} ", v as i64),
        };
        return;
    }
    match kind {
        Kind::I8 => bytes!(v as i8),
        Kind::U8 => bytes!(v as u8),
        Kind::I16 => bytes!(v as i16),
        Kind::U16 => bytes!(v as u16),
        Kind::I32 => bytes!(v as i32),
        Kind::U32 => bytes!(v as u32),
        Kind::F32 => bytes!(v as f32),
        Kind::F64 => bytes!(v),
    }
}
