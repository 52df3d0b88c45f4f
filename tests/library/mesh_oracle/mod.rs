//! The mesher's oracle, shared by the mesher tests: written from the definitions alone (exact
//! integer arithmetic, nothing of the crate but the mesh's plain fields). The board oracle checks
//! section 14.3's input conditions; the mesh oracle checks that the triangles tile the board, are
//! counter-clockwise, conforming and right isosceles (angles 45, 45, 90); every component
//! outline is a chain of mesh edges with its component on the left; the regions are right; the
//! segments are exactly the outline's mesh edges and the boundary edges.
#![allow(dead_code)]

use orthtree::mesh::{Board, Component, Mesh, Point, SegmentKind};
use std::collections::{HashMap, HashSet};

// ---------------------------------------------------------------------------------------------
// Exact geometry
// ---------------------------------------------------------------------------------------------

pub fn sub(a: Point, b: Point) -> Point {
    [a[0] - b[0], a[1] - b[1]]
}

pub fn cross(a: Point, b: Point) -> i128 {
    a[0] as i128 * b[1] as i128 - a[1] as i128 * b[0] as i128
}

pub fn dot(a: Point, b: Point) -> i128 {
    a[0] as i128 * b[0] as i128 + a[1] as i128 * b[1] as i128
}

/// Orientation of `c` relative to the line `a -> b`: 1 left, -1 right, 0 on it.
pub fn orient(a: Point, b: Point, c: Point) -> i32 {
    cross(sub(b, a), sub(c, a)).signum() as i32
}

/// `true` when `c`, known to be on the line through `a` and `b`, lies within their box.
pub fn within(a: Point, b: Point, c: Point) -> bool {
    (0..2).all(|k| a[k].min(b[k]) <= c[k] && c[k] <= a[k].max(b[k]))
}

/// `true` when the closed segments `ab` and `cd` share a point.
pub fn segments_meet(a: Point, b: Point, c: Point, d: Point) -> bool {
    let (o1, o2, o3, o4) = (
        orient(a, b, c),
        orient(a, b, d),
        orient(c, d, a),
        orient(c, d, b),
    );
    if o1 * o2 < 0 && o3 * o4 < 0 {
        return true;
    }
    (o1 == 0 && within(a, b, c))
        || (o2 == 0 && within(a, b, d))
        || (o3 == 0 && within(c, d, a))
        || (o4 == 0 && within(c, d, b))
}

/// Crossing-number test; `p` must not lie on the outline.
pub fn inside(outline: &[Point], p: Point) -> bool {
    let mut odd = false;
    for i in 0..outline.len() {
        let (a, b) = (outline[i], outline[(i + 1) % outline.len()]);
        if (a[1] > p[1]) != (b[1] > p[1]) {
            // x of the edge at height p[1], compared exactly: p is left of the crossing when
            // (p - a) x (b - a) has the sign that puts the crossing to the right.
            let c = cross(sub(b, a), sub(p, a));
            if (c > 0) == (b[1] > a[1]) {
                odd = !odd;
            }
        }
    }
    odd
}

/// Bounding box of an outline.
pub fn bbox(outline: &[Point]) -> (Point, Point) {
    let lo = [0, 1].map(|k| outline.iter().map(|p| p[k]).min().unwrap());
    let hi = [0, 1].map(|k| outline.iter().map(|p| p[k]).max().unwrap());
    (lo, hi)
}

pub fn edges(outline: &[Point]) -> impl Iterator<Item = (Point, Point)> + '_ {
    (0..outline.len()).map(move |i| (outline[i], outline[(i + 1) % outline.len()]))
}

pub fn doubled_area(outline: &[Point]) -> i128 {
    edges(outline).map(|(a, b)| cross(a, b)).sum()
}

/// The lattice points of an edge at 0, 45, 90 or 135 degrees that are multiples of `g`, from
/// `a` to `b` (both multiples of `g`).
pub fn points_on(a: Point, b: Point, g: i64) -> impl Iterator<Item = Point> {
    let d = [(b[0] - a[0]).signum(), (b[1] - a[1]).signum()];
    let n = (b[0] - a[0]).abs().max((b[1] - a[1]).abs()) / g;
    (0..=n).map(move |t| [a[0] + t * g * d[0], a[1] + t * g * d[1]])
}

/// The largest power of two dividing U and every vertex coordinate of the board.
pub fn grid_unit(board: &Board) -> i64 {
    let mut g = board.size();
    for c in board.components() {
        for p in &c.outline {
            for x in p {
                while x % g != 0 {
                    g /= 2;
                }
            }
        }
    }
    g
}

// ---------------------------------------------------------------------------------------------
// Board oracle: the chapter's input conditions, checked from scratch
// ---------------------------------------------------------------------------------------------

/// Panics unless `board` meets section 14.3's conditions: vertices in [0, U]^2, edges at 0, 45, 90
/// or 135 degrees, simple counter-clockwise outlines without collinear vertices, and pairwise
/// disjoint components (no shared point, none inside another).
pub fn assert_valid_board(board: &Board) {
    let u = board.size();
    assert!(u >= 1 && u & (u - 1) == 0);
    let comps = board.components();
    for (i, c) in comps.iter().enumerate() {
        let o = &c.outline;
        assert!(o.len() >= 3, "component {i}: fewer than 3 vertices");
        assert!(doubled_area(o) > 0, "component {i}: not counter-clockwise");
        for (k, (a, b)) in edges(o).enumerate() {
            assert!(
                (0..2).all(|x| (0..=u).contains(&a[x])),
                "component {i}: vertex {a:?} out of range"
            );
            let d = sub(b, a);
            assert!(
                d != [0, 0] && (d[0] == 0 || d[1] == 0 || d[0].abs() == d[1].abs()),
                "component {i} edge {k}: {a:?} -> {b:?} has a bad angle"
            );
            let next = sub(o[(k + 2) % o.len()], b);
            assert!(cross(d, next) != 0, "component {i}: collinear vertex {b:?}");
        }
        let n = o.len();
        for k in 0..n {
            for l in k + 2..n {
                if k == 0 && l == n - 1 {
                    continue;
                }
                let (a, b) = (o[k], o[(k + 1) % n]);
                let (c, d) = (o[l], o[(l + 1) % n]);
                assert!(
                    !segments_meet(a, b, c, d),
                    "component {i}: edges {k} and {l} meet"
                );
            }
        }
    }
    let boxes: Vec<_> = comps.iter().map(|c| bbox(&c.outline)).collect();
    for i in 0..comps.len() {
        for j in i + 1..comps.len() {
            let ((l1, h1), (l2, h2)) = (boxes[i], boxes[j]);
            if h1[0] < l2[0] || h2[0] < l1[0] || h1[1] < l2[1] || h2[1] < l1[1] {
                continue;
            }
            let (a, b) = (&comps[i].outline, &comps[j].outline);
            for (p, q) in edges(a) {
                for (r, s) in edges(b) {
                    assert!(
                        !segments_meet(p, q, r, s),
                        "components {i} and {j} touch: {p:?}-{q:?} and {r:?}-{s:?}"
                    );
                }
            }
            assert!(!inside(b, a[0]), "component {i} inside component {j}");
            assert!(!inside(a, b[0]), "component {j} inside component {i}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Mesh oracle
// ---------------------------------------------------------------------------------------------

/// What the mesh oracle counted.
#[derive(Debug, Default)]
pub struct Stats {
    pub triangles: usize,
    pub vertices: usize,
    pub right_angles: usize,
    pub half_right_angles: usize,
    pub boundary_edges: usize,
    /// Mesh edges along the component outlines.
    pub outline_edges: usize,
    /// Their total length in lattice steps (a diagonal step counts one).
    pub outline_length: i64,
}

/// Panics unless `mesh` is a correct mesh of `board` (see the file doc). Independent of the
/// crate's own validation: only the mesh's fields and the board's outlines are used.
pub fn assert_valid_mesh(board: &Board, mesh: &Mesh) -> Stats {
    let u = board.size();
    let comps = board.components();
    let v = &mesh.vertices;
    let mut stats = Stats {
        triangles: mesh.triangles.len(),
        vertices: v.len(),
        ..Stats::default()
    };

    // Vertices: distinct lattice points of the board. The outlines are walked in steps of g, a
    // power of two dividing every vertex coordinate of the board and of the mesh.
    let g = v.iter().flatten().fold(grid_unit(board), |g, &x| {
        g.min(1 << x.trailing_zeros().min(62))
    });
    let index: HashMap<Point, u32> = v.iter().enumerate().map(|(i, &p)| (p, i as u32)).collect();
    assert_eq!(index.len(), v.len(), "duplicate vertices");
    assert!(
        v.iter().all(|p| (0..2).all(|k| (0..=u).contains(&p[k]))),
        "vertex out of range"
    );

    // Triangles: counter-clockwise, right isosceles, tiling an area of U^2.
    assert_eq!(
        mesh.regions.len(),
        mesh.triangles.len(),
        "one region per triangle"
    );
    let mut area2: i128 = 0;
    let mut directed: HashMap<(u32, u32), usize> = HashMap::with_capacity(3 * mesh.triangles.len());
    for (t, tri) in mesh.triangles.iter().enumerate() {
        assert!(
            tri.iter().all(|&i| (i as usize) < v.len()),
            "triangle {t}: bad index"
        );
        let p = tri.map(|i| v[i as usize]);
        let a2 = cross(sub(p[1], p[0]), sub(p[2], p[0]));
        assert!(a2 > 0, "triangle {t} {p:?} is not counter-clockwise");
        area2 += a2;
        for k in 0..3 {
            let (o, b, c) = (p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
            let (e, f) = (sub(b, o), sub(c, o));
            let (d, x) = (dot(e, f), cross(e, f));
            if d == 0 {
                stats.right_angles += 1;
            } else if d == x {
                stats.half_right_angles += 1;
            } else {
                panic!("triangle {t} {p:?}: angle at {o:?} is neither 45 nor 90 degrees");
            }
            let prev = directed.insert((tri[k], tri[(k + 1) % 3]), t);
            assert!(prev.is_none(), "directed edge {:?} used twice", (b, c));
        }
    }
    assert_eq!(
        area2,
        2 * (u as i128) * (u as i128),
        "triangles do not tile the board"
    );
    assert_eq!(stats.right_angles, mesh.triangles.len());

    // Conforming: a directed edge without a twin is on the board boundary (and vice versa: no
    // twin can exist there), and those edges cover the boundary's length 4U exactly. With the
    // area and the orientation this makes the triangles a conforming tiling of the square.
    let on_side = |a: Point, b: Point| {
        (a[0] == b[0] && (a[0] == 0 || a[0] == u)) || (a[1] == b[1] && (a[1] == 0 || a[1] == u))
    };
    let mut boundary: HashSet<(Point, Point)> = HashSet::new();
    let mut length = 0;
    for &(a, b) in directed.keys() {
        let (pa, pb) = (v[a as usize], v[b as usize]);
        let twin = directed.contains_key(&(b, a));
        assert_eq!(
            !twin,
            on_side(pa, pb),
            "edge {pa:?}-{pb:?}: twin {twin} but on boundary {}",
            on_side(pa, pb)
        );
        if !twin {
            length += (pa[0] - pb[0]).abs() + (pa[1] - pb[1]).abs();
            boundary.insert((pa.min(pb), pa.max(pb)));
        }
    }
    assert_eq!(length, 4 * u, "boundary edges do not cover the boundary");
    stats.boundary_edges = boundary.len();

    // Regions: each component's triangles have its area; each outline step has the component on
    // its left and the board (region 0) on its right, unless it lies on the board boundary.
    assert!(
        mesh.regions.iter().all(|&r| r as usize <= comps.len()),
        "region out of range"
    );
    let mut region_area = vec![0i128; comps.len() + 1];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let p = tri.map(|i| v[i as usize]);
        region_area[mesh.regions[t] as usize] += cross(sub(p[1], p[0]), sub(p[2], p[0]));
    }
    let mut outline_steps: HashSet<(Point, Point, u32)> = HashSet::new();
    for (i, c) in comps.iter().enumerate() {
        let r = i as u32 + 1;
        assert_eq!(
            region_area[r as usize],
            doubled_area(&c.outline),
            "area of region {r}"
        );
        for (a, b) in edges(&c.outline) {
            // The mesh vertices on the edge, in order: every vertex is a multiple of g, and
            // consecutive ones must be joined by a mesh edge (a vertex inside it would be a
            // T-junction, which the conformity check above rules out).
            let chain: Vec<(Point, u32)> = points_on(a, b, g)
                .filter_map(|p| index.get(&p).map(|&i| (p, i)))
                .collect();
            assert!(
                chain.first().map(|x| x.0) == Some(a) && chain.last().map(|x| x.0) == Some(b),
                "component {r}: an end of {a:?}-{b:?} is not a mesh vertex"
            );
            for w in chain.windows(2) {
                let ((p, ip), (q, iq)) = (w[0], w[1]);
                let left = directed.get(&(ip, iq));
                let left = left.unwrap_or_else(|| panic!("component {r}: {p:?}-{q:?} not an edge"));
                assert_eq!(
                    mesh.regions[*left], r,
                    "left of {p:?}-{q:?} is not region {r}"
                );
                match directed.get(&(iq, ip)) {
                    Some(&right) => assert_eq!(mesh.regions[right], 0, "right of {p:?}-{q:?}"),
                    None => assert!(on_side(p, q)),
                }
                if outline_steps.insert((p.min(q), p.max(q), r)) {
                    stats.outline_length += (q[0] - p[0]).abs().max((q[1] - p[1]).abs());
                }
            }
        }
    }
    stats.outline_edges = outline_steps.len();

    // Every triangle's centroid lies in its region's outline (and in no outline for region 0).
    let boxes: Vec<_> = comps.iter().map(|c| bbox(&c.outline)).collect();
    let scaled: Vec<Vec<Point>> = comps
        .iter()
        .map(|c| c.outline.iter().map(|p| [3 * p[0], 3 * p[1]]).collect())
        .collect();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let p = tri.map(|i| v[i as usize]);
        let g3 = [p[0][0] + p[1][0] + p[2][0], p[0][1] + p[1][1] + p[2][1]];
        let mut containing = (0..comps.len()).filter(|&i| {
            let (lo, hi) = boxes[i];
            (0..2).all(|k| 3 * lo[k] < g3[k] && g3[k] < 3 * hi[k]) && inside(&scaled[i], g3)
        });
        let expect = containing.next().map_or(0, |i| i as u32 + 1);
        assert_eq!(containing.next(), None);
        assert_eq!(
            mesh.regions[t], expect,
            "triangle {t} {p:?} has the wrong region"
        );
    }

    // Segments: exactly the outline steps (kind Component(r)) and the boundary edges, each once.
    let mut seen_outline = HashSet::new();
    let mut seen_boundary = HashSet::new();
    for s in &mesh.segments {
        let [a, b] = s.vertices.map(|i| v[i as usize]);
        let key = (a.min(b), a.max(b));
        match s.kind {
            SegmentKind::Boundary => {
                assert!(
                    boundary.contains(&key),
                    "boundary segment {key:?} is not on it"
                );
                assert!(seen_boundary.insert(key), "boundary segment {key:?} twice");
            }
            SegmentKind::Component(r) => {
                assert!(
                    outline_steps.contains(&(key.0, key.1, r)),
                    "segment {key:?} of {r}"
                );
                assert!(
                    seen_outline.insert((key.0, key.1, r)),
                    "segment {key:?} twice"
                );
            }
        }
    }
    assert_eq!(
        seen_boundary.len(),
        boundary.len(),
        "boundary segments missing"
    );
    assert_eq!(
        seen_outline.len(),
        outline_steps.len(),
        "outline segments missing"
    );
    stats
}

/// A valid board of side `size` with the given outlines.
pub fn board(size: i64, outlines: &[&[Point]]) -> Board {
    let comps = outlines
        .iter()
        .map(|o| Component::new(o.to_vec()))
        .collect();
    Board::new(size, comps).expect("valid test board")
}

/// Figure 14.2's input scaled to U = 2^j: a unit square at distance 1 from the left and top
/// sides, [1, 2] x [U - 2, U - 1].
pub fn figure_14_2(j: u32) -> Board {
    let u = 1i64 << j;
    board(u, &[&[[1, u - 2], [2, u - 2], [2, u - 1], [1, u - 1]]])
}
