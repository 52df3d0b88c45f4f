//! The bulk-build bench's adapters and groups, shared by the library's `build` bench and the
//! comparison crate's (which adds kiddo and rstar to every group); each includes this file with
//! `#[path]`.
//!
//! Each way of building sits behind one small [`Adapter`]: it turns the shared points into its
//! input once, outside the timing, and then only the build is timed. Where the API takes
//! ownership the input is cloned outside the timing (`iter_batched`); the built trees are
//! dropped outside the timing.

use std::time::Duration;

use criterion::measurement::WallTime;
use criterion::{BatchSize, BenchmarkGroup, Criterion, SamplingMode, Throughput};
use orthtree::prelude::*;
use orthtree::{points::PointTreeBuilder, PointTree};

/// The sizes of every group: a small one to show scaling, and 10^6.
pub const SIZES: [usize; 2] = [10_000, 1_000_000];
/// The seed of every point set.
pub const SEED: u64 = 0x5EED_0F7E_E5ED;

/// How an adapter's build receives its input.
pub enum Build<I, T> {
    /// Borrows the prepared input: nothing is copied per iteration.
    Borrow(fn(&I) -> T),
    /// Consumes the input: a fresh clone is made per iteration, outside the timing.
    Own(fn(I) -> T),
}

/// One crate's bulk build of a `D`-dimensional point set.
pub trait Adapter<const D: usize> {
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
pub struct Orthtree;

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
pub struct OrthtreeVec;

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

/// orthtree's input: each point with its index as item.
fn entries<const D: usize>(points: &[[f64; D]]) -> Vec<([f64; D], u32)> {
    points
        .iter()
        .enumerate()
        .map(|(i, &p)| (p, i as u32))
        .collect()
}

/// Times `A`'s build of `points` in `group`, after one untimed build that checks the size.
///
/// # Panics
///
/// When the built tree does not hold every point.
pub fn run<A: Adapter<D>, const D: usize>(
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

/// The groups `build/{D}d/{name}/{n}` for every size of [`SIZES`], on `points(n)`: orthtree's
/// two builds, then whatever `rivals` adds to the group.
pub fn groups<const D: usize>(
    c: &mut Criterion,
    name: &str,
    points: impl Fn(usize) -> Vec<[f64; D]>,
    rivals: impl Fn(&mut BenchmarkGroup<'_, WallTime>, &[[f64; D]]),
) {
    for n in SIZES {
        let points = points(n);
        let mut group = c.benchmark_group(format!("build/{D}d/{name}/{n}"));
        group.throughput(Throughput::Elements(n as u64));
        if n >= 100_000 {
            // One build takes tens to hundreds of milliseconds: ten samples of equal iteration
            // counts instead of criterion's linear ramp.
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
        rivals(&mut group, &points);
        group.finish();
    }
}
