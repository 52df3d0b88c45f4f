//! The dual-tree joins against a loop of single-tree queries, on 10^5 seeded uniform points in
//! the unit cube, 3D `f64`, single-threaded.
//!
//! Groups: `joins/knn_self/{k}` (every point's `k` nearest others: `k_nearest_self` against one
//! `k_nearest(p, k + 1)` per point) and `joins/pairs/10` (every unordered pair within the radius
//! that holds about 10 neighbours per point: `pairs_within` against one ball query per point
//! keeping the neighbours of higher item). Answers are consumed.
//!
//! Run with `cargo bench --bench joins` (about a minute).

// Only the uniform points of the shared generators are used here.
#[allow(dead_code)]
mod common;

use core::ops::ControlFlow;
use criterion::{criterion_group, criterion_main, Criterion};
use orthtree::prelude::*;
use orthtree::query::Boundary;
use orthtree::PointTree;
use std::time::Duration;

const N: usize = 100_000;

fn bench(c: &mut Criterion) {
    let points = common::uniform::<3>(N, 21);
    let entries: Vec<([f64; 3], u32)> = points
        .iter()
        .enumerate()
        .map(|(i, &p)| (p, i as u32))
        .collect();
    let t = PointTree::new(&entries).unwrap();

    for k in [1, 16] {
        let mut g = c.benchmark_group(format!("joins/knn_self/{k}"));
        setup(&mut g);
        g.bench_function("dual_tree", |b| {
            b.iter(|| {
                let table = t.k_nearest_self(k);
                table.slots().iter().sum::<usize>()
            })
        });
        g.bench_function("single_tree_loop", |b| {
            b.iter(|| {
                let mut s = 0;
                for slot in 0..t.len() {
                    for n in t.k_nearest(t.point(slot), k + 1).unwrap() {
                        if n.index != slot {
                            s += n.index;
                        }
                    }
                }
                s
            })
        });
        g.finish();
    }

    // About 10 neighbours per point: 4/3 pi r^3 N = 10.
    let r = (10.0 * 3.0 / (4.0 * core::f64::consts::PI * N as f64)).cbrt();
    let mut g = c.benchmark_group("joins/pairs/10");
    setup(&mut g);
    g.bench_function("dual_tree", |b| {
        b.iter(|| {
            let mut s = 0usize;
            let _ = t.pairs_within(r, Boundary::Inclusive, |i, j, _| {
                s += i ^ j;
                ControlFlow::<()>::Continue(())
            });
            s
        })
    });
    g.bench_function("single_tree_loop", |b| {
        b.iter(|| {
            let mut s = 0usize;
            for slot in 0..t.len() {
                let me = t.items()[slot] as usize;
                for (_, &j) in t.in_ball(t.point(slot), r).unwrap() {
                    if j as usize > me {
                        s += me ^ j as usize;
                    }
                }
            }
            s
        })
    });
    g.finish();
}

fn setup(g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>) {
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
}

criterion_group!(benches, bench);
criterion_main!(benches);
