//! Running a program as a user runs it, for the command-line tests of the library's examples,
//! the command-line program and the comparison programs: start the binary with no standard
//! input in a fresh folder, capture its exit code, standard output and error and how long it
//! took, kill it past a time limit, and fail on any panic; then check a refusal (exit 2 with one
//! `error:` line naming the offending argument, at once).
//!
//! Each of those test files includes this one with `#[path = "..."] mod programs;`.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// What one run gave.
pub struct Run {
    /// The exit code.
    pub code: i32,
    /// Standard output, lossily decoded.
    pub stdout: String,
    /// Standard error, lossily decoded.
    pub stderr: String,
    /// Wall time from start to exit.
    pub took: Duration,
}

/// Runs `exe` with `args` in `cwd` (a fresh folder, removed afterwards, when `None`), killing it
/// after `limit`; `name` labels the messages and the scratch folder.
///
/// # Panics
///
/// When the program cannot start, is still running after `limit`, ends by a signal, or prints
/// a panic.
pub fn run(exe: &Path, name: &str, args: &[&str], cwd: Option<&Path>, limit: Duration) -> Run {
    let scratch = scratch_dir(name);
    let mut child = Command::new(exe)
        .args(args)
        .current_dir(cwd.unwrap_or(&scratch))
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("start {}: {e}", exe.display()));
    let start = Instant::now();
    while child.try_wait().expect("wait for the program").is_none() {
        if start.elapsed() > limit {
            let _ = child.kill();
            panic!("{name} {args:?}: still running after {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    let took = start.elapsed();
    let out = child.wait_with_output().expect("the program's output");
    let _ = std::fs::remove_dir_all(&scratch);
    let run = Run {
        code: out
            .status
            .code()
            .unwrap_or_else(|| panic!("{name} {args:?}: killed by a signal: {:?}", out.status)),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
        took,
    };
    assert!(
        !run.stderr.contains("panicked") && !run.stdout.contains("panicked"),
        "{name} {args:?} panicked:\n{}",
        run.stderr
    );
    run
}

/// Runs `mpirun -np np exe args` (oversubscribed, allowed as root, without the shared-memory
/// single-copy mechanism that containers refuse), as [`run`] runs a program.
///
/// # Panics
///
/// When OpenMPI's `mpirun` is missing, and as [`run`].
#[allow(dead_code)] // only the tests of the distributed programs use it
pub fn mpirun(np: usize, exe: &Path, args: &[&str], limit: Duration) -> Run {
    let mpirun = Command::new("mpirun").arg("--version").output();
    assert!(
        mpirun.is_ok_and(|o| o.status.success()),
        "mpirun (OpenMPI) is needed for the tests of the distributed programs"
    );
    let np = np.to_string();
    let name = exe
        .file_name()
        .map_or("mpirun".into(), |n| n.to_string_lossy());
    let exe = exe.to_string_lossy();
    let mut all = vec![
        "--allow-run-as-root",
        "--oversubscribe",
        "-x",
        "OMPI_MCA_btl_vader_single_copy_mechanism=none",
        "-np",
        &np,
        &exe,
    ];
    all.extend_from_slice(args);
    run(Path::new("mpirun"), &name, &all, None, limit)
}

/// Checks `exe args` against a standard output it cannot write. Into a pipe whose reading end
/// is already closed (as in `program | head` once `head` has quit) it stops printing and exits
/// 0, never with a panic. Into `/dev/full` (every write fails, as on a full disk; skipped where
/// the system has none), when `full_disk` is set, it exits 1 and its last line on standard
/// error says it cannot write to standard output.
///
/// # Panics
///
/// When either does not hold, or the program cannot start or ends by a signal.
#[allow(dead_code)] // the tests of the distributed commands do not use it
pub fn check_unwritable_output(exe: &Path, name: &str, args: &[&str], full_disk: bool) {
    let (reader, writer) = std::io::pipe().expect("a pipe");
    drop(reader);
    let (code, stderr) = run_into(exe, name, args, writer.into());
    assert_eq!(code, 0, "{name} {args:?} into a closed pipe: {stderr}");
    assert!(!stderr.contains("panicked"), "{name} {args:?}: {stderr}");
    let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") else {
        return;
    };
    if full_disk {
        let (code, stderr) = run_into(exe, name, args, full.into());
        assert_eq!(code, 1, "{name} {args:?} into /dev/full: {stderr}");
        let last = stderr.lines().last().unwrap_or_default();
        assert!(
            last.starts_with("error: cannot write to standard output"),
            "{name} {args:?}: {stderr}"
        );
    }
}

/// Runs `exe` with `args` in a fresh folder, standard output to `stdout`; its exit code and
/// standard error.
#[allow(dead_code)]
fn run_into(exe: &Path, name: &str, args: &[&str], stdout: Stdio) -> (i32, String) {
    let scratch = scratch_dir(name);
    let out = Command::new(exe)
        .args(args)
        .current_dir(&scratch)
        .stdin(Stdio::null())
        .stdout(stdout)
        .stderr(Stdio::piped())
        .output()
        .unwrap_or_else(|e| panic!("start {}: {e}", exe.display()));
    let _ = std::fs::remove_dir_all(&scratch);
    let code = out
        .status
        .code()
        .unwrap_or_else(|| panic!("{name} {args:?}: killed by a signal: {:?}", out.status));
    (code, String::from_utf8_lossy(&out.stderr).into_owned())
}

/// A fresh empty folder for one run, under the system's temporary folder.
pub fn scratch_dir(name: &str) -> PathBuf {
    static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let k = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!(
        "{}-{}-{name}-{k}",
        env!("CARGO_PKG_NAME"),
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    dir
}

/// Checks that run `r` of `name args` was a refusal: exit 2 within 20 seconds, a first line
/// `error: ...` that contains every string in `named`, and `follows` (the pointer to the usage)
/// somewhere on standard error. Returns the first line.
///
/// # Panics
///
/// When any of those does not hold.
pub fn refusal(r: &Run, name: &str, args: &[&str], named: &[&str], follows: &str) -> String {
    assert_eq!(
        r.code, 2,
        "{name} {args:?}: exit code; stderr:\n{}",
        r.stderr
    );
    let first = r.stderr.lines().next().unwrap_or_default().to_string();
    assert!(first.starts_with("error: "), "{name} {args:?}: {first}");
    for n in named {
        assert!(first.contains(n), "{name} {args:?}: {first:?} names {n:?}");
    }
    assert!(
        r.stderr.contains(follows),
        "{name} {args:?}: {follows:?} follows:\n{}",
        r.stderr
    );
    assert!(
        r.took < Duration::from_secs(20),
        "{name} {args:?}: refused only after {:?}",
        r.took
    );
    first
}
