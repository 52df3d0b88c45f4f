//! The validator behind [`Mesh::validate`](super::Mesh::validate): one method per check, sharing
//! the edge pairing (by sorting) and the lookups the checks need.

use super::*;

pub(super) const NONE: u32 = u32::MAX;

/// What an input step makes of a half-edge: the component on its left, or on its right.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Input {
    None,
    Left(u32),
    Right(u32),
}

/// State shared by the checks. Half-edge `3t + i` runs from `triangles[t][i]` to
/// `triangles[t][(i + 1) % 3]`; edges are found by sorting, not hashing, which keeps the
/// validation of a mesh with a million triangles well under a second.
pub(super) struct Validator<'m> {
    pub(super) mesh: &'m Mesh,
    pub(super) board: &'m Board,
    /// Triangles whose indices are in range and vertices inside the board.
    pub(super) good: Vec<bool>,
    /// Doubled signed area of each good triangle (0 for the others).
    pub(super) area2: Vec<i128>,
    /// (undirected edge key, half-edge) of the good triangles' half-edges, sorted.
    pub(super) keys: Vec<(u64, u32)>,
    /// The opposite half-edge of each half-edge, [`NONE`] if there is none (or more than one).
    pub(super) twins: Vec<u32>,
    /// Used vertices sorted by position.
    pub(super) points: Vec<(Point, u32)>,
    /// Undirected board-boundary edges, in half-edge order.
    pub(super) boundary_edges: Vec<(u32, u32)>,
    /// The input step on each half-edge, if any.
    pub(super) input: Vec<Input>,
    /// The mesh edges along the component edges, in board order, with their component (from 1).
    pub(super) input_steps: Vec<((u32, u32), u32)>,
    /// One half-edge leaving each used vertex, [`NONE`] for the others.
    pub(super) leaving: Vec<u32>,
}

/// Sorts (edge key, half-edge) pairs as `sort_unstable` would: a counting sort on the edge's
/// smaller vertex (the key's high half, below `vertices`), then a sort of each vertex's few edges.
/// O(n + V) plus O(d log d) per vertex of degree d.
fn sort_edge_keys(keys: Vec<(u64, u32)>, vertices: usize) -> Vec<(u64, u32)> {
    let mut start = vec![0usize; vertices + 1];
    for k in &keys {
        start[(k.0 >> 32) as usize + 1] += 1;
    }
    for v in 0..vertices {
        start[v + 1] += start[v];
    }
    let mut out = vec![(0u64, 0u32); keys.len()];
    let mut next = start.clone();
    for k in keys {
        let b = (k.0 >> 32) as usize;
        out[next[b]] = k;
        next[b] += 1;
    }
    for v in 0..vertices {
        out[start[v]..start[v + 1]].sort_unstable();
    }
    out
}

/// The sort key of an undirected edge.
fn edge_key(a: u32, b: u32) -> u64 {
    (u64::from(a.min(b)) << 32) | u64::from(a.max(b))
}

impl<'m> Validator<'m> {
    pub(super) fn new(mesh: &'m Mesh, board: &'m Board) -> Self {
        Validator {
            mesh,
            board,
            good: Vec::new(),
            area2: Vec::new(),
            keys: Vec::new(),
            twins: Vec::new(),
            points: Vec::new(),
            boundary_edges: Vec::new(),
            input: Vec::new(),
            input_steps: Vec::new(),
            leaving: Vec::new(),
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
        Some(self.twins[h as usize]).filter(|&g| g != NONE)
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
        let start = self.keys.partition_point(|&(k, _)| k < key);
        (self.keys[start..].iter())
            .take_while(|&&(k, _)| k == key)
            .map(|&(_, h)| h)
            .find(|&h| self.origin(h) == a)
    }

    pub(super) fn is_edge(&self, a: u32, b: u32) -> bool {
        let key = edge_key(a, b);
        let i = self.keys.partition_point(|&(k, _)| k < key);
        self.keys.get(i).is_some_and(|&(k, _)| k == key)
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

    pub(super) fn run(mut self) -> ValidationReport {
        let indices = self.indices();
        let orientation = self.orientation();
        let conforming = self.conforming();
        let area = self.area();
        let respects_input = self.respects_input();
        let (angles, angle_range_deg) = self.angles();
        let regions = self.regions();
        let (euler, vertices_used, edges) = self.euler();
        let delaunay = self.delaunay();
        let segments = self.segments();
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
            triangles: self.mesh.triangles.len(),
            angle_range_deg,
        }
    }

    fn indices(&mut self) -> Check {
        let mesh = self.mesh;
        let (nv, u) = (mesh.vertices.len(), self.board.size());
        let mut f = Finding::default();
        if let Err(problem) = mesh.check_indices() {
            f.fail(|| problem);
        }
        if 3 * mesh.triangles.len() >= NONE as usize {
            f.fail(|| format!("{} triangles: too many to check", mesh.triangles.len()));
        }
        let inside = |p: &Point| (0..=u).contains(&p[0]) && (0..=u).contains(&p[1]);
        if let Some((v, p)) = mesh.vertices.iter().enumerate().find(|(_, p)| !inside(p)) {
            f.fail(|| format!("vertex {v} at {p:?} lies outside the board [0, {u}]^2"));
        }
        let fits = 3 * mesh.triangles.len() < NONE as usize;
        self.good = (mesh.triangles.iter())
            .map(|tri| {
                fits && tri
                    .iter()
                    .all(|&v| mesh.vertices.get(v as usize).is_some_and(inside))
            })
            .collect();
        f.finish(|| {
            format!(
                "{} vertices, {} triangles, {} segments",
                nv,
                mesh.triangles.len(),
                mesh.segments.len()
            )
        })
    }

    fn orientation(&mut self) -> Check {
        let mut f = Finding::default();
        let mut area2 = vec![0; self.mesh.triangles.len()];
        for (t, tri) in self.good_triangles() {
            let [a, b, c] = self.tri_points(t);
            let a2 = cross(a, b, c);
            area2[t] = a2;
            if a2 <= 0 {
                let what = if a2 == 0 { "degenerate" } else { "clockwise" };
                f.fail(|| {
                    format!(
                        "triangle {t} {tri:?} at {a:?}, {b:?}, {c:?} is {what} (doubled area {a2})"
                    )
                });
            }
        }
        self.area2 = area2;
        f.finish(|| "every triangle counter-clockwise".into())
    }

    fn conforming(&mut self) -> Check {
        let mut f = Finding::default();
        let u = self.board.size();
        let keys: Vec<(u64, u32)> = self
            .half_edges()
            .map(|(h, a, b)| (edge_key(a, b), h))
            .collect();
        let keys = sort_edge_keys(keys, self.mesh.vertices.len());
        let mut twins = vec![NONE; 3 * self.mesh.triangles.len()];
        for group in keys.chunk_by(|x, y| x.0 == y.0) {
            let (g, h) = (group[0].1, group.get(1).map_or(NONE, |x| x.1));
            if group.len() > 2 {
                let (a, b) = (self.origin(g), self.target(g));
                f.fail(|| {
                    let ts: Vec<u32> = group.iter().map(|x| x.1 / 3).collect();
                    format!("edge {a}-{b} belongs to {} triangles {ts:?}", ts.len())
                });
            } else if h != NONE && self.origin(g) == self.origin(h) {
                let (a, b) = (self.origin(g), self.target(g));
                f.fail(|| {
                    format!(
                        "triangles {} and {} both use the directed edge {a} -> {b}",
                        g / 3,
                        h / 3
                    )
                });
            } else if h != NONE {
                twins[g as usize] = h;
                twins[h as usize] = g;
            }
        }
        self.keys = keys;
        self.twins = twins;

        let mut sides: [Vec<(i64, i64, u32)>; 4] = Default::default();
        let mut boundary_edges = Vec::new();
        for (h, a, b) in self.half_edges() {
            if self.twins[h as usize] != NONE {
                continue;
            }
            let (pa, pb) = (self.point(a), self.point(b));
            match boundary_side(pa, pb, u) {
                Some((side, s, e)) => {
                    sides[side].push((s, e, h));
                    boundary_edges.push(undirected(a, b));
                }
                None => f.fail(|| {
                    format!(
                        "edge {a} -> {b} ({pa:?} -> {pb:?}) of triangle {} has no triangle on \
                         its other side and does not run counter-clockwise along the board boundary",
                        h / 3
                    )
                }),
            }
        }
        self.boundary_edges = boundary_edges;
        for (side, edges) in sides.iter_mut().enumerate() {
            edges.sort_unstable();
            let mut at = 0;
            for &(s, e, h) in edges.iter() {
                if s != at {
                    let what = if s > at { "a gap" } else { "an overlap" };
                    f.fail(|| {
                        format!(
                            "the boundary edges on the {} side have {what} at {} (triangle {})",
                            SIDES[side],
                            s.min(at),
                            h / 3
                        )
                    });
                }
                at = at.max(e);
            }
            if at != u {
                f.fail(|| {
                    format!(
                        "the boundary edges on the {} side end at {at}, not at U = {u}",
                        SIDES[side]
                    )
                });
            }
        }

        let mut used = vec![false; self.mesh.vertices.len()];
        for (_, tri) in self.good_triangles() {
            for v in tri {
                used[v as usize] = true;
            }
        }
        let mut points: Vec<(Point, u32)> = (used.iter().enumerate())
            .filter(|(_, &u)| u)
            .map(|(v, _)| (self.point(v as u32), v as u32))
            .collect();
        points.sort_unstable();
        if let Some(w) = points.windows(2).find(|w| w[0].0 == w[1].0) {
            f.fail(|| {
                format!(
                    "vertices {} and {} are both at {:?}",
                    w[0].1, w[1].1, w[0].0
                )
            });
        }
        self.points = points;
        f.finish(|| {
            format!(
                "interior edges paired, {} edges cover the board boundary",
                self.boundary_edges.len()
            )
        })
    }

    fn area(&self) -> Check {
        let total: i128 = self.area2.iter().sum();
        let u = self.board.size() as i128;
        if total == 2 * u * u {
            Check::pass(format!("{} = U^2", u * u))
        } else {
            Check {
                ok: false,
                message: format!(
                    "the triangles cover area {}, not U^2 = {}",
                    half(total),
                    u * u
                ),
            }
        }
    }

    fn regions(&self) -> Check {
        let mut f = Finding::default();
        let k = self.board.components().len() as u32;
        let mut area = vec![0i128; k as usize + 1];
        for (t, tri) in self.good_triangles() {
            let Some(r) = self.region(t) else { continue };
            if r > k {
                f.fail(|| {
                    format!("triangle {t} {tri:?} has region {r}, but the board has {k} components")
                });
            } else {
                area[r as usize] += self.area2[t];
            }
        }
        for (h, a, b) in self.half_edges() {
            let t = h as usize / 3;
            let Some(r) = self.region(t) else { continue };
            let (expected, why) = match (self.input[h as usize], self.twin(h)) {
                (Input::Left(c), _) if r != c => (c, format!("left of component {c}'s outline")),
                (Input::Right(c), _) if r != 0 => (0, format!("right of component {c}'s outline")),
                (Input::None, Some(g)) => match self.region(g as usize / 3) {
                    Some(other) if other != r => (
                        other,
                        format!("across a non-input edge from triangle {}", g / 3),
                    ),
                    _ => continue,
                },
                _ => continue,
            };
            f.fail(|| {
                format!(
                    "triangle {t} has region {r}, but it lies {why} (edge {a} -> {b}), so \
                     region {expected}"
                )
            });
        }
        for (ci, comp) in self.board.components().iter().enumerate() {
            let (got, want) = (area[ci + 1], comp.doubled_area().abs());
            if got != want {
                f.fail(|| {
                    format!(
                        "the triangles of region {} cover area {}, component {} has area {}",
                        ci + 1,
                        half(got),
                        ci + 1,
                        half(want)
                    )
                });
            }
        }
        f.finish(|| format!("{} regions consistent", k + 1))
    }

    fn euler(&self) -> (Check, usize, usize) {
        let v = self.points.len();
        let e = self.keys.chunk_by(|x, y| x.0 == y.0).count();
        let t = self.good.iter().filter(|&&g| g).count();
        let chi = v as i64 - e as i64 + t as i64;
        let text = format!("V - E + F = {v} - {e} + {t} = {chi}");
        let check = if chi == 1 {
            Check::pass(text)
        } else {
            Check {
                ok: false,
                message: format!("{text}, not 1"),
            }
        };
        (check, v, e)
    }

    fn segments(&self) -> Check {
        let mut f = Finding::default();
        let nv = self.mesh.vertices.len() as u64;
        let mut marked: FastMap<((u32, u32), SegmentKind), usize> = FastMap::default();
        for (k, s) in self.mesh.segments.iter().enumerate() {
            let [a, b] = s.vertices;
            if u64::from(a) >= nv || u64::from(b) >= nv {
                f.fail(|| {
                    format!(
                        "segment {k} {:?} refers to a vertex out of range",
                        s.vertices
                    )
                });
                continue;
            }
            if !self.is_edge(a, b) {
                f.fail(|| format!("segment {k} {a}-{b} ({:?}) is not a mesh edge", s.kind));
            }
            if let Some(&j) = marked.get(&(undirected(a, b), s.kind)) {
                f.fail(|| format!("segments {j} and {k} both mark {a}-{b} as {:?}", s.kind));
            } else {
                marked.insert((undirected(a, b), s.kind), k);
            }
        }
        let mut expected: FastMap<((u32, u32), SegmentKind), ()> = FastMap::default();
        for &e in &self.boundary_edges {
            expected.insert((e, SegmentKind::Boundary), ());
            if !marked.contains_key(&(e, SegmentKind::Boundary)) {
                f.fail(|| {
                    format!(
                        "board boundary edge {}-{} has no Boundary segment",
                        e.0, e.1
                    )
                });
            }
        }
        for &((a, b), c) in &self.input_steps {
            let key = (undirected(a, b), SegmentKind::Component(c));
            expected.insert(key, ());
            if !marked.contains_key(&key) {
                f.fail(|| format!("edge {a}-{b} of component {c}'s outline has no segment"));
            }
        }
        for (k, s) in self.mesh.segments.iter().enumerate() {
            let [a, b] = s.vertices;
            let in_range = u64::from(a) < nv && u64::from(b) < nv;
            if in_range && !expected.contains_key(&(undirected(a, b), s.kind)) {
                let what = match s.kind {
                    SegmentKind::Boundary => "the board boundary".to_string(),
                    SegmentKind::Component(c) => format!("component {c}'s outline"),
                };
                f.fail(|| format!("segment {k} {a}-{b} is marked as on {what}, but is not"));
            }
        }
        f.finish(|| format!("{} segments", self.mesh.segments.len()))
    }
}
