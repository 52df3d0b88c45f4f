//! [`Mesh`]: the mesher's output: integer vertices, counter-clockwise triangles, a region per
//! triangle and the marked segments (input edges and the board boundary).

/// What a marked segment of a [`Mesh`] lies on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SegmentKind {
    /// The board's boundary.
    Boundary,
    /// The outline of component `i` (numbered from 1, as regions).
    Component(u32),
}

/// A mesh edge that lies on the board boundary or on a component's outline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Segment {
    /// The two vertex indices.
    pub vertices: [u32; 2],
    /// What it lies on.
    pub kind: SegmentKind,
}

/// A triangle mesh of a board.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Mesh {
    /// Vertex coordinates (integers: every vertex of the chapter's mesh is a grid point).
    pub vertices: Vec<[i64; 2]>,
    /// Triangles as vertex indices, counter-clockwise.
    pub triangles: Vec<[u32; 3]>,
    /// Region of each triangle: 0 for the board, `i` for component `i`.
    pub regions: Vec<u32>,
    /// Mesh edges on the board boundary and on component outlines, each once per kind: an outline
    /// step on the board's boundary is listed both as `Boundary` and as `Component(i)`.
    pub segments: Vec<Segment>,
}

impl Mesh {
    /// Heap bytes used.
    pub fn heap_bytes(&self) -> usize {
        self.vertices.capacity() * 16
            + self.triangles.capacity() * 12
            + self.regions.capacity() * 4
            + self.segments.capacity() * core::mem::size_of::<Segment>()
    }
}
