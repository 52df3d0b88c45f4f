//! [`Mesh::validate`]: checks a mesh against its board, property by property, in exact integer
//! arithmetic (coordinates lie in [0, U]^2 with U <= 2^30, so every product fits an `i128`).
//!
//! The checks, one field of [`ValidationReport`] each, are described there, with why
//! `orientation` and `conforming` together rule out T-junctions.

use super::{Board, Mesh, Point, SegmentKind};
use crate::hash::FastMap;
use core::fmt;

/// The outcome of one check of [`Mesh::validate`]: a short summary if the property holds, else
/// the first broken invariant, naming the offending triangle, edge or vertex (0-based indices).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Check {
    /// The property holds; a short summary of what was checked.
    Passed(String),
    /// The first violation found.
    Failed(MeshValidationError),
}

impl Check {
    /// `true` if the property holds.
    pub fn is_ok(&self) -> bool {
        matches!(self, Check::Passed(_))
    }

    /// The violation found, `None` if the property holds.
    pub fn error(&self) -> Option<&MeshValidationError> {
        match self {
            Check::Passed(_) => None,
            Check::Failed(e) => Some(e),
        }
    }
}

impl fmt::Display for Check {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Check::Passed(summary) => write!(f, "ok ({summary})"),
            Check::Failed(e) => write!(f, "FAILED: {e}"),
        }
    }
}

/// The first failure of a check, or a summary if none.
#[derive(Default)]
struct Finding(Option<MeshValidationError>);

impl Finding {
    /// Records the violation unless one is already recorded (the first one is kept).
    fn fail(&mut self, violation: impl FnOnce() -> MeshValidationError) {
        self.0.get_or_insert_with(violation);
    }

    /// Records `violation` unless one is already recorded.
    fn keep(&mut self, violation: Option<MeshValidationError>) {
        self.0 = self.0.take().or(violation);
    }

    fn finish(self, summary: impl FnOnce() -> String) -> Check {
        self.0
            .map_or_else(|| Check::Passed(summary()), Check::Failed)
    }
}

/// What [`Mesh::validate`] found: one [`Check`] per property, the counts, and the angle range.
/// Its `Display` prints a one-line verdict, then one line per failed check. Every check is
/// exact, in integer arithmetic (coordinates lie in [0, U]^2 with U <= 2^30, so every product
/// fits an `i128`).
///
/// The checks, one field each:
///
/// - `indices`: every vertex index in range, one region per triangle, every vertex inside the
///   board. A triangle failing this is left out of all other checks (which may fail in turn).
/// - `orientation`: every triangle counter-clockwise with positive area.
/// - `conforming`: every directed edge used by at most one triangle; every edge shared by two
///   triangles in opposite directions, except edges on the board boundary, which are used once
///   and run counter-clockwise around the board; these boundary edges cover each side of the
///   board exactly (no gap, no overlap); no two used vertices at the same point.
/// - `area`: the triangles' total area is U^2.
/// - `respects_input`: every component edge is a chain of mesh edges: walked from its start,
///   some mesh edge leaves each vertex reached along the component edge's direction without
///   passing its end (found by turning around the vertex), up to the end.
/// - `angles`: every angle in [45, 90] degrees, exactly: for the angle between integer vectors
///   `u` and `v`, it is at most 90 degrees iff `u·v >= 0`, and at least 45 iff `u·v <= |u×v|`.
/// - `regions`: across an interior edge that is not an input edge both triangles have the same
///   region; left of an input edge of component `i` (outlines run counter-clockwise) the triangle
///   has region `i`, right of it region 0; every region is at most the number of components; the
///   triangles of region `i` cover the component's area (shoelace formula).
/// - `euler`: V - E + F = 1 (a disc), counting only vertices some triangle uses.
/// - `delaunay` (the chapter's exercise 14.3): across every interior edge, the opposite vertex of
///   one triangle is not strictly inside the circumcircle of the other (the incircle determinant).
/// - `segments`: every segment is a mesh edge, none is repeated, and the marked segments are
///   exactly the board-boundary edges (kind `Boundary`) and the mesh edges along the component
///   edges (kind `Component(i)`); an outline along the board boundary is marked both ways.
///
/// Why `orientation` and `conforming` together rule out T-junctions (a vertex inside another
/// triangle's edge): the oriented edges of all triangles add up, as a 1-chain, to the board's
/// counter-clockwise boundary, since interior edges cancel in pairs and the boundary edges cover
/// each side exactly. Winding numbers are additive, so for a point `p` on no edge the number of
/// triangles winding around `p` equals the board boundary's winding number: 1 inside the board,
/// 0 outside. Every triangle is counter-clockwise, so it winds around `p` once if `p` is inside
/// and never otherwise: every point of the board lies in exactly one triangle, none outside.
/// Now let vertex `v` lie strictly inside edge `ab` of triangle T. Near `v`, the side of `ab`
/// inside T is covered by T, and the other side by the triangle T' using `ba` (or lies outside
/// the board if `ab` is on its boundary). A triangle with a corner at `v` has positive area, so
/// it has interior points near `v` off the line `ab`, which would be covered twice (or lie
/// outside the board): a contradiction, since such a triangle is neither T nor T' (their
/// corners are `a`, `b` and points off the line). For a valid mesh the total area and Euler's
/// formula follow as well; they are kept as cheap cross-checks that name a different symptom.
/// Likewise 45-90 degree triangles are always Delaunay (exercise 14.3), so `delaunay` fails only
/// together with `angles`.
///
/// Validation never panics on a malformed mesh: indices out of range, vertices outside the board,
/// missing regions and degenerate triangles are reported, and the triangles concerned skipped.
/// Its cost is given at [`Mesh::validate`].
#[derive(Clone, Debug, PartialEq)]
pub struct ValidationReport {
    /// Vertex indices in range, one region per triangle, vertices inside the board.
    pub indices: Check,
    /// Every triangle counter-clockwise with positive area.
    pub orientation: Check,
    /// Edges paired in opposite directions except on the board boundary, which they cover
    /// exactly; no two vertices at one point.
    pub conforming: Check,
    /// Total area U^2.
    pub area: Check,
    /// Every component edge a chain of mesh edges.
    pub respects_input: Check,
    /// Every angle in [45, 90] degrees.
    pub angles: Check,
    /// Regions constant across non-input edges, component `i` left of its outline and the board
    /// right of it, component areas matching.
    pub regions: Check,
    /// V - E + F = 1.
    pub euler: Check,
    /// No vertex strictly inside the circumcircle of the triangle across an edge.
    pub delaunay: Check,
    /// The segments: mesh edges, exactly the board boundary plus the input-edge chains.
    pub segments: Check,
    /// Vertices used by some triangle.
    pub vertices_used: usize,
    /// Distinct (undirected) edges.
    pub edges: usize,
    /// Triangles.
    pub triangles: usize,
    /// The smallest and largest angle in degrees (floating point, for reporting), `None` without
    /// triangles.
    pub angle_range_deg: Option<[f64; 2]>,
}

impl ValidationReport {
    /// `true` if every check passed.
    pub fn is_ok(&self) -> bool {
        self.checks().iter().all(|(_, c)| c.is_ok())
    }

    /// The checks with their field names, in the order of the struct.
    pub fn checks(&self) -> [(&'static str, &Check); 10] {
        [
            ("indices", &self.indices),
            ("orientation", &self.orientation),
            ("conforming", &self.conforming),
            ("area", &self.area),
            ("respects_input", &self.respects_input),
            ("angles", &self.angles),
            ("regions", &self.regions),
            ("euler", &self.euler),
            ("delaunay", &self.delaunay),
            ("segments", &self.segments),
        ]
    }

    /// The names of the failed checks.
    pub fn failed(&self) -> Vec<&'static str> {
        self.checks()
            .into_iter()
            .filter_map(|(name, c)| c.error().map(|_| name))
            .collect()
    }
}

impl fmt::Display for ValidationReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let failed = self.failed();
        if failed.is_empty() {
            write!(f, "valid mesh: ")?;
        } else {
            write!(f, "INVALID mesh ({} of 10 checks failed): ", failed.len())?;
        }
        write!(
            f,
            "{} triangles, {} vertices, {} edges",
            self.triangles, self.vertices_used, self.edges
        )?;
        if let Some([lo, hi]) = self.angle_range_deg {
            write!(f, ", angles {lo:.1} to {hi:.1} degrees")?;
        }
        for (name, check) in self.checks() {
            if let Some(e) = check.error() {
                write!(f, "\n  {name}: {e}")?;
            }
        }
        Ok(())
    }
}

impl Mesh {
    /// The cheap part of [`Mesh::validate`] that a file writer needs: every triangle and segment
    /// vertex index in range, and one region per triangle.
    ///
    /// # Errors
    /// The first offender: [`MeshValidationError::TriangleVertexOutOfRange`],
    /// [`MeshValidationError::RegionCount`] or [`MeshValidationError::SegmentVertexOutOfRange`].
    ///
    /// # Complexity
    /// O(T + S) for T triangles and S segments, no allocation.
    ///
    /// ```
    /// use orthtree::mesh::{Mesh, MeshValidationError};
    /// let mut mesh = Mesh {
    ///     vertices: vec![[0, 0], [1, 0], [1, 1]],
    ///     triangles: vec![[0, 1, 2]],
    ///     regions: vec![0],
    ///     segments: vec![],
    /// };
    /// assert!(mesh.check_indices().is_ok());
    /// mesh.triangles[0][2] = 3;
    /// let err = mesh.check_indices().unwrap_err();
    /// assert_eq!(
    ///     err,
    ///     MeshValidationError::TriangleVertexOutOfRange {
    ///         triangle: 0,
    ///         vertices: [0, 1, 3],
    ///         vertex_count: 3
    ///     }
    /// );
    /// assert!(err.to_string().contains("triangle 0"));
    /// ```
    pub fn check_indices(&self) -> Result<(), MeshValidationError> {
        let vertex_count = self.vertices.len();
        if let Some((triangle, tri)) = (self.triangles.iter().enumerate())
            .find(|(_, tri)| tri.iter().any(|&v| v as usize >= vertex_count))
        {
            return Err(MeshValidationError::TriangleVertexOutOfRange {
                triangle,
                vertices: *tri,
                vertex_count,
            });
        }
        if self.regions.len() != self.triangles.len() {
            return Err(MeshValidationError::RegionCount {
                regions: self.regions.len(),
                triangles: self.triangles.len(),
            });
        }
        if let Some((segment, s)) = (self.segments.iter().enumerate())
            .find(|(_, s)| s.vertices.iter().any(|&v| v as usize >= vertex_count))
        {
            return Err(MeshValidationError::SegmentVertexOutOfRange {
                segment,
                vertices: s.vertices,
                vertex_count,
            });
        }
        Ok(())
    }
}

/// The angle of a dot and an absolute cross product ([`MeshValidationError::Angle`]) in
/// degrees (floating point, for reporting).
fn degrees((dot, cross): (i128, i128)) -> f64 {
    (cross as f64).atan2(dot as f64).to_degrees()
}

/// Twice the signed area of (a, b, c).
fn cross(a: Point, b: Point, c: Point) -> i128 {
    let (ux, uy) = (b[0] as i128 - a[0] as i128, b[1] as i128 - a[1] as i128);
    let (vx, vy) = (c[0] as i128 - a[0] as i128, c[1] as i128 - a[1] as i128);
    ux * vy - uy * vx
}

/// Positive iff `d` is strictly inside the circumcircle of the counter-clockwise (a, b, c).
/// With coordinates in [0, 2^30] every term is below 2^123.
fn incircle(a: Point, b: Point, c: Point, d: Point) -> i128 {
    let diff = |p: Point| (p[0] as i128 - d[0] as i128, p[1] as i128 - d[1] as i128);
    let ((ax, ay), (bx, by), (cx, cy)) = (diff(a), diff(b), diff(c));
    let lift = |x: i128, y: i128| x * x + y * y;
    lift(ax, ay) * (bx * cy - cx * by)
        + lift(bx, by) * (cx * ay - ax * cy)
        + lift(cx, cy) * (ax * by - bx * ay)
}

/// The side of the board a directed edge lies on, running counter-clockwise (as an index into
/// [`BoardSide::ALL`]), with its extent measured along that side from the side's start.
fn boundary_side(a: Point, b: Point, u: i64) -> Option<(usize, i64, i64)> {
    if a[1] == 0 && b[1] == 0 && b[0] > a[0] {
        Some((0, a[0], b[0]))
    } else if a[0] == u && b[0] == u && b[1] > a[1] {
        Some((1, a[1], b[1]))
    } else if a[1] == u && b[1] == u && b[0] < a[0] {
        Some((2, u - a[0], u - b[0]))
    } else if a[0] == 0 && b[0] == 0 && b[1] < a[1] {
        Some((3, u - a[1], u - b[1]))
    } else {
        None
    }
}

/// An undirected edge key, smaller vertex first.
fn undirected(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

impl Mesh {
    /// Checks this mesh against `board`, property by property (see [`ValidationReport`]): exact,
    /// never panicking on malformed meshes.
    ///
    /// ```
    /// use orthtree::mesh::{Board, Mesh, MeshValidationError, Segment, SegmentKind};
    /// // the board U = 1 cut along its rising diagonal
    /// let board = Board::new(1, vec![]).unwrap();
    /// let side = |a, b| Segment { vertices: [a, b], kind: SegmentKind::Boundary };
    /// let mut mesh = Mesh {
    ///     vertices: vec![[0, 0], [1, 0], [1, 1], [0, 1]],
    ///     triangles: vec![[0, 1, 2], [0, 2, 3]],
    ///     regions: vec![0, 0],
    ///     segments: vec![side(0, 1), side(1, 2), side(2, 3), side(3, 0)],
    /// };
    /// let report = mesh.validate(&board);
    /// assert!(report.is_ok(), "{report}");
    /// assert_eq!(report.angle_range_deg, Some([45.0, 90.0]));
    /// mesh.triangles[1] = [0, 3, 2]; // clockwise
    /// let report = mesh.validate(&board);
    /// assert!(matches!(
    ///     report.orientation.error(),
    ///     Some(MeshValidationError::NotCounterClockwise { triangle: 1, doubled_area: -1, .. })
    /// ));
    /// ```
    ///
    /// # Complexity
    /// O(T + V) time plus O(d log d) per vertex of degree d for T triangles and V vertices
    /// (edges are paired by a counting sort), plus O(1) per mesh edge along the component edges
    /// and O(1) expected per segment.
    pub fn validate(&self, board: &Board) -> ValidationReport {
        checks::run(self, board)
    }
}

mod checks;
mod geometry;
mod input;
#[cfg(test)]
mod tests;
mod violation;
mod violation_message;

pub use violation::{BoardSide, MeshValidationError, RegionRule};
