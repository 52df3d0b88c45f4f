//! [`random_board`] and [`try_random_board`]: seeded random boards of any size, from the shapes
//! of `samples.rs` placed at random poses on a grid.
//!
//! No randomness crate is used: the boards are drawn from a SplitMix64 generator, so a seed
//! gives the same board on every platform and version of its dependencies. Placement tests each
//! new bounding box against the earlier ones through a small quadtree of boxes
//! ([`BoxIndex`](super::box_index::BoxIndex)), so a board of `n` components takes about
//! `O(n log U)` time, and memory grows with the components placed, never with the count asked
//! for.

use super::box_index::BoxIndex;
use super::samples::{ccw, chamfered, diamond, rect, swept, Frame};
use super::{Board, Point};
use std::fmt;

/// SplitMix64 (Steele, Lea and Flood, 2014): tiny, fast, and good enough to place shapes.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        let z = crate::hash::splitmix64(self.0);
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        z
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

/// Why [`try_random_board`] refused its arguments.
///
/// ```
/// use orthtree::mesh::{try_random_board, RandomBoardError};
/// assert_eq!(
///     try_random_board(0, 12, 5),
///     Err(RandomBoardError::SizeNotPowerOfTwo { size: 12 })
/// );
/// let e = try_random_board(0, 8, 17).unwrap_err();
/// assert_eq!(e, RandomBoardError::TooManyComponents { count: 17, size: 8, capacity: 16 });
/// assert_eq!(
///     e.to_string(),
///     "17 components cannot fit a board of size 8: at most 16 fit ((U / 2)^2, \
///      since every component's bounding box holds a point with both coordinates odd)"
/// );
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum RandomBoardError {
    /// The size is not a power of two from 8 to 2^30.
    SizeNotPowerOfTwo {
        /// The size given.
        size: i64,
    },
    /// More components than any board of this size can hold.
    TooManyComponents {
        /// The count asked for.
        count: usize,
        /// The board's side U.
        size: i64,
        /// The most components a board of side U can hold, `(U / 2)^2`.
        capacity: u64,
    },
}

impl fmt::Display for RandomBoardError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RandomBoardError::SizeNotPowerOfTwo { size } => {
                write!(f, "size {size} is not a power of two from 8 to 2^30")
            }
            RandomBoardError::TooManyComponents {
                count,
                size,
                capacity,
            } => write!(
                f,
                "{count} components cannot fit a board of size {size}: at most {capacity} fit \
                 ((U / 2)^2, since every component's bounding box holds a point with both \
                 coordinates odd)"
            ),
        }
    }
}

impl std::error::Error for RandomBoardError {}

/// Placement stops after this many rejected attempts in a row: the board is full for the shapes
/// drawn (fewer than one attempt in a thousand succeeds).
const MAX_REJECTIONS_IN_A_ROW: usize = 1000;

/// The most components a board of side `size` can hold: `(size / 2)^2`.
///
/// Components are disjoint, and on a random board their bounding boxes are too: every component
/// has a positive area, so its bounding box spans two lattice points on each axis and holds a
/// point whose coordinates are both odd, and [0, U]^2 has `(U / 2)^2` such points.
pub fn random_board_capacity(size: i64) -> u64 {
    let half = (size.max(0) / 2) as u64;
    half.saturating_mul(half)
}

/// A seeded random board of side `size` with up to `count` components; the
/// panicking twin of [`try_random_board`].
///
/// # Panics
///
/// When [`try_random_board`] refuses the arguments: `size` is not a power of two from 8 to
/// 2^30, or `count` is above [`random_board_capacity`]`(size)`.
///
/// ```
/// use orthtree::mesh::{random_board, Board};
/// let board = random_board(7, 256, 40);
/// assert_eq!(board.size(), 256);
/// assert!(board.components().len() <= 40);
/// assert!(board.components().len() >= 10);
/// assert_eq!(random_board(7, 256, 40), board); // deterministic
/// assert!(Board::new(256, board.components().to_vec()).is_ok());
/// ```
pub fn random_board(seed: u64, size: i64, count: usize) -> Board {
    try_random_board(seed, size, count).unwrap_or_else(|e| panic!("random_board: {e}"))
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
/// components: placement gives up after `20 * count + 100` rejected attempts in all, or 1000 in
/// a row, which happens when the board fills up (small `size`, large `count`). The same arguments give the
/// same board on every platform (a built-in SplitMix64 generator is used).
///
/// # Errors
///
/// [`RandomBoardError::SizeNotPowerOfTwo`] unless `size` is a power of two from 8 to 2^30;
/// [`RandomBoardError::TooManyComponents`] when `count` is above
/// [`random_board_capacity`]`(size)`, which no placement could reach.
///
/// # Complexity
///
/// At most `21 * count + 100` attempts, each a test against the boxes placed through a quadtree
/// of boxes (`O(log U)` nodes when the boxes near the new one are few). Memory grows with the
/// components placed (nothing is reserved for `count` up front), so a large `count` on a board
/// that fills up early costs only the board it gets.
///
/// # Examples
///
/// # Panics
/// Never: every component it places was checked to fit, so the board is valid.
///
/// ```
/// use orthtree::mesh::{try_random_board, RandomBoardError};
/// let board = try_random_board(7, 256, 40)?;
/// assert!(board.components().len() <= 40);
/// // a small board fills up: fewer components than asked for, still valid
/// assert!(try_random_board(1, 8, 16)?.components().len() < 16);
/// // more than can ever fit: refused at once, nothing allocated
/// assert!(try_random_board(1, 8, 100_000_000).is_err());
/// # Ok::<(), RandomBoardError>(())
/// ```
pub fn try_random_board(seed: u64, size: i64, count: usize) -> Result<Board, RandomBoardError> {
    if !(8..=1 << 30).contains(&size) || size & (size - 1) != 0 {
        return Err(RandomBoardError::SizeNotPowerOfTwo { size });
    }
    let capacity = random_board_capacity(size);
    if count as u64 > capacity {
        return Err(RandomBoardError::TooManyComponents {
            count,
            size,
            capacity,
        });
    }
    let mut rng = SplitMix64(seed);
    let levels = size.trailing_zeros() as i64;
    let mut placed = BoxIndex::new(size);
    let mut outlines = Vec::new();
    let (mut rejections, mut in_a_row) = (0usize, 0usize);
    let max_rejections = count.saturating_mul(20).saturating_add(100);
    while outlines.len() < count
        && rejections < max_rejections
        && in_a_row < MAX_REJECTIONS_IN_A_ROW
    {
        // Extent 2^l to 2^(l + 1), with l uniform in 1..=levels - 3 (extent up to size / 4).
        let l = rng.range(1, (levels - 3).max(1));
        let e = rng.range(1 << l, 1 << (l + 1));
        let local = random_shape(&mut rng, e);
        let (shape, hi) = random_pose(&mut rng, &local);
        // Rejected when it does not fit the board or meets a placed one.
        let fits = hi[0] <= size && hi[1] <= size;
        let at = fits.then(|| [rng.range(0, size - hi[0]), rng.range(0, size - hi[1])]);
        let Some(at) = at.filter(|at| !placed.meets(*at, [at[0] + hi[0], at[1] + hi[1]])) else {
            rejections += 1;
            in_a_row += 1;
            continue;
        };
        in_a_row = 0;
        placed.insert(at, [at[0] + hi[0], at[1] + hi[1]]);
        outlines.push(ccw(shape
            .iter()
            .map(|p| [p[0] + at[0], p[1] + at[1]])
            .collect()));
    }
    Ok(Board::new(size, outlines).expect("random boards are valid by construction"))
}
