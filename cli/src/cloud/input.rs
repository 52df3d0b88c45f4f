//! The clouds `orthtree cloud` reads and writes: PLY, XYZ/CSV text and LAS/LAZ (features `las`
//! and `laz`), chosen by the file's extension whatever its case; every cloud is taken to world
//! coordinates (`f64`, a LAS file's scale and offset applied) before any work. Results are
//! written as binary PLY.

use crate::Failure;
use orthtree::cloud::{Cloud, Frame};
use orthtree::io::{ply, xyz};
use std::path::Path;

/// The file formats by extension (lower case).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// `.ply`
    Ply,
    /// `.xyz`, `.csv`, `.txt`
    Xyz,
    /// `.las`
    Las,
    /// `.laz`
    Laz,
}

/// The extensions read, for messages.
pub const READ: &str = "ply, xyz, csv, txt, las (feature las), laz (feature laz)";

/// The format of `path` by its extension, or a usage error naming it.
pub fn format_of(path: &str) -> Result<Format, Failure> {
    let ext = Path::new(path)
        .extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .unwrap_or_default();
    let format = match ext.as_str() {
        "ply" => Format::Ply,
        "xyz" | "csv" | "txt" => Format::Xyz,
        "las" => Format::Las,
        "laz" => Format::Laz,
        _ => {
            return Err(Failure::Usage(format!(
                "{}: unsupported extension {ext:?} (read: {READ})",
                crate::limits::shown(path)
            )))
        }
    };
    let missing = match format {
        Format::Las if !cfg!(feature = "las") => Some("las"),
        Format::Laz if !cfg!(feature = "laz") => Some("laz"),
        _ => None,
    };
    if let Some(feature) = missing {
        return Err(Failure::Usage(format!(
            "{}: .{feature} files need the program built with `--features {feature}`",
            crate::limits::shown(path)
        )));
    }
    Ok(format)
}

/// Reads the cloud at `path` in world coordinates.
///
/// # Errors
/// [`Failure::Usage`] for an unsupported extension; [`Failure::Input`] naming the file and
/// what its reader refused (line, field, byte offset or point).
pub fn read(path: &str) -> Result<Cloud<f64>, Failure> {
    let format = format_of(path)?;
    let named = |e: &dyn std::fmt::Display| Failure::Input(format!("{}: {e}", shown(path)));
    let open = || std::fs::File::open(path).map_err(|e| named(&e));
    let cloud: Cloud<f64> = match format {
        Format::Ply => ply::read(open()?).map_err(|e| named(&e))?,
        Format::Xyz => xyz::read(open()?).map_err(|e| named(&e))?,
        Format::Las | Format::Laz => read_las(path)?,
    };
    let cloud = to_world(cloud);
    cloud.check().map_err(|e| named(&e))?;
    Ok(cloud)
}

#[cfg(feature = "las")]
fn read_las(path: &str) -> Result<Cloud<f64>, Failure> {
    let cloud = orthtree::io::las::read(path)
        .map_err(|e| Failure::Input(format!("{}: {e}", shown(path))))?;
    Ok(to_world(cloud))
}

#[cfg(not(feature = "las"))]
fn read_las(path: &str) -> Result<Cloud<f64>, Failure> {
    Err(Failure::Usage(format!(
        "{}: LAS needs `--features las`",
        shown(path)
    )))
}

/// The cloud with its frame applied: world coordinates, identity frame.
pub fn to_world<S: orthtree::Scalar>(cloud: Cloud<S>) -> Cloud<f64> {
    if cloud.frame == Frame::IDENTITY {
        let points = cloud.points.iter().map(|p| p.map(|c| c.to_f64())).collect();
        return Cloud {
            points,
            attributes: cloud.attributes,
            frame: Frame::IDENTITY,
        };
    }
    Cloud {
        points: cloud.world_points(),
        attributes: cloud.attributes,
        frame: Frame::IDENTITY,
    }
}

/// Writes `cloud` as binary little-endian PLY to `path`.
///
/// # Errors
/// [`Failure::Input`] naming the file when creating or writing fails.
pub fn write_ply(cloud: &Cloud<f64>, path: &Path) -> Result<(), Failure> {
    let fail = |e: &dyn std::fmt::Display| Failure::Input(format!("{}: {e}", path.display()));
    let file = std::fs::File::create(path).map_err(|e| fail(&e))?;
    ply::write(cloud, ply::Encoding::BinaryLittleEndian, file).map_err(|e| fail(&e))
}

fn shown(path: &str) -> String {
    crate::limits::shown(path)
}
