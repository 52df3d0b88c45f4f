//! Bulk build, side by side: orthtree's `PointTreeBuilder` against kiddo's `ImmutableKdTree` and
//! rstar's `RTree::bulk_load`, on the same seeded points (uniform in the unit cube, and 64
//! Gaussian clusters of sigma 0.01, unclamped), in 2D and 3D, `f64`, single-threaded.
//!
//! Each crate sits behind one small [`Adapter`] so that every crate runs the same workload: the
//! adapter turns the shared points into the crate's input once, outside the timing, and then only
//! the build is timed. Where the API takes ownership the input is cloned outside the timing
//! (`iter_batched`); the built trees are dropped outside the timing for every crate.
//!
//! Groups are named `build/{2d,3d}/{uniform,clustered}/{n}` with functions `orthtree` (default
//! bucket size, `build(&entries)`), `orthtree_vec` (`build_from_vec(entries)`), `kiddo` (bucket
//! 32, `u32` items) and `rstar`.
//!
//! Run with `cargo bench -p orthtree-compare --bench build` (about two minutes on two cores).

use std::time::Duration;

use criterion::measurement::WallTime;
use criterion::{
    criterion_group, criterion_main, BatchSize, BenchmarkGroup, Criterion, SamplingMode, Throughput,
};
use kiddo::ImmutableKdTree;
use orthtree::prelude::*;
use orthtree::{PointTree, PointTreeBuilder};
use orthtree_compare::points::Distribution;

/// The sizes of every group: a small one to show scaling, and 10^6.
const SIZES: [usize; 2] = [10_000, 1_000_000];
/// The seed of every point set.
const SEED: u64 = 0x5EED_0F7E_E5ED;

/// How an adapter's build receives its input.
enum Build<I, T> {
    /// Borrows the prepared input: nothing is copied per iteration.
    Borrow(fn(&I) -> T),
    /// Consumes the input: a fresh clone is made per iteration, outside the timing.
    Own(fn(I) -> T),
}

/// One crate's bulk build of a `D`-dimensional point set.
trait Adapter<const D: usize> {
    /// The benchmark function's name within a group.
    const NAME: &'static str;
    /// What the build takes, prepared from the shared points outside the timing.
    type Input: Clone;
    /// What the build returns.
    type Tree;
    /// The timed call.
    const BUILD: Build<Self::Input, Self::Tree>;
    /// Makes the crate's input from the shared points.
    fn prepare(points: &[[f64; D]]) -> Self::Input;
    /// The number of points in a built tree, to check that every crate got them all.
    fn len(tree: &Self::Tree) -> usize;
}

/// orthtree, default bucket size, `build(&entries)` (items cloned from the slice).
struct Orthtree;

impl<const D: usize> Adapter<D> for Orthtree {
    const NAME: &'static str = "orthtree";
    type Input = Vec<([f64; D], u32)>;
    type Tree = PointTree<f64, u32, D>;
    const BUILD: Build<Self::Input, Self::Tree> =
        Build::Borrow(|entries| PointTreeBuilder::new().build(entries).unwrap());
    fn prepare(points: &[[f64; D]]) -> Self::Input {
        entries(points)
    }
    fn len(tree: &Self::Tree) -> usize {
        tree.len()
    }
}

/// orthtree, default bucket size, `build_from_vec(entries)` (items moved).
struct OrthtreeVec;

impl<const D: usize> Adapter<D> for OrthtreeVec {
    const NAME: &'static str = "orthtree_vec";
    type Input = Vec<([f64; D], u32)>;
    type Tree = PointTree<f64, u32, D>;
    const BUILD: Build<Self::Input, Self::Tree> =
        Build::Own(|entries| PointTreeBuilder::new().build_from_vec(entries).unwrap());
    fn prepare(points: &[[f64; D]]) -> Self::Input {
        entries(points)
    }
    fn len(tree: &Self::Tree) -> usize {
        tree.len()
    }
}

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

/// orthtree's input: each point with its index as item.
fn entries<const D: usize>(points: &[[f64; D]]) -> Vec<([f64; D], u32)> {
    points
        .iter()
        .enumerate()
        .map(|(i, &p)| (p, i as u32))
        .collect()
}

/// Times `A`'s build of `points` in `group`, after one untimed build that checks the size.
fn run<A: Adapter<D>, const D: usize>(
    group: &mut BenchmarkGroup<'_, WallTime>,
    points: &[[f64; D]],
) {
    let input = A::prepare(points);
    let check = match A::BUILD {
        Build::Borrow(build) => build(&input),
        Build::Own(build) => build(input.clone()),
    };
    assert_eq!(A::len(&check), points.len(), "{} lost points", A::NAME);
    drop(check);
    group.bench_function(A::NAME, |b| match A::BUILD {
        Build::Borrow(build) => b.iter_batched(
            || (),
            |()| build(std::hint::black_box(&input)),
            BatchSize::LargeInput,
        ),
        Build::Own(build) => b.iter_batched(|| input.clone(), build, BatchSize::LargeInput),
    });
}

/// Every group of dimension `D`.
fn bench_dim<const D: usize>(c: &mut Criterion)
where
    Orthtree: Adapter<D>,
    OrthtreeVec: Adapter<D>,
    Kiddo: Adapter<D>,
    Rstar: Adapter<D>,
{
    for dist in Distribution::ALL {
        for n in SIZES {
            let points = dist.points::<D>(n, SEED);
            let mut group = c.benchmark_group(format!("build/{D}d/{}/{n}", dist.name()));
            group.throughput(Throughput::Elements(n as u64));
            if n >= 100_000 {
                // One build takes tens to hundreds of milliseconds: ten samples of equal
                // iteration counts instead of criterion's linear ramp.
                group
                    .sampling_mode(SamplingMode::Flat)
                    .sample_size(10)
                    .warm_up_time(Duration::from_millis(1000))
                    .measurement_time(Duration::from_secs(3));
            } else {
                group
                    .sample_size(20)
                    .warm_up_time(Duration::from_millis(500))
                    .measurement_time(Duration::from_millis(1500));
            }
            run::<Orthtree, D>(&mut group, &points);
            run::<OrthtreeVec, D>(&mut group, &points);
            run::<Kiddo, D>(&mut group, &points);
            run::<Rstar, D>(&mut group, &points);
            group.finish();
        }
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
