//! A rival driven through Python: the shared points written to a file of little-endian `f64`,
//! a script run on them in a venv's Python, and its median times and answers read back (one
//! `key value` line each, as [`ScipyRun::parse`] reads them). Open3D's driver for
//! `cloud_compare`; scipy's (`scipy.rs`) works the same way.

use crate::scipy::{ScipyRun, TempFile};
use std::path::{Path, PathBuf};
use std::process::Command;

/// A Python that can import the rival's module, and the script that runs its workloads.
#[derive(Clone, Debug)]
pub struct PythonRival {
    python: PathBuf,
    script: PathBuf,
    /// The module's version, as `module.__version__` gives it.
    pub version: String,
}

impl PythonRival {
    /// The Python at `python` when it exists and imports `module`, running `script`; `None`
    /// otherwise.
    pub fn find(python: &Path, module: &str, script: PathBuf) -> Option<PythonRival> {
        let out = Command::new(python)
            .args([
                "-c",
                &format!("import {module}; print({module}.__version__)"),
            ])
            .output()
            .ok()?;
        if !out.status.success() {
            return None;
        }
        let version = String::from_utf8_lossy(&out.stdout).trim().to_string();
        Some(PythonRival {
            python: python.to_path_buf(),
            script,
            version,
        })
    }

    /// Runs workload `name` of the script on `points` with the extra arguments `args`, `reps`
    /// timed runs each.
    ///
    /// # Errors
    /// A temporary file that cannot be written, a script that fails (its error output is
    /// quoted) or output that lacks the build or query time (the line is named).
    pub fn run(
        &self,
        name: &str,
        points: &[[f64; 3]],
        args: &[String],
        reps: usize,
    ) -> Result<ScipyRun, String> {
        let tag = format!("python-rival-{}-{name}", std::process::id());
        let file = TempFile::write(std::env::temp_dir().join(format!("{tag}.f64")), points)?;
        let out = Command::new(&self.python)
            .arg(&self.script)
            .arg(name)
            .arg(&file.0)
            .arg("--reps")
            .arg(reps.to_string())
            .args(args)
            .output()
            .map_err(|e| format!("cannot run {}: {e}", self.python.display()))?;
        if !out.status.success() {
            return Err(format!(
                "the {name} run of {} failed ({}): {}",
                self.script.display(),
                out.status,
                String::from_utf8_lossy(&out.stderr).trim()
            ));
        }
        ScipyRun::parse(&String::from_utf8_lossy(&out.stdout))
    }
}
