//! [`HalfEdges`]: the doubly-connected edge list of a [`Mesh`] (the chapter's exercise 14.9), as a
//! view that borrows the mesh's triangles and adds only the twin of every half-edge and one
//! outgoing half-edge per vertex.
//!
//! The layout, the cost of construction and the memory used are described at [`HalfEdges`].

use super::pairing::{edge_key, key_vertices, pair, PairDefect, NONE};
use super::Mesh;
use core::fmt;

/// Why a mesh has no doubly-connected edge list. Triangles and vertices are 0-based indices into
/// the mesh's arrays.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum HalfEdgeError {
    /// More than (2^32 - 2) / 3 triangles: half-edge indices would not fit in a `u32`.
    TooManyTriangles {
        /// The number of triangles.
        triangles: usize,
    },
    /// A triangle refers to a vertex that does not exist.
    VertexOutOfRange {
        /// The triangle.
        triangle: u32,
        /// The vertex index it uses.
        vertex: u32,
    },
    /// A triangle uses one vertex twice.
    DegenerateTriangle {
        /// The triangle.
        triangle: u32,
    },
    /// Two triangles both use the directed edge `from -> to`: they overlap or one is flipped.
    RepeatedDirectedEdge {
        /// The edge's first vertex.
        from: u32,
        /// The edge's second vertex.
        to: u32,
        /// The two triangles.
        triangles: [u32; 2],
    },
    /// An edge belongs to more than two triangles.
    EdgeInMoreThanTwoTriangles {
        /// The edge's vertices, smaller first.
        edge: [u32; 2],
        /// Three of its triangles.
        triangles: [u32; 3],
    },
    /// The triangles around a vertex form more than one fan (they meet only at the vertex).
    NonManifoldVertex {
        /// The vertex.
        vertex: u32,
    },
}

impl fmt::Display for HalfEdgeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            HalfEdgeError::TooManyTriangles { triangles } => {
                write!(
                    f,
                    "{triangles} triangles: too many for u32 half-edge indices"
                )
            }
            HalfEdgeError::VertexOutOfRange { triangle, vertex } => {
                write!(
                    f,
                    "triangle {triangle} uses vertex {vertex}, which does not exist"
                )
            }
            HalfEdgeError::DegenerateTriangle { triangle } => {
                write!(f, "triangle {triangle} uses a vertex twice")
            }
            HalfEdgeError::RepeatedDirectedEdge {
                from,
                to,
                triangles: [s, t],
            } => write!(
                f,
                "triangles {s} and {t} both use the directed edge {from} -> {to}"
            ),
            HalfEdgeError::EdgeInMoreThanTwoTriangles {
                edge: [a, b],
                triangles: [s, t, u],
            } => write!(
                f,
                "edge {a}-{b} belongs to more than two triangles ({s}, {t}, {u}, ...)"
            ),
            HalfEdgeError::NonManifoldVertex { vertex } => {
                write!(
                    f,
                    "the triangles around vertex {vertex} form more than one fan"
                )
            }
        }
    }
}

impl std::error::Error for HalfEdgeError {}

/// The doubly-connected edge list of a triangle mesh (the chapter's exercise 14.9), as a view
/// that borrows the mesh's triangles.
///
/// Half-edge `h = 3t + i` runs from `triangles[t][i]` to `triangles[t][(i + 1) % 3]`, so its
/// face, `next` and `prev` are arithmetic on `h`; only `twin` is stored. Since triangles are
/// counter-clockwise, the face of a half-edge lies on its left, as in the book's doubly-connected
/// edge lists. Half-edges on the mesh boundary have no twin (the book's outer face is left
/// implicit).
///
/// Construction sorts the 3T undirected edge keys (`u64`, the smaller vertex in the high 32
/// bits) with their half-edges, by a counting sort on the smaller vertex and a sort of each
/// vertex's few edges, and pairs equal keys: O(T + V) time plus O(d log d) per vertex of degree
/// d. A mesh that is not a manifold
/// is an error, never a panic: a vertex index out of range, a triangle repeating a vertex, an edge
/// used twice in the same direction or by more than two triangles, or a vertex whose triangles
/// form more than one fan (two triangles touching only at a vertex).
///
/// Memory: 12 bytes per triangle (one `u32` twin per half-edge) plus 4 bytes per vertex (one
/// outgoing half-edge), about 14 bytes per triangle for the chapter's meshes (about half as many
/// vertices as triangles; 14.0 measured on [`sample_board`](super::sample_board)'s 367,672
/// triangles), on top of the mesh itself. Construction needs 48 more bytes per triangle for the
/// sorted keys and 8 per vertex, freed on return.
///
/// The accessors taking a half-edge or a vertex panic if it is out of range, like slice indexing.
///
/// ```
/// use orthtree::mesh::Mesh;
/// // the unit square cut along its rising diagonal
/// let mesh = Mesh {
///     vertices: vec![[0, 0], [1, 0], [1, 1], [0, 1]],
///     triangles: vec![[0, 1, 2], [0, 2, 3]],
///     regions: vec![0, 0],
///     segments: vec![],
/// };
/// let he = mesh.half_edges().unwrap();
/// assert_eq!(he.len(), 6);
/// // half-edge 1 runs 1 -> 2, half-edge 2 runs 2 -> 0; the diagonal's twin is 3 (0 -> 2)
/// assert_eq!((he.origin(2), he.target(2)), (2, 0));
/// assert_eq!(he.twin(2), Some(3));
/// assert_eq!(he.twin(0), None); // on the boundary
/// assert_eq!(he.next(2), 0);
/// assert_eq!(he.prev(0), 2);
/// assert_eq!(he.face(4), 1);
/// // vertex 0 has two outgoing half-edges, 0 -> 1 (on the boundary) and 0 -> 2; the boundary
/// // edge 3 -> 0 enters it
/// let out: Vec<u32> = he.outgoing(0).map(|h| he.target(h)).collect();
/// assert_eq!(out, [1, 2]);
/// let last = he.outgoing(0).last().unwrap();
/// assert_eq!(he.origin(he.prev(last)), 3);
/// assert_eq!(he.edge_count(), 5);
/// ```
#[derive(Clone, Debug)]
pub struct HalfEdges<'a> {
    triangles: &'a [[u32; 3]],
    /// The twin of each half-edge, [`NONE`] on the boundary.
    twins: Vec<u32>,
    /// Per vertex: an outgoing half-edge, the one on the boundary if there is one; [`NONE`] for a
    /// vertex no triangle uses.
    first_out: Vec<u32>,
}

/// The outgoing half-edges of a vertex in counter-clockwise order, from [`HalfEdges::outgoing`].
#[derive(Clone, Debug)]
pub struct Outgoing<'h, 'a> {
    half_edges: &'h HalfEdges<'a>,
    start: u32,
    current: u32,
}

impl Iterator for Outgoing<'_, '_> {
    type Item = u32;

    fn next(&mut self) -> Option<u32> {
        if self.current == NONE {
            return None;
        }
        let h = self.current;
        // The next outgoing half-edge counter-clockwise: the twin of the half-edge entering
        // the vertex in the same triangle.
        self.current = match self.half_edges.twin(self.half_edges.prev(h)) {
            Some(t) if t != self.start => t,
            _ => NONE,
        };
        Some(h)
    }
}

impl Mesh {
    /// The doubly-connected edge list of this mesh; see [`HalfEdges::new`].
    ///
    /// # Errors
    /// As [`HalfEdges::new`].
    pub fn half_edges(&self) -> Result<HalfEdges<'_>, HalfEdgeError> {
        HalfEdges::new(self)
    }
}

/// The triangles' vertex indices checked: in range, three distinct per triangle, and few enough
/// triangles for `u32` half-edge indices.
fn check_triangles(triangles: &[[u32; 3]], nv: usize) -> Result<(), HalfEdgeError> {
    let n = triangles.len();
    if n > (NONE as usize - 1) / 3 {
        return Err(HalfEdgeError::TooManyTriangles { triangles: n });
    }
    for (t, tri) in triangles.iter().enumerate() {
        if let Some(&vertex) = tri.iter().find(|&&v| v as usize >= nv) {
            return Err(HalfEdgeError::VertexOutOfRange {
                triangle: t as u32,
                vertex,
            });
        }
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0] {
            return Err(HalfEdgeError::DegenerateTriangle { triangle: t as u32 });
        }
    }
    Ok(())
}

/// The error for an edge whose half-edges do not pair.
fn pairing_error(triangles: &[[u32; 3]], defect: PairDefect) -> HalfEdgeError {
    let origin = |h: u32| triangles[h as usize / 3][h as usize % 3];
    let target = |h: u32| triangles[h as usize / 3][(h as usize % 3 + 1) % 3];
    match defect {
        PairDefect::SameDirection([g, h]) => HalfEdgeError::RepeatedDirectedEdge {
            from: origin(g),
            to: target(g),
            triangles: [g / 3, h / 3],
        },
        PairDefect::Crowded(half_edges) => HalfEdgeError::EdgeInMoreThanTwoTriangles {
            edge: key_vertices(edge_key(origin(half_edges[0]), target(half_edges[0]))),
            triangles: [half_edges[0] / 3, half_edges[1] / 3, half_edges[2] / 3],
        },
    }
}

/// One outgoing half-edge per vertex, the boundary one if any (a fan is walked
/// counter-clockwise from it), and each vertex's number of outgoing half-edges; a second
/// boundary one means two fans.
fn first_outgoing(
    triangles: &[[u32; 3]],
    twins: &[u32],
    nv: usize,
) -> Result<(Vec<u32>, Vec<u32>), HalfEdgeError> {
    let mut first_out = vec![NONE; nv];
    let mut degree = vec![0u32; nv];
    for h in 0..twins.len() as u32 {
        let v = triangles[h as usize / 3][h as usize % 3] as usize;
        degree[v] += 1;
        let slot = &mut first_out[v];
        if twins[h as usize] == NONE {
            if *slot != NONE && twins[*slot as usize] == NONE {
                return Err(HalfEdgeError::NonManifoldVertex { vertex: v as u32 });
            }
            *slot = h;
        } else if *slot == NONE {
            *slot = h;
        }
    }
    Ok((first_out, degree))
}

impl<'a> HalfEdges<'a> {
    /// Builds the doubly-connected edge list of `mesh`. Vertices that no triangle uses are
    /// allowed; they have no outgoing half-edges. The half-edges are paired as
    /// [`Mesh::validate`] pairs them (one shared routine).
    ///
    /// # Errors
    /// The [`HalfEdgeError`] saying why the mesh is not a manifold: too many triangles, a vertex
    /// index out of range, a triangle repeating a vertex, an edge used twice in one direction or
    /// by more than two triangles (the first such edge in vertex order), or a vertex whose
    /// triangles form more than one fan.
    ///
    /// # Complexity
    /// O(T + V) time plus O(d log d) per vertex of degree d, for T triangles and V vertices
    /// (the edge keys are sorted by a counting sort on their smaller vertex).
    pub fn new(mesh: &'a Mesh) -> Result<Self, HalfEdgeError> {
        let triangles = &mesh.triangles[..];
        let nv = mesh.vertices.len();
        check_triangles(triangles, nv)?;
        let pairing = pair(triangles, nv, |_| true);
        if let Some(defect) = pairing.defect {
            return Err(pairing_error(triangles, defect));
        }
        drop(pairing.keys);
        let twins = pairing.twins;
        let (first_out, degree) = first_outgoing(triangles, &twins, nv)?;
        let he = HalfEdges {
            triangles,
            twins,
            first_out,
        };
        // Every outgoing half-edge must be reached from the first one: else several fans.
        for (v, &d) in degree.iter().enumerate() {
            if d > 0 && he.outgoing(v as u32).take(d as usize + 1).count() != d as usize {
                return Err(HalfEdgeError::NonManifoldVertex { vertex: v as u32 });
            }
        }
        Ok(he)
    }

    /// The number of half-edges, 3 per triangle.
    pub fn len(&self) -> usize {
        self.twins.len()
    }

    /// `true` for a mesh without triangles.
    pub fn is_empty(&self) -> bool {
        self.twins.is_empty()
    }

    /// The number of (undirected) edges: each interior edge has two half-edges, each boundary
    /// edge one.
    pub fn edge_count(&self) -> usize {
        let boundary = self.twins.iter().filter(|&&t| t == NONE).count();
        (self.twins.len() + boundary) / 2
    }

    /// The vertex half-edge `h` starts at.
    pub fn origin(&self, h: u32) -> u32 {
        self.triangles[h as usize / 3][h as usize % 3]
    }

    /// The vertex half-edge `h` ends at.
    pub fn target(&self, h: u32) -> u32 {
        self.triangles[h as usize / 3][(h as usize % 3 + 1) % 3]
    }

    /// The opposite half-edge (same edge, other triangle), `None` on the mesh boundary.
    pub fn twin(&self, h: u32) -> Option<u32> {
        Some(self.twins[h as usize]).filter(|&t| t != NONE)
    }

    /// The next half-edge around the same triangle (counter-clockwise).
    pub fn next(&self, h: u32) -> u32 {
        3 * self.face(h) + (h + 1) % 3
    }

    /// The previous half-edge around the same triangle.
    pub fn prev(&self, h: u32) -> u32 {
        3 * self.face(h) + (h + 2) % 3
    }

    /// The triangle (face) on the left of `h`: `h / 3`.
    pub fn face(&self, h: u32) -> u32 {
        let _ = self.twins[h as usize];
        h / 3
    }

    /// `true` when `h` has no twin.
    pub fn is_boundary(&self, h: u32) -> bool {
        self.twins[h as usize] == NONE
    }

    /// An outgoing half-edge of vertex `v`: the one on the boundary if `v` is a boundary
    /// vertex; `None` if no triangle uses `v`.
    pub fn vertex_half_edge(&self, v: u32) -> Option<u32> {
        Some(self.first_out[v as usize]).filter(|&h| h != NONE)
    }

    /// The half-edges leaving vertex `v`, counter-clockwise; at a boundary vertex, from the
    /// boundary half-edge leaving `v` round to the one whose previous half-edge enters `v` from
    /// the boundary.
    ///
    /// # Complexity
    /// O(1) per step.
    pub fn outgoing(&self, v: u32) -> Outgoing<'_, 'a> {
        let start = self.first_out[v as usize];
        Outgoing {
            half_edges: self,
            start,
            current: start,
        }
    }

    /// The half-edges without twin, in index order.
    pub fn boundary(&self) -> impl Iterator<Item = u32> + '_ {
        (0..self.twins.len() as u32).filter(|&h| self.twins[h as usize] == NONE)
    }

    /// Heap bytes used (the borrowed triangles not counted).
    pub fn heap_bytes(&self) -> usize {
        (self.twins.capacity() + self.first_out.capacity()) * 4
    }
}
