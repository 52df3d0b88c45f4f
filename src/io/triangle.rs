//! Writers of a [`Mesh`] in the formats of Shewchuk's Triangle: `.node`, `.ele` and `.edge`
//! (<https://www.cs.cmu.edu/~quake/triangle.html>), numbered from 1, no dependencies.
//!
//! - `.node`: `<#vertices> 2 0 1`, then `<i> <x> <y> <marker>`; the marker is 1 for a vertex of
//!   a `Boundary` segment (for a valid mesh: every vertex on the board boundary), else 0.
//! - `.ele`: `<#triangles> 3 1`, then `<i> <v1> <v2> <v3> <region>`: the region is Triangle's
//!   regional attribute (0 board, `i` component `i`); vertices counter-clockwise.
//! - `.edge`: `<#edges> 1`, then `<i> <v1> <v2> <marker>` for every mesh edge (each once, in order
//!   of first appearance in the triangles, oriented as there). Markers: 0 interior, 1 on the board
//!   boundary, `1 + i` on the outline of component `i`; an outline edge that also lies on the
//!   board boundary gets `1 + i` (as in Triangle, a segment's own marker beats the default 1).
//!   Markers come from the mesh's segments; a segment that is not a mesh edge is not written.
//!
//! Every writer first runs [`Mesh::check_indices`] and returns an
//! [`std::io::ErrorKind::InvalidInput`] error, writing nothing, if an index is out of range.

use crate::hash::FastMap;
use crate::mesh::{Mesh, SegmentKind};
use std::io::{self, BufWriter, Write};
use std::path::Path;

/// The mesh's indices checked, as an I/O error.
pub(super) fn checked(mesh: &Mesh) -> io::Result<()> {
    mesh.check_indices()
        .map_err(|e| io::Error::new(io::ErrorKind::InvalidInput, e))
}

/// The `.edge` marker of a segment kind: 1 for the board boundary, `1 + i` for component `i`.
fn marker(kind: SegmentKind) -> u64 {
    match kind {
        SegmentKind::Boundary => 1,
        SegmentKind::Component(i) => 1 + u64::from(i),
    }
}

/// Every mesh edge once, in order of first appearance in the triangles (oriented as there), with
/// its `.edge` marker (see the module doc). Indices are 0-based; the mesh's indices are assumed
/// in range (checked by the writers).
///
/// ```
/// use orthtree::io::triangle::edges_with_markers;
/// use orthtree::mesh::{Mesh, Segment, SegmentKind};
/// let mesh = Mesh {
///     vertices: vec![[0, 0], [1, 0], [1, 1], [0, 1]],
///     triangles: vec![[0, 1, 2], [0, 2, 3]],
///     regions: vec![0, 0],
///     segments: vec![Segment { vertices: [1, 0], kind: SegmentKind::Boundary }],
/// };
/// let edges = edges_with_markers(&mesh);
/// assert_eq!(edges, [([0, 1], 1), ([1, 2], 0), ([2, 0], 0), ([2, 3], 0), ([3, 0], 0)]);
/// ```
pub fn edges_with_markers(mesh: &Mesh) -> Vec<([u32; 2], u64)> {
    let mut index: FastMap<(u32, u32), usize> = FastMap::default();
    let mut edges = Vec::new();
    for tri in &mesh.triangles {
        for i in 0..3 {
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            index.entry((a.min(b), a.max(b))).or_insert_with(|| {
                edges.push(([a, b], 0));
                edges.len() - 1
            });
        }
    }
    for s in &mesh.segments {
        let [a, b] = s.vertices;
        if let Some(&k) = index.get(&(a.min(b), a.max(b))) {
            let m = &mut edges[k].1;
            // An outline marker beats the board-boundary marker.
            if *m <= 1 {
                *m = marker(s.kind);
            }
        }
    }
    edges
}

/// Writes the `.node` file (see the module doc).
pub fn write_node(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    checked(mesh)?;
    let mut on_boundary = vec![false; mesh.vertices.len()];
    for s in &mesh.segments {
        if s.kind == SegmentKind::Boundary {
            for v in s.vertices {
                on_boundary[v as usize] = true;
            }
        }
    }
    writeln!(out, "{} 2 0 1", mesh.vertices.len())?;
    for (i, (p, &b)) in mesh.vertices.iter().zip(&on_boundary).enumerate() {
        writeln!(out, "{} {} {} {}", i + 1, p[0], p[1], u8::from(b))?;
    }
    Ok(())
}

/// Writes the `.ele` file (see the module doc).
pub fn write_ele(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    checked(mesh)?;
    writeln!(out, "{} 3 1", mesh.triangles.len())?;
    for (i, (t, r)) in mesh.triangles.iter().zip(&mesh.regions).enumerate() {
        let [a, b, c] = t.map(|v| u64::from(v) + 1);
        writeln!(out, "{} {a} {b} {c} {r}", i + 1)?;
    }
    Ok(())
}

/// Writes the `.edge` file (see the module doc and [`edges_with_markers`]).
pub fn write_edge(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    checked(mesh)?;
    let edges = edges_with_markers(mesh);
    writeln!(out, "{} 1", edges.len())?;
    for (i, ([a, b], m)) in edges.iter().enumerate() {
        writeln!(
            out,
            "{} {} {} {m}",
            i + 1,
            u64::from(*a) + 1,
            u64::from(*b) + 1
        )?;
    }
    Ok(())
}

/// Writes `<stem>.node`, `<stem>.ele` and `<stem>.edge` (the suffix is appended, so a stem such
/// as `board.1` keeps its dot). Checks the indices before creating any file.
pub fn write_triangle_files(mesh: &Mesh, stem: impl AsRef<Path>) -> io::Result<()> {
    checked(mesh)?;
    let with = |suffix: &str| {
        let mut s = stem.as_ref().as_os_str().to_owned();
        s.push(suffix);
        std::path::PathBuf::from(s)
    };
    type Writer = fn(&Mesh, &mut BufWriter<std::fs::File>) -> io::Result<()>;
    let files: [(&str, Writer); 3] = [
        (".node", |m, o| write_node(m, o)),
        (".ele", |m, o| write_ele(m, o)),
        (".edge", |m, o| write_edge(m, o)),
    ];
    for (suffix, write) in files {
        let mut out = BufWriter::new(std::fs::File::create(with(suffix))?);
        write(mesh, &mut out)?;
        out.flush()?;
    }
    Ok(())
}
