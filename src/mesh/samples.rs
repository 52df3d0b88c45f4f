//! Ready-made boards for examples, tests and benchmarks: [`sample_board`], a fixed board that
//! looks like a small circuit board, and [`random_board`], seeded random boards of any size.
//!
//! Both are built from the shapes a board has: rectangles (pads, chip bodies, connector fingers),
//! rectangles with 45-degree chamfered corners (chips, octagonal pads and mounting holes),
//! 45-degree rotated squares (fiducials), L-shapes, and traces: strips of constant width along a
//! polyline with 45-degree bends. Every vertex is an integer point and every edge runs at 0, 45,
//! 90 or 135 degrees, so both functions always return a board that [`Board::new`] accepts.
//!
//! A trace is built as the region swept by its centre polyline `P` moved along a fixed vector
//! `v` (one of the eight lattice directions, of length the width): the outline is `P` followed by
//! `P + v` backwards. When every run of `P` turns the same way towards `v` (the cross product of
//! the run's direction and `v` has one sign), `P` is a graph over the axis perpendicular to `v`,
//! so the strip is a simple polygon. A horizontal trace with one 45-degree bend is the chapter's
//! example: bottom side `(x0, y0) -> (x1, y0) -> (x1 + d, y0 + d) -> (x2, y0 + d)`, top side the
//! same moved up by the width.
//!
//! [`random_board`] (in `random_board.rs`) places the same shapes at random.

use super::{Board, Component, Point};

// ---------------------------------------------------------------------------------------------
// Shapes
// ---------------------------------------------------------------------------------------------

/// A component from an outline, turned counter-clockwise (the orientation [`Board::new`]
/// normalises to) so that the shapes below need not care about their winding.
pub(super) fn ccw(outline: Vec<Point>) -> Component {
    let mut c = Component::new(outline);
    if c.doubled_area() < 0 {
        c.outline.reverse();
    }
    c
}

/// The axis rectangle `[x0, x1] x [y0, y1]`.
pub(super) fn rect(x0: i64, y0: i64, x1: i64, y1: i64) -> Vec<Point> {
    debug_assert!(x0 < x1 && y0 < y1);
    vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
}

/// The rectangle `[x0, x1] x [y0, y1]` with its corners (south-west, south-east, north-east,
/// north-west) cut at 45 degrees by `c[k]` units each (0: a square corner). Needs the cuts of two
/// corners on one side to leave a positive length of that side.
pub(super) fn chamfered(x0: i64, y0: i64, x1: i64, y1: i64, c: [i64; 4]) -> Vec<Point> {
    debug_assert!(c[0] + c[1] < x1 - x0 && c[2] + c[3] < x1 - x0);
    debug_assert!(c[1] + c[2] < y1 - y0 && c[3] + c[0] < y1 - y0);
    let corners = [
        [[x0, y0 + c[0]], [x0 + c[0], y0]],
        [[x1 - c[1], y0], [x1, y0 + c[1]]],
        [[x1, y1 - c[2]], [x1 - c[2], y1]],
        [[x0 + c[3], y1], [x0, y1 - c[3]]],
    ];
    let mut out = Vec::with_capacity(8);
    for (k, [a, b]) in corners.into_iter().enumerate() {
        out.push(a);
        if c[k] > 0 {
            out.push(b);
        }
    }
    out
}

/// The square of half-side `r` centred at `(cx, cy)` with every corner cut by `c`: an octagon.
pub(super) fn octagon(cx: i64, cy: i64, r: i64, c: i64) -> Vec<Point> {
    chamfered(cx - r, cy - r, cx + r, cy + r, [c; 4])
}

/// The square rotated by 45 degrees with centre `(cx, cy)` and half-diagonal `r`.
pub(super) fn diamond(cx: i64, cy: i64, r: i64) -> Vec<Point> {
    vec![[cx, cy - r], [cx + r, cy], [cx, cy + r], [cx - r, cy]]
}

/// The strip swept by the polyline `path` moved along `v` (see the module doc): `path`, then
/// `path + v` backwards. Every run of `path` must have a lattice direction whose cross product
/// with `v` has the same sign, consecutive runs differing in direction; `v` must be a lattice
/// direction too (axis or diagonal).
pub(super) fn swept(path: &[Point], v: Point) -> Vec<Point> {
    debug_assert!(path.len() >= 2);
    debug_assert!(path.windows(2).all(|w| {
        let d = [w[1][0] - w[0][0], w[1][1] - w[0][1]];
        d[0] * v[1] - d[1] * v[0] != 0 && (d[0] == 0 || d[1] == 0 || d[0].abs() == d[1].abs())
    }));
    let mut out = path.to_vec();
    out.extend(path.iter().rev().map(|p| [p[0] + v[0], p[1] + v[1]]));
    out
}

/// A lattice frame: local `(u, w)` is `origin + u * ex + w * ey` on the board, with `ex`, `ey`
/// orthogonal unit axis vectors. Its eight choices of axes are the symmetries of the square, so
/// shapes built in the frame keep their angles and simplicity.
#[derive(Clone, Copy)]
pub(super) struct Frame {
    pub(super) origin: Point,
    pub(super) ex: Point,
    pub(super) ey: Point,
}

impl Frame {
    /// The identity frame.
    const ID: Frame = Frame {
        origin: [0, 0],
        ex: [1, 0],
        ey: [0, 1],
    };

    /// The board point of local point `p`.
    fn point(&self, p: Point) -> Point {
        let v = self.vector(p);
        [self.origin[0] + v[0], self.origin[1] + v[1]]
    }

    /// The board vector of local vector `v`.
    fn vector(&self, v: Point) -> Point {
        [
            v[0] * self.ex[0] + v[1] * self.ey[0],
            v[0] * self.ex[1] + v[1] * self.ey[1],
        ]
    }

    /// The outline mapped to the board.
    pub(super) fn outline(&self, local: &[Point]) -> Vec<Point> {
        local.iter().map(|&p| self.point(p)).collect()
    }
}

/// A bundle of traces of width `w` running "up" in `frame` from local height `y0` to `y1`: trace
/// `k` starts at local `x = a[k]`, runs up to `turn`, bends by 45 degrees to `x = b[k]`, and runs
/// up again. With `a` and `b` increasing and consecutive entries more than `w` apart, the traces
/// are disjoint: the gap between two neighbours, at any height, is monotone between its values
/// `a[k + 1] - a[k]` and `b[k + 1] - b[k]` (minus `w`). Needs `turn + max |b[k] - a[k]| < y1`.
fn fan(
    frame: Frame,
    a: &[i64],
    b: &[i64],
    (y0, turn, y1): (i64, i64, i64),
    w: i64,
) -> Vec<Vec<Point>> {
    a.iter()
        .zip(b)
        .map(|(&a, &b)| {
            let (a, b) = (a - w / 2, b - w / 2);
            let top = turn + (b - a).abs();
            debug_assert!(y0 < turn && top < y1);
            let path = if a == b {
                vec![[a, y0], [a, y1]]
            } else {
                vec![[a, y0], [a, turn], [b, top], [b, y1]]
            };
            swept(&frame.outline(&path), frame.vector([w, 0]))
        })
        .collect()
}

// ---------------------------------------------------------------------------------------------
// The sample board
// ---------------------------------------------------------------------------------------------

/// Side of [`sample_board`].
const SAMPLE_SIZE: i64 = 1024;

/// Components being laid out, one outline each.
type Layout = Vec<Vec<Point>>;

/// One side of the board's lower half, laid out for the left side and mirrored for the right:
/// an 8-pin SOIC chip near the edge and a bus of 4 traces that leaves 4 of the edge connector's
/// fingers upwards, bends by 45 degrees and ends level with 4 of the chip's pins.
fn lower_side(out: &mut Layout, mirror: bool) {
    let frame = if mirror {
        Frame {
            origin: [SAMPLE_SIZE, 0],
            ex: [-1, 0],
            ey: [0, 1],
        }
    } else {
        Frame::ID
    };
    let mut add = |local: Vec<Point>| out.push(frame.outline(&local));
    // The chip body, pin 1 marked by a chamfer; 4 pins a side, 12 x 20, 6 from the body.
    add(chamfered(60, 260, 140, 420, [0, 0, 0, 10]));
    for k in 0..4 {
        let y = 286 + 30 * k;
        add(rect(34, y - 6, 54, y + 6));
        add(rect(146, y - 6, 166, y + 6));
    }
    // The bus: finger k (centre 212 + 40 k) to pin k (centre 286 + 30 k), width 3, swept along
    // (3, 3): up, 45 degrees up and left, then left, ending 3 units right of the pin.
    for k in 0..4 {
        let (x, y) = (211 + 40 * k, 285 + 30 * k);
        let path = [[x, 72], [x, y - 20], [x - 20, y], [169, y]];
        add(swept(&path, [3, 3]));
    }
    // A mounting hole and a fiducial.
    add(octagon(40, 40, 18, 6));
    add(diamond(110, 150, 9));
}

/// A fixed board on U = 1024 that looks like a small circuit board, with 147 components:
///
/// - an edge connector of 16 fingers along the bottom edge (touching the board boundary);
/// - a QFP chip in the centre (chamfered pin-1 corner) with 7 pads a side, each side fanned out
///   by 7 traces of width 3 or 4 with 45-degree bends: down to the edge connector, up to a row
///   of octagonal header pads, left to a column of test pads, right to a column of resistors;
/// - two SOIC chips left and right of the fan, each wired to 4 connector fingers by a bus of
///   traces that turn by 90 degrees in two 45-degree bends;
/// - a large chip with all four corners chamfered and its row of pads, a crystal between two
///   octagonal pads, two capacitors, four octagonal mounting holes and diamond fiducials.
///
/// Components are pairwise at least one unit apart; traces stop 2 to 4 units short of the pads
/// they lead to.
///
/// # Panics
/// Never: the board is a fixed, valid board (its tests build it).
///
/// ```
/// use orthtree::mesh::{sample_board, Board};
/// let board = sample_board();
/// assert_eq!(board.size(), 1024);
/// assert!(board.components().len() > 40);
/// // it is a valid board: validating its components again accepts them unchanged
/// let again = Board::new(board.size(), board.components().to_vec()).unwrap();
/// assert_eq!(again, board);
/// // the edge connector touches the bottom side of the board
/// assert!(board.components().iter().any(|c| c.outline.iter().any(|p| p[1] == 0)));
/// ```
pub fn sample_board() -> Board {
    let mut out = Layout::new();
    let u = SAMPLE_SIZE;

    // Edge connector J1: 16 fingers, 20 wide and 70 tall, pitch 40, centres 212 + 40 i.
    for i in 0..16 {
        out.push(rect(202 + 40 * i, 0, 222 + 40 * i, 70));
    }

    // U1, a QFP: body [412, 612] x [520, 720], pin 1 chamfered (north-west). 7 pads a side,
    // 10 x 24, pitch 20, 8 from the body; centres 452 + 20 k (along x) and 560 + 20 k (along y).
    out.push(chamfered(412, 520, 612, 720, [0, 0, 0, 16]));
    let along: Vec<i64> = (0..7).map(|k| 452 + 20 * k).collect();
    let across: Vec<i64> = (0..7).map(|k| 560 + 20 * k).collect();
    for k in 0..7 {
        let (x, y) = (along[k], across[k]);
        out.push(rect(x - 5, 488, x + 5, 512)); // bottom
        out.push(rect(x - 5, 728, x + 5, 752)); // top
        out.push(rect(380, y - 5, 404, y + 5)); // left
        out.push(rect(620, y - 5, 644, y + 5)); // right
    }

    // Bottom fan: fingers 4 to 10 (centres 372 + 40 k) up to the bottom pads, width 4; finger 11
    // is left unconnected.
    let fingers: Vec<i64> = (0..7).map(|k| 372 + 40 * k).collect();
    out.extend(fan(Frame::ID, &fingers, &along, (72, 120, 486), 4));

    // Top fan: top pads up to header J2, 7 octagonal pads of side 16 at y 900..916.
    let header: Vec<i64> = (0..7).map(|k| 392 + 40 * k).collect();
    out.extend(fan(Frame::ID, &along, &header, (754, 780, 896), 4));
    for &x in &header {
        out.push(octagon(x, 908, 8, 3));
    }

    // Left fan: left pads out to a column of 7 test pads, 14 x 14, pitch 30 (centres 530 + 30 k).
    // In the frame local x = board y and local up = board left (local y = -board x).
    let tests: Vec<i64> = (0..7).map(|k| 530 + 30 * k).collect();
    let left = Frame {
        origin: [0, 0],
        ex: [0, 1],
        ey: [-1, 0],
    };
    out.extend(fan(left, &across, &tests, (-378, -360, -273), 3));
    for &y in &tests {
        out.push(rect(256, y - 7, 270, y + 7));
    }

    // Right fan: right pads out to a column of 7 resistors (pairs of 12 x 14 pads, 14 apart),
    // mirrored: local x = board y and local up = board right.
    let right = Frame {
        origin: [0, 0],
        ex: [0, 1],
        ey: [1, 0],
    };
    out.extend(fan(right, &across, &tests, (646, 664, 751), 3));
    for &y in &tests {
        out.push(rect(754, y - 7, 766, y + 7));
        out.push(rect(780, y - 7, 792, y + 7));
    }

    // The lower corners: SOIC chips U2 and U3, their buses, mounting holes, fiducials.
    lower_side(&mut out, false);
    lower_side(&mut out, true);

    // Upper left: U4, a large chip with every corner chamfered, and a row of 5 pads under it.
    out.push(chamfered(80, 770, 240, 870, [12; 4]));
    for k in 0..5 {
        let x = 100 + 30 * k;
        out.push(rect(x - 5, 736, x + 5, 756));
    }

    // Upper right: crystal Y1 between two octagonal pads, a row of 4 capacitors above it.
    out.push(chamfered(820, 790, 900, 830, [6; 4]));
    out.push(octagon(800, 810, 8, 3));
    out.push(octagon(920, 810, 8, 3));
    for x in [800, 860] {
        out.push(rect(x - 12, 880, x - 2, 892));
        out.push(rect(x + 2, 880, x + 12, 892));
    }

    // Mounting holes at the upper corners, a fiducial upper left.
    out.push(octagon(40, u - 40, 18, 6));
    out.push(octagon(u - 40, u - 40, 18, 6));
    out.push(diamond(110, u - 110, 9));

    let components = out.into_iter().map(ccw).collect();
    Board::new(u, components).expect("the sample board is valid by construction")
}
