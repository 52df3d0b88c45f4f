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
//! No randomness crate is used: [`random_board`] draws from a SplitMix64 generator, so a seed
//! gives the same board on every platform and version of its dependencies.

use super::{Board, Component, Point};

// ---------------------------------------------------------------------------------------------
// Shapes
// ---------------------------------------------------------------------------------------------

/// A component from an outline, turned counter-clockwise (the orientation [`Board::new`]
/// normalises to) so that the shapes below need not care about their winding.
fn ccw(mut outline: Vec<Point>) -> Component {
    let doubled: i128 = (0..outline.len())
        .map(|i| {
            let (a, b) = (outline[i], outline[(i + 1) % outline.len()]);
            a[0] as i128 * b[1] as i128 - b[0] as i128 * a[1] as i128
        })
        .sum();
    if doubled < 0 {
        outline.reverse();
    }
    Component::new(outline)
}

/// The axis rectangle `[x0, x1] x [y0, y1]`.
fn rect(x0: i64, y0: i64, x1: i64, y1: i64) -> Vec<Point> {
    debug_assert!(x0 < x1 && y0 < y1);
    vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
}

/// The rectangle `[x0, x1] x [y0, y1]` with its corners (south-west, south-east, north-east,
/// north-west) cut at 45 degrees by `c[k]` units each (0: a square corner). Needs the cuts of two
/// corners on one side to leave a positive length of that side.
fn chamfered(x0: i64, y0: i64, x1: i64, y1: i64, c: [i64; 4]) -> Vec<Point> {
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
fn octagon(cx: i64, cy: i64, r: i64, c: i64) -> Vec<Point> {
    chamfered(cx - r, cy - r, cx + r, cy + r, [c; 4])
}

/// The square rotated by 45 degrees with centre `(cx, cy)` and half-diagonal `r`.
fn diamond(cx: i64, cy: i64, r: i64) -> Vec<Point> {
    vec![[cx, cy - r], [cx + r, cy], [cx, cy + r], [cx - r, cy]]
}

/// The strip swept by the polyline `path` moved along `v` (see the module doc): `path`, then
/// `path + v` backwards. Every run of `path` must have a lattice direction whose cross product
/// with `v` has the same sign, consecutive runs differing in direction; `v` must be a lattice
/// direction too (axis or diagonal).
fn swept(path: &[Point], v: Point) -> Vec<Point> {
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
struct Frame {
    origin: Point,
    ex: Point,
    ey: Point,
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
        [
            self.origin[0] + p[0] * self.ex[0] + p[1] * self.ey[0],
            self.origin[1] + p[0] * self.ex[1] + p[1] * self.ey[1],
        ]
    }

    /// The board vector of local vector `v`.
    fn vector(&self, v: Point) -> Point {
        [
            v[0] * self.ex[0] + v[1] * self.ey[0],
            v[0] * self.ex[1] + v[1] * self.ey[1],
        ]
    }

    /// The outline mapped to the board.
    fn outline(&self, local: &[Point]) -> Vec<Point> {
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
            let path: Vec<Point> = path.into_iter().map(|p| frame.point(p)).collect();
            swept(&path, frame.vector([w, 0]))
        })
        .collect()
}

// ---------------------------------------------------------------------------------------------
// The sample board
// ---------------------------------------------------------------------------------------------

/// Side of [`sample_board`].
const SAMPLE_SIZE: i64 = 1024;

/// Components being laid out.
#[derive(Default)]
struct Layout {
    parts: Vec<Vec<Point>>,
}

impl Layout {
    fn add(&mut self, outline: Vec<Point>) {
        self.parts.push(outline);
    }

    fn extend(&mut self, outlines: impl IntoIterator<Item = Vec<Point>>) {
        self.parts.extend(outlines);
    }
}

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
    let mut add = |local: Vec<Point>| out.add(frame.outline(&local));
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
    let mut out = Layout::default();
    let u = SAMPLE_SIZE;

    // Edge connector J1: 16 fingers, 20 wide and 70 tall, pitch 40, centres 212 + 40 i.
    for i in 0..16 {
        out.add(rect(202 + 40 * i, 0, 222 + 40 * i, 70));
    }

    // U1, a QFP: body [412, 612] x [520, 720], pin 1 chamfered (north-west). 7 pads a side,
    // 10 x 24, pitch 20, 8 from the body; centres 452 + 20 k (along x) and 560 + 20 k (along y).
    out.add(chamfered(412, 520, 612, 720, [0, 0, 0, 16]));
    let along: Vec<i64> = (0..7).map(|k| 452 + 20 * k).collect();
    let across: Vec<i64> = (0..7).map(|k| 560 + 20 * k).collect();
    for k in 0..7 {
        let (x, y) = (along[k], across[k]);
        out.add(rect(x - 5, 488, x + 5, 512)); // bottom
        out.add(rect(x - 5, 728, x + 5, 752)); // top
        out.add(rect(380, y - 5, 404, y + 5)); // left
        out.add(rect(620, y - 5, 644, y + 5)); // right
    }

    // Bottom fan: fingers 4 to 10 (centres 372 + 40 k) up to the bottom pads, width 4; finger 11
    // is left unconnected.
    let fingers: Vec<i64> = (0..7).map(|k| 372 + 40 * k).collect();
    out.extend(fan(Frame::ID, &fingers, &along, (72, 120, 486), 4));

    // Top fan: top pads up to header J2, 7 octagonal pads of side 16 at y 900..916.
    let header: Vec<i64> = (0..7).map(|k| 392 + 40 * k).collect();
    out.extend(fan(Frame::ID, &along, &header, (754, 780, 896), 4));
    for &x in &header {
        out.add(octagon(x, 908, 8, 3));
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
        out.add(rect(256, y - 7, 270, y + 7));
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
        out.add(rect(754, y - 7, 766, y + 7));
        out.add(rect(780, y - 7, 792, y + 7));
    }

    // The lower corners: SOIC chips U2 and U3, their buses, mounting holes, fiducials.
    lower_side(&mut out, false);
    lower_side(&mut out, true);

    // Upper left: U4, a large chip with every corner chamfered, and a row of 5 pads under it.
    out.add(chamfered(80, 770, 240, 870, [12; 4]));
    for k in 0..5 {
        let x = 100 + 30 * k;
        out.add(rect(x - 5, 736, x + 5, 756));
    }

    // Upper right: crystal Y1 between two octagonal pads, a row of 4 capacitors above it.
    out.add(chamfered(820, 790, 900, 830, [6; 4]));
    out.add(octagon(800, 810, 8, 3));
    out.add(octagon(920, 810, 8, 3));
    for x in [800, 860] {
        out.add(rect(x - 12, 880, x - 2, 892));
        out.add(rect(x + 2, 880, x + 12, 892));
    }

    // Mounting holes at the upper corners, a fiducial upper left.
    out.add(octagon(40, u - 40, 18, 6));
    out.add(octagon(u - 40, u - 40, 18, 6));
    out.add(diamond(110, u - 110, 9));

    let components = out.parts.into_iter().map(ccw).collect();
    Board::new(u, components).expect("the sample board is valid by construction")
}

// ---------------------------------------------------------------------------------------------
// Random boards
// ---------------------------------------------------------------------------------------------

/// SplitMix64 (Steele, Lea and Flood, 2014): tiny, fast, and good enough to place shapes.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `lo..=hi` (up to a bias of at most 2^-32 for the ranges used here).
    fn range(&mut self, lo: i64, hi: i64) -> i64 {
        debug_assert!(lo <= hi);
        let span = (hi - lo) as u64 + 1;
        lo + ((self.next() as u128 * span as u128) >> 64) as i64
    }

    /// `true` with probability 1/2.
    fn coin(&mut self) -> bool {
        self.next() >> 63 == 1
    }
}

/// One random shape of extent about `e` (at least 2) in local coordinates, before moving it.
fn random_shape(rng: &mut SplitMix64, e: i64) -> Vec<Point> {
    let side = |rng: &mut SplitMix64| rng.range((e / 2).max(1), e);
    match rng.range(0, 5) {
        // An axis rectangle (a pad or a chip body).
        0 => rect(0, 0, side(rng), side(rng)),
        // A rectangle with chamfered corners (an octagon when all four are cut).
        1 => {
            let (w, h) = (side(rng).max(3), side(rng).max(3));
            let c = rng.range(1, (w.min(h) - 1) / 2);
            let all = rng.coin();
            let cuts = [(); 4].map(|()| if all || rng.coin() { c } else { 0 });
            chamfered(0, 0, w, h, cuts)
        }
        // A diamond.
        2 => {
            let r = (side(rng) / 2).max(1);
            diamond(r, r, r)
        }
        // An L-shape.
        3 => {
            let (w, h) = (side(rng).max(2), side(rng).max(2));
            let (tx, ty) = (rng.range(1, w - 1), rng.range(1, h - 1));
            vec![[0, 0], [w, 0], [w, ty], [tx, ty], [tx, h], [0, h]]
        }
        // A trace (drawn twice as often as the other shapes): runs along x alternating with
        // 45-degree runs, swept up by its width.
        _ => {
            let width = rng.range(1, (e / 4).clamp(1, 4));
            let bends = rng.range(1, 3);
            let (mut x, mut y) = (0, 0);
            let mut path = vec![[x, y]];
            for k in 0..=2 * bends {
                let run = rng.range(1, e.max(2));
                x += run;
                if k % 2 == 1 {
                    y += if rng.coin() { run } else { -run };
                }
                path.push([x, y]);
            }
            swept(&path, [0, width])
        }
    }
}

/// `local` turned by a random symmetry of the square and moved so its bounding box starts at
/// the origin; returns the outline and the bounding box's far corner.
fn random_pose(rng: &mut SplitMix64, local: &[Point]) -> (Vec<Point>, Point) {
    let (ex, ey) = match rng.range(0, 7) {
        0 => ([1, 0], [0, 1]),
        1 => ([-1, 0], [0, 1]),
        2 => ([1, 0], [0, -1]),
        3 => ([-1, 0], [0, -1]),
        4 => ([0, 1], [1, 0]),
        5 => ([0, -1], [1, 0]),
        6 => ([0, 1], [-1, 0]),
        _ => ([0, -1], [-1, 0]),
    };
    let turned = Frame {
        origin: [0, 0],
        ex,
        ey,
    }
    .outline(local);
    let lo = [0, 1].map(|a| turned.iter().map(|p| p[a]).min().unwrap_or(0));
    let moved: Vec<Point> = turned
        .iter()
        .map(|p| [p[0] - lo[0], p[1] - lo[1]])
        .collect();
    let hi = [0, 1].map(|a| moved.iter().map(|p| p[a]).max().unwrap_or(0));
    (moved, hi)
}

/// A seeded random board of side `size` with up to `count` components.
///
/// Components are axis rectangles, rectangles with chamfered corners (octagons among them),
/// diamonds (squares turned by 45 degrees), L-shapes and traces with 45-degree bends, each turned
/// by a random symmetry of the square. Their extents are spread over scales from 2 units to
/// `size / 4` (log-uniformly), so the quadtree has both fine and coarse parts. Each is placed at a
/// uniform random position with rejection: its bounding box must keep at least one unit from
/// every earlier bounding box, so no two components touch; they may touch the board's boundary.
///
/// The result is always a valid board, for every seed. It may hold fewer than `count`
/// components: placement gives up after `20 * count + 100` rejected attempts in all, which
/// happens when the board fills up (small `size`, large `count`). The same arguments give the
/// same board on every platform (a built-in SplitMix64 generator is used).
///
/// # Panics
///
/// If `size` is not a power of two from 8 to 2^30.
///
/// ```
/// use orthtree::mesh::{random_board, Board};
/// let board = random_board(7, 256, 40);
/// assert_eq!(board.size(), 256);
/// assert!(board.components().len() <= 40);
/// assert!(board.components().len() >= 10);
/// assert_eq!(random_board(7, 256, 40), board); // deterministic
/// assert!(Board::new(256, board.components().to_vec()).is_ok());
/// // a small board fills up: fewer components than asked for, still valid
/// assert!(random_board(1, 8, 1000).components().len() < 1000);
/// ```
pub fn random_board(seed: u64, size: i64, count: usize) -> Board {
    assert!(
        (8..=1 << 30).contains(&size) && size & (size - 1) == 0,
        "random_board: size {size} is not a power of two from 8 to 2^30"
    );
    let mut rng = SplitMix64(seed);
    let levels = size.trailing_zeros() as i64;
    let mut boxes: Vec<(Point, Point)> = Vec::with_capacity(count);
    let mut outlines = Vec::with_capacity(count);
    let mut rejections = 0;
    while outlines.len() < count && rejections < 20 * count + 100 {
        // Extent 2^l to 2^(l + 1), with l uniform in 1..=levels - 3 (extent up to size / 4).
        let l = rng.range(1, (levels - 3).max(1));
        let e = rng.range(1 << l, 1 << (l + 1));
        let local = random_shape(&mut rng, e);
        let (shape, hi) = random_pose(&mut rng, &local);
        if hi[0] > size || hi[1] > size {
            rejections += 1;
            continue;
        }
        let at = [rng.range(0, size - hi[0]), rng.range(0, size - hi[1])];
        let (lo, hi) = (at, [at[0] + hi[0], at[1] + hi[1]]);
        let apart = |(l2, h2): &(Point, Point)| {
            hi[0] < l2[0] || h2[0] < lo[0] || hi[1] < l2[1] || h2[1] < lo[1]
        };
        if !boxes.iter().all(apart) {
            rejections += 1;
            continue;
        }
        boxes.push((lo, hi));
        outlines.push(ccw(shape
            .iter()
            .map(|p| [p[0] + at[0], p[1] + at[1]])
            .collect()));
    }
    Board::new(size, outlines).expect("random boards are valid by construction")
}
