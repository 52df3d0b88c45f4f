//! The command line, run as a user runs it: every command answers `--help` (usage text, exit
//! 0); an unknown option, a missing or bad value and work too large for memory each give one
//! `error:` line naming the argument and exit 2, at once and never with a panic; small valid
//! runs succeed.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

/// The commands covered here.
const COMMANDS: [&str; 5] = ["balance", "cloud", "heat", "image", "mesh"];

#[path = "../../tests/programs/mod.rs"]
mod programs;

use programs::{scratch_dir, Run};

/// Runs `orthtree name args` in `cwd` (a fresh folder when `None`), killing it after `limit`.
fn run_in(name: &str, args: &[&str], cwd: Option<&Path>, limit: Duration) -> Run {
    let exe = Path::new(env!("CARGO_BIN_EXE_orthtree"));
    let all: Vec<&str> = std::iter::once(name).chain(args.iter().copied()).collect();
    programs::run(exe, name, &all, cwd, limit)
}

fn run(name: &str, args: &[&str]) -> Run {
    run_in(name, args, None, Duration::from_secs(120))
}

/// `name args` is refused at once: exit 2, one error line naming every string in `named`, the
/// pointer to `--help` after it.
fn refused(name: &str, args: &[&str], named: &[&str]) -> String {
    programs::refusal(&run(name, args), name, args, named, "--help")
}

#[test]
fn every_command_answers_help() {
    for top in [&["--help"][..], &["-h"], &["help"]] {
        let r = run_top(top);
        assert_eq!(r.code, 0, "orthtree {top:?}: {}", r.stderr);
        assert!(
            r.stdout.contains("Usage: orthtree <COMMAND>"),
            "{}",
            r.stdout
        );
        for name in COMMANDS {
            assert!(r.stdout.contains(name), "orthtree --help lists {name}");
        }
        assert!(r.stdout.contains("Exit codes:"), "{}", r.stdout);
    }
    for name in COMMANDS {
        for flag in ["--help", "-h"] {
            let r = run(name, &[flag]);
            assert_eq!(r.code, 0, "{name} {flag}: {}", r.stderr);
            assert!(
                r.stdout.contains(&format!("Usage: orthtree {name}")),
                "{name}: {}",
                r.stdout
            );
            assert!(
                r.stdout.contains("--help"),
                "{name}: the options are listed"
            );
            assert!(r.stdout.contains("Exit codes:"), "{name}: {}", r.stdout);
            assert!(r.stderr.is_empty(), "{name} {flag}: {}", r.stderr);
        }
        // --help wins wherever it stands, even before a bad argument.
        let r = run(name, &["--help", "--no-such-option"]);
        assert_eq!(r.code, 0, "{name}: {}", r.stderr);
    }
    // No command, or an unknown one: a usage error.
    for top in [&[][..], &["no-such-command"]] {
        let r = run_top(top);
        assert_eq!(r.code, 2, "orthtree {top:?}: {}", r.stderr);
    }
}

/// Runs `orthtree args` (no command chosen by the test).
fn run_top(args: &[&str]) -> Run {
    let (name, rest) = match args.split_first() {
        Some((first, rest)) => (*first, rest),
        None => ("", &[][..]),
    };
    if name.is_empty() {
        let out = Command::new(env!("CARGO_BIN_EXE_orthtree"))
            .stdin(Stdio::null())
            .output()
            .expect("run orthtree");
        return Run {
            code: out.status.code().expect("an exit code"),
            stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
            stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
            took: Duration::ZERO,
        };
    }
    run(name, rest)
}

#[test]
fn unknown_options_and_stray_arguments_are_named() {
    for name in COMMANDS {
        for arg in ["--no-such-option", "-x", "--N"] {
            refused(name, &[arg], &[arg]);
        }
        // A value given to a flag that takes none.
        refused(name, &["--help=1"], &["--help", "1"]);
    }
    refused("balance", &["stray"], &["stray"]);
    refused("heat", &["a.poly", "b.poly"], &["b.poly"]);
    refused("mesh", &["a.poly", "b.poly"], &["b.poly"]);
    refused("image", &["a.pbm", "b.pbm", "c.pbm"], &["c.pbm"]);
}

#[test]
fn missing_and_bad_values_are_named() {
    let cases: [(&str, &str); 5] = [
        ("balance", "--level"),
        ("balance", "--dim"),
        ("balance", "--reps"),
        ("heat", "--max-triangles"),
        ("mesh", "--max-triangles"),
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
            let named = if name == "mesh" {
                vec![flag, "invalid value"]
            } else {
                vec![flag, "expected a number from"]
            };
            refused(name, &[flag, bad], &named);
        }
    }
    // heat --size needs a board file, so it is checked with one.
    for bad in ["abc", "-1", "1.5", "0", "2147483648", ""] {
        refused(
            "heat",
            &["board.poly", "--size", bad],
            &["--size", "expected a number from 1"],
        );
    }
    refused(
        "balance",
        &["--connect", "diagonal"],
        &["--connect", "diagonal"],
    );
    refused("balance", &["--dim", "5"], &["--dim", "5", "from 2 to 4"]);
    refused("mesh", &["--mode", "fine"], &["--mode", "fine"]);
    refused(
        "image",
        &["a.pbm", "--op", "nand", "--out", "c.pbm"],
        &["--op", "nand"],
    );
    for zero in [("balance", "--reps"), ("heat", "--max-triangles")] {
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
        refused("heat", &["--random", random], &["--random"]);
        refused("mesh", &["--random", random], &["--random"]);
    }
    for name in ["heat", "mesh"] {
        refused(
            name,
            &["--random", "1,64,3", "--size", "64"],
            &["--size", "--random"],
        );
        refused(name, &["board.poly", "--random", "1,64,3"], &["--random"]);
        // --size without a board file: the built-in board has its own size.
        refused(name, &["--size", "64"], &["--size"]);
    }
    refused(
        "mesh",
        &["--random", "1,1024,100001"],
        &["--random", "100000"],
    );
    refused("image", &["a.pbm"], &["--op", "--out"]);
    refused("image", &["--op", "xor"], &["--out"]);
}

#[test]
fn work_too_large_for_memory_is_estimated_and_refused() {
    // Levels past the tree's deepest level, then levels whose leaves cannot fit in memory.
    for (dim, level, deepest) in [("2", "40", "32"), ("3", "22", "21"), ("4", "255", "16")] {
        refused(
            "balance",
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
            "balance",
            &["--dim", dim, "--level", level],
            &["--level", level, "leaves", "estimated", "the limit is"],
        );
    }
    // heat's random boards: counts above the capacity (U / 2)^2, then counts that fit the
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
        refused("heat", &["--random", random], &["--random", named]);
    }
    // mesh's random boards: counts above the capacity, before any work (a panic before).
    for (random, named) in [
        ("1,8,17", "at most 16"),
        ("1,16,65", "at most 64"),
        ("1,1024,262145", "at most 262144"),
    ] {
        refused("mesh", &["--random", random], &["--random", named]);
    }
}

#[test]
fn outputs_in_missing_folders_are_refused_before_any_work() {
    for prefix in ["no-such-folder/board", "a/b/c/board", ""] {
        refused("mesh", &["--out", prefix], &["--out"]);
    }
    // image: the input need not exist, the output is refused first; so is a format it cannot
    // write.
    for out in ["no-such-folder/c.pbm", "", "c.gif", "c"] {
        refused(
            "image",
            &["no-such-input.pbm", "--op", "not", "--out", out],
            &["--out"],
        );
    }
}

#[test]
fn a_closed_or_full_standard_output_is_handled() {
    let exe = Path::new(env!("CARGO_BIN_EXE_orthtree"));
    for args in [
        &["mesh", "--random", "2,8,16", "--no-files"][..],
        &["balance", "--dim", "2", "--level", "3"],
        &["image", "--help"],
        &["--help"],
    ] {
        // Clap prints `--help` itself, ignoring a failed write.
        let full_disk = !args.contains(&"--help");
        programs::check_unwritable_output(exe, args[0], args, full_disk);
    }
}

#[test]
fn small_valid_runs_succeed() {
    // balance: the leaf estimate its memory check uses is exact.
    for (dim, level) in [("2", "0"), ("2", "3"), ("2", "7"), ("3", "5"), ("4", "4")] {
        let r = run("balance", &["--dim", dim, "--level", level]);
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
    // mesh: random boards, every file written, and nothing with --no-files.
    let dir = scratch_dir("mesh-out");
    for random in ["1,64,10", "2,8,16", "3,1024,0"] {
        let prefix = dir.join(format!("r{}", &random[..1]));
        let r = run(
            "mesh",
            &["--random", random, "--out", prefix.to_str().unwrap()],
        );
        assert_eq!(r.code, 0, "mesh --random {random}: {}", r.stderr);
        assert!(r.stdout.contains("validation:  ok"), "{}", r.stdout);
        for ext in ["node", "ele", "edge", "msh", "vtk", "svg"] {
            assert!(prefix.with_extension(ext).is_file(), "{random}: .{ext}");
        }
        let r = run(
            "mesh",
            &["--random", random, "--no-files", "--mode", "coarsest"],
        );
        assert_eq!(r.code, 0, "{}", r.stderr);
        assert!(r.stdout.contains("wrote:       nothing"), "{}", r.stdout);
    }
    // A board file that is not there, or that is not a board: exit 1, naming the file once.
    std::fs::write(
        dir.join("touching.txt"),
        "size 8\n1 1 3 1 3 3\n3 1 5 1 5 3\n",
    )
    .unwrap();
    for (board, why) in [
        ("no-such-board.poly", "No such file"),
        ("touching.txt", "must not touch"),
    ] {
        // without its feature, `heat` says how to rebuild before it reads anything
        let commands: &[&str] = if cfg!(feature = "heat") {
            &["mesh", "heat"]
        } else {
            &["mesh"]
        };
        for &command in commands {
            let r = run_in(command, &[board], Some(&dir), Duration::from_secs(60));
            assert_eq!(r.code, 1, "{}", r.stderr);
            assert!(
                r.stderr.starts_with("error: ") && r.stderr.contains(why),
                "{}",
                r.stderr
            );
            assert_eq!(r.stderr.matches(board).count(), 1, "{}", r.stderr);
        }
    }
    // image: the built-in demo, then its output read back and complemented.
    let r = run_in("image", &[], Some(&dir), Duration::from_secs(60));
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(dir.join("image_ops.pbm").is_file() && dir.join("image_ops.svg").is_file());
    let out = dir.join("not.pbm");
    let r = run_in(
        "image",
        &[
            "image_ops.pbm",
            "--op",
            "not",
            "--out",
            out.to_str().unwrap(),
        ],
        Some(&dir),
        Duration::from_secs(60),
    );
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(out.is_file());
    let r = run_in(
        "image",
        &["image_ops.pbm", "--op", "xor", "--out", "x.pbm"],
        Some(&dir),
        Duration::from_secs(60),
    );
    assert_eq!(r.code, 2, "xor of one image: {}", r.stderr);
    // the operation as the first word: the image against itself, then its complement
    for (args, code) in [
        (
            &["xor", "image_ops.pbm", "image_ops.pbm", "--out", "x.pbm"][..],
            0,
        ),
        (&["NOT", "image_ops.pbm", "--out", "not2.pbm"][..], 0),
        // with --op, the first word is an image: three of them
        (
            &["xor", "a.pbm", "b.pbm", "--op", "and", "--out", "x.pbm"][..],
            2,
        ),
    ] {
        let r = run_in("image", args, Some(&dir), Duration::from_secs(60));
        assert_eq!(r.code, code, "{args:?}: {}", r.stderr);
    }
    let xor_self = orthtree::io::pbm::read(dir.join("x.pbm")).unwrap();
    assert_eq!((xor_self.extent(), xor_self.len()), ([512, 384], 0));
    assert_eq!(
        std::fs::read(dir.join("not2.pbm")).unwrap(),
        std::fs::read(&out).unwrap()
    );
    let r = run_in("image", &["--help"], None, Duration::from_secs(60));
    assert!(r.stdout.contains("[OP] IMAGE"), "{}", r.stdout);
    let _ = std::fs::remove_dir_all(&dir);
    heat_runs();
}

/// heat on small random boards, or without the `heat` feature the rebuild message (exit 1).
fn heat_runs() {
    for random in ["1,64,10", "2,8,16", "3,1024,0"] {
        let r = run("heat", &["--random", random, "--no-files"]);
        if cfg!(feature = "heat") {
            assert_eq!(r.code, 0, "heat --random {random}: {}", r.stderr);
            assert!(r.stdout.contains("temperature:"), "{}", r.stdout);
        } else {
            assert_eq!(r.code, 1, "heat --random {random}: {}", r.stderr);
            assert!(r.stderr.contains("--features heat"), "{}", r.stderr);
        }
    }
}
