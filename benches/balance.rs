//! 2:1 balance on p4est's fractal workload (criterion): `Tree::balance` for face and corner
//! connectivity in 2D and 3D at several levels, beside `is_balanced` on the result and the
//! chapter's BALANCEQUADTREE (`Tree::balance_chapter`) on the smaller trees; with `--features
//! rayon`, `par_balance` and `par_is_balanced` too.

use criterion::{criterion_group, criterion_main, BatchSize, BenchmarkId, Criterion, Throughput};
use orthtree::tree::fractal;
use orthtree::{Connectivity, Tree};

fn bench_dim<const D: usize>(c: &mut Criterion, levels: &[u8]) {
    for conn in [Connectivity::Face, Connectivity::Corner] {
        let mut group = c.benchmark_group(format!("balance/{D}d/{conn:?}").to_lowercase());
        group.sample_size(10);
        for &level in levels {
            let tree: Tree<D> = fractal::fractal(level);
            group.throughput(Throughput::Elements(tree.leaf_count() as u64));
            group.bench_with_input(BenchmarkId::new("balance", level), &tree, |b, t| {
                b.iter_batched(|| t.clone(), |mut t| t.balance(conn), BatchSize::LargeInput)
            });
            let mut balanced = tree.clone();
            balanced.balance(conn);
            group.bench_with_input(BenchmarkId::new("is_balanced", level), &balanced, |b, t| {
                b.iter(|| t.is_balanced(conn))
            });
            #[cfg(feature = "rayon")]
            {
                group.bench_with_input(BenchmarkId::new("par_balance", level), &tree, |b, t| {
                    b.iter_batched(
                        || t.clone(),
                        |mut t| t.par_balance(conn),
                        BatchSize::LargeInput,
                    )
                });
                group.bench_with_input(
                    BenchmarkId::new("par_is_balanced", level),
                    &balanced,
                    |b, t| b.iter(|| t.par_is_balanced(conn)),
                );
            }
            if tree.leaf_count() <= 200_000 {
                group.bench_with_input(
                    BenchmarkId::new("balance_chapter", level),
                    &tree,
                    |b, t| {
                        b.iter_batched(
                            || t.clone(),
                            |mut t| t.balance_chapter(conn),
                            BatchSize::LargeInput,
                        )
                    },
                );
            }
        }
        group.finish();
    }
}

fn balance(c: &mut Criterion) {
    bench_dim::<2>(c, &[8, 10, 12]);
    bench_dim::<3>(c, &[6, 8]);
}

criterion_group!(benches, balance);
criterion_main!(benches);
