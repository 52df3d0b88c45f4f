//! Boolean operations on region trees (criterion, sample size 10) against dense bit-packed
//! operations (`u64` words) on the same images: a union of random discs (balls in 3D) with
//! another, on 2^12 and 2^14 sides in 2D and 2^9 in 3D, and on a 65536^2 image whose trees are
//! built from the shapes directly (the dense image, 512 MiB, is never built on the tree side).
//!
//! Before the criterion groups a summary table is printed: time per input leaf of the tree union,
//! dense time per pixel, and the break-even compression ratio (pixels per input leaf above
//! which the tree is faster): `ns per leaf / ns per pixel`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use orthtree::image::RegionTree;
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};
use std::hint::black_box;
use std::time::{Duration, Instant};

/// The union of `count` random balls of radius 2%..15% of the side.
fn shapes<const D: usize>(side: u32, count: usize, seed: u64) -> RegionTree<D> {
    let mut rng = SmallRng::seed_from_u64(seed);
    let s = f64::from(side);
    let mut t = RegionTree::<D>::empty([side; D]).unwrap();
    for _ in 0..count {
        let centre = core::array::from_fn(|_| rng.gen_range(0.0..s));
        let r = rng.gen_range(0.02 * s..0.15 * s);
        t |= RegionTree::<D>::from_ball([side; D], centre, r).unwrap();
    }
    t
}

fn dense_or(a: &[u64], b: &[u64]) -> Vec<u64> {
    a.iter().zip(b).map(|(x, y)| x | y).collect()
}

/// The fastest of `runs` timings of `f`, in seconds.
fn best<T>(runs: usize, mut f: impl FnMut() -> T) -> f64 {
    (0..runs)
        .map(|_| {
            let t = Instant::now();
            black_box(f());
            t.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

fn row<const D: usize>(side: u32, a: &RegionTree<D>, b: &RegionTree<D>, dense: bool) {
    let leaves = (a.leaf_count() + b.leaf_count()) as f64;
    let pixels = f64::from(side).powi(D as i32);
    let tree = best(5, || a | b);
    let per_leaf = tree * 1e9 / leaves;
    let dense_t = if dense {
        let (da, db) = (a.to_packed(), b.to_packed());
        best(if pixels > 1e9 { 1 } else { 5 }, || dense_or(&da, &db))
    } else {
        // the dense image of the 65536^2 case is never built from the trees: time the same
        // word-wise OR on two zeroed 512 MiB bitmaps, once
        let words = (pixels / 64.0) as usize;
        let (da, db) = (vec![0u64; words], vec![1u64; words]);
        best(1, || dense_or(&da, &db))
    };
    let per_pixel = dense_t * 1e9 / pixels;
    println!(
        "{D}D side 2^{:<2} leaves {:>9} union {:>9.3} ms = {:>5.2} ns/leaf | dense {:>9.3} ms = {:.4} ns/pixel | speed-up {:>8.1}x | break-even {:>5.0} pixels/leaf (here {:.0})",
        side.trailing_zeros(),
        leaves,
        tree * 1e3,
        per_leaf,
        dense_t * 1e3,
        per_pixel,
        dense_t / tree,
        per_leaf / per_pixel,
        pixels / leaves
    );
}

fn summary() {
    println!("region-tree union vs dense bit-packed OR (best of 5):");
    row::<2>(
        1 << 12,
        &shapes(1 << 12, 8, 1),
        &shapes(1 << 12, 8, 2),
        true,
    );
    row::<2>(
        1 << 14,
        &shapes(1 << 14, 8, 1),
        &shapes(1 << 14, 8, 2),
        true,
    );
    row::<3>(1 << 9, &shapes(1 << 9, 8, 1), &shapes(1 << 9, 8, 2), true);
    row::<2>(
        1 << 16,
        &shapes(1 << 16, 4, 1),
        &shapes(1 << 16, 4, 2),
        false,
    );
}

fn bench_side<const D: usize>(c: &mut Criterion, side: u32) {
    let mut group = c.benchmark_group(format!("image_ops/{D}d/2^{}", side.trailing_zeros()));
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2));
    let (a, b) = (shapes::<D>(side, 8, 1), shapes::<D>(side, 8, 2));
    group.throughput(Throughput::Elements(
        (a.leaf_count() + b.leaf_count()) as u64,
    ));
    group.bench_function(BenchmarkId::new("tree", "union"), |bench| {
        bench.iter(|| &a | &b)
    });
    group.bench_function(BenchmarkId::new("tree", "intersection"), |bench| {
        bench.iter(|| &a & &b)
    });
    group.bench_function(BenchmarkId::new("tree", "xor"), |bench| {
        bench.iter(|| &a ^ &b)
    });
    group.bench_function(BenchmarkId::new("tree", "intersection_len"), |bench| {
        bench.iter(|| a.intersection_len(&b))
    });
    let (da, db) = (a.to_packed(), b.to_packed());
    group.bench_function(BenchmarkId::new("dense", "union"), |bench| {
        bench.iter(|| dense_or(&da, &db))
    });
    group.finish();
}

fn benches(c: &mut Criterion) {
    summary();
    bench_side::<2>(c, 1 << 12);
    bench_side::<2>(c, 1 << 14);
    bench_side::<3>(c, 1 << 9);
}

criterion_group!(image_ops, benches);
criterion_main!(image_ops);
