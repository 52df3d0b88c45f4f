//! Step 1 of the mesher: the quadtree on the board's cells, and the rule that splits a cell.
//!
//! The chapter's GENERATEMESH (section 14.3) splits a cell while it is larger than unit size and
//! its closed square meets a closed component edge. [`SplitRule`] generalises that rule in the
//! ways [`MeshOptions`](super::MeshOptions) offers: the size next to component edges may be any
//! power of two of grid units (the chapter's is one), cells may be capped everywhere (a maximum
//! size, or a user size function as in Chew's refinement, where the user says where a cell is
//! fine enough), and the coarsest mode splits a cell only where the triangulation of step 3 could
//! not respect the input otherwise ([`must_split`]):
//!
//! - a component edge crosses the open square other than along one full diagonal, or
//! - a component vertex lies on the closed square other than at a corner or a side's midpoint.
//!
//! A leaf that passes both tests meets the component outlines only in corners, side midpoints,
//! whole or half sides and a whole diagonal. After balance, [`provide_midpoints`] splits the leaf
//! across each side whose midpoint is a component vertex, so that the midpoint is a mesh vertex;
//! then the triangles of step 3 (which have every corner, every side or half side and, when a
//! component cuts the leaf, that diagonal or its two halves among their edges) respect the
//! input. A unit cell always
//! passes: its corners are the only lattice points on it, so an edge through its interior joins
//! two opposite corners. Splitting therefore stops at unit size in every mode.
//!
//! Each node keeps the edges meeting its closed square; a child filters its parent's list, so the
//! chapter's O(p(S) log U) work bound holds in book mode. Explicit stack, no recursion.

use super::{Board, OptionsError, Point, SizeFn};
use crate::geom::Cell;
use crate::tree::{NodeId, Tree};

/// One component edge: endpoints and component number (from 1).
#[derive(Clone, Copy, Debug)]
pub(super) struct InputEdge {
    pub a: Point,
    pub b: Point,
    pub component: u32,
}

impl InputEdge {
    /// The unit lattice direction from `a` to `b`.
    pub fn direction(&self) -> Point {
        [
            (self.b[0] - self.a[0]).signum(),
            (self.b[1] - self.a[1]).signum(),
        ]
    }

    /// The length in lattice steps (a diagonal step counts one).
    pub fn steps(&self) -> i64 {
        (self.b[0] - self.a[0])
            .abs()
            .max((self.b[1] - self.a[1]).abs())
    }

    /// `true` when `p` lies on the closed segment.
    fn holds(&self, p: Point) -> bool {
        let d = self.direction();
        let t = (p[0] - self.a[0]) * d[0] + (p[1] - self.a[1]) * d[1];
        let t = if d[0] != 0 && d[1] != 0 { t / 2 } else { t };
        (0..=self.steps()).contains(&t) && [self.a[0] + t * d[0], self.a[1] + t * d[1]] == p
    }
}

/// The edges of every component, outlines counter-clockwise, components numbered from 1.
pub(super) fn input_edges(board: &Board) -> Vec<InputEdge> {
    (board.components().iter().enumerate())
        .flat_map(|(i, c)| {
            c.edges().map(move |(a, b)| InputEdge {
                a,
                b,
                component: i as u32 + 1,
            })
        })
        .collect()
}

/// The closed square of `cell` on a board of side `size`: (x0, y0, side).
pub(super) fn square(cell: &Cell<2>, size: i64) -> (i64, i64, i64) {
    let side = size >> cell.level();
    let [x, y] = cell.coords();
    (x as i64 * side, y as i64 * side, side)
}

/// The parameters `t` in `[lo, hi]` where `a + t d` lies in the square, per axis: with `open`,
/// strictly inside it on every axis the edge moves along, and strictly between the lines on an
/// axis it does not move along. Empty when `lo > hi` (closed) or `lo >= hi` (open).
fn clip(e: &InputEdge, (x0, y0, side): (i64, i64, i64), open: bool) -> Option<(i64, i64)> {
    let d = e.direction();
    let (mut lo, mut hi) = (0i64, e.steps());
    let (mut open_lo, mut open_hi) = (i64::MIN, i64::MAX);
    for (axis, min) in [(0, x0), (1, y0)] {
        let (a, max) = (e.a[axis], min + side);
        let (l, h) = match d[axis] {
            0 if a < min || a > max || (open && (a == min || a == max)) => return None,
            0 => continue,
            1 => (min - a, max - a),
            _ => (a - max, a - min),
        };
        if open {
            (open_lo, open_hi) = (open_lo.max(l), open_hi.min(h));
        } else {
            (lo, hi) = (lo.max(l), hi.min(h));
        }
    }
    if open {
        // Some t in [0, steps] with open_lo < t < open_hi.
        (open_lo < open_hi && lo < open_hi && open_lo < hi).then_some((lo, hi))
    } else {
        (lo <= hi).then_some((lo, hi))
    }
}

/// `true` when the closed segment meets the closed square, exactly.
fn meets(e: &InputEdge, sq: (i64, i64, i64)) -> bool {
    clip(e, sq, false).is_some()
}

/// Where a point lies on a closed square: 0-3 the midpoint of side k (S, E, N, W), 4 a corner,
/// 5 elsewhere on the square, 6 off it.
fn place(p: Point, (x0, y0, s): (i64, i64, i64)) -> u8 {
    let (h, on) = (s / 2, |a: i64, lo: i64| a == lo || a == lo + s);
    if !(x0..=x0 + s).contains(&p[0]) || !(y0..=y0 + s).contains(&p[1]) {
        6
    } else if on(p[0], x0) && on(p[1], y0) {
        4
    } else if s >= 2 && p[0] == x0 + h && on(p[1], y0) {
        2 * u8::from(p[1] != y0) // S or N
    } else if s >= 2 && p[1] == y0 + h && on(p[0], x0) {
        3 - 2 * u8::from(p[0] != x0) // W or E
    } else {
        5
    }
}

/// The side of the square whose midpoint is `p`, if any.
pub(super) fn midpoint_side(p: Point, sq: (i64, i64, i64)) -> Option<usize> {
    Some(place(p, sq) as usize).filter(|&k| k < 4)
}

/// `true` when the triangles of step 3 could not respect `e` in a leaf with square `sq`: the
/// edge crosses the open square other than along a full diagonal, or one of its endpoints (a
/// component vertex) lies on the closed square other than at a corner or a side's midpoint.
///
/// A component vertex at the midpoint of side k is allowed: the leaf keeps it as a mesh vertex
/// (with a Steiner point at its centre) once the leaf across side k is split, which
/// [`provide_midpoints`] ensures after balance. An edge may then run along half a side.
pub(super) fn must_split(e: &InputEdge, sq: (i64, i64, i64)) -> bool {
    if [e.a, e.b].iter().any(|&p| place(p, sq) == 5) {
        return true;
    }
    if clip(e, sq, true).is_none() {
        return false;
    }
    let (x0, y0, s) = sq;
    let rising = e.holds([x0, y0]) && e.holds([x0 + s, y0 + s]);
    let falling = e.holds([x0 + s, y0]) && e.holds([x0, y0 + s]);
    !(rising || falling)
}

/// The leaf below `start` (with square `sq`) holding the points just beside `p` on the side
/// given by `up` (per axis: true for p + e, false for p - e), and its square. O(depth).
pub(super) fn leaf_beside(
    tree: &Tree<2>,
    start: NodeId,
    sq: (i64, i64, i64),
    p: Point,
    up: [bool; 2],
) -> (NodeId, (i64, i64, i64)) {
    let (mut v, (mut x, mut y, mut s)) = (start, sq);
    while let Some(first) = tree.child(v, 0) {
        s /= 2;
        let mid = [x + s, y + s];
        let bit = |a: usize| if up[a] { p[a] >= mid[a] } else { p[a] > mid[a] };
        let (bx, by) = (bit(0), bit(1));
        (x, y) = (x + s * bx as i64, y + s * by as i64);
        v = NodeId(first.0 + bx as u32 + 2 * by as u32);
    }
    (v, (x, y, s))
}

/// After balance: every component vertex at the midpoint of a leaf's side must be a mesh vertex,
/// so the node across that side at the leaf's level must be split. Splits the leaf across where
/// it is not (a leaf there of the same size, or larger) and balances again, until none is left.
/// A split leaf's children meet the outlines as it did, in corners, whole sides, half sides and
/// whole diagonals, so no new demand arises inside them; each round refines the leaves across by
/// a level, so the rounds end within the tree's depth. Returns the number of rounds that split.
pub(super) fn provide_midpoints(tree: &mut Tree<2>, size: i64, edges: &[InputEdge]) -> usize {
    let root = (0, 0, size);
    let mut rounds = 0;
    loop {
        let mut todo = Vec::new();
        for e in edges {
            let p = e.a;
            for up in [[false, false], [true, false], [false, true], [true, true]] {
                let outside = (0..2).any(|a| (up[a] && p[a] == size) || (!up[a] && p[a] == 0));
                if outside {
                    continue;
                }
                let (leaf, sq) = leaf_beside(tree, NodeId::ROOT, root, p, up);
                let Some(k) = midpoint_side(p, sq) else {
                    continue;
                };
                let across = tree.neighbor(leaf, super::labels::SIDES[k]);
                if let Some(n) = across.filter(|&n| tree.is_leaf(n)) {
                    todo.push(n);
                }
            }
        }
        if todo.is_empty() {
            return rounds;
        }
        todo.sort_unstable();
        todo.dedup();
        for n in todo {
            tree.split(n);
        }
        tree.balance(crate::Connectivity::Face);
        rounds += 1;
    }
}

/// When a cell is split, in grid units of the board being meshed (see the module doc). Wherever
/// [`must_split`] holds the cell is split in every mode: in the chapter's (near size one unit) it
/// never holds of a cell larger than a unit that the size rule keeps, so it adds nothing there.
pub(super) struct SplitRule<'a> {
    /// Cells meeting a component edge are split while larger than this.
    pub near: i64,
    /// Every cell is split while larger than this.
    pub max: i64,
    /// The grid unit in board coordinates, to call `size_fn` in board coordinates.
    pub unit: i64,
    /// The user's size function: a cell is split while its side exceeds the value at its centre.
    pub size_fn: Option<&'a SizeFn>,
}

impl SplitRule<'_> {
    /// Whether the cell with square `sq` and the edges `mine` meeting it is split.
    fn split(
        &self,
        sq: (i64, i64, i64),
        edges: &[InputEdge],
        mine: &[u32],
    ) -> Result<bool, OptionsError> {
        let (x0, y0, s) = sq;
        if s <= 1 {
            return Ok(false);
        }
        if let Some(f) = self.size_fn {
            let g = self.unit as f64;
            let at = [
                (x0 as f64 + s as f64 / 2.0) * g,
                (y0 as f64 + s as f64 / 2.0) * g,
            ];
            let value = f(at);
            if value.is_nan() {
                return Err(OptionsError::SizeFunctionNaN { at });
            }
            if value <= 0.0 {
                return Err(OptionsError::SizeFunctionNotPositive { at, value });
            }
            if s as f64 * g > value {
                return Ok(true);
            }
        }
        if s > self.max || (s > self.near && !mine.is_empty()) {
            return Ok(true);
        }
        Ok(mine.iter().any(|&e| must_split(&edges[e as usize], sq)))
    }
}

/// Step 1: the quadtree, split by `rule` from the root down. Errors from the size function, and
/// as soon as the leaves (each at least two triangles) imply more than `max_triangles`
/// triangles, so that at most `max_triangles / 2` leaves are ever made.
pub(super) fn build_quadtree(
    size: i64,
    edges: &[InputEdge],
    rule: &SplitRule,
    max_triangles: u64,
) -> Result<Tree<2>, OptionsError> {
    let mut tree = Tree::<2>::new();
    let mut leaves: u64 = 1;
    // Edge lists of the nodes on the stack, one run each, in stack order.
    let mut lists: Vec<u32> = (0..edges.len() as u32).collect();
    let mut mine: Vec<u32> = Vec::new();
    let mut stack = vec![(NodeId::ROOT, Cell::<2>::root(), 0usize)];
    while let Some((v, cell, begin)) = stack.pop() {
        // The node on top of the stack owns the last run of `lists`: move it out.
        mine.clear();
        mine.extend_from_slice(&lists[begin..]);
        lists.truncate(begin);
        if !rule.split(square(&cell, size), edges, &mine)? {
            continue;
        }
        leaves += 3;
        super::budget::check(2 * leaves, max_triangles)?;
        tree.split(v);
        // Children in reverse, so that child 0, pushed last, owns the last run.
        for c in (0..4).rev() {
            let child_cell = cell.child(c);
            let child_sq = square(&child_cell, size);
            let child_begin = lists.len();
            lists.extend(
                mine.iter()
                    .filter(|&&e| meets(&edges[e as usize], child_sq)),
            );
            let child = tree.child(v, c).expect("just split");
            stack.push((child, child_cell, child_begin));
        }
    }
    Ok(tree)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn edge(a: Point, b: Point) -> InputEdge {
        InputEdge { a, b, component: 1 }
    }

    #[test]
    fn diagonals_and_vertices() {
        let sq = (0, 0, 4);
        // the full rising diagonal, and a longer edge along it
        assert!(!must_split(&edge([0, 0], [4, 4]), sq));
        assert!(!must_split(&edge([-2, -2], [6, 6]), sq));
        // the falling diagonal
        assert!(!must_split(&edge([4, 0], [0, 4]), sq));
        // half a diagonal: a vertex at the centre
        assert!(must_split(&edge([0, 0], [2, 2]), sq));
        // a vertex at a side's midpoint, the edge along half the side or away from the square
        assert!(!must_split(&edge([0, 0], [0, 2]), sq));
        assert!(!must_split(&edge([2, 4], [2, 6]), sq));
        // a vertex at a quarter of a side
        assert!(must_split(&edge([0, 0], [1, 0]), sq));
        // a diagonal that is not the cell's
        assert!(must_split(&edge([1, 0], [4, 3]), sq));
        // along a side, whole: fine; ending inside a side: split
        assert!(!must_split(&edge([0, 0], [4, 0]), sq));
        assert!(!must_split(&edge([-4, 4], [8, 4]), sq));
        assert!(must_split(&edge([0, 0], [3, 0]), sq));
        // through the interior, axis-parallel
        assert!(must_split(&edge([2, -1], [2, 5]), sq));
        // touching a corner only, from outside
        assert!(!must_split(&edge([4, 4], [6, 6]), sq));
        assert!(!must_split(&edge([5, 3], [3, 5]), sq));
        // missing the square
        assert!(!must_split(&edge([5, 0], [5, 4]), sq));
        assert!(meets(&edge([4, 4], [6, 6]), sq));
        assert!(!meets(&edge([5, 0], [5, 4]), sq));
    }
}
