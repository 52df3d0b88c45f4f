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

use super::text_out::{Counter, TextOut};
use crate::hash::FastMap;
use crate::mesh::{Mesh, SegmentKind};
use std::io::{self, Write};
use std::path::Path;

/// The elements of one entity: its tag, name, element indices (triangles or segments) and the
/// bounding box of their vertices, `[min x, min y, max x, max y]`.
struct Group {
    tag: u64,
    name: String,
    members: Vec<usize>,
    bbox: [i64; 4],
}

/// The entities of a mesh: surfaces (one per region with triangles) and curves (one per
/// segment kind present), each in order of tag.
struct Entities {
    surfaces: Vec<Group>,
    curves: Vec<Group>,
}

/// Adds element `member` with the given vertices to the group of `tag`, made by `name` if it
/// is new; `last` caches the position of the group of the previous element, as neighbouring
/// elements mostly share one.
fn add_member(
    groups: &mut Vec<Group>,
    index: &mut FastMap<u64, usize>,
    last: &mut Option<(u64, usize)>,
    (tag, member): (u64, usize),
    points: &[[i64; 2]],
    name: impl FnOnce() -> String,
) {
    let at = match *last {
        Some((t, at)) if t == tag => at,
        _ => *index.entry(tag).or_insert_with(|| {
            let [x, y] = points[0];
            groups.push(Group {
                tag,
                name: name(),
                members: Vec::new(),
                bbox: [x, y, x, y],
            });
            groups.len() - 1
        }),
    };
    *last = Some((tag, at));
    let g = &mut groups[at];
    g.members.push(member);
    g.bbox = points.iter().fold(g.bbox, |b, &p| grow(b, p));
}

/// The bounding box `b`, `[min x, min y, max x, max y]`, grown to hold the point `[x, y]`.
fn grow(b: [i64; 4], [x, y]: [i64; 2]) -> [i64; 4] {
    [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)]
}

/// The groups of a mesh whose indices are checked, in one pass over its triangles and one over
/// its segments.
fn entities(mesh: &Mesh) -> Entities {
    let point = |v: u32| mesh.vertices[v as usize];
    let (mut surfaces, mut index, mut last) = (Vec::new(), FastMap::default(), None);
    for (t, (tri, &r)) in mesh.triangles.iter().zip(&mesh.regions).enumerate() {
        let points = tri.map(point);
        let name = || match r {
            0 => "board".to_string(),
            i => format!("component {i}"),
        };
        let key = (1 + u64::from(r), t);
        add_member(&mut surfaces, &mut index, &mut last, key, &points, name);
    }
    let (mut curves, mut index, mut last) = (Vec::new(), FastMap::default(), None);
    for (k, s) in mesh.segments.iter().enumerate() {
        let (tag, name) = match s.kind {
            SegmentKind::Boundary => (1, "board boundary".to_string()),
            SegmentKind::Component(i) => (1 + u64::from(i), format!("outline {i}")),
        };
        let (key, points) = ((tag, k), s.vertices.map(point));
        add_member(&mut curves, &mut index, &mut last, key, &points, || name);
    }
    surfaces.sort_unstable_by_key(|g| g.tag);
    curves.sort_unstable_by_key(|g| g.tag);
    Entities { surfaces, curves }
}

/// The bounding box of all vertices (zeros if none).
fn all_vertices_box(mesh: &Mesh) -> [i64; 4] {
    let Some(&[x, y]) = mesh.vertices.first() else {
        return [0; 4];
    };
    mesh.vertices.iter().fold([x, y, x, y], |b, &p| grow(b, p))
}

/// Writes the mesh as MSH 4.1 ASCII (see the module doc).
///
/// # Errors
///
/// [`std::io::ErrorKind::InvalidInput`] if an index of the mesh is out of range (nothing is
/// written); else those of `out`.
///
/// # Examples
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
    let entities = entities(mesh);
    let mut o = TextOut::new(out);
    o.s("$MeshFormat\n4.1 0 8\n$EndMeshFormat").nl()?;
    write_physical_names(&mut o, &entities)?;
    write_entities(&mut o, mesh, &entities)?;
    // Gmsh itself leaves out the sections it has nothing for (and warns about the tag range
    // of an empty $Nodes section).
    if !mesh.vertices.is_empty() {
        // The entity holding the nodes: the first surface, or a bare surface 1 if there is none.
        let node_entity = entities.surfaces.first().map_or(1, |g| g.tag);
        write_nodes(&mut o, mesh, node_entity)?;
    }
    if !(mesh.triangles.is_empty() && mesh.segments.is_empty()) {
        write_elements(&mut o, mesh, &entities)?;
    }
    o.finish()
}

/// The `$PhysicalNames` section: the surfaces' groups (dimension 2), then the curves' (1).
fn write_physical_names<W: Write>(o: &mut TextOut<'_, W>, e: &Entities) -> io::Result<()> {
    o.s("$PhysicalNames").nl()?;
    o.u((e.surfaces.len() + e.curves.len()) as u64).nl()?;
    for (dim, groups) in [("2 ", &e.surfaces), ("1 ", &e.curves)] {
        for g in groups {
            o.s(dim).u(g.tag).s(" \"").s(&g.name).s("\"").nl()?;
        }
    }
    o.s("$EndPhysicalNames").nl()
}

/// The `$Entities` section: no points, the curves, the surfaces (a bare surface 1 holding the
/// nodes when vertices but no triangles), each with its bounding box and physical tag.
fn write_entities<W: Write>(o: &mut TextOut<'_, W>, mesh: &Mesh, e: &Entities) -> io::Result<()> {
    let bare_surface = e.surfaces.is_empty() && !mesh.vertices.is_empty();
    let surface_count = e.surfaces.len() + usize::from(bare_surface);
    o.s("$Entities").nl()?;
    o.s("0 ")
        .u(e.curves.len() as u64)
        .sp()
        .u(surface_count as u64)
        .s(" 0")
        .nl()?;
    for g in e.curves.iter().chain(&e.surfaces) {
        put_box(o.u(g.tag).sp(), g.bbox)
            .s(" 1 ")
            .u(g.tag)
            .s(" 0")
            .nl()?;
    }
    if bare_surface {
        put_box(o.s("1 "), all_vertices_box(mesh)).s(" 0 0").nl()?;
    }
    o.s("$EndEntities").nl()
}

/// Writes a bounding box `[x0, y0, x1, y1]` as Gmsh's `minX minY minZ maxX maxY maxZ`, z = 0.
fn put_box<'o, 'a, W: Write>(
    o: &'o mut TextOut<'a, W>,
    [x0, y0, x1, y1]: [i64; 4],
) -> &'o mut TextOut<'a, W> {
    o.i(x0).sp().i(y0).s(" 0 ").i(x1).sp().i(y1).s(" 0")
}

/// The `$Nodes` section: one block of all vertices on `entity`, tags from 1, z = 0.
fn write_nodes<W: Write>(o: &mut TextOut<'_, W>, mesh: &Mesh, entity: u64) -> io::Result<()> {
    let n = mesh.vertices.len() as u64;
    o.s("$Nodes\n1 ").u(n).s(" 1 ").u(n).nl()?;
    o.s("2 ").u(entity).s(" 0 ").u(n).nl()?;
    let mut tag = Counter::new(1);
    for _ in 0..n {
        o.count(&mut tag).nl()?;
    }
    for p in &mesh.vertices {
        o.i(p[0]).sp().i(p[1]).s(" 0").nl()?;
    }
    o.s("$EndNodes").nl()
}

/// The `$Elements` section: a block of triangles per surface (triangle `t` tagged `t + 1`),
/// then a block of lines per curve (tagged on from `T + 1`).
fn write_elements<W: Write>(o: &mut TextOut<'_, W>, mesh: &Mesh, e: &Entities) -> io::Result<()> {
    let elements = (mesh.triangles.len() + mesh.segments.len()) as u64;
    let blocks = (e.surfaces.len() + e.curves.len()) as u64;
    o.s("$Elements").nl()?;
    o.u(blocks).sp().u(elements).s(" 1 ").u(elements).nl()?;
    for g in &e.surfaces {
        o.s("2 ").u(g.tag).s(" 2 ").u(g.members.len() as u64).nl()?;
        for &t in &g.members {
            let [a, b, c] = mesh.triangles[t].map(|v| u64::from(v) + 1);
            o.u(t as u64 + 1).sp().u(a).sp().u(b).sp().u(c).nl()?;
        }
    }
    let mut tag = Counter::new(mesh.triangles.len() as u64 + 1);
    for g in &e.curves {
        o.s("1 ").u(g.tag).s(" 1 ").u(g.members.len() as u64).nl()?;
        for &k in &g.members {
            let [a, b] = mesh.segments[k].vertices.map(|v| u64::from(v) + 1);
            o.count(&mut tag).sp().u(a).sp().u(b).nl()?;
        }
    }
    o.s("$EndElements").nl()
}

/// Writes [`write_msh`]'s output to a file (checking the indices before creating it).
///
/// # Errors
///
/// As [`write_msh`] (no file is created for a mesh with an index out of range), and those of
/// creating the file.
pub fn write_msh_to(mesh: &Mesh, path: impl AsRef<Path>) -> io::Result<()> {
    super::triangle::checked(mesh)?;
    super::write_file(path, |out| write_unchecked(mesh, out))
}
