//! The chapter's GENERATEMESH (section 14.3, Theorem 14.5), exactly:
//!
//! 1. Build a quadtree on the board's cells: split a cell while it is larger than unit size and
//!    its closed square meets a closed component edge. Each node keeps the edges meeting it; a
//!    child filters its parent's list, so the work is O(p(S) log U). Explicit stack, no recursion.
//! 2. 2:1 balance with face connectivity, in the shared [`Tree::balance`].
//! 3. Triangulate each leaf: a unit cell crossed by a component diagonal is cut along it; a leaf
//!    with only its four corners on its boundary is cut along one diagonal; otherwise a Steiner
//!    point at its centre is joined to every vertex on its boundary (its corners and the midpoints
//!    of sides next to smaller leaves; balance allows at most one per side). Every triangle has
//!    angles 45, 45 and 90 degrees, and every vertex is a grid point.
//! 4. Regions, before step 3 so that each triangle gets its region as it is made: a leaf lies in
//!    one region, except a unit cell cut by a component diagonal, which is two halves ("pieces").
//!    The piece left of each unit step of a component outline (outlines run counter-clockwise) is
//!    in the component; labels spread from piece to piece across leaf sides that are not on an
//!    outline, which visits only the pieces inside components; every other piece is board.

use super::vertices::Numbering;
use super::{Board, BoardError, Mesh, Point, Segment, SegmentKind};
use crate::geom::{Cell, Connectivity};
use crate::hash::FastMap;
use crate::tree::{NodeId, Tree};
use crate::Direction;
use std::time::{Duration, Instant};

/// What [`generate_mesh`] produced, with counts and times of its phases.
#[derive(Clone, Debug)]
pub struct MeshOutcome {
    /// The mesh.
    pub mesh: Mesh,
    /// The quadtree after balance.
    pub tree: Tree<2>,
    /// Leaves before balance.
    pub leaves_before_balance: usize,
    /// Time to build the quadtree.
    pub build_time: Duration,
    /// Time to balance it.
    pub balance_time: Duration,
    /// Time to triangulate the leaves and label regions.
    pub triangulate_time: Duration,
}

/// One component edge: endpoints and component number (from 1).
#[derive(Clone, Copy, Debug)]
struct InputEdge {
    a: Point,
    b: Point,
    component: u32,
}

/// Meshes a board with the chapter's algorithm (see the module doc).
///
/// Complexity: O(p(S) log U) triangles, built in O(p(S) log^2 U) (Theorem 14.5).
///
/// Errors: none for a validated [`Board`]; the `Result` is kept for the checks later modes add.
///
/// ```
/// use orthtree::mesh::{generate_mesh, Board, Component};
/// // the chapter's Figure 14.2: U = 16, a unit square at distance 1 from the left and top sides
/// let board = Board::new(16, vec![Component::new(vec![[1, 14], [2, 14], [2, 15], [1, 15]])]).unwrap();
/// let out = generate_mesh(&board).unwrap();
/// let area2: i64 = out.mesh.triangles.iter().map(|t| {
///     let [a, b, c] = t.map(|v| out.mesh.vertices[v as usize]);
///     (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
/// }).sum();
/// assert_eq!(area2, 2 * 16 * 16);
/// assert_eq!(out.mesh.regions.iter().filter(|&&r| r == 1).count(), 2);
/// ```
pub fn generate_mesh(board: &Board) -> Result<MeshOutcome, BoardError> {
    let start = Instant::now();
    let edges: Vec<InputEdge> = board
        .components()
        .iter()
        .enumerate()
        .flat_map(|(i, c)| {
            c.edges().map(move |(a, b)| InputEdge {
                a,
                b,
                component: i as u32 + 1,
            })
        })
        .collect();
    let mut tree = build_quadtree(board, &edges);
    let build_time = start.elapsed();
    let leaves_before_balance = tree.leaf_count();

    let start = Instant::now();
    tree.balance(Connectivity::Face);
    let balance_time = start.elapsed();

    let start = Instant::now();
    let diagonals = diagonal_cells(&edges);
    let mut cells = vec![Cell::<2>::root(); tree.node_count()];
    for (id, cell) in tree.pre_order() {
        cells[id.index()] = cell;
    }
    let labels = label_pieces(board, &tree, &cells, &edges, &diagonals);
    let mesh = triangulate(board, &tree, &cells, &edges, &diagonals, &labels);
    let triangulate_time = start.elapsed();
    Ok(MeshOutcome {
        mesh,
        tree,
        leaves_before_balance,
        build_time,
        balance_time,
        triangulate_time,
    })
}

/// The closed square of `cell` on a board of side `size`: (x0, y0, side).
fn square(cell: &Cell<2>, size: i64) -> (i64, i64, i64) {
    let side = size >> cell.level();
    let [x, y] = cell.coords();
    (x as i64 * side, y as i64 * side, side)
}

/// `true` when the closed segment meets the closed square, exactly: the segment is
/// `a + t * d`, `0 <= t <= steps`, with `d` in {-1, 0, 1}^2, and each axis bounds `t`.
fn meets(e: &InputEdge, (x0, y0, side): (i64, i64, i64)) -> bool {
    let delta = [e.b[0] - e.a[0], e.b[1] - e.a[1]];
    let steps = delta[0].abs().max(delta[1].abs());
    let (mut lo, mut hi) = (0i64, steps);
    for (axis, min) in [(0, x0), (1, y0)] {
        let (a, max) = (e.a[axis], min + side);
        match delta[axis].signum() {
            0 if a < min || a > max => return false,
            0 => {}
            1 => (lo, hi) = (lo.max(min - a), hi.min(max - a)),
            _ => (lo, hi) = (lo.max(a - max), hi.min(a - min)),
        }
    }
    lo <= hi
}

/// Step 1: split while larger than unit size and meeting a component edge.
fn build_quadtree(board: &Board, edges: &[InputEdge]) -> Tree<2> {
    let mut tree = Tree::<2>::new();
    // Edge lists of the nodes on the stack, one run each, in stack order.
    let mut lists: Vec<u32> = (0..edges.len() as u32).collect();
    let mut mine: Vec<u32> = Vec::new();
    let mut stack = vec![(NodeId::ROOT, Cell::<2>::root(), 0usize)];
    while let Some((v, cell, begin)) = stack.pop() {
        // The node on top of the stack owns the last run of `lists`: move it out.
        mine.clear();
        mine.extend_from_slice(&lists[begin..]);
        lists.truncate(begin);
        if square(&cell, board.size()).2 <= 1 || mine.is_empty() {
            continue;
        }
        tree.split(v);
        // Children in reverse, so that child 0, pushed last, owns the last run.
        for c in (0..4).rev() {
            let child_cell = cell.child(c);
            let child_sq = square(&child_cell, board.size());
            let child_begin = lists.len();
            lists.extend(
                mine.iter()
                    .filter(|&&e| meets(&edges[e as usize], child_sq)),
            );
            let child = tree.child(v, c).expect("just split");
            stack.push((child, child_cell, child_begin));
        }
    }
    tree
}

/// Unit cells cut by a component diagonal, keyed by their lower-left corner; `true` for the
/// rising diagonal (SW-NE).
fn diagonal_cells(edges: &[InputEdge]) -> FastMap<Point, bool> {
    let mut cells = FastMap::default();
    for e in edges {
        let d = [(e.b[0] - e.a[0]).signum(), (e.b[1] - e.a[1]).signum()];
        if d[0] == 0 || d[1] == 0 {
            continue;
        }
        let steps = (e.b[0] - e.a[0]).abs();
        for t in 0..steps {
            let p = [e.a[0] + t * d[0], e.a[1] + t * d[1]];
            let corner = [p[0].min(p[0] + d[0]), p[1].min(p[1] + d[1])];
            cells.insert(corner, d[0] == d[1]);
        }
    }
    cells
}

/// Step 3: triangles of every leaf, and the board-boundary and input segments.
fn triangulate(
    board: &Board,
    tree: &Tree<2>,
    cells: &[Cell<2>],
    edges: &[InputEdge],
    diagonals: &FastMap<Point, bool>,
    labels: &Labels,
) -> Mesh {
    let u = board.size();
    let cut = |leaf: NodeId| {
        let (x, y, s) = square(&cells[leaf.index()], u);
        s == 1 && diagonals.contains_key(&[x, y])
    };
    let numbering = Numbering::new(tree, cells, u, cut);
    let mut triangles = Vec::with_capacity(tree.leaf_count() * 3);
    let mut regions = Vec::with_capacity(tree.leaf_count() * 3);
    let mut segments = Vec::new();
    let mut ring = Vec::with_capacity(8);
    for (leaf, cell) in tree.leaves() {
        let (x, y, s) = square(&cell, u);
        let vx = numbering.leaf(leaf);
        let ids = vx.corners;
        // Sides on the board's boundary (south, east, north, west): one mesh edge each, since
        // no smaller leaf lies beyond them.
        for (k, on_boundary) in [y == 0, x + s == u, y + s == u, x == 0]
            .into_iter()
            .enumerate()
        {
            if on_boundary {
                let vertices = [ids[k], ids[(k + 1) % 4]];
                segments.push(Segment {
                    vertices,
                    kind: SegmentKind::Boundary,
                });
            }
        }
        if let Some(&rising) = diagonals.get(&[x, y]).filter(|_| s == 1) {
            // Half 0 first: the SE half of a rising diagonal, the SW half of a falling one.
            if rising {
                triangles.extend([[ids[0], ids[1], ids[2]], [ids[0], ids[2], ids[3]]]);
            } else {
                triangles.extend([[ids[0], ids[1], ids[3]], [ids[1], ids[2], ids[3]]]);
            }
            regions.extend(labels.of(leaf));
            continue;
        }
        let region = labels.of(leaf)[0];
        let Some(centre) = vx.centre else {
            triangles.extend([[ids[0], ids[1], ids[2]], [ids[0], ids[2], ids[3]]]);
            regions.extend([region; 2]);
            continue;
        };
        ring.clear();
        for (&corner, &mid) in ids.iter().zip(&vx.mids) {
            ring.push(corner);
            ring.extend(mid);
        }
        for k in 0..ring.len() {
            triangles.push([centre, ring[k], ring[(k + 1) % ring.len()]]);
            regions.push(region);
        }
    }
    outline_segments(edges, &numbering, &mut segments);
    Mesh {
        vertices: numbering.coords,
        triangles,
        regions,
        segments,
    }
}

/// The unit steps of every component edge, as mesh segments.
fn outline_segments(edges: &[InputEdge], numbering: &Numbering, out: &mut Vec<Segment>) {
    for e in edges {
        let d = [(e.b[0] - e.a[0]).signum(), (e.b[1] - e.a[1]).signum()];
        let steps = (e.b[0] - e.a[0]).abs().max((e.b[1] - e.a[1]).abs());
        // Every lattice point of an outline is a corner of the unit cells along it.
        let at = |t: i64| numbering.at([e.a[0] + t * d[0], e.a[1] + t * d[1]]);
        let mut from = at(0);
        for t in 1..=steps {
            let to = at(t);
            out.push(Segment {
                vertices: [from, to],
                kind: SegmentKind::Component(e.component),
            });
            from = to;
        }
    }
}

/// The sides of a cell in the order south, east, north, west (counter-clockwise from the bottom).
const SIDES: [Direction; 4] = [
    Direction::SOUTH,
    Direction::EAST,
    Direction::NORTH,
    Direction::WEST,
];

/// Region labels of the pieces of the leaves, 0 = board: `[whole leaf, unused]`, or for a unit
/// cell cut by a diagonal `[half 0, half 1]` (see [`half_touching`]).
struct Labels(Vec<[u32; 2]>);

impl Labels {
    fn of(&self, leaf: NodeId) -> [u32; 2] {
        self.0[leaf.index()]
    }
}

/// The half of a diagonal cell that touches side `side` (0 S, 1 E, 2 N, 3 W): half 0 is the SE
/// half of a rising diagonal and the SW half of a falling one.
fn half_touching(rising: bool, side: usize) -> usize {
    match (rising, side) {
        (true, 0 | 1) | (false, 0 | 3) => 0,
        _ => 1,
    }
}

/// The sides a piece touches: all four for a whole leaf, two for a half.
fn sides_of(half: Option<(bool, usize)>) -> &'static [usize] {
    match half {
        None => &[0, 1, 2, 3],
        Some((true, 0)) => &[0, 1],
        Some((true, _)) => &[2, 3],
        Some((false, 0)) => &[0, 3],
        Some((false, _)) => &[1, 2],
    }
}

/// Step 4: label the pieces inside components by flood fill from their outlines.
fn label_pieces(
    board: &Board,
    tree: &Tree<2>,
    cells: &[Cell<2>],
    edges: &[InputEdge],
    diagonals: &FastMap<Point, bool>,
) -> Labels {
    let unit_level = board.levels();
    // Axis-parallel unit steps of the outlines: (lower-left end, horizontal?).
    let mut walls: FastMap<(Point, bool), ()> = FastMap::default();
    let mut labels = Labels(vec![[0, 0]; tree.node_count()]);
    let mut stack: Vec<(NodeId, usize)> = Vec::new();
    let unit = |x: i64, y: i64| {
        let cell = Cell::new(unit_level, [x as u32, y as u32]).expect("a unit cell on the board");
        tree.locate_cell(&cell)
    };
    let half_at = |x: i64, y: i64, side: usize| {
        diagonals
            .get(&[x, y])
            .map_or(0, |&r| half_touching(r, side))
    };
    let mut seeds = Vec::new();
    for e in edges {
        let d = [(e.b[0] - e.a[0]).signum(), (e.b[1] - e.a[1]).signum()];
        let steps = (e.b[0] - e.a[0]).abs().max((e.b[1] - e.a[1]).abs());
        for t in 0..steps {
            let [x, y] = [e.a[0] + t * d[0], e.a[1] + t * d[1]];
            // The unit cell left of the step, and the half of it there.
            let (cx, cy, half) = match d {
                [1, 0] => (x, y, half_at(x, y, 0)),
                [0, 1] => (x - 1, y, half_at(x - 1, y, 1)),
                [-1, 0] => (x - 1, y - 1, half_at(x - 1, y - 1, 2)),
                [0, -1] => (x, y - 1, half_at(x, y - 1, 3)),
                [1, 1] => (x, y, 1),
                [-1, -1] => (x - 1, y - 1, 0),
                [1, -1] => (x, y - 1, 1),
                _ => (x - 1, y, 0),
            };
            if d[0] == 0 || d[1] == 0 {
                walls.insert(([x.min(x + d[0]), y.min(y + d[1])], d[1] == 0), ());
            }
            seeds.push((unit(cx, cy), half, e.component));
        }
    }
    for (leaf, half, component) in seeds {
        if labels.0[leaf.index()][half] == 0 {
            labels.0[leaf.index()][half] = component;
            stack.push((leaf, half));
        }
    }
    let mut neighbours = Vec::new();
    while let Some((leaf, half)) = stack.pop() {
        let component = labels.0[leaf.index()][half];
        let cell = cells[leaf.index()];
        let (x, y, s) = square(&cell, board.size());
        let diagonal = if s == 1 {
            diagonals.get(&[x, y]).map(|&r| (r, half))
        } else {
            None
        };
        for &side in sides_of(diagonal) {
            let wall = match side {
                0 => ([x, y], true),
                1 => ([x + 1, y], false),
                2 => ([x, y + 1], true),
                _ => ([x, y], false),
            };
            if s == 1 && walls.contains_key(&wall) {
                continue;
            }
            neighbours.clear();
            tree.leaf_neighbors(leaf, SIDES[side], &mut neighbours);
            for &m in &neighbours {
                let (mx, my, ms) = square(&cells[m.index()], board.size());
                let facing = (side + 2) % 4;
                let h = if ms == 1 {
                    diagonals
                        .get(&[mx, my])
                        .map_or(0, |&r| half_touching(r, facing))
                } else {
                    0
                };
                if labels.0[m.index()][h] == 0 {
                    labels.0[m.index()][h] = component;
                    stack.push((m, h));
                }
            }
        }
    }
    labels
}
