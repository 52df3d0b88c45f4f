//! The finite elements of `orthtree heat` (feature `heat`): the stiffness matrix on the mesher's meshes is
//! an M-matrix and the discrete maximum principle holds; P1 converges at second order in L2 on
//! the unit square; assembly and solve times (printed with `--nocapture`).

#![cfg(feature = "heat")]

#[path = "../src/heat/fem.rs"]
mod fem;

use orthtree::mesh::{generate_mesh, random_board, sample_board};
use std::f64::consts::PI;
use std::time::Instant;

/// SplitMix64, for reproducible random materials.
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

#[test]
fn m_matrix_and_maximum_principle_on_random_boards() {
    for (seed, size, count) in [
        (1, 64, 10),
        (2, 256, 40),
        (3, 512, 80),
        (4, 1024, 150),
        (5, 128, 1000),
    ] {
        let board = random_board(seed, size, count);
        let mesh = generate_mesh(&board).unwrap().mesh;
        // random k in [10, 400] and q in (0, 1e6] per component; board k in [0.3, 1], q = 0
        let regions = board.components().len() + 1;
        let mut k = Vec::with_capacity(regions);
        let mut q = Vec::with_capacity(regions);
        for r in 0..regions as u64 {
            let (a, b) = (mix(seed * 1000 + 2 * r), mix(seed * 1000 + 2 * r + 1));
            let (a, b) = (
                (a >> 11) as f64 / (1u64 << 53) as f64,
                (b >> 11) as f64 / (1u64 << 53) as f64,
            );
            if r == 0 {
                k.push(0.3 + 0.7 * a);
                q.push(0.0);
            } else {
                k.push(10.0 + 390.0 * a);
                q.push(1e6 * (1.0 - b));
            }
        }
        let sys = fem::assemble_board(&mesh, &k, &q);
        assert!(sys.n > 0);
        let worst = sys.max_off_diagonal();
        assert!(
            worst <= 0.0,
            "seed {seed}: positive off-diagonal entry {worst:e}"
        );
        // diagonal positive, rows weakly diagonally dominant (lower triangle: check via sums)
        let mut row_sum = vec![0.0; sys.n];
        for c in 0..sys.n {
            for e in sys.col_ptr[c]..sys.col_ptr[c + 1] {
                let r = sys.row_idx[e];
                row_sum[r] += sys.values[e];
                if r != c {
                    row_sum[c] += sys.values[e];
                } else {
                    assert!(sys.values[e] > 0.0);
                }
            }
        }
        let scale = k.iter().copied().fold(0.0, f64::max);
        assert!(
            row_sum.iter().all(|&s| s >= -1e-9 * scale),
            "seed {seed}: not diagonally dominant"
        );
        let (t, _) = fem::solve(&sys).unwrap();
        let t_min = t.iter().copied().fold(f64::INFINITY, f64::min);
        let t_max = t.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        assert!(t_max > 0.0);
        assert!(
            t_min >= 0.0,
            "seed {seed}: min T = {t_min:e} < 0 (max {t_max:e})"
        );
    }
}

/// The n x n grid of squares on the unit square, each square split by a diagonal (alternating
/// directions, so every triangle is a 45-90 one), with its boundary vertices.
fn unit_square(n: usize) -> (Vec<[f64; 2]>, Vec<[u32; 3]>, Vec<bool>) {
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let h = 1.0 / n as f64;
    let mut points = Vec::new();
    let mut fixed = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            points.push([i as f64 * h, j as f64 * h]);
            fixed.push(i == 0 || j == 0 || i == n || j == n);
        }
    }
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if (i + j) % 2 == 0 {
                triangles.extend([[a, b, c], [a, c, d]]);
            } else {
                triangles.extend([[a, b, d], [b, c, d]]);
            }
        }
    }
    (points, triangles, fixed)
}

/// L2 error of the P1 solution against `u`, with the 6-point degree-4 rule per triangle.
fn l2_error(
    points: &[[f64; 2]],
    triangles: &[[u32; 3]],
    t: &[f64],
    u: impl Fn([f64; 2]) -> f64,
) -> f64 {
    const RULE: [(f64, f64, f64); 6] = [
        (
            0.108_103_018_168_070,
            0.445_948_490_915_965,
            0.223_381_589_678_011,
        ),
        (
            0.445_948_490_915_965,
            0.108_103_018_168_070,
            0.223_381_589_678_011,
        ),
        (
            0.445_948_490_915_965,
            0.445_948_490_915_965,
            0.223_381_589_678_011,
        ),
        (
            0.816_847_572_980_459,
            0.091_576_213_509_771,
            0.109_951_743_655_322,
        ),
        (
            0.091_576_213_509_771,
            0.816_847_572_980_459,
            0.109_951_743_655_322,
        ),
        (
            0.091_576_213_509_771,
            0.091_576_213_509_771,
            0.109_951_743_655_322,
        ),
    ];
    let mut sum = 0.0;
    for tri in triangles {
        let p = tri.map(|v| points[v as usize]);
        let val = tri.map(|v| t[v as usize]);
        let area = 0.5
            * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1])
                - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]));
        for &(l1, l2, w) in &RULE {
            let l = [1.0 - l1 - l2, l1, l2];
            let x = [
                l[0] * p[0][0] + l[1] * p[1][0] + l[2] * p[2][0],
                l[0] * p[0][1] + l[1] * p[1][1] + l[2] * p[2][1],
            ];
            let th = l[0] * val[0] + l[1] * val[1] + l[2] * val[2];
            sum += w * area * (u(x) - th).powi(2);
        }
    }
    sum.sqrt()
}

#[test]
fn second_order_convergence_on_the_unit_square() {
    let u = |x: [f64; 2]| (PI * x[0]).sin() * (PI * x[1]).sin();
    let q = |_: usize, x: [f64; 2]| 2.0 * PI * PI * u(x);
    let mut errors = Vec::new();
    for n in [8, 16, 32, 64, 128] {
        let (points, triangles, fixed) = unit_square(n);
        let sys = fem::assemble(&points, &triangles, &fixed, |_| 1.0, q);
        assert!(sys.max_off_diagonal() <= 0.0);
        let (t, _) = fem::solve(&sys).unwrap();
        errors.push((n, l2_error(&points, &triangles, &t, u)));
    }
    for w in errors.windows(2) {
        let ((n0, e0), (n1, e1)) = (w[0], w[1]);
        let rate = (e0 / e1).log2();
        println!(
            "n = {n0:>3} -> {n1:>3}: L2 error {e0:.3e} -> {e1:.3e}, ratio {:.3}, rate {rate:.3}",
            e0 / e1
        );
        assert!(
            (1.8..=2.2).contains(&rate),
            "rate {rate} between n = {n0} and {n1}"
        );
    }
}

fn report(name: &str, board: &orthtree::mesh::Board) {
    let mesh = generate_mesh(board).unwrap().mesh;
    let (k, q) = fem::board_materials(board);
    let start = Instant::now();
    let sys = fem::assemble_board(&mesh, &k, &q);
    let assembly = start.elapsed();
    let (t, times) = fem::solve(&sys).unwrap();
    let t_min = t.iter().copied().fold(f64::INFINITY, f64::min);
    let t_max = t.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    println!(
        "{name}: {} triangles, {} unknowns, assembly {:.1} ms, solve {:.1} ms \
         (symbolic {:.1}, Cholesky {:.1}, substitution {:.1}), T in [{t_min:.3e}, {t_max:.4}] K",
        mesh.triangles.len(),
        sys.n,
        assembly.as_secs_f64() * 1e3,
        times.total().as_secs_f64() * 1e3,
        times.symbolic.as_secs_f64() * 1e3,
        times.numeric.as_secs_f64() * 1e3,
        times.substitution.as_secs_f64() * 1e3,
    );
    assert!(t_min >= 0.0 && t_max > 0.0);
}

#[test]
fn timings_for_the_sample_board() {
    report("sample_board", &sample_board());
}
