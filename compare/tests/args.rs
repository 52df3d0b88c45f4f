//! The comparison programs' command lines (`compare`, `mesh_compare`), run as a user runs them:
//! `--help` (exit 0); an unknown option, a missing or bad value and work too large for memory
//! each give one `error:` line naming the argument and exit 2, at once and never with a panic;
//! small valid runs succeed, their answers checked equal across the crates.

use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const PROGRAMS: [&str; 2] = ["compare", "mesh_compare"];

/// What one run gave.
struct Run {
    code: i32,
    stdout: String,
    stderr: String,
    took: Duration,
}

/// Runs program `name` with `args` in a fresh folder, killing it after `limit`.
fn run_in(name: &str, args: &[&str], limit: Duration) -> Run {
    let exe = match name {
        "compare" => env!("CARGO_BIN_EXE_compare"),
        _ => env!("CARGO_BIN_EXE_mesh_compare"),
    };
    let scratch = scratch_dir(name);
    let mut child = Command::new(exe)
        .args(args)
        .current_dir(&scratch)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("start {exe}: {e}"));
    let start = Instant::now();
    while child.try_wait().expect("wait for the example").is_none() {
        if start.elapsed() > limit {
            let _ = child.kill();
            panic!("{name} {args:?}: still running after {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    let took = start.elapsed();
    let out = child.wait_with_output().expect("the example's output");
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

fn run(name: &str, args: &[&str]) -> Run {
    run_in(name, args, Duration::from_secs(120))
}

/// A fresh empty folder for one run.
fn scratch_dir(name: &str) -> PathBuf {
    static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let k = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!(
        "orthtree-compare-{}-{name}-{k}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    dir
}

/// `name args` is refused at once: exit 2, one error line naming every string in `named`.
fn refused(name: &str, args: &[&str], named: &[&str]) -> String {
    let r = run(name, args);
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
        r.stderr.contains("--help"),
        "{name} {args:?}: the pointer to --help follows:\n{}",
        r.stderr
    );
    assert!(
        r.took < Duration::from_secs(20),
        "{name} {args:?}: refused only after {:?}",
        r.took
    );
    first
}

#[test]
fn every_program_answers_help() {
    for name in PROGRAMS {
        for flag in ["--help", "-h"] {
            let r = run(name, &[flag]);
            assert_eq!(r.code, 0, "{name} {flag}: {}", r.stderr);
            assert!(
                r.stdout.contains(&format!("Usage: {name}")),
                "{name}: {}",
                r.stdout
            );
            assert!(
                r.stdout.contains("--help"),
                "{name}: the options are listed"
            );
            assert!(r.stderr.is_empty(), "{name} {flag}: {}", r.stderr);
        }
        let r = run(name, &["--help", "--no-such-option"]);
        assert_eq!(r.code, 0, "{name}: {}", r.stderr);
    }
}

#[test]
fn unknown_options_and_stray_arguments_are_named() {
    for name in PROGRAMS {
        for arg in ["--no-such-option", "-x", "--N", "stray"] {
            refused(name, &[arg], &[arg]);
        }
        refused(name, &["--help=1"], &["--help", "1"]);
    }
}

#[test]
fn missing_and_bad_values_are_named() {
    let cases: [(&str, &str); 6] = [
        ("compare", "--n"),
        ("compare", "--queries"),
        ("compare", "--reps"),
        ("compare", "--dim"),
        ("mesh_compare", "--seeds"),
        ("mesh_compare", "--runs"),
    ];
    for (name, flag) in cases {
        let missing = refused(name, &[flag], &[flag]);
        assert!(missing.contains("a value is required"), "{missing}");
        refused(name, &[flag, "--help"], &[flag, "a value is required"]);
        for bad in [
            "abc",
            "-1",
            "1.5",
            "1e3",
            "",
            " ",
            "99999999999999999999999",
            "0x10",
        ] {
            refused(name, &[flag, bad], &[flag, "expected a number from"]);
        }
    }
    refused("compare", &["--dim", "4"], &["--dim", "from 2 to 3"]);
    refused(
        "compare",
        &["--workload", "gaussian"],
        &["--workload", "gaussian"],
    );
    for (name, flag) in [
        ("compare", "--n"),
        ("compare", "--queries"),
        ("compare", "--reps"),
        ("mesh_compare", "--runs"),
    ] {
        refused(name, &[flag, "0"], &[flag, "0"]);
    }
}

#[test]
fn work_too_large_for_memory_is_estimated_and_refused() {
    for n in ["100000000000", "18446744073709551615", "10000000000000"] {
        refused(
            "compare",
            &["--n", n],
            &["--n", n, "estimated", "the limit is"],
        );
    }
    refused(
        "compare",
        &["--queries", "100000000000"],
        &["--queries", "estimated"],
    );
    refused(
        "mesh_compare",
        &["--seeds", "1000000000"],
        &["--seeds", "to 10000"],
    );
}

#[test]
fn small_valid_runs_succeed() {
    for args in [
        &["--n", "1", "--queries", "1", "--reps", "1"][..],
        &["--n", "7", "--queries", "3", "--reps", "1", "--dim", "3"],
        &[
            "--n",
            "2000",
            "--queries",
            "50",
            "--reps",
            "1",
            "--workload",
            "lattice",
        ],
    ] {
        let r = run("compare", args);
        assert_eq!(r.code, 0, "compare {args:?}: {}", r.stderr);
        assert!(r
            .stdout
            .contains("| workload | operation | orthtree | kiddo | rstar |"));
    }
    let r = run("mesh_compare", &["--target", "--runs", "1"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
}
