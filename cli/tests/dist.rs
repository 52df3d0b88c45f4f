//! `orthtree dist-balance` and `orthtree dist-points` (feature `mpi`) run under `mpirun -np 2`
//! as a user runs them: the balanced fractal's leaf count and checksum equal the serial
//! `orthtree balance`'s, the point workload's checksums equal the one-rank run's, and bad
//! settings are refused with exit code 2 naming the option, before MPI starts.
#![cfg(feature = "mpi")]

use std::path::Path;
use std::time::Duration;

#[path = "../../tests/programs/mod.rs"]
mod programs;

use programs::Run;

const EXE: &str = env!("CARGO_BIN_EXE_orthtree");

/// Runs `orthtree args` directly (one process).
fn orthtree(args: &[&str]) -> Run {
    programs::run(
        Path::new(EXE),
        args[0],
        args,
        None,
        Duration::from_secs(300),
    )
}

/// Runs `mpirun -np np orthtree args`.
fn mpirun(np: usize, args: &[&str]) -> Run {
    programs::mpirun(np, Path::new(EXE), args, Duration::from_secs(300))
}

/// The text after `label` on its line of `out`, up to the first space or parenthesis.
fn field<'a>(out: &'a str, label: &str) -> &'a str {
    let line = out
        .lines()
        .find(|l| l.starts_with(label))
        .unwrap_or_else(|| panic!("{label:?} in:\n{out}"));
    line[label.len()..]
        .trim_start_matches([' ', ':'])
        .split([' ', '('])
        .next()
        .unwrap_or_default()
}

#[test]
fn dist_balance_at_two_ranks_equals_the_serial_balance() {
    for (dim, level, connect) in [
        ("2", "8", "corner"),
        ("3", "6", "corner"),
        ("3", "5", "face"),
    ] {
        let settings = ["--dim", dim, "--level", level, "--connect", connect];
        let serial = orthtree(&[&["balance"][..], &settings].concat());
        assert_eq!(serial.code, 0, "balance {settings:?}: {}", serial.stderr);
        let dist = mpirun(2, &[&["dist-balance", "--check"][..], &settings].concat());
        assert_eq!(dist.code, 0, "dist-balance {settings:?}: {}", dist.stderr);
        for label in ["leaves before balance", "leaves after balance", "checksum"] {
            let (a, b) = (field(&serial.stdout, label), field(&dist.stdout, label));
            assert!(!a.is_empty(), "{label} in {}", serial.stdout);
            assert_eq!(
                a, b,
                "{settings:?}: {label}\n{}\n{}",
                serial.stdout, dist.stdout
            );
        }
        assert!(dist.stdout.contains("2 ranks"), "{}", dist.stdout);
        assert!(dist.stdout.contains("same: true"), "{}", dist.stdout);
        assert!(dist.stdout.contains("local balance"), "{}", dist.stdout);
    }
}

#[test]
fn dist_points_checksums_are_the_same_at_one_and_two_ranks() {
    let args = [
        "dist-points",
        "--n",
        "20000",
        "--queries",
        "2000",
        "--k",
        "5",
    ];
    let one = mpirun(1, &args);
    let two = mpirun(2, &args);
    assert_eq!(one.code, 0, "{}", one.stderr);
    assert_eq!(two.code, 0, "{}", two.stderr);
    let sums = |out: &str| -> Vec<String> {
        out.lines()
            .filter(|l| l.contains("checksum"))
            .map(|l| l.split_once(':').map_or("", |(_, r)| r).trim().to_string())
            .collect()
    };
    let (a, b) = (sums(&one.stdout), sums(&two.stdout));
    assert_eq!(a.len(), 2, "uniform and clustered lines:\n{}", one.stdout);
    assert_eq!(a, b, "\n{}\n{}", one.stdout, two.stdout);
    // 2000 queries of 5 neighbours among 20000 points
    assert!(a[0].contains("10000 neighbours"), "{}", a[0]);
}

#[test]
fn bad_settings_are_refused_naming_the_option() {
    let r = orthtree(&["dist-balance", "--dim", "3", "--level", "22"]);
    programs::refusal(&r, "dist-balance", &[], &["--level 22", "21"], "--help");
    let r = orthtree(&["dist-balance", "--dim", "5"]);
    programs::refusal(&r, "dist-balance", &[], &["--dim"], "--help");
    let r = orthtree(&["dist-points", "--k", "0"]);
    programs::refusal(&r, "dist-points", &[], &["--k"], "--help");
    // work that would not fit in memory, refused before MPI starts
    let r = orthtree(&["dist-points", "--n", "200000000000000"]);
    programs::refusal(
        &r,
        "dist-points",
        &[],
        &["--n 200000000000000", "limit"],
        "--help",
    );
    let r = orthtree(&["dist-points", "--queries", "1000000000000", "--k", "1000"]);
    programs::refusal(
        &r,
        "dist-points",
        &[],
        &["--queries 1000000000000", "limit"],
        "--help",
    );
    let r = orthtree(&["dist-balance", "--dim", "2", "--level", "30"]);
    programs::refusal(&r, "dist-balance", &[], &["--level 30", "limit"], "--help");
}
