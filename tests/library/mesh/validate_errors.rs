//! `Mesh::validate`: each check names the broken invariant with its typed variant, on meshes of
//! random boards broken on purpose.

use orthtree::mesh::MeshValidationError as V;
use orthtree::mesh::*;

/// Valid meshes of a few random boards (components of several shapes).
fn meshes() -> Vec<(Board, Mesh)> {
    ((1..=5).map(|seed| random_board(seed, 64, 4)))
        .map(|board| {
            let mesh = generate_mesh(&board).unwrap().mesh;
            assert!(mesh.validate(&board).is_ok());
            (board, mesh)
        })
        .collect()
}

/// The error of check `name` in `mesh`'s report, which must have failed.
fn error_of(mesh: &Mesh, board: &Board, name: &str) -> V {
    let report = mesh.validate(board);
    let (_, check) = (report.checks().into_iter())
        .find(|(n, _)| *n == name)
        .unwrap();
    check
        .error()
        .unwrap_or_else(|| panic!("{name} passed: {report}"))
        .clone()
}

/// A triangle with a corner on the board's boundary, and one away from it.
fn boundary_and_inner_triangles(mesh: &Mesh, board: &Board) -> (usize, usize) {
    let u = board.size();
    let on_boundary = |v: u32| mesh.vertices[v as usize].iter().any(|&c| c == 0 || c == u);
    let outer =
        (0..mesh.triangles.len()).find(|&t| mesh.triangles[t].iter().any(|&v| on_boundary(v)));
    let inner =
        (0..mesh.triangles.len()).find(|&t| mesh.triangles[t].iter().all(|&v| !on_boundary(v)));
    (outer.unwrap(), inner.unwrap())
}

#[test]
fn indices_name_the_offending_item() {
    for (board, mesh) in meshes() {
        let (nv, last) = (mesh.vertices.len(), mesh.triangles.len() - 1);
        let mut m = mesh.clone();
        m.triangles[last][1] = nv as u32;
        let vertices = m.triangles[last];
        let expected = V::TriangleVertexOutOfRange {
            triangle: last,
            vertices,
            vertex_count: nv,
        };
        assert_eq!(error_of(&m, &board, "indices"), expected);
        assert_eq!(m.check_indices(), Err(expected));
        let mut m = mesh.clone();
        m.regions.pop();
        let expected = V::RegionCount {
            regions: last,
            triangles: last + 1,
        };
        assert_eq!(error_of(&m, &board, "indices"), expected);
        let mut m = mesh.clone();
        m.segments.push(Segment {
            vertices: [0, u32::MAX],
            kind: SegmentKind::Boundary,
        });
        let segment = m.segments.len() - 1;
        let expected = V::SegmentVertexOutOfRange {
            segment,
            vertices: [0, u32::MAX],
            vertex_count: nv,
        };
        assert_eq!(error_of(&m, &board, "indices"), expected);
        assert_eq!(error_of(&m, &board, "segments"), expected);
        let mut m = mesh.clone();
        let u = board.size();
        m.vertices[nv / 2] = [u + 1, -3];
        let expected = V::VertexOutsideBoard {
            vertex: nv / 2,
            point: [u + 1, -3],
            size: u,
        };
        assert_eq!(error_of(&m, &board, "indices"), expected);
    }
}

#[test]
fn orientation_and_conforming_name_triangles_and_edges() {
    for (board, mesh) in meshes() {
        let (outer, inner) = boundary_and_inner_triangles(&mesh, &board);
        // a flipped inner triangle: clockwise, and its edges run as its neighbours' do
        let mut m = mesh.clone();
        m.triangles[inner].swap(0, 1);
        let e = error_of(&m, &board, "orientation");
        assert!(
            matches!(e, V::NotCounterClockwise { triangle, doubled_area, .. }
                if triangle == inner && doubled_area < 0),
            "{e}"
        );
        let e = error_of(&m, &board, "conforming");
        assert!(
            matches!(e, V::RepeatedDirectedEdge { triangles, .. } if triangles.contains(&(inner as u32))),
            "{e}"
        );
        // a degenerate triangle has zero area
        let mut m = mesh.clone();
        m.triangles[outer][2] = m.triangles[outer][1];
        let e = error_of(&m, &board, "orientation");
        assert!(
            matches!(e, V::NotCounterClockwise { triangle, doubled_area: 0, .. } if triangle == outer),
            "{e}"
        );
        // an inner triangle removed: its edges lose their twins away from the boundary
        let mut m = mesh.clone();
        let [a, b, c] = m.triangles.remove(inner);
        m.regions.remove(inner);
        let e = error_of(&m, &board, "conforming");
        let V::UnpairedEdge { from, to, .. } = e else {
            panic!("{e}")
        };
        assert!([[b, a], [c, b], [a, c]].contains(&[from, to]), "{e}");
        // a third triangle on an inner edge
        let mut m = mesh.clone();
        let [a, b, _] = mesh.triangles[inner];
        let far = mesh.triangles[outer][0];
        m.triangles.push([b, a, far]);
        m.regions.push(0);
        let e = error_of(&m, &board, "conforming");
        assert!(
            matches!(&e, V::EdgeInMoreThanTwoTriangles { triangles, .. } if triangles.len() >= 3)
                || matches!(e, V::RepeatedDirectedEdge { .. }),
            "{e}"
        );
        // the mesh of a smaller board: its boundary ends short of the larger board's sides
        let larger = Board::new(2 * board.size(), board.components().to_vec()).unwrap();
        let e = error_of(&mesh, &larger, "conforming");
        assert!(
            matches!(e, V::UnpairedEdge { .. } | V::BoundaryEnd { .. }),
            "{e}"
        );
        assert!(
            matches!(error_of(&mesh, &larger, "area"), V::Area { size, .. } if size == larger.size())
        );
    }
}

#[test]
fn regions_euler_and_segments_name_what_is_wrong() {
    for (board, mesh) in meshes() {
        let k = board.components().len() as u32;
        let (outer, inner) = boundary_and_inner_triangles(&mesh, &board);
        let mut m = mesh.clone();
        m.regions[outer] = k + 1;
        let e = error_of(&m, &board, "regions");
        assert!(
            matches!(e, V::RegionOutOfRange { triangle, region, components, .. }
            if triangle == outer && region == k + 1 && components == k),
            "{e}"
        );
        // a triangle in another region than its neighbours (or than its outline requires)
        let mut m = mesh.clone();
        m.regions[inner] = if mesh.regions[inner] == 0 { k } else { 0 };
        if k > 0 {
            let e = error_of(&m, &board, "regions");
            let wrong_region = matches!(e, V::WrongRegion { triangle, rule, .. }
                if triangle == inner || rule == RegionRule::AcrossFrom(inner as u32));
            assert!(wrong_region || matches!(e, V::RegionArea { .. }), "{e}");
        }
        // an inner triangle removed leaves a hole: V - E + F = 0
        let mut m = mesh.clone();
        m.triangles.remove(inner);
        m.regions.remove(inner);
        let e = error_of(&m, &board, "euler");
        assert!(
            matches!(e, V::Euler { vertices, edges, triangles }
            if vertices + triangles == edges),
            "{e}"
        );
        // segments: one missing, one repeated, one of the wrong kind
        let mut m = mesh.clone();
        let s = m.segments.remove(0);
        let e = error_of(&m, &board, "segments");
        let missing = match s.kind {
            SegmentKind::Boundary => matches!(e, V::MissingBoundarySegment { .. }),
            SegmentKind::Component(_) => matches!(e, V::MissingOutlineSegment { .. }),
        };
        assert!(missing, "{e}");
        let mut m = mesh.clone();
        m.segments.push(s);
        let e = error_of(&m, &board, "segments");
        assert!(
            matches!(e, V::RepeatedSegment { segments: [0, j], .. } if j == mesh.segments.len()),
            "{e}"
        );
        let mut m = mesh.clone();
        let inner_edge = [mesh.triangles[inner][0], mesh.triangles[inner][1]];
        m.segments.push(Segment {
            vertices: inner_edge,
            kind: SegmentKind::Boundary,
        });
        let e = error_of(&m, &board, "segments");
        assert_eq!(
            e,
            V::SegmentWrongKind {
                segment: mesh.segments.len(),
                vertices: inner_edge,
                kind: SegmentKind::Boundary
            }
        );
        let far = [mesh.triangles[inner][0], mesh.triangles[outer][0]];
        let mut m = mesh.clone();
        m.segments.push(Segment {
            vertices: far,
            kind: SegmentKind::Boundary,
        });
        let e = error_of(&m, &board, "segments");
        assert_eq!(
            e,
            V::SegmentNotEdge {
                segment: mesh.segments.len(),
                vertices: far,
                kind: SegmentKind::Boundary
            }
        );
    }
}

#[test]
fn respects_input_names_the_component() {
    // the mesh of an empty board against a board with a component off its vertices
    let board = Board::new(16, vec![]).unwrap();
    let mesh = generate_mesh(&board).unwrap().mesh;
    for (lo, hi) in [(1, 3), (5, 9), (3, 15)] {
        let square = orthtree::mesh::Component::new(vec![[lo, lo], [hi, lo], [hi, hi], [lo, hi]]);
        let other = Board::new(16, vec![square]).unwrap();
        let e = error_of(&mesh, &other, "respects_input");
        assert!(
            matches!(
                e,
                V::OutlineVertexMissing { component: 1, .. }
                    | V::OutlineEdgeBroken { component: 1, .. }
            ),
            "{e}"
        );
        assert!(e.to_string().contains("component 1"), "{e}");
    }
}
