//! Vertex numbering of the chapter's mesh without hashing: every mesh vertex is a grid point with
//! exactly one owner leaf, so ids are handed out leaf by leaf in Morton order and found again by
//! neighbour search.
//!
//! Ownership: a vertex p belongs to the leaf holding the points just above and right of p
//! (p + (e, e) for a small e > 0). Since every vertex lies on a leaf's boundary or at its centre,
//! and balance leaves at most the midpoint of a side as a vertex inside it, that leaf's owned
//! vertices are: its lower-left corner; the midpoints of its south and west sides when the
//! neighbours there are split; its centre when it has a Steiner point. On the board's top and
//! right edges, where p + (e, e) leaves the board, a leaf also owns its lower-right corner (when
//! its east side is on the edge), its upper-left corner (north side on the edge) and its
//! upper-right corner (both).
//!
//! Pass 1 gives each leaf its first id and a few flags; pass 2 ([`Numbering::leaf`]) finds the
//! ids of a leaf's other corners and midpoints in the leaves east, north and north-east of it.
//! Memory: 5 bytes per node plus the cells the caller already holds.
//!
//! Also [`Grid`], the balanced tree as the later steps read it: the square of a node and point
//! location just beside a grid point.

use super::labels::SIDES;
use super::Point;
use crate::geom::Cell;
use crate::geom::Direction;
use crate::tree::{NodeId, Tree};

/// The balanced quadtree with the cell of every node, on a board of side `size` grid units.
#[derive(Clone, Copy)]
pub(super) struct Grid<'a> {
    /// The tree.
    pub tree: &'a Tree<2>,
    /// The cell of each node, by node index.
    pub cells: &'a [Cell<2>],
    /// The board's side in grid units.
    pub size: i64,
}

impl Grid<'_> {
    /// The closed square of a node: (x0, y0, side).
    pub fn square(&self, id: NodeId) -> (i64, i64, i64) {
        super::refine::square(&self.cells[id.index()], self.size)
    }

    /// The leaf below `start` holding the points just beside `p` on the side given by `up`
    /// (per axis: true for p + e, false for p - e). O(depth).
    pub fn leaf_at(&self, start: NodeId, p: Point, up: [bool; 2]) -> NodeId {
        super::refine::leaf_beside(self.tree, start, self.square(start), p, up).0
    }
}

// Flags per leaf: bit k (0 S, 1 E, 2 N, 3 W) for a midpoint on side k, then the centre.
const MID_S: u8 = 1;
const MID_W: u8 = 8;
const CENTRE: u8 = 16;

/// The ids of a leaf's boundary vertices and centre.
pub(super) struct LeafVertices {
    /// Corners SW, SE, NE, NW.
    pub corners: [u32; 4],
    /// Midpoints of the sides S, E, N, W, where present.
    pub mids: [Option<u32>; 4],
    /// The Steiner point, where present.
    pub centre: Option<u32>,
}

/// Vertex ids and coordinates of the mesh of a balanced quadtree.
pub(super) struct Numbering<'a> {
    grid: Grid<'a>,
    base: Vec<u32>,
    flags: Vec<u8>,
    /// Coordinates by id.
    pub coords: Vec<Point>,
}

impl<'a> Numbering<'a> {
    /// Pass 1. A leaf gets a midpoint on each side whose same-size neighbour is split, and a
    /// Steiner point at its centre when it has a midpoint. (A unit cell never has one, since no
    /// leaf is smaller, so a unit cell cut by a component diagonal stays two triangles.)
    pub fn new(grid: Grid<'a>) -> Self {
        let (tree, size) = (grid.tree, grid.size);
        let mut n = Numbering {
            grid,
            base: vec![0; tree.node_count()],
            flags: vec![0; tree.node_count()],
            coords: Vec::with_capacity(tree.leaf_count() * 3 / 2),
        };
        for (leaf, cell) in tree.leaves() {
            let mut f = 0u8;
            for (k, &d) in SIDES.iter().enumerate() {
                let split = tree
                    .neighbor(leaf, d)
                    .is_some_and(|m| tree.level(m) == cell.level() && !tree.is_leaf(m));
                f |= (split as u8) << k;
            }
            if f != 0 {
                f |= CENTRE;
            }
            n.flags[leaf.index()] = f;
            n.base[leaf.index()] = n.coords.len() as u32;
            let (x, y, s) = n.square(leaf);
            let h = s / 2;
            n.coords.push([x, y]);
            if f & MID_S != 0 {
                n.coords.push([x + h, y]);
            }
            if f & MID_W != 0 {
                n.coords.push([x, y + h]);
            }
            if f & CENTRE != 0 {
                n.coords.push([x + h, y + h]);
            }
            let (right, top) = (x + s == size, y + s == size);
            if right {
                n.coords.push([x + s, y]);
            }
            if top {
                n.coords.push([x, y + s]);
            }
            if right && top {
                n.coords.push([x + s, y + s]);
            }
        }
        n
    }

    fn square(&self, id: NodeId) -> (i64, i64, i64) {
        self.grid.square(id)
    }

    /// The number of triangles step 3 makes: two per leaf without a Steiner point, one per
    /// boundary vertex (four corners and its midpoints) for a leaf with one.
    pub fn triangle_count(&self) -> u64 {
        let per_leaf = |(leaf, _): (NodeId, Cell<2>)| {
            let f = self.flags[leaf.index()];
            if f & CENTRE == 0 {
                2
            } else {
                4 + u64::from((f & 15).count_ones())
            }
        };
        self.grid.tree.leaves().map(per_leaf).sum()
    }

    /// The id of `p`, owned by the leaf `owner` (whose closure holds `p` where it owns it).
    fn owned(&self, owner: NodeId, p: Point) -> u32 {
        let (x, y, s) = self.square(owner);
        let f = self.flags[owner.index()];
        let h = s / 2;
        let own = 1 + (f & MID_S != 0) as u32 + (f & MID_W != 0) as u32 + (f & CENTRE != 0) as u32;
        let (right, top) = (x + s == self.grid.size, y + s == self.grid.size);
        let offset = if p == [x, y] {
            0
        } else if p == [x + h, y] {
            1
        } else if p == [x, y + h] {
            1 + (f & MID_S != 0) as u32
        } else if p == [x + h, y + h] {
            own - 1
        } else if p == [x + s, y] && right {
            own
        } else if p == [x, y + s] && top {
            own + right as u32
        } else {
            debug_assert!(
                p == [x + s, y + s] && right && top,
                "{p:?} is not owned by {x},{y},{s}"
            );
            own + 2
        };
        self.base[owner.index()] + offset
    }

    /// The id of `p` found from `hint`, a node whose cell holds the owner of `p`.
    fn via(&self, hint: NodeId, p: Point) -> u32 {
        let size = self.grid.size;
        let up = [p[0] < size, p[1] < size];
        self.owned(self.grid.leaf_at(hint, p, up), p)
    }

    /// Pass 2: the ids of a leaf's corners, midpoints and centre.
    pub fn leaf(&self, leaf: NodeId) -> LeafVertices {
        let (x, y, s) = self.square(leaf);
        let (h, f) = (s / 2, self.flags[leaf.index()]);
        let (right, top) = (x + s == self.grid.size, y + s == self.grid.size);
        let own = self.base[leaf.index()];
        let neighbour = |d: Direction| self.grid.tree.neighbor(leaf, d).expect("inside the board");
        let east = (!right).then(|| neighbour(Direction::EAST));
        let north = (!top).then(|| neighbour(Direction::NORTH));
        let id = |p: Point| -> u32 {
            // The owner of p lies in the leaf itself, or east, north or north-east of it.
            let east_of = p[0] == x + s && !right;
            let north_of = p[1] == y + s && !top;
            match (east_of, north_of) {
                (false, false) => self.owned(leaf, p),
                (true, false) => self.via(east.expect("east"), p),
                (false, true) => self.via(north.expect("north"), p),
                (true, true) => {
                    let ne = Direction::NORTH
                        .combine(Direction::EAST)
                        .expect("distinct axes");
                    self.via(neighbour(ne), p)
                }
            }
        };
        let corners = [[x, y], [x + s, y], [x + s, y + s], [x, y + s]];
        let mid_points = [[x + h, y], [x + s, y + h], [x + h, y + s], [x, y + h]];
        LeafVertices {
            corners: [own, id(corners[1]), id(corners[2]), id(corners[3])],
            mids: core::array::from_fn(|k| (f & (1 << k) != 0).then(|| id(mid_points[k]))),
            centre: (f & CENTRE != 0).then(|| self.owned(leaf, [x + h, y + h])),
        }
    }
}
