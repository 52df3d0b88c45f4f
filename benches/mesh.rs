//! The board mesher (criterion): `generate_mesh` (the chapter's mode), the coarsest mode and
//! `Mesh::validate` on random boards of growing size, with throughput in triangles so that
//! near-linear growth shows as a flat rate.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use orthtree::mesh::{generate_mesh, random_board, sample_board, MeshOptions, Mode};

fn mesh(c: &mut Criterion) {
    let mut group = c.benchmark_group("mesh");
    group.sample_size(10);
    let boards = [
        ("sample".to_string(), sample_board()),
        ("random/U=2^8".to_string(), random_board(1, 1 << 8, 40)),
        ("random/U=2^10".to_string(), random_board(2, 1 << 10, 160)),
        ("random/U=2^12".to_string(), random_board(3, 1 << 12, 640)),
        ("random/U=2^14".to_string(), random_board(4, 1 << 14, 2560)),
    ];
    for (name, board) in &boards {
        let out = generate_mesh(board).expect("random boards are valid");
        group.throughput(Throughput::Elements(out.mesh.triangles.len() as u64));
        group.bench_with_input(BenchmarkId::new("generate", name), board, |b, board| {
            b.iter(|| generate_mesh(board).expect("valid"))
        });
        group.bench_with_input(BenchmarkId::new("validate", name), &out.mesh, |b, m| {
            b.iter(|| m.validate(board))
        });
        let coarsest = MeshOptions::new().mode(Mode::Coarsest);
        let coarse = coarsest.generate(board).expect("valid");
        group.throughput(Throughput::Elements(coarse.mesh.triangles.len() as u64));
        group.bench_with_input(BenchmarkId::new("coarsest", name), board, |b, board| {
            b.iter(|| coarsest.generate(board).expect("valid"))
        });
    }
    group.finish();
}

criterion_group!(benches, mesh);
criterion_main!(benches);
