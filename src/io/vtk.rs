//! Writer of a [`Mesh`] as a legacy VTK ASCII unstructured grid (file version 3.0, read by
//! ParaView, VisIt and meshio), no dependencies: `POINTS` (z = 0), `CELLS` (one triangle per
//! mesh triangle, 0-based vertex indices), `CELL_TYPES` (5, `VTK_TRIANGLE`) and `CELL_DATA` with
//! an `int` scalar array `region` (0 board, `i` component `i`). Segments are not written.
//!
//! The writer first runs [`Mesh::check_indices`] and returns an
//! [`std::io::ErrorKind::InvalidInput`] error, writing nothing, if an index is out of range.

use super::text_out::TextOut;
use crate::mesh::Mesh;
use std::io::{self, Write};
use std::path::Path;

/// Writes the mesh as legacy VTK (see the module doc).
///
/// ```
/// use orthtree::io::vtk::write_vtk;
/// use orthtree::mesh::Mesh;
/// let mesh = Mesh {
///     vertices: vec![[0, 0], [1, 0], [1, 1]],
///     triangles: vec![[0, 1, 2]],
///     regions: vec![0],
///     segments: vec![],
/// };
/// let mut out = Vec::new();
/// write_vtk(&mesh, &mut out).unwrap();
/// let text = String::from_utf8(out).unwrap();
/// assert!(text.contains("POINTS 3 double\n0 0 0\n1 0 0\n1 1 0\n"));
/// assert!(text.contains("CELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\n"));
/// assert!(text.ends_with("SCALARS region int 1\nLOOKUP_TABLE default\n0\n"));
/// ```
///
/// # Errors
/// [`io::ErrorKind::InvalidData`] for a triangle or segment naming a vertex the mesh does not
/// have (checked before anything is written), else the writer's I/O error.
pub fn write_vtk(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    super::triangle::checked(mesh)?;
    write_unchecked(mesh, out)
}

/// [`write_vtk`] on a mesh whose indices are checked.
fn write_unchecked(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    let (n, t) = (mesh.vertices.len() as u64, mesh.triangles.len() as u64);
    let mut o = TextOut::new(out);
    o.s("# vtk DataFile Version 3.0\northtree quadtree mesh\nASCII\nDATASET UNSTRUCTURED_GRID");
    o.nl()?;
    o.s("POINTS ").u(n).s(" double").nl()?;
    for p in &mesh.vertices {
        o.i(p[0]).sp().i(p[1]).s(" 0").nl()?;
    }
    o.s("CELLS ").u(t).sp().u(4 * t).nl()?;
    for &[a, b, c] in &mesh.triangles {
        o.s("3").spaced(&[a, b, c].map(u64::from)).nl()?;
    }
    o.s("CELL_TYPES ").u(t).nl()?;
    for _ in 0..t {
        o.s("5").nl()?;
    }
    o.s("CELL_DATA ").u(t).nl()?;
    o.s("SCALARS region int 1\nLOOKUP_TABLE default").nl()?;
    for &r in &mesh.regions {
        o.u(r.into()).nl()?;
    }
    o.finish()
}

/// Writes [`write_vtk`]'s output to a file (checking the indices before creating it).
///
/// # Errors
/// As [`write_vtk`], and the file's I/O error.
pub fn write_vtk_to(mesh: &Mesh, path: impl AsRef<Path>) -> io::Result<()> {
    super::triangle::checked(mesh)?;
    super::write_file(path, |out| write_unchecked(mesh, out))
}
