//! The input check of [`Mesh::validate`](super::Mesh::validate): every component edge is a chain
//! of mesh edges, walked from vertex to vertex along the edge's direction in exact integer steps
//! (edges of any length, so the coarsest mode's long mesh edges are followed too), with the
//! component on the proper side of each step.

use super::checks::{Input, InputEdges, Validator};
use super::*;
use crate::mesh::pairing::NONE;

impl Validator<'_> {
    /// `respects_input`, and the input steps found: the side of each half-edge along a
    /// component edge, and the mesh edges along the component edges.
    pub(super) fn respects_input(&self) -> (Check, InputEdges) {
        let mut f = Finding::default();
        let mut found = InputEdges {
            sides: vec![Input::None; self.half_edge_count()],
            steps: Vec::new(),
        };
        let components = self.board.components();
        for (ci, comp) in components.iter().enumerate() {
            for (k, (p, q)) in comp.edges().enumerate() {
                f.keep(self.follow(ci as u32 + 1, k, p, q, &mut found));
            }
        }
        let edges: usize = components.iter().map(|c| c.outline.len()).sum();
        let steps = found.steps.len();
        let check =
            f.finish(|| format!("{edges} component edges are chains of {steps} mesh edges"));
        (check, found)
    }

    /// Walks edge `k` of component `c`, from `p` to `q`, along mesh edges, recording in `found`
    /// each mesh edge reached and the component's side of its half-edges; the violation that
    /// stops the walk, if any.
    fn follow(
        &self,
        c: u32,
        k: usize,
        p: Point,
        q: Point,
        found: &mut InputEdges,
    ) -> Option<MeshValidationError> {
        let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
        if (dx == 0 && dy == 0) || (dx != 0 && dy != 0 && dx.abs() != dy.abs()) {
            return Some(MeshValidationError::NotLatticeDirection {
                component: c,
                edge: k,
                from: p,
                to: q,
            });
        }
        let d = [dx.signum(), dy.signum()];
        let Some(first) = self.vertex_at(p) else {
            return Some(MeshValidationError::OutlineVertexMissing {
                component: c,
                point: p,
            });
        };
        let (mut at, mut from) = (p, first);
        while at != q {
            let left = (q[0] - at[0]).abs().max((q[1] - at[1]).abs());
            let Some((to, next)) = self.step_along(from, at, d, left) else {
                return Some(MeshValidationError::OutlineEdgeBroken {
                    component: c,
                    edge: k,
                    from: p,
                    to: q,
                    at,
                });
            };
            let mut mark = |h: u32, side: Input| {
                if found.sides[h as usize] == Input::None {
                    found.sides[h as usize] = side;
                }
            };
            if let Some(h) = self.find(from, to) {
                mark(h, Input::Left(c));
                if let Some(g) = self.twin(h) {
                    mark(g, Input::Right(c));
                }
            } else if let Some(g) = self.find(to, from) {
                mark(g, Input::Right(c));
            }
            found.steps.push(((from, to), c));
            (at, from) = (next, to);
        }
        None
    }

    /// The half-edges leaving `v`, found by turning around it through the triangles (both ways,
    /// so that a vertex on the boundary is covered). At most 64 of them: a vertex of a valid mesh
    /// has at most 8, and the bound keeps a malformed mesh from looping.
    fn outgoing(&self, v: u32) -> impl Iterator<Item = u32> + '_ {
        let first = self.leaving[v as usize];
        let turn = move |back: bool| {
            let mut h = Some(first).filter(|&h| h != NONE);
            let mut count = 0;
            core::iter::from_fn(move || {
                let g = h?;
                count += 1;
                let (t, i) = (g / 3, g % 3);
                h = if back {
                    self.twin(g).map(|g| g / 3 * 3 + (g % 3 + 1) % 3)
                } else {
                    self.twin(3 * t + (i + 2) % 3)
                }
                .filter(|&n| n != first && count < 64);
                Some(g)
            })
        };
        turn(false).chain(turn(true).skip(1))
    }

    /// The mesh edge leaving vertex `from` at `at` along the unit lattice direction `d`, ending
    /// at most `left` steps on: (its other vertex, that vertex's position). Found by turning
    /// around `from`; where that fails (a malformed mesh, with a hole or a flipped triangle at
    /// `from`), the unit step to `at + d` is tried as an undirected edge.
    fn step_along(&self, from: u32, at: Point, d: Point, left: i64) -> Option<(u32, Point)> {
        let along = self.outgoing(from).find_map(|h| {
            let to = self.target(h);
            let q = self.point(to);
            let v = [q[0] - at[0], q[1] - at[1]];
            let t = v[0] * d[0] + v[1] * d[1];
            let t = if d[0] != 0 && d[1] != 0 { t / 2 } else { t };
            let on_ray = t > 0 && t <= left && v == [t * d[0], t * d[1]];
            on_ray.then_some((to, q))
        });
        along.or_else(|| {
            let next = [at[0] + d[0], at[1] + d[1]];
            let to = self.vertex_at(next).filter(|&to| self.is_edge(from, to))?;
            Some((to, next))
        })
    }
}
