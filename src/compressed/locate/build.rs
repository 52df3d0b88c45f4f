//! The construction of a [`PointLocator`] (see the parent module's doc): top-down with an
//! explicit stack of tasks, each a square with the vertices and edges that meet it; a square
//! is shrunk to the smallest cell holding its contents, then either stored as a leaf (checked
//! for crossing edges where they can meet) or split, each quadrant's contents becoming a task
//! and an empty quadrant getting its face.

use super::{clip_params, Node, PointLocator};
use crate::compressed::subdivision::{Subdivision, SubdivisionError};
use crate::compressed::topology::NIL;
use crate::geom::{Aabb, Cell, RootGeometry};

/// Pending work of the construction: a cell and what meets it, and where its node goes.
struct Task {
    parent: u32,
    quadrant: usize,
    cell: Cell<2>,
    vertices: Vec<u32>,
    edges: Vec<u32>,
}

impl PointLocator {
    pub(super) fn build_with(
        subdivision: Subdivision,
        split_edges: bool,
    ) -> Result<Self, SubdivisionError> {
        let v = subdivision.vertices();
        // no vertices: the unit square
        let bounds = Aabb::around(if v.is_empty() {
            &[[0.0; 2], [1.0; 2]]
        } else {
            v
        });
        let mut locator = PointLocator {
            geometry: RootGeometry::enclosing(&bounds),
            subdivision,
            nodes: Vec::new(),
            lists: Vec::new(),
        };
        locator.build(split_edges)?;
        Ok(locator)
    }

    /// Builds the nodes top-down from the root task (see the module doc), with an explicit
    /// stack of tasks.
    fn build(&mut self, split_edges: bool) -> Result<(), SubdivisionError> {
        let s = &self.subdivision;
        // The exercise's rule has no size bound in the input size: stop it before memory runs out.
        let limit = 64 * (s.vertices().len() + s.edges().len()) + 4096;
        let mut stack = vec![Task {
            parent: NIL,
            quadrant: 0,
            cell: Cell::root(),
            vertices: (0..s.vertices().len() as u32).collect(),
            edges: (0..s.edges().len() as u32).collect(),
        }];
        while let Some(task) = stack.pop() {
            if split_edges && self.nodes.len() >= limit {
                return Err(SubdivisionError::TooManySquares { limit });
            }
            let cell = self.attach(&task);
            let simple = self.is_simple(&task, split_edges);
            if simple || cell.level() == Cell::<2>::MAX_LEVEL {
                self.push_leaf(cell, &task, simple)?;
            } else {
                self.push_internal(cell, &task, &mut stack);
            }
        }
        Ok(())
    }

    /// The cell of `task`'s node (its cell shrunk to its contents, except at the root), linked
    /// into its parent with the face of the part of the quadrant outside it.
    fn attach(&mut self, task: &Task) -> Cell<2> {
        if task.parent == NIL {
            return task.cell;
        }
        let cell = self.shrink(task.cell, &task.vertices, &task.edges);
        let id = self.nodes.len() as u32;
        self.nodes[task.parent as usize].children[task.quadrant] = id;
        if cell != task.cell {
            let face = self.outside_face(task.cell, cell, &task.edges);
            self.nodes[task.parent as usize].faces[task.quadrant] = face;
        }
        cell
    }

    /// The face of the points of `quadrant` outside its shrunk `cell`: that region meets no
    /// edge, so the face near a corner the cell misses is the face of all of it.
    fn outside_face(&self, quadrant: Cell<2>, cell: Cell<2>, edges: &[u32]) -> u32 {
        let qb = self.geometry.cell_box(&quadrant);
        let cb = self.geometry.cell_box(&cell);
        let corners = [
            qb.min,
            [qb.max[0], qb.min[1]],
            [qb.min[0], qb.max[1]],
            qb.max,
        ];
        let sample = corners
            .into_iter()
            .find(|p| !cb.contains(p))
            .unwrap_or(qb.min);
        self.face_near(&sample, &qb, edges).0
    }

    /// Whether `task`'s square stops splitting: no vertex (and, under the exercise's rule, at
    /// most one edge), or one vertex and only edges incident to it.
    fn is_simple(&self, task: &Task, split_edges: bool) -> bool {
        let s = &self.subdivision;
        let incident = |v: u32| {
            task.edges
                .iter()
                .all(|&e| s.edges()[e as usize].contains(&v))
        };
        match task.vertices[..] {
            [] => !split_edges || task.edges.len() <= 1,
            [v] => incident(v),
            _ => false,
        }
    }

    /// A new node at `cell` with no children yet.
    fn node(cell: Cell<2>) -> Node {
        Node {
            cell,
            key: cell.aligned_key(),
            children: [NIL; 4],
            faces: [NIL; 4],
            vertex: NIL,
            list: (0, 0),
            leaf: true,
        }
    }

    /// Stores `task`'s square as a leaf with its edges (and its vertex when `simple`); a leaf
    /// holding several edges and no vertex, or stopped at the finest level, is checked for
    /// crossing edges.
    fn push_leaf(
        &mut self,
        cell: Cell<2>,
        task: &Task,
        simple: bool,
    ) -> Result<(), SubdivisionError> {
        let mut node = Self::node(cell);
        if !simple || (task.vertices.is_empty() && task.edges.len() > 1) {
            check_crossings(&self.subdivision, &task.edges)?;
        } else if let [v] = task.vertices[..] {
            node.vertex = v;
        }
        node.list = (
            self.lists.len() as u32,
            (self.lists.len() + task.edges.len()) as u32,
        );
        self.lists.extend(&task.edges);
        self.nodes.push(node);
        Ok(())
    }

    /// Stores `task`'s square as an internal node: each quadrant's contents become a task, an
    /// empty quadrant gets its face.
    fn push_internal(&mut self, cell: Cell<2>, task: &Task, stack: &mut Vec<Task>) {
        let s = &self.subdivision;
        let id = self.nodes.len() as u32;
        let mut node = Self::node(cell);
        node.leaf = false;
        let bbox = self.geometry.cell_box(&cell);
        for q in 0..4 {
            let child = cell.child(q);
            let cb = self.geometry.cell_box(&child);
            let vertices: Vec<u32> = (task.vertices.iter().copied())
                .filter(|&v| cb.contains(&s.vertices()[v as usize]))
                .collect();
            let edges: Vec<u32> = (task.edges.iter().copied())
                .filter(|&e| clip(s, e, &cb).is_some())
                .collect();
            if vertices.is_empty() && edges.is_empty() {
                let centre = [0.5 * (cb.min[0] + cb.max[0]), 0.5 * (cb.min[1] + cb.max[1])];
                node.faces[q] = self.face_near(&centre, &bbox, &task.edges).0;
            } else {
                stack.push(Task {
                    parent: id,
                    quadrant: q,
                    cell: child,
                    vertices,
                    edges,
                });
            }
        }
        self.nodes.push(node);
    }

    /// The smallest cell inside `cell` whose closed box holds the vertices and the parts of the
    /// edges inside `cell`.
    fn shrink(&self, cell: Cell<2>, vertices: &[u32], edges: &[u32]) -> Cell<2> {
        let s = &self.subdivision;
        let b = self.geometry.cell_box(&cell);
        let mut content = Aabb::empty();
        vertices
            .iter()
            .for_each(|&v| content.add_point(&s.vertices()[v as usize]));
        for &e in edges {
            if let Some((p, q)) = clip(s, e, &b) {
                content.add_point(&p);
                content.add_point(&q);
            }
        }
        let mut at = cell;
        while at.level() < Cell::<2>::MAX_LEVEL {
            let inner = (0..4).map(|q| at.child(q)).find(|c| {
                let cb = self.geometry.cell_box(c);
                cb.contains(&content.min) && cb.contains(&content.max)
            });
            match inner {
                Some(c) => at = c,
                None => break,
            }
        }
        at
    }
}

/// The part of edge `e` inside the closed box `b`, as its two end points.
fn clip(s: &Subdivision, e: u32, b: &Aabb<f64, 2>) -> Option<([f64; 2], [f64; 2])> {
    let [u, v] = s.edges()[e as usize].map(|i| s.vertices()[i as usize]);
    let at = |t: f64| match t {
        0.0 => u,
        1.0 => v,
        _ => [u[0] + t * (v[0] - u[0]), u[1] + t * (v[1] - u[1])],
    };
    clip_params(u, v, b).map(|(t0, t1)| (at(t0), at(t1)))
}

/// `Err(Crossing)` for the first two of `edges` that meet other than at a shared endpoint.
fn check_crossings(s: &Subdivision, edges: &[u32]) -> Result<(), SubdivisionError> {
    let orient = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        let x = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        (x > 0.0) as i8 - (x < 0.0) as i8
    };
    let on = |a: [f64; 2], b: [f64; 2], p: [f64; 2]| {
        orient(a, b, p) == 0 && (0..2).all(|i| a[i].min(b[i]) <= p[i] && p[i] <= a[i].max(b[i]))
    };
    for (i, &e) in edges.iter().enumerate() {
        for &f in &edges[i + 1..] {
            let (ev, fv) = (s.edges()[e as usize], s.edges()[f as usize]);
            let [a, b] = ev.map(|x| s.vertices()[x as usize]);
            let [c, d] = fv.map(|x| s.vertices()[x as usize]);
            let shared = ev.iter().any(|x| fv.contains(x));
            let meet = if shared {
                // Only an overlap counts: the far end of one on the other.
                (!ev.contains(&fv[0]) && on(a, b, c))
                    || (!ev.contains(&fv[1]) && on(a, b, d))
                    || (!fv.contains(&ev[0]) && on(c, d, a))
                    || (!fv.contains(&ev[1]) && on(c, d, b))
            } else {
                let (o1, o2) = (orient(a, b, c), orient(a, b, d));
                let (o3, o4) = (orient(c, d, a), orient(c, d, b));
                (o1 != o2 && o3 != o4) || on(a, b, c) || on(a, b, d) || on(c, d, a) || on(c, d, b)
            };
            if meet {
                return Err(SubdivisionError::Crossing {
                    a: e as usize,
                    b: f as usize,
                });
            }
        }
    }
    Ok(())
}
