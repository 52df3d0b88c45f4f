//! Guards for what the arguments ask for, checked before any work: numbers in a range, output
//! paths whose folder exists, and work the arguments make huge (an estimate of its memory
//! against the memory this process may use). Every message names the argument and the limit.
//!
//! The comparison crate and the library's examples include this file too (with `#[path]`), so
//! not every item is used by each.
#![allow(dead_code)]

use std::fmt::Display;
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// A clap value parser for a number in `min..=max`: anything else is refused with the range.
pub fn number<T>(min: T, max: T) -> impl Fn(&str) -> Result<T, String> + Clone + Send + Sync
where
    T: FromStr + PartialOrd + Display + Copy + Send + Sync + 'static,
{
    move |raw| parse_number(raw, min, max)
}

/// `raw` as a number in `min..=max`, or a message naming the range.
pub fn parse_number<T>(raw: &str, min: T, max: T) -> Result<T, String>
where
    T: FromStr + PartialOrd + Display + Copy,
{
    match raw.trim().parse::<T>() {
        Ok(v) if min <= v && v <= max => Ok(v),
        _ => Err(format!("expected a number from {min} to {max}")),
    }
}

/// A clap value parser for a path to write, checked before any work: its folder must exist and
/// the path must not be a folder itself.
pub fn output_path(raw: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(raw);
    if raw.is_empty() {
        return Err("the path is empty".into());
    }
    if path.is_dir() {
        return Err("is a folder, not a file".into());
    }
    check_folder(path.parent().unwrap_or(Path::new("")))?;
    Ok(path)
}

/// A clap value parser for a folder that exists.
pub fn existing_folder(raw: &str) -> Result<PathBuf, String> {
    check_folder(Path::new(raw))?;
    Ok(PathBuf::from(raw))
}

/// An error unless `folder` (empty: the current folder) is a folder.
pub fn check_folder(folder: &Path) -> Result<(), String> {
    let folder = if folder.as_os_str().is_empty() {
        Path::new(".")
    } else {
        folder
    };
    let problem = if folder.is_dir() {
        return Ok(());
    } else if folder.exists() {
        "is not a folder"
    } else {
        "does not exist"
    };
    Err(format!(
        "the folder {:?} {problem}",
        folder.display().to_string()
    ))
}

/// `raw` quoted, cut to 60 characters, invisible characters escaped.
pub fn shown(raw: &str) -> String {
    let cut: String = raw.chars().take(60).collect();
    let more = if cut.len() < raw.len() { "..." } else { "" };
    format!("{cut:?}{more}")
}

/// The memory this process may use, and where that figure comes from.
#[derive(Clone, Copy, Debug)]
pub struct MemoryLimit {
    /// Bytes.
    pub bytes: f64,
    /// What set it, for messages.
    pub source: &'static str,
}

/// Used when the system does not say (no `/proc/meminfo`): 4 GiB.
pub const FALLBACK_MEMORY_BYTES: f64 = 4.0 * 1024.0 * 1024.0 * 1024.0;

/// The smaller of the available memory (`MemAvailable` in `/proc/meminfo`) and three quarters of
/// the address-space limit (`ulimit -v`, `prlimit --as`; a quarter is left for code, stacks and
/// allocator slack); [`FALLBACK_MEMORY_BYTES`] when neither is known.
pub fn memory_limit() -> MemoryLimit {
    let available = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|s| kib_field(&s, "MemAvailable:"))
        .map(|kib| kib * 1024.0);
    let address_space = std::fs::read_to_string("/proc/self/limits")
        .ok()
        .and_then(|s| {
            let line = s.lines().find(|l| l.starts_with("Max address space"))?;
            line.split_whitespace().nth(3)?.parse::<f64>().ok()
        })
        .map(|bytes| bytes * 0.75);
    const LIMIT: &str = "three quarters of the address-space limit";
    match (available, address_space) {
        (Some(a), Some(l)) if l < a => MemoryLimit {
            bytes: l,
            source: LIMIT,
        },
        (Some(a), _) => MemoryLimit {
            bytes: a,
            source: "the available memory",
        },
        (None, Some(l)) => MemoryLimit {
            bytes: l,
            source: LIMIT,
        },
        (None, None) => MemoryLimit {
            bytes: FALLBACK_MEMORY_BYTES,
            source: "the fallback limit, 4 GiB",
        },
    }
}

fn kib_field(text: &str, name: &str) -> Option<f64> {
    let line = text.lines().find(|l| l.starts_with(name))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// Refuses work estimated at `bytes` when it exceeds the memory limit: the message names `what`
/// (the arguments and the size they ask for), the estimate and the limit.
pub fn check_memory(what: &str, bytes: f64) -> Result<(), String> {
    let limit = memory_limit();
    if bytes.is_finite() && bytes <= limit.bytes {
        Ok(())
    } else {
        Err(format!(
            "{what}: needs an estimated {}; the limit is {} ({})",
            human_bytes(bytes),
            human_bytes(limit.bytes),
            limit.source
        ))
    }
}

/// Bytes with a binary prefix: `1.5 GiB`; huge or infinite values in scientific notation.
pub fn human_bytes(bytes: f64) -> String {
    const UNITS: [&str; 7] = ["B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"];
    if !bytes.is_finite() || bytes >= 1024f64.powi(7) {
        return format!("{bytes:.2e} bytes");
    }
    let mut value = bytes.max(0.0);
    let mut unit = 0;
    while value >= 1024.0 && unit + 1 < UNITS.len() {
        value /= 1024.0;
        unit += 1;
    }
    format!("{value:.1} {}", UNITS[unit])
}
