//! `joins_compare` on small inputs: every crate's answer to each workload agrees with
//! orthtree's (and orthtree's with a brute-force count), scipy's output is read and converted
//! as the program needs, and a missing scipy is reported, not a failure. The runs through
//! scipy are skipped when `compare/scipy/setup.sh` has not been run.

use orthtree_compare::joins::{self, Answer};
use orthtree_compare::points::uniform;
use orthtree_compare::scipy::{self, Scipy, ScipyRun};
use std::path::Path;
use std::time::Duration;

// Shared with the other program tests; this file uses only `run`.
#[allow(dead_code)]
#[path = "../../tests/programs/mod.rs"]
mod programs;

/// Runs `joins_compare` with `args`, killing it after three minutes.
fn run(args: &[&str]) -> programs::Run {
    let exe = Path::new(env!("CARGO_BIN_EXE_joins_compare"));
    programs::run(exe, "joins_compare", args, None, Duration::from_secs(180))
}

/// scipy when it is set up; else `None`, with a note on stderr.
fn scipy() -> Option<Scipy> {
    let s = Scipy::find(&scipy::default_python());
    if s.is_none() {
        eprintln!("{}: skipping its runs", scipy::NOT_SET_UP);
    }
    s
}

/// The squared distance of two points.
fn d2(p: &[f64; 3], q: &[f64; 3]) -> f64 {
    (0..3).map(|a| (p[a] - q[a]).powi(2)).sum()
}

#[test]
fn a_small_run_of_every_workload_agrees_and_prints_its_rows() {
    let r = run(&["--n", "2000", "--queries", "300", "--reps", "1"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    for row in [
        "| periodic 10-nearest, 300 queries |",
        "| self-join 16-nearest |",
        "| all pairs within r (~10 per point) |",
        "| count_neighbors, 20 radii |",
        "| count_neighbors, 20 radii (build) |",
    ] {
        assert!(r.stdout.contains(row), "{row}: {}", r.stdout);
    }
    let set_up = scipy().is_some();
    assert_eq!(
        !set_up,
        r.stdout.contains(scipy::NOT_SET_UP),
        "{}",
        r.stdout
    );
    // Every row has a time for orthtree and kiddo (not for kiddo's missing count query) and, when
    // set up, for scipy.
    for line in r
        .stdout
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| workload") && !l.starts_with("| ---"))
    {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        assert!(cells[3].parse::<f64>().is_ok(), "orthtree: {line}");
        assert_eq!(
            cells[4].parse::<f64>().is_ok(),
            !line.contains("count_neighbors"),
            "kiddo: {line}"
        );
        assert_eq!(cells[5].parse::<f64>().is_ok(), set_up, "scipy: {line}");
    }
}

#[test]
fn a_missing_python_is_reported_and_the_rest_still_runs() {
    let r = run(&[
        "--n",
        "500",
        "--reps",
        "1",
        "--workload",
        "pairs",
        "--python",
        "/no/such/python",
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(r.stdout.contains(scipy::NOT_SET_UP), "{}", r.stdout);
    assert!(
        r.stdout
            .contains("| all pairs within r (~10 per point) | 1 |"),
        "{}",
        r.stdout
    );
}

#[test]
fn orthtree_and_kiddo_agree_with_brute_force_on_pairs_and_counts() {
    let pts = joins::surface(1500, 11);
    let r = joins::radius_for(&pts, 10.0);
    let mut all: Vec<(f64, u64)> = Vec::new();
    for i in 0..pts.len() {
        for j in i + 1..pts.len() {
            all.push((d2(&pts[i], &pts[j]), (i + j) as u64));
        }
    }
    let within = |x: f64| all.iter().filter(move |(d, _)| *d <= x * x);
    let pairs = within(r).count() as u64;
    // About 10 neighbours per point: 5 pairs per point.
    assert!(
        (3 * pts.len() as u64..8 * pts.len() as u64).contains(&pairs),
        "{pairs}"
    );
    let want = Answer::Found(orthtree_compare::rivals::Answers {
        count: pairs,
        items: Some(within(r).map(|(_, s)| s).sum()),
        distance: None,
    });
    for got in [
        joins::orthtree_pairs(&pts, r, 1),
        joins::kiddo_pairs(&pts, r, 1),
    ] {
        assert_eq!(got.answer, want);
    }
    let radii = joins::log_radii(r / 4.0, 4.0 * r, 20);
    let counts: Vec<u64> = radii.iter().map(|&x| within(x).count() as u64).collect();
    assert_eq!(
        joins::orthtree_counts(&pts, &radii, 1).answer,
        Answer::Counts(counts)
    );
}

#[test]
fn orthtree_and_kiddo_agree_on_periodic_and_self_knn() {
    let (pts, qs) = (uniform::<3>(3000, 5), uniform::<3>(200, 6));
    let (a, b, c) = (
        joins::orthtree_periodic(&pts, &qs, 10, 1, false),
        joins::kiddo_periodic(&pts, &qs, 10, 1),
        joins::orthtree_periodic(&pts, &qs, 10, 1, true),
    );
    for other in [&b, &c] {
        assert!(
            a.answer.agrees_with(&other.answer, true),
            "{:?} {:?}",
            a.answer,
            other.answer
        );
    }
    // One query's answer against a scan over the 27 images.
    let q = qs[0];
    let mut best: Vec<f64> = pts
        .iter()
        .map(|p| {
            (0..27)
                .map(|c| {
                    let s = [c % 3, c / 3 % 3, c / 9].map(|v| f64::from(v) - 1.0);
                    d2(&q, &[p[0] + s[0], p[1] + s[1], p[2] + s[2]])
                })
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    best.sort_by(f64::total_cmp);
    let one = joins::orthtree_periodic(&pts, &qs[..1], 10, 1, false);
    let Answer::Found(f) = one.answer else {
        panic!("neighbours")
    };
    let want: f64 = best[..10].iter().sum();
    assert!((f.distance.unwrap() - want).abs() <= 1e-12, "{f:?} {want}");

    let surface = joins::surface(2500, 8);
    let (a, b) = (
        joins::orthtree_self_knn(&surface, 16, 1),
        joins::kiddo_self_knn(&surface, 16, 1),
    );
    assert!(
        a.answer.agrees_with(&b.answer, false),
        "{:?} {:?}",
        a.answer,
        b.answer
    );
    let Answer::Found(f) = a.answer else {
        panic!("neighbours")
    };
    assert_eq!(f.count, 2500 * 16);
}

#[test]
fn scipy_agrees_when_set_up() {
    let Some(sp) = scipy() else { return };
    let pts = joins::surface(2000, 9);
    let r = joins::radius_for(&pts, 10.0);
    let ours = joins::orthtree_pairs(&pts, r, 1);
    let theirs = sp
        .run("pairs", &pts, None, &[format!("--r={r:e}")], 1)
        .unwrap()
        .into_run(pts.len())
        .unwrap();
    assert_eq!(ours.answer, theirs.answer);
    let radii = joins::log_radii(r / 4.0, 4.0 * r, 20);
    let list: Vec<String> = radii.iter().map(|x| format!("{x:e}")).collect();
    let theirs = sp
        .run(
            "count",
            &pts,
            None,
            &[format!("--radii={}", list.join(","))],
            1,
        )
        .unwrap()
        .into_run(pts.len())
        .unwrap();
    assert_eq!(
        joins::orthtree_counts(&pts, &radii, 1).answer,
        theirs.answer
    );
}

#[test]
fn scipy_output_is_parsed_and_bad_lines_are_named() {
    let r = ScipyRun::parse("build 1.5\nquery 2.25\ncount 7\nitems 12\ndist2 0.5\n").unwrap();
    assert_eq!(
        (r.build_ms, r.query_ms, r.count, r.items, r.dist2),
        (1.5, 2.25, Some(7), Some(12), Some(0.5))
    );
    let e = ScipyRun::parse("build 1\nquery x\n").unwrap_err();
    assert!(e.contains("line 2") && e.contains("query x"), "{e}");
    let e = ScipyRun::parse("build 1\n").unwrap_err();
    assert!(e.contains("`query`"), "{e}");
    // count_neighbors' ordered counts with each point itself: 2 p + n.
    let c = ScipyRun::parse("build 1\nquery 1\ncounts 10,14,30\n").unwrap();
    assert_eq!(
        c.clone().into_run(10).unwrap().answer,
        Answer::Counts(vec![0, 2, 10])
    );
    let e = c.into_run(11).unwrap_err();
    assert!(e.contains("count 10 at radius 0"), "{e}");
}
