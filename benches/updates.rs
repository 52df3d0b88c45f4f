//! Updates of a `PointTree` (default bucket, 2D, f64, `u32` items) for 10^3 to 10^6 stored
//! points, uniform and clustered:
//!
//! - `updates/{dist}/single/{n}`: 1000 single `insert`s of new points of the same distribution,
//!   then 1000 `remove`s of them (the tree is the same after every iteration); time per element
//!   is one insert plus one remove. Each moves the points after its position (`update.rs`), so
//!   it grows with n.
//! - `updates/{dist}/dynamic/{n}`: the same on a `DynamicPointTree` (leaves in chunks with
//!   slack): amortised O(depth), flat in n.
//! - `updates/{dist}/extend/{n}`: one `extend_from_vec` of n / 10 new points (at least 1000)
//!   into a clone of the tree, the clone not timed; time per inserted point
//!   (`batch_update.rs`: one merge and one cut).
//! - `updates/{dist}/retain/{n}`: one `retain` dropping every tenth point from a clone; time per
//!   stored point.
//!
//! Run with `cargo bench --bench updates` (about two minutes).

mod common;

use orthtree::prelude::*;
use std::hint::black_box;
use std::time::Duration;

use common::Distribution;
use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use orthtree::{Aabb, DynamicPointTree, PointTree};

const SIZES: [usize; 4] = [1_000, 10_000, 100_000, 1_000_000];
const BATCH: usize = 1000;

fn bench(c: &mut Criterion) {
    for dist in Distribution::ALL {
        let mut g = c.benchmark_group(format!("updates/{}", dist.name()));
        g.sample_size(10)
            .warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(2));
        for n in SIZES {
            // One draw (the same clusters) split into the stored points and the new ones.
            let mut points = dist.points::<2>(n + (n / 10).max(BATCH), 31);
            let extra = points.split_off(n);
            let entries: Vec<([f64; 2], u32)> = points
                .iter()
                .enumerate()
                .map(|(i, &p)| (p, i as u32))
                .collect();
            // The clustered generator may reach beyond the unit square: a root box for both sets.
            let root = Aabb::new([-1.0; 2], [2.0; 2]).unwrap();
            let mut tree = PointTree::builder().root_box(root).build(&entries).unwrap();
            g.throughput(Throughput::Elements(BATCH as u64));
            g.bench_function(format!("single/{n}"), |b| {
                b.iter(|| {
                    for (i, q) in extra[..BATCH].iter().enumerate() {
                        tree.insert(*q, i as u32).unwrap();
                    }
                    for (i, q) in extra[..BATCH].iter().enumerate() {
                        black_box(tree.remove(q, &(i as u32)));
                    }
                })
            });
            let mut dynamic = DynamicPointTree::from(tree.clone());
            g.bench_function(format!("dynamic/{n}"), |b| {
                b.iter(|| {
                    for (i, q) in extra[..BATCH].iter().enumerate() {
                        dynamic.insert(*q, i as u32).unwrap();
                    }
                    for (i, q) in extra[..BATCH].iter().enumerate() {
                        black_box(dynamic.remove(q, &(i as u32)));
                    }
                })
            });
            let batch: Vec<([f64; 2], u32)> = extra
                .iter()
                .enumerate()
                .map(|(i, &p)| (p, i as u32))
                .collect();
            g.throughput(Throughput::Elements(batch.len() as u64));
            g.bench_function(format!("extend/{n}"), |b| {
                b.iter_batched(
                    || (tree.clone(), batch.clone()),
                    |(mut t, batch)| {
                        t.extend_from_vec(batch).unwrap();
                        t
                    },
                    BatchSize::LargeInput,
                )
            });
            g.throughput(Throughput::Elements(n as u64));
            g.bench_function(format!("retain/{n}"), |b| {
                b.iter_batched(
                    || tree.clone(),
                    |mut t| {
                        t.retain(|_, &i| i % 10 != 0);
                        t
                    },
                    BatchSize::LargeInput,
                )
            });
        }
        g.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
