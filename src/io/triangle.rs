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

use super::text_out::TextOut;
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
    // Edges are found again by their smaller endpoint: `slots[start[v]..filled[v]]` holds the
    // ids of the edges seen so far whose smaller endpoint is v (a handful per vertex), in a
    // table sized by counting first, so nothing is hashed and nothing grows.
    let n = mesh.vertices.len();
    let key = |a: u32, b: u32| (a.min(b) as usize, a.max(b));
    let mut start = vec![0usize; n + 1];
    for tri in &mesh.triangles {
        for i in 0..3 {
            start[key(tri[i], tri[(i + 1) % 3]).0 + 1] += 1;
        }
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let mut filled = start.clone();
    let mut slots = vec![0usize; start[n]];
    let mut edges: Vec<([u32; 2], u64)> = Vec::new();
    for tri in &mesh.triangles {
        for i in 0..3 {
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            let (lo, hi) = key(a, b);
            let seen = slots[start[lo]..filled[lo]]
                .iter()
                .any(|&e| key(edges[e].0[0], edges[e].0[1]).1 == hi);
            if !seen {
                slots[filled[lo]] = edges.len();
                filled[lo] += 1;
                edges.push(([a, b], 0));
            }
        }
    }
    for s in &mesh.segments {
        let (lo, hi) = key(s.vertices[0], s.vertices[1]);
        let Some(range) = start.get(lo).zip(filled.get(lo)).map(|(&a, &b)| a..b) else {
            continue;
        };
        let found = slots[range]
            .iter()
            .find(|&&e| key(edges[e].0[0], edges[e].0[1]).1 == hi);
        if let Some(&k) = found {
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
    node_unchecked(mesh, out)
}

/// [`write_node`] on a mesh whose indices are checked.
fn node_unchecked(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    let mut on_boundary = vec![false; mesh.vertices.len()];
    for s in &mesh.segments {
        if s.kind == SegmentKind::Boundary {
            for v in s.vertices {
                on_boundary[v as usize] = true;
            }
        }
    }
    let mut o = TextOut::new(out);
    o.u(mesh.vertices.len() as u64).s(" 2 0 1").nl()?;
    for (i, (p, &b)) in mesh.vertices.iter().zip(&on_boundary).enumerate() {
        o.u(i as u64 + 1)
            .sp()
            .i(p[0])
            .sp()
            .i(p[1])
            .sp()
            .u(u64::from(b));
        o.nl()?;
    }
    o.finish()
}

/// Writes the `.ele` file (see the module doc).
pub fn write_ele(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    checked(mesh)?;
    ele_unchecked(mesh, out)
}

/// [`write_ele`] on a mesh whose indices are checked.
fn ele_unchecked(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    let mut o = TextOut::new(out);
    o.u(mesh.triangles.len() as u64).s(" 3 1").nl()?;
    for (i, (t, &r)) in mesh.triangles.iter().zip(&mesh.regions).enumerate() {
        let [a, b, c] = t.map(|v| u64::from(v) + 1);
        o.u(i as u64 + 1)
            .sp()
            .u(a)
            .sp()
            .u(b)
            .sp()
            .u(c)
            .sp()
            .u(u64::from(r));
        o.nl()?;
    }
    o.finish()
}

/// Writes the `.edge` file (see the module doc and [`edges_with_markers`]).
pub fn write_edge(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    checked(mesh)?;
    edge_unchecked(mesh, out)
}

/// [`write_edge`] on a mesh whose indices are checked.
fn edge_unchecked(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    let edges = edges_with_markers(mesh);
    let mut o = TextOut::new(out);
    o.u(edges.len() as u64).s(" 1").nl()?;
    for (i, &([a, b], m)) in edges.iter().enumerate() {
        let (a, b) = (u64::from(a) + 1, u64::from(b) + 1);
        o.u(i as u64 + 1).sp().u(a).sp().u(b).sp().u(m);
        o.nl()?;
    }
    o.finish()
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
        (".node", |m, o| node_unchecked(m, o)),
        (".ele", |m, o| ele_unchecked(m, o)),
        (".edge", |m, o| edge_unchecked(m, o)),
    ];
    for (suffix, write) in files {
        let mut out = BufWriter::new(std::fs::File::create(with(suffix))?);
        write(mesh, &mut out)?;
        out.flush()?;
    }
    Ok(())
}
