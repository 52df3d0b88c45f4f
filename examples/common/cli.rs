//! Command-line handling shared by the examples (each includes this file with `#[path]`):
//! flags and their values, `--help`, errors that name the argument, and the guards for work the
//! arguments make huge (an estimate checked against the memory this process may use) and for
//! output paths in folders that do not exist.
//!
//! Exit codes: 0 after `--help` (the usage text on standard output), 2 for a bad argument or
//! refused work (one `error:` line naming the argument, then the usage line, on standard error),
//! 1 for a failure while running (a file that cannot be written, a check that fails).
#![allow(dead_code)] // not every example uses every helper

#[macro_use]
#[path = "../../cli/src/print.rs"]
mod print;

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

// The guards are the command-line program's own (one copy of the range, path and memory checks);
// these wrappers only put the argument's name in front of their messages.
#[path = "../../cli/src/limits.rs"]
mod guards;
pub use guards::shown;

/// The message of a refused `raw`, naming the argument `what` and the value.
fn named(what: &str, raw: &str) -> impl FnOnce(String) -> CliError + use<> {
    let name = format!("{what} {}", shown(raw));
    move |message| CliError::new(format!("{name}: {message}"))
}

/// `raw` as a number in `min..=max`, or an error naming `what`, the value and the range.
pub fn parse_number<T>(what: &str, raw: &str, min: T, max: T) -> Result<T, CliError>
where
    T: FromStr + PartialOrd + Display + Copy,
{
    guards::parse_number(raw, min, max).map_err(named(what, raw))
}

/// `raw` as a path to write, checked before any work: its folder must exist and the path must
/// not be a folder itself.
pub fn output_path(what: &str, raw: &str) -> Result<PathBuf, CliError> {
    guards::output_path(raw).map_err(named(what, raw))
}

/// An error naming `what` and `raw` unless `folder` (empty: the current folder) is a folder.
pub fn check_folder(what: &str, raw: &str, folder: &Path) -> Result<(), CliError> {
    guards::check_folder(folder).map_err(named(what, raw))
}

/// Refuses work estimated at `bytes` when it exceeds the memory this process may use: the
/// message names `what` (the arguments and the size they ask for), the estimate and the limit.
pub fn check_memory(what: &str, bytes: f64) -> Result<(), CliError> {
    guards::check_memory(what, bytes).map_err(CliError::new)
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
            say!("{}", usage.trim_end());
            std::process::exit(0)
        }
        CliError::Invalid(message) => {
            let synopsis = usage.lines().next().unwrap_or_default();
            eprintln!("error: {message}\n{synopsis}\n(--help for the options)");
            std::process::exit(2)
        }
    }
}
