//! Command-line handling shared by the examples (each includes this file with `#[path]`):
//! flags and their values, `--help`, errors that name the argument, and the guards for work the
//! arguments make huge (an estimate checked against the memory this process may use) and for
//! output paths in folders that do not exist.
//!
//! Exit codes: 0 after `--help` (the usage text on standard output), 2 for a bad argument or
//! refused work (one `error:` line naming the argument, then the usage line, on standard error),
//! 1 for a failure while running (a file that cannot be written, a check that fails).
#![allow(dead_code)] // not every example uses every helper

use std::collections::VecDeque;
use std::fmt::Display;
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// `--help`, or an argument that is wrong.
#[derive(Debug, PartialEq)]
pub enum CliError {
    /// `-h` or `--help` was given: print the usage text and stop.
    Help,
    /// A bad argument or refused work; the message names the argument.
    Invalid(String),
}

impl CliError {
    /// An error with this message.
    pub fn new(message: impl Into<String>) -> Self {
        CliError::Invalid(message.into())
    }

    /// The error for an argument no example option matches.
    pub fn unknown(arg: &str) -> Self {
        if arg.starts_with('-') {
            CliError::new(format!("unknown option {arg:?}"))
        } else {
            CliError::new(format!("unexpected argument {arg:?}"))
        }
    }
}

impl std::fmt::Display for CliError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CliError::Help => f.write_str("help asked for"),
            CliError::Invalid(message) => f.write_str(message),
        }
    }
}

/// The arguments still to read.
pub struct Cli {
    args: VecDeque<String>,
}

impl Cli {
    /// The given arguments (without the program name).
    pub fn new<S: Into<String>>(args: impl IntoIterator<Item = S>) -> Self {
        Cli {
            args: args.into_iter().map(Into::into).collect(),
        }
    }

    /// The process's arguments; one that is not valid UTF-8 is an error naming its position.
    pub fn from_env() -> Result<Self, CliError> {
        let mut args = Vec::new();
        for (i, arg) in std::env::args_os().skip(1).enumerate() {
            match arg.into_string() {
                Ok(s) => args.push(s),
                Err(raw) => {
                    return Err(CliError::new(format!(
                        "argument {} ({raw:?}) is not valid UTF-8",
                        i + 1
                    )))
                }
            }
        }
        Ok(Cli::new(args))
    }

    /// The next argument, or `None` after the last; [`CliError::Help`] for `-h` or `--help`.
    pub fn next_arg(&mut self) -> Result<Option<String>, CliError> {
        match self.args.pop_front() {
            Some(arg) if arg == "-h" || arg == "--help" => Err(CliError::Help),
            other => Ok(other),
        }
    }

    /// The value after `flag`; missing (the end, or another option) is an error naming `flag`.
    pub fn value(&mut self, flag: &str) -> Result<String, CliError> {
        match self.args.front() {
            Some(v) if !v.starts_with("--") => Ok(self.args.pop_front().unwrap_or_default()),
            Some(v) => Err(CliError::new(format!(
                "{flag} needs a value, found the option {v:?}"
            ))),
            None => Err(CliError::new(format!("{flag} needs a value"))),
        }
    }

    /// The value after `flag` as a number in `min..=max`; anything else is an error naming
    /// `flag`, the value and the range.
    pub fn number<T>(&mut self, flag: &str, min: T, max: T) -> Result<T, CliError>
    where
        T: FromStr + PartialOrd + Display + Copy,
    {
        let raw = self.value(flag)?;
        parse_number(flag, &raw, min, max)
    }

    /// The value after `flag` as an output file path whose folder exists.
    pub fn output_path(&mut self, flag: &str) -> Result<PathBuf, CliError> {
        let raw = self.value(flag)?;
        output_path(flag, &raw)
    }
}

/// `raw` as a number in `min..=max`, or an error naming `what`, the value and the range.
pub fn parse_number<T>(what: &str, raw: &str, min: T, max: T) -> Result<T, CliError>
where
    T: FromStr + PartialOrd + Display + Copy,
{
    match raw.trim().parse::<T>() {
        Ok(v) if min <= v && v <= max => Ok(v),
        _ => Err(CliError::new(format!(
            "{what} {}: expected a number from {min} to {max}",
            shown(raw)
        ))),
    }
}

/// `raw` as a path to write, checked before any work: its folder must exist and the path must
/// not be a folder itself.
pub fn output_path(what: &str, raw: &str) -> Result<PathBuf, CliError> {
    let path = PathBuf::from(raw);
    if raw.is_empty() {
        return Err(CliError::new(format!("{what}: the path is empty")));
    }
    if path.is_dir() {
        return Err(CliError::new(format!(
            "{what} {}: is a folder, not a file",
            shown(raw)
        )));
    }
    check_folder(what, raw, path.parent().unwrap_or(Path::new("")))?;
    Ok(path)
}

/// An error naming `what` and `raw` unless `folder` (empty: the current folder) is a folder.
pub fn check_folder(what: &str, raw: &str, folder: &Path) -> Result<(), CliError> {
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
    Err(CliError::new(format!(
        "{what} {}: the folder {:?} {problem}",
        shown(raw),
        folder.display().to_string()
    )))
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
    match (available, address_space) {
        (Some(a), Some(l)) if l < a => MemoryLimit {
            bytes: l,
            source: "three quarters of the address-space limit",
        },
        (Some(a), _) => MemoryLimit {
            bytes: a,
            source: "the available memory",
        },
        (None, Some(l)) => MemoryLimit {
            bytes: l,
            source: "three quarters of the address-space limit",
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

/// Refuses work estimated at `bytes` when it exceeds `limit`: the message names `what` (the
/// arguments and the size they ask for), the estimate and the limit.
pub fn check_memory(what: &str, bytes: f64, limit: MemoryLimit) -> Result<(), CliError> {
    if bytes.is_finite() && bytes <= limit.bytes {
        Ok(())
    } else {
        Err(CliError::new(format!(
            "{what}: needs an estimated {}; the limit is {} ({})",
            human_bytes(bytes),
            human_bytes(limit.bytes),
            limit.source
        )))
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

/// Runs `parse` on the process's arguments: `--help` prints `usage` and exits 0; an error
/// prints it with the usage's first line and exits 2.
pub fn parse_or_exit<T>(usage: &str, parse: impl FnOnce(&mut Cli) -> Result<T, CliError>) -> T {
    let result = Cli::from_env().and_then(|mut cli| parse(&mut cli));
    result.unwrap_or_else(|e| exit_with(usage, e))
}

/// Prints what `error` needs (see [`parse_or_exit`]) and exits.
pub fn exit_with(usage: &str, error: CliError) -> ! {
    match error {
        CliError::Help => {
            println!("{}", usage.trim_end());
            std::process::exit(0)
        }
        CliError::Invalid(message) => {
            let synopsis = usage.lines().next().unwrap_or_default();
            eprintln!("error: {message}\n{synopsis}\n(--help for the options)");
            std::process::exit(2)
        }
    }
}
