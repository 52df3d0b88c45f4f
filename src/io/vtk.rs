//! Writer of a [`Mesh`] as a legacy VTK ASCII unstructured grid (file version 3.0, read by
//! ParaView, VisIt and meshio), no dependencies: `POINTS` (z = 0), `CELLS` (one triangle per
//! mesh triangle, 0-based vertex indices), `CELL_TYPES` (5, `VTK_TRIANGLE`) and `CELL_DATA` with
//! an `int` scalar array `region` (0 board, `i` component `i`). Segments are not written.
//!
//! The writer first runs [`Mesh::check_indices`] and returns an
//! [`std::io::ErrorKind::InvalidInput`] error, writing nothing, if an index is out of range.

use crate::mesh::Mesh;
use std::io::{self, BufWriter, Write};
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
pub fn write_vtk(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    super::triangle::checked(mesh)?;
    let (n, t) = (mesh.vertices.len(), mesh.triangles.len());
    writeln!(out, "# vtk DataFile Version 3.0")?;
    writeln!(out, "orthtree quadtree mesh")?;
    writeln!(out, "ASCII\nDATASET UNSTRUCTURED_GRID")?;
    writeln!(out, "POINTS {n} double")?;
    for p in &mesh.vertices {
        writeln!(out, "{} {} 0", p[0], p[1])?;
    }
    writeln!(out, "CELLS {t} {}", 4 * t)?;
    for [a, b, c] in &mesh.triangles {
        writeln!(out, "3 {a} {b} {c}")?;
    }
    writeln!(out, "CELL_TYPES {t}")?;
    for _ in 0..t {
        writeln!(out, "5")?;
    }
    writeln!(out, "CELL_DATA {t}")?;
    writeln!(out, "SCALARS region int 1\nLOOKUP_TABLE default")?;
    for r in &mesh.regions {
        writeln!(out, "{r}")?;
    }
    Ok(())
}

/// Writes [`write_vtk`]'s output to a file (checking the indices before creating it).
pub fn write_vtk_to(mesh: &Mesh, path: impl AsRef<Path>) -> io::Result<()> {
    super::triangle::checked(mesh)?;
    let mut out = BufWriter::new(std::fs::File::create(path)?);
    write_vtk(mesh, &mut out)?;
    out.flush()
}
