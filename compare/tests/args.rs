//! The comparison programs' command lines (`compare`, `mesh_compare`), run as a user runs them:
//! `--help` (exit 0); an unknown option, a missing or bad value and work too large for memory
//! each give one `error:` line naming the argument and exit 2, at once and never with a panic;
//! small valid runs succeed, their answers checked equal across the crates.

use std::path::Path;

use std::time::Duration;

const PROGRAMS: [&str; 3] = ["compare", "mesh_compare", "joins_compare"];

#[path = "../../tests/programs/mod.rs"]
mod programs;

use programs::Run;

/// Runs program `name` with `args` in a fresh folder, killing it after two minutes.
fn run(name: &str, args: &[&str]) -> Run {
    let exe = match name {
        "compare" => env!("CARGO_BIN_EXE_compare"),
        "joins_compare" => env!("CARGO_BIN_EXE_joins_compare"),
        _ => env!("CARGO_BIN_EXE_mesh_compare"),
    };
    programs::run(Path::new(exe), name, args, None, Duration::from_secs(120))
}

/// `name args` is refused at once: exit 2, one error line naming every string in `named`, the
/// pointer to `--help` after it.
fn refused(name: &str, args: &[&str], named: &[&str]) -> String {
    programs::refusal(&run(name, args), name, args, named, "--help")
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
    let cases: [(&str, &str); 9] = [
        ("compare", "--n"),
        ("compare", "--queries"),
        ("compare", "--reps"),
        ("compare", "--dim"),
        ("mesh_compare", "--seeds"),
        ("mesh_compare", "--runs"),
        ("joins_compare", "--n"),
        ("joins_compare", "--queries"),
        ("joins_compare", "--reps"),
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
    refused("compare", &["--dim", "9"], &["--dim", "from 2 to 8"]);
    refused(
        "compare",
        &["--dim", "5"],
        &["--dim", "one of 2, 3, 4, 6 and 8"],
    );
    refused(
        "compare",
        &["--workload", "gaussian"],
        &["--workload", "gaussian"],
    );
    refused(
        "joins_compare",
        &["--workload", "knn"],
        &["--workload", "knn"],
    );
    refused("joins_compare", &["--n", "99"], &["--n", "99", "from 100"]);
    for (name, flag) in [
        ("compare", "--n"),
        ("compare", "--queries"),
        ("compare", "--reps"),
        ("mesh_compare", "--runs"),
        ("joins_compare", "--queries"),
        ("joins_compare", "--reps"),
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
        "joins_compare",
        &["--n", "4000000000"],
        &["--n", "4000000000", "estimated", "the limit is"],
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
        &["--n", "300", "--queries", "3", "--reps", "1", "--dim", "8"],
    ] {
        let r = run("compare", args);
        assert_eq!(r.code, 0, "compare {args:?}: {}", r.stderr);
        assert!(r
            .stdout
            .contains("| workload | operation | orthtree | kiddo | rstar |"));
    }
    // the workloads one at a time
    for workload in ["lattice", "sphere", "off-data"] {
        let args = [
            "--n",
            "2000",
            "--queries",
            "50",
            "--reps",
            "1",
            "--workload",
            workload,
        ];
        let r = run("compare", &args);
        assert_eq!(r.code, 0, "compare {args:?}: {}", r.stderr);
        assert!(r.stdout.contains(&format!("| {workload}")), "{}", r.stdout);
    }
    let r = run("mesh_compare", &["--target", "--runs", "1"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
}

#[test]
fn a_closed_or_full_standard_output_is_handled() {
    let exe = Path::new(env!("CARGO_BIN_EXE_compare"));
    let args = ["--n", "300", "--queries", "5", "--reps", "1", "--dim", "2"];
    programs::check_unwritable_output(exe, "compare", &args, true);
}
