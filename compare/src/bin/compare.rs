//! orthtree beside kiddo 6 (`ImmutableKdTree`) and rstar 0.12 (`RTree::bulk_load`) on the
//! standard workloads, in one process, single-threaded, each crate through its adapter
//! (`orthtree_compare::rivals`): prints a markdown table of median times and the ratio
//! orthtree / best rival per row (below 1: orthtree is faster).
//!
//! ```sh
//! cargo run --release -p orthtree-compare --bin compare          # N = 10^6, 10^5 queries
//! cargo run --release -p orthtree-compare --bin compare -- --n 100000 --queries 10000 --reps 3
//! cargo run --release -p orthtree-compare --features rayon --bin compare -- --parallel
//! cargo run --release -p orthtree-compare --bin compare -- --dim 3 --workload clustered
//! ```
//!
//! Then single updates, uniform points: `--queries` inserts of new points into a tree of N, then
//! their removals, in microseconds per insert + remove, for orthtree's `PointTree` (dense runs:
//! each update moves the points after it, so 1000 updates only), its `DynamicPointTree` (leaves
//! in chunks with slack, amortised O(depth)), kiddo's `MutableKdTree` and rstar's `RTree`; and
//! what the dynamic layout costs the queries (10-nearest and box, as above, against the
//! `PointTree` holding the same points).
//!
//! With `--parallel` (feature `rayon`) it also prints the speed-up of `par_build` over `build`
//! and of the batch `par_k_nearest` (k = 10) over one `k_nearest` call per query, on uniform
//! points, with all of rayon's threads.
//!
//! Workloads: D = 2 and 3 (or 4, 6 or 8 with `--dim`), f64; uniform in the unit cube, 64 Gaussian
//! clusters (sigma 0.01), duplicate-heavy (N / 8 uniform points, each 8 times), lattice (integer
//! grid points), a sphere's surface (points on the sphere of radius 1/2 in the unit cube, queries
//! uniform in the cube) and off-data queries (the clustered points, queries uniform in the cube).
//! Rows: build; box queries with about 100 results; radius queries with about 100 results;
//! k-nearest for k = 1, 10, 100. Query centres follow the data's distribution (but in the last
//! two); the box side and radius are calibrated so that the average answer holds about 100 points.
//! Every query's answer is consumed (item ids summed), and the sums are checked equal across the
//! crates. Each timing is the median of `--reps` runs after one untimed warm-up run.

use clap::Parser;
use orthtree::prelude::*;
use orthtree::{Aabb, Ball, DynamicPointTree, PointTree};
use orthtree_compare::limits;
use orthtree_compare::points::{self as common, Distribution};
use orthtree_compare::rivals::{Answers, Kiddo, Orthtree, Rival, Rstar, KIDDO_BUCKET};
use orthtree_compare::say;
use orthtree_compare::timing::time;
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};
use rstar::RTree;

/// orthtree beside kiddo and rstar: build, box, radius and k-nearest queries, then single
/// updates.
#[derive(Parser, Debug)]
#[command(name = "compare", allow_negative_numbers = true)]
struct Args {
    /// Points per workload; counts whose trees would not fit in memory are refused
    #[arg(long, value_name = "N", default_value_t = 1_000_000,
          value_parser = limits::number(1usize, usize::MAX))]
    n: usize,
    /// Queries per row and updates per tree
    #[arg(long, value_name = "Q", default_value_t = 100_000,
          value_parser = limits::number(1usize, usize::MAX))]
    queries: usize,
    /// Timed runs per row, median reported
    #[arg(long, value_name = "R", default_value_t = 5, value_parser = limits::number(1usize, 1000))]
    reps: usize,
    /// Only dimension D: 2 or 3 (both by default), or 4, 6 or 8
    #[arg(long, value_name = "D", value_parser = dimension)]
    dim: Option<usize>,
    /// Only workloads whose name starts with NAME (uniform, clustered, duplicates, lattice)
    #[arg(long, value_name = "NAME", value_parser = workload)]
    workload: Option<String>,
    /// Also rayon's speed-ups (needs the `rayon` feature)
    #[arg(long)]
    parallel: bool,
}

/// A `--dim` this program is built for.
fn dimension(raw: &str) -> Result<usize, String> {
    match limits::parse_number(raw, 2usize, 8)? {
        d @ (2 | 3 | 4 | 6 | 8) => Ok(d),
        _ => Err("expected a number from 2 to 8, one of 2, 3, 4, 6 and 8".into()),
    }
}

/// Calls `$f::<D>($args)` for each dimension `--dim` asks for: 2 and 3 when it is absent.
macro_rules! each_dimension {
    ($a:expr, $f:ident($($arg:expr),*)) => {
        match $a.dim {
            None => {
                $f::<2>($($arg),*);
                $f::<3>($($arg),*);
            }
            Some(2) => $f::<2>($($arg),*),
            Some(3) => $f::<3>($($arg),*),
            Some(4) => $f::<4>($($arg),*),
            Some(6) => $f::<6>($($arg),*),
            Some(8) => $f::<8>($($arg),*),
            Some(d) => unreachable!("--dim {d} is refused by its parser"),
        }
    };
}

/// A `--workload` that starts at least one workload's name.
fn workload(raw: &str) -> Result<String, String> {
    let known = [
        "uniform",
        "clustered",
        "duplicates x8",
        "lattice",
        "sphere",
        "off-data",
    ];
    if known.iter().any(|k| k.starts_with(raw)) {
        Ok(raw.to_string())
    } else {
        Err(format!("no workload starts with it ({})", known.join(", ")))
    }
}

/// Peak bytes per point of one workload in 3D: the points, their entries, the three crates'
/// trees and the update trees (measured: 360 B per point at N = 10^6 and 440 B at 2 * 10^5 in
/// 3D, the peak resident memory with `/usr/bin/time -v`); with a margin.
const PEAK_BYTES_PER_POINT: f64 = 600.0;
/// Peak bytes per query point (the query points, and 100 answers per k-nearest query are
/// consumed one query at a time).
const PEAK_BYTES_PER_QUERY: f64 = 200.0;

/// The parsed arguments, with the work they ask for checked against the memory.
fn parse() -> Args {
    let a = Args::parse();
    let refuse = |message: String| -> ! {
        use clap::CommandFactory;
        Args::command()
            .error(clap::error::ErrorKind::ValueValidation, message)
            .exit()
    };
    if a.parallel && !cfg!(feature = "rayon") {
        refuse("--parallel needs the `rayon` feature".into());
    }
    // The lattice workload rounds N to side^D points, at most (N^(1/2) + 1)^2 in 2D.
    let lattice = ((a.n as f64).sqrt() + 1.0).powi(2);
    // Points take D / 3 times their 3D bytes; the lattice at most 2^D times N from 4D up.
    let scale = (a.dim.unwrap_or(3) as f64 / 3.0).max(1.0);
    let lattice = match a.dim {
        Some(d) if d > 3 => lattice.max((a.n as f64).powf(1.0 / d as f64).round().powi(d as i32)),
        _ => lattice,
    };
    let bytes = (a.n as f64).max(lattice) * PEAK_BYTES_PER_POINT * scale
        + a.queries as f64 * PEAK_BYTES_PER_QUERY;
    if let Err(e) = limits::check_memory(&format!("--n {} --queries {}", a.n, a.queries), bytes) {
        refuse(e);
    }
    a
}

/// One table row: the median time of each crate, `None` where it has no such query.
struct Row {
    workload: String,
    op: String,
    /// orthtree, kiddo, rstar.
    times: [Option<f64>; 3],
}

fn ratio(r: &Row) -> f64 {
    let best = r.times[1..]
        .iter()
        .flatten()
        .fold(f64::INFINITY, |a, &b| a.min(b));
    r.times[0].unwrap_or(f64::NAN) / best
}

/// A side (or radius) `s` such that the average count over the first queries is about 100.
fn calibrate<const D: usize>(
    tree: &PointTree<f64, u64, D>,
    queries: &[[f64; D]],
    n: usize,
    count: impl Fn(&PointTree<f64, u64, D>, &[f64; D], f64) -> usize,
) -> f64 {
    let sample = &queries[..queries.len().min(2000)];
    let mut s = (100.0 / n as f64).powf(1.0 / D as f64);
    for _ in 0..6 {
        let total: usize = sample.iter().map(|q| count(tree, q, s)).sum();
        let avg = (total as f64 / sample.len() as f64).max(0.5);
        s *= (100.0 / avg).powf(1.0 / D as f64).clamp(0.25, 4.0);
    }
    s
}

/// The query sizes of one workload, calibrated on orthtree's tree.
struct Workload<'a, const D: usize> {
    points: &'a [[f64; D]],
    queries: &'a [[f64; D]],
    side: f64,
    radius: f64,
}

/// One crate's times on `w`, by row (build, box, radius, k = 1, 10, 100), and its answers.
fn measure<R: Rival<D>, const D: usize>(
    w: &Workload<'_, D>,
    reps: usize,
) -> (Vec<Option<f64>>, Vec<Option<Answers>>) {
    let input = R::prepare(w.points);
    let (t_build, n) = time(reps, || R::build(&input).size());
    assert_eq!(n, w.points.len(), "{} lost points", R::NAME);
    let tree = R::build(&input);
    drop(input);
    let mut times = vec![Some(t_build)];
    let mut answers = vec![None];
    let (t, a) = time(reps, || tree.boxes(w.queries, w.side));
    times.push(a.map(|_| t));
    answers.push(a);
    let (t, a) = time(reps, || tree.balls(w.queries, w.radius));
    times.push(Some(t));
    answers.push(Some(a));
    for k in [1usize, 10, 100] {
        let (t, a) = time(reps, || tree.nearest(w.queries, k));
        times.push(Some(t));
        answers.push(Some(a));
    }
    (times, answers)
}

fn run<const D: usize>(
    name: &str,
    points: &[[f64; D]],
    queries: &[[f64; D]],
    a: &Args,
    rows: &mut Vec<Row>,
) where
    [f64; D]: rstar::Point<Scalar = f64>,
{
    let workload = format!("{name} {D}D");
    if a.workload
        .as_ref()
        .is_some_and(|w| !name.starts_with(w.as_str()))
    {
        return;
    }
    let n = points.len();
    eprintln!("{workload}: n = {n}, {} queries", queries.len());
    let tree = Orthtree::build(&Orthtree::prepare(points)).0;
    let side = calibrate(&tree, queries, n, |t, q, s| {
        let (min, max) = orthtree_compare::rivals::corners(q, s);
        t.query_count(Aabb { min, max }).unwrap()
    });
    let radius = calibrate(&tree, queries, n, |t, q, r| {
        t.query_count(Ball {
            center: *q,
            radius: r,
        })
        .unwrap()
    });
    let w = Workload {
        points,
        queries,
        side,
        radius,
    };
    let (ours, ours_answers) = measure::<Orthtree<D>, D>(&w, a.reps);
    let (kd, kd_answers) = measure::<Kiddo<D>, D>(&w, a.reps);
    let (rt, rt_answers) = measure::<Rstar<D>, D>(&w, a.reps);
    let per_query = |a: &Option<Answers>| a.map_or(0.0, |a| a.count as f64 / queries.len() as f64);
    let ops = [
        "build".to_string(),
        format!("box (~{:.0} results)", per_query(&ours_answers[1])),
        format!("radius (~{:.0} results)", per_query(&ours_answers[2])),
        "1-nearest".into(),
        "10-nearest".into(),
        "100-nearest".into(),
    ];
    for (row, op) in ops.iter().enumerate() {
        // Items of k-nearest answers may differ at ties; counts and distances may not.
        let items = row < 3;
        for (rival, theirs) in [("kiddo", &kd_answers[row]), ("rstar", &rt_answers[row])] {
            if let (Some(ours), Some(theirs)) = (&ours_answers[row], theirs) {
                assert!(
                    ours.agrees_with(theirs, items),
                    "{workload} {op}: orthtree {ours:?}, {rival} {theirs:?}"
                );
            }
        }
        rows.push(Row {
            workload: workload.clone(),
            op: op.clone(),
            times: [ours[row], kd[row], rt[row]],
        });
    }

    if name == "uniform" {
        let extra = |heap: usize| heap as f64 / n as f64;
        let ours = tree.heap_bytes()
            - std::mem::size_of_val(tree.points())
            - std::mem::size_of_val(tree.items());
        let leaves = n.div_ceil(KIDDO_BUCKET);
        let stems = if leaves < 2 {
            0
        } else {
            leaves.next_power_of_two()
        };
        let kiddo = stems * 8 + leaves * 8;
        eprintln!(
            "memory beyond points and items, {D}D uniform: orthtree {:.2} B/point ({} nodes), kiddo {:.2} B/point (estimated from its stems and leaf extents)",
            extra(ours),
            tree.node_count(),
            extra(kiddo)
        );
        say!(
            "<!-- memory {D}D: orthtree {:.2} B/point, kiddo {:.2} B/point -->",
            extra(ours),
            extra(kiddo)
        );
    }
}

fn workloads<const D: usize>(a: &Args, rows: &mut Vec<Row>)
where
    [f64; D]: rstar::Point<Scalar = f64>,
{
    let mut rng = SmallRng::seed_from_u64(7);
    // kept for the off-data queries below
    let mut clustered = Vec::new();
    for dist in Distribution::ALL {
        let points = dist.points::<D>(a.n, 1);
        let queries = dist.points::<D>(a.queries, 2);
        run(dist.name(), &points, &queries, a, rows);
        if matches!(dist, Distribution::Clustered) {
            clustered = points;
        }
    }
    let distinct = common::uniform::<D>(a.n.div_ceil(8), 3);
    let dup: Vec<[f64; D]> = distinct
        .iter()
        .flat_map(|p| std::iter::repeat_n(*p, 8))
        .take(a.n)
        .collect();
    let queries = common::uniform::<D>(a.queries, 4);
    run("duplicates x8", &dup, &queries, a, rows);
    let side = (a.n as f64).powf(1.0 / D as f64).round().max(1.0) as usize;
    let total = side.pow(D as u32);
    let lattice: Vec<[f64; D]> = (0..total)
        .map(|mut i| {
            core::array::from_fn(|_| {
                let c = i % side;
                i /= side;
                c as f64
            })
        })
        .collect();
    let queries: Vec<[f64; D]> = (0..a.queries)
        .map(|_| core::array::from_fn(|_| rng.r#gen::<f64>() * side as f64))
        .collect();
    run("lattice", &lattice, &queries, a, rows);
    // A surface in the space (a scan), queries anywhere in the cube around it.
    let sphere = common::sphere_surface::<D>(a.n, 5);
    let queries = common::uniform::<D>(a.queries, 6);
    run("sphere surface", &sphere, &queries, a, rows);
    // The clustered points, queries uniform in the cube: most queries far from every point.
    run("off-data queries", &clustered, &queries, a, rows);
}

fn main() {
    let a = parse();
    let mut rows = Vec::new();
    each_dimension!(a, workloads(&a, &mut rows));
    say!(
        "\nN = {}, {} queries per row, median of {} runs, ms (total over all queries; build: one build)\n",
        a.n, a.queries, a.reps
    );
    say!("| workload | operation | orthtree | kiddo | rstar | orthtree / best rival |");
    say!("| --- | --- | ---: | ---: | ---: | ---: |");
    let show = |t: Option<f64>| t.map_or("-".to_string(), |t| format!("{t:.1}"));
    for r in &rows {
        say!(
            "| {} | {} | {:.1} | {} | {} | {:.2} |",
            r.workload,
            r.op,
            r.times[0].unwrap_or(f64::NAN),
            show(r.times[1]),
            show(r.times[2]),
            ratio(r)
        );
    }
    say!(
        "\nsingle updates, uniform points: {} inserts into a tree of {} then their removals, median of {} runs, microseconds per insert + remove (PointTree: 1000 of each)\n",
        a.queries, a.n, a.reps
    );
    say!("| dimension | PointTree | DynamicPointTree | kiddo KdTree | rstar RTree | DynamicPointTree / best rival |");
    say!("| --- | ---: | ---: | ---: | ---: | ---: |");
    each_dimension!(a, updates(&a));
    #[cfg(feature = "rayon")]
    if a.parallel {
        say!(
            "\nrayon, {} threads: median ms of {} runs\n",
            rayon::current_num_threads(),
            a.reps
        );
        say!("| workload | operation | serial | rayon | speed-up |");
        say!("| --- | --- | ---: | ---: | ---: |");
        each_dimension!(a, parallel(&a));
    }
}

/// `build` against `par_build` and per-query `k_nearest` against `par_k_nearest` (k = 10).
#[cfg(feature = "rayon")]
fn parallel<const D: usize>(a: &Args) {
    let points = common::uniform::<D>(a.n, 1);
    let queries = common::uniform::<D>(a.queries, 2);
    let entries: Vec<([f64; D], u64)> = points
        .iter()
        .enumerate()
        .map(|(i, &p)| (p, i as u64))
        .collect();
    let b = PointTree::builder();
    let (serial, n) = time(a.reps, || b.build(&entries).unwrap().len());
    let (par, m) = time(a.reps, || b.par_build(&entries).unwrap().len());
    assert_eq!(n, m);
    say!(
        "| uniform {D}D | build | {serial:.1} | {par:.1} | {:.2} |",
        serial / par
    );
    let tree = b.build(&entries).unwrap();
    let sum = |answers: Vec<Vec<orthtree::query::Neighbor<'_, f64, u64, D>>>| -> u64 {
        answers.iter().flatten().map(|n| *n.item).sum()
    };
    let (serial, s1) = time(a.reps, || {
        sum(queries
            .iter()
            .map(|q| tree.k_nearest(q, 10).unwrap())
            .collect())
    });
    let (par, s2) = time(a.reps, || sum(tree.par_k_nearest(&queries, 10).unwrap()));
    assert_eq!(s1, s2);
    say!(
        "| uniform {D}D | 10-nearest | {serial:.1} | {par:.1} | {:.2} |",
        serial / par
    );
}

/// Single inserts then removes of `--queries` new uniform points into trees of N: one row of
/// microseconds per insert + remove; then the dynamic tree's 10-nearest and box queries beside
/// the point tree's on the same points.
fn updates<const D: usize>(a: &Args) {
    let points = common::uniform::<D>(a.n, 1);
    let new = common::uniform::<D>(a.queries, 5);
    let entries: Vec<([f64; D], u64)> = points
        .iter()
        .enumerate()
        .map(|(i, &p)| (p, i as u64))
        .collect();
    let root = Aabb::new([0.0; D], [1.0; D]).unwrap();
    let built = PointTree::builder().root_box(root).build(&entries).unwrap();
    let per_op = |ms: f64, ops: usize| ms * 1e3 / ops as f64;
    let few = new.len().min(1000);
    let mut dense = built.clone();
    let (t_dense, _) = time(a.reps, || {
        for (i, p) in new[..few].iter().enumerate() {
            dense.insert(*p, i as u64).unwrap();
        }
        new[..few]
            .iter()
            .enumerate()
            .filter(|&(i, p)| dense.remove(p, &(i as u64)))
            .count()
    });
    let mut dynamic = DynamicPointTree::from(built.clone());
    let (t_dynamic, _) = time(a.reps, || {
        for (i, p) in new.iter().enumerate() {
            dynamic.insert(*p, i as u64).unwrap();
        }
        new.iter()
            .enumerate()
            .filter(|&(i, p)| dynamic.remove(p, &(i as u64)))
            .count()
    });
    // Grown by single adds, as a tree that takes updates is in use.
    let mut kiddo = kiddo::MutableKdTree::<f64, D>::default();
    for (p, i) in &entries {
        kiddo.add(p, *i as u32).expect("fewer than 2^32 points");
    }
    let (t_kiddo, _) = time(a.reps, || {
        for (i, p) in new.iter().enumerate() {
            kiddo
                .add(p, (a.n + i) as u32)
                .expect("fewer than 2^32 points");
        }
        let before = kiddo.size();
        for (i, p) in new.iter().enumerate() {
            kiddo.remove(p, (a.n + i) as u32);
        }
        before - kiddo.size()
    });
    type Entry<const D: usize> = rstar::primitives::GeomWithData<[f64; D], u64>;
    let mut rtree: RTree<Entry<D>> =
        RTree::bulk_load(entries.iter().map(|&(p, i)| Entry::new(p, i)).collect());
    if !leaves_at_one_depth(&rtree) {
        // rstar 0.12's bulk_load leaves some leaves one level deeper at some sizes (for example
        // N = 2 * 10^5 in 3D), and a later insert then panics; one insert at a time builds a
        // tree that takes updates.
        eprintln!(
            "{D}D: rstar's bulk-loaded tree has leaves at several depths (N = {}); its update \
             row uses a tree built by single inserts",
            a.n
        );
        rtree = RTree::new();
        for &(p, i) in &entries {
            rtree.insert(Entry::new(p, i));
        }
    }
    let (t_rstar, _) = time(a.reps, || {
        for (i, p) in new.iter().enumerate() {
            rtree.insert(Entry::new(*p, (a.n + i) as u64));
        }
        new.iter()
            .enumerate()
            .filter(|&(i, p)| rtree.remove(&Entry::new(*p, (a.n + i) as u64)).is_some())
            .count()
    });
    let (ours, k, r) = (
        per_op(t_dynamic, new.len()),
        per_op(t_kiddo, new.len()),
        per_op(t_rstar, new.len()),
    );
    say!(
        "| {D}D | {:.2} | {ours:.2} | {k:.2} | {r:.2} | {:.2} |",
        per_op(t_dense, few),
        ours / k.min(r)
    );
    // What the chunks cost the queries: the dynamic tree after the updates against the point
    // tree, both holding the same points.
    let queries = common::uniform::<D>(a.queries, 2);
    let sum_knn = |f: &dyn Fn(&[f64; D]) -> u64| queries.iter().map(f).sum::<u64>();
    let (t_pk, s1) = time(a.reps, || {
        sum_knn(&|q| {
            built
                .k_nearest(q, 10)
                .unwrap()
                .iter()
                .map(|n| *n.item)
                .sum()
        })
    });
    let (t_dk, s2) = time(a.reps, || {
        sum_knn(&|q| {
            dynamic
                .k_nearest(q, 10)
                .unwrap()
                .iter()
                .map(|n| *n.item)
                .sum()
        })
    });
    assert_eq!(s1, s2);
    let side = (100.0 / a.n as f64).powf(1.0 / D as f64);
    let boxes: Vec<Aabb<f64, D>> = queries
        .iter()
        .map(|q| Aabb::new(q.map(|x| x - side / 2.0), q.map(|x| x + side / 2.0)).unwrap())
        .collect();
    let (t_pb, b1) = time(a.reps, || {
        boxes
            .iter()
            .map(|b| built.in_box(b).unwrap().map(|(_, &i)| i).sum::<u64>())
            .sum::<u64>()
    });
    let (t_db, b2) = time(a.reps, || {
        boxes
            .iter()
            .map(|b| dynamic.in_box(b).unwrap().map(|(_, &i)| i).sum::<u64>())
            .sum::<u64>()
    });
    assert_eq!(b1, b2);
    eprintln!(
        "{D}D queries after the updates, ms: 10-nearest PointTree {t_pk:.1}, DynamicPointTree {t_dk:.1} ({:.2}x); box PointTree {t_pb:.1}, DynamicPointTree {t_db:.1} ({:.2}x)",
        t_dk / t_pk,
        t_db / t_pb
    );
    say!(
        "<!-- {D}D queries: 10-nearest dynamic/point {:.2}, box dynamic/point {:.2} -->",
        t_dk / t_pk,
        t_db / t_pb
    );
}

/// Whether every leaf of `tree` is at the same depth, which rstar's insert assumes.
fn leaves_at_one_depth<T: rstar::RTreeObject>(tree: &RTree<T>) -> bool {
    let mut depths = None;
    let mut stack = vec![(tree.root(), 0usize)];
    while let Some((node, depth)) = stack.pop() {
        for child in node.children() {
            match child {
                rstar::RTreeNode::Leaf(_) => {
                    if *depths.get_or_insert(depth) != depth {
                        return false;
                    }
                }
                rstar::RTreeNode::Parent(parent) => stack.push((parent, depth + 1)),
            }
        }
    }
    true
}
