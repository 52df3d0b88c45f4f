//! Bulk build, side by side: orthtree's `PointTreeBuilder` against kiddo's `ImmutableKdTree` and
//! rstar's `RTree::bulk_load`, on the same seeded points (uniform in the unit cube, and 64
//! Gaussian clusters of sigma 0.01, unclamped), in 2D and 3D, `f64`, single-threaded.
//!
//! Each crate sits behind one small [`Adapter`] so that every crate runs the same workload: the
//! adapter turns the shared points into the crate's input once, outside the timing, and then only
//! the build is timed. Where the API takes ownership the input is cloned outside the timing
//! (`iter_batched`); the built trees are dropped outside the timing for every crate. orthtree's
//! adapters and the groups are the library's `build` bench's (`benches/workloads/build.rs`).
//!
//! Groups are named `build/{2d,3d}/{uniform,clustered}/{n}` with functions `orthtree` (default
//! bucket size, `build(&entries)`), `orthtree_vec` (`build_from_vec(entries)`), `kiddo` (bucket
//! 32, `u32` items) and `rstar`.
//!
//! Run with `cargo bench -p orthtree-compare --bench build` (about two minutes on two cores).

use criterion::{criterion_group, criterion_main, Criterion};
use kiddo::ImmutableKdTree;
use orthtree_compare::points::Distribution;
use workloads::{Adapter, Build, SEED};

#[path = "../../benches/workloads/build.rs"]
mod workloads;

/// kiddo 6, `ImmutableKdTree<f64, D>::new_from_slice` (its alias for static sets: Eytzinger
/// stems, arena leaves of 32, `u32` items that are the indices), single-threaded.
struct Kiddo;

impl<const D: usize> Adapter<D> for Kiddo {
    const NAME: &'static str = "kiddo";
    type Input = Vec<[f64; D]>;
    type Tree = ImmutableKdTree<f64, D>;
    const BUILD: Build<Self::Input, Self::Tree> =
        Build::Borrow(|p| Self::Tree::new_from_slice(p).expect("fewer than 2^32 points"));
    fn prepare(points: &[[f64; D]]) -> Self::Input {
        points.to_vec()
    }
    fn len(tree: &Self::Tree) -> usize {
        tree.size()
    }
}

/// rstar 0.12, `RTree::bulk_load` of bare `[f64; D]` points (takes ownership).
struct Rstar;

impl<const D: usize> Adapter<D> for Rstar
where
    [f64; D]: rstar::Point,
{
    const NAME: &'static str = "rstar";
    type Input = Vec<[f64; D]>;
    type Tree = rstar::RTree<[f64; D]>;
    const BUILD: Build<Self::Input, Self::Tree> = Build::Own(rstar::RTree::bulk_load);
    fn prepare(points: &[[f64; D]]) -> Self::Input {
        points.to_vec()
    }
    fn len(tree: &Self::Tree) -> usize {
        tree.size()
    }
}

/// Every group of dimension `D`.
fn bench_dim<const D: usize>(c: &mut Criterion)
where
    Rstar: Adapter<D>,
{
    for dist in Distribution::ALL {
        workloads::groups::<D>(
            c,
            dist.name(),
            |n| dist.points(n, SEED),
            |group, points| {
                workloads::run::<Kiddo, D>(group, points);
                workloads::run::<Rstar, D>(group, points);
            },
        );
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
