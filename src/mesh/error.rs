//! [`BoardError`]: why a board was refused, naming the component, edge and input line.

use super::{Point, TooManyTriangles};

/// A board the mesher refuses. Components and edges are numbered from 1 (component i is region
/// i; edge k of a component runs from its vertex k to vertex k + 1); `line` is the input line when
/// the board came from a file.
///
/// Its `Display` is one sentence naming the component, edge, coordinates and input line:
///
/// ```
/// use orthtree::mesh::BoardError;
/// let e = BoardError::BadAngle { component: 3, edge: 2, from: [4, 4], to: [7, 5], line: Some(17) };
/// assert_eq!(
///     e.to_string(),
///     "component 3, edge 2 (line 17): edge (4, 4)-(7, 5) is not at 0, 45, 90 or 135 degrees"
/// );
/// let e = BoardError::ComponentsTouch {
///     component: 1, edge: 1, other: 2, other_edge: 4, at_half_units: [5, 1], line: None,
/// };
/// assert_eq!(
///     e.to_string(),
///     "component 1, edge 1: edge meets edge 4 of component 2 at (2.5, 0.5); \
///      components must not touch or overlap"
/// );
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum BoardError {
    /// U is not a power of two between 1 and 2^30.
    SizeNotPowerOfTwo {
        /// The size given.
        size: i64,
    },
    /// A component has fewer than 3 vertices.
    TooFewVertices {
        /// The component.
        component: usize,
        /// Its input line, if known.
        line: Option<usize>,
    },
    /// A vertex lies outside [0, U]^2.
    OutOfRange {
        /// The component.
        component: usize,
        /// The edge starting at the vertex.
        edge: usize,
        /// The vertex.
        point: Point,
        /// The input line, if known.
        line: Option<usize>,
    },
    /// An edge of length zero.
    ZeroLengthEdge {
        /// The component.
        component: usize,
        /// The edge.
        edge: usize,
        /// The input line, if known.
        line: Option<usize>,
    },
    /// An edge not at 0, 45, 90 or 135 degrees.
    BadAngle {
        /// The component.
        component: usize,
        /// The edge.
        edge: usize,
        /// Its endpoints.
        from: Point,
        /// Its endpoints.
        to: Point,
        /// The input line, if known.
        line: Option<usize>,
    },
    /// Two edges of one component meet other than at their shared vertex.
    SelfIntersection {
        /// The component.
        component: usize,
        /// One edge.
        edge: usize,
        /// The other edge.
        other_edge: usize,
        /// A point they share, in half units (divide by 2).
        at_half_units: Point,
        /// The input line of `edge`, if known.
        line: Option<usize>,
    },
    /// Two components touch or overlap.
    ComponentsTouch {
        /// One component.
        component: usize,
        /// Its edge.
        edge: usize,
        /// The other component.
        other: usize,
        /// The other's edge.
        other_edge: usize,
        /// A point they share, in half units (divide by 2).
        at_half_units: Point,
        /// The input line of `edge`, if known.
        line: Option<usize>,
    },
    /// One component lies inside another.
    ComponentInside {
        /// The inner component.
        component: usize,
        /// The outer one.
        other: usize,
    },
    /// The input text could not be read.
    Parse {
        /// The input line (from 1).
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A segment loop of a `.poly` file does not close.
    OpenLoop {
        /// The loop (component) number.
        component: usize,
        /// The input line of its last segment.
        line: Option<usize>,
    },
    /// The board's side is given both by the file and by the caller, differently.
    SizeMismatch {
        /// The size the file gives.
        file: i64,
        /// The line that gives it.
        line: usize,
        /// The size the caller gives.
        caller: i64,
    },
    /// A vertex of a `.poly` file lies on no segment.
    UnusedVertex {
        /// The vertex id, as numbered in the file.
        vertex: i64,
        /// Its input line.
        line: usize,
    },
    /// A `.poly` file lists holes, which are not supported yet.
    HolesNotSupported {
        /// The line of the hole count.
        line: usize,
        /// The hole count.
        count: usize,
    },
    /// A `.poly` file lists regional attributes, which are not supported (the mesh's regions
    /// are its components).
    RegionsNotSupported {
        /// The line of the regional attribute count.
        line: usize,
        /// The count.
        count: usize,
    },
    /// The input is not valid UTF-8.
    InvalidUtf8 {
        /// The input line (from 1).
        line: usize,
        /// The byte offset, from 0 at the start of the input, of the first byte that is not
        /// UTF-8.
        offset: usize,
        /// That byte.
        byte: u8,
    },
    /// The mesh would have more triangles than the mesher's limit
    /// ([`MeshOptions::max_triangles`](super::MeshOptions::max_triangles)).
    TooManyTriangles(TooManyTriangles),
}

/// A value given in half units (a coordinate, or a doubled area), written as a decimal: 5 as
/// `2.5`, -3 as `-1.5`, 4 as `2`.
pub(super) struct Half(pub(super) i128);

impl core::fmt::Display for Half {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let sign = if self.0 < 0 { "-" } else { "" };
        let m = self.0.unsigned_abs();
        let half = if m.is_multiple_of(2) { "" } else { ".5" };
        write!(f, "{sign}{}{half}", m / 2)
    }
}

/// Where an error is: `component 3`, `component 3, edge 2`, then ` (line 17)` when known (the
/// component, the edge if any, the line if known).
struct Place(usize, Option<usize>, Option<usize>);

impl core::fmt::Display for Place {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "component {}", self.0)?;
        if let Some(edge) = self.1 {
            write!(f, ", edge {edge}")?;
        }
        if let Some(line) = self.2 {
            write!(f, " (line {line})")?;
        }
        Ok(())
    }
}

impl core::fmt::Display for BoardError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            BoardError::SizeNotPowerOfTwo { size } => write!(
                f,
                "board size {size} is not a power of two between 1 and 2^30 (1073741824)"
            ),
            BoardError::TooFewVertices { component, line } => write!(
                f,
                "{}: a component needs at least 3 vertices",
                Place(component, None, line)
            ),
            BoardError::OutOfRange {
                component,
                edge,
                point: [x, y],
                line,
            } => write!(
                f,
                "{}: vertex ({x}, {y}) lies outside the board [0, U]^2",
                Place(component, Some(edge), line)
            ),
            BoardError::ZeroLengthEdge {
                component,
                edge,
                line,
            } => write!(
                f,
                "{}: edge has length zero (its two ends are the same point)",
                Place(component, Some(edge), line)
            ),
            BoardError::BadAngle {
                component,
                edge,
                from: [x0, y0],
                to: [x1, y1],
                line,
            } => write!(
                f,
                "{}: edge ({x0}, {y0})-({x1}, {y1}) is not at 0, 45, 90 or 135 degrees",
                Place(component, Some(edge), line)
            ),
            BoardError::SelfIntersection {
                component,
                edge,
                other_edge,
                at_half_units: [x, y],
                line,
            } => write!(
                f,
                "{}: edge meets edge {other_edge} of the same component at ({}, {}), so the \
                 outline is not a simple polygon",
                Place(component, Some(edge), line),
                Half(x.into()),
                Half(y.into())
            ),
            BoardError::ComponentsTouch {
                component,
                edge,
                other,
                other_edge,
                at_half_units: [x, y],
                line,
            } => write!(
                f,
                "{}: edge meets edge {other_edge} of component {other} at ({}, {}); components \
                 must not touch or overlap",
                Place(component, Some(edge), line),
                Half(x.into()),
                Half(y.into())
            ),
            BoardError::ComponentInside { component, other } => write!(
                f,
                "component {component} lies inside component {other}; components must not be \
                 nested"
            ),
            BoardError::Parse { line, ref message } => write!(f, "line {line}: {message}"),
            BoardError::OpenLoop { component, line } => write!(
                f,
                "{}: its segments do not close into a loop (no segment continues from the last \
                 one)",
                Place(component, None, line)
            ),
            BoardError::SizeMismatch { file, line, caller } => write!(
                f,
                "line {line}: the file gives board size {file}, but the caller asks for size \
                 {caller}; give one of them, or the same in both"
            ),
            BoardError::UnusedVertex { vertex, line } => write!(
                f,
                "line {line}: vertex {vertex} is on no segment; every vertex must join two \
                 segments of one loop"
            ),
            BoardError::HolesNotSupported { line, count } => write!(
                f,
                "line {line}: the file lists {count} hole(s); holes are not supported yet (each \
                 loop of segments is a solid component, so a hole would be meshed as part of \
                 the component around it)"
            ),
            BoardError::RegionsNotSupported { line, count } => write!(
                f,
                "line {line}: the file lists {count} regional attribute(s); these are not \
                 supported (the regions of the mesh are the board and its components)"
            ),
            BoardError::InvalidUtf8 { line, offset, byte } => write!(
                f,
                "line {line} (byte offset {offset}): byte 0x{byte:02x} is not valid UTF-8; a \
                 board file must be UTF-8 text"
            ),
            BoardError::TooManyTriangles(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for BoardError {}
