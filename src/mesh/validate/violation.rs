//! [`MeshValidationError`]: the first broken invariant of each check of
//! [`Mesh::validate`](super::Mesh::validate), one variant per invariant, naming the triangles,
//! vertices, edges, segments and points concerned (0-based indices into the mesh's arrays;
//! components and regions numbered from 1).

use super::{Point, SegmentKind};
use core::fmt;

/// A side of the board, as the board boundary runs counter-clockwise.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BoardSide {
    /// y = 0, run left to right.
    Bottom,
    /// x = U, run bottom to top.
    Right,
    /// y = U, run right to left.
    Top,
    /// x = 0, run top to bottom.
    Left,
}

impl BoardSide {
    /// The four sides in counter-clockwise order from the bottom.
    pub const ALL: [BoardSide; 4] = [
        BoardSide::Bottom,
        BoardSide::Right,
        BoardSide::Top,
        BoardSide::Left,
    ];
}

impl fmt::Display for BoardSide {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            BoardSide::Bottom => "bottom (y = 0)",
            BoardSide::Right => "right (x = U)",
            BoardSide::Top => "top (y = U)",
            BoardSide::Left => "left (x = 0)",
        })
    }
}

/// Why a triangle must have another region than it has ([`MeshValidationError::WrongRegion`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RegionRule {
    /// The triangle lies left of component `0`'s outline, so it has that component's region.
    LeftOfOutline(u32),
    /// The triangle lies right of component `0`'s outline, so it has region 0 (the board).
    RightOfOutline(u32),
    /// The triangle shares a non-input edge with triangle `0`, so it has that triangle's region.
    AcrossFrom(u32),
}

/// The first invariant a check of [`Mesh::validate`](super::Mesh::validate) found broken, or
/// why [`Mesh::check_indices`](super::Mesh::check_indices) refused a mesh. The variants are
/// grouped by the check ([`ValidationReport`](super::ValidationReport) field) that reports them.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum MeshValidationError {
    /// `indices`: a triangle refers to a vertex that does not exist.
    TriangleVertexOutOfRange {
        /// The triangle.
        triangle: usize,
        /// Its vertex indices.
        vertices: [u32; 3],
        /// The number of vertices.
        vertex_count: usize,
    },
    /// `indices`: the regions are not one per triangle.
    RegionCount {
        /// The number of regions.
        regions: usize,
        /// The number of triangles.
        triangles: usize,
    },
    /// `indices` and `segments`: a segment refers to a vertex that does not exist.
    SegmentVertexOutOfRange {
        /// The segment.
        segment: usize,
        /// Its vertex indices.
        vertices: [u32; 2],
        /// The number of vertices.
        vertex_count: usize,
    },
    /// `indices`: too many triangles for `u32` half-edge indices.
    TooManyTriangles {
        /// The number of triangles.
        triangles: usize,
    },
    /// `indices`: a vertex lies outside the board [0, U]^2.
    VertexOutsideBoard {
        /// The vertex.
        vertex: usize,
        /// Its position.
        point: Point,
        /// The board size U.
        size: i64,
    },
    /// `orientation`: a triangle is clockwise (negative area) or degenerate (zero area).
    NotCounterClockwise {
        /// The triangle.
        triangle: usize,
        /// Its vertex indices.
        vertices: [u32; 3],
        /// Their positions.
        points: [Point; 3],
        /// Twice its signed area.
        doubled_area: i128,
    },
    /// `conforming`: an edge belongs to more than two triangles.
    EdgeInMoreThanTwoTriangles {
        /// The edge, as its first half-edge runs.
        edge: [u32; 2],
        /// Every triangle using it.
        triangles: Vec<u32>,
    },
    /// `conforming`: two triangles use the same directed edge (they overlap or one is flipped).
    RepeatedDirectedEdge {
        /// The edge's first vertex.
        from: u32,
        /// The edge's second vertex.
        to: u32,
        /// The two triangles.
        triangles: [u32; 2],
    },
    /// `conforming`: an edge has no triangle on its other side and does not run
    /// counter-clockwise along the board boundary.
    UnpairedEdge {
        /// The edge's first vertex.
        from: u32,
        /// The edge's second vertex.
        to: u32,
        /// Their positions.
        points: [Point; 2],
        /// The triangle the edge belongs to.
        triangle: u32,
    },
    /// `conforming`: the boundary edges on a side of the board leave a gap or overlap.
    BoundaryCover {
        /// The side.
        side: BoardSide,
        /// Where the gap or overlap starts, measured along the side from its start.
        at: i64,
        /// `true` for a gap, `false` for an overlap.
        gap: bool,
        /// The triangle of the boundary edge met there.
        triangle: u32,
    },
    /// `conforming`: the boundary edges on a side of the board end before or after its end.
    BoundaryEnd {
        /// The side.
        side: BoardSide,
        /// Where its boundary edges end, measured along the side.
        end: i64,
        /// The board size U, where they should end.
        size: i64,
    },
    /// `conforming`: two used vertices lie at the same point.
    CoincidentVertices {
        /// The two vertices.
        vertices: [u32; 2],
        /// Their position.
        point: Point,
    },
    /// `area`: the triangles' total area is not U^2.
    Area {
        /// Twice the total area.
        doubled_area: i128,
        /// The board size U.
        size: i64,
    },
    /// `respects_input`: a component edge is neither axis-parallel nor diagonal.
    NotLatticeDirection {
        /// The component (from 1).
        component: u32,
        /// The edge's index in the component's outline.
        edge: usize,
        /// Its start.
        from: Point,
        /// Its end.
        to: Point,
    },
    /// `respects_input`: a component's outline vertex is not a mesh vertex.
    OutlineVertexMissing {
        /// The component (from 1).
        component: u32,
        /// The outline vertex.
        point: Point,
    },
    /// `respects_input`: no mesh edge leaves a point of a component edge along it.
    OutlineEdgeBroken {
        /// The component (from 1).
        component: u32,
        /// The edge's index in the component's outline.
        edge: usize,
        /// Its start.
        from: Point,
        /// Its end.
        to: Point,
        /// The mesh vertex on it that no mesh edge leaves along it.
        at: Point,
    },
    /// `angles`: an angle is above 90 or below 45 degrees.
    Angle {
        /// The triangle.
        triangle: usize,
        /// Its vertex indices.
        vertices: [u32; 3],
        /// The vertex at the angle.
        vertex: u32,
        /// Its position.
        point: Point,
        /// The dot product of the two edge vectors leaving the vertex (negative above 90).
        dot: i128,
        /// The absolute cross product of those vectors (below `dot` under 45 degrees).
        cross: i128,
    },
    /// `regions`: a triangle's region is above the number of components.
    RegionOutOfRange {
        /// The triangle.
        triangle: usize,
        /// Its vertex indices.
        vertices: [u32; 3],
        /// Its region.
        region: u32,
        /// The number of components.
        components: u32,
    },
    /// `regions`: a triangle has another region than an input edge or a neighbour requires.
    WrongRegion {
        /// The triangle.
        triangle: usize,
        /// Its region.
        region: u32,
        /// The region it should have.
        expected: u32,
        /// The edge (as the triangle runs it) that requires it.
        edge: [u32; 2],
        /// Why.
        rule: RegionRule,
    },
    /// `regions`: the triangles of a region do not cover its component's area.
    RegionArea {
        /// The region (= component, from 1).
        region: u32,
        /// Twice the area its triangles cover.
        doubled_area: i128,
        /// Twice the component's area.
        expected_doubled_area: i128,
    },
    /// `euler`: V - E + F is not 1.
    Euler {
        /// Used vertices.
        vertices: usize,
        /// Distinct edges.
        edges: usize,
        /// Triangles checked.
        triangles: usize,
    },
    /// `delaunay`: a vertex lies strictly inside the circumcircle of the triangle across an edge.
    NotDelaunay {
        /// The shared edge, as `circumcircle_of` runs it.
        edge: [u32; 2],
        /// The vertex inside.
        vertex: u32,
        /// Its position.
        point: Point,
        /// The triangle it belongs to (opposite the edge).
        triangle: usize,
        /// The triangle whose circumcircle holds it.
        circumcircle_of: usize,
        /// That triangle's vertex opposite the edge.
        opposite: u32,
    },
    /// `segments`: a segment is not a mesh edge.
    SegmentNotEdge {
        /// The segment.
        segment: usize,
        /// Its vertices.
        vertices: [u32; 2],
        /// Its kind.
        kind: SegmentKind,
    },
    /// `segments`: two segments mark the same edge with the same kind.
    RepeatedSegment {
        /// The two segments.
        segments: [usize; 2],
        /// The vertices of the second.
        vertices: [u32; 2],
        /// Their kind.
        kind: SegmentKind,
    },
    /// `segments`: a board-boundary edge has no `Boundary` segment.
    MissingBoundarySegment {
        /// The edge, smaller vertex first.
        edge: [u32; 2],
    },
    /// `segments`: a mesh edge along a component's outline has no segment of that component.
    MissingOutlineSegment {
        /// The edge, as the outline runs.
        edge: [u32; 2],
        /// The component (from 1).
        component: u32,
    },
    /// `segments`: a segment marks an edge as on the board boundary or an outline, but it is not.
    SegmentWrongKind {
        /// The segment.
        segment: usize,
        /// Its vertices.
        vertices: [u32; 2],
        /// Its kind.
        kind: SegmentKind,
    },
}

impl std::error::Error for MeshValidationError {}
