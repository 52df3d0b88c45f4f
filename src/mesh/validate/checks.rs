//! The validator behind [`Mesh::validate`](super::Mesh::validate): the data the checks share
//! (the half-edge pairing, used vertices by position, one half-edge leaving each vertex), built
//! once, and one function per check, each taking what it reads and returning its [`Check`] with
//! what later checks need.

use super::*;
use crate::mesh::pairing::{edge_key, pair, PairDefect, Pairing, NONE};

/// What an input step makes of a half-edge: the component on its left, or on its right.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Input {
    None,
    Left(u32),
    Right(u32),
}

/// What `respects_input` found along the component edges, for `regions` and `segments`.
pub(super) struct InputEdges {
    /// The input step on each half-edge, if any.
    pub(super) sides: Vec<Input>,
    /// The mesh edges along the component edges, in board order, with their component (from 1).
    pub(super) steps: Vec<((u32, u32), u32)>,
}

/// What the checks share, built from the triangles that passed `indices` ("good"): read-only
/// once built. Half-edge `3t + i` runs from `triangles[t][i]` to `triangles[t][(i + 1) % 3]`.
pub(super) struct Validator<'m> {
    pub(super) mesh: &'m Mesh,
    pub(super) board: &'m Board,
    /// Triangles whose indices are in range and vertices inside the board.
    pub(super) good: Vec<bool>,
    /// The good triangles' half-edges sorted by edge, and their twins.
    pairing: Pairing,
    /// Used vertices sorted by position.
    pub(super) points: Vec<(Point, u32)>,
    /// One half-edge leaving each used vertex, [`NONE`] for the others.
    pub(super) leaving: Vec<u32>,
}

/// Runs every check in turn, each handed what the earlier ones produced.
pub(super) fn run(mesh: &Mesh, board: &Board) -> ValidationReport {
    let (indices, good) = indices(mesh, board);
    let v = Validator::new(mesh, board, good);
    let (orientation, area2) = v.orientation();
    let (conforming, boundary_edges) = v.conforming();
    let area = area(&area2, board.size());
    let (respects_input, input) = v.respects_input();
    let (angles, angle_range_deg) = v.angles();
    let regions = v.regions(&area2, &input.sides);
    let (euler, vertices_used, edges) = v.euler();
    let delaunay = v.delaunay(&area2);
    let segments = v.segments(&boundary_edges, &input.steps);
    ValidationReport {
        indices,
        orientation,
        conforming,
        area,
        respects_input,
        angles,
        regions,
        euler,
        delaunay,
        segments,
        vertices_used,
        edges,
        triangles: mesh.triangles.len(),
        angle_range_deg,
    }
}

/// `indices`, and which triangles are good (indices in range, vertices inside the board, and
/// few enough triangles for `u32` half-edge indices).
fn indices(mesh: &Mesh, board: &Board) -> (Check, Vec<bool>) {
    let (nv, u) = (mesh.vertices.len(), board.size());
    let mut f = Finding::default();
    f.keep(mesh.check_indices().err());
    let fits = 3 * mesh.triangles.len() < NONE as usize;
    if !fits {
        f.fail(|| MeshValidationError::TooManyTriangles {
            triangles: mesh.triangles.len(),
        });
    }
    let inside = |p: &Point| (0..=u).contains(&p[0]) && (0..=u).contains(&p[1]);
    if let Some((vertex, &point)) = mesh.vertices.iter().enumerate().find(|(_, p)| !inside(p)) {
        f.fail(|| MeshValidationError::VertexOutsideBoard {
            vertex,
            point,
            size: u,
        });
    }
    let good = (mesh.triangles.iter())
        .map(|tri| {
            fits && tri
                .iter()
                .all(|&v| mesh.vertices.get(v as usize).is_some_and(inside))
        })
        .collect();
    let (nt, ns) = (mesh.triangles.len(), mesh.segments.len());
    let check = f.finish(|| format!("{nv} vertices, {nt} triangles, {ns} segments"));
    (check, good)
}

/// `area`, from the doubled areas of the good triangles.
fn area(area2: &[i128], size: i64) -> Check {
    let total: i128 = area2.iter().sum();
    let u = i128::from(size);
    if total == 2 * u * u {
        Check::Passed(format!("{} = U^2", u * u))
    } else {
        Check::Failed(MeshValidationError::Area {
            doubled_area: total,
            size,
        })
    }
}

impl<'m> Validator<'m> {
    /// The shared data of the good triangles: paired half-edges, used vertices by position, one
    /// half-edge leaving each vertex.
    pub(super) fn new(mesh: &'m Mesh, board: &'m Board, good: Vec<bool>) -> Self {
        let nv = mesh.vertices.len();
        let pairing = pair(&mesh.triangles, nv, |t| good[t]);
        let mut used = vec![false; nv];
        let mut leaving = vec![NONE; nv];
        for (t, tri) in mesh.triangles.iter().enumerate().filter(|&(t, _)| good[t]) {
            for (i, &v) in tri.iter().enumerate() {
                used[v as usize] = true;
                leaving[v as usize] = (3 * t + i) as u32;
            }
        }
        let mut points: Vec<(Point, u32)> = (used.iter().enumerate())
            .filter(|&(_, &u)| u)
            .map(|(v, _)| (mesh.vertices[v], v as u32))
            .collect();
        points.sort_unstable();
        Validator {
            mesh,
            board,
            good,
            pairing,
            points,
            leaving,
        }
    }

    pub(super) fn point(&self, v: u32) -> Point {
        self.mesh.vertices[v as usize]
    }

    pub(super) fn tri_points(&self, t: usize) -> [Point; 3] {
        self.mesh.triangles[t].map(|v| self.point(v))
    }

    pub(super) fn origin(&self, h: u32) -> u32 {
        self.mesh.triangles[h as usize / 3][h as usize % 3]
    }

    pub(super) fn target(&self, h: u32) -> u32 {
        self.mesh.triangles[h as usize / 3][(h as usize % 3 + 1) % 3]
    }

    pub(super) fn twin(&self, h: u32) -> Option<u32> {
        Some(self.pairing.twins[h as usize]).filter(|&g| g != NONE)
    }

    /// The number of half-edges, 3 per triangle (good or not).
    pub(super) fn half_edge_count(&self) -> usize {
        self.pairing.twins.len()
    }

    /// The good triangles with their indices.
    pub(super) fn good_triangles(&self) -> impl Iterator<Item = (usize, [u32; 3])> + '_ {
        (self.mesh.triangles.iter().enumerate())
            .filter(|(t, _)| self.good[*t])
            .map(|(t, &tri)| (t, tri))
    }

    /// The half-edges (3t + i, from, to) of the good triangles.
    pub(super) fn half_edges(&self) -> impl Iterator<Item = (u32, u32, u32)> + '_ {
        self.good_triangles().flat_map(|(t, tri)| {
            (0..3).map(move |i| ((3 * t + i) as u32, tri[i], tri[(i + 1) % 3]))
        })
    }

    /// A half-edge running from `a` to `b`, if any.
    pub(super) fn find(&self, a: u32, b: u32) -> Option<u32> {
        let key = edge_key(a, b);
        let keys = &self.pairing.keys;
        let start = keys.partition_point(|&(k, _)| k < key);
        (keys[start..].iter())
            .take_while(|&&(k, _)| k == key)
            .map(|&(_, h)| h)
            .find(|&h| self.origin(h) == a)
    }

    pub(super) fn is_edge(&self, a: u32, b: u32) -> bool {
        self.find(a, b).or_else(|| self.find(b, a)).is_some()
    }

    /// The used vertex at `p`, if any.
    pub(super) fn vertex_at(&self, p: Point) -> Option<u32> {
        let i = self.points.partition_point(|&(q, _)| q < p);
        self.points
            .get(i)
            .filter(|&&(q, _)| q == p)
            .map(|&(_, v)| v)
    }

    pub(super) fn region(&self, t: usize) -> Option<u32> {
        self.mesh.regions.get(t).copied()
    }

    /// `orientation`, and the doubled signed area of each good triangle (0 for the others).
    fn orientation(&self) -> (Check, Vec<i128>) {
        let mut f = Finding::default();
        let mut area2 = vec![0; self.mesh.triangles.len()];
        for (triangle, vertices) in self.good_triangles() {
            let points = self.tri_points(triangle);
            let [a, b, c] = points;
            let doubled_area = cross(a, b, c);
            area2[triangle] = doubled_area;
            if doubled_area <= 0 {
                f.fail(|| MeshValidationError::NotCounterClockwise {
                    triangle,
                    vertices,
                    points,
                    doubled_area,
                });
            }
        }
        let check = f.finish(|| "every triangle counter-clockwise".into());
        (check, area2)
    }

    /// `conforming`: the pairing, the boundary cover and distinct vertices; and the undirected
    /// board-boundary edges, in half-edge order, for `segments`.
    fn conforming(&self) -> (Check, Vec<(u32, u32)>) {
        let mut f = Finding::default();
        f.keep(self.pairing_violation());
        let (cover, boundary_edges) = self.boundary_cover();
        f.keep(cover);
        f.keep(self.coincident_vertices());
        let n = boundary_edges.len();
        let check =
            f.finish(|| format!("interior edges paired, {n} edges cover the board boundary"));
        (check, boundary_edges)
    }

    /// The first edge whose half-edges do not pair.
    fn pairing_violation(&self) -> Option<MeshValidationError> {
        Some(match self.pairing.defect.as_ref()? {
            PairDefect::SameDirection([g, h]) => MeshValidationError::RepeatedDirectedEdge {
                from: self.origin(*g),
                to: self.target(*g),
                triangles: [g / 3, h / 3],
            },
            PairDefect::Crowded(half_edges) => MeshValidationError::EdgeInMoreThanTwoTriangles {
                edge: [self.origin(half_edges[0]), self.target(half_edges[0])],
                triangles: half_edges.iter().map(|h| h / 3).collect(),
            },
        })
    }

    /// The half-edges without twin: each must run counter-clockwise along the board boundary,
    /// and together they must cover each side exactly. The first violation, and those edges
    /// (undirected, in half-edge order).
    fn boundary_cover(&self) -> (Option<MeshValidationError>, Vec<(u32, u32)>) {
        let mut f = Finding::default();
        let u = self.board.size();
        let mut sides: [Vec<(i64, i64, u32)>; 4] = Default::default();
        let mut boundary_edges = Vec::new();
        for (h, a, b) in self
            .half_edges()
            .filter(|&(h, _, _)| self.twin(h).is_none())
        {
            let points = [self.point(a), self.point(b)];
            match boundary_side(points[0], points[1], u) {
                Some((side, s, e)) => {
                    sides[side].push((s, e, h));
                    boundary_edges.push(undirected(a, b));
                }
                None => f.fail(|| MeshValidationError::UnpairedEdge {
                    from: a,
                    to: b,
                    points,
                    triangle: h / 3,
                }),
            }
        }
        for (side, mut edges) in BoardSide::ALL.into_iter().zip(sides) {
            edges.sort_unstable();
            f.keep(side_cover(side, &edges, u));
        }
        (f.0, boundary_edges)
    }

    /// Two used vertices at one point, if any.
    pub(super) fn coincident_vertices(&self) -> Option<MeshValidationError> {
        let w = self.points.windows(2).find(|w| w[0].0 == w[1].0)?;
        Some(MeshValidationError::CoincidentVertices {
            vertices: [w[0].1, w[1].1],
            point: w[0].0,
        })
    }

    /// `regions`, from the doubled areas and the input steps on the half-edges.
    fn regions(&self, area2: &[i128], sides: &[Input]) -> Check {
        let mut f = Finding::default();
        let k = self.board.components().len() as u32;
        let mut area = vec![0i128; k as usize + 1];
        for (triangle, vertices) in self.good_triangles() {
            let Some(region) = self.region(triangle) else {
                continue;
            };
            if region > k {
                f.fail(|| MeshValidationError::RegionOutOfRange {
                    triangle,
                    vertices,
                    region,
                    components: k,
                });
            } else {
                area[region as usize] += area2[triangle];
            }
        }
        for (h, a, b) in self.half_edges() {
            f.keep(self.region_across(h, [a, b], sides[h as usize]));
        }
        for (ci, comp) in self.board.components().iter().enumerate() {
            let (got, want) = (area[ci + 1], comp.doubled_area().abs());
            if got != want {
                f.fail(|| MeshValidationError::RegionArea {
                    region: ci as u32 + 1,
                    doubled_area: got,
                    expected_doubled_area: want,
                });
            }
        }
        f.finish(|| format!("{} regions consistent", k + 1))
    }

    /// The region the triangle of half-edge `h` (running along `edge`) breaks, if any: the
    /// component on the left of an outline, the board on its right, or the same region as
    /// across a non-input edge.
    fn region_across(&self, h: u32, edge: [u32; 2], side: Input) -> Option<MeshValidationError> {
        let triangle = h as usize / 3;
        let region = self.region(triangle)?;
        let (expected, rule) = match (side, self.twin(h)) {
            (Input::Left(c), _) if region != c => (c, RegionRule::LeftOfOutline(c)),
            (Input::Right(c), _) if region != 0 => (0, RegionRule::RightOfOutline(c)),
            (Input::None, Some(g)) => match self.region(g as usize / 3) {
                Some(other) if other != region => (other, RegionRule::AcrossFrom(g / 3)),
                _ => return None,
            },
            _ => return None,
        };
        Some(MeshValidationError::WrongRegion {
            triangle,
            region,
            expected,
            edge,
            rule,
        })
    }

    /// `euler`, with the numbers of used vertices and of distinct edges.
    fn euler(&self) -> (Check, usize, usize) {
        let vertices = self.points.len();
        let edges = (self.pairing.keys).chunk_by(|x, y| x.0 == y.0).count();
        let triangles = self.good.iter().filter(|&&g| g).count();
        let chi = vertices as i64 - edges as i64 + triangles as i64;
        let check = if chi == 1 {
            Check::Passed(format!(
                "V - E + F = {vertices} - {edges} + {triangles} = {chi}"
            ))
        } else {
            Check::Failed(MeshValidationError::Euler {
                vertices,
                edges,
                triangles,
            })
        };
        (check, vertices, edges)
    }

    /// `segments`, against the board-boundary edges of `conforming` and the input steps of
    /// `respects_input`.
    fn segments(&self, boundary_edges: &[(u32, u32)], steps: &[((u32, u32), u32)]) -> Check {
        let mut f = Finding::default();
        let marked = self.marked_segments(&mut f);
        let mut expected: FastMap<((u32, u32), SegmentKind), ()> = FastMap::default();
        for &e in boundary_edges {
            expected.insert((e, SegmentKind::Boundary), ());
            if !marked.contains_key(&(e, SegmentKind::Boundary)) {
                f.fail(|| MeshValidationError::MissingBoundarySegment { edge: [e.0, e.1] });
            }
        }
        for &((a, b), component) in steps {
            let key = (undirected(a, b), SegmentKind::Component(component));
            expected.insert(key, ());
            if !marked.contains_key(&key) {
                f.fail(|| MeshValidationError::MissingOutlineSegment {
                    edge: [a, b],
                    component,
                });
            }
        }
        let nv = self.mesh.vertices.len() as u64;
        for (segment, s) in self.mesh.segments.iter().enumerate() {
            let [a, b] = s.vertices;
            let in_range = u64::from(a) < nv && u64::from(b) < nv;
            if in_range && !expected.contains_key(&(undirected(a, b), s.kind)) {
                f.fail(|| MeshValidationError::SegmentWrongKind {
                    segment,
                    vertices: s.vertices,
                    kind: s.kind,
                });
            }
        }
        f.finish(|| format!("{} segments", self.mesh.segments.len()))
    }

    /// The segments by (undirected edge, kind), each mapped to its first index; violations of
    /// the segments themselves (out of range, not a mesh edge, repeated) recorded in `f`.
    fn marked_segments(&self, f: &mut Finding) -> FastMap<((u32, u32), SegmentKind), usize> {
        let vertex_count = self.mesh.vertices.len();
        let mut marked: FastMap<((u32, u32), SegmentKind), usize> = FastMap::default();
        for (segment, s) in self.mesh.segments.iter().enumerate() {
            let [a, b] = s.vertices;
            if a as usize >= vertex_count || b as usize >= vertex_count {
                f.fail(|| MeshValidationError::SegmentVertexOutOfRange {
                    segment,
                    vertices: s.vertices,
                    vertex_count,
                });
                continue;
            }
            if !self.is_edge(a, b) {
                f.fail(|| MeshValidationError::SegmentNotEdge {
                    segment,
                    vertices: s.vertices,
                    kind: s.kind,
                });
            }
            if let Some(&j) = marked.get(&(undirected(a, b), s.kind)) {
                f.fail(|| MeshValidationError::RepeatedSegment {
                    segments: [j, segment],
                    vertices: s.vertices,
                    kind: s.kind,
                });
            } else {
                marked.insert((undirected(a, b), s.kind), segment);
            }
        }
        marked
    }
}

/// The first gap or overlap among the boundary edges on one side of the board, given as
/// (start, end, half-edge) measured along the side and sorted, or their not ending at U.
pub(super) fn side_cover(
    side: BoardSide,
    edges: &[(i64, i64, u32)],
    u: i64,
) -> Option<MeshValidationError> {
    let mut at = 0;
    for &(s, e, h) in edges {
        if s != at {
            return Some(MeshValidationError::BoundaryCover {
                side,
                at: s.min(at),
                gap: s > at,
                triangle: h / 3,
            });
        }
        at = at.max(e);
    }
    (at != u).then_some(MeshValidationError::BoundaryEnd {
        side,
        end: at,
        size: u,
    })
}
