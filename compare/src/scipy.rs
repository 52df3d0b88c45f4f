//! The driver of scipy's `cKDTree`: writes the shared points to a file of little-endian `f64`,
//! runs the script `compare/scipy/ckdtree.py` on them in the Python of the venv that
//! `compare/scipy/setup.sh` makes (`target/scipy-venv`), and reads back its median times and
//! answers (one `key value` line each) as a [`Run`].

use crate::joins::{Answer, Run};
use crate::rivals::Answers;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::Command;

/// What to run when scipy is missing.
pub const NOT_SET_UP: &str = "scipy not set up: run compare/scipy/setup.sh";

/// The Python of the venv that `compare/scipy/setup.sh` creates.
pub fn default_python() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/scipy-venv/bin/python")
}

/// The script that runs the workloads.
fn script() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scipy/ckdtree.py")
}

/// A Python that can import scipy, and the scipy version it has.
#[derive(Clone, Debug)]
pub struct Scipy {
    python: PathBuf,
    /// scipy's version, as `scipy.__version__` gives it.
    pub version: String,
}

impl Scipy {
    /// The Python at `python` when it exists and imports scipy; `None` otherwise (then print
    /// [`NOT_SET_UP`]).
    pub fn find(python: &Path) -> Option<Scipy> {
        let out = Command::new(python)
            .args(["-c", "import scipy; print(scipy.__version__)"])
            .output()
            .ok()?;
        if !out.status.success() {
            return None;
        }
        let version = String::from_utf8_lossy(&out.stdout).trim().to_string();
        Some(Scipy {
            python: python.to_path_buf(),
            version,
        })
    }

    /// Runs workload `name` of the script on `points` (and `queries`, for `periodic`) with the
    /// extra arguments `args`, `reps` timed runs each.
    ///
    /// # Errors
    /// A temporary file that cannot be written, a script that fails (its error output is
    /// quoted) or output that lacks the build or query time (the line is named).
    pub fn run(
        &self,
        name: &str,
        points: &[[f64; 3]],
        queries: Option<&[[f64; 3]]>,
        args: &[String],
        reps: usize,
    ) -> Result<ScipyRun, String> {
        let dir = std::env::temp_dir();
        let tag = format!("joins_compare-{}-{name}", std::process::id());
        let points_file = TempFile::write(dir.join(format!("{tag}-points.f64")), points)?;
        let mut cmd = Command::new(&self.python);
        cmd.arg(script())
            .arg(name)
            .arg(&points_file.0)
            .arg("3")
            .arg("--reps")
            .arg(reps.to_string())
            .args(args);
        let _queries_file = match queries {
            Some(q) => {
                let f = TempFile::write(dir.join(format!("{tag}-queries.f64")), q)?;
                cmd.arg("--queries").arg(&f.0);
                Some(f)
            }
            None => None,
        };
        let out = cmd
            .output()
            .map_err(|e| format!("cannot run {}: {e}", self.python.display()))?;
        if !out.status.success() {
            return Err(format!(
                "scipy's {name} run failed ({}): {}",
                out.status,
                String::from_utf8_lossy(&out.stderr).trim()
            ));
        }
        ScipyRun::parse(&String::from_utf8_lossy(&out.stdout))
    }
}

/// What the script printed: its median times and its answers.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ScipyRun {
    /// The median build time, ms.
    pub build_ms: f64,
    /// The median workload time, ms.
    pub query_ms: f64,
    /// Neighbours or pairs found.
    pub count: Option<u64>,
    /// The sum of their indices.
    pub items: Option<u64>,
    /// The sum of their squared distances.
    pub dist2: Option<f64>,
    /// `count_neighbors`' counts (ordered pairs, each point with itself included).
    pub counts: Option<Vec<u64>>,
}

impl ScipyRun {
    /// Reads the script's `key value` lines.
    ///
    /// # Errors
    /// A line whose value does not parse, or a missing `build` or `query` line (named).
    pub fn parse(text: &str) -> Result<ScipyRun, String> {
        let (mut r, mut build, mut query) = (ScipyRun::default(), None, None);
        for (n, line) in text.lines().enumerate() {
            let Some((key, value)) = line.split_once(' ') else {
                continue;
            };
            let bad =
                |e: &dyn std::fmt::Display| format!("scipy output line {}: {line:?}: {e}", n + 1);
            let float = || value.parse::<f64>().map_err(|e| bad(&e));
            let int = || value.parse::<u64>().map_err(|e| bad(&e));
            match key {
                "build" => build = Some(float()?),
                "query" => query = Some(float()?),
                "count" => r.count = Some(int()?),
                "items" => r.items = Some(int()?),
                "dist2" => r.dist2 = Some(float()?),
                "counts" => {
                    let cs: Result<Vec<u64>, _> = value.split(',').map(str::parse).collect();
                    r.counts = Some(cs.map_err(|e| bad(&e))?);
                }
                _ => {}
            }
        }
        r.build_ms = build.ok_or("scipy output has no `build` line")?;
        r.query_ms = query.ok_or("scipy output has no `query` line")?;
        Ok(r)
    }

    /// As a [`Run`]: `points` turns `count_neighbors`' ordered counts (each point with itself
    /// included) into unordered pairs of distinct points.
    ///
    /// # Errors
    /// Counts that are not `2 p + points` for a whole `p` (named by position).
    pub fn into_run(self, points: usize) -> Result<Run, String> {
        let answer = match self.counts {
            Some(cs) => {
                let n = points as u64;
                let pairs: Result<Vec<u64>, String> = cs
                    .iter()
                    .enumerate()
                    .map(|(i, &c)| match c.checked_sub(n) {
                        Some(d) if d % 2 == 0 => Ok(d / 2),
                        _ => Err(format!(
                            "scipy's count {c} at radius {i} is not twice the pairs plus {n}"
                        )),
                    })
                    .collect();
                Answer::Counts(pairs?)
            }
            None => Answer::Found(Answers {
                count: self.count.unwrap_or(0),
                items: self.items,
                distance: self.dist2,
            }),
        };
        Ok(Run {
            build_ms: self.build_ms,
            query_ms: self.query_ms,
            answer,
        })
    }
}

/// A file of points that is removed when dropped.
pub(crate) struct TempFile(pub(crate) PathBuf);

impl TempFile {
    /// `points` as little-endian `f64`, row after row, at `path`.
    pub(crate) fn write(path: PathBuf, points: &[[f64; 3]]) -> Result<TempFile, String> {
        let file = TempFile(path);
        let err = |e: std::io::Error| format!("cannot write {}: {e}", file.0.display());
        let mut w = BufWriter::new(File::create(&file.0).map_err(err)?);
        for x in points.iter().flatten() {
            w.write_all(&x.to_le_bytes()).map_err(err)?;
        }
        w.flush().map_err(err)?;
        Ok(file)
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}
