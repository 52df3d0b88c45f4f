//! The mesh writers (criterion): each format on its own into a reused in-memory buffer (the
//! formatting, without the page cache), on the built-in board's mesh and on a random board's
//! about eight times larger, with throughput in bytes written. Writing files adds the kernel's
//! copy into the page cache on top; `orthtree mesh` prints that wall time.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use orthtree::io::{gmsh, svg, triangle, vtk};
use orthtree::mesh::{generate_mesh, random_board, sample_board, Board, Mesh};
use std::io;

/// A writer of one format, by name.
type Writer = fn(&Mesh, &Board, &mut Vec<u8>) -> io::Result<()>;

const WRITERS: [(&str, Writer); 6] = [
    ("node", |m, _, o| triangle::write_node(m, o)),
    ("ele", |m, _, o| triangle::write_ele(m, o)),
    ("edge", |m, _, o| triangle::write_edge(m, o)),
    ("msh", |m, _, o| gmsh::write_msh(m, o)),
    ("vtk", |m, _, o| vtk::write_vtk(m, o)),
    ("svg", |m, b, o| svg::write_mesh_svg(m, b, o)),
];

fn writers(c: &mut Criterion) {
    let mut group = c.benchmark_group("writers");
    group.sample_size(10);
    let boards = [
        ("sample", sample_board()),
        ("random/U=2^12", random_board(1, 1 << 12, 1000)),
    ];
    for (name, board) in &boards {
        let mesh = generate_mesh(board).expect("valid boards").mesh;
        for (format, write) in WRITERS {
            let mut out = Vec::new();
            write(&mesh, board, &mut out).expect("an in-memory buffer");
            group.throughput(Throughput::Bytes(out.len() as u64));
            group.bench_function(BenchmarkId::new(format, name), |b| {
                b.iter(|| {
                    out.clear();
                    write(&mesh, board, &mut out).expect("an in-memory buffer");
                    out.len()
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, writers);
criterion_main!(benches);
