//! Exercise 14.11: the node count of a region quadtree of a shape drawn into a 2^k x 2^k image is
//! at most 16 P + 16 k + 1 for a shape bounded by one closed curve of length P (the bound proved
//! in the `image` module docs), on random discs and random star-shaped polygons.

use orthtree::image::ImageTree;
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

fn bound(perimeter: f64, k: u8) -> f64 {
    16.0 * perimeter + 16.0 * f64::from(k) + 1.0
}

#[test]
fn discs_within_the_perimeter_bound() {
    let mut rng = SmallRng::seed_from_u64(14_11);
    let mut worst: f64 = 0.0;
    for _ in 0..200 {
        let k = rng.gen_range(1..=11u8);
        let side = 1u32 << k;
        let s = f64::from(side);
        let centre = [rng.gen_range(0.0..s), rng.gen_range(0.0..s)];
        let r = rng.gen_range(0.0..s / 2.0);
        let t = ImageTree::from_ball([side, side], centre, r).unwrap();
        let p = 2.0 * std::f64::consts::PI * r;
        let n = t.node_count() as f64;
        assert!(
            n <= bound(p, k),
            "k {k}, r {r}: {n} nodes > {}",
            bound(p, k)
        );
        if p > 8.0 {
            worst = worst.max((n - 16.0 * f64::from(k) - 1.0) / p);
        }
    }
    // in practice far below the proved 16 nodes per unit of perimeter
    assert!(worst < 8.0, "{worst}");
}

/// Even-odd point-in-polygon test.
fn inside(poly: &[[f64; 2]], [x, y]: [f64; 2]) -> bool {
    let mut c = false;
    for i in 0..poly.len() {
        let ([x0, y0], [x1, y1]) = (poly[i], poly[(i + 1) % poly.len()]);
        if (y0 > y) != (y1 > y) && x < x0 + (y - y0) / (y1 - y0) * (x1 - x0) {
            c = !c;
        }
    }
    c
}

#[test]
fn polygons_within_the_perimeter_bound() {
    let mut rng = SmallRng::seed_from_u64(14_12);
    for _ in 0..60 {
        let k = rng.gen_range(2..=9u8);
        let side = 1u32 << k;
        let s = f64::from(side);
        // a star-shaped polygon: sorted angles, random radii around a centre (simple)
        let n = rng.gen_range(3..20);
        let mut angles: Vec<f64> = (0..n)
            .map(|_| rng.gen_range(0.0..std::f64::consts::TAU))
            .collect();
        angles.sort_by(f64::total_cmp);
        let c = [rng.gen_range(0.0..s), rng.gen_range(0.0..s)];
        let poly: Vec<[f64; 2]> = angles
            .iter()
            .map(|&a| {
                let r = rng.gen_range(0.0..s / 2.0);
                [c[0] + r * a.cos(), c[1] + r * a.sin()]
            })
            .collect();
        let perimeter: f64 = (0..n)
            .map(|i| {
                let (p, q) = (poly[i], poly[(i + 1) % n]);
                (p[0] - q[0]).hypot(p[1] - q[1])
            })
            .sum();
        let t = ImageTree::from_fn([side, side], |[x, y]| {
            inside(&poly, [f64::from(x) + 0.5, f64::from(y) + 0.5])
        })
        .unwrap();
        assert!(t.is_canonical());
        let nodes = t.node_count() as f64;
        assert!(
            nodes <= bound(perimeter, k),
            "k {k}: {nodes} nodes > {}",
            bound(perimeter, k)
        );
    }
}
