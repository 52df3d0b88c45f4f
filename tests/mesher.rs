//! The circuit-board mesher (`generate_mesh`, the chapter's section 14.3) on the chapter's
//! Figure 14.2 family (exercise 14.1), on the built-in `sample_board`, on seeded `random_board`s
//! and on edge cases, checked by an oracle written here from the definitions alone (exact integer
//! arithmetic, nothing of the crate but the mesh's plain fields): the triangles tile the board,
//! are counter-clockwise, conforming and right isosceles (angles 45, 45, 90); every component
//! outline is a chain of mesh edges with its component on the left; the regions are right; the
//! segments are exactly the outline steps and the boundary edges. Also Theorem 14.5's size bound.
//!
//! Run with `--nocapture` to see the measured counts.

use orthtree::mesh::{
    generate_mesh, random_board, sample_board, Board, Component, Mesh, MeshOutcome, Point,
    SegmentKind,
};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use std::collections::{HashMap, HashSet};

// ---------------------------------------------------------------------------------------------
// Exact geometry
// ---------------------------------------------------------------------------------------------

fn sub(a: Point, b: Point) -> Point {
    [a[0] - b[0], a[1] - b[1]]
}

fn cross(a: Point, b: Point) -> i128 {
    a[0] as i128 * b[1] as i128 - a[1] as i128 * b[0] as i128
}

fn dot(a: Point, b: Point) -> i128 {
    a[0] as i128 * b[0] as i128 + a[1] as i128 * b[1] as i128
}

/// Orientation of `c` relative to the line `a -> b`: 1 left, -1 right, 0 on it.
fn orient(a: Point, b: Point, c: Point) -> i32 {
    cross(sub(b, a), sub(c, a)).signum() as i32
}

/// `true` when `c`, known to be on the line through `a` and `b`, lies within their box.
fn within(a: Point, b: Point, c: Point) -> bool {
    (0..2).all(|k| a[k].min(b[k]) <= c[k] && c[k] <= a[k].max(b[k]))
}

/// `true` when the closed segments `ab` and `cd` share a point.
fn segments_meet(a: Point, b: Point, c: Point, d: Point) -> bool {
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
fn inside(outline: &[Point], p: Point) -> bool {
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
fn bbox(outline: &[Point]) -> (Point, Point) {
    let lo = [0, 1].map(|k| outline.iter().map(|p| p[k]).min().unwrap());
    let hi = [0, 1].map(|k| outline.iter().map(|p| p[k]).max().unwrap());
    (lo, hi)
}

fn edges(outline: &[Point]) -> impl Iterator<Item = (Point, Point)> + '_ {
    (0..outline.len()).map(move |i| (outline[i], outline[(i + 1) % outline.len()]))
}

fn doubled_area(outline: &[Point]) -> i128 {
    edges(outline).map(|(a, b)| cross(a, b)).sum()
}

/// The unit lattice steps of an edge at 0, 45, 90 or 135 degrees.
fn steps(a: Point, b: Point) -> impl Iterator<Item = (Point, Point)> {
    let d = [(b[0] - a[0]).signum(), (b[1] - a[1]).signum()];
    let n = (b[0] - a[0]).abs().max((b[1] - a[1]).abs());
    (0..n).map(move |t| {
        let p = [a[0] + t * d[0], a[1] + t * d[1]];
        (p, [p[0] + d[0], p[1] + d[1]])
    })
}

// ---------------------------------------------------------------------------------------------
// Board oracle: the chapter's input conditions, checked from scratch
// ---------------------------------------------------------------------------------------------

/// Panics unless `board` meets section 14.3's conditions: vertices in [0, U]^2, edges at 0, 45, 90
/// or 135 degrees, simple counter-clockwise outlines without collinear vertices, and pairwise
/// disjoint components (no shared point, none inside another).
fn assert_valid_board(board: &Board) {
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
struct Stats {
    triangles: usize,
    vertices: usize,
    right_angles: usize,
    half_right_angles: usize,
    boundary_edges: usize,
    outline_steps: usize,
}

/// Panics unless `mesh` is a correct mesh of `board` (see the file doc). Independent of the
/// crate's own validation: only the mesh's fields and the board's outlines are used.
fn assert_valid_mesh(board: &Board, mesh: &Mesh) -> Stats {
    let u = board.size();
    let comps = board.components();
    let v = &mesh.vertices;
    let mut stats = Stats {
        triangles: mesh.triangles.len(),
        vertices: v.len(),
        ..Stats::default()
    };

    // Vertices: distinct lattice points of the board.
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
            for (p, q) in steps(a, b) {
                let (Some(&ip), Some(&iq)) = (index.get(&p), index.get(&q)) else {
                    panic!("component {r}: outline point {p:?} or {q:?} is not a mesh vertex");
                };
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
                outline_steps.insert((p.min(q), p.max(q), r));
            }
        }
    }
    stats.outline_steps = outline_steps.len();

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

/// Meshes `board`, checks board and mesh with the oracles and with the crate's own
/// `Mesh::validate`, and returns the outcome and the oracle's counts.
fn mesh_and_check(board: &Board) -> (MeshOutcome, Stats) {
    assert_valid_board(board);
    let out = generate_mesh(board).expect("a valid board meshes");
    let report = out.mesh.validate(board);
    assert!(report.is_ok(), "{report}");
    let stats = assert_valid_mesh(board, &out.mesh);
    assert_eq!(stats.triangles, report.triangles);
    (out, stats)
}

fn board(size: i64, outlines: &[&[Point]]) -> Board {
    let comps = outlines
        .iter()
        .map(|o| Component::new(o.to_vec()))
        .collect();
    Board::new(size, comps).expect("valid test board")
}

/// Number of triangles in each region 0..=components.
fn region_counts(board: &Board, mesh: &Mesh) -> Vec<usize> {
    let mut n = vec![0; board.components().len() + 1];
    for &r in &mesh.regions {
        n[r as usize] += 1;
    }
    n
}

// ---------------------------------------------------------------------------------------------
// Figure 14.2 and exercise 14.1
// ---------------------------------------------------------------------------------------------

/// Figure 14.2's input scaled to U = 2^j: a unit square at distance 1 from the left and top
/// sides, [1, 2] x [U - 2, U - 1].
fn figure_14_2(j: u32) -> Board {
    let u = 1i64 << j;
    board(u, &[&[[1, u - 2], [2, u - 2], [2, u - 1], [1, u - 1]]])
}

/// Exercise 14.1, for the uniform mesh and for the chapter's algorithm (GENERATEMESH).
///
/// Uniform: U^2 unit cells, two triangles each: 2 * 4^j (512 at j = 4, as in the figure).
///
/// GENERATEMESH: 28 j - 18 triangles for j >= 3 (94 at j = 4; the figure's hand-drawn
/// non-uniform mesh has 52, the algorithm refines more). Measure y' = U - y downwards from the
/// top side, so the square is [1, 2] x [1, 2] and B_s = [0, s]^2 is the top-left cell of side s.
///
/// Before balance: B_s meets the closed square for every s, and for s >= 8 no other child of
/// B_s does (the square lies inside B_{s/2}); at s = 4 all four children of B_4 meet it (at x = 2,
/// y' = 2 or the corner), so they become 16 unit cells. Leaves: 3 per level for s = U/2 .. 8, plus
/// 16: 3 j + 10.
///
/// After balance (face connectivity), per level s = 4, 8, .., U/4 (j - 3 levels) the leaves of
/// side s are: Q = the south-east child of B_{2s}; and the east sibling E = [2s, 4s] x [0, 2s] of
/// B_{2s}, split into four, and likewise the south sibling (both forced by the split children of
/// B_{2s} next to them). Triangles: Q has split cells on its west and north sides (the south-west
/// and north-east children of B_{2s}, split at the level below) and same-size leaves east and
/// south: a Steiner point with 6 boundary vertices, 6 triangles. In E, the north-west quarter
/// has a split west neighbour (5 triangles); the other three see only same-size or larger leaves
/// or the board boundary (2 each): 11. The south sibling, by symmetry: 11. So 6 + 11 + 11 = 28 per
/// level: each doubling of U adds one such level, the old tree sitting unchanged in the new
/// root's north-west quadrant (the other quadrants do not meet the square, and the cells balance
/// adds in them are never smaller than half their neighbour in the old tree).
///
/// The ends: the 16 unit cells (2 triangles each: no neighbour is smaller) plus E and S of B_4
/// split into side-2 leaves, whose west/north quarters next to unit cells have 5 triangles and the
/// others 2 (14 each): 32 + 28 = 60; and the root's south-east quadrant, with split neighbours
/// west and north: 6. Total 60 + 28 (j - 3) + 6 = 28 j - 18. Leaves: 16 + 8 + 9 (j - 3) + 1 =
/// 9 j - 2.
#[test]
fn figure_14_2_family_counts() {
    // U = 4: the square touches the split lines at x = 2 and y = 2, every cell is a unit cell,
    // and the mesh is the uniform one.
    let (out, _) = mesh_and_check(&figure_14_2(2));
    assert_eq!(out.mesh.triangles.len(), 2 * 4 * 4);
    for j in 3..=12u32 {
        let b = figure_14_2(j);
        let (out, stats) = mesh_and_check(&b);
        let uniform = 2u64 << (2 * j);
        let non_uniform = out.mesh.triangles.len() as u64;
        eprintln!(
            "Figure 14.2 at U = 2^{j}: uniform {uniform} triangles, GENERATEMESH {non_uniform} \
             (28 j - 18 = {}), {} vertices, leaves {} -> {} after balance",
            28 * j - 18,
            stats.vertices,
            out.leaves_before_balance,
            out.tree.leaf_count()
        );
        assert_eq!(uniform, 2 * (b.size() as u64).pow(2));
        assert_eq!(non_uniform, 28 * u64::from(j) - 18, "j = {j}");
        assert_eq!(out.leaves_before_balance as u32, 3 * j + 10, "j = {j}");
        assert_eq!(out.tree.leaf_count() as u32, 9 * j - 2, "j = {j}");
        assert_eq!(region_counts(&b, &out.mesh)[1], 2);
    }
    assert_eq!(
        generate_mesh(&figure_14_2(4)).unwrap().mesh.triangles.len(),
        94
    );
}

// ---------------------------------------------------------------------------------------------
// Theorem 14.5: O(p(S) log U) triangles
// ---------------------------------------------------------------------------------------------

/// The measured constant of Theorem 14.5 on random boards: triangles < C p(S) log2 U.
///
/// Measured over random_board(seed, U, count) for seeds 0..12, U = 64, 256, 1024, 4096 and
/// count = 1, 3, 10, 40, 150: the ratio is 1.0 to 2.1 on boards with 10 or more components and
/// at most 7.7 overall, the largest for a single small component (seed 5, U = 256: an octagon
/// of perimeter 8). C = 12 leaves a margin of about 1.5 over that.
///
/// 12 is also the limit of the worst case for one component of perimeter 4 (a unit square or a
/// unit diamond): at the board's centre it meets one cell of each quadrant at every level, and
/// each of the four adds a fixed corner pattern of 12 triangles per level, 48 in all (measured
/// below: 48 j - 64). The ratio (48 j - 64) / (4 j) stays below 12; a unit right triangle (p = 3)
/// there reaches (48 j - 64) / (3 j) < 16, so no C below 16 holds for every board.
const C: f64 = 12.0;

fn ratio(board: &Board, triangles: usize) -> f64 {
    triangles as f64 / (board.perimeter_steps() as f64 * f64::from(board.levels()))
}

#[test]
fn theorem_14_5_size_bound() {
    let mut worst = (0.0, 0, 0, 0);
    for seed in 0..6u64 {
        for size in [64, 256, 1024, 4096] {
            for count in [1, 4, 30, 150] {
                let b = random_board(seed, size, count);
                let triangles = generate_mesh(&b).unwrap().mesh.triangles.len();
                let r = ratio(&b, triangles);
                if r > worst.0 {
                    worst = (r, seed, size, count);
                }
                assert!(r < C, "random_board({seed}, {size}, {count}): ratio {r:.2}");
            }
        }
    }
    eprintln!(
        "Theorem 14.5: largest triangles / (p(S) log2 U) on random boards {:.3} \
         (seed {}, U = {}, count {}); C = {C}",
        worst.0, worst.1, worst.2, worst.3
    );

    // The sample board.
    let b = sample_board();
    let r = ratio(&b, generate_mesh(&b).unwrap().mesh.triangles.len());
    eprintln!("Theorem 14.5: sample_board ratio {r:.3}");
    assert!(r < C);

    // A tiny component at the centre: 48 triangles per level, the ratio below 12 (p = 4) and
    // 16 (p = 3), approaching them as U grows.
    for j in 4..=20u32 {
        let (u, c) = (1i64 << j, 1i64 << (j - 1));
        let square: &[Point] = &[[c - 1, c - 1], [c, c - 1], [c, c], [c - 1, c]];
        let diamond: &[Point] = &[[c, c - 1], [c + 1, c], [c, c + 1], [c - 1, c]];
        let triangle: &[Point] = &[[c - 1, c - 1], [c, c - 1], [c, c]];
        for (outline, bound) in [(square, 12.0), (diamond, 12.0), (triangle, 16.0)] {
            let b = board(u, &[outline]);
            let t = generate_mesh(&b).unwrap().mesh.triangles.len();
            assert_eq!(t as u32, 48 * j - 64, "j = {j}, {outline:?}");
            assert!(ratio(&b, t) < bound);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The samples
// ---------------------------------------------------------------------------------------------

#[test]
fn sample_board_meshes() {
    let b = sample_board();
    assert_eq!(b.size(), 1024);
    assert_eq!(b.components().len(), 147);
    let touching = b
        .components()
        .iter()
        .filter(|c| c.outline.iter().any(|p| p[1] == 0))
        .count();
    assert_eq!(
        touching, 16,
        "the edge connector's fingers touch the bottom side"
    );
    let (out, stats) = mesh_and_check(&b);
    eprintln!(
        "sample_board: {} components, p(S) = {}, {} triangles, {} vertices, {} outline steps, \
         leaves {} -> {} after balance",
        b.components().len(),
        b.perimeter_steps(),
        stats.triangles,
        stats.vertices,
        stats.outline_steps,
        out.leaves_before_balance,
        out.tree.leaf_count()
    );
    assert_eq!(stats.outline_steps as u64, b.perimeter_steps());
    // A regression value: the chapter's algorithm is deterministic, so this changes only if the
    // sample board or the algorithm does.
    assert_eq!(stats.triangles, 367_672);
    assert!(region_counts(&b, &out.mesh).iter().all(|&n| n > 0));
}

#[test]
fn random_boards_mesh() {
    for (seed, size, count) in [(1, 8, 10), (2, 64, 20), (3, 256, 60), (4, 1024, 100)] {
        let b = random_board(seed, size, count);
        let (out, stats) = mesh_and_check(&b);
        eprintln!(
            "random_board({seed}, {size}, {count}): {} components, p(S) = {}, {} triangles",
            b.components().len(),
            b.perimeter_steps(),
            stats.triangles
        );
        assert!(region_counts(&b, &out.mesh).iter().all(|&n| n > 0));
    }
}

#[test]
fn random_boards_are_valid_at_every_size() {
    for level in 3..=30u32 {
        let size = 1i64 << level;
        for seed in 0..4 {
            let b = random_board(seed, size, 60);
            assert_valid_board(&b);
            assert_eq!(b, random_board(seed, size, 60), "deterministic");
            assert!(!b.components().is_empty());
            if level >= 8 {
                assert_eq!(b.components().len(), 60, "room for all at U = {size}");
            }
        }
    }
    // Small boards fill up: fewer components than asked, but valid.
    let full = random_board(9, 8, 500);
    assert_valid_board(&full);
    assert!(full.components().len() < 500);
    assert!(random_board(9, 16, 0).components().is_empty());
}

#[test]
#[should_panic(expected = "not a power of two")]
fn random_board_rejects_bad_sizes() {
    random_board(0, 12, 5);
}

// ---------------------------------------------------------------------------------------------
// Edge cases
// ---------------------------------------------------------------------------------------------

#[test]
fn empty_boards_have_two_triangles() {
    for j in 0..=20u32 {
        let b = board(1 << j, &[]);
        let (out, stats) = mesh_and_check(&b);
        assert_eq!(stats.triangles, 2, "U = 2^{j}");
        assert_eq!(out.mesh.vertices.len(), 4);
        assert_eq!(out.mesh.regions, vec![0, 0]);
        assert_eq!(out.mesh.segments.len(), 4, "the four sides");
        assert!(out
            .mesh
            .segments
            .iter()
            .all(|s| s.kind == SegmentKind::Boundary));
    }
}

#[test]
fn unit_and_size_two_boards() {
    // U = 1: a component along either diagonal of the only cell, and the whole board.
    for (outline, regions) in [
        (&[[0, 0], [1, 0], [1, 1]][..], [1, 1]),
        (&[[0, 0], [1, 0], [0, 1]][..], [1, 1]),
        (&[[0, 0], [1, 0], [1, 1], [0, 1]][..], [0, 2]),
    ] {
        let b = board(1, &[outline]);
        let (out, stats) = mesh_and_check(&b);
        assert_eq!(stats.triangles, 2);
        assert_eq!(region_counts(&b, &out.mesh), regions, "{outline:?}");
    }
    // U = 2: every component edge meets the root, so there are 4 unit cells, 8 triangles.
    let cases: [(&[&[Point]], &[usize]); 5] = [
        (&[&[[1, 0], [2, 1], [1, 2], [0, 1]]], &[4, 4]), // inscribed diamond
        (&[&[[0, 0], [2, 0], [2, 2], [0, 2]]], &[0, 8]), // the whole board
        (&[&[[0, 0], [1, 0], [1, 1], [0, 1]]], &[6, 2]), // a corner cell
        (&[&[[0, 0], [2, 0], [0, 2]]], &[4, 4]),         // half the board
        (
            &[&[[0, 0], [1, 0], [0, 1]], &[[2, 2], [1, 2], [2, 1]]],
            &[6, 1, 1],
        ), // two opposite corners
    ];
    for (outlines, regions) in cases {
        let b = board(2, outlines);
        let (out, stats) = mesh_and_check(&b);
        assert_eq!(stats.triangles, 8, "{outlines:?}");
        assert_eq!(region_counts(&b, &out.mesh), regions, "{outlines:?}");
    }
}

#[test]
fn components_touching_the_boundary() {
    let b = board(
        64,
        &[
            &[[8, 0], [24, 0], [24, 4], [8, 4]], // an edge along the bottom
            &[[56, 56], [64, 56], [64, 64], [56, 64]], // the top right corner
            &[[0, 0], [6, 0], [6, 2], [2, 2], [2, 6], [0, 6]], // an L in the bottom left corner
            &[[0, 20], [4, 20], [8, 24], [8, 28], [4, 32], [0, 32]], // chamfered, on the left side
            &[[64, 40], [60, 44], [56, 40], [60, 36]], // a diamond's vertex on the right
            &[[16, 61], [30, 61], [33, 64], [16, 64]], // a trace end along the top
        ],
    );
    let (out, stats) = mesh_and_check(&b);
    // Outline steps on the board boundary are marked both ways.
    let v = &out.mesh.vertices;
    let on_boundary = |s: &orthtree::mesh::Segment| {
        let [a, b] = s.vertices.map(|i| v[i as usize]);
        (a[0] == b[0] && (a[0] == 0 || a[0] == 64)) || (a[1] == b[1] && (a[1] == 0 || a[1] == 64))
    };
    let marked_both = out
        .mesh
        .segments
        .iter()
        .filter(|s| matches!(s.kind, SegmentKind::Component(_)) && on_boundary(s))
        .count();
    // 16 + (8 + 8) + (6 + 6) + 12 + 0 + 17 unit steps lie on the boundary.
    assert_eq!(marked_both, 73);
    eprintln!("boundary-touching board: {} triangles", stats.triangles);
    assert!(region_counts(&b, &out.mesh).iter().all(|&n| n > 0));
}

/// Theorem 14.5's time bound, O(p(S) log^2 U), makes an empty board cheap at any U: the mesher
/// must not walk the board's boundary in unit steps. At U = 2^30 the mesh is two triangles and
/// four boundary segments (one per side), whatever the walk would have found.
#[test]
fn huge_empty_board_is_two_triangles() {
    let b = board(1 << 30, &[]);
    let (out, _) = mesh_and_check(&b);
    assert_eq!(out.mesh.triangles.len(), 2);
    assert_eq!(out.mesh.segments.len(), 4);
    assert!(out
        .mesh
        .segments
        .iter()
        .all(|s| s.kind == SegmentKind::Boundary));
}

// ---------------------------------------------------------------------------------------------
// Property test
// ---------------------------------------------------------------------------------------------

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 48,
        rng_seed: RngSeed::Fixed(0x0b0a_4d01),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn random_boards_mesh_correctly(seed in any::<u64>(), level in 3u32..=9, count in 0usize..50) {
        let b = random_board(seed, 1 << level, count);
        prop_assert!(b.components().len() <= count);
        let (out, stats) = mesh_and_check(&b);
        prop_assert_eq!(stats.outline_steps as u64, b.perimeter_steps());
        prop_assert!(ratio(&b, out.mesh.triangles.len()) < C || b.components().is_empty());
    }
}
