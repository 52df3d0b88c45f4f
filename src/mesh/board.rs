//! [`Board`]: the mesher's input (the chapter's section 14.3): the square [0, U]^2 with U = 2^j,
//! and disjoint simple polygonal components with integer vertices and edges at 0, 45, 90 or 135
//! degrees. [`Board::new`] checks all of it and names the offending component, edge and line.

use super::BoardError;

/// An integer point of the board.
pub type Point = [i64; 2];

/// One component: a simple polygon given by its vertices in order (the first not repeated at
/// the end). After [`Board::new`] the vertices run counter-clockwise and no vertex is the middle
/// of two collinear edges.
#[derive(Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Component {
    /// The vertices in order.
    pub outline: Vec<Point>,
    /// For each edge `i` (from vertex `i` to vertex `i + 1`), the input line it came from, if
    /// known; used in error messages.
    pub lines: Vec<Option<usize>>,
}

impl Component {
    /// A component with no line information.
    pub fn new(outline: Vec<Point>) -> Self {
        let lines = vec![None; outline.len()];
        Component { outline, lines }
    }

    /// The edges as (start, end) pairs, the last closing the loop.
    pub fn edges(&self) -> impl Iterator<Item = (Point, Point)> + '_ {
        let n = self.outline.len();
        (0..n).map(move |i| (self.outline[i], self.outline[(i + 1) % n]))
    }

    /// Twice the signed area (positive when counter-clockwise).
    pub fn doubled_area(&self) -> i128 {
        self.edges()
            .map(|(a, b)| a[0] as i128 * b[1] as i128 - b[0] as i128 * a[1] as i128)
            .sum()
    }

    /// The length of the outline in grid units, counting a diagonal step as one unit.
    pub fn perimeter_steps(&self) -> u64 {
        self.edges()
            .map(|(a, b)| {
                (a[0] - b[0])
                    .unsigned_abs()
                    .max((a[1] - b[1]).unsigned_abs())
            })
            .sum()
    }
}

/// A validated board: side `size` = U = 2^j and its components, numbered from 1 in this order
/// (region 0 is the board itself).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Board {
    size: i64,
    components: Vec<Component>,
}

impl Board {
    /// Checks and normalises a board: U a power of two (1 to 2^30); every vertex in [0, U]^2;
    /// every edge non-zero and at 0, 45, 90 or 135 degrees; every component a simple polygon
    /// with at least 3 vertices; no two components touching or overlapping (nor one inside
    /// another). Orients each outline counter-clockwise and drops vertices between collinear
    /// edges.
    ///
    /// # Errors
    /// The first [`BoardError`] found, naming the component, vertex or edge and the rule it
    /// breaks.
    pub fn new(size: i64, components: Vec<Component>) -> Result<Board, BoardError> {
        super::check::check_board(size, components).map(|components| Board { size, components })
    }

    /// The side U.
    pub fn size(&self) -> i64 {
        self.size
    }

    /// j with U = 2^j.
    pub fn levels(&self) -> u8 {
        self.size.trailing_zeros() as u8
    }

    /// The components; component `i` here is region `i + 1` of the mesh.
    pub fn components(&self) -> &[Component] {
        &self.components
    }

    /// The grid unit: the largest power of two dividing U and every vertex coordinate (U itself
    /// for a board without components). Meshing in this unit makes a board scaled by 2^k mesh
    /// to the same triangles, scaled.
    ///
    /// ```
    /// use orthtree::mesh::{Board, Component};
    /// let b = Board::new(64, vec![Component::new(vec![[8, 8], [24, 8], [24, 12], [8, 12]])]).unwrap();
    /// assert_eq!(b.grid_unit(), 4);
    /// assert_eq!(Board::new(64, vec![]).unwrap().grid_unit(), 64);
    /// ```
    pub fn grid_unit(&self) -> i64 {
        let zeros = (self.components.iter())
            .flat_map(|c| c.outline.iter().flatten())
            .filter(|&&c| c != 0)
            .map(|c| c.trailing_zeros())
            .fold(self.size.trailing_zeros(), u32::min);
        1 << zeros
    }

    /// The same board with every coordinate divided by `unit`, which must divide them all.
    pub(super) fn scaled_down(&self, unit: i64) -> Board {
        let scale = |c: &Component| Component {
            outline: c.outline.iter().map(|p| p.map(|x| x / unit)).collect(),
            lines: c.lines.clone(),
        };
        Board {
            size: self.size / unit,
            components: self.components.iter().map(scale).collect(),
        }
    }

    /// p(S): the sum of the components' perimeters, in grid steps.
    pub fn perimeter_steps(&self) -> u64 {
        self.components.iter().map(Component::perimeter_steps).sum()
    }
}
