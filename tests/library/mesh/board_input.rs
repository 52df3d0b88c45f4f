//! Board input: every `BoardError` kind from `Board::new`, the `.poly` reader and the plain-text
//! reader, naming the right component, edge, point and line; normalisation (counter-clockwise,
//! collinear vertices dropped); round trips through both writers; half-integer crossings of
//! diagonals; nesting; a large board; and random boards against a brute-force oracle that walks
//! every half-unit lattice point of every edge.

use orthtree::io::board_text::{read_board_text, write_board_text};
use orthtree::io::poly::{read_poly, write_poly, PolyWriteError};
use orthtree::mesh::{Board, BoardError, Component, Point};
use proptest::prelude::*;
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};
use std::collections::{HashMap, HashSet};
use std::time::Instant;

// ---------------------------------------------------------------------------------------------
// Helpers and the brute-force oracle
// ---------------------------------------------------------------------------------------------

fn comp(points: &[[i64; 2]]) -> Component {
    Component::new(points.to_vec())
}

fn square(x: i64, y: i64, side: i64) -> Component {
    comp(&[[x, y], [x + side, y], [x + side, y + side], [x, y + side]])
}

fn text(s: &str) -> Result<Board, BoardError> {
    read_board_text(s, None)
}

fn outlines(b: &Board) -> Vec<Vec<Point>> {
    b.components().iter().map(|c| c.outline.clone()).collect()
}

/// The half-unit lattice points of the closed edge a-b, in doubled coordinates: every point two
/// edges of the four directions can share is one of these.
fn edge_points(a: Point, b: Point) -> Vec<Point> {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let steps = 2 * dx.abs().max(dy.abs());
    (0..=steps)
        .map(|t| [2 * a[0] + t * dx.signum(), 2 * a[1] + t * dy.signum()])
        .collect()
}

fn edge(c: &Component, k: usize) -> (Point, Point) {
    let n = c.outline.len();
    (c.outline[k], c.outline[(k + 1) % n])
}

/// `true` when the doubled point `p` lies on the closed edge a-b.
fn on_edge(p: Point, (a, b): (Point, Point)) -> bool {
    edge_points(a, b).contains(&p)
}

/// Every pair of edges that share a point they should not (brute force over lattice points):
/// ((component, edge), (component, edge)), from 0.
fn oracle_conflicts(components: &[Component]) -> Vec<((usize, usize), (usize, usize))> {
    let mut at: HashMap<Point, Vec<(usize, usize)>> = HashMap::new();
    for (ci, c) in components.iter().enumerate() {
        for k in 0..c.outline.len() {
            let (a, b) = edge(c, k);
            for p in edge_points(a, b) {
                at.entry(p).or_default().push((ci, k));
            }
        }
    }
    let mut out = Vec::new();
    for (p, list) in &at {
        for (i, &e) in list.iter().enumerate() {
            for &f in &list[i + 1..] {
                if !allowed(components, e, f, *p) {
                    out.push((e, f));
                }
            }
        }
    }
    out
}

/// Consecutive edges of one component may share their common vertex, and nothing else.
fn allowed(components: &[Component], e: (usize, usize), f: (usize, usize), p: Point) -> bool {
    if e.0 != f.0 {
        return false;
    }
    let n = components[e.0].outline.len();
    let common = if (e.1 + 1) % n == f.1 {
        f.1
    } else if (f.1 + 1) % n == e.1 {
        e.1
    } else {
        return false;
    };
    let v = components[e.0].outline[common];
    p == [2 * v[0], 2 * v[1]]
}

/// Exact point-in-polygon (crossing number) for a point not on the outline.
fn inside(p: Point, c: &Component) -> bool {
    let mut odd = false;
    for k in 0..c.outline.len() {
        let (a, b) = edge(c, k);
        if (a[1] > p[1]) != (b[1] > p[1]) {
            // x of the crossing > p.x, exactly: (p.x - a.x)(b.y - a.y) < (p.y - a.y)(b.x - a.x)
            let lhs = (p[0] - a[0]) * (b[1] - a[1]);
            let rhs = (p[1] - a[1]) * (b[0] - a[0]);
            if (b[1] > a[1] && lhs < rhs) || (b[1] < a[1] && lhs > rhs) {
                odd = !odd;
            }
        }
    }
    odd
}

/// Checks an error against the brute force, or a board against its input.
fn check_against_oracle(size: i64, input: &[Component]) {
    let conflicts = oracle_conflicts(input);
    let nested: Vec<(usize, usize)> = if conflicts.is_empty() {
        (0..input.len())
            .flat_map(|i| (0..input.len()).map(move |j| (i, j)))
            .filter(|&(i, j)| i != j && inside(input[i].outline[0], &input[j]))
            .collect()
    } else {
        Vec::new()
    };
    match Board::new(size, input.to_vec()) {
        Ok(board) => {
            assert!(
                conflicts.is_empty(),
                "missed conflicts {conflicts:?} in {input:?}"
            );
            assert!(nested.is_empty(), "missed nesting {nested:?} in {input:?}");
            check_normalised(&board, input);
        }
        Err(BoardError::SelfIntersection {
            component,
            edge: e,
            other_edge,
            at_half_units,
            ..
        }) => {
            let c = &input[component - 1];
            assert!(e < other_edge);
            assert!(on_edge(at_half_units, edge(c, e - 1)));
            assert!(on_edge(at_half_units, edge(c, other_edge - 1)));
            assert!(!allowed(
                input,
                (component - 1, e - 1),
                (component - 1, other_edge - 1),
                at_half_units
            ));
        }
        Err(BoardError::ComponentsTouch {
            component,
            edge: e,
            other,
            other_edge,
            at_half_units,
            ..
        }) => {
            assert!(component < other);
            assert!(on_edge(at_half_units, edge(&input[component - 1], e - 1)));
            assert!(on_edge(
                at_half_units,
                edge(&input[other - 1], other_edge - 1)
            ));
        }
        Err(BoardError::ComponentInside { component, other }) => {
            assert!(conflicts.is_empty());
            assert!(
                nested.contains(&(component - 1, other - 1)),
                "{component} is not inside {other}: {input:?}"
            );
        }
        Err(e) => panic!("unexpected {e:?} for {input:?}"),
    }
}

/// A normalised board: counter-clockwise, no vertex between collinear edges, the same point
/// sets as its input, and a fixed point of `Board::new`.
fn check_normalised(board: &Board, input: &[Component]) {
    assert_eq!(board.components().len(), input.len());
    for (c, given) in board.components().iter().zip(input) {
        assert!(c.doubled_area() > 0);
        assert_eq!(c.doubled_area(), given.doubled_area().abs());
        assert_eq!(c.lines.len(), c.outline.len());
        let n = c.outline.len();
        for k in 0..n {
            let (a, b) = edge(c, k);
            let (_, d) = edge(c, (k + 1) % n);
            let dir = |p: Point, q: Point| [(q[0] - p[0]).signum(), (q[1] - p[1]).signum()];
            assert_ne!(dir(a, b), dir(b, d), "collinear vertex {b:?} kept");
        }
        let set = |c: &Component| -> HashSet<Point> {
            (0..c.outline.len())
                .flat_map(|k| {
                    let (a, b) = edge(c, k);
                    edge_points(a, b)
                })
                .collect()
        };
        assert_eq!(set(c), set(given));
    }
    let again = Board::new(board.size(), board.components().to_vec()).unwrap();
    assert_eq!(&again, board);
}

/// Random small components on a 16 x 16 board: rectangles, diamonds, triangles, octagons, and
/// random closed walks in the eight directions (often not simple).
fn random_component(r: &mut SmallRng, size: i64) -> Option<Component> {
    let c = |p: &[[i64; 2]]| Some(comp(p));
    let (x, y) = (r.gen_range(0..size), r.gen_range(0..size));
    let s = r.gen_range(1..=6i64);
    let fits = |p: &[Point]| {
        p.iter()
            .all(|q| (0..=size).contains(&q[0]) && (0..=size).contains(&q[1]))
    };
    let shape = match r.gen_range(0..7) {
        0 => {
            let h = r.gen_range(1..=4);
            c(&[[x, y], [x + s, y], [x + s, y + h], [x, y + h]])
        }
        1 => c(&[[x, y], [x + s, y + s], [x, y + 2 * s], [x - s, y + s]]),
        2 => c(&[[x, y], [x + s, y], [x, y + s]]),
        6 => {
            // a large rectangle, often holding others
            let (w, h) = (r.gen_range(6..=size), r.gen_range(6..=size));
            let (x, y) = (r.gen_range(0..=size - w), r.gen_range(0..=size - h));
            c(&[[x, y], [x + w, y], [x + w, y + h], [x, y + h]])
        }
        3 => c(&[
            [x, y],
            [x + s, y],
            [x + 2 * s, y + s],
            [x + 2 * s, y + 2 * s],
            [x + s, y + 3 * s],
            [x, y + 3 * s],
            [x - s, y + 2 * s],
            [x - s, y + s],
        ]),
        _ => {
            let dirs = [
                [1, 0],
                [1, 1],
                [0, 1],
                [-1, 1],
                [-1, 0],
                [-1, -1],
                [0, -1],
                [1, -1],
            ];
            let start = [x, y];
            let mut pts = vec![start];
            let mut p = start;
            for _ in 0..r.gen_range(1..6) {
                let d = dirs[r.gen_range(0..8)];
                let len = r.gen_range(1..4);
                p = [p[0] + d[0] * len, p[1] + d[1] * len];
                pts.push(p);
            }
            // close with a diagonal run and an axis run
            let (dx, dy) = (start[0] - p[0], start[1] - p[1]);
            let m = dx.abs().min(dy.abs());
            let q = [p[0] + m * dx.signum(), p[1] + m * dy.signum()];
            pts.push(q);
            pts.dedup();
            while pts.len() > 1 && pts.last() == pts.first() {
                pts.pop();
            }
            if pts.len() < 3 {
                return None;
            }
            Some(comp(&pts))
        }
    }?;
    fits(&shape.outline).then_some(shape)
}

fn random_disjoint_squares(seed: u64, count: usize, size: i64, max_side: i64) -> Vec<Component> {
    let mut r = SmallRng::seed_from_u64(seed);
    let mut placed: Vec<(i64, i64, i64)> = Vec::new();
    // A grid of buckets keeps the rejection test cheap.
    let cell = 2 * max_side;
    let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    while placed.len() < count {
        let s = r.gen_range(1..=max_side);
        let (x, y) = (r.gen_range(0..=size - s), r.gen_range(0..=size - s));
        let (gx, gy) = (x / cell, y / cell);
        let clear = (gx - 1..=gx + 1).all(|i| {
            (gy - 1..=gy + 1).all(|j| {
                grid.get(&(i, j)).is_none_or(|list| {
                    list.iter().all(|&k| {
                        let (a, b, t) = placed[k];
                        // apart by at least one unit
                        x > a + t || a > x + s || y > b + t || b > y + s
                    })
                })
            })
        });
        if clear {
            grid.entry((gx, gy)).or_default().push(placed.len());
            placed.push((x, y, s));
        }
    }
    placed
        .into_iter()
        .map(|(x, y, s)| square(x, y, s))
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Each error kind, with component, edge and line
// ---------------------------------------------------------------------------------------------

#[test]
fn size_must_be_a_power_of_two_up_to_2_pow_30() {
    let tri = || vec![comp(&[[0, 0], [1, 0], [0, 1]])];
    for size in [0, -4, 12, 3, 1 << 31, i64::MAX, i64::MIN] {
        assert_eq!(
            Board::new(size, tri()),
            Err(BoardError::SizeNotPowerOfTwo { size })
        );
    }
    for size in [1, 2, 1 << 16, 1 << 30] {
        assert_eq!(Board::new(size, tri()).unwrap().size(), size);
    }
    let e = text("size 12\n0 0 4 0 0 4\n").unwrap_err();
    assert_eq!(e, BoardError::SizeNotPowerOfTwo { size: 12 });
    assert!(e
        .to_string()
        .contains("board size 12 is not a power of two"));
    let e = read_poly(
        "# size 12\n3 2 0 0\n1 0 0\n2 4 0\n3 0 4\n3 0\n1 1 2\n2 2 3\n3 3 1\n",
        None,
    );
    assert_eq!(e.unwrap_err(), BoardError::SizeNotPowerOfTwo { size: 12 });
}

#[test]
fn too_few_vertices_names_component_and_line() {
    let e = text("size 16\n0 0 4 0 0 4\n\n# a comment\n5 5  6 6\n").unwrap_err();
    assert_eq!(
        e,
        BoardError::TooFewVertices {
            component: 2,
            line: Some(5)
        }
    );
    assert_eq!(
        e.to_string(),
        "component 2 (line 5): a component needs at least 3 vertices"
    );
    // a repeated first vertex at the end is dropped, leaving two
    let e = text("1 1  2 2  1 1\n").unwrap_err();
    assert_eq!(
        e,
        BoardError::TooFewVertices {
            component: 1,
            line: Some(1)
        }
    );
    // without line information
    let e = Board::new(8, vec![square(0, 0, 1), comp(&[[5, 5], [6, 6]])]).unwrap_err();
    assert_eq!(
        e,
        BoardError::TooFewVertices {
            component: 2,
            line: None
        }
    );
    assert_eq!(
        e.to_string(),
        "component 2: a component needs at least 3 vertices"
    );
    // .poly: a loop of two segments, and a segment from a vertex to itself
    let poly = "3 2 0 0\n1 0 0\n2 4 0\n3 0 4\n3 0\n1 1 2\n2 2 1\n3 3 3\n";
    assert_eq!(
        read_poly(poly, Some(8)).unwrap_err(),
        BoardError::TooFewVertices {
            component: 1,
            line: Some(6)
        }
    );
    let poly = "1 2 0 0\n1 3 3\n1 0\n1 1 1\n";
    assert_eq!(
        read_poly(poly, Some(8)).unwrap_err(),
        BoardError::TooFewVertices {
            component: 1,
            line: Some(4)
        }
    );
}

#[test]
fn out_of_range_vertex_names_its_edge_and_line() {
    let e = text("size 16\n0 0 2 0 0 2\n1 10  17 10  9 18\n").unwrap_err();
    // vertex 2 of component 2 is the first outside; edge 2 starts there
    assert_eq!(
        e,
        BoardError::OutOfRange {
            component: 2,
            edge: 2,
            point: [17, 10],
            line: Some(3)
        }
    );
    assert_eq!(
        e.to_string(),
        "component 2, edge 2 (line 3): vertex (17, 10) lies outside the board [0, U]^2"
    );
    let e = text("size 16\n-1 0  2 0  2 3\n").unwrap_err();
    assert_eq!(
        e,
        BoardError::OutOfRange {
            component: 1,
            edge: 1,
            point: [-1, 0],
            line: Some(2)
        }
    );
    // extreme i64 coordinates are refused without overflow
    let e = text("size 16\n0 0  9223372036854775807 0  0 9223372036854775807\n").unwrap_err();
    assert!(matches!(
        e,
        BoardError::OutOfRange {
            component: 1,
            edge: 2,
            ..
        }
    ));
    let e = text("-9223372036854775808 0  0 0  0 5\n").unwrap_err();
    assert!(matches!(
        e,
        BoardError::OutOfRange {
            component: 1,
            edge: 1,
            ..
        }
    ));
    // .poly: the line is that of the segment starting at the vertex
    let poly = "# size 8\n3 2 0 0\n1 0 0\n2 9 0\n3 0 9\n3 0\n10 1 2\n11 2 3\n12 3 1\n";
    assert_eq!(
        read_poly(poly, None).unwrap_err(),
        BoardError::OutOfRange {
            component: 1,
            edge: 2,
            point: [9, 0],
            line: Some(8)
        }
    );
}

#[test]
fn zero_length_edge_names_its_edge_and_line() {
    let e = text("size 8\n\n0 0  4 0  4 0  4 4\n").unwrap_err();
    assert_eq!(
        e,
        BoardError::ZeroLengthEdge {
            component: 1,
            edge: 2,
            line: Some(3)
        }
    );
    assert_eq!(
        e.to_string(),
        "component 1, edge 2 (line 3): edge has length zero (its two ends are the same point)"
    );
    // .poly: two vertex ids at one point
    let poly = "4 2 0 0\n1 0 0\n2 4 0\n3 4 0\n4 4 4\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n";
    assert_eq!(
        read_poly(poly, Some(8)).unwrap_err(),
        BoardError::ZeroLengthEdge {
            component: 1,
            edge: 2,
            line: Some(8)
        }
    );
}

#[test]
fn bad_angle_names_component_edge_coordinates_and_line() {
    let mut s = String::from("size 16\n");
    s.push_str(&"# filler\n".repeat(13));
    s.push_str("0 0 1 0 0 1\n"); // line 15
    s.push_str("10 10 11 10 10 11\n"); // line 16
    s.push_str("3 3  4 4  7 5  3 5\n"); // line 17
    let e = text(&s).unwrap_err();
    assert_eq!(
        e,
        BoardError::BadAngle {
            component: 3,
            edge: 2,
            from: [4, 4],
            to: [7, 5],
            line: Some(17)
        }
    );
    assert_eq!(
        e.to_string(),
        "component 3, edge 2 (line 17): edge (4, 4)-(7, 5) is not at 0, 45, 90 or 135 degrees"
    );
    // the closing edge is the last one
    let e = text("0 0  4 0  4 4  1 4\n").unwrap_err();
    assert_eq!(
        e,
        BoardError::BadAngle {
            component: 1,
            edge: 4,
            from: [1, 4],
            to: [0, 0],
            line: Some(1)
        }
    );
    let poly = "3 2 0 0\n1 0 0\n2 4 0\n3 1 2\n3 0\n1 1 2\n2 2 3\n3 3 1\n";
    assert_eq!(
        read_poly(poly, Some(8)).unwrap_err(),
        BoardError::BadAngle {
            component: 1,
            edge: 2,
            from: [4, 0],
            to: [1, 2],
            line: Some(7)
        }
    );
}

#[test]
fn self_intersections_are_found() {
    // a bow tie: edges 1 and 3 cross at (1, 1)
    let e = text("size 4\n0 0  2 2  2 0  0 2\n").unwrap_err();
    assert_eq!(
        e,
        BoardError::SelfIntersection {
            component: 1,
            edge: 1,
            other_edge: 3,
            at_half_units: [2, 2],
            line: Some(2)
        }
    );
    // a small bow tie crossing at a half-integer point
    let e = text("size 4\n0 0  1 1  1 0  0 1\n").unwrap_err();
    assert_eq!(
        e,
        BoardError::SelfIntersection {
            component: 1,
            edge: 1,
            other_edge: 3,
            at_half_units: [1, 1],
            line: Some(2)
        }
    );
    assert_eq!(
        e.to_string(),
        "component 1, edge 1 (line 2): edge meets edge 3 of the same component at (0.5, 0.5), so \
         the outline is not a simple polygon"
    );
    // a spike: edge 3 runs back along edge 2 (consecutive edges sharing more than a vertex)
    let e = text("size 8\n0 0  4 0  4 4  4 2  2 2\n").unwrap_err();
    assert_eq!(
        e,
        BoardError::SelfIntersection {
            component: 1,
            edge: 2,
            other_edge: 3,
            at_half_units: [8, 6],
            line: Some(2)
        }
    );
    // a figure of eight through (2, 2): two non-consecutive edges among 2, 3, 6, 7 meet there
    let c = comp(&[
        [0, 0],
        [2, 0],
        [2, 2],
        [4, 2],
        [4, 4],
        [2, 4],
        [2, 2],
        [0, 2],
    ]);
    match Board::new(8, vec![square(5, 5, 1), c]).unwrap_err() {
        BoardError::SelfIntersection {
            component: 2,
            edge,
            other_edge,
            at_half_units,
            line,
        } => {
            assert_eq!(at_half_units, [4, 4]);
            assert!([2, 3, 6, 7].contains(&edge) && [2, 3, 6, 7].contains(&other_edge));
            assert!(other_edge > edge + 1);
            assert_eq!(line, None);
        }
        e => panic!("{e:?}"),
    }
    // a vertex on the interior of a non-adjacent edge of its own outline
    let c = comp(&[[0, 0], [6, 0], [6, 3], [3, 0], [0, 3]]);
    match Board::new(8, vec![c]).unwrap_err() {
        BoardError::SelfIntersection {
            component: 1,
            edge: 1,
            other_edge,
            at_half_units,
            ..
        } => {
            assert_eq!(at_half_units, [6, 0]);
            assert!(other_edge == 3 || other_edge == 4);
        }
        e => panic!("{e:?}"),
    }
    // .poly names the segment's line
    let poly = "4 2 0 0\n1 0 0\n2 2 2\n3 2 0\n4 0 2\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n";
    assert_eq!(
        read_poly(poly, Some(4)).unwrap_err(),
        BoardError::SelfIntersection {
            component: 1,
            edge: 1,
            other_edge: 3,
            at_half_units: [2, 2],
            line: Some(7)
        }
    );
}

#[test]
fn touching_components_are_found() {
    // sharing part of an edge: midpoint of the overlap
    let e = Board::new(8, vec![square(0, 0, 4), square(4, 1, 2)]).unwrap_err();
    assert_eq!(
        e,
        BoardError::ComponentsTouch {
            component: 1,
            edge: 2,
            other: 2,
            other_edge: 4,
            at_half_units: [8, 4],
            line: None
        }
    );
    assert_eq!(
        e.to_string(),
        "component 1, edge 2: edge meets edge 4 of component 2 at (4, 2); components must not \
         touch or overlap"
    );
    // squares side by side share an edge and two corners
    let e = Board::new(8, vec![square(0, 0, 2), square(2, 0, 2)]).unwrap_err();
    assert!(matches!(
        e,
        BoardError::ComponentsTouch {
            component: 1,
            other: 2,
            ..
        }
    ));
    // corner to corner
    let e = text("size 8\n0 0 2 0 2 2 0 2\n2 2 4 2 4 4 2 4\n").unwrap_err();
    match e {
        BoardError::ComponentsTouch {
            component: 1,
            other: 2,
            at_half_units,
            line,
            ..
        } => {
            assert_eq!(at_half_units, [4, 4]);
            assert_eq!(line, Some(2));
        }
        e => panic!("{e:?}"),
    }
    // a vertex on the interior of another component's edge
    let e = text("size 8\n0 0 4 0 4 4 0 4\n5 2 4 2 5 1\n").unwrap_err();
    assert!(matches!(
        e,
        BoardError::ComponentsTouch {
            component: 1,
            edge: 2,
            other: 2,
            at_half_units: [8, 4],
            ..
        }
    ));
    // the two diagonals of a square in different components cross at its centre
    let e = text("size 8\n1 1  3 3  5 1\n1 3  3 1  3 0  0 0  0 3\n").unwrap_err();
    match e {
        BoardError::ComponentsTouch {
            component: 1,
            other: 2,
            ..
        } => {}
        e => panic!("{e:?}"),
    }
    // one component overlapping another entirely
    let e = Board::new(8, vec![square(0, 0, 4), square(0, 0, 4)]).unwrap_err();
    assert!(matches!(
        e,
        BoardError::ComponentsTouch {
            component: 1,
            other: 2,
            ..
        }
    ));
    // .poly: two loops, the second touching the first
    let poly = "6 2 0 0\n1 0 0\n2 2 0\n3 0 2\n4 2 0\n5 4 0\n6 4 2\n\
                6 0\n1 1 2\n2 2 3\n3 3 1\n4 4 5\n5 5 6\n6 6 4\n";
    match read_poly(poly, Some(8)).unwrap_err() {
        BoardError::ComponentsTouch {
            component: 1,
            other: 2,
            at_half_units: [4, 0],
            ..
        } => {}
        e => panic!("{e:?}"),
    }
}

#[test]
fn diagonals_crossing_only_at_half_integer_points_are_found() {
    // two diamonds, the second one unit to the right: they cross at (2.5, 0.5) and (2.5, 3.5)
    // only, points no integer lattice holds
    let a = comp(&[[2, 0], [4, 2], [2, 4], [0, 2]]);
    let b = comp(&[[3, 0], [5, 2], [3, 4], [1, 2]]);
    let shared = oracle_conflicts(&[a.clone(), b.clone()]);
    assert_eq!(shared.len(), 2);
    let e = Board::new(8, vec![a.clone(), b.clone()]).unwrap_err();
    assert_eq!(
        e,
        BoardError::ComponentsTouch {
            component: 1,
            edge: 1,
            other: 2,
            other_edge: 4,
            at_half_units: [5, 1],
            line: None
        }
    );
    assert!(e.to_string().contains("at (2.5, 0.5)"));
    // the same in either order and as text
    let e = Board::new(8, vec![b, a]).unwrap_err();
    assert!(matches!(
        e,
        BoardError::ComponentsTouch {
            component: 1,
            other: 2,
            ..
        }
    ));
    let e = text("size 8\n2 0 4 2 2 4 0 2\n3 0 5 2 3 4 1 2\n").unwrap_err();
    assert!(matches!(
        e,
        BoardError::ComponentsTouch {
            at_half_units: [5, 1],
            line: Some(2),
            ..
        }
    ));
    // four units apart they touch at a vertex; five apart they are disjoint
    let e = text("size 16\n2 0 4 2 2 4 0 2\n6 0 8 2 6 4 4 2\n").unwrap_err();
    assert!(matches!(
        e,
        BoardError::ComponentsTouch {
            at_half_units: [8, 4],
            ..
        }
    ));
    assert_eq!(
        text("size 16\n2 0 4 2 2 4 0 2\n7 0 9 2 7 4 5 2\n").map(|b| b.components().len()),
        Ok(2)
    );
}

#[test]
fn nested_components_are_found() {
    let e = Board::new(16, vec![square(0, 0, 10), square(2, 2, 2)]).unwrap_err();
    assert_eq!(
        e,
        BoardError::ComponentInside {
            component: 2,
            other: 1
        }
    );
    assert_eq!(
        e.to_string(),
        "component 2 lies inside component 1; components must not be nested"
    );
    let e = Board::new(16, vec![square(2, 2, 2), square(0, 0, 10)]).unwrap_err();
    assert_eq!(
        e,
        BoardError::ComponentInside {
            component: 1,
            other: 2
        }
    );
    // clockwise outer outline, diamond inside an octagon
    let outer = comp(&[[0, 0], [0, 12], [12, 12], [12, 0]]);
    let diamond = comp(&[[6, 1], [8, 3], [6, 5], [4, 3]]);
    assert_eq!(
        Board::new(16, vec![outer.clone(), diamond]).unwrap_err(),
        BoardError::ComponentInside {
            component: 2,
            other: 1
        }
    );
    // two components side by side inside a third, at the same height
    let e = Board::new(32, vec![square(0, 0, 20), square(2, 2, 2), square(6, 2, 2)]).unwrap_err();
    assert!(matches!(e, BoardError::ComponentInside { other: 1, .. }));
    // an inner one whose nearest neighbour to the left is a sibling, not the container
    let e = Board::new(
        32,
        vec![
            square(0, 0, 20),
            square(2, 5, 2),
            comp(&[[6, 6], [8, 4], [8, 8]]),
        ],
    )
    .unwrap_err();
    assert!(matches!(e, BoardError::ComponentInside { other: 1, .. }));
    // in the notch of a U the square is outside it: valid
    let u = comp(&[
        [0, 0],
        [10, 0],
        [10, 10],
        [8, 10],
        [8, 2],
        [2, 2],
        [2, 10],
        [0, 10],
    ]);
    assert!(Board::new(16, vec![u.clone(), square(4, 4, 2)]).is_ok());
    // ... and with a second one in the notch, to the left of and above the first
    assert!(Board::new(16, vec![u, square(4, 4, 2), square(3, 7, 1)]).is_ok());
    // text and .poly both report it
    let e = text("size 16\n0 0 10 0 10 10 0 10\n2 2 4 2 4 4 2 4\n").unwrap_err();
    assert_eq!(
        e,
        BoardError::ComponentInside {
            component: 2,
            other: 1
        }
    );
    let poly = "8 2 0 0\n1 2 2\n2 4 2\n3 4 4\n4 2 4\n5 0 0\n6 10 0\n7 10 10\n8 0 10\n\
                8 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n5 5 6\n6 6 7\n7 7 8\n8 8 5\n";
    assert_eq!(
        read_poly(poly, Some(16)).unwrap_err(),
        BoardError::ComponentInside {
            component: 1,
            other: 2
        }
    );
}

// ---------------------------------------------------------------------------------------------
// .poly specifics
// ---------------------------------------------------------------------------------------------

#[test]
fn poly_open_loops_and_overused_vertices() {
    // component 1 closes; the second loop is a path 4-5-6
    let poly = "6 2 0 0\n1 0 0\n2 2 0\n3 0 2\n4 5 5\n5 7 5\n6 7 7\n\
                5 0\n1 1 2\n2 4 5\n3 2 3\n4 3 1\n5 5 6\n";
    let e = read_poly(poly, Some(8)).unwrap_err();
    assert_eq!(
        e,
        BoardError::OpenLoop {
            component: 2,
            line: Some(13)
        }
    );
    assert_eq!(
        e.to_string(),
        "component 2 (line 13): its segments do not close into a loop (no segment continues from \
         the last one)"
    );
    // a third segment at vertex 1
    let poly = "4 2 0 0\n1 0 0\n2 2 0\n3 0 2\n4 2 2\n4 0\n1 1 2\n2 2 3\n3 3 1\n4 1 4\n";
    match read_poly(poly, Some(8)).unwrap_err() {
        BoardError::Parse { line: 10, message } => assert!(message.contains("third segment")),
        e => panic!("{e:?}"),
    }
}

#[test]
fn poly_parse_errors_name_the_line() {
    let good = "3 2 0 0\n1 0 0\n2 4 0\n3 0 4\n3 0\n1 1 2\n2 2 3\n3 3 1\n";
    assert!(read_poly(good, Some(8)).is_ok());
    let cases: &[(&str, usize, &str)] = &[
        (
            "3 2 0 0\n1 0 0\n2 3.5 0\n3 0 4\n3 0\n1 1 2\n2 2 3\n3 3 1\n",
            3,
            "not an integer",
        ),
        (
            "3 2 0 0\n1 0 0\n2 1e400 0\n3 0 4\n3 0\n1 1 2\n2 2 3\n3 3 1\n",
            3,
            "not an integer",
        ),
        (
            "3 2 0 0\n1 0 0\n2 abc 0\n3 0 4\n3 0\n1 1 2\n2 2 3\n3 3 1\n",
            3,
            "not a number",
        ),
        (
            "3 2 0 0\n1 0 0\n2 4 0\n3 0 99999999999999999999\n",
            4,
            "out of range",
        ),
        ("3 2 0 0\n1 0 0\n2 4 0\n3 0\n", 4, "two coordinates"),
        ("3 2 0 0\n1 0 0\n3 4 0\n3 0 4\n", 3, "out of sequence"),
        ("3 2 0 0\n2 0 0\n3 4 0\n4 0 4\n", 2, "must be 0 or 1"),
        ("0 2 0 0\n", 1, "separate .node"),
        ("3 3 0 0\n", 1, "only 2"),
        ("3 2 0 2\n", 1, "expected 0 or 1"),
        ("x 2 0 0\n", 1, "vertex count"),
        (
            "3 2 0 0\n1 0 0\n2 4 0\n3 0 4\n3 0\n1 1 2\n2 2 3\n3 3 4\n",
            8,
            "not a vertex id",
        ),
        (
            "3 2 0 0\n1 0 0\n2 4 0\n3 0 4\n3 0\n1 1 2\n2 2 3\n",
            5,
            "the segment count is 3, but the input ends after 2 segment lines",
        ),
        ("3 2 0 0\n1 0 0\n2 4 0\n3 0 4\n", 4, "end of input"),
        ("", 1, "end of input"),
        ("# size 8\n# size 16\n", 2, "contradicts"),
    ];
    for &(input, line, needle) in cases {
        match read_poly(input, Some(8)) {
            Err(BoardError::Parse { line: l, message }) => {
                assert_eq!(l, line, "{input:?}: {message}");
                assert!(message.contains(needle), "{input:?}: {message}");
                assert!(BoardError::Parse { line: l, message }
                    .to_string()
                    .starts_with(&format!("line {line}: ")));
            }
            other => panic!("{input:?}: {other:?}"),
        }
    }
}

#[test]
fn poly_numbering_comments_markers_and_size() {
    // ids from 0, comments everywhere, attributes and markers, empty holes and regions
    let poly = "# a board\n\n4 2 1 1   # header\n0 1 1 0.5 7\n1 5 1 0.5 7  # vertex 1\n\
                2 5 5 0.5 7\n3 1 5 0.5 7\n# segments\n4 1\n0 0 1 3\n1 1 2 3\n2 2 3 3\n3 3 0 3\n\
                0\n0\n";
    let b = read_poly(poly, None).unwrap();
    assert_eq!(b.size(), 8); // inferred: the largest coordinate is 5
    assert_eq!(outlines(&b), vec![vec![[1, 1], [5, 1], [5, 5], [1, 5]]]);
    assert_eq!(
        b.components()[0].lines,
        vec![Some(10), Some(11), Some(12), Some(13)]
    );
    // a hole or a regional attribute is refused, naming its line
    let holes = poly.replace("0\n0\n", "1\n1 2 2\n0\n");
    assert_eq!(
        read_poly(&holes, None).unwrap_err(),
        BoardError::HolesNotSupported { line: 14, count: 1 }
    );
    let regions = poly.replace("0\n0\n", "0\n1\n1 3 3 1.0 0.5\n");
    assert_eq!(
        read_poly(&regions, None).unwrap_err(),
        BoardError::RegionsNotSupported { line: 15, count: 1 }
    );
    // `# size U` and the caller's size must agree; the caller's size wins over the inferred one
    let with_size = format!("# size 64\n{poly}");
    assert_eq!(read_poly(&with_size, Some(64)).unwrap().size(), 64);
    assert_eq!(
        read_poly(&with_size, Some(16)).unwrap_err(),
        BoardError::SizeMismatch {
            file: 64,
            line: 1,
            caller: 16
        }
    );
    assert_eq!(read_poly(poly, Some(16)).unwrap().size(), 16);
    // a comment starting with the word "size" must be a size line; other words are comments
    let other = format!("# size of the board: large\n{poly}");
    assert!(matches!(
        read_poly(&other, None),
        Err(BoardError::Parse { line: 1, .. })
    ));
    let other = format!("# sizes are in units of 0.1 mm\n{poly}");
    assert_eq!(read_poly(&other, None).unwrap().size(), 8);
    // `3.0` is read as 3; coordinates exactly on a power of two give that power
    let poly = "3 2 0 0\n1 0.0 0\n2 4. 0\n3 0 4.000\n3 0\n1 1 2\n2 2 3\n3 3 1\n";
    let b = read_poly(poly, None).unwrap();
    assert_eq!(b.size(), 4);
    assert_eq!(outlines(&b), vec![vec![[0, 0], [4, 0], [0, 4]]]);
    // loops are numbered by their first segment; each starts at that segment's first vertex
    let poly = "6 2 0 0\n1 5 5\n2 7 5\n3 5 7\n4 0 0\n5 2 0\n6 0 2\n\
                6 0\n1 6 5\n2 1 2\n3 4 5\n4 2 3\n5 6 4\n6 3 1\n";
    let b = read_poly(poly, None).unwrap();
    assert_eq!(
        outlines(&b),
        vec![vec![[0, 2], [0, 0], [2, 0]], vec![[5, 5], [7, 5], [5, 7]]]
    );
    // the first loop, (0,2) (2,0) (0,0), was clockwise: turned round, keeping each edge's line
    assert_eq!(b.components()[0].lines, vec![Some(13), Some(11), Some(9)]);
    assert_eq!(b.components()[1].lines, vec![Some(10), Some(12), Some(14)]);
}

// ---------------------------------------------------------------------------------------------
// Text format specifics
// ---------------------------------------------------------------------------------------------

#[test]
fn text_format_parse_errors_and_size() {
    let b = text("# board\nsize 32   # side\n(1, 1) (5, 1) (5, 5)\n7,7 9,7 9,9 7,9 7,7\n").unwrap();
    assert_eq!(b.size(), 32);
    assert_eq!(
        outlines(&b),
        vec![
            vec![[1, 1], [5, 1], [5, 5]],
            vec![[7, 7], [9, 7], [9, 9], [7, 9]]
        ]
    );
    assert_eq!(b.components()[1].lines, vec![Some(4); 4]);
    // inferred size, and the caller's size
    assert_eq!(text("1 1 5 1 5 5\n").unwrap().size(), 8);
    assert_eq!(text("0 0 1 0 0 1\n").unwrap().size(), 1);
    assert_eq!(
        read_board_text("1 1 5 1 5 5\n", Some(64)).unwrap().size(),
        64
    );
    assert_eq!(
        read_board_text("size 16\n1 1 5 1 5 5\n", Some(64)).unwrap_err(),
        BoardError::SizeMismatch {
            file: 16,
            line: 1,
            caller: 64
        }
    );
    // no components at all is a valid (empty) board
    assert_eq!(text("size 4\n").unwrap().components().len(), 0);
    assert_eq!(text("").unwrap().size(), 1);
    let cases: &[(&str, usize, &str)] = &[
        ("size 16\n1 1 5 1 5\n", 2, "x y pairs"),
        ("size 16\n1 1 5 1 5 2.5\n", 2, "not an integer"),
        ("size 16\n1 1 5 1 5 five\n", 2, "not a number"),
        ("1 1 5 1 5 1e400\n", 1, "not an integer"),
        ("size sixteen\n", 1, "size U"),
        ("size 16 32\n", 1, "size U"),
        ("size 16\n\nsize 16\n", 3, "second size line"),
    ];
    for &(input, line, needle) in cases {
        match text(input) {
            Err(BoardError::Parse { line: l, message }) => {
                assert_eq!(l, line, "{input:?}: {message}");
                assert!(message.contains(needle), "{input:?}: {message}");
            }
            other => panic!("{input:?}: {other:?}"),
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Normalisation
// ---------------------------------------------------------------------------------------------

#[test]
fn clockwise_outlines_are_made_counter_clockwise() {
    let cw = comp(&[[0, 0], [0, 4], [4, 4], [4, 0]]);
    assert!(cw.doubled_area() < 0);
    let b = Board::new(8, vec![cw.clone()]).unwrap();
    assert_eq!(outlines(&b), vec![vec![[0, 0], [4, 0], [4, 4], [0, 4]]]);
    assert_eq!(b.components()[0].doubled_area(), 32);
    // lines follow their edges: the text line of each poly segment
    let poly = "# size 8\n4 2 0 0\n1 0 0\n2 0 4\n3 4 4\n4 4 0\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n";
    let b = read_poly(poly, None).unwrap();
    let c = &b.components()[0];
    assert_eq!(c.outline, vec![[0, 0], [4, 0], [4, 4], [0, 4]]);
    // segment 4-1 (line 11) is now edge (0,0)-(4,0), and so on round the square
    assert_eq!(c.lines, vec![Some(11), Some(10), Some(9), Some(8)]);
    // counter-clockwise input is kept as it is
    let ccw = square(1, 1, 2);
    assert_eq!(
        Board::new(8, vec![ccw.clone()]).unwrap().components()[0],
        ccw
    );
}

#[test]
fn collinear_middle_vertices_are_dropped() {
    let b = text("size 8\n0 0  2 0  4 0  4 4  2 2  0 0\n").unwrap();
    assert_eq!(outlines(&b), vec![vec![[0, 0], [4, 0], [4, 4]]]);
    // the first vertex may itself be a middle one: the outline then starts at the next corner
    let b = text("size 8\n2 0  4 0  4 2  4 4  0 4  0 0\n").unwrap();
    assert_eq!(outlines(&b), vec![vec![[4, 0], [4, 4], [0, 4], [0, 0]]]);
    // diagonal runs too; each merged edge keeps the line of its first piece
    let poly = "# size 8\n5 2 0 0\n1 0 0\n2 4 0\n3 2 2\n4 1 3\n5 0 4\n\
                5 0\n1 1 2\n2 2 3\n3 3 4\n4 4 5\n5 5 1\n";
    let b = read_poly(poly, None).unwrap();
    assert_eq!(outlines(&b), vec![vec![[0, 0], [4, 0], [0, 4]]]);
    assert_eq!(b.components()[0].lines, vec![Some(9), Some(10), Some(13)]);
    // and clockwise with a middle vertex
    let b = Board::new(8, vec![comp(&[[0, 0], [0, 2], [0, 4], [4, 4], [4, 0]])]).unwrap();
    assert_eq!(outlines(&b), vec![vec![[0, 0], [4, 0], [4, 4], [0, 4]]]);
}

#[test]
fn components_may_touch_the_board_boundary() {
    let b = text(
        "size 8\n0 0 2 0 0 2\n8 8 6 8 8 6\n3 0 5 0 5 8 3 8\n0 8 0 5 2 5 2 8\n6 0 8 0 8 5 6 3\n",
    )
    .unwrap();
    assert_eq!(b.components().len(), 5);
    // the whole board as one component
    let b = Board::new(4, vec![square(0, 0, 4)]).unwrap();
    assert_eq!(b.perimeter_steps(), 16);
    // U = 1
    assert!(Board::new(1, vec![comp(&[[0, 0], [1, 0], [1, 1]])]).is_ok());
}

// ---------------------------------------------------------------------------------------------
// Round trips
// ---------------------------------------------------------------------------------------------

#[test]
fn round_trips_through_both_formats() {
    let mut comps = random_disjoint_squares(7, 150, 1 << 9, 12);
    comps.push(comp(&[[700, 700], [710, 710], [700, 720], [690, 710]]));
    comps.push(comp(&[[800, 800], [800, 810], [810, 800]]));
    let board = Board::new(1 << 10, comps).unwrap();
    let t = write_board_text(&board);
    let p = write_poly(&board).unwrap();
    for back in [
        read_board_text(&t, None).unwrap(),
        read_poly(&p, None).unwrap(),
    ] {
        assert_eq!(back.size(), board.size());
        assert_eq!(outlines(&back), outlines(&board));
    }
    // writing what was read gives the same text
    assert_eq!(write_board_text(&read_board_text(&t, None).unwrap()), t);
    assert_eq!(write_poly(&read_poly(&p, None).unwrap()).unwrap(), p);
    // across formats, and the size line survives even when no coordinate reaches it
    let small = text("size 64\n1 1 2 1 2 2\n").unwrap();
    let via = read_board_text(
        &write_board_text(&read_poly(&write_poly(&small).unwrap(), None).unwrap()),
        None,
    )
    .unwrap();
    assert_eq!(via.size(), 64);
    assert_eq!(outlines(&via), outlines(&small));
    // an empty board
    let empty = Board::new(2, vec![]).unwrap();
    assert_eq!(
        read_board_text(&write_board_text(&empty), None).unwrap(),
        empty
    );
    // .poly needs a vertex: the writer refuses the empty board rather than write a file the
    // reader refuses
    assert!(read_poly("# size 2\n0 2 0 0\n0 0\n", None).is_err());
    assert_eq!(
        write_poly(&empty),
        Err(PolyWriteError::NoVertices { size: 2 })
    );
}

// ---------------------------------------------------------------------------------------------
// Scale
// ---------------------------------------------------------------------------------------------

#[test]
fn large_board_validates_quickly() {
    let comps = random_disjoint_squares(1, 2000, 1 << 16, 400);
    let start = Instant::now();
    let board = Board::new(1 << 16, comps.clone()).unwrap();
    let elapsed = start.elapsed();
    assert_eq!(board.components().len(), 2000);
    assert!(elapsed.as_secs_f64() < 2.0, "{elapsed:?}");
    // reading it back as text is fast too
    let t = write_board_text(&board);
    let start = Instant::now();
    assert_eq!(read_board_text(&t, None).unwrap().components().len(), 2000);
    assert!(start.elapsed().as_secs_f64() < 2.0);
    // one overlapping pair among them is found: a triangle in the corner of square 1001
    let mut bad = comps;
    let o = bad[1000].outline[2];
    bad.push(comp(&[o, [o[0], o[1] - 1], [o[0] - 1, o[1] - 1]]));
    let e = Board::new(1 << 16, bad).unwrap_err();
    assert!(matches!(
        e,
        BoardError::ComponentsTouch {
            component: 1001,
            other: 2001,
            ..
        }
    ));
}

#[test]
fn cost_does_not_depend_on_edge_length() {
    // a perimeter of 2^32 units, 64-unit-wide strips of length 2^30 - 2, a comb with 2^12 teeth
    let size = 1i64 << 30;
    let mut comps = vec![comp(&[[0, 0], [size, 0], [size, 1], [0, 1]])];
    for i in 0..1000 {
        let x = 4 + 64 * i;
        comps.push(comp(&[[x, 2], [x + 32, 2], [x + 32, size], [x, size]]));
    }
    let (x0, x1) = (100_000, 100_000 + 8 * 4096);
    let mut comb = vec![[x0, 4], [x1, 4], [x1, 1000]];
    for t in (0..4096).rev() {
        let x = x0 + 8 * t;
        comb.extend([[x + 6, 1000], [x + 6, 6], [x, 6]]);
        if t > 0 {
            comb.push([x, 1000]);
        }
    }
    comps.push(Component::new(comb));
    let start = Instant::now();
    let b = Board::new(size, comps).unwrap();
    assert!(start.elapsed().as_secs_f64() < 2.0);
    assert!(b.perimeter_steps() > 1 << 32);
}

// ---------------------------------------------------------------------------------------------
// Random boards against the brute force
// ---------------------------------------------------------------------------------------------

#[test]
fn random_boards_agree_with_brute_force() {
    let mut kinds: HashMap<&'static str, usize> = HashMap::new();
    for seed in 0..6000u64 {
        let mut r = SmallRng::seed_from_u64(seed);
        let size = 16;
        let n = r.gen_range(1..=4);
        let comps: Vec<Component> = (0..n)
            .filter_map(|_| random_component(&mut r, size))
            .collect();
        if comps.is_empty() {
            continue;
        }
        check_against_oracle(size, &comps);
        let kind = match Board::new(size, comps) {
            Ok(_) => "ok",
            Err(BoardError::SelfIntersection { .. }) => "self",
            Err(BoardError::ComponentsTouch { .. }) => "touch",
            Err(BoardError::ComponentInside { .. }) => "inside",
            Err(_) => "other",
        };
        *kinds.entry(kind).or_default() += 1;
    }
    // every outcome is well represented
    for kind in ["ok", "self", "touch", "inside"] {
        assert!(kinds.get(kind).copied().unwrap_or(0) > 50, "{kinds:?}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// Any text gives Ok or Err from both readers, never a panic, and errors display.
    #[test]
    fn arbitrary_text_never_panics(s in "\\PC{0,200}") {
        if let Err(e) = read_board_text(&s, None) {
            prop_assert!(!e.to_string().is_empty());
        }
        if let Err(e) = read_poly(&s, None) {
            prop_assert!(!e.to_string().is_empty());
        }
    }

    /// Number soup shaped like the formats reaches deeper into both readers.
    #[test]
    fn number_soup_never_panics(
        lines in prop::collection::vec(
            prop::collection::vec(
                prop_oneof![
                    (-3i64..12).prop_map(|v| v.to_string()),
                    Just("#".to_string()),
                    Just("size".to_string()),
                    Just("2".to_string()),
                    Just("0".to_string()),
                    Just("1.5".to_string()),
                    Just("(".to_string()),
                    Just(",".to_string()),
                    Just("9223372036854775807".to_string()),
                    Just("-9223372036854775808".to_string()),
                ],
                0..8,
            ),
            0..16,
        ),
        size in prop::option::of(-2i64..40),
    ) {
        let s: String = lines.iter().map(|l| l.join(" ") + "\n").collect();
        let _ = read_board_text(&s, size).map(|b| write_board_text(&b));
        if let Ok(b) = read_poly(&s, size) {
            let p = write_poly(&b).expect("a board read from .poly has a vertex");
            assert_eq!(outlines(&read_poly(&p, None).unwrap()), outlines(&b));
        }
    }

    /// Random components: `Board::new` agrees with the brute force.
    #[test]
    fn random_components_agree_with_brute_force(seed in any::<u64>(), n in 1usize..6) {
        let mut r = SmallRng::seed_from_u64(seed);
        let comps: Vec<Component> = (0..n).filter_map(|_| random_component(&mut r, 16)).collect();
        check_against_oracle(16, &comps);
    }
}
