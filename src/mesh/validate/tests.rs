//! Unit tests of the exact predicates used by the validator.

use super::*;
use crate::mesh::error::Half;

#[test]
fn incircle_signs() {
    let (a, b, c) = ([0, 0], [2, 0], [0, 2]);
    assert!(incircle(a, b, c, [1, 1]) > 0);
    assert_eq!(incircle(a, b, c, [2, 2]), 0); // cocircular
    assert!(incircle(a, b, c, [3, 3]) < 0);
    // extreme coordinates do not overflow
    let u = 1i64 << 30;
    assert!(incircle([0, 0], [u, 0], [0, u], [u, u]) == 0);
    assert!(incircle([0, 0], [u, 0], [0, u], [1, 1]) > 0);
}

#[test]
fn boundary_sides() {
    assert_eq!(boundary_side([0, 0], [1, 0], 2), Some((0, 0, 1)));
    assert_eq!(boundary_side([1, 0], [0, 0], 2), None);
    assert_eq!(boundary_side([2, 2], [1, 2], 2), Some((2, 0, 1)));
    assert_eq!(boundary_side([0, 1], [0, 0], 2), Some((3, 1, 2)));
    assert_eq!(Half(7).to_string(), "3.5");
    assert_eq!(Half(8).to_string(), "4");
    assert_eq!(Half(-1).to_string(), "-0.5");
}

// ---------------------------------------------------------------------------------------------
// The boundary cover and coincident-vertex checks on their own, on meshes of random boards
// broken on purpose.
// ---------------------------------------------------------------------------------------------

use super::checks::{side_cover, Validator};
use super::MeshValidationError as V;
use crate::mesh::{generate_mesh, random_board};

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
fn boundary_cover_and_coincident_vertices() {
    let side = BoardSide::Right;
    let gap = side_cover(side, &[(0, 2, 3), (3, 4, 7)], 4);
    assert_eq!(
        gap,
        Some(V::BoundaryCover {
            side,
            at: 2,
            gap: true,
            triangle: 2
        })
    );
    let overlap = side_cover(side, &[(0, 2, 3), (1, 4, 7)], 4);
    assert_eq!(
        overlap,
        Some(V::BoundaryCover {
            side,
            at: 1,
            gap: false,
            triangle: 2
        })
    );
    let short = side_cover(side, &[(0, 2, 3), (2, 3, 7)], 4);
    assert_eq!(
        short,
        Some(V::BoundaryEnd {
            side,
            end: 3,
            size: 4
        })
    );
    assert_eq!(side_cover(side, &[(0, 2, 3), (2, 4, 7)], 4), None);
    for (board, mesh) in meshes() {
        // a copy of a used vertex, taken by one triangle
        let mut m = mesh.clone();
        let (_, inner) = boundary_and_inner_triangles(&mesh, &board);
        let v = m.triangles[inner][0];
        m.vertices.push(m.vertices[v as usize]);
        m.triangles[inner][0] = m.vertices.len() as u32 - 1;
        let good = vec![true; m.triangles.len()];
        let copy = m.vertices.len() as u32 - 1;
        let e = Validator::new(&m, &board, good).coincident_vertices();
        assert_eq!(
            e,
            Some(V::CoincidentVertices {
                vertices: [v.min(copy), v.max(copy)],
                point: m.vertices[v as usize]
            })
        );
    }
}
