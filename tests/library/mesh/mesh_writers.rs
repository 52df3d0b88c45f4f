//! The streamed mesh writers against plain reference writers written here with `writeln!` (the
//! layout each format's module documents): byte-identical `.node`, `.ele`, `.edge` and VTK files
//! on meshes of several boards; and the SVG of a large mesh drawn merged, its size bounded by
//! the picture and the board, not by the mesh.

use orthtree::io::svg::{mesh_svg, write_mesh_svg, MESH_SVG_DETAIL_TRIANGLES};
use orthtree::io::{triangle, vtk};
use orthtree::mesh::{
    random_board, sample_board, Board, Component, Mesh, MeshOptions, Mode, SegmentKind,
};
use std::collections::HashMap;
use std::fmt::Write as _;

fn reference_node(mesh: &Mesh) -> String {
    let mut on_boundary = vec![false; mesh.vertices.len()];
    for s in &mesh.segments {
        if s.kind == SegmentKind::Boundary {
            for v in s.vertices {
                on_boundary[v as usize] = true;
            }
        }
    }
    let mut out = format!("{} 2 0 1\n", mesh.vertices.len());
    for (i, (p, &b)) in mesh.vertices.iter().zip(&on_boundary).enumerate() {
        writeln!(out, "{} {} {} {}", i + 1, p[0], p[1], u8::from(b)).unwrap();
    }
    out
}

fn reference_ele(mesh: &Mesh) -> String {
    let mut out = format!("{} 3 1\n", mesh.triangles.len());
    for (i, (t, r)) in mesh.triangles.iter().zip(&mesh.regions).enumerate() {
        writeln!(out, "{} {} {} {} {r}", i + 1, t[0] + 1, t[1] + 1, t[2] + 1).unwrap();
    }
    out
}

fn reference_edge(mesh: &Mesh) -> String {
    let mut index: HashMap<(u32, u32), usize> = HashMap::new();
    let mut edges: Vec<([u32; 2], u64)> = Vec::new();
    for t in &mesh.triangles {
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            index.entry((a.min(b), a.max(b))).or_insert_with(|| {
                edges.push(([a, b], 0));
                edges.len() - 1
            });
        }
    }
    for s in &mesh.segments {
        let [a, b] = s.vertices;
        if let Some(&k) = index.get(&(a.min(b), a.max(b)))
            && edges[k].1 <= 1
        {
            edges[k].1 = match s.kind {
                SegmentKind::Boundary => 1,
                SegmentKind::Component(i) => 1 + u64::from(i),
            };
        }
    }
    let mut out = format!("{} 1\n", edges.len());
    for (i, ([a, b], m)) in edges.iter().enumerate() {
        writeln!(out, "{} {} {} {m}", i + 1, a + 1, b + 1).unwrap();
    }
    out
}

fn reference_vtk(mesh: &Mesh) -> String {
    let (n, t) = (mesh.vertices.len(), mesh.triangles.len());
    let mut out = String::from(
        "# vtk DataFile Version 3.0\northtree quadtree mesh\nASCII\nDATASET UNSTRUCTURED_GRID\n",
    );
    writeln!(out, "POINTS {n} double").unwrap();
    for p in &mesh.vertices {
        writeln!(out, "{} {} 0", p[0], p[1]).unwrap();
    }
    writeln!(out, "CELLS {t} {}", 4 * t).unwrap();
    for [a, b, c] in &mesh.triangles {
        writeln!(out, "3 {a} {b} {c}").unwrap();
    }
    writeln!(out, "CELL_TYPES {t}").unwrap();
    for _ in 0..t {
        out.push_str("5\n");
    }
    writeln!(
        out,
        "CELL_DATA {t}\nSCALARS region int 1\nLOOKUP_TABLE default"
    )
    .unwrap();
    for r in &mesh.regions {
        writeln!(out, "{r}").unwrap();
    }
    out
}

fn written(write: impl Fn(&mut Vec<u8>) -> std::io::Result<()>) -> String {
    let mut out = Vec::new();
    write(&mut out).unwrap();
    String::from_utf8(out).unwrap()
}

fn boards() -> Vec<Board> {
    vec![
        sample_board(),
        random_board(1, 1 << 10, 30),
        random_board(5, 1 << 14, 50),
        Board::new(
            16,
            vec![Component::new(vec![[1, 14], [2, 14], [2, 15], [1, 15]])],
        )
        .unwrap(),
        Board::new(1, vec![]).unwrap(),
        // coordinates and indices of many digits
        Board::new(
            1 << 30,
            vec![Component::new(vec![
                [1 << 20, 3 << 20],
                [9 << 22, 3 << 20],
                [9 << 22, (3 << 20) + (9 << 22) - (1 << 20)],
            ])],
        )
        .unwrap(),
    ]
}

#[test]
fn streamed_files_equal_the_reference_layout() {
    for board in boards() {
        for mode in [Mode::Book, Mode::Coarsest] {
            let mesh = MeshOptions::new().mode(mode).generate(&board).unwrap().mesh;
            assert_eq!(
                written(|o| triangle::write_node(&mesh, o)),
                reference_node(&mesh)
            );
            assert_eq!(
                written(|o| triangle::write_ele(&mesh, o)),
                reference_ele(&mesh)
            );
            assert_eq!(
                written(|o| triangle::write_edge(&mesh, o)),
                reference_edge(&mesh)
            );
            assert_eq!(written(|o| vtk::write_vtk(&mesh, o)), reference_vtk(&mesh));
        }
    }
}

#[test]
fn streamed_files_through_a_one_byte_writer() {
    // a writer taking one byte per call still receives every byte, in order
    struct Trickle(Vec<u8>);
    impl std::io::Write for Trickle {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            self.0.extend(buf.first());
            Ok(buf.len().min(1))
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    let board = random_board(2, 1 << 12, 20);
    let mesh = MeshOptions::new().generate(&board).unwrap().mesh;
    let mut t = Trickle(Vec::new());
    triangle::write_ele(&mesh, &mut t).unwrap();
    assert_eq!(String::from_utf8(t.0).unwrap(), reference_ele(&mesh));
}

#[test]
fn large_meshes_are_drawn_merged_and_bounded() {
    // 0.5 to 1 million triangles each, 10 to 20 times the threshold of the merged drawing, on
    // boards of few components (60) to many (300)
    for (seed, levels, count) in [(3, 14, 60), (7, 12, 200), (5, 11, 300)] {
        let board = random_board(seed, 1 << levels, count);
        let mesh = MeshOptions::new().generate(&board).unwrap().mesh;
        assert!(
            mesh.triangles.len() > MESH_SVG_DETAIL_TRIANGLES,
            "{}",
            mesh.triangles.len()
        );
        let mut out = Vec::new();
        write_mesh_svg(&mesh, &board, &mut out).unwrap();
        let svg = String::from_utf8(out).unwrap();
        assert_eq!(svg, mesh_svg(&mesh, &board));
        assert!(svg.starts_with("<svg") && svg.ends_with("</svg>\n"));
        assert_eq!(svg.matches("<polygon").count(), 0);
        // one filled path per component, one outline path per component
        let filled = svg.matches("<path fill=\"#").count();
        assert_eq!(filled, board.components().len());
        // bounded by the picture (about 800 x 800 pixels) and the board, not by the mesh
        let vertices: usize = board.components().iter().map(|c| c.outline.len()).sum();
        assert!(svg.len() < 8_000_000 + 60 * vertices, "{} bytes", svg.len());
        assert!(svg.len() < 40 * mesh.triangles.len(), "{} bytes", svg.len());
    }
}

#[test]
fn small_meshes_are_drawn_triangle_by_triangle() {
    for board in boards() {
        let mesh = MeshOptions::new()
            .mode(Mode::Coarsest)
            .generate(&board)
            .unwrap()
            .mesh;
        if mesh.triangles.len() <= MESH_SVG_DETAIL_TRIANGLES {
            let svg = mesh_svg(&mesh, &board);
            assert_eq!(svg.matches("<polygon").count(), mesh.triangles.len());
        }
    }
}
