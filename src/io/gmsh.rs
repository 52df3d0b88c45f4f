//! Writer of a [`Mesh`] as a Gmsh MSH 4.1 ASCII file
//! (<https://gmsh.info/doc/texinfo/gmsh.html#MSH-file-format>), no dependencies.
//!
//! Layout:
//!
//! - `$PhysicalNames`: one 2D group per region with triangles, `"board"` (tag 1) and
//!   `"component i"` (tag `1 + i`); one 1D group per segment kind present, `"board boundary"`
//!   (tag 1) and `"outline i"` (tag `1 + i`). Gmsh numbers physical groups per dimension, so the
//!   tags of both dimensions match the markers of [`crate::io::triangle`].
//! - `$Entities`: no points; one curve per 1D group and one surface per 2D group, with the same
//!   tag as its physical group and its bounding box; no bounding entities.
//! - `$Nodes`: all vertices in one block on the first surface (Gmsh finds nodes by tag, whatever
//!   entity holds them); node tag = vertex index + 1; z = 0. Left out when there are no
//!   vertices, as Gmsh does; likewise `$Elements` when there are no elements.
//! - `$Elements`: one block of 3-node triangles (type 2) per surface, triangle `t` having element
//!   tag `t + 1` whatever its block; then one block of 2-node lines (type 1) per curve, one
//!   element per segment as the mesh stores it, tagged on from `T + 1`. An outline along the
//!   board boundary has a line element in both curves.
//!
//! The writer first runs [`Mesh::check_indices`] and returns an
//! [`std::io::ErrorKind::InvalidInput`] error, writing nothing, if an index is out of range.
//! Checked by loading written files with the gmsh 4.15 Python API and with meshio 5.3.

use super::text_out::TextOut;
use crate::mesh::{Mesh, SegmentKind};
use std::collections::BTreeMap;
use std::io::{self, BufWriter, Write};
use std::path::Path;

/// The elements of one entity: its tag, name and element indices (triangles or segments).
struct Group {
    tag: u64,
    name: String,
    members: Vec<usize>,
}

/// The bounding box of the given vertices, `[min x, min y, max x, max y]` (zeros if none).
fn bounding_box(mesh: &Mesh, vertices: impl Iterator<Item = u32>) -> [i64; 4] {
    let mut bb: Option<[i64; 4]> = None;
    for v in vertices {
        let [x, y] = mesh.vertices[v as usize];
        bb = Some(match bb {
            None => [x, y, x, y],
            Some([a, b, c, d]) => [a.min(x), b.min(y), c.max(x), d.max(y)],
        });
    }
    bb.unwrap_or([0; 4])
}

/// Writes the mesh as MSH 4.1 ASCII (see the module doc).
///
/// ```
/// use orthtree::io::gmsh::write_msh;
/// use orthtree::mesh::{Mesh, Segment, SegmentKind};
/// let mesh = Mesh {
///     vertices: vec![[0, 0], [1, 0], [1, 1], [0, 1]],
///     triangles: vec![[0, 1, 2], [0, 2, 3]],
///     regions: vec![0, 1],
///     segments: vec![Segment { vertices: [0, 2], kind: SegmentKind::Component(1) }],
/// };
/// let mut out = Vec::new();
/// write_msh(&mesh, &mut out).unwrap();
/// let text = String::from_utf8(out).unwrap();
/// assert!(text.starts_with("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"));
/// assert!(text.contains("2 1 \"board\"\n2 2 \"component 1\"\n1 2 \"outline 1\"\n"));
/// assert!(text.contains("$Elements\n3 3 1 3\n2 1 2 1\n1 1 2 3\n"));
/// ```
pub fn write_msh(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    super::triangle::checked(mesh)?;
    write_unchecked(mesh, out)
}

/// [`write_msh`] on a mesh whose indices are checked.
fn write_unchecked(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    let mut surfaces: BTreeMap<u64, Group> = BTreeMap::new();
    for (t, &r) in mesh.regions.iter().enumerate() {
        let tag = 1 + u64::from(r);
        (surfaces.entry(tag))
            .or_insert_with(|| Group {
                tag,
                name: match r {
                    0 => "board".into(),
                    i => format!("component {i}"),
                },
                members: Vec::new(),
            })
            .members
            .push(t);
    }
    let mut curves: BTreeMap<u64, Group> = BTreeMap::new();
    for (k, s) in mesh.segments.iter().enumerate() {
        let (tag, name) = match s.kind {
            SegmentKind::Boundary => (1, "board boundary".to_string()),
            SegmentKind::Component(i) => (1 + u64::from(i), format!("outline {i}")),
        };
        (curves.entry(tag))
            .or_insert_with(|| Group {
                tag,
                name,
                members: Vec::new(),
            })
            .members
            .push(k);
    }
    // The entity holding the nodes: the first surface, or a bare surface 1 if there is none.
    let node_entity = surfaces.keys().next().copied().unwrap_or(1);
    let bare_surface = surfaces.is_empty() && !mesh.vertices.is_empty();

    writeln!(out, "$MeshFormat\n4.1 0 8\n$EndMeshFormat")?;

    writeln!(out, "$PhysicalNames\n{}", surfaces.len() + curves.len())?;
    for (dim, groups) in [(2, &surfaces), (1, &curves)] {
        for g in groups.values() {
            writeln!(out, "{dim} {} \"{}\"", g.tag, g.name)?;
        }
    }
    writeln!(out, "$EndPhysicalNames")?;

    writeln!(out, "$Entities")?;
    let surface_count = surfaces.len() + usize::from(bare_surface);
    writeln!(out, "0 {} {surface_count} 0", curves.len())?;
    for g in curves.values() {
        let vertices = g.members.iter().flat_map(|&k| mesh.segments[k].vertices);
        let [x0, y0, x1, y1] = bounding_box(mesh, vertices);
        writeln!(out, "{} {x0} {y0} 0 {x1} {y1} 0 1 {} 0", g.tag, g.tag)?;
    }
    for g in surfaces.values() {
        let vertices = g.members.iter().flat_map(|&t| mesh.triangles[t]);
        let [x0, y0, x1, y1] = bounding_box(mesh, vertices);
        writeln!(out, "{} {x0} {y0} 0 {x1} {y1} 0 1 {} 0", g.tag, g.tag)?;
    }
    if bare_surface {
        let [x0, y0, x1, y1] = bounding_box(mesh, 0..mesh.vertices.len() as u32);
        writeln!(out, "1 {x0} {y0} 0 {x1} {y1} 0 0 0")?;
    }
    writeln!(out, "$EndEntities")?;

    // Gmsh itself leaves out the sections it has nothing for (and warns about the tag range
    // of an empty $Nodes section).
    let n = mesh.vertices.len() as u64;
    let mut o = TextOut::new(out);
    if n > 0 {
        o.s("$Nodes\n1 ").u(n).s(" 1 ").u(n).nl()?;
        o.s("2 ").u(node_entity).s(" 0 ").u(n).nl()?;
        for i in 1..=n {
            o.u(i).nl()?;
        }
        for p in &mesh.vertices {
            o.i(p[0]).sp().i(p[1]).s(" 0").nl()?;
        }
        o.s("$EndNodes").nl()?;
    }

    let elements = (mesh.triangles.len() + mesh.segments.len()) as u64;
    if elements == 0 {
        return o.finish();
    }
    o.s("$Elements").nl()?;
    let blocks = (surfaces.len() + curves.len()) as u64;
    o.u(blocks).sp().u(elements).s(" 1 ").u(elements).nl()?;
    for g in surfaces.values() {
        o.s("2 ").u(g.tag).s(" 2 ").u(g.members.len() as u64).nl()?;
        for &t in &g.members {
            let [a, b, c] = mesh.triangles[t].map(|v| u64::from(v) + 1);
            o.u(t as u64 + 1).sp().u(a).sp().u(b).sp().u(c).nl()?;
        }
    }
    let mut tag = mesh.triangles.len() as u64;
    for g in curves.values() {
        o.s("1 ").u(g.tag).s(" 1 ").u(g.members.len() as u64).nl()?;
        for &k in &g.members {
            tag += 1;
            let [a, b] = mesh.segments[k].vertices.map(|v| u64::from(v) + 1);
            o.u(tag).sp().u(a).sp().u(b).nl()?;
        }
    }
    o.s("$EndElements").nl()?;
    o.finish()
}

/// Writes [`write_msh`]'s output to a file (checking the indices before creating it).
pub fn write_msh_to(mesh: &Mesh, path: impl AsRef<Path>) -> io::Result<()> {
    super::triangle::checked(mesh)?;
    let mut out = BufWriter::new(std::fs::File::create(path)?);
    write_unchecked(mesh, &mut out)?;
    out.flush()
}
