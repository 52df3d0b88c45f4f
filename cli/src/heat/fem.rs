//! Linear (P1) finite elements for the steady heat equation `-div(k grad T) = q` on a triangle
//! mesh, with `T = 0` at the fixed (Dirichlet) vertices, and a sparse Cholesky solve with faer.
//!
//! Shared by `orthtree heat` and its tests (`tests/heat.rs` (included with `#[path]`), so not every
//! item is used by both.
#![allow(dead_code)]

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Mat, Side};
use std::time::{Duration, Instant};

/// Marks an eliminated (fixed) vertex in [`System::unknown`].
pub const FIXED: u32 = u32::MAX;

/// The assembled linear system `A x = b` over the free vertices.
pub struct System {
    /// Unknown index of each vertex, or [`FIXED`].
    pub unknown: Vec<u32>,
    /// Number of unknowns.
    pub n: usize,
    /// Lower triangle (row >= column) of the symmetric stiffness matrix in compressed sparse
    /// column form: rows sorted and unique within each column.
    pub col_ptr: Vec<usize>,
    /// Row index of each stored entry.
    pub row_idx: Vec<usize>,
    /// Value of each stored entry.
    pub values: Vec<f64>,
    /// Load vector.
    pub rhs: Vec<f64>,
}

/// The element stiffness matrix of the P1 triangle `p` (counter-clockwise) for conductivity
/// `k`: `K_ij = k (b_i b_j + c_i c_j) / (2 d)` with `d` twice the area and `(b_i, c_i)` the
/// rotated opposite edge. Also returns twice the area.
pub fn element_stiffness(p: [[f64; 2]; 3], k: f64) -> ([[f64; 3]; 3], f64) {
    let mut b = [0.0; 3];
    let mut c = [0.0; 3];
    for i in 0..3 {
        let (j, l) = ((i + 1) % 3, (i + 2) % 3);
        b[i] = p[j][1] - p[l][1];
        c[i] = p[l][0] - p[j][0];
    }
    let d = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
    let mut m = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            m[i][j] = k * (b[i] * b[j] + c[i] * c[j]) / (2.0 * d);
        }
    }
    (m, d)
}

/// Assembles the system. `fixed[v]` marks Dirichlet vertices (`T = 0`, eliminated);
/// `k(t)` is the conductivity of triangle `t`; `q(t, x)` the heat source in triangle `t` at
/// point `x`, integrated against the hat functions with the edge-midpoint rule (exact for `q`
/// linear in each triangle, so for a constant `q` each vertex gets `q A / 3`).
pub fn assemble(
    points: &[[f64; 2]],
    triangles: &[[u32; 3]],
    fixed: &[bool],
    k: impl Fn(usize) -> f64,
    q: impl Fn(usize, [f64; 2]) -> f64,
) -> System {
    let mut unknown = vec![FIXED; points.len()];
    let mut n = 0usize;
    for (v, u) in unknown.iter_mut().enumerate() {
        if !fixed[v] {
            *u = n as u32;
            n += 1;
        }
    }
    let mut rhs = vec![0.0; n];
    // (column << 32 | row, value), lower triangle only.
    let mut entries: Vec<(u64, f64)> = Vec::with_capacity(6 * triangles.len());
    for (t, tri) in triangles.iter().enumerate() {
        let p = tri.map(|v| points[v as usize]);
        let (m, d) = element_stiffness(p, k(t));
        let mid = |i: usize, j: usize| [(p[i][0] + p[j][0]) / 2.0, (p[i][1] + p[j][1]) / 2.0];
        let qm = [q(t, mid(1, 2)), q(t, mid(2, 0)), q(t, mid(0, 1))]; // opposite vertex i
        for i in 0..3 {
            let ui = unknown[tri[i] as usize];
            if ui == FIXED {
                continue;
            }
            // vertex i sees the two midpoints of its edges with weight 1/2 each
            rhs[ui as usize] += d / 6.0 * (qm[(i + 1) % 3] + qm[(i + 2) % 3]) / 2.0;
            for j in 0..3 {
                let uj = unknown[tri[j] as usize];
                if uj == FIXED || uj > ui {
                    continue;
                }
                entries.push((((uj as u64) << 32) | ui as u64, m[i][j]));
            }
        }
    }
    entries.sort_unstable_by_key(|e| e.0);
    let mut col_ptr = vec![0usize; n + 1];
    let mut row_idx = Vec::with_capacity(entries.len() / 2);
    let mut values: Vec<f64> = Vec::with_capacity(entries.len() / 2);
    let mut last = u64::MAX;
    for &(key, val) in &entries {
        if key == last {
            *values.last_mut().unwrap() += val;
        } else {
            last = key;
            row_idx.push((key & 0xffff_ffff) as usize);
            values.push(val);
            col_ptr[(key >> 32) as usize + 1] += 1;
        }
    }
    for c in 0..n {
        col_ptr[c + 1] += col_ptr[c];
    }
    System {
        unknown,
        n,
        col_ptr,
        row_idx,
        values,
        rhs,
    }
}

impl System {
    /// The largest off-diagonal entry of the stiffness matrix (`<= 0` for an M-matrix), or
    /// `-inf` when there is none.
    pub fn max_off_diagonal(&self) -> f64 {
        let mut worst = f64::NEG_INFINITY;
        for c in 0..self.n {
            for e in self.col_ptr[c]..self.col_ptr[c + 1] {
                if self.row_idx[e] != c {
                    worst = worst.max(self.values[e]);
                }
            }
        }
        worst
    }

    /// The stored lower triangle as a faer matrix view.
    pub fn matrix(&self) -> SparseColMatRef<'_, usize, f64> {
        let symbolic = SymbolicSparseColMatRef::new_checked(
            self.n,
            self.n,
            &self.col_ptr,
            None,
            &self.row_idx,
        );
        SparseColMatRef::new(symbolic, &self.values)
    }
}

/// Times of a [`solve`].
#[derive(Clone, Copy, Debug, Default)]
pub struct SolveTimes {
    /// Symbolic analysis (fill-reducing ordering, elimination tree).
    pub symbolic: Duration,
    /// Numeric Cholesky factorization.
    pub numeric: Duration,
    /// Forward and back substitution.
    pub substitution: Duration,
}

impl SolveTimes {
    /// Total solve time.
    pub fn total(&self) -> Duration {
        self.symbolic + self.numeric + self.substitution
    }
}

/// Solves the system with faer's sparse Cholesky (`L L^T`) factorization and returns the
/// temperature at every vertex (0 at the fixed ones).
pub fn solve(sys: &System) -> Result<(Vec<f64>, SolveTimes), String> {
    let mut times = SolveTimes::default();
    let a = sys.matrix();
    let start = Instant::now();
    let symbolic = SymbolicLlt::try_new(a.symbolic(), Side::Lower).map_err(|e| format!("{e:?}"))?;
    times.symbolic = start.elapsed();
    let start = Instant::now();
    let llt = Llt::try_new_with_symbolic(symbolic, a, Side::Lower).map_err(|e| format!("{e:?}"))?;
    times.numeric = start.elapsed();
    let start = Instant::now();
    let mut x = Mat::from_fn(sys.n, 1, |i, _| sys.rhs[i]);
    llt.solve_in_place(x.as_mut());
    times.substitution = start.elapsed();
    let t = sys
        .unknown
        .iter()
        .map(|&u| if u == FIXED { 0.0 } else { x[(u as usize, 0)] })
        .collect();
    Ok((t, times))
}

// ---------------------------------------------------------------------------------------------
// The board problem
// ---------------------------------------------------------------------------------------------

/// Length of one board unit in metres (0.1 mm: the built-in board, U = 1024, is 102.4 mm wide).
pub const UNIT_M: f64 = 1e-4;
/// Conductivity of the bare board (FR-4), W/(m K).
pub const K_BOARD: f64 = 0.3;
/// Conductivity of a chip (a component whose bounding box is at least [`CHIP_SIDE`] units on
/// both sides), W/(m K).
pub const K_CHIP: f64 = 20.0;
/// Conductivity of the other components (copper pads, traces, connector fingers), W/(m K).
pub const K_COPPER: f64 = 400.0;
/// Heat source in a chip, W/m^3 (a 2D model: per unit thickness).
pub const Q_CHIP: f64 = 2.0e5;
/// Heat source in the other components (resistive loss), W/m^3.
pub const Q_COPPER: f64 = 2.0e4;
/// Smallest side of a chip's bounding box, in board units.
pub const CHIP_SIDE: i64 = 40;

/// Conductivity and heat source per region (index 0 the board, `i` component `i`).
pub fn board_materials(board: &orthtree::mesh::Board) -> (Vec<f64>, Vec<f64>) {
    let mut k = vec![K_BOARD];
    let mut q = vec![0.0];
    for c in board.components() {
        let lo = c
            .outline
            .iter()
            .fold([i64::MAX; 2], |a, p| [a[0].min(p[0]), a[1].min(p[1])]);
        let hi = c
            .outline
            .iter()
            .fold([i64::MIN; 2], |a, p| [a[0].max(p[0]), a[1].max(p[1])]);
        let chip = hi[0] - lo[0] >= CHIP_SIDE && hi[1] - lo[1] >= CHIP_SIDE;
        k.push(if chip { K_CHIP } else { K_COPPER });
        q.push(if chip { Q_CHIP } else { Q_COPPER });
    }
    (k, q)
}

/// The vertices on the board's boundary (on a `Boundary` segment).
pub fn boundary_vertices(mesh: &orthtree::mesh::Mesh) -> Vec<bool> {
    let mut fixed = vec![false; mesh.vertices.len()];
    for s in &mesh.segments {
        if s.kind == orthtree::mesh::SegmentKind::Boundary {
            fixed[s.vertices[0] as usize] = true;
            fixed[s.vertices[1] as usize] = true;
        }
    }
    fixed
}

/// Assembles the board problem on `mesh`: per-region `k` and `q`, `T = 0` on the board's
/// boundary. The stiffness matrix is scale invariant in 2D, so it is computed in the exact
/// integer board units (a right angle then gives an exact 0, never a rounding error of either
/// sign); the load is scaled by `UNIT_M^2` to metres.
pub fn assemble_board(mesh: &orthtree::mesh::Mesh, k: &[f64], q: &[f64]) -> System {
    let points: Vec<[f64; 2]> = mesh
        .vertices
        .iter()
        .map(|p| [p[0] as f64, p[1] as f64])
        .collect();
    let fixed = boundary_vertices(mesh);
    let regions = &mesh.regions;
    assemble(
        &points,
        &mesh.triangles,
        &fixed,
        |t| k[regions[t] as usize],
        |t, _| q[regions[t] as usize] * UNIT_M * UNIT_M,
    )
}
