//! [`Subdivision`]: a connected planar straight-line graph with its faces, the input of point
//! location (exercise 14.10 of de Berg, Cheong, van Kreveld and Overmars, *Computational
//! Geometry*, chapter 14).
//!
//! The faces come from a doubly-connected edge list (the book's chapter 2): each edge gives two
//! half-edges, the outgoing half-edges of every vertex are sorted by angle, and the next
//! half-edge after `u -> v` around the face on its left is the outgoing half-edge of `v` just
//! clockwise of `v -> u`. Every cycle of `next` bounds one face; in a connected graph exactly
//! one cycle runs clockwise (signed area <= 0), and bounds the outer face. O(E log E).
//!
//! The sorted half-edges around a vertex are also the exercise's "additional data structure at
//! the quadtree leaves storing vertices": the face around a vertex in a given direction is found
//! by binary search over them, in O(log degree) ([`Subdivision::face_around`]).

/// A face of a [`Subdivision`]: a number below [`Subdivision::face_count`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct FaceId(pub u32);

/// A subdivision the crate refuses, naming the offending vertex or edge.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum SubdivisionError {
    /// Vertex `vertex` has NaN or an infinity on `axis`.
    NotFinite {
        /// The vertex.
        vertex: usize,
        /// The bad axis.
        axis: usize,
    },
    /// Edge `edge` names a vertex that does not exist.
    NoSuchVertex {
        /// The edge.
        edge: usize,
        /// The vertex index it names.
        vertex: u32,
    },
    /// Edge `edge` joins a vertex to itself.
    Loop {
        /// The edge.
        edge: usize,
    },
    /// Edges `first` and `edge` join the same two vertices.
    DuplicateEdge {
        /// The earlier edge.
        first: usize,
        /// The repeated edge.
        edge: usize,
    },
    /// Vertices `first` and `vertex` have the same coordinates.
    DuplicateVertex {
        /// The earlier vertex.
        first: usize,
        /// The repeated vertex.
        vertex: usize,
    },
    /// Vertex `vertex` is not connected to vertex 0.
    Disconnected {
        /// The first vertex not reached.
        vertex: usize,
    },
    /// Edges `a` and `b` meet other than at a shared endpoint (found where the quadtree reached
    /// its finest cells).
    Crossing {
        /// One edge.
        a: usize,
        /// The other.
        b: usize,
    },
    /// More vertices or edges than a `u32` can index.
    TooLarge,
    /// The exercise's rule ([`PointLocator::with_exercise_rule`](super::PointLocator::with_exercise_rule))
    /// would need more than `limit` squares: edges too close for their length.
    TooManySquares {
        /// The budget: 64 squares per vertex and edge, plus 4096.
        limit: usize,
    },
}

impl core::fmt::Display for SubdivisionError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::NotFinite { vertex, axis } => {
                write!(
                    f,
                    "vertex {vertex}: coordinate on axis {axis} is not finite"
                )
            }
            Self::NoSuchVertex { edge, vertex } => {
                write!(f, "edge {edge} names vertex {vertex}, which does not exist")
            }
            Self::Loop { edge } => write!(f, "edge {edge} joins a vertex to itself"),
            Self::DuplicateEdge { first, edge } => {
                write!(f, "edge {edge} repeats edge {first}")
            }
            Self::DuplicateVertex { first, vertex } => {
                write!(f, "vertex {vertex} repeats vertex {first}'s coordinates")
            }
            Self::Disconnected { vertex } => {
                write!(f, "vertex {vertex} is not connected to vertex 0")
            }
            Self::Crossing { a, b } => write!(f, "edges {a} and {b} cross"),
            Self::TooLarge => f.write_str("too many vertices or edges"),
            Self::TooManySquares { limit } => write!(
                f,
                "the exercise's rule needs more than {limit} squares (edges too close for their \
                 length); use PointLocator::new"
            ),
        }
    }
}

impl std::error::Error for SubdivisionError {}

/// A connected planar straight-line graph and its faces.
///
/// ```
/// use orthtree::compressed::Subdivision;
/// // a square split by a diagonal: two triangles and the outer face
/// let v = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
/// let e = vec![[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]];
/// let s = Subdivision::new(v, e).unwrap();
/// assert_eq!(s.face_count(), 3);
/// let (below, above) = (s.left_face(0), s.right_face(0)); // edge 0 runs 0 -> 1
/// assert_eq!(above, s.outer_face());
/// assert_ne!(below, s.outer_face());
/// ```
#[derive(Clone, Debug)]
pub struct Subdivision {
    vertices: Vec<[f64; 2]>,
    edges: Vec<[u32; 2]>,
    /// Outgoing half-edges of vertex `v`: `around[start[v]..start[v + 1]]`, by angle.
    start: Vec<u32>,
    around: Vec<u32>,
    angle: Vec<f64>,
    /// The face left of each half-edge (half-edge `2e` runs along edge `e`, `2e + 1` back).
    face: Vec<u32>,
    face_count: u32,
    outer: u32,
}

/// The direction angle of `b - a`.
fn angle(a: [f64; 2], b: [f64; 2]) -> f64 {
    (b[1] - a[1]).atan2(b[0] - a[0])
}

/// Checks the vertices: few enough (with the edges) for `u32` half-edge indices, finite, and
/// no two at one point.
fn check_vertices(vertices: &[[f64; 2]], edge_count: usize) -> Result<(), SubdivisionError> {
    let n = vertices.len();
    if n >= u32::MAX as usize / 2 || edge_count >= u32::MAX as usize / 2 {
        return Err(SubdivisionError::TooLarge);
    }
    for (vertex, p) in vertices.iter().enumerate() {
        if let Some(axis) = p.iter().position(|x| !x.is_finite()) {
            return Err(SubdivisionError::NotFinite { vertex, axis });
        }
    }
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| {
        vertices[a]
            .partial_cmp(&vertices[b])
            .expect("finite")
            .then(a.cmp(&b))
    });
    for w in order.windows(2) {
        if vertices[w[0]] == vertices[w[1]] {
            return Err(SubdivisionError::DuplicateVertex {
                first: w[0],
                vertex: w[1],
            });
        }
    }
    Ok(())
}

/// Checks the edges against `n` vertices: existing ends, no loop, no edge twice.
fn check_edges(n: usize, edges: &[[u32; 2]]) -> Result<(), SubdivisionError> {
    let mut pairs = Vec::with_capacity(edges.len());
    for (edge, &[a, b]) in edges.iter().enumerate() {
        if let Some(&vertex) = [a, b].iter().find(|&&x| x as usize >= n) {
            return Err(SubdivisionError::NoSuchVertex { edge, vertex });
        }
        if a == b {
            return Err(SubdivisionError::Loop { edge });
        }
        pairs.push((a.min(b), a.max(b), edge));
    }
    pairs.sort_unstable();
    for w in pairs.windows(2) {
        if (w[0].0, w[0].1) == (w[1].0, w[1].1) {
            return Err(SubdivisionError::DuplicateEdge {
                first: w[0].2.min(w[1].2),
                edge: w[0].2.max(w[1].2),
            });
        }
    }
    Ok(())
}

/// The rotation system: the outgoing half-edges of each vertex sorted by angle (half-edge
/// `2e` runs along edge `e`, `2e + 1` back).
struct Rotation {
    /// Outgoing half-edges of vertex `v`: `around[start[v]..start[v + 1]]`.
    start: Vec<u32>,
    around: Vec<u32>,
    /// The direction angle of each entry of `around`.
    angle: Vec<f64>,
    /// The index in `around` of each half-edge.
    position: Vec<u32>,
}

impl Rotation {
    /// Sorts the half-edges around each vertex (a counting sort by origin, then small sorts).
    fn new(vertices: &[[f64; 2]], edges: &[[u32; 2]]) -> Self {
        let n = vertices.len();
        let origin = |h: u32| edges[(h / 2) as usize][(h % 2) as usize];
        let target = |h: u32| edges[(h / 2) as usize][1 - (h % 2) as usize];
        let mut start = vec![0u32; n + 1];
        for h in 0..2 * edges.len() as u32 {
            start[origin(h) as usize + 1] += 1;
        }
        for v in 0..n {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        let mut around = vec![0u32; 2 * edges.len()];
        for h in 0..2 * edges.len() as u32 {
            let o = origin(h) as usize;
            around[fill[o] as usize] = h;
            fill[o] += 1;
        }
        let dir = |h: u32| angle(vertices[origin(h) as usize], vertices[target(h) as usize]);
        for v in 0..n {
            around[start[v] as usize..start[v + 1] as usize]
                .sort_by(|&a, &b| dir(a).total_cmp(&dir(b)));
        }
        let angle_of: Vec<f64> = around.iter().map(|&h| dir(h)).collect();
        let mut position = vec![0u32; around.len()];
        for (i, &h) in around.iter().enumerate() {
            position[h as usize] = i as u32;
        }
        Rotation {
            start,
            around,
            angle: angle_of,
            position,
        }
    }

    /// next(u -> v): the outgoing half-edge of v just clockwise of v -> u.
    fn next(&self, edges: &[[u32; 2]], h: u32) -> u32 {
        let twin = h ^ 1;
        let v = edges[(twin / 2) as usize][(twin % 2) as usize] as usize;
        let (s, e) = (self.start[v], self.start[v + 1]);
        let at = self.position[twin as usize];
        self.around[if at == s { e - 1 } else { at - 1 } as usize]
    }
}

/// The faces: the face left of each half-edge, found by walking every face cycle once, and
/// the doubled signed area of each face (the outer face's is the most negative).
fn trace_faces(
    vertices: &[[f64; 2]],
    edges: &[[u32; 2]],
    rotation: &Rotation,
) -> (Vec<u32>, Vec<f64>) {
    let origin = |h: u32| edges[(h / 2) as usize][(h % 2) as usize];
    let target = |h: u32| edges[(h / 2) as usize][1 - (h % 2) as usize];
    let mut face = vec![u32::MAX; rotation.around.len()];
    let mut areas = Vec::new();
    for h0 in 0..face.len() as u32 {
        if face[h0 as usize] != u32::MAX {
            continue;
        }
        let id = areas.len() as u32;
        let mut area = 0.0;
        let mut h = h0;
        while face[h as usize] == u32::MAX {
            face[h as usize] = id;
            let (a, b) = (vertices[origin(h) as usize], vertices[target(h) as usize]);
            area += a[0] * b[1] - a[1] * b[0];
            h = rotation.next(edges, h);
        }
        areas.push(area);
    }
    (face, areas)
}

impl Subdivision {
    /// Checks the graph and computes its faces.
    ///
    /// # Errors
    /// A [`SubdivisionError`]: too many vertices or edges, a non-finite or repeated vertex; an
    /// edge naming a missing vertex, joining a vertex to itself, or repeated; a vertex not
    /// connected to vertex 0.
    ///
    /// # Complexity
    /// O((V + E) log(V + E)) time for V vertices and E edges.
    pub fn new(vertices: Vec<[f64; 2]>, edges: Vec<[u32; 2]>) -> Result<Self, SubdivisionError> {
        check_vertices(&vertices, edges.len())?;
        check_edges(vertices.len(), &edges)?;
        check_connected(vertices.len(), &edges)?;
        let rotation = Rotation::new(&vertices, &edges);
        let (face, areas) = trace_faces(&vertices, &edges, &rotation);
        let outer = (0..areas.len())
            .min_by(|&a, &b| areas[a].total_cmp(&areas[b]))
            .unwrap_or(0) as u32;
        Ok(Subdivision {
            face_count: areas.len().max(1) as u32,
            vertices,
            edges,
            start: rotation.start,
            around: rotation.around,
            angle: rotation.angle,
            face,
            outer,
        })
    }

    /// The vertices.
    pub fn vertices(&self) -> &[[f64; 2]] {
        &self.vertices
    }

    /// The edges, as pairs of vertex indices.
    pub fn edges(&self) -> &[[u32; 2]] {
        &self.edges
    }

    /// The number of faces (1 for a graph without edges).
    pub fn face_count(&self) -> usize {
        self.face_count as usize
    }

    /// The unbounded face.
    pub fn outer_face(&self) -> FaceId {
        FaceId(self.outer)
    }

    /// The face left of edge `e` seen from its first vertex to its second.
    ///
    /// # Panics
    /// If `e` is not an edge index.
    pub fn left_face(&self, e: usize) -> FaceId {
        FaceId(self.face[2 * e])
    }

    /// The face right of edge `e` seen from its first vertex to its second.
    ///
    /// # Panics
    /// If `e` is not an edge index.
    pub fn right_face(&self, e: usize) -> FaceId {
        FaceId(self.face[2 * e + 1])
    }

    /// The face next to vertex `v` in the direction of `to` (any point other than `v`): the
    /// face left of the last outgoing edge at or before that direction, counter-clockwise.
    /// O(log degree) by binary search. The outer face for a vertex without edges.
    pub(crate) fn face_around(&self, v: usize, to: [f64; 2]) -> FaceId {
        let (s, e) = (self.start[v] as usize, self.start[v + 1] as usize);
        if s == e {
            return self.outer_face();
        }
        let theta = angle(self.vertices[v], to);
        let at = s + self.angle[s..e].partition_point(|&a| a <= theta);
        let h = self.around[if at == s { e - 1 } else { at - 1 }];
        FaceId(self.face[h as usize])
    }
}

/// `Err(Disconnected)` naming the first vertex not reached from vertex 0.
fn check_connected(n: usize, edges: &[[u32; 2]]) -> Result<(), SubdivisionError> {
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(parent: &mut [usize], mut x: usize) -> usize {
        while parent[x] != x {
            parent[x] = parent[parent[x]];
            x = parent[x];
        }
        x
    }
    for &[a, b] in edges {
        let (ra, rb) = (find(&mut parent, a as usize), find(&mut parent, b as usize));
        parent[ra.max(rb)] = ra.min(rb);
    }
    match (1..n).find(|&v| find(&mut parent, v) != find(&mut parent, 0)) {
        Some(vertex) => Err(SubdivisionError::Disconnected { vertex }),
        None => Ok(()),
    }
}
