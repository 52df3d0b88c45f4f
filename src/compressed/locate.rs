//! [`PointLocator`]: point location in a planar subdivision with a compressed quadtree, exercise
//! 14.10 of de Berg, Cheong, van Kreveld and Overmars, *Computational Geometry* (chapter 14).
//!
//! # Structure
//! The exercise's rule: split a square until it holds at most one vertex and only edges incident
//! to it, or no vertex and at most one edge. Squares are closed cells of a [`RootGeometry`] over
//! the vertices (the cells, keys and split convention of the point trees). As in the compressed
//! quadtree of exercise 14.5, a child whose contents (its vertices, and its edges clipped to it)
//! fit in the closed box of a smaller cell is replaced by the smallest such cell, so chains of
//! squares with a single non-empty child are not stored. Every node keeps, per quadrant, the
//! face of the points of the quadrant outside its child (that region meets no edge, so one face
//! covers it). Leaves keep their edges; a leaf with a vertex answers by binary search over the
//! vertex's edges sorted by angle (the "additional data structure" the exercise asks for,
//! [`Subdivision`]'s half-edges around each vertex).
//!
//! [`PointLocator::new`] stops at a square without a vertex whatever its edges: those cross the
//! square without meeting, and the nearest of them decides the face (the segment from the query
//! to its nearest edge point stays in the convex square and crosses no edge). The exercise's
//! rule as stated ([`PointLocator::with_exercise_rule`]) also splits such squares until one
//! edge is left, which costs squares in proportion to the length of close edges over their
//! distance (about 2^33 for two unit edges 2^-40 apart); the relaxed rule keeps the size
//! O(V h) for V vertices and height h whatever the spacing. Leaves at the finest level
//! ([`Cell::MAX_LEVEL`]) keep every edge they meet. Leaves holding several edges and no vertex
//! (or stopped at the finest level) are checked for crossing edges, which always end up there.
//!
//! # Query
//! Walk down by the point's Morton key: at each node take the child of the point's quadrant if
//! its cell holds the point, else answer the quadrant's face. At a leaf: the wedge of its vertex
//! containing the point (O(log degree)); the side of its single edge (O(1)); or the side of the
//! nearest edge point within the cell (O(k) for k edges). Time O(h + log degree + k), h at most
//! 33 nodes.
//!
//! # Construction and size
//! In `locate/build.rs`. Top-down with an explicit stack: a node distributes its vertices and edges to the four closed
//! quadrants (an edge may go to several), then shrinks each non-empty quadrant to the smallest
//! cell holding its contents. A square splits only while it holds a vertex and a feature not
//! incident to it (or two vertices), so with `s` the smallest distance between a vertex and a
//! feature not incident to it, the height is at most about log2(side of the root / s) + 2
//! (capped by the finest level), and every level holds O(V) split squares: O(V h) nodes. Each
//! node costs time proportional to the features it holds, O(F) for F feature copies over all
//! nodes, at most O((V + E) h) in the worst case, plus O(E log E) for the faces.
//! `tests/point_location.rs` and `benches/compressed.rs` measure both.

use super::subdivision::{FaceId, Subdivision, SubdivisionError};
use super::topology::NIL;
use crate::geom::{digit, same_cell, Aabb, Cell, RootGeometry};
use crate::query::{Location, QueryError};

mod build;

/// A node of the locator's tree.
#[derive(Clone, Debug)]
struct Node {
    cell: Cell<2>,
    key: u64,
    /// The child node in each quadrant, NIL if none (then the whole quadrant has `faces[q]`).
    children: [u32; 4],
    /// The face of the points of each quadrant outside its child.
    faces: [u32; 4],
    /// A leaf's vertex (NIL if none) and edges (`edges[list.0..list.1]`); `leaf` false for an
    /// internal node.
    vertex: u32,
    list: (u32, u32),
    leaf: bool,
}

/// A planar subdivision stored in a compressed quadtree for point location (exercise 14.10).
///
/// ```
/// use orthtree::compressed::{PointLocator, Subdivision};
/// use orthtree::query::Location;
/// let v = vec![[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]];
/// let e = vec![[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]];
/// let s = Subdivision::new(v, e).unwrap();
/// let lower = s.left_face(0); // the triangle 0, 1, 2
/// let locator = PointLocator::new(s).unwrap();
/// assert_eq!(locator.locate(&[3.0, 1.0]).unwrap(), Location::Inside(lower));
/// assert_ne!(locator.locate(&[1.0, 3.0]).unwrap(), Location::Inside(lower));
/// assert_eq!(locator.locate(&[5.0, 1.0]).unwrap(), Location::Outside { axis: 0 });
/// ```
#[derive(Clone, Debug)]
pub struct PointLocator {
    subdivision: Subdivision,
    geometry: RootGeometry<2>,
    nodes: Vec<Node>,
    lists: Vec<u32>,
}

impl PointLocator {
    /// Builds the tree (see the module doc for the time).
    ///
    /// # Errors
    /// [`SubdivisionError::Crossing`] for two edges found to meet other than at a shared
    /// endpoint.
    pub fn new(subdivision: Subdivision) -> Result<Self, SubdivisionError> {
        Self::build_with(subdivision, false)
    }

    /// [`PointLocator::new`] with the exercise's rule as stated: a square without a vertex is
    /// split until it holds at most one edge. Queries then scan at most one edge outside the
    /// finest cells, but the size grows like the length of close edges over their distance
    /// (two unit edges 2^-40 apart need about 2^33 squares): use it on well-spaced input.
    ///
    /// # Errors
    /// Those of [`PointLocator::new`], and [`SubdivisionError::TooManySquares`] once the
    /// tree would pass 64 squares per vertex and edge plus 4096.
    pub fn with_exercise_rule(subdivision: Subdivision) -> Result<Self, SubdivisionError> {
        Self::build_with(subdivision, true)
    }

    /// The face of `q` (inside the closed box `b`) from the nearest point, within `b`, of the
    /// edges `edges` (every edge meeting `b`): the wedge of a vertex, or the side of an edge.
    fn face_near(&self, q: &[f64; 2], b: &Aabb<f64, 2>, edges: &[u32]) -> (u32, usize) {
        let s = &self.subdivision;
        let mut best: Option<(f64, u32, f64)> = None;
        for &e in edges {
            let [u, v] = s.edges()[e as usize].map(|i| s.vertices()[i as usize]);
            let Some((t0, t1)) = clip_params(u, v, b) else {
                continue;
            };
            let d = [v[0] - u[0], v[1] - u[1]];
            let len = d[0] * d[0] + d[1] * d[1];
            let t = (((q[0] - u[0]) * d[0] + (q[1] - u[1]) * d[1]) / len).clamp(t0, t1);
            let x = [u[0] + t * d[0], u[1] + t * d[1]];
            let dist = (x[0] - q[0]).powi(2) + (x[1] - q[1]).powi(2);
            if best.is_none_or(|(bd, _, _)| dist < bd) {
                best = Some((dist, e, t));
            }
        }
        let Some((_, e, t)) = best else {
            return (s.outer_face().0, 0);
        };
        let [a, b] = s.edges()[e as usize];
        let face = if t == 0.0 {
            s.face_around(a as usize, *q)
        } else if t == 1.0 {
            s.face_around(b as usize, *q)
        } else {
            side(s, e as usize, q)
        };
        (face.0, edges.len())
    }

    /// The face holding `point` inside the root square (a point on an edge gets the face left
    /// of it, first vertex to second; a point inside the square but outside every bounded face
    /// the outer face), or [`Location::Outside`] for a point outside the root square, which lies
    /// in the outer face.
    ///
    /// # Errors
    /// [`QueryError::NotFinite`] for a NaN or infinite coordinate, naming its axis.
    ///
    /// # Complexity
    /// O(h + log degree), h the height of the tree.
    pub fn locate(&self, point: &[f64; 2]) -> Result<Location<FaceId>, QueryError> {
        self.locate_counted(point).map(|(f, _)| f)
    }

    /// The face holding `point` anywhere in the plane: [`PointLocator::locate`]'s face inside
    /// the root square, the outer face outside it.
    ///
    /// # Errors
    /// As [`PointLocator::locate`].
    ///
    /// ```
    /// use orthtree::compressed::{PointLocator, Subdivision};
    /// let s = Subdivision::new(vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], vec![[0, 1], [1, 2], [2, 0]]).unwrap();
    /// let locator = PointLocator::new(s).unwrap();
    /// assert_eq!(locator.face(&[7.0, 7.0]), Ok(locator.subdivision().outer_face()));
    /// assert_ne!(locator.face(&[0.2, 0.2]), Ok(locator.subdivision().outer_face()));
    /// ```
    pub fn face(&self, point: &[f64; 2]) -> Result<FaceId, QueryError> {
        Ok(self
            .locate(point)?
            .inside()
            .unwrap_or(self.subdivision.outer_face()))
    }

    /// [`PointLocator::locate`], with the number of nodes visited plus edges examined.
    ///
    /// # Errors
    /// As [`PointLocator::locate`].
    pub fn locate_counted(
        &self,
        point: &[f64; 2],
    ) -> Result<(Location<FaceId>, usize), QueryError> {
        match crate::query::place_point(point, &self.geometry.root_box())? {
            Location::Inside(p) => {
                let (face, work) = self.face_of(&p);
                Ok((Location::Inside(face), work))
            }
            Location::Outside { axis } => Ok((Location::Outside { axis }, 0)),
        }
    }

    /// The face holding `point`, a point inside the root square, with the work it took.
    fn face_of(&self, point: &[f64; 2]) -> (FaceId, usize) {
        let s = &self.subdivision;
        let key = self.geometry.key(point);
        let mut v = 0usize;
        let mut touched = 1;
        loop {
            let node = &self.nodes[v];
            if node.leaf {
                let edges = &self.lists[node.list.0 as usize..node.list.1 as usize];
                let (face, work) = match edges {
                    _ if node.vertex != NIL => (s.face_around(node.vertex as usize, *point).0, 1),
                    [] => (s.outer_face().0, 0),
                    [e] => (side(s, *e as usize, point).0, 1),
                    _ => self.face_near(point, &self.geometry.cell_box(&node.cell), edges),
                };
                return (FaceId(face), touched + work);
            }
            let q = digit::<2>(key, node.cell.level());
            let c = node.children[q];
            if c == NIL || !holds(&self.nodes[c as usize], key) {
                return (FaceId(node.faces[q]), touched);
            }
            v = c as usize;
            touched += 1;
        }
    }

    /// The subdivision.
    pub fn subdivision(&self) -> &Subdivision {
        &self.subdivision
    }

    /// The number of nodes of the tree.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The number of nodes on the longest root-to-leaf path, the root included.
    pub fn height(&self) -> usize {
        let mut best = 0;
        let mut stack = vec![(0usize, 1usize)];
        while let Some((v, h)) = stack.pop() {
            best = best.max(h);
            stack.extend(
                self.nodes[v]
                    .children
                    .iter()
                    .filter(|&&c| c != NIL)
                    .map(|&c| (c as usize, h + 1)),
            );
        }
        best
    }

    /// Where the cells lie.
    pub fn geometry(&self) -> &RootGeometry<2> {
        &self.geometry
    }

    /// The cell of every node with `true` for a leaf (for pictures).
    pub fn cells(&self) -> impl Iterator<Item = (Cell<2>, bool)> + '_ {
        self.nodes.iter().map(|n| (n.cell, n.leaf))
    }
}

/// `true` when `node`'s cell holds the point of finest key `key`.
#[inline]
fn holds(node: &Node, key: u64) -> bool {
    same_cell::<2>(node.key, key, node.cell.level())
}

/// The face on `q`'s side of edge `e` (left on the edge itself).
fn side(s: &Subdivision, e: usize, q: &[f64; 2]) -> FaceId {
    let [u, v] = s.edges()[e].map(|i| s.vertices()[i as usize]);
    let cross = (v[0] - u[0]) * (q[1] - u[1]) - (v[1] - u[1]) * (q[0] - u[0]);
    if cross >= 0.0 {
        s.left_face(e)
    } else {
        s.right_face(e)
    }
}

/// The parameter interval of segment `u v` inside the closed box `b` (Liang and Barsky).
fn clip_params(u: [f64; 2], v: [f64; 2], b: &Aabb<f64, 2>) -> Option<(f64, f64)> {
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for a in 0..2 {
        let d = v[a] - u[a];
        if d == 0.0 {
            if u[a] < b.min[a] || u[a] > b.max[a] {
                return None;
            }
            continue;
        }
        let (mut lo, mut hi) = ((b.min[a] - u[a]) / d, (b.max[a] - u[a]) / d);
        if lo > hi {
            core::mem::swap(&mut lo, &mut hi);
        }
        t0 = t0.max(lo);
        t1 = t1.min(hi);
    }
    (t0 <= t1).then_some((t0, t1))
}
