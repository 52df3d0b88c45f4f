//! What consumes a mesh: `Mesh::validate` on hand-built meshes, each broken one failing exactly
//! the checks its defect implies; the half-edge view's twin/next/prev consistency and its
//! refusals; the Triangle, Gmsh and VTK writers parsed back by small parsers written here; the
//! SVG picture. Meshes from `generate_mesh` are validated too.

use orthtree::io::svg::mesh_svg;
use orthtree::io::{gmsh, triangle, vtk};
use orthtree::mesh::{
    generate_mesh, random_board, sample_board, Board, Component, HalfEdgeError, Mesh,
    MeshValidationError as V, Point, RegionRule, Segment, SegmentKind,
};
use std::collections::{BTreeMap, BTreeSet, HashMap};

// ---------------------------------------------------------------------------------------------
// Hand-built meshes
// ---------------------------------------------------------------------------------------------

/// Index of grid point (x, y) in a `(n + 1) x (n + 1)` grid of vertices.
fn gv(n: i64, x: i64, y: i64) -> u32 {
    (y * (n + 1) + x) as u32
}

fn grid_vertices(n: i64) -> Vec<Point> {
    (0..=n).flat_map(|y| (0..=n).map(move |x| [x, y])).collect()
}

fn seg(a: u32, b: u32, kind: SegmentKind) -> Segment {
    Segment {
        vertices: [a, b],
        kind,
    }
}

/// Boundary segments of the board [0, n]^2 meshed on the unit grid, counter-clockwise.
fn grid_boundary(n: i64) -> Vec<Segment> {
    let mut ring = Vec::new();
    ring.extend((0..n).map(|x| [x, 0]));
    ring.extend((0..n).map(|y| [n, y]));
    ring.extend((0..n).map(|x| [n - x, n]));
    ring.extend((0..n).map(|y| [0, n - y]));
    (0..ring.len())
        .map(|i| {
            let (p, q) = (ring[i], ring[(i + 1) % ring.len()]);
            seg(gv(n, p[0], p[1]), gv(n, q[0], q[1]), SegmentKind::Boundary)
        })
        .collect()
}

/// The unit-square component at (0, 0)-(1, 1), counter-clockwise.
fn unit_square() -> Component {
    Component::new(vec![[0, 0], [1, 0], [1, 1], [0, 1]])
}

/// The brief's example: U = 2, one unit-square component at (0, 0)-(1, 1); every unit cell cut
/// along its rising diagonal (8 triangles with angles 45, 45, 90); the cell of the component
/// is region 1. Two of the component's edges lie on the board boundary, so they are marked
/// twice (Boundary and Component(1)).
fn square_board() -> (Board, Mesh) {
    let board = Board::new(2, vec![unit_square()]).unwrap();
    let n = 2;
    let mut triangles = Vec::new();
    let mut regions = Vec::new();
    for y in 0..n {
        for x in 0..n {
            let (a, b, c, d) = (
                gv(n, x, y),
                gv(n, x + 1, y),
                gv(n, x + 1, y + 1),
                gv(n, x, y + 1),
            );
            triangles.extend([[a, b, c], [a, c, d]]);
            let r = u32::from(x == 0 && y == 0);
            regions.extend([r, r]);
        }
    }
    let mut segments = grid_boundary(n);
    let c1 = SegmentKind::Component(1);
    let (a, b, c, d) = (gv(n, 0, 0), gv(n, 1, 0), gv(n, 1, 1), gv(n, 0, 1));
    segments.extend([seg(a, b, c1), seg(b, c, c1), seg(c, d, c1), seg(d, a, c1)]);
    let mesh = Mesh {
        vertices: grid_vertices(n),
        triangles,
        regions,
        segments,
    };
    (board, mesh)
}

/// A board without components and the boundary segments of a mesh whose boundary vertices
/// are exactly `ring` (counter-clockwise vertex indices).
fn empty_board(u: i64) -> Board {
    Board::new(u, vec![]).unwrap()
}

fn ring_segments(ring: &[u32]) -> Vec<Segment> {
    (0..ring.len())
        .map(|i| seg(ring[i], ring[(i + 1) % ring.len()], SegmentKind::Boundary))
        .collect()
}

/// A named change to a mesh.
type Edit = (&'static str, fn(&mut Mesh));

fn failed(mesh: &Mesh, board: &Board) -> Vec<&'static str> {
    let report = mesh.validate(board);
    // Display never panics and names every failed check.
    let text = report.to_string();
    for name in report.failed() {
        assert!(text.contains(name), "{text}");
    }
    report.failed()
}

// ---------------------------------------------------------------------------------------------
// validate
// ---------------------------------------------------------------------------------------------

#[test]
fn hand_built_square_board_is_valid() {
    let (board, mesh) = square_board();
    let report = mesh.validate(&board);
    assert!(report.is_ok(), "{report}");
    assert_eq!(report.angle_range_deg, Some([45.0, 90.0]));
    assert_eq!(
        (report.vertices_used, report.edges, report.triangles),
        (9, 16, 8)
    );
    assert!(report.to_string().starts_with("valid mesh: 8 triangles"));
    // the falling diagonals are just as good
    let mut other = mesh.clone();
    let n = 2;
    for (k, (x, y)) in [(0, 0), (1, 0), (0, 1), (1, 1)].into_iter().enumerate() {
        let (a, b, c, d) = (
            gv(n, x, y),
            gv(n, x + 1, y),
            gv(n, x + 1, y + 1),
            gv(n, x, y + 1),
        );
        other.triangles[2 * k] = [a, b, d];
        other.triangles[2 * k + 1] = [b, c, d];
    }
    assert!(other.validate(&board).is_ok());
}

/// A vertex in the middle of another triangle's edge: (1, 1) lies on the big triangle's
/// hypotenuse. The edge is unpaired (conforming) and the extra edge breaks Euler's formula
/// (5 - 8 + 3 = 0); area, angles and the rest are fine.
#[test]
fn t_junction_fails_conforming_and_euler() {
    let board = empty_board(2);
    let mesh = Mesh {
        vertices: vec![[0, 0], [2, 0], [2, 2], [0, 2], [1, 1]],
        triangles: vec![[0, 1, 2], [0, 4, 3], [4, 2, 3]],
        regions: vec![0; 3],
        segments: ring_segments(&[0, 1, 2, 3]),
    };
    assert_eq!(failed(&mesh, &board), ["conforming", "euler"]);
    let report = mesh.validate(&board);
    assert!(
        matches!(
            report.conforming.error(),
            Some(V::UnpairedEdge {
                from: 2,
                to: 0,
                triangle: 0,
                points: [[2, 2], [0, 0]]
            })
        ),
        "{report}"
    );
    assert!(report.to_string().contains("2 -> 0"), "{report}");
}

#[test]
fn wrong_region_fails_regions_only() {
    let (board, mut mesh) = square_board();
    // a board triangle of cell (1, 1) put into the component
    mesh.regions[6] = 1;
    assert_eq!(failed(&mesh, &board), ["regions"]);
    // the component's triangle put on the board: the left of its outline is wrong
    let (_, mut mesh) = square_board();
    mesh.regions[0] = 0;
    let report = mesh.validate(&board);
    assert_eq!(report.failed(), ["regions"]);
    assert!(
        matches!(
            report.regions.error(),
            Some(V::WrongRegion {
                triangle: 0,
                region: 0,
                expected: 1,
                rule: RegionRule::LeftOfOutline(1),
                ..
            })
        ),
        "{report}"
    );
    // a region number beyond the components
    let (_, mut mesh) = square_board();
    mesh.regions[7] = 5;
    let report = mesh.validate(&board);
    assert_eq!(report.failed(), ["regions"]);
    assert_eq!(
        report.regions.error(),
        Some(&V::RegionOutOfRange {
            triangle: 7,
            vertices: mesh.triangles[7],
            region: 5,
            components: 1
        }),
        "{report}"
    );
}

/// U = 4 fanned from (2, 1): the bottom triangle has a 126.9-degree angle (and 26.6-degree
/// ones), all triangles are still Delaunay (each opposite vertex is outside the circumcircle).
#[test]
fn obtuse_triangle_fails_angles_only() {
    let board = empty_board(4);
    let mesh = Mesh {
        vertices: vec![[0, 0], [4, 0], [4, 4], [0, 4], [2, 1]],
        triangles: vec![[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]],
        regions: vec![0; 4],
        segments: ring_segments(&[0, 1, 2, 3]),
    };
    let report = mesh.validate(&board);
    assert_eq!(report.failed(), ["angles"], "{report}");
    assert!(
        matches!(
            report.angles.error(),
            Some(V::Angle { triangle: 0, vertex: 0, point: [0, 0], dot, cross, .. }) if dot > cross
        ),
        "{report}"
    );
    let [lo, hi] = report.angle_range_deg.unwrap();
    assert!((hi - 126.87).abs() < 0.01, "{hi}");
    assert!((lo - 26.57).abs() < 0.01, "{lo}");
}

/// Flipping a triangle: it is clockwise (orientation), its edges now run the same way as its
/// neighbours' (conforming), its area counts negatively (area, and the component's area under
/// regions), and its side on the board boundary now runs clockwise, so it no longer counts as a
/// boundary edge while still marked as one (segments); edges, vertices and so Euler's formula
/// are unchanged.
#[test]
fn clockwise_triangle_fails_orientation() {
    let (board, mut mesh) = square_board();
    mesh.triangles[0].swap(1, 2);
    let report = mesh.validate(&board);
    assert_eq!(
        report.failed(),
        ["orientation", "conforming", "area", "regions", "segments"],
        "{report}"
    );
    assert!(
        matches!(
            report.orientation.error(),
            Some(V::NotCounterClockwise { triangle: 0, doubled_area, .. }) if *doubled_area < 0
        ),
        "{report}"
    );
    assert!(
        report.orientation.to_string().contains("clockwise"),
        "{report}"
    );
    // a flipped board triangle away from the component
    let (_, mut mesh) = square_board();
    mesh.triangles[6].swap(0, 1);
    let report = mesh.validate(&board);
    assert!(report.failed().contains(&"orientation"));
    assert!(
        matches!(
            report.orientation.error(),
            Some(V::NotCounterClockwise { triangle: 6, .. })
        ),
        "{report}"
    );
}

/// Removing a triangle. The board triangle of cell (1, 1) at the board's right side: conforming
/// (its diagonal and its lower side are now unpaired), area 3.5, and the board-boundary segment
/// (2, 1)-(2, 2) is no longer a mesh edge (segments); Euler's formula still holds, the rest is a
/// disc. The upper triangle of cell (1, 0) touches the boundary only at a vertex: removing it
/// leaves a hole, so V - E + F = 9 - 16 + 7 = 0 (euler), and its outline segments remain.
#[test]
fn missing_triangle_fails_conforming_and_area() {
    let (board, mut mesh) = square_board();
    mesh.triangles.remove(6);
    mesh.regions.remove(6);
    let report = mesh.validate(&board);
    assert_eq!(
        report.failed(),
        ["conforming", "area", "segments"],
        "{report}"
    );
    assert_eq!(
        report.area.error(),
        Some(&V::Area {
            doubled_area: 7,
            size: 2
        }),
        "{report}"
    );
    assert!(report.area.to_string().contains("3.5"), "{report}");
    assert!(
        matches!(report.segments.error(), Some(V::SegmentNotEdge { .. })),
        "{report}"
    );

    let (_, mut mesh) = square_board();
    mesh.triangles.remove(3);
    mesh.regions.remove(3);
    let report = mesh.validate(&board);
    assert_eq!(report.failed(), ["conforming", "area", "euler"], "{report}");
    assert_eq!(
        report.euler.error(),
        Some(&V::Euler {
            vertices: 9,
            edges: 16,
            triangles: 7
        }),
        "{report}"
    );
    assert!(report.euler.to_string().contains("= 0"), "{report}");
}

/// A valid tiling whose shared diagonal is not Delaunay: (2, 3) lies inside the circumcircle of
/// (0, 0), (2, 1), (4, 4). Such triangles are necessarily obtuse (exercise 14.3).
#[test]
fn non_delaunay_fails_delaunay_and_angles() {
    let board = empty_board(4);
    let mesh = Mesh {
        vertices: vec![[0, 0], [4, 0], [4, 4], [0, 4], [2, 1], [2, 3]],
        triangles: vec![
            [0, 1, 4],
            [1, 2, 4],
            [0, 4, 2],
            [0, 2, 5],
            [2, 3, 5],
            [3, 0, 5],
        ],
        regions: vec![0; 6],
        segments: ring_segments(&[0, 1, 2, 3]),
    };
    let report = mesh.validate(&board);
    assert_eq!(report.failed(), ["angles", "delaunay"], "{report}");
    assert!(
        matches!(
            report.delaunay.error(),
            Some(V::NotDelaunay {
                edge: [2, 0],
                vertex: 5,
                point: [2, 3],
                ..
            })
        ),
        "{report}"
    );
}

/// A triangular component (0, 0), (1, 0), (1, 1) in a mesh cut along the other diagonal: its
/// hypotenuse is not a chain of mesh edges (respects_input), its segment is not a mesh edge
/// (segments), and no set of triangles has its area (regions).
#[test]
fn missing_input_edge_fails_respects_input() {
    let comp = Component::new(vec![[0, 0], [1, 0], [1, 1]]);
    let board = Board::new(2, vec![comp]).unwrap();
    let (_, mut mesh) = square_board();
    let n = 2;
    let (a, b, c, d) = (gv(n, 0, 0), gv(n, 1, 0), gv(n, 1, 1), gv(n, 0, 1));
    mesh.triangles[0] = [a, b, d];
    mesh.triangles[1] = [b, c, d];
    mesh.regions[0] = 1;
    mesh.regions[1] = 0;
    let c1 = SegmentKind::Component(1);
    mesh.segments.truncate(8);
    mesh.segments
        .extend([seg(a, b, c1), seg(b, c, c1), seg(c, a, c1)]);
    let report = mesh.validate(&board);
    assert_eq!(
        report.failed(),
        ["respects_input", "regions", "segments"],
        "{report}"
    );
    assert!(
        matches!(
            report.respects_input.error(),
            Some(V::OutlineEdgeBroken {
                component: 1,
                from: [1, 1],
                to: [0, 0],
                ..
            })
        ),
        "{report}"
    );
    // cut along the right diagonal, it is valid
    let (_, mut mesh) = square_board();
    mesh.regions[1] = 0;
    mesh.segments.truncate(8);
    mesh.segments
        .extend([seg(a, b, c1), seg(b, c, c1), seg(c, a, c1)]);
    let report = mesh.validate(&board);
    assert!(report.is_ok(), "{report}");
}

#[test]
fn segment_defects_fail_segments_only() {
    let (board, base) = square_board();
    let edits: [Edit; 5] = [
        ("missing boundary segment", |m| {
            m.segments.remove(3);
        }),
        ("missing outline segment", |m| {
            m.segments.remove(10);
        }),
        ("wrong kind", |m| {
            m.segments[10].kind = SegmentKind::Boundary
        }),
        ("repeated", |m| m.segments.push(m.segments[4])),
        ("not a mesh edge", |m| {
            m.segments
                .push(seg(gv(2, 0, 0), gv(2, 2, 2), SegmentKind::Boundary))
        }),
    ];
    for (what, edit) in edits {
        let mut mesh = base.clone();
        edit(&mut mesh);
        assert_eq!(failed(&mesh, &board), ["segments"], "{what}");
    }
    // the reversed direction of a segment is the same edge
    let mut mesh = base.clone();
    for s in &mut mesh.segments {
        s.vertices.reverse();
    }
    assert!(mesh.validate(&board).is_ok());
}

/// A mesh of the wrong board: its boundary does not reach U = 4.
#[test]
fn wrong_board_size_fails_conforming() {
    let (_, mesh) = square_board();
    let board = Board::new(4, vec![unit_square()]).unwrap();
    let report = mesh.validate(&board);
    assert!(report.failed().contains(&"conforming"), "{report}");
    assert!(report.failed().contains(&"area"), "{report}");
    assert!(!report.is_ok());
}

#[test]
fn overlapping_duplicate_fails_conforming() {
    let (board, mut mesh) = square_board();
    // the same triangle twice
    mesh.triangles.push(mesh.triangles[4]);
    mesh.regions.push(0);
    let report = mesh.validate(&board);
    // its edges are used by three triangles, or twice in one direction
    assert!(
        matches!(
            report.conforming.error(),
            Some(V::EdgeInMoreThanTwoTriangles { triangles, .. }) if triangles == &[1, 4, 8]
        ) || matches!(
            report.conforming.error(),
            Some(V::RepeatedDirectedEdge {
                triangles: [4, 8],
                ..
            })
        ),
        "{report}"
    );
    assert!(report.failed().contains(&"area"));
    // two vertices at one point
    let (_, mut mesh) = square_board();
    mesh.vertices.push([2, 2]);
    let last = mesh.vertices.len() as u32 - 1;
    mesh.triangles[6][2] = last; // (1,1),(2,1),(2,2) now uses the copy
    let report = mesh.validate(&board);
    assert!(!report.conforming.is_ok(), "{report}");
}

/// Indices out of range, regions missing, vertices far outside the board: reported, never a
/// panic (also in the writers, which refuse to write, and in the half-edge view).
#[test]
fn malformed_meshes_are_reported_not_panics() {
    let (board, base) = square_board();
    let edits: [Edit; 6] = [
        ("triangle index", |m| m.triangles[3][1] = 99),
        ("segment index", |m| m.segments[2].vertices[0] = u32::MAX),
        ("regions too short", |m| {
            m.regions.pop();
        }),
        ("regions too long", |m| m.regions.push(0)),
        ("vertex far away", |m| m.vertices[4] = [i64::MAX, i64::MIN]),
        ("vertex just outside", |m| m.vertices[8] = [3, 2]),
    ];
    for (what, edit) in edits {
        let mut mesh = base.clone();
        edit(&mut mesh);
        let report = mesh.validate(&board);
        assert!(!report.indices.is_ok(), "{what}: {report}");
        let _ = report.to_string();
        let _ = mesh_svg(&mesh, &board);
        let _ = mesh.half_edges();
        if mesh.check_indices().is_err() {
            let mut out = Vec::new();
            for result in [
                triangle::write_node(&mesh, &mut out),
                triangle::write_ele(&mesh, &mut out),
                triangle::write_edge(&mesh, &mut out),
                gmsh::write_msh(&mesh, &mut out),
                vtk::write_vtk(&mesh, &mut out),
            ] {
                let err = result.unwrap_err();
                assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput, "{what}");
            }
            assert!(out.is_empty(), "{what}: nothing written");
        }
    }
    // empty mesh
    let report = Mesh::default().validate(&board);
    assert!(!report.is_ok());
    assert_eq!(report.angle_range_deg, None);
    assert!(report.failed().contains(&"conforming"));
    assert!(report.failed().contains(&"area"));
}

// ---------------------------------------------------------------------------------------------
// Generated meshes
// ---------------------------------------------------------------------------------------------

fn figure_14_2() -> Board {
    Board::new(
        16,
        vec![Component::new(vec![[1, 14], [2, 14], [2, 15], [1, 15]])],
    )
    .unwrap()
}

fn diagonal_board() -> Board {
    // a diamond and a 45-degree trace-like hexagon, away from each other
    let diamond = Component::new(vec![[8, 4], [12, 8], [8, 12], [4, 8]]);
    let hexagon = Component::new(vec![
        [18, 18],
        [24, 18],
        [28, 22],
        [28, 26],
        [22, 26],
        [18, 22],
    ]);
    Board::new(32, vec![diamond, hexagon]).unwrap()
}

fn generated_boards() -> Vec<(&'static str, Board)> {
    vec![
        ("figure 14.2", figure_14_2()),
        ("diagonals", diagonal_board()),
        ("square corner", square_board().0),
        ("random 256", random_board(3, 256, 30)),
        ("sample", sample_board()),
    ]
}

#[test]
fn generated_meshes_validate() {
    for (name, board) in generated_boards() {
        let mesh = generate_mesh(&board).unwrap().mesh;
        let report = mesh.validate(&board);
        assert!(report.is_ok(), "{name}: {report}");
        assert_eq!(report.angle_range_deg, Some([45.0, 90.0]), "{name}");
    }
}

// ---------------------------------------------------------------------------------------------
// Half-edges
// ---------------------------------------------------------------------------------------------

fn check_half_edges(mesh: &Mesh) {
    let he = mesh.half_edges().unwrap();
    assert_eq!(he.len(), 3 * mesh.triangles.len());
    let mut out_of: HashMap<u32, BTreeSet<u32>> = HashMap::new();
    let mut boundary = 0;
    for h in 0..he.len() as u32 {
        assert_eq!(he.next(he.next(he.next(h))), h);
        assert_eq!(he.prev(he.next(h)), h);
        assert_eq!(he.next(he.prev(h)), h);
        assert_eq!(he.face(he.next(h)), he.face(h));
        assert_eq!(he.target(h), he.origin(he.next(h)));
        let t = &mesh.triangles[he.face(h) as usize];
        assert!(t.contains(&he.origin(h)) && t.contains(&he.target(h)));
        match he.twin(h) {
            Some(g) => {
                assert_ne!(g, h);
                assert_eq!(he.twin(g), Some(h));
                assert_eq!(he.origin(g), he.target(h));
                assert_eq!(he.target(g), he.origin(h));
                assert_ne!(he.face(g), he.face(h));
            }
            None => {
                boundary += 1;
                assert!(he.is_boundary(h));
            }
        }
        out_of.entry(he.origin(h)).or_default().insert(h);
    }
    assert_eq!(he.boundary().count(), boundary);
    assert_eq!(he.edge_count(), (he.len() + boundary) / 2);
    for v in 0..mesh.vertices.len() as u32 {
        let walked: Vec<u32> = he.outgoing(v).collect();
        let set: BTreeSet<u32> = walked.iter().copied().collect();
        assert_eq!(set.len(), walked.len(), "vertex {v}: no repeats");
        assert_eq!(set, out_of.remove(&v).unwrap_or_default(), "vertex {v}");
        // counter-clockwise: each next outgoing half-edge is the twin of the previous one's prev
        for w in walked.windows(2) {
            assert_eq!(he.twin(he.prev(w[0])), Some(w[1]));
        }
        assert_eq!(he.vertex_half_edge(v), walked.first().copied());
    }
    assert!(he.heap_bytes() >= 12 * mesh.triangles.len());
}

#[test]
fn half_edges_are_consistent() {
    check_half_edges(&square_board().1);
    for (_, board) in generated_boards() {
        check_half_edges(&generate_mesh(&board).unwrap().mesh);
    }
    // an unused vertex has no outgoing half-edges
    let (_, mut mesh) = square_board();
    mesh.vertices.push([5, 5]);
    let he = mesh.half_edges().unwrap();
    assert_eq!(he.outgoing(9).count(), 0);
    assert_eq!(he.vertex_half_edge(9), None);
}

#[test]
fn half_edges_refuse_non_manifold_meshes() {
    let (_, base) = square_board();
    let with = |edit: fn(&mut Mesh)| {
        let mut m = base.clone();
        edit(&mut m);
        m.half_edges().map(|_| ()).unwrap_err()
    };
    assert!(matches!(
        with(|m| m.triangles.push(m.triangles[0])),
        HalfEdgeError::RepeatedDirectedEdge { .. }
            | HalfEdgeError::EdgeInMoreThanTwoTriangles { .. }
    ));
    // a flipped triangle: its edges run the same way as its neighbours'
    assert!(matches!(
        with(|m| m.triangles[0].swap(1, 2)),
        HalfEdgeError::RepeatedDirectedEdge { .. }
    ));
    // a third triangle on the diagonal 0-4, hanging outside
    assert_eq!(
        with(|m| {
            m.vertices.push([2, -1]);
            m.triangles.push([4, 0, 9]);
            m.triangles.push([0, 9, 4]);
        }),
        HalfEdgeError::EdgeInMoreThanTwoTriangles {
            edge: [0, 4],
            triangles: [0, 1, 8]
        }
    );
    assert_eq!(
        with(|m| m.triangles[2][0] = 42),
        HalfEdgeError::VertexOutOfRange {
            triangle: 2,
            vertex: 42
        }
    );
    assert_eq!(
        with(|m| m.triangles[5] = [3, 3, 4]),
        HalfEdgeError::DegenerateTriangle { triangle: 5 }
    );
    // a bow tie: two triangles sharing only vertex 2
    let bow = Mesh {
        vertices: vec![[0, 0], [1, 0], [1, 1], [2, 1], [2, 2]],
        triangles: vec![[0, 1, 2], [2, 3, 4]],
        regions: vec![0, 0],
        segments: vec![],
    };
    assert_eq!(
        bow.half_edges().unwrap_err(),
        HalfEdgeError::NonManifoldVertex { vertex: 2 }
    );
    // every error has a message
    assert!(HalfEdgeError::NonManifoldVertex { vertex: 2 }
        .to_string()
        .contains("vertex 2"));
}

// ---------------------------------------------------------------------------------------------
// Writers, parsed back
// ---------------------------------------------------------------------------------------------

fn written(write: impl FnOnce(&mut Vec<u8>) -> std::io::Result<()>) -> String {
    let mut out = Vec::new();
    write(&mut out).unwrap();
    String::from_utf8(out).unwrap()
}

/// Lines of integers, skipping blank lines and `#` comments.
fn int_lines(text: &str) -> Vec<Vec<i64>> {
    text.lines()
        .map(|l| l.split('#').next().unwrap().trim())
        .filter(|l| !l.is_empty())
        .map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect())
        .collect()
}

/// Checks a Triangle file: header `[count, rest...]`, then `count` lines numbered from 1 with
/// `columns` numbers each; returns the rows without their numbers.
fn triangle_rows(text: &str, header_rest: &[i64], columns: usize) -> Vec<Vec<i64>> {
    let lines = int_lines(text);
    let count = lines[0][0] as usize;
    assert_eq!(&lines[0][1..], header_rest);
    assert_eq!(lines.len(), count + 1);
    lines[1..]
        .iter()
        .enumerate()
        .map(|(i, row)| {
            assert_eq!(row.len(), columns + 1);
            assert_eq!(row[0], i as i64 + 1, "numbered from 1");
            row[1..].to_vec()
        })
        .collect()
}

fn check_triangle_files(mesh: &Mesh, board: &Board) {
    let u = board.size();
    let node = written(|o| triangle::write_node(mesh, o));
    let rows = triangle_rows(&node, &[2, 0, 1], 3);
    assert_eq!(rows.len(), mesh.vertices.len());
    for (row, p) in rows.iter().zip(&mesh.vertices) {
        assert_eq!(&row[..2], p);
        let on_boundary = p[0] == 0 || p[1] == 0 || p[0] == u || p[1] == u;
        assert_eq!(row[2], i64::from(on_boundary), "{p:?}");
    }

    let ele = written(|o| triangle::write_ele(mesh, o));
    let rows = triangle_rows(&ele, &[3, 1], 4);
    assert_eq!(rows.len(), mesh.triangles.len());
    for ((row, t), r) in rows.iter().zip(&mesh.triangles).zip(&mesh.regions) {
        let one_based: Vec<i64> = t.iter().map(|&v| i64::from(v) + 1).collect();
        assert_eq!(&row[..3], &one_based[..]);
        assert!(row[..3]
            .iter()
            .all(|&v| (1..=mesh.vertices.len() as i64).contains(&v)));
        assert_eq!(row[3], i64::from(*r));
    }

    let edge = written(|o| triangle::write_edge(mesh, o));
    let rows = triangle_rows(&edge, &[1], 3);
    let report = mesh.validate(board);
    assert_eq!(rows.len(), report.edges);
    let mut seen = BTreeSet::new();
    let mut kinds: BTreeMap<(u32, u32), Vec<SegmentKind>> = BTreeMap::new();
    for s in &mesh.segments {
        let [a, b] = s.vertices;
        kinds.entry((a.min(b), a.max(b))).or_default().push(s.kind);
    }
    for row in &rows {
        let (a, b) = (row[0] as u32 - 1, row[1] as u32 - 1);
        assert!(seen.insert((a.min(b), a.max(b))), "each edge once");
        let expected = match kinds.get(&(a.min(b), a.max(b))) {
            None => 0,
            Some(k) => k
                .iter()
                .map(|k| match k {
                    SegmentKind::Boundary => 1,
                    SegmentKind::Component(i) => 1 + i64::from(*i),
                })
                .max()
                .unwrap(),
        };
        assert_eq!(row[2], expected, "edge {a}-{b}");
    }
}

/// A VTK legacy file: header, counts and the region array.
fn check_vtk(mesh: &Mesh) {
    let text = written(|o| vtk::write_vtk(mesh, o));
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "# vtk DataFile Version 3.0");
    assert_eq!(lines[2], "ASCII");
    assert_eq!(lines[3], "DATASET UNSTRUCTURED_GRID");
    let (n, t) = (mesh.vertices.len(), mesh.triangles.len());
    let mut i = 4;
    assert_eq!(lines[i], format!("POINTS {n} double"));
    for p in &mesh.vertices {
        i += 1;
        assert_eq!(lines[i], format!("{} {} 0", p[0], p[1]));
    }
    i += 1;
    assert_eq!(lines[i], format!("CELLS {t} {}", 4 * t));
    for tri in &mesh.triangles {
        i += 1;
        let row = int_lines(lines[i]).remove(0);
        assert_eq!(row[0], 3);
        assert!(row[1..].iter().all(|&v| (0..n as i64).contains(&v)));
        assert_eq!(row[1..], tri.map(i64::from));
    }
    i += 1;
    assert_eq!(lines[i], format!("CELL_TYPES {t}"));
    assert!(lines[i + 1..=i + t].iter().all(|&l| l == "5"));
    i += t + 1;
    assert_eq!(lines[i], format!("CELL_DATA {t}"));
    assert_eq!(lines[i + 1], "SCALARS region int 1");
    assert_eq!(lines[i + 2], "LOOKUP_TABLE default");
    let regions: Vec<u32> = lines[i + 3..].iter().map(|l| l.parse().unwrap()).collect();
    assert_eq!(regions, mesh.regions);
}

/// An MSH 4.1 file: sections in order, counts and tags consistent.
fn check_msh(mesh: &Mesh) {
    let text = written(|o| gmsh::write_msh(mesh, o));
    let mut sections: Vec<(String, Vec<&str>)> = Vec::new();
    let mut lines = text.lines();
    while let Some(l) = lines.next() {
        let name = l.strip_prefix('$').expect("section start").to_string();
        let end = format!("$End{name}");
        let body: Vec<&str> = lines.by_ref().take_while(|&l| l != end).collect();
        sections.push((name, body));
    }
    let names: Vec<&str> = sections.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(
        names,
        [
            "MeshFormat",
            "PhysicalNames",
            "Entities",
            "Nodes",
            "Elements"
        ]
    );
    assert_eq!(sections[0].1, ["4.1 0 8"]);

    // physical names: (dim, tag) -> name
    let body = &sections[1].1;
    let count: usize = body[0].parse().unwrap();
    assert_eq!(body.len(), count + 1);
    let mut physical: BTreeMap<(i64, i64), String> = BTreeMap::new();
    for l in &body[1..] {
        let mut w = l.splitn(3, ' ');
        let dim: i64 = w.next().unwrap().parse().unwrap();
        let tag: i64 = w.next().unwrap().parse().unwrap();
        let name = w.next().unwrap().trim_matches('"').to_string();
        assert!(physical.insert((dim, tag), name).is_none());
    }

    // entities: no points, curves and surfaces each with one physical tag equal to their own
    let ent = int_lines(&sections[2].1.join("\n"));
    let [points, curves, surfaces, volumes] = ent[0][..] else {
        panic!("entity counts")
    };
    assert_eq!((points, volumes), (0, 0));
    assert_eq!(ent.len() as i64, 1 + curves + surfaces);
    let mut entities = BTreeSet::new();
    for (k, row) in ent[1..].iter().enumerate() {
        let dim = if (k as i64) < curves { 1 } else { 2 };
        assert_eq!(
            row.len(),
            10,
            "tag, box, 1 physical tag, no bounding entities"
        );
        assert_eq!((row[7], row[9]), (1, 0));
        assert_eq!(row[8], row[0]);
        assert!(physical.contains_key(&(dim, row[0])));
        entities.insert((dim, row[0]));
    }
    assert_eq!(entities.len(), physical.len());

    // nodes: one block, tags 1..=n, coordinates
    let nodes = int_lines(&sections[3].1.join("\n"));
    let n = mesh.vertices.len() as i64;
    assert_eq!(nodes[0], [1, n, 1, n]);
    assert_eq!(nodes[1][0], 2);
    assert!(entities.contains(&(2, nodes[1][1])));
    assert_eq!(nodes[1][2..], [0, n]);
    for i in 0..n as usize {
        assert_eq!(nodes[2 + i], [i as i64 + 1]);
        let p = mesh.vertices[i];
        assert_eq!(nodes[2 + n as usize + i], [p[0], p[1], 0]);
    }
    assert_eq!(nodes.len(), 2 + 2 * n as usize);

    // elements: blocks of triangles (type 2) then lines (type 1), tags 1..=total, each once
    let el = int_lines(&sections[4].1.join("\n"));
    let total = (mesh.triangles.len() + mesh.segments.len()) as i64;
    let blocks = el[0][0] as usize;
    assert_eq!(el[0][1..], [total, 1, total]);
    let mut at = 1;
    let mut tags = BTreeSet::new();
    let mut per_region: BTreeMap<i64, usize> = BTreeMap::new();
    for _ in 0..blocks {
        let [dim, entity, kind, count] = el[at][..] else {
            panic!("block header")
        };
        assert!(entities.contains(&(dim, entity)));
        assert_eq!(kind, if dim == 2 { 2 } else { 1 });
        for row in &el[at + 1..at + 1 + count as usize] {
            assert_eq!(row.len(), 1 + if dim == 2 { 3 } else { 2 });
            assert!(tags.insert(row[0]));
            assert!(row[1..].iter().all(|&v| (1..=n).contains(&v)));
            if dim == 2 {
                let t = row[0] as usize - 1;
                let tri = mesh.triangles[t].map(|v| i64::from(v) + 1);
                assert_eq!(row[1..], tri, "triangle t has tag t + 1");
                assert_eq!(entity, 1 + i64::from(mesh.regions[t]));
                *per_region.entry(entity).or_default() += 1;
            }
        }
        at += 1 + count as usize;
    }
    assert_eq!(at, el.len());
    assert_eq!(tags, (1..=total).collect());
    for (&(dim, tag), name) in &physical {
        let expected = match (dim, tag) {
            (2, 1) => "board".to_string(),
            (2, t) => format!("component {}", t - 1),
            (1, 1) => "board boundary".to_string(),
            (_, t) => format!("outline {}", t - 1),
        };
        assert_eq!(name, &expected);
        if dim == 2 {
            assert!(per_region[&tag] > 0);
        }
    }
}

#[test]
fn writers_parse_back() {
    let (board, mesh) = square_board();
    check_triangle_files(&mesh, &board);
    check_vtk(&mesh);
    check_msh(&mesh);
    for (_, board) in generated_boards() {
        let mesh = generate_mesh(&board).unwrap().mesh;
        check_triangle_files(&mesh, &board);
        check_vtk(&mesh);
        check_msh(&mesh);
    }
}

#[test]
fn square_board_files_exactly() {
    let (_, mesh) = square_board();
    let edge = written(|o| triangle::write_edge(&mesh, o));
    // the component's bottom edge lies on the board boundary: its outline marker wins
    assert!(edge.starts_with("16 1\n1 1 2 2\n"), "{edge}");
    let node = written(|o| triangle::write_node(&mesh, o));
    assert!(node.starts_with("9 2 0 1\n1 0 0 1\n"), "{node}");
    assert!(
        node.contains("\n5 1 1 0\n"),
        "the centre is interior: {node}"
    );
    let ele = written(|o| triangle::write_ele(&mesh, o));
    assert!(
        ele.starts_with("8 3 1\n1 1 2 5 1\n2 1 5 4 1\n3 2 3 6 0\n"),
        "{ele}"
    );
    let msh = written(|o| gmsh::write_msh(&mesh, o));
    assert!(msh.contains(
        "$PhysicalNames\n4\n2 1 \"board\"\n2 2 \"component 1\"\n1 1 \"board boundary\"\n1 2 \"outline 1\"\n"
    ));
    assert!(msh.contains("$Entities\n0 2 2 0\n"), "{msh}");
}

#[test]
fn writers_to_paths() {
    let dir = std::env::temp_dir().join(format!("orthtree-mesh-io-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (board, mesh) = square_board();
    triangle::write_triangle_files(&mesh, dir.join("square.1")).unwrap();
    for ext in ["node", "ele", "edge"] {
        let text = std::fs::read_to_string(dir.join(format!("square.1.{ext}"))).unwrap();
        let mut expected = Vec::new();
        match ext {
            "node" => triangle::write_node(&mesh, &mut expected),
            "ele" => triangle::write_ele(&mesh, &mut expected),
            _ => triangle::write_edge(&mesh, &mut expected),
        }
        .unwrap();
        assert_eq!(text.as_bytes(), expected);
    }
    gmsh::write_msh_to(&mesh, dir.join("square.msh")).unwrap();
    vtk::write_vtk_to(&mesh, dir.join("square.vtk")).unwrap();
    assert!(std::fs::read_to_string(dir.join("square.msh"))
        .unwrap()
        .ends_with("$EndElements\n"));
    assert!(std::fs::read_to_string(dir.join("square.vtk"))
        .unwrap()
        .contains("CELL_TYPES 8"));
    std::fs::write(dir.join("square.svg"), mesh_svg(&mesh, &board)).unwrap();
    // refused before creating anything
    let mut bad = mesh.clone();
    bad.triangles[0][0] = 77;
    assert!(gmsh::write_msh_to(&bad, dir.join("bad.msh")).is_err());
    assert!(triangle::write_triangle_files(&bad, dir.join("bad")).is_err());
    assert!(!dir.join("bad.msh").exists() && !dir.join("bad.node").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn mesh_svg_draws_every_triangle_and_outline() {
    let (board, mesh) = square_board();
    let svg = mesh_svg(&mesh, &board);
    assert!(svg.starts_with("<svg"));
    assert!(svg.trim_end().ends_with("</svg>"));
    assert_eq!(svg.matches("<polygon").count(), 8);
    // one fill group per region, the board's and the component's colours differ
    let fills: BTreeSet<&str> = svg
        .match_indices("<g fill=\"")
        .map(|(i, _)| svg[i + 9..].split('"').next().unwrap())
        .filter(|f| *f != "none")
        .collect();
    assert_eq!(fills.len(), 2, "{svg}");
    let board = diagonal_board();
    let mesh = generate_mesh(&board).unwrap().mesh;
    let svg = mesh_svg(&mesh, &board);
    assert_eq!(svg.matches("<polygon").count(), mesh.triangles.len());
}
