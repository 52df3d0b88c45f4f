//! The examples' command lines, run as a user runs them: every example answers `--help` (usage
//! text, exit 0); an unknown option, a missing or bad value, work too large for memory and an
//! output path in a missing folder each give one `error:` line naming the argument and exit 2,
//! at once and never with a panic; small valid runs succeed.
//!
//! The binaries are the ones `cargo test` builds next to this test (in the profile's
//! `examples/` folder). When they are missing or older than the sources (this file run alone,
//! `cargo test --release --test examples_args`), they are built first with `cargo build
//! --examples` of the same profile.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::OnceLock;
use std::time::{Duration, Instant, SystemTime};

/// The examples covered here.
const EXAMPLES: [&str; 6] = [
    "balance_fractal",
    "compare",
    "mesh_compare",
    "pcb_heat",
    "point_location",
    "quadtree_points",
];

/// The profile's folder (`target/release`): this test runs from its `deps/` folder.
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
            if profile.file_name().is_some_and(|n| n == "release") {
                build.arg("--release");
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

/// What one run gave.
struct Run {
    code: i32,
    stdout: String,
    stderr: String,
    took: Duration,
}

/// Runs example `name` with `args` in `cwd` (a fresh folder when `None`), killing it after
/// `limit`.
fn run_in(name: &str, args: &[&str], cwd: Option<&Path>, limit: Duration) -> Run {
    let exe = binaries().join(format!("{name}{}", std::env::consts::EXE_SUFFIX));
    let scratch = scratch_dir(name);
    let mut child = Command::new(&exe)
        .args(args)
        .current_dir(cwd.unwrap_or(&scratch))
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("start {}: {e}", exe.display()));
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
    run_in(name, args, None, Duration::from_secs(120))
}

/// A fresh empty folder for one run.
fn scratch_dir(name: &str) -> PathBuf {
    static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let k = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!(
        "orthtree-examples-{}-{name}-{k}",
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
        r.stderr.contains(&format!("usage: {name}")),
        "{name} {args:?}: the usage line follows:\n{}",
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
    for name in [
        "balance_fractal",
        "compare",
        "mesh_compare",
        "quadtree_points",
    ] {
        refused(name, &["stray"], &["stray"]);
    }
    refused(
        "point_location",
        &["a.svg", "b.svg"],
        &["b.svg", "only one"],
    );
    refused("pcb_heat", &["a.poly", "b.poly"], &["b.poly"]);
}

#[test]
fn missing_and_bad_values_are_named() {
    let cases: [(&str, &str); 11] = [
        ("balance_fractal", "--level"),
        ("balance_fractal", "--dim"),
        ("balance_fractal", "--reps"),
        ("compare", "--n"),
        ("compare", "--queries"),
        ("compare", "--reps"),
        ("compare", "--dim"),
        ("mesh_compare", "--seeds"),
        ("mesh_compare", "--runs"),
        ("quadtree_points", "--n"),
        ("pcb_heat", "--size"),
    ];
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
    refused(
        "balance_fractal",
        &["--connect", "diagonal"],
        &["--connect", "diagonal"],
    );
    refused(
        "balance_fractal",
        &["--dim", "5"],
        &["--dim", "5", "from 2 to 4"],
    );
    refused("compare", &["--dim", "4"], &["--dim", "from 2 to 3"]);
    refused(
        "compare",
        &["--workload", "gaussian"],
        &["--workload", "gaussian"],
    );
    for zero in [
        ("compare", "--n"),
        ("compare", "--queries"),
        ("compare", "--reps"),
        ("balance_fractal", "--reps"),
        ("mesh_compare", "--runs"),
        ("quadtree_points", "--n"),
        ("pcb_heat", "--size"),
    ] {
        refused(zero.0, &[zero.1, "0"], &[zero.1, "0"]);
    }
    for random in [
        "1,2",
        "1,2,3,4",
        "a,64,3",
        "1,64,x",
        "1,63,3",
        "1,4,1",
        "1,2147483648,3",
        ",",
    ] {
        refused("pcb_heat", &["--random", random], &["--random"]);
    }
    refused(
        "pcb_heat",
        &["--random", "1,64,3", "--size", "64"],
        &["--size", "--random"],
    );
    refused(
        "pcb_heat",
        &["board.poly", "--random", "1,64,3"],
        &["board.poly", "--random"],
    );
}

#[test]
fn work_too_large_for_memory_is_estimated_and_refused() {
    // Levels past the tree's deepest level, then levels whose leaves cannot fit in memory.
    for (dim, level, deepest) in [("2", "40", "32"), ("3", "22", "21"), ("4", "255", "16")] {
        refused(
            "balance_fractal",
            &["--dim", dim, "--level", level],
            &["--level", level, deepest],
        );
    }
    for (dim, level) in [
        ("2", "32"),
        ("2", "24"),
        ("3", "21"),
        ("3", "16"),
        ("4", "16"),
    ] {
        refused(
            "balance_fractal",
            &["--dim", dim, "--level", level],
            &["--level", level, "leaves", "estimated", "the limit is"],
        );
    }
    for n in ["100000000000", "18446744073709551615", "10000000000000"] {
        refused(
            "compare",
            &["--n", n],
            &["--n", n, "estimated", "the limit is"],
        );
        refused(
            "quadtree_points",
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
    // pcb_heat's random boards: counts above the capacity (U / 2)^2, then counts that fit the
    // board but whose mesh and solve would not fit in memory.
    for (random, named) in [
        ("1,8,17", "at most 16"),
        ("1,8,1000", "at most 16"),
        ("1,1024,262145", "at most 262144"),
        ("1,1073741824,100000000", "estimated"),
        (
            "1,1073741824,18446744073709551615",
            "at most 288230376151711744",
        ),
    ] {
        refused("pcb_heat", &["--random", random], &["--random", named]);
    }
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
    // balance_fractal: the leaf estimate its memory check uses is exact.
    for (dim, level) in [("2", "0"), ("2", "3"), ("2", "7"), ("3", "5"), ("4", "4")] {
        let r = run("balance_fractal", &["--dim", dim, "--level", level]);
        assert_eq!(r.code, 0, "{}", r.stderr);
        let field = |key: &str| {
            let line = r.stdout.lines().find(|l| l.starts_with(key)).unwrap();
            line[key.len()..].trim().to_string()
        };
        assert_eq!(
            field("leaves before balance:"),
            field("estimated before:"),
            "dim {dim}, level {level}"
        );
    }
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
    }
    let r = run("mesh_compare", &["--target", "--runs", "1"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    for random in ["1,64,10", "2,8,16", "3,1024,0"] {
        let r = run("pcb_heat", &["--random", random, "--no-files"]);
        assert_eq!(r.code, 0, "pcb_heat --random {random}: {}", r.stderr);
        assert!(r.stdout.contains("temperature:"), "{}", r.stdout);
    }
}
