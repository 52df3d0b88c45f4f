//! Seeded point sets shared by the benchmarks.
//!
//! Every generator is deterministic (`SmallRng::seed_from_u64`), so each crate and each run sees
//! exactly the same points.

use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

/// The point distributions the benchmarks run on.
#[derive(Clone, Copy, Debug)]
pub enum Distribution {
    /// Independent uniform coordinates in `[0, 1)`.
    Uniform,
    /// 64 isotropic Gaussian clusters, sigma 0.01, centres uniform in `[0, 1)^D`; each point picks
    /// a cluster uniformly at random. Not clamped: a few points fall slightly outside the unit
    /// cube, which only moves the bounding box.
    Clustered,
}

impl Distribution {
    /// Both distributions, in the order they are benchmarked.
    pub const ALL: [Distribution; 2] = [Distribution::Uniform, Distribution::Clustered];

    /// The name used in benchmark ids.
    pub fn name(self) -> &'static str {
        match self {
            Distribution::Uniform => "uniform",
            Distribution::Clustered => "clustered",
        }
    }

    /// `n` points of this distribution; the same `(n, seed)` always gives the same points.
    pub fn points<const D: usize>(self, n: usize, seed: u64) -> Vec<[f64; D]> {
        match self {
            Distribution::Uniform => uniform(n, seed),
            Distribution::Clustered => clustered(n, 64, 0.01, seed),
        }
    }
}

/// `n` points with independent uniform coordinates in `[0, 1)`.
pub fn uniform<const D: usize>(n: usize, seed: u64) -> Vec<[f64; D]> {
    let mut rng = SmallRng::seed_from_u64(seed);
    (0..n)
        .map(|_| core::array::from_fn(|_| rng.r#gen::<f64>()))
        .collect()
}

/// `n` points in `clusters` Gaussian clusters of standard deviation `sigma` (not clamped). The
/// centres depend on `clusters` alone, not on `seed`: query points drawn with another seed fall
/// in the same clusters as the data (with the centres drawn from `seed`, as before 2026-11-22,
/// most queries landed in empty space, and the calibrated boxes and balls grew to match).
pub fn clustered<const D: usize>(
    n: usize,
    clusters: usize,
    sigma: f64,
    seed: u64,
) -> Vec<[f64; D]> {
    let mut centre_rng = SmallRng::seed_from_u64(CENTRE_SEED);
    let centres: Vec<[f64; D]> = (0..clusters)
        .map(|_| core::array::from_fn(|_| centre_rng.r#gen::<f64>()))
        .collect();
    let mut rng = SmallRng::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            let c = centres[rng.gen_range(0..clusters)];
            core::array::from_fn(|a| c[a] + sigma * standard_normal(&mut rng))
        })
        .collect()
}

/// `n` points on the surface of the sphere of radius 1/2 centred in the unit cube (a circle in
/// 2D): data of one dimension less than the space, as a scan of a surface gives.
#[allow(dead_code)] // a workload of the comparison program, not of the benches
pub fn sphere_surface<const D: usize>(n: usize, seed: u64) -> Vec<[f64; D]> {
    let mut rng = SmallRng::seed_from_u64(seed);
    (0..n)
        .map(|_| loop {
            let v: [f64; D] = core::array::from_fn(|_| standard_normal(&mut rng));
            let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            if norm > 1e-9 {
                break core::array::from_fn(|a| 0.5 + 0.5 * v[a] / norm);
            }
        })
        .collect()
}

/// The seed of the cluster centres, shared by every point set.
const CENTRE_SEED: u64 = 0x005E_EDC1;

/// One standard normal sample (Box-Muller, cosine branch).
fn standard_normal(rng: &mut SmallRng) -> f64 {
    let u1 = 1.0 - rng.r#gen::<f64>(); // (0, 1]: ln is finite
    let u2 = rng.r#gen::<f64>();
    (-2.0 * u1.ln()).sqrt() * (core::f64::consts::TAU * u2).cos()
}
