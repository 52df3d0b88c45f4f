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

use super::text_out::{Counter, TextOut};
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
    let first = FirstAppearances::new(mesh);
    let markers = SegmentMarkers::new(mesh);
    let mut edges = Vec::with_capacity(first.count);
    let Ok(()) = first.try_for_each::<std::convert::Infallible>(mesh, |a, b| {
        edges.push(([a, b], markers.get(a, b)));
        Ok(())
    });
    edges
}

/// Which half-edges (edge `i` of triangle `t` is bit `3t + i`) are the first appearance of their
/// edge, as a bit set: 3 bits per triangle, so the edges need not be held to be counted first.
struct FirstAppearances {
    bits: Vec<u64>,
    count: usize,
}

impl FirstAppearances {
    fn new(mesh: &Mesh) -> Self {
        let mut seen = SeenEdges::new(mesh);
        let mut bits = vec![0u64; (3 * mesh.triangles.len()).div_ceil(64)];
        let mut count = 0;
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for i in 0..3 {
                if seen.insert(tri[i], tri[(i + 1) % 3]) {
                    let h = 3 * t + i;
                    bits[h / 64] |= 1 << (h % 64);
                    count += 1;
                }
            }
        }
        FirstAppearances { bits, count }
    }

    /// Calls `f(a, b)` for every edge once, in order of first appearance, oriented as there,
    /// until it fails.
    fn try_for_each<E>(
        &self,
        mesh: &Mesh,
        mut f: impl FnMut(u32, u32) -> Result<(), E>,
    ) -> Result<(), E> {
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for i in 0..3 {
                let h = 3 * t + i;
                if self.bits[h / 64] >> (h % 64) & 1 == 1 {
                    f(tri[i], tri[(i + 1) % 3])?;
                }
            }
        }
        Ok(())
    }
}

/// The `.edge` markers of the mesh's segments, by unordered endpoints (see the module doc).
struct SegmentMarkers {
    /// Whether a vertex is an endpoint of a segment: most edges are not looked up.
    on_segment: Vec<bool>,
    markers: FastMap<(u32, u32), u64>,
}

impl SegmentMarkers {
    fn new(mesh: &Mesh) -> Self {
        let mut on_segment = vec![false; mesh.vertices.len()];
        let mut markers = FastMap::default();
        for s in &mesh.segments {
            let [a, b] = s.vertices;
            for v in [a, b] {
                if let Some(flag) = on_segment.get_mut(v as usize) {
                    *flag = true;
                }
            }
            let m = markers.entry((a.min(b), a.max(b))).or_insert(0);
            // An outline marker beats the board-boundary marker.
            if *m <= 1 {
                *m = marker(s.kind);
            }
        }
        SegmentMarkers {
            on_segment,
            markers,
        }
    }

    /// The marker of the edge `a`-`b`: 0 unless it is a segment.
    #[inline]
    fn get(&self, a: u32, b: u32) -> u64 {
        let flagged = |v: u32| self.on_segment.get(v as usize) == Some(&true);
        if !(flagged(a) && flagged(b)) {
            return 0;
        }
        let key = (a.min(b), a.max(b));
        self.markers.get(&key).copied().unwrap_or(0)
    }
}

/// The edges seen so far, found again by their smaller endpoint: with `(from, to) =
/// bucket[v]`, `larger[from..to]` holds the larger endpoints of those whose smaller endpoint is
/// v (a handful per vertex, next to each other in memory), in a table sized by counting first,
/// so nothing is hashed and nothing grows.
struct SeenEdges {
    bucket: Vec<(usize, usize)>,
    larger: Vec<u32>,
}

impl SeenEdges {
    /// The empty table of a mesh whose triangles' indices are in range.
    fn new(mesh: &Mesh) -> Self {
        let mut bucket = vec![(0usize, 0usize); mesh.vertices.len()];
        for tri in &mesh.triangles {
            for i in 0..3 {
                bucket[tri[i].min(tri[(i + 1) % 3]) as usize].1 += 1;
            }
        }
        let mut total = 0;
        for b in &mut bucket {
            let count = b.1;
            *b = (total, total);
            total += count;
        }
        SeenEdges {
            bucket,
            larger: vec![0; total],
        }
    }

    /// Adds the edge `a`-`b` (one of the mesh's); false if it was there already.
    #[inline]
    fn insert(&mut self, a: u32, b: u32) -> bool {
        let (lo, hi) = (a.min(b) as usize, a.max(b));
        let (from, to) = self.bucket[lo];
        if self.larger[from..to].contains(&hi) {
            return false;
        }
        self.larger[to] = hi;
        self.bucket[lo].1 += 1;
        true
    }
}

/// Writes the `.node` file (see the module doc).
///
/// # Errors
///
/// [`std::io::ErrorKind::InvalidInput`] if an index of the mesh is out of range (nothing is
/// written); else those of `out`.
pub fn write_node(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    checked(mesh)?;
    node_unchecked(mesh, out)
}

/// [`write_node`] on a mesh whose indices are checked.
fn node_unchecked(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    let mut on_boundary = vec![false; mesh.vertices.len()];
    let boundary = (mesh.segments.iter()).filter(|s| s.kind == SegmentKind::Boundary);
    for v in boundary.flat_map(|s| s.vertices) {
        on_boundary[v as usize] = true;
    }
    let mut o = TextOut::new(out);
    o.u(mesh.vertices.len() as u64).s(" 2 0 1").nl()?;
    let mut line = Counter::new(1);
    for (p, &b) in mesh.vertices.iter().zip(&on_boundary) {
        o.count(&mut line)
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
///
/// # Errors
///
/// [`std::io::ErrorKind::InvalidInput`] if an index of the mesh is out of range (nothing is
/// written); else those of `out`.
pub fn write_ele(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    checked(mesh)?;
    ele_unchecked(mesh, out)
}

/// [`write_ele`] on a mesh whose indices are checked.
fn ele_unchecked(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    let mut o = TextOut::new(out);
    o.u(mesh.triangles.len() as u64).s(" 3 1").nl()?;
    let mut line = Counter::new(1);
    for (t, &r) in mesh.triangles.iter().zip(&mesh.regions) {
        let [a, b, c] = t.map(|v| u64::from(v) + 1);
        o.count(&mut line).spaced(&[a, b, c, u64::from(r)]).nl()?;
    }
    o.finish()
}

/// Writes the `.edge` file (see the module doc and [`edges_with_markers`]).
///
/// # Errors
///
/// [`std::io::ErrorKind::InvalidInput`] if an index of the mesh is out of range (nothing is
/// written); else those of `out`.
pub fn write_edge(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    checked(mesh)?;
    edge_unchecked(mesh, out)
}

/// [`write_edge`] on a mesh whose indices are checked.
fn edge_unchecked(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    let first = FirstAppearances::new(mesh);
    let markers = SegmentMarkers::new(mesh);
    let mut o = TextOut::new(out);
    o.u(first.count as u64).s(" 1").nl()?;
    let mut line = Counter::new(1);
    first.try_for_each(mesh, |a, b| {
        let m = markers.get(a, b);
        let (a, b) = (u64::from(a) + 1, u64::from(b) + 1);
        o.count(&mut line).sp().u(a).sp().u(b).sp().u(m);
        o.nl()
    })?;
    o.finish()
}

/// Writes `<stem>.node`, `<stem>.ele` and `<stem>.edge` (the suffix is appended, so a stem such
/// as `board.1` keeps its dot), each through a buffer, the three files on threads of their own.
/// Checks the indices before creating any file.
///
/// # Errors
///
/// [`std::io::ErrorKind::InvalidInput`] if an index of the mesh is out of range (no file is
/// created); else the first error, in the order `.node`, `.ele`, `.edge`, met in creating or
/// writing a file (the other files are still written).
pub fn write_triangle_files(mesh: &Mesh, stem: impl AsRef<Path>) -> io::Result<()> {
    checked(mesh)?;
    let with = |suffix: &str| {
        let mut s = stem.as_ref().as_os_str().to_owned();
        s.push(suffix);
        std::path::PathBuf::from(s)
    };
    type Writer = fn(&Mesh, &mut BufWriter<std::fs::File>) -> io::Result<()>;
    let files: [(std::path::PathBuf, Writer); 3] = [
        (with(".node"), |m, o| node_unchecked(m, o)),
        (with(".ele"), |m, o| ele_unchecked(m, o)),
        (with(".edge"), |m, o| edge_unchecked(m, o)),
    ];
    std::thread::scope(|scope| {
        let jobs = files.map(|(path, write)| {
            scope.spawn(move || super::write_file(path, |out| write(mesh, out)))
        });
        let results = jobs.map(|job| {
            job.join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
        });
        results.into_iter().collect()
    })
}
