//! Bulk build of `PointTreeBuilder` on seeded points (uniform in the unit cube, and 64 Gaussian
//! clusters of sigma 0.01, unclamped), in 2D and 3D, `f64`, single-threaded. The same groups with
//! kiddo and rstar beside it are the comparison crate's `build` bench
//! (`cargo bench -p orthtree-compare --bench build`); both share their adapters and groups
//! (`workloads/build.rs`).
//!
//! Groups are named `build/{2d,3d}/{uniform,clustered}/{n}` with functions `orthtree` (default
//! bucket size, `build(&entries)`) and `orthtree_vec` (`build_from_vec(entries)`).
//!
//! Run with `cargo bench --bench build` (about a minute on two cores).

mod common;
#[path = "workloads/build.rs"]
mod workloads;

use common::Distribution;
use criterion::{criterion_group, criterion_main, Criterion};
use workloads::SEED;

/// Every group of dimension `D`.
fn bench_dim<const D: usize>(c: &mut Criterion) {
    for dist in Distribution::ALL {
        workloads::groups::<D>(c, dist.name(), |n| dist.points(n, SEED), |_, _| {});
    }
}

fn build_2d(c: &mut Criterion) {
    bench_dim::<2>(c);
}

fn build_3d(c: &mut Criterion) {
    bench_dim::<3>(c);
}

criterion_group!(benches, build_2d, build_3d);
criterion_main!(benches);
