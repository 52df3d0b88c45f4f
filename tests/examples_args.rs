//! The library examples' command lines (`quadtree_points`, `point_location`, `build_scale`; the
//! command-line program has its own tests), run as a user runs them: every example answers
//! `--help` (usage text, exit 0); an unknown option, a missing or bad value, work too large for
//! memory and an output path in a missing folder each give one `error:` line naming the
//! argument and exit 2, at once and never with a panic; small valid runs succeed.
//!
//! The binaries are the ones `cargo test` builds next to this test (in the profile's
//! `examples/` folder). When they are missing or older than the sources (this file run alone,
//! `cargo test --test examples_args`), they are built first with `cargo build
//! --examples` of the same profile.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;
use std::time::{Duration, SystemTime};

/// The examples covered here.
const EXAMPLES: [&str; 3] = ["point_location", "quadtree_points", "build_scale"];

/// The profile's folder (`target/debug` for `cargo test`, `target/release` with `--release`):
/// this test runs from its `deps/` folder.
fn profile_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("the test's path");
    exe.parent()
        .and_then(Path::parent)
        .expect("the test runs from <profile>/deps")
        .to_path_buf()
}

/// The newest modification time under `dir` (the sources the examples are built from).
fn newest(dir: &Path) -> SystemTime {
    let mut newest = SystemTime::UNIX_EPOCH;
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
            } else if let Ok(t) = entry.metadata().and_then(|m| m.modified()) {
                newest = newest.max(t);
            }
        }
    }
    newest
}

/// The example binaries, built first if missing or stale.
fn binaries() -> &'static Path {
    static BUILT: OnceLock<PathBuf> = OnceLock::new();
    BUILT.get_or_init(|| {
        let profile = profile_dir();
        let dir = profile.join("examples");
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let sources = ["src", "examples", "benches"]
            .iter()
            .map(|d| newest(&root.join(d)))
            .max()
            .unwrap_or(SystemTime::UNIX_EPOCH);
        let fresh = EXAMPLES.iter().all(|name| {
            std::fs::metadata(dir.join(format!("{name}{}", std::env::consts::EXE_SUFFIX)))
                .and_then(|m| m.modified())
                .is_ok_and(|t| t >= sources)
        });
        if !fresh {
            let mut build = Command::new(env!("CARGO"));
            build.current_dir(root).args(["build", "--examples"]);
            // `target/release` holds the release profile's builds, `target/debug` the test
            // profile's (the one `cargo test` builds with).
            if profile.file_name().is_some_and(|n| n == "release") {
                build.arg("--release");
            } else {
                build.args(["--profile", "test"]);
            }
            let out = build.output().expect("run cargo build --examples");
            assert!(
                out.status.success(),
                "cargo build --examples failed:\n{}",
                String::from_utf8_lossy(&out.stderr)
            );
        }
        dir
    })
}

#[path = "programs/mod.rs"]
mod programs;

use programs::{scratch_dir, Run};

/// Runs example `name` with `args` in `cwd` (a fresh folder when `None`), killing it after
/// `limit`.
fn run_in(name: &str, args: &[&str], cwd: Option<&Path>, limit: Duration) -> Run {
    let exe = binaries().join(format!("{name}{}", std::env::consts::EXE_SUFFIX));
    programs::run(&exe, name, args, cwd, limit)
}

fn run(name: &str, args: &[&str]) -> Run {
    run_in(name, args, None, Duration::from_secs(120))
}

/// `name args` is refused at once: exit 2, one error line naming every string in `named`, the
/// usage line after it.
fn refused(name: &str, args: &[&str], named: &[&str]) -> String {
    programs::refusal(
        &run(name, args),
        name,
        args,
        named,
        &format!("usage: {name}"),
    )
}

#[test]
fn every_example_answers_help() {
    for name in EXAMPLES {
        for flag in ["--help", "-h"] {
            let r = run(name, &[flag]);
            assert_eq!(r.code, 0, "{name} {flag}: {}", r.stderr);
            assert!(
                r.stdout.starts_with(&format!("usage: {name}")),
                "{name}: {}",
                r.stdout
            );
            assert!(
                r.stdout.contains("--help"),
                "{name}: the options are listed"
            );
            assert!(r.stderr.is_empty(), "{name} {flag}: {}", r.stderr);
        }
        // --help wins wherever it stands, even after a bad argument's value.
        let r = run(name, &["--help", "--no-such-option"]);
        assert_eq!(r.code, 0, "{name}: {}", r.stderr);
    }
}

#[test]
fn unknown_options_and_stray_arguments_are_named() {
    for name in EXAMPLES {
        for arg in ["--no-such-option", "-x", "--N", "--help=1"] {
            refused(name, &[arg], &[arg]);
        }
    }
    refused("quadtree_points", &["stray"], &["stray"]);
    refused(
        "point_location",
        &["a.svg", "b.svg"],
        &["b.svg", "only one"],
    );
}

#[test]
fn missing_and_bad_values_are_named() {
    let cases: [(&str, &str); 1] = [("quadtree_points", "--n")];
    for (name, flag) in cases {
        let missing = refused(name, &[flag], &[flag]);
        assert!(missing.contains("needs a value"), "{missing}");
        refused(name, &[flag, "--help"], &[flag, "needs a value"]);
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
    refused("quadtree_points", &["--n", "0"], &["--n", "0"]);
    refused("build_scale", &["--runs", "0"], &["--runs", "0"]);
}

#[test]
fn work_too_large_for_memory_is_estimated_and_refused() {
    for n in ["100000000000", "18446744073709551615", "10000000000000"] {
        refused(
            "quadtree_points",
            &["--n", n],
            &["--n", n, "estimated", "the limit is"],
        );
    }
    // within build_scale's range of counts, beyond this machine's memory
    refused(
        "build_scale",
        &["--n", "4000000000"],
        &["--n", "estimated", "the limit is"],
    );
}

#[test]
fn outputs_in_missing_folders_are_refused_before_any_work() {
    let missing = ["no-such-folder/picture.svg", "a/b/c/picture.svg"];
    for path in missing {
        refused("point_location", &[path], &[path, "does not exist"]);
        refused(
            "point_location",
            &["--out", path],
            &["--out", path, "does not exist"],
        );
    }
    refused("point_location", &["--out", "."], &["--out", "is a folder"]);
    for dir in ["no-such-folder", "a/b/c"] {
        refused(
            "quadtree_points",
            &["--out-dir", dir],
            &["--out-dir", dir, "does not exist"],
        );
    }
}

#[test]
fn small_valid_runs_succeed() {
    let dir = scratch_dir("outputs");
    let r = run_in(
        "quadtree_points",
        &["--n", "300", "--out-dir", dir.to_str().unwrap()],
        None,
        Duration::from_secs(60),
    );
    assert_eq!(r.code, 0, "{}", r.stderr);
    for file in ["quadtree_uniform.svg", "quadtree_clustered.svg"] {
        assert!(dir.join(file).is_file(), "{file} written");
    }
    let svg = dir.join("located.svg");
    let r = run("point_location", &["--out", svg.to_str().unwrap()]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(svg.is_file());
    let _ = std::fs::remove_dir_all(&dir);
    let r = run("build_scale", &["--n", "5000", "--runs", "2"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    // two builds of the same points: the same tree, digest and all
    let digests: Vec<&str> = r
        .stdout
        .lines()
        .filter_map(|l| l.split("items digest ").nth(1))
        .collect();
    assert_eq!(digests.len(), 2, "{}", r.stdout);
    assert_eq!(digests[0], digests[1]);
    assert!(r.stdout.contains("n 5000 build: median"), "{}", r.stdout);
}

#[test]
fn a_closed_or_full_standard_output_is_handled() {
    let dir = scratch_dir("closed-pipe");
    let out_dir = dir.to_str().unwrap();
    let svg = dir.join("located.svg");
    for (name, args) in [
        ("quadtree_points", vec!["--n", "300", "--out-dir", out_dir]),
        ("point_location", vec!["--out", svg.to_str().unwrap()]),
        ("build_scale", vec!["--n", "5000", "--runs", "2"]),
        ("build_scale", vec!["--help"]),
    ] {
        let exe = binaries().join(format!("{name}{}", std::env::consts::EXE_SUFFIX));
        programs::check_unwritable_output(&exe, name, &args, true);
    }
    let _ = std::fs::remove_dir_all(&dir);
}
