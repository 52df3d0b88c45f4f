//! Queries, side by side: orthtree's `PointTree` against kiddo's `ImmutableKdTree` (bucket 32)
//! and rstar's `RTree`, on the same seeded points (uniform in the unit square, and 64 Gaussian
//! clusters of sigma 0.01), 2D `f64`, single-threaded, for sizes 10^3 to 10^6. Every crate runs
//! through its adapter (`orthtree_compare::rivals`), so each answers the same batch the same
//! way and consumes every answer.
//!
//! Groups `queries/{uniform,clustered}/{kind}/{n}` with functions `orthtree`, `kiddo` (where it
//! has the query) and `rstar`; kinds: `box` (about 100 results; kiddo has no box query),
//! `radius` (about 100 results), `knn1`, `knn10`, `knn100`. One iteration runs a batch of 1000
//! queries centred on points of the same distribution.
//!
//! Run with `cargo bench -p orthtree-compare --bench queries` (a few minutes; `-- knn10` to pick
//! one kind).

use std::time::Duration;

use criterion::measurement::WallTime;
use criterion::{criterion_group, criterion_main, BenchmarkGroup, Criterion, Throughput};
use orthtree::prelude::*;
use orthtree::{Aabb, Ball};
use orthtree_compare::points::Distribution;
use orthtree_compare::rivals::{corners, Kiddo, Orthtree, Rival, Rstar};

const SIZES: [usize; 4] = [1_000, 10_000, 100_000, 1_000_000];
const BATCH: usize = 1000;

/// One query kind of the groups.
#[derive(Clone, Copy)]
enum Kind {
    Box,
    Radius,
    Nearest(usize),
}

impl Kind {
    const ALL: [Kind; 5] = [
        Kind::Box,
        Kind::Radius,
        Kind::Nearest(1),
        Kind::Nearest(10),
        Kind::Nearest(100),
    ];

    fn name(self) -> String {
        match self {
            Kind::Box => "box".into(),
            Kind::Radius => "radius".into(),
            Kind::Nearest(k) => format!("knn{k}"),
        }
    }
}

/// The shared batch and its calibrated box side and radius.
struct Batch {
    queries: Vec<[f64; 2]>,
    side: f64,
    radius: f64,
}

/// Adds crate `R`'s function for `kind` to `group` (nothing where it has no such query).
fn bench_rival<R: Rival<2>>(
    group: &mut BenchmarkGroup<'_, WallTime>,
    n: usize,
    tree: &R,
    batch: &Batch,
    kind: Kind,
) {
    if matches!(kind, Kind::Box) && tree.boxes(&batch.queries, batch.side).is_none() {
        return;
    }
    group.bench_function(format!("{n}/{}", R::NAME), |b| {
        b.iter(|| match kind {
            Kind::Box => tree.boxes(&batch.queries, batch.side),
            Kind::Radius => Some(tree.balls(&batch.queries, batch.radius)),
            Kind::Nearest(k) => Some(tree.nearest(&batch.queries, k)),
        })
    });
}

fn bench(c: &mut Criterion) {
    for dist in Distribution::ALL {
        for n in SIZES {
            let points = dist.points::<2>(n, 11);
            let queries = dist.points::<2>(BATCH, 12);
            let ours = Orthtree::build(&Orthtree::prepare(&points));
            let kd = Kiddo::build(&Kiddo::prepare(&points));
            let rt = Rstar::build(&Rstar::prepare(&points));
            // About 100 results: side and radius from the mean density (uniform) or measured.
            let mut side = (100.0 / n as f64).sqrt().min(1.0);
            let mut radius = side / core::f64::consts::PI.sqrt();
            for _ in 0..4 {
                let count = |f: &dyn Fn(&[f64; 2]) -> usize| {
                    (queries.iter().map(f).sum::<usize>() as f64 / BATCH as f64).max(0.5)
                };
                let b = count(&|q| {
                    let (min, max) = corners(q, side);
                    ours.0.query_count(Aabb { min, max }).unwrap()
                });
                side *= (100.0f64.min(n as f64) / b).sqrt().clamp(0.5, 2.0);
                let r = count(&|q| ours.0.query_count(Ball { center: *q, radius }).unwrap());
                radius *= (100.0f64.min(n as f64) / r).sqrt().clamp(0.5, 2.0);
            }
            let batch = Batch {
                queries,
                side,
                radius,
            };
            for kind in Kind::ALL {
                let mut g = c.benchmark_group(format!("queries/{}/{}", dist.name(), kind.name()));
                g.sample_size(10)
                    .warm_up_time(Duration::from_millis(200))
                    .measurement_time(Duration::from_millis(600))
                    .throughput(Throughput::Elements(BATCH as u64));
                bench_rival(&mut g, n, &ours, &batch, kind);
                bench_rival(&mut g, n, &kd, &batch, kind);
                bench_rival(&mut g, n, &rt, &batch, kind);
                g.finish();
            }
        }
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
