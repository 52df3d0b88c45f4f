//! Validation and normalisation of a board: `check_board`, called by [`Board::new`].
//!
//! The checks run in this order, and the first failure is returned as a [`BoardError`]:
//!
//! 1. U is a power of two in 1..=2^30.
//! 2. Each component in input order: at least 3 vertices; every vertex in [0, U]^2; no edge of
//!    length zero; every edge at 0, 45, 90 or 135 degrees.
//! 3. No two edges share a point unless they are consecutive edges of one component meeting only
//!    at their common vertex (so each outline is simple and no two components touch).
//! 4. No component lies inside another.
//!
//! Then each outline is turned counter-clockwise and vertices between two collinear edges are
//! dropped, keeping `lines` in step.
//!
//! Steps 3 and 4 cost O(E log E) time and O(E) memory for E edges in all, whatever the edges'
//! lengths (so a board with a few very long edges is as cheap as a small one):
//!
//! - Step 3 uses that every edge runs in one of four directions. Edges of one direction that lie
//!   on one line are sorted along it and overlaps found by a scan. For each of the six pairs of
//!   directions an integer shear or rotation maps the two directions to horizontal and vertical
//!   (for the two diagonals, `(x + y, x - y)`; for horizontal and 45 degrees, `(x - y, y)`; and so
//!   on), and a sweep with an ordered set of the horizontal edges finds every crossing. Crossings of
//!   consecutive edges at their common vertex are allowed (there are at most E of them); any other
//!   is an error. Crossing points of two diagonals can be half-integer, so points are reported in
//!   half units.
//! - Step 4 (no component inside another) is a sweep over half-integer lines, in `nesting.rs`.
//!
//! [`Board::new`]: super::Board::new

use super::{BoardError, Component, Point};
use std::collections::BTreeSet;

/// The largest board side, 2^30 (doubled coordinates and their sums then fit easily in `i64`).
const MAX_SIZE: i64 = 1 << 30;

/// Checks and normalises the components of a board of side `size` (see the module doc).
pub(super) fn check_board(
    size: i64,
    mut components: Vec<Component>,
) -> Result<Vec<Component>, BoardError> {
    if !(1..=MAX_SIZE).contains(&size) || size & (size - 1) != 0 {
        return Err(BoardError::SizeNotPowerOfTwo { size });
    }
    for c in &mut components {
        let n = c.outline.len();
        c.lines.resize(n, None);
    }
    for (i, c) in components.iter().enumerate() {
        check_component(size, i + 1, c)?;
    }
    let edges = edge_table(&components);
    check_collinear(&edges)?;
    check_crossings(&edges)?;
    for c in &mut components {
        if c.doubled_area() < 0 {
            reverse(c);
        }
    }
    super::nesting::check_nesting(&components)?;
    for c in &mut components {
        drop_collinear_vertices(c);
    }
    Ok(components)
}

/// Step 2 for component number `number` (from 1).
fn check_component(size: i64, number: usize, c: &Component) -> Result<(), BoardError> {
    let n = c.outline.len();
    if n < 3 {
        return Err(BoardError::TooFewVertices {
            component: number,
            line: c.lines.iter().flatten().next().copied(),
        });
    }
    for (k, p) in c.outline.iter().enumerate() {
        if !(0..=size).contains(&p[0]) || !(0..=size).contains(&p[1]) {
            return Err(BoardError::OutOfRange {
                component: number,
                edge: k + 1,
                point: *p,
                line: c.lines[k],
            });
        }
    }
    for (k, (a, b)) in c.edges().enumerate() {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        if dx == 0 && dy == 0 {
            return Err(BoardError::ZeroLengthEdge {
                component: number,
                edge: k + 1,
                line: c.lines[k],
            });
        }
        if dx != 0 && dy != 0 && dx.abs() != dy.abs() {
            return Err(BoardError::BadAngle {
                component: number,
                edge: k + 1,
                from: a,
                to: b,
                line: c.lines[k],
            });
        }
    }
    Ok(())
}

/// The direction class of an edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Class {
    /// 0 degrees: y constant.
    Horizontal,
    /// 90 degrees: x constant.
    Vertical,
    /// 45 degrees: x - y constant.
    Rising,
    /// 135 degrees: x + y constant.
    Falling,
}

/// One edge of the board, as given (before normalisation).
#[derive(Clone, Copy, Debug)]
struct Edge {
    a: Point,
    b: Point,
    /// Component, from 0.
    component: usize,
    /// Edge within the component, from 0.
    index: usize,
    /// Number of edges of the component.
    count: usize,
    line: Option<usize>,
}

impl Edge {
    fn class(&self) -> Class {
        let (dx, dy) = (self.b[0] - self.a[0], self.b[1] - self.a[1]);
        if dy == 0 {
            Class::Horizontal
        } else if dx == 0 {
            Class::Vertical
        } else if (dx > 0) == (dy > 0) {
            Class::Rising
        } else {
            Class::Falling
        }
    }
}

fn edge_table(components: &[Component]) -> Vec<Edge> {
    (components.iter().enumerate())
        .flat_map(|(component, c)| {
            c.edges().enumerate().map(move |(index, (a, b))| Edge {
                a,
                b,
                component,
                index,
                count: c.outline.len(),
                line: c.lines[index],
            })
        })
        .collect()
}

/// `true` when edges `i` and `j` follow each other along one outline.
fn consecutive(edges: &[Edge], i: usize, j: usize) -> bool {
    let (e, f) = (&edges[i], &edges[j]);
    e.component == f.component
        && ((e.index + 1) % e.count == f.index || (f.index + 1) % f.count == e.index)
}

/// The error for edges `i` and `j` sharing the point `at` (in half units), naming the edge that
/// comes first in the input first.
fn conflict(edges: &[Edge], i: usize, j: usize, at_half_units: Point) -> BoardError {
    let (e, f) = if (edges[i].component, edges[i].index) <= (edges[j].component, edges[j].index) {
        (&edges[i], &edges[j])
    } else {
        (&edges[j], &edges[i])
    };
    if e.component == f.component {
        BoardError::SelfIntersection {
            component: e.component + 1,
            edge: e.index + 1,
            other_edge: f.index + 1,
            at_half_units,
            line: e.line,
        }
    } else {
        BoardError::ComponentsTouch {
            component: e.component + 1,
            edge: e.index + 1,
            other: f.component + 1,
            other_edge: f.index + 1,
            at_half_units,
            line: e.line,
        }
    }
}

/// Step 3, parallel edges: edges of one class on one line must not overlap, and may touch only
/// when they are consecutive (then they meet at their common vertex).
fn check_collinear(edges: &[Edge]) -> Result<(), BoardError> {
    // (class, line key, lo, hi, edge): the edge covers the parameter range [lo, hi] of its line.
    let mut items: Vec<(Class, i64, i64, i64, usize)> = edges
        .iter()
        .enumerate()
        .map(|(id, e)| {
            let (a, b) = (e.a, e.b);
            let class = e.class();
            let (key, ta, tb) = match class {
                Class::Horizontal => (a[1], a[0], b[0]),
                Class::Vertical => (a[0], a[1], b[1]),
                Class::Rising => (a[1] - a[0], a[0], b[0]),
                Class::Falling => (a[0] + a[1], a[0], b[0]),
            };
            (class, key, ta.min(tb), ta.max(tb), id)
        })
        .collect();
    items.sort_unstable();
    // The point at doubled parameter `t2` of a line, in half units.
    let point = |class: Class, key: i64, t2: i64| -> Point {
        match class {
            Class::Horizontal => [t2, 2 * key],
            Class::Vertical => [2 * key, t2],
            Class::Rising => [t2, t2 + 2 * key],
            Class::Falling => [t2, 2 * key - t2],
        }
    };
    // (class, key, the largest hi so far on this line, the edge reaching it)
    let mut run: Option<(Class, i64, i64, usize)> = None;
    for &(class, key, lo, hi, id) in &items {
        match run {
            Some((c, k, end, holder)) if c == class && k == key => {
                if lo < end {
                    // Overlap [lo, min(hi, end)] of positive length: report its midpoint, which
                    // is never a common vertex.
                    return Err(conflict(
                        edges,
                        holder,
                        id,
                        point(class, key, lo + hi.min(end)),
                    ));
                }
                if lo == end && !consecutive(edges, holder, id) {
                    return Err(conflict(edges, holder, id, point(class, key, 2 * lo)));
                }
                if hi > end {
                    run = Some((class, key, hi, id));
                }
            }
            _ => run = Some((class, key, hi, id)),
        }
    }
    Ok(())
}

/// A segment in sheared coordinates: `fixed` is Y for a horizontal one (X for a vertical one),
/// and it covers `[lo, hi]` of the other coordinate.
#[derive(Clone, Copy)]
struct Seg {
    fixed: i64,
    lo: i64,
    hi: i64,
    edge: usize,
}

/// Step 3, edges of different classes: for each pair of classes, map them to horizontal and
/// vertical with an integer shear or rotation and sweep.
fn check_crossings(edges: &[Edge]) -> Result<(), BoardError> {
    type Map = fn(Point) -> [i64; 2];
    type Back = fn(i64, i64) -> Point;
    // (class mapped to horizontal, class mapped to vertical, map, inverse map in half units)
    let pairs: [(Class, Class, Map, Back); 6] = [
        (
            Class::Horizontal,
            Class::Vertical,
            |p| p,
            |x, y| [2 * x, 2 * y],
        ),
        (
            Class::Rising,
            Class::Falling,
            |p| [p[0] + p[1], p[0] - p[1]],
            |x, y| [x + y, x - y],
        ),
        (
            Class::Horizontal,
            Class::Rising,
            |p| [p[0] - p[1], p[1]],
            |x, y| [2 * (x + y), 2 * y],
        ),
        (
            Class::Horizontal,
            Class::Falling,
            |p| [p[0] + p[1], p[1]],
            |x, y| [2 * (x - y), 2 * y],
        ),
        (
            Class::Rising,
            Class::Vertical,
            |p| [p[0], p[1] - p[0]],
            |x, y| [2 * x, 2 * (y + x)],
        ),
        (
            Class::Falling,
            Class::Vertical,
            |p| [p[0], p[0] + p[1]],
            |x, y| [2 * x, 2 * (y - x)],
        ),
    ];
    let classes: Vec<Class> = edges.iter().map(Edge::class).collect();
    // The segment of mapped ends `a`, `b` fixed on axis `f` (1 for horizontal, 0 for vertical).
    let seg = |f: usize, a: [i64; 2], b: [i64; 2], edge| Seg {
        fixed: a[f],
        lo: a[1 - f].min(b[1 - f]),
        hi: a[1 - f].max(b[1 - f]),
        edge,
    };
    for (hclass, vclass, map, back) in pairs {
        let mut hs = Vec::new();
        let mut vs = Vec::new();
        for (id, e) in edges.iter().enumerate() {
            let (a, b) = (map(e.a), map(e.b));
            if classes[id] == hclass {
                hs.push(seg(1, a, b, id));
            } else if classes[id] == vclass {
                vs.push(seg(0, a, b, id));
            }
        }
        sweep(edges, &hs, &vs, back)?;
    }
    Ok(())
}

/// Finds the crossings of horizontal segments `hs` and vertical segments `vs` (closed), sweeping
/// left to right; any crossing other than that of consecutive edges is an error.
fn sweep(
    edges: &[Edge],
    hs: &[Seg],
    vs: &[Seg],
    back: fn(i64, i64) -> Point,
) -> Result<(), BoardError> {
    if hs.is_empty() || vs.is_empty() {
        return Ok(());
    }
    // (x, kind, index): at one x, horizontal segments start (0) before vertical ones are
    // queried (1) before horizontal ones end (2), as the segments are closed.
    let mut events: Vec<(i64, u8, usize)> = Vec::with_capacity(2 * hs.len() + vs.len());
    for (i, h) in hs.iter().enumerate() {
        events.push((h.lo, 0, i));
        events.push((h.hi, 2, i));
    }
    for (i, v) in vs.iter().enumerate() {
        events.push((v.fixed, 1, i));
    }
    events.sort_unstable();
    let mut active: BTreeSet<(i64, usize)> = BTreeSet::new();
    for (_, kind, i) in events {
        match kind {
            0 => {
                active.insert((hs[i].fixed, i));
            }
            2 => {
                active.remove(&(hs[i].fixed, i));
            }
            _ => {
                let v = &vs[i];
                for &(y, h) in active.range((v.lo, 0)..=(v.hi, usize::MAX)) {
                    // Two non-parallel consecutive edges meet only at their common vertex.
                    if !consecutive(edges, hs[h].edge, v.edge) {
                        return Err(conflict(edges, hs[h].edge, v.edge, back(v.fixed, y)));
                    }
                }
            }
        }
    }
    Ok(())
}

/// Turns an outline around, keeping its first vertex and each edge's line.
fn reverse(c: &mut Component) {
    c.outline[1..].reverse();
    c.lines.reverse();
}

/// Drops every vertex between two edges of the same direction, keeping for each remaining edge
/// the line of its first piece.
fn drop_collinear_vertices(c: &mut Component) {
    let n = c.outline.len();
    let dir = |k: usize| {
        let (a, b) = (c.outline[k], c.outline[(k + 1) % n]);
        [(b[0] - a[0]).signum(), (b[1] - a[1]).signum()]
    };
    let keep: Vec<usize> = (0..n).filter(|&k| dir((k + n - 1) % n) != dir(k)).collect();
    if keep.len() == n {
        return;
    }
    c.outline = keep.iter().map(|&k| c.outline[k]).collect();
    c.lines = keep.iter().map(|&k| c.lines[k]).collect();
}
