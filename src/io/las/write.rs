//! The LAS writer: a [`Cloud<i32>`] as LAS 1.4 records, the point format chosen by the columns
//! the cloud has (see [`write_to`]), each value checked against its field's range.

use super::{las_error, Fields, LasError, BATCH_BYTES};
use crate::cloud::{Attributes, Cloud};
use ::las::raw::point::{Flags, ScanAngle};
use ::las::{point::Format, raw, Builder, Header, PointDataBuilder, Transform, Vector, Writer};
use std::io::{Seek, Write};
use std::path::Path;

/// Writes `cloud` as a LAS 1.4 file at `path` (LAZ when `compressed`, with the `laz` feature).
///
/// # Errors
/// As [`write_to`], and [`LasError::Io`] when the file cannot be created.
pub fn write(cloud: &Cloud<i32>, path: impl AsRef<Path>, compressed: bool) -> Result<(), LasError> {
    let file = std::io::BufWriter::new(std::fs::File::create(path)?);
    write_to(cloud, file, compressed).map(|_| ())
}

/// Writes `cloud` as LAS 1.4 to `out` and returns it: point format 0-3 (by GPS time and
/// colour), or 6-8 when the cloud has columns only those formats hold (`overlap`,
/// `scanner_channel`, `scan_angle`, `nir`); missing flag columns are 0, a missing
/// classification 0 and a missing intensity 0.
///
/// # Errors
/// [`LasError::UnsupportedColumn`] for a column no LAS field holds,
/// [`LasError::MissingColumn`] for one the format needs, [`LasError::BadValue`] naming the point
/// and column of a value that does not fit its field, [`LasError::Field`] for a frame with a
/// scale factor of 0 or one that is not finite, or an offset that is not finite (the header
/// field it would be written to), [`LasError::Las`] and
/// [`LasError::Io`] when writing fails.
///
/// # Complexity
/// O(n) time; the records are encoded in batches of 4 MiB.
pub fn write_to<W: Write + Seek + Send + Sync + 'static>(
    cloud: &Cloud<i32>,
    out: W,
    compressed: bool,
) -> Result<W, LasError> {
    let (mut format, fields) = point_format(&cloud.attributes, cloud.len())?;
    format.is_compressed = compressed;
    let header = header(cloud, format)?;
    let transforms = *header.transforms();
    let mut writer = Writer::new(out, header).map_err(las_error(None))?;
    let columns = RecordColumns::new(&cloud.attributes, fields);
    let batch = (BATCH_BYTES / usize::from(format.len())).max(1);
    let mut bytes = Vec::new();
    for start in (0..cloud.len()).step_by(batch) {
        bytes.clear();
        for i in start..(start + batch).min(cloud.len()) {
            columns
                .record(cloud, i)?
                .write_to(&mut bytes, &format)
                .map_err(las_error(Some(i as u64)))?;
        }
        let mut slab_format = format;
        slab_format.is_compressed = false;
        let data = PointDataBuilder::new()
            .with_format(slab_format)
            .with_transforms(transforms)
            .build_from_bytes(std::mem::take(&mut bytes))
            .map_err(las_error(Some(start as u64)))?;
        writer
            .write_points(&data)
            .map_err(las_error(Some(start as u64)))?;
    }
    writer.into_inner().map_err(las_error(None))
}

/// The point format the columns need, and its field layout; refuses a column no field holds.
fn point_format(a: &Attributes, len: usize) -> Result<(Format, Fields), LasError> {
    a.check(len)
        .map_err(|e| LasError::UnsupportedColumn(e.to_string()))?;
    if a.normal.is_some() {
        return Err(LasError::UnsupportedColumn("normal".into()));
    }
    let has = |n: &str| a.extra.iter().any(|c| c.name == n);
    let extended = ["overlap", "scanner_channel", "scan_angle", "nir"]
        .iter()
        .any(|n| has(n));
    let extra_bytes = a
        .extra
        .iter()
        .filter(|c| c.name.starts_with("extra_byte_"))
        .count();
    let fields = Fields {
        extended,
        extra_bytes,
    };
    let mut known: Vec<String> = fields.columns().iter().map(|c| c.0.to_string()).collect();
    known.push("nir".into());
    known.extend((0..extra_bytes).map(|i| format!("extra_byte_{i}")));
    if let Some(c) = a.extra.iter().find(|c| !known.contains(&c.name)) {
        return Err(LasError::UnsupportedColumn(c.name.clone()));
    }
    let number = match (
        extended,
        a.gps_time.is_some(),
        a.color.is_some(),
        has("nir"),
    ) {
        // Formats 0-3: GPS time adds 1, colour 2.
        (false, gps, color, _) => u8::from(gps) + 2 * u8::from(color),
        (true, false, _, _) => return Err(LasError::MissingColumn("gps_time")),
        (true, true, false, true) => return Err(LasError::MissingColumn("color")),
        // Formats 6-8: colour adds 1, NIR (which needs colour) 1 more.
        (true, true, color, nir) => 6 + u8::from(color) + u8::from(nir),
    };
    let mut format = Format::new(number).map_err(las_error(None))?;
    format.extra_bytes = extra_bytes as u16;
    Ok((format, fields))
}

/// A LAS 1.4 header for `format` with the cloud's frame as its transforms.
fn header(cloud: &Cloud<i32>, format: Format) -> Result<Header, LasError> {
    let mut builder = Builder::from((1, 4));
    builder.point_format = format;
    super::header::check_frame(&cloud.frame)?;
    let (s, o) = (cloud.frame.scale, cloud.frame.offset);
    let axis = |k: usize| Transform {
        scale: s[k],
        offset: o[k],
    };
    builder.transforms = Vector {
        x: axis(0),
        y: axis(1),
        z: axis(2),
    };
    builder.into_header().map_err(las_error(None))
}

/// The cloud's columns in the order of the format's fields, looked up once.
struct RecordColumns<'a> {
    attributes: &'a Attributes,
    fields: Fields,
    /// The flag and scan columns, by the position of their name in `fields.columns()`.
    flags: Vec<Option<&'a [f64]>>,
    nir: Option<&'a [f64]>,
    extra_bytes: Vec<&'a [f64]>,
}

impl<'a> RecordColumns<'a> {
    /// The columns of `a` for `fields` (whose extra-byte columns [`point_format`] has checked).
    fn new(a: &'a Attributes, fields: Fields) -> Self {
        let column = |name: &str| a.extra_column(name);
        RecordColumns {
            attributes: a,
            flags: fields.columns().iter().map(|c| column(c.0)).collect(),
            nir: column("nir"),
            extra_bytes: (0..fields.extra_bytes)
                .map(|i| column(&format!("extra_byte_{i}")).unwrap_or(&[]))
                .collect(),
            fields,
        }
    }

    /// Point `i`'s value in the column `name`, checked to be an integer in `[min, max]`.
    fn integer(
        &self,
        column: Option<&[f64]>,
        name: &str,
        i: usize,
        min: f64,
        max: f64,
    ) -> Result<f64, LasError> {
        let v = column.map_or(0.0, |c| c.get(i).copied().unwrap_or(f64::NAN));
        if v >= min && v <= max && v.fract() == 0.0 {
            Ok(v)
        } else {
            Err(LasError::BadValue {
                point: i,
                column: name.to_string(),
                value: v,
            })
        }
    }

    /// Point `i`'s value in the flag or scan column at position `k` of the format's names.
    fn field(&self, k: usize, i: usize, min: f64, max: f64) -> Result<f64, LasError> {
        self.integer(self.flags[k], self.fields.columns()[k].0, i, min, max)
    }

    /// The flag bytes, scan angle and the position of `user_data` among the names, for point
    /// `i` with classification `class`.
    fn flags(&self, i: usize, class: u8) -> Result<(Flags, ScanAngle, usize), LasError> {
        let bit = |k: usize| -> Result<u8, LasError> { Ok(self.field(k, i, 0.0, 1.0)? as u8) };
        if self.fields.extended {
            let returns =
                self.field(0, i, 0.0, 15.0)? as u8 | (self.field(1, i, 0.0, 15.0)? as u8) << 4;
            let mut f = 0u8;
            for (k, shift) in [(4, 0), (5, 1), (6, 2), (7, 3), (2, 6), (3, 7)] {
                f |= bit(k)? << shift;
            }
            f |= (self.field(8, i, 0.0, 3.0)? as u8) << 4;
            let angle = self.field(9, i, -32768.0, 32767.0)? as i16;
            Ok((
                Flags::ThreeByte(returns, f, class),
                ScanAngle::Scaled(angle),
                10,
            ))
        } else {
            if class > 31 {
                return Err(LasError::BadValue {
                    point: i,
                    column: "classification".into(),
                    value: f64::from(class),
                });
            }
            let mut r =
                self.field(0, i, 0.0, 7.0)? as u8 | (self.field(1, i, 0.0, 7.0)? as u8) << 3;
            r |= bit(2)? << 6 | bit(3)? << 7;
            let mut c = class;
            for (k, shift) in [(4, 5), (5, 6), (6, 7)] {
                c |= bit(k)? << shift;
            }
            let angle = self.field(7, i, -128.0, 127.0)? as i8;
            Ok((Flags::TwoByte(r, c), ScanAngle::Rank(angle), 8))
        }
    }

    /// Point `i` of `cloud` as a LAS record.
    fn record(&self, cloud: &Cloud<i32>, i: usize) -> Result<raw::Point, LasError> {
        let a = self.attributes;
        let class = a.classification.as_ref().map_or(0, |c| c[i]);
        let (flags, scan_angle, rest) = self.flags(i, class)?;
        let nir = match self.nir {
            Some(c) => Some(self.integer(Some(c), "nir", i, 0.0, 65535.0)? as u16),
            None => None,
        };
        let extra_bytes = self
            .extra_bytes
            .iter()
            .map(|c| Ok(self.integer(Some(c), "extra_byte", i, 0.0, 255.0)? as u8))
            .collect::<Result<Vec<u8>, LasError>>()?;
        let [x, y, z] = cloud.points[i];
        Ok(raw::Point {
            x,
            y,
            z,
            intensity: a.intensity.as_ref().map_or(0, |c| c[i]),
            flags,
            scan_angle,
            user_data: self.field(rest, i, 0.0, 255.0)? as u8,
            point_source_id: self.field(rest + 1, i, 0.0, 65535.0)? as u16,
            gps_time: a.gps_time.as_ref().map(|c| c[i]),
            color: a.color.as_ref().map(|c| ::las::Color {
                red: c[i][0],
                green: c[i][1],
                blue: c[i][2],
            }),
            waveform: None,
            nir,
            extra_bytes,
        })
    }
}
