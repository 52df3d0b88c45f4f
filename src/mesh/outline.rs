//! The component outlines on the balanced quadtree: which leaves a component edge cuts along a
//! diagonal, which leaf sides lie on an outline, the piece left of each stretch of outline (the
//! seeds of the region labelling), and the mesh edges along each outline (the segments).
//!
//! Every mode of the mesher leaves the outlines meeting each leaf only in corners, whole sides
//! and whole diagonals (see the `refine` module), so an edge is walked leaf by leaf rather than
//! in unit steps: from a point `p` on the edge, the leaf holding the points just past `p` (along
//! the edge, and to the chosen side for an edge on leaf sides) is found from the root in
//! O(depth), and the walk jumps to where the edge leaves it. In the chapter's mesh these leaves
//! are the unit cells along the edge; in coarser meshes there are as many as mesh edges.

use super::refine::InputEdge;
use super::vertices::{Grid, LeafVertices, Numbering};
use super::{Point, Segment, SegmentKind};
use crate::tree::NodeId;

/// [`Outlines::diagonal`] of a leaf cut along its south-west to north-east diagonal.
pub(super) const RISING: u8 = 1;
/// [`Outlines::diagonal`] of a leaf cut along its south-east to north-west diagonal.
pub(super) const FALLING: u8 = 2;

/// What a leaf has on its left where an outline passes it.
#[derive(Clone, Copy, Debug)]
pub(super) enum Piece {
    /// The outline runs along side k (0 S, 1 E, 2 N, 3 W) of the leaf.
    Side(usize),
    /// The outline runs along the leaf's diagonal, with half h on its left (half 0 is the SE half
    /// of a rising diagonal and the SW half of a falling one).
    Half(usize),
}

/// The outlines as seen by the leaves.
pub(super) struct Outlines {
    /// Per node: 0, [`RISING`] or [`FALLING`] when a component edge runs along the diagonal.
    pub diagonal: Vec<u8>,
    /// Per node: bit k set when side k (0 S, 1 E, 2 N, 3 W) lies on an outline. (A side may also
    /// lie half on an outline, from a corner to its midpoint, when the leaves across are smaller;
    /// their sides are marked.)
    pub walls: Vec<u8>,
    /// The piece left of each stretch of outline, with the component (outlines run
    /// counter-clockwise, so the component is on the left).
    pub seeds: Vec<(NodeId, Piece, u32)>,
}

/// The side of a leaf left of an axis-parallel edge with direction `d` lies on: the leaf above
/// an eastward edge has it on its south side, and so on.
fn left_side(d: Point) -> usize {
    match d {
        [1, 0] => 0,
        [0, 1] => 1,
        [-1, 0] => 2,
        _ => 3,
    }
}

/// Walks edge `e` leaf by leaf on its left (or right) side, calling `visit(leaf, from, to)` for
/// each stretch `from -> to` of the edge along the leaf. A diagonal edge runs inside its leaves,
/// which are the same on both sides. An edge on the board's boundary has nothing on its outer
/// side: the walk there visits nothing.
fn walk(grid: &Grid, e: &InputEdge, right: bool, mut visit: impl FnMut(NodeId, Point, Point)) {
    let d = e.direction();
    let normal = if right { [d[1], -d[0]] } else { [-d[1], d[0]] };
    let probe = if d[0] != 0 && d[1] != 0 {
        d
    } else {
        [d[0] + normal[0], d[1] + normal[1]]
    };
    let outside = |a: usize| {
        (probe[a] < 0 && e.a[a] == 0 && d[a] == 0)
            || (probe[a] > 0 && e.a[a] == grid.size && d[a] == 0)
    };
    if outside(0) || outside(1) {
        return;
    }
    let up = [probe[0] > 0, probe[1] > 0];
    let (mut p, mut left) = (e.a, e.steps());
    while left > 0 {
        let leaf = grid.leaf_at(NodeId::ROOT, p, up);
        let (x, y, s) = grid.square(leaf);
        let room = |a: usize, lo: i64| match d[a] {
            0 => i64::MAX,
            1 => lo + s - p[a],
            _ => p[a] - lo,
        };
        let t = room(0, x).min(room(1, y)).min(left);
        debug_assert!(t > 0, "the walk of {e:?} is stuck at {p:?}");
        let q = [p[0] + t * d[0], p[1] + t * d[1]];
        visit(leaf, p, q);
        (p, left) = (q, left - t.max(1));
    }
}

/// The id of `p`, a corner or side midpoint of the leaf with vertices `vx` and square `sq`.
fn vertex_at(vx: &LeafVertices, sq: (i64, i64, i64), p: Point) -> u32 {
    if let Some(k) = super::refine::midpoint_side(p, sq) {
        return vx.mids[k].expect("a component vertex at a side's midpoint is a mesh vertex");
    }
    let (x, y, _) = sq;
    let k = match [p[0] == x, p[1] == y] {
        [true, true] => 0,
        [false, true] => 1,
        [false, false] => 2,
        [true, false] => 3,
    };
    vx.corners[k]
}

/// Walks every component edge (see the module doc): the diagonal cuts, walls and seeds, and the
/// mesh edges along each outline, appended to `segments` in outline order.
pub(super) fn trace_outlines(
    grid: &Grid,
    numbering: &Numbering,
    edges: &[InputEdge],
    segments: &mut Vec<Segment>,
) -> Outlines {
    let nodes = grid.tree.node_count();
    let mut out = Outlines {
        diagonal: vec![0; nodes],
        walls: vec![0; nodes],
        seeds: Vec::new(),
    };
    for e in edges {
        let d = e.direction();
        let kind = SegmentKind::Component(e.component);
        let diagonal = d[0] != 0 && d[1] != 0;
        walk(grid, e, false, |leaf, p, q| {
            let sq = grid.square(leaf);
            let vx = numbering.leaf(leaf);
            let whole = (q[0] - p[0]).abs().max((q[1] - p[1]).abs()) == sq.2;
            let middle = if diagonal {
                out.diagonal[leaf.index()] = if d[0] == d[1] { RISING } else { FALLING };
                out.seeds
                    .push((leaf, Piece::Half((d[0] > 0) as usize), e.component));
                vx.centre
            } else {
                let side = left_side(d);
                out.walls[leaf.index()] |= (whole as u8) << side;
                out.seeds.push((leaf, Piece::Side(side), e.component));
                vx.mids[side].filter(|_| whole)
            };
            let (from, to) = (vertex_at(&vx, sq, p), vertex_at(&vx, sq, q));
            match middle {
                Some(m) => {
                    segments.extend([[from, m], [m, to]].map(|vertices| Segment { vertices, kind }))
                }
                None => segments.push(Segment {
                    vertices: [from, to],
                    kind,
                }),
            }
        });
        if !diagonal {
            let side = (left_side(d) + 2) % 4;
            walk(grid, e, true, |leaf, p, q| {
                let whole = (q[0] - p[0]).abs().max((q[1] - p[1]).abs()) == grid.square(leaf).2;
                out.walls[leaf.index()] |= (whole as u8) << side;
            });
        }
    }
    out
}
