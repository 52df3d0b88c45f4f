//! Region labels of the mesh (step 4 of the mesher's module doc), before triangulation so that
//! each triangle gets its region as it is made.
//!
//! A leaf lies in one region, except a leaf cut along its diagonal by a component edge, which is
//! two halves ("pieces"). The piece left of each stretch of a component outline (outlines run
//! counter-clockwise) is in the component; labels spread from piece to piece across leaf sides
//! that are not on an outline, which visits only the pieces inside components; every other piece
//! is board (region 0). A flood fill with an explicit stack: O(pieces inside components) steps,
//! each a neighbour search of O(depth).

use super::outline::{Outlines, Piece, RISING};
use super::vertices::Grid;
use crate::geom::Direction;
use crate::tree::NodeId;

/// The sides of a cell in the order south, east, north, west (counter-clockwise from the bottom).
pub(super) const SIDES: [Direction; 4] = [
    Direction::SOUTH,
    Direction::EAST,
    Direction::NORTH,
    Direction::WEST,
];

/// Region labels of the pieces of the leaves, 0 = board: `[whole leaf, unused]`, or for a leaf
/// cut by a diagonal `[half 0, half 1]` (see [`half_touching`]).
pub(super) struct Labels(Vec<[u32; 2]>);

impl Labels {
    /// The labels of a leaf's pieces.
    pub fn of(&self, leaf: NodeId) -> [u32; 2] {
        self.0[leaf.index()]
    }
}

/// The half of a diagonal cell that touches side `side` (0 S, 1 E, 2 N, 3 W): half 0 is the SE
/// half of a rising diagonal and the SW half of a falling one.
pub(super) fn half_touching(rising: bool, side: usize) -> usize {
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

/// Labels the pieces inside components by flood fill from their outlines.
pub(super) fn label_pieces(grid: &Grid, outlines: &Outlines) -> Labels {
    let tree = grid.tree;
    let rising = |leaf: NodeId| match outlines.diagonal[leaf.index()] {
        0 => None,
        d => Some(d == RISING),
    };
    // The piece of `leaf` touching side `side`.
    let piece_at = |leaf: NodeId, side: usize| rising(leaf).map_or(0, |r| half_touching(r, side));
    let mut labels = Labels(vec![[0, 0]; tree.node_count()]);
    let mut stack: Vec<(NodeId, usize)> = Vec::new();
    for &(leaf, piece, component) in &outlines.seeds {
        let half = match piece {
            Piece::Side(side) => piece_at(leaf, side),
            Piece::Half(h) => h,
        };
        if labels.0[leaf.index()][half] == 0 {
            labels.0[leaf.index()][half] = component;
            stack.push((leaf, half));
        }
    }
    let mut neighbours = Vec::new();
    while let Some((leaf, half)) = stack.pop() {
        let component = labels.0[leaf.index()][half];
        for &side in sides_of(rising(leaf).map(|r| (r, half))) {
            neighbours.clear();
            tree.leaf_neighbors(leaf, SIDES[side], &mut neighbours);
            for &m in &neighbours {
                // The smaller leaf's side is the shared stretch, wholly on an outline or not.
                let facing = (side + 2) % 4;
                let (w, k) = if tree.level(m) >= tree.level(leaf) {
                    (m, facing)
                } else {
                    (leaf, side)
                };
                if outlines.walls[w.index()] & (1 << k) != 0 {
                    continue;
                }
                let h = piece_at(m, facing);
                if labels.0[m.index()][h] == 0 {
                    labels.0[m.index()][h] = component;
                    stack.push((m, h));
                }
            }
        }
    }
    labels
}
