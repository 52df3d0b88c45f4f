//! Point clouds as ASPRS LAS files (and LAZ, their compressed form, with the `laz` feature),
//! through the `las` crate: every point record of formats 0-3 and 6-8 with all its fields.
//!
//! Coordinates stay the file's integers (a [`Cloud<i32>`]) with its scale and offset as the
//! cloud's [`Frame`](crate::cloud::Frame); intensity, classification, GPS time and colour fill
//! their columns and every other field an extra column: `return_number`, `number_of_returns`,
//! `scan_direction`, `edge_of_flight_line`, `synthetic`, `key_point`, `withheld`, `user_data`,
//! `point_source_id`, `scan_angle_rank` (formats 0-5) or `scan_angle`, `overlap` and
//! `scanner_channel` (formats 6-10), `nir`, and `extra_byte_0`, `extra_byte_1`, ... for the
//! extra bytes. [`write_to`] writes all of them back, choosing the point format the columns
//! need, so a read and a write give the same records. Waveform formats (4, 5, 9, 10) are
//! refused rather than read without their packets.
//!
//! Points are read in batches of at most 4 MiB: memory follows the points read, never the
//! count the header claims; a file that ends early is refused, naming the point.
//!
//! ```
//! use orthtree::cloud::{Cloud, Frame};
//! use orthtree::io::las;
//! let mut cloud = Cloud::from_points(vec![[1000, 2000, 30], [-5, 7, 0]]);
//! cloud.frame = Frame { scale: [0.01; 3], offset: [500_000.0, 4_000_000.0, 0.0] };
//! cloud.attributes.intensity = Some(vec![12, 34]);
//! let bytes = las::write_to(&cloud, std::io::Cursor::new(Vec::new()), false).unwrap().into_inner();
//! let back = las::read_from(std::io::Cursor::new(bytes)).unwrap();
//! assert_eq!(back.points, cloud.points);
//! assert_eq!(back.frame, cloud.frame);
//! assert_eq!(back.attributes.intensity, Some(vec![12, 34]));
//! ```

use crate::cloud::{Attributes, Cloud, Column};
use ::las::raw::point::{Flags, ScanAngle};
use ::las::{point::Format, raw, PointDataBuilder, Reader};
use core::fmt;
use std::io::{Read, Seek, SeekFrom};
use std::path::Path;

pub(crate) mod entries;
mod header;
mod write;
pub use entries::read_entries;
pub use write::{write, write_to};

/// The most bytes of point records read at once.
const BATCH_BYTES: usize = 1 << 22;

/// Why a LAS file was refused or could not be written.
#[derive(Debug)]
#[non_exhaustive]
pub enum LasError {
    /// The `las` crate refused the file (its header, or a record at `point`).
    Las {
        /// The point being read, if the error came from the records.
        point: Option<u64>,
        /// The crate's message.
        message: String,
    },
    /// The file ends inside point `point` of the `count` the header declares.
    Truncated {
        /// The first point missing or incomplete (in a LAZ file, the first point of the batch
        /// of at most 4 MiB of records being decompressed).
        point: u64,
        /// The points declared.
        count: u64,
        /// The file's length in bytes.
        length: u64,
    },
    /// A header field claims more than the file holds: a point count whose records would end
    /// beyond 2^64 bytes, a first EVLR starting or ending beyond the file, a LAZ chunk table
    /// with more chunks than bytes of compressed points. Checked before the `las` crate reads
    /// (or allocates) anything by it.
    Field {
        /// The field.
        field: &'static str,
        /// Its byte offset in the file.
        offset: u64,
        /// The value found.
        found: String,
        /// The limit it broke.
        expected: String,
    },
    /// A point format with waveform packets (4, 5, 9, 10).
    UnsupportedFormat(u8),
    /// A column the LAS point records cannot hold (a PLY property, normals).
    UnsupportedColumn(String),
    /// A column the chosen point format needs (`gps_time` for formats 6-8, colour for `nir`).
    MissingColumn(&'static str),
    /// Point `point`'s value in `column` does not fit its LAS field.
    BadValue {
        /// The point.
        point: usize,
        /// The column.
        column: String,
        /// The value.
        value: f64,
    },
    /// Reading or writing failed.
    Io(std::io::Error),
}

impl fmt::Display for LasError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LasError::Las {
                point: Some(p),
                message,
            } => write!(f, "LAS point {p}: {message}"),
            LasError::Las { point: None, message } => write!(f, "LAS: {message}"),
            LasError::Truncated {
                point,
                count,
                length,
            } => write!(
                f,
                "LAS: the file ends (at byte offset {length}) inside point {point} of the {count} declared"
            ),
            LasError::Field {
                field,
                offset,
                found,
                expected,
            } => write!(
                f,
                "LAS: {field} (byte offset {offset}) is {found}, expected {expected}"
            ),
            LasError::UnsupportedFormat(n) => {
                write!(f, "LAS: point format {n} carries waveforms, which are not read")
            }
            LasError::UnsupportedColumn(name) => {
                write!(f, "LAS: column {name} has no field in a LAS point record")
            }
            LasError::MissingColumn(name) => {
                write!(f, "LAS: the point format needs column {name}")
            }
            LasError::BadValue {
                point,
                column,
                value,
            } => write!(f, "LAS point {point}: {column} = {value} does not fit its field"),
            LasError::Io(e) => write!(f, "LAS: {e}"),
        }
    }
}

impl std::error::Error for LasError {}

impl From<std::io::Error> for LasError {
    fn from(e: std::io::Error) -> Self {
        LasError::Io(e)
    }
}

fn las_error(point: Option<u64>) -> impl Fn(::las::Error) -> LasError {
    move |e| LasError::Las {
        point,
        message: e.to_string(),
    }
}

/// Runs `f` with a panic of the `las` crate's decoder in it turned into [`LasError::Las`], with
/// the panic's message.
fn caught<T>(point: Option<u64>, f: impl FnOnce() -> T) -> Result<T, LasError> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)).map_err(|panic| {
        let message = panic
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| panic.downcast_ref::<String>().cloned())
            .unwrap_or_default();
        LasError::Las {
            point,
            message: format!("the decoder failed on damaged data: {message}"),
        }
    })
}

/// Reads the LAS (or, with the `laz` feature, LAZ) file at `path`.
///
/// # Errors
/// As [`read_from`], and [`LasError::Io`] when the file cannot be opened.
pub fn read(path: impl AsRef<Path>) -> Result<Cloud<i32>, LasError> {
    read_from(std::io::BufReader::new(std::fs::File::open(path)?))
}

/// Reads a LAS (or LAZ) cloud from `input`, keeping the integer coordinates.
///
/// # Errors
/// [`LasError::Las`] for a header or record the `las` crate refuses, [`LasError::Field`] for a
/// header field claiming more than the file holds (checked before the `las` crate reads on),
/// [`LasError::Truncated`] naming the first missing point, [`LasError::UnsupportedFormat`] for
/// waveform formats.
///
/// # Complexity
/// O(n); memory is the cloud plus one batch of at most 4 MiB of records.
pub fn read_from<R: Read + Seek + Send + Sync + 'static>(
    mut input: R,
) -> Result<Cloud<i32>, LasError> {
    let length = input.seek(SeekFrom::End(0))?;
    let raw_header = header::checked_header(&mut input, length)?;
    input.seek(SeekFrom::Start(0))?;
    // A panic in the `las` crate (its LAZ decoder panics on some damaged chunk tables that no
    // check of the header rules out) is an error too.
    let mut reader = caught(None, || Reader::new(input))?.map_err(las_error(None))?;
    let header = reader.header().clone();
    let format = *header.point_format();
    if format.has_waveform {
        return Err(LasError::UnsupportedFormat(format.to_u8().unwrap_or(4)));
    }
    let fields = Fields::new(&format);
    let record = usize::from(format.len());
    // Room for the points the file's bytes can hold, never more than the header claims
    // (`Cloud::with_capacity`: memory for huge pages).
    let room = (length / record.max(1) as u64).min(header.number_of_points());
    let mut cloud = Cloud {
        // Every format's columns; the optional ones come with the first record.
        attributes: Attributes {
            intensity: Some(Vec::new()),
            classification: Some(Vec::new()),
            ..Attributes::default()
        },
        // The transforms the `las` crate read from the same header.
        frame: header::frame_of(&raw_header),
        ..Cloud::with_capacity(usize::try_from(room).unwrap_or(0))
    };
    let count = header.number_of_points();
    let batch = (BATCH_BYTES / record.max(1)).max(1) as u64;
    let mut data = PointDataBuilder::new().for_header(&header).build();
    let mut done = 0u64;
    while done < count {
        let want = batch.min(count - done);
        match caught(Some(done), || reader.fill_points(want, &mut data))? {
            Ok(got) if got == want => {}
            Ok(_) | Err(::las::Error::Io(_)) => {
                // Find the first point that cannot be read, one at a time. Not in a LAZ file:
                // seeking there follows its chunk table, which a damaged file can point
                // anywhere; the batch's first point is named.
                let mut point = done;
                if !format.is_compressed {
                    reader.seek(done).map_err(las_error(Some(done)))?;
                    while reader.fill_points(1, &mut data).is_ok_and(|n| n == 1) {
                        point += 1;
                    }
                }
                return Err(LasError::Truncated {
                    point,
                    count,
                    length,
                });
            }
            Err(e) => return Err(las_error(Some(done))(e)),
        }
        for (i, bytes) in data.raw_bytes().chunks_exact(record).enumerate() {
            let p =
                raw::Point::read_from(bytes, &format).map_err(las_error(Some(done + i as u64)))?;
            fields.push(&p, &mut cloud);
        }
        done += want;
    }
    Ok(cloud)
}

/// The columns of a point format.
struct Fields {
    extended: bool,
    extra_bytes: usize,
}

/// A flag or scan column of a point format: its name and, for a bit field, the byte of the
/// record's flags it lies in (0 the return byte, 1 the next), its shift and its width in bits.
/// The last three columns of each format (scan angle, user data, point source id) have no bits.
type FlagColumn = (&'static str, usize, u32, u32);

/// The extra columns of legacy formats (0-5), in order.
const LEGACY: [FlagColumn; 10] = [
    ("return_number", 0, 0, 3),
    ("number_of_returns", 0, 3, 3),
    ("scan_direction", 0, 6, 1),
    ("edge_of_flight_line", 0, 7, 1),
    ("synthetic", 1, 5, 1),
    ("key_point", 1, 6, 1),
    ("withheld", 1, 7, 1),
    ("scan_angle_rank", 0, 0, 0),
    ("user_data", 0, 0, 0),
    ("point_source_id", 0, 0, 0),
];

/// The extra columns of extended formats (6-10), in order.
const EXTENDED: [FlagColumn; 12] = [
    ("return_number", 0, 0, 4),
    ("number_of_returns", 0, 4, 4),
    ("scan_direction", 1, 6, 1),
    ("edge_of_flight_line", 1, 7, 1),
    ("synthetic", 1, 0, 1),
    ("key_point", 1, 1, 1),
    ("withheld", 1, 2, 1),
    ("overlap", 1, 3, 1),
    ("scanner_channel", 1, 4, 2),
    ("scan_angle", 0, 0, 0),
    ("user_data", 0, 0, 0),
    ("point_source_id", 0, 0, 0),
];

impl Fields {
    fn new(format: &Format) -> Fields {
        Fields {
            extended: format.is_extended,
            extra_bytes: usize::from(format.extra_bytes),
        }
    }

    fn columns(&self) -> &'static [FlagColumn] {
        if self.extended {
            &EXTENDED
        } else {
            &LEGACY
        }
    }

    /// The bit fields of the flag bytes: every column but the last three.
    fn bits(&self) -> &'static [FlagColumn] {
        let columns = self.columns();
        &columns[..columns.len() - 3]
    }

    /// Appends one record's fields to the cloud, creating the optional columns on the first.
    fn push(&self, p: &raw::Point, cloud: &mut Cloud<i32>) {
        let a = &mut cloud.attributes;
        if cloud.points.is_empty() {
            a.gps_time = p.gps_time.map(|_| Vec::new());
            a.color = p.color.map(|_| Vec::new());
            let mut names: Vec<String> = self.columns().iter().map(|c| c.0.to_string()).collect();
            names.extend(p.nir.map(|_| "nir".to_string()));
            names.extend((0..self.extra_bytes).map(|i| format!("extra_byte_{i}")));
            a.extra = names
                .into_iter()
                .map(|name| Column {
                    name,
                    values: Vec::new(),
                })
                .collect();
        }
        cloud.points.push([p.x, p.y, p.z]);
        let angle = match p.scan_angle {
            ScanAngle::Scaled(s) => f64::from(s),
            ScanAngle::Rank(r) => f64::from(r),
        };
        let (bytes, class) = match p.flags {
            Flags::TwoByte(r, c) => ([r, c], c & 0x1f),
            Flags::ThreeByte(r, f, c) => ([r, f], c),
        };
        // One record's columns, each pushed to its column as it is read.
        let bits = (self.bits().iter())
            .map(|&(_, b, shift, width)| f64::from((bytes[b] >> shift) & ((1u8 << width) - 1)));
        let rest = [angle, f64::from(p.user_data), f64::from(p.point_source_id)];
        let values = (bits.chain(rest).chain(p.nir.map(f64::from)))
            .chain(p.extra_bytes.iter().map(|&b| f64::from(b)));
        a.intensity.as_mut().expect("created").push(p.intensity);
        a.classification.as_mut().expect("created").push(class);
        if let (Some(col), Some(t)) = (a.gps_time.as_mut(), p.gps_time) {
            col.push(t);
        }
        if let (Some(col), Some(c)) = (a.color.as_mut(), p.color) {
            col.push([c.red, c.green, c.blue]);
        }
        for (col, v) in a.extra.iter_mut().zip(values) {
            col.values.push(v);
        }
    }
}
