//! Point location, insert and delete on the compressed quadtree (walking down from its root)
//! and on the skip quadtree, for 10^3 to 10^6 points, to show the growth per operation; and
//! location on caterpillars as deep as f64 coordinates allow, with the nodes each location
//! touches (printed once per input to stderr).
//!
//! Groups `compressed/{uniform,clustered}/{locate,update}` with functions `compressed/{n}` and
//! `skip/{n}`. One iteration of `locate` locates a batch of 1000 points of the same
//! distribution; one of `update` inserts 1000 new points and removes them again (so the tree is
//! the same after every iteration): the time per element is one insert plus one delete.
//!
//! Groups `compressed/deep/locate` (caterpillars 53 levels deep below the unit square, n
//! growing; functions `{compressed,skip}/{n}`) and `compressed/deep_by_depth/locate` (n near
//! 2^14, legs 6 to 48 deep; functions `{compressed,skip}/legs{legs}`) locate 1000 points taken
//! from the deepest quarter of the legs, the lookups a walk from the root pays most for.
//!
//! Group `compressed/point_location/{relaxed,exercise}` builds the point locator of exercise
//! 14.10 on triangulated grids (`build/{edges}`, time per edge) and locates 1000 random points
//! (`locate/{edges}`).
//!
//! Groups `compressed/queries/{box,knn10}` run the shared query engines on a `PointTree`
//! (default bucket) and on the `CompressedTree` of the same points: 1000 box counts of about 100
//! points, and 1000 10-nearest searches.
//!
//! Run with `cargo bench --bench compressed` (a few minutes).

mod common;
#[path = "workloads/compressed.rs"]
mod workload;

use orthtree::prelude::*;
use std::hint::black_box;
use std::time::Duration;

use common::Distribution;
use criterion::{criterion_group, criterion_main, BenchmarkGroup, Criterion, Throughput};
use orthtree::compressed::{PointLocator, SkipQuadtree, Subdivision};
use orthtree::{Aabb, CompressedTree, PointTree};

const SIZES: [usize; 4] = [1_000, 10_000, 100_000, 1_000_000];
const BATCH: usize = 1000;

fn setup(g: &mut BenchmarkGroup<'_, criterion::measurement::WallTime>) {
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .throughput(Throughput::Elements(BATCH as u64));
}

/// A root box holding `points` with a margin of 1 (room for the inserted points).
fn margin(points: &[[f64; 2]]) -> Aabb<f64, 2> {
    let lo = points
        .iter()
        .fold([0.0f64; 2], |m, p| [m[0].min(p[0]), m[1].min(p[1])]);
    let hi = points
        .iter()
        .fold([1.0f64; 2], |m, p| [m[0].max(p[0]), m[1].max(p[1])]);
    Aabb::new([lo[0] - 1.0, lo[1] - 1.0], [hi[0] + 1.0, hi[1] + 1.0]).unwrap()
}

/// Builds both trees over `points` with `root` as root box.
fn trees(
    points: &[[f64; 2]],
    root: Aabb<f64, 2>,
) -> (CompressedTree<f64, u32, 2>, SkipQuadtree<f64, u32, 2>) {
    let entries: Vec<([f64; 2], u32)> = points
        .iter()
        .enumerate()
        .map(|(i, &p)| (p, i as u32))
        .collect();
    let c = CompressedTree::builder()
        .root_box(root)
        .build(&entries)
        .unwrap();
    let s = SkipQuadtree::with_seed(c.clone(), 7);
    (c, s)
}

fn locate(
    c: &mut Criterion,
    group: &str,
    label: &str,
    queries: &[[f64; 2]],
    t: &(CompressedTree<f64, u32, 2>, SkipQuadtree<f64, u32, 2>),
) {
    let (ct, st) = t;
    let mut g = c.benchmark_group(group);
    setup(&mut g);
    g.throughput(Throughput::Elements(queries.len() as u64));
    g.bench_function(format!("compressed/{label}"), |b| {
        b.iter(|| {
            queries
                .iter()
                .map(|q| ct.locate(q).unwrap().inside().unwrap().node as usize)
                .sum::<usize>()
        })
    });
    g.bench_function(format!("skip/{label}"), |b| {
        b.iter(|| {
            queries
                .iter()
                .map(|q| st.locate(q).unwrap().inside().unwrap().node as usize)
                .sum::<usize>()
        })
    });
    g.finish();
    let touched = |f: &dyn Fn(&[f64; 2]) -> usize| {
        queries.iter().map(f).sum::<usize>() as f64 / queries.len() as f64
    };
    eprintln!(
        "{group} {label}, n = {}: depth {}, nodes touched per location: compressed walk {:.1}, skip {:.1} ({} levels)",
        ct.len(),
        ct.depth(),
        touched(&|q| ct.locate(q).unwrap().inside().unwrap().touched),
        touched(&|q| st.locate(q).unwrap().inside().unwrap().touched),
        st.level_count()
    );
}

fn bench(c: &mut Criterion) {
    for dist in Distribution::ALL {
        for n in SIZES {
            let points = dist.points::<2>(n, 21);
            let queries = dist.points::<2>(BATCH, 22);
            let mut t = trees(&points, margin(&points));
            let name = dist.name();
            let group = format!("compressed/{name}/locate");
            locate(c, &group, &n.to_string(), &queries, &t);
            let mut g = c.benchmark_group(format!("compressed/{name}/update"));
            setup(&mut g);
            g.bench_function(format!("compressed/{n}"), |b| {
                b.iter(|| {
                    for (i, q) in queries.iter().enumerate() {
                        t.0.insert(*q, i as u32).unwrap();
                    }
                    for q in &queries {
                        black_box(t.0.remove_point(q));
                    }
                })
            });
            g.bench_function(format!("skip/{n}"), |b| {
                b.iter(|| {
                    for (i, q) in queries.iter().enumerate() {
                        t.1.insert(*q, i as u32).unwrap();
                    }
                    for q in &queries {
                        black_box(t.1.remove_point(q));
                    }
                })
            });
            g.finish();
        }
    }
    // Caterpillars: copies of the points at 1 - 2^-k of a square, nested down to the last bit
    // of f64; n growing at the greatest depth, then the depth growing at n near 2^14.
    for copies in [16usize, 256, 4096, 32768] {
        let (pts, legs) = workload::caterpillars(copies, 53);
        deep(
            c,
            "compressed/deep/locate",
            &pts.len().to_string(),
            &pts,
            legs,
        );
    }
    for legs in [6u32, 12, 24, 48] {
        let (pts, legs) = workload::caterpillars((1 << 14) / legs as usize, legs);
        deep(
            c,
            "compressed/deep_by_depth/locate",
            &format!("legs{legs}"),
            &pts,
            legs,
        );
    }
}

/// Location of (at most) 1000 points from the deepest quarter of the caterpillars' legs.
fn deep(c: &mut Criterion, group: &str, label: &str, pts: &[[f64; 2]], legs: u32) {
    let t = trees(pts, Aabb::new([0.0; 2], [1.0; 2]).unwrap());
    let deepest = workload::deep_legs(pts, legs);
    let step = (deepest.len() / BATCH).max(1);
    let queries: Vec<[f64; 2]> = deepest.iter().step_by(step).copied().take(BATCH).collect();
    locate(c, group, label, &queries, &t);
}

/// Point location (exercise 14.10) on jittered triangulated grids: building the locator, and a
/// batch of 1000 random queries, for both leaf rules.
fn point_location(c: &mut Criterion) {
    use rand::{Rng, SeedableRng};
    for k in [16usize, 64, 256] {
        let (v, e, _) = workload::triangulated_grid(k, 5);
        let s = Subdivision::new(v, e).unwrap();
        let mut rng = rand::rngs::SmallRng::seed_from_u64(6);
        let top = k as f64 - 1.0;
        let queries: Vec<[f64; 2]> = (0..BATCH)
            .map(|_| [rng.gen_range(0.0..top), rng.gen_range(0.0..top)])
            .collect();
        let edges = s.edges().len();
        for (rule, exercise) in [("relaxed", false), ("exercise", true)] {
            let build = |s: &Subdivision| {
                let s = s.clone();
                if exercise {
                    PointLocator::with_exercise_rule(s)
                } else {
                    PointLocator::new(s)
                }
                .unwrap()
            };
            let locator = build(&s);
            eprintln!(
                "point location {rule}, {edges} edges: {} nodes, height {}",
                locator.node_count(),
                locator.height()
            );
            let mut g = c.benchmark_group(format!("compressed/point_location/{rule}"));
            setup(&mut g);
            g.throughput(Throughput::Elements(edges as u64));
            g.bench_function(format!("build/{edges}"), |b| b.iter(|| build(&s)));
            g.throughput(Throughput::Elements(BATCH as u64));
            g.bench_function(format!("locate/{edges}"), |b| {
                b.iter(|| {
                    queries
                        .iter()
                        .map(|q| locator.face(q).unwrap().0)
                        .sum::<u32>()
                })
            });
            g.finish();
        }
    }
}

/// The shared query engines on both trees: 1000 box counts (about 100 points each) and 1000
/// 10-nearest searches, uniform points.
fn queries(c: &mut Criterion) {
    for n in SIZES {
        let points = Distribution::Uniform.points::<2>(n, 31);
        let queries = Distribution::Uniform.points::<2>(BATCH, 32);
        let entries: Vec<([f64; 2], u32)> = points
            .iter()
            .enumerate()
            .map(|(i, &p)| (p, i as u32))
            .collect();
        let plain = PointTree::new(&entries).unwrap();
        let compressed = CompressedTree::from(&plain);
        let half = 0.5 * (100.0 / n as f64).sqrt();
        let square = |q: &[f64; 2]| Aabb {
            min: [q[0] - half, q[1] - half],
            max: [q[0] + half, q[1] + half],
        };
        let mut g = c.benchmark_group("compressed/queries/box");
        setup(&mut g);
        g.bench_function(format!("point_tree/{n}"), |b| {
            b.iter(|| {
                queries
                    .iter()
                    .map(|q| plain.query_count(square(q)).unwrap())
                    .sum::<usize>()
            })
        });
        g.bench_function(format!("compressed/{n}"), |b| {
            b.iter(|| {
                queries
                    .iter()
                    .map(|q| compressed.query_count(square(q)).unwrap())
                    .sum::<usize>()
            })
        });
        g.finish();
        let mut g = c.benchmark_group("compressed/queries/knn10");
        setup(&mut g);
        g.bench_function(format!("point_tree/{n}"), |b| {
            b.iter(|| {
                queries
                    .iter()
                    .map(|q| plain.k_nearest(q, 10).unwrap().len())
                    .sum::<usize>()
            })
        });
        g.bench_function(format!("compressed/{n}"), |b| {
            b.iter(|| {
                queries
                    .iter()
                    .map(|q| compressed.k_nearest(q, 10).unwrap().len())
                    .sum::<usize>()
            })
        });
        g.finish();
    }
}

criterion_group!(benches, bench, point_location, queries);
criterion_main!(benches);
