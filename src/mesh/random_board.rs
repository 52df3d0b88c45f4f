//! [`random_board`]: seeded random boards of any size, from the shapes of `samples.rs` placed at
//! random poses on a grid.
//!
//! No randomness crate is used: [`random_board`] draws from a SplitMix64 generator, so a seed
//! gives the same board on every platform and version of its dependencies.

use super::samples::{ccw, chamfered, diamond, rect, swept, Frame};
use super::{Board, Point};

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
