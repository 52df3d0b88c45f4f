//! Queries of `PointTree` on seeded points (uniform in the unit square, and 64 Gaussian clusters
//! of sigma 0.01), 2D `f64`, single-threaded, for sizes 10^3 to 10^6. The same groups with kiddo
//! and rstar beside it are the comparison crate's `queries` bench
//! (`cargo bench -p orthtree-compare --bench queries`).
//!
//! Groups `queries/{uniform,clustered}/{kind}/{n}` with the function `orthtree`; kinds: `box`
//! (about 100 results), `radius` (about 100 results), `knn1`, `knn10`, `knn100`. One iteration
//! runs a batch of 1000 queries centred on points of the same distribution; answers are
//! consumed.
//!
//! Run with `cargo bench --bench queries` (a minute; `-- knn10` to pick one kind).

mod common;

use orthtree::prelude::*;
use std::time::Duration;

use common::Distribution;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use orthtree::{Aabb, Ball, PointTree};

const SIZES: [usize; 4] = [1_000, 10_000, 100_000, 1_000_000];
const BATCH: usize = 1000;

fn bench(c: &mut Criterion) {
    for dist in Distribution::ALL {
        for n in SIZES {
            let points = dist.points::<2>(n, 11);
            let queries = dist.points::<2>(BATCH, 12);
            let entries: Vec<([f64; 2], u64)> = points
                .iter()
                .enumerate()
                .map(|(i, &p)| (p, i as u64))
                .collect();
            let ours = PointTree::new(&entries).unwrap();
            // About 100 results: side and radius from the mean density (uniform) or measured.
            let mut side = (100.0 / n as f64).sqrt().min(1.0);
            let mut radius = side / core::f64::consts::PI.sqrt();
            for _ in 0..4 {
                let count = |f: &dyn Fn(&[f64; 2]) -> usize| {
                    (queries.iter().map(f).sum::<usize>() as f64 / BATCH as f64).max(0.5)
                };
                let b = count(&|q| ours.query_count(square(q, side)).unwrap());
                side *= (100.0f64.min(n as f64) / b).sqrt().clamp(0.5, 2.0);
                let r = count(&|q| ours.query_count(Ball { center: *q, radius }).unwrap());
                radius *= (100.0f64.min(n as f64) / r).sqrt().clamp(0.5, 2.0);
            }

            let name = dist.name();
            let mut g = c.benchmark_group(format!("queries/{name}/box"));
            setup(&mut g);
            g.bench_function(n.to_string() + "/orthtree", |b| {
                b.iter(|| {
                    let mut s = 0u64;
                    for q in &queries {
                        s += ours
                            .query(square(q, side))
                            .unwrap()
                            .map(|(_, &i)| i)
                            .sum::<u64>();
                    }
                    s
                })
            });
            g.finish();

            let mut g = c.benchmark_group(format!("queries/{name}/radius"));
            setup(&mut g);
            g.bench_function(n.to_string() + "/orthtree", |b| {
                b.iter(|| {
                    let mut s = 0u64;
                    for q in &queries {
                        let ball = Ball { center: *q, radius };
                        s += ours.query(ball).unwrap().map(|(_, &i)| i).sum::<u64>();
                    }
                    s
                })
            });
            g.finish();

            for k in [1usize, 10, 100] {
                let mut g = c.benchmark_group(format!("queries/{name}/knn{k}"));
                setup(&mut g);
                g.bench_function(n.to_string() + "/orthtree", |b| {
                    b.iter(|| {
                        let mut s = 0.0;
                        for q in &queries {
                            s += ours
                                .k_nearest(q, k)
                                .unwrap()
                                .iter()
                                .map(|nn| nn.distance)
                                .sum::<f64>();
                        }
                        s
                    })
                });
                g.finish();
            }
        }
    }
}

fn square(q: &[f64; 2], side: f64) -> Aabb<f64, 2> {
    Aabb {
        min: q.map(|x| x - side / 2.0),
        max: q.map(|x| x + side / 2.0),
    }
}

fn setup(g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>) {
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(200))
        .measurement_time(Duration::from_millis(600))
        .throughput(Throughput::Elements(BATCH as u64));
}

criterion_group!(benches, bench);
criterion_main!(benches);
