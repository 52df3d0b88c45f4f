//! The tests of [`RootGeometry`](super::RootGeometry): split lines go to the lower cell at
//! every level, the quantisation's fast guess agrees with the exact boundaries (near and far
//! from the origin, tiny and huge cubes), the batched keys agree with one key at a time, and
//! extreme boxes keep their boundaries finite and monotone.

use super::*;

#[test]
fn split_lines_go_to_the_lower_cell_at_every_level() {
    let g = RootGeometry::<2>::new([-1.0, -1.0], 2.0);
    assert_eq!(g.cell_of(&[0.0, 0.0], 1).coords(), [0, 0]);
    assert_eq!(g.cell_of(&[0.5, -0.5], 2).coords(), [2, 0]);
    assert_eq!(g.cell_of(&[0.5000001, -0.5], 2).coords(), [3, 0]);
    assert_eq!(g.cell_of(&[-1.0, 1.0], 3).coords(), [0, 7]);
}

/// The guess's shortcut against the boundaries alone, on boundaries, next to them, and at
/// random, for cubes near and far from the origin, tiny and huge.
#[test]
fn the_guess_shortcut_agrees_with_the_boundaries() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand::rngs::SmallRng::seed_from_u64(3);
    fn check<const D: usize>(g: &RootGeometry<D>, x: f64) {
        let finest = RootGeometry::<D>::FINEST as u8;
        for axis in 0..D {
            // the finest level, and level 32, where the deep cells start
            for level in [finest, 32] {
                let finer = (1u64 << (level - finest)) as f64;
                let scaled = (x * 0.5 - g.half_lo[axis]) * g.scale * finer;
                assert_eq!(
                    g.coordinate_at(axis, x, level),
                    g.exact_coordinate(axis, x, scaled, level),
                    "x = {x:e} at level {level} in {g:?}"
                );
            }
        }
    }
    let cubes = [
        (0.0, 1.0),
        (-1.0, 2.0),
        (0.1, 0.7),
        (100.0, 1.0),
        (-1e4, 3.0),
        (1e6, 1.0),
        (-3e9, 1e-3),
        (1e15, 7.0),
        (1e-300, 1e-300),
        (0.0, 1e300),
        (-1e300, 1e300),
    ];
    // the shortcut is taken nearly always on the usual cubes
    assert!(guess_margin(0.0, 0.5, 32) < 1e-5);
    assert!(guess_margin(-50.0, 0.5, 32) < 1e-3);
    for (lo, side) in cubes {
        let g2 = RootGeometry::<2>::new([lo; 2], side);
        let g3 = RootGeometry::<3>::new([lo; 3], side);
        for _ in 0..20_000 {
            let t: f64 = rng.gen_range(-0.01..1.01);
            let x = lo + side * t;
            check(&g2, x);
            check(&g3, x);
            let j = rng.gen_range(0..1u64 << 32);
            for b in [g2.boundary(0, j, 32)] {
                for y in [b, b.next_up(), b.next_down()] {
                    check(&g2, y);
                }
            }
            let j = rng.gen_range(0..1u64 << 21);
            let b = g3.boundary(0, j, 21);
            for y in [b, b.next_up(), b.next_down()] {
                check(&g3, y);
            }
        }
    }
}

/// The lanes of `keys_into` against `key`: random points, points on and next to cell
/// boundaries, the cube's corners, and cubes where the guess is never trusted.
#[test]
fn lane_keys_agree_with_key() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand::rngs::SmallRng::seed_from_u64(5);
    fn check<const D: usize>(g: &RootGeometry<D>, points: &[[f64; D]]) {
        let mut keys = Vec::new();
        g.keys_into(points.len(), |i| &points[i], |i, k| keys.push((i, k)));
        let expected: Vec<(usize, u64)> = points.iter().map(|p| g.key(p)).enumerate().collect();
        assert_eq!(keys, expected, "in {g:?}");
    }
    for (lo, side) in [
        (0.0, 1.0),
        (-3.0, 7.0),
        (1e6, 1.0),
        (-1e300, 1e300),
        (0.0, 1e-310),
    ] {
        let g2 = RootGeometry::<2>::new([lo; 2], side);
        let g3 = RootGeometry::<3>::new([lo; 3], side);
        let mut p2 = vec![[lo; 2], [lo + side; 2]];
        let mut p3 = vec![[lo; 3], [lo + side; 3]];
        for _ in 0..3001 {
            let x = lo + side * rng.r#gen::<f64>();
            let j = rng.gen_range(0..1u64 << 32);
            let b = g2.boundary(0, j, 32);
            p2.push([x, [b, b.next_up(), b.next_down()][j as usize % 3]]);
            let b = g3.boundary(1, j >> 11, 21);
            p3.push([x, b, lo + side * rng.r#gen::<f64>()]);
        }
        check(&g2, &p2);
        check(&g3, &p3);
        // the other dimensions' spreading
        let p1: Vec<[f64; 1]> = p2.iter().map(|p| [p[1]]).collect();
        check(&RootGeometry::<1>::new([lo], side), &p1);
        let p5: Vec<[f64; 5]> = p3.iter().map(|p| [p[0], p[1], p[2], p[1], p[0]]).collect();
        check(&RootGeometry::<5>::new([lo; 5], side), &p5);
    }
}

#[test]
fn extreme_boxes_stay_finite_and_monotone() {
    let b = Aabb::around(&[[-f64::MAX, -1.0], [f64::MAX, 1.0]]);
    let g = RootGeometry::enclosing(&b);
    assert!(g.root_box().max[0] >= f64::MAX);
    assert!(g.boundary(0, 1, 1).is_finite());
    assert_eq!(g.cell_of(&[f64::MAX, 0.0], 1).coords()[0], 1);
    assert_eq!(g.cell_of(&[0.0, 0.0], 1).coords()[0], 0);
    let tiny = Aabb::around(&[[0.0; 2], [f64::MIN_POSITIVE / 4.0; 2]]);
    let g = RootGeometry::enclosing(&tiny);
    assert!(g.root_box().max[0] >= tiny.max[0]);
    let same = Aabb::around(&[[3.0; 2]]);
    assert_eq!(RootGeometry::enclosing(&same).root_box().max, [4.0, 4.0]);
}
