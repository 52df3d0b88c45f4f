//! The node budget of the region-tree shape constructors: astronomically large shapes are
//! refused before building (an estimate named in the error), every construction stops at its
//! limit while building, and a shape that needs exactly the limit is built.

use orthtree::image::{Coverage, ImageError, RegionTree, DEFAULT_MAX_NODES};
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};
use std::time::{Duration, Instant};

/// The smallest limit under which `build` succeeds (at most `ceiling`), found by bisection;
/// every failure below it must be a `TooManyNodes` naming the limit tried.
fn smallest_limit<T>(ceiling: u64, build: impl Fn(u64) -> Result<T, ImageError>) -> u64 {
    assert!(build(ceiling).is_ok(), "the shape does not fit {ceiling}");
    let (mut lo, mut hi) = (0u64, ceiling); // build(lo) fails (or lo = 0), build(hi) succeeds
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        match build(mid) {
            Ok(_) => hi = mid,
            Err(ImageError::TooManyNodes { limit, nodes, .. }) => {
                assert_eq!(limit, mid);
                assert!(
                    nodes > mid,
                    "{nodes} cells reported against the limit {mid}"
                );
                lo = mid;
            }
            Err(e) => panic!("unexpected error {e}"),
        }
    }
    hi
}

/// Asserts `result` is refused before building, with an estimate above `limit`, quickly.
fn assert_refused_at_once<T>(started: Instant, result: Result<T, ImageError>, limit: u64) {
    match result {
        Err(ImageError::TooManyNodes {
            nodes,
            limit: l,
            estimated: true,
        }) => {
            assert_eq!(l, limit);
            assert!(nodes > limit);
            let message = ImageError::TooManyNodes {
                nodes,
                limit,
                estimated: true,
            }
            .to_string();
            assert!(message.contains(&nodes.to_string()) && message.contains(&limit.to_string()));
        }
        Err(e) => panic!("refused with {e}, not by the estimate"),
        Ok(_) => panic!("built a shape above the limit"),
    }
    // An estimate, not a build: well under a second even on a loaded machine.
    assert!(started.elapsed() < Duration::from_secs(2));
}

#[test]
fn huge_balls_are_refused_before_building_in_every_dimension() {
    fn ball<const D: usize>(depth: u32, radius_fraction: f64) {
        let side = 1u32 << depth;
        let centre = [f64::from(side) / 2.0; D];
        let r = f64::from(side) * radius_fraction;
        let t = Instant::now();
        let result = RegionTree::<D>::from_ball([side; D], centre, r);
        assert_refused_at_once(t, result, DEFAULT_MAX_NODES);
        let t = Instant::now();
        let result = RegionTree::<D>::from_ball_with_limit([side; D], centre, r, 1000);
        assert_refused_at_once(t, result, 1000);
    }
    ball::<2>(31, 0.3);
    ball::<2>(30, 0.49);
    ball::<3>(21, 0.25);
    ball::<3>(18, 0.4);
    ball::<4>(15, 0.3);
    ball::<5>(12, 0.3);
    ball::<8>(7, 0.3);
}

#[test]
fn huge_boxes_and_pixel_functions_are_refused_before_building() {
    let side = (1u32 << 21) - 1;
    let t = Instant::now();
    assert_refused_at_once(t, RegionTree::<3>::full([side; 3]), DEFAULT_MAX_NODES);
    let t = Instant::now();
    let odd = ([3, 5], [1 << 30, (1 << 31) - 3]);
    let result = RegionTree::<2>::from_boxes([1 << 31; 2], &[odd]);
    assert_refused_at_once(t, result, DEFAULT_MAX_NODES);
    let t = Instant::now();
    let result = RegionTree::<4>::from_boxes_with_limit([1 << 15; 4], &[([1; 4], [7; 4])], 10);
    assert_refused_at_once(t, result, 10);
    let t = Instant::now();
    let result = RegionTree::<2>::from_fn([1 << 16, 1 << 13], |[x, y]| x < y);
    assert_refused_at_once(t, result, DEFAULT_MAX_NODES);
    let t = Instant::now();
    let result = RegionTree::<3>::from_fn_with_limit([10, 10, 10], 999, |_| true);
    assert_refused_at_once(t, result, 999);
}

#[test]
fn boxes_that_cost_nothing_are_not_refused() {
    // Faces on the grid of the largest cells, even at the deepest depth.
    let s = 1u32 << 21;
    let t = RegionTree::<3>::from_boxes([s; 3], &[([0, s / 2, 0], [s / 2, s, s])]).unwrap();
    assert_eq!(t.node_count(), 9);
    let t = RegionTree::<2>::full([1 << 31; 2]).unwrap();
    assert_eq!(t.node_count(), 1);
    // A ball holding the whole extent, or missing it.
    let t = RegionTree::<3>::from_ball([s; 3], [0.0; 3], 1e300).unwrap();
    assert_eq!(t.node_count(), 1);
    let t = RegionTree::<3>::from_ball([s; 3], [-1e9; 3], 1e9).unwrap();
    assert_eq!(t.node_count(), 1);
}

#[test]
fn the_count_stops_every_construction_at_its_limit() {
    // Several boxes: no estimate, the count alone.
    let boxes = [([1, 1], [1 << 20, 3]), ([5, 0], [9, 1 << 20])];
    let err = RegionTree::<2>::from_boxes_with_limit([1 << 20; 2], &boxes, 5000).unwrap_err();
    assert_eq!(
        err,
        ImageError::TooManyNodes {
            nodes: 5001,
            limit: 5000,
            estimated: false
        }
    );
    assert!(err.to_string().contains("more than 5000 cells"));
    // Any classifier: counted cell by cell.
    let mut calls = 0u64;
    let err = RegionTree::<3>::from_region_with_limit([1 << 20; 3], 777, |_, _| {
        calls += 1;
        Coverage::Partial
    })
    .unwrap_err();
    assert!(matches!(err, ImageError::TooManyNodes { limit: 777, .. }));
    assert_eq!(calls, 777, "the classifier is not called past the limit");
}

#[test]
fn shapes_needing_exactly_the_limit_are_built() {
    let mut rng = SmallRng::seed_from_u64(5);
    for _ in 0..6 {
        let side = rng.gen_range(16..300u32);
        let c = [rng.gen_range(-20.0..320.0), rng.gen_range(-20.0..320.0)];
        let r = rng.gen_range(0.0..200.0);
        let expected = RegionTree::<2>::from_ball([side, side], c, r).unwrap();
        let build = |limit| RegionTree::<2>::from_ball_with_limit([side, side], c, r, limit);
        let n = smallest_limit(1 << 24, build);
        assert_eq!(build(n).unwrap(), expected, "ball {c:?} {r} on {side}");
    }
    for _ in 0..4 {
        let side = rng.gen_range(8..40u32);
        let c = [0.0; 3].map(|_: f64| rng.gen_range(0.0..f64::from(side)));
        let r = rng.gen_range(1.0..30.0);
        let build = |limit| RegionTree::<3>::from_ball_with_limit([side; 3], c, r, limit);
        let n = smallest_limit(1 << 24, build);
        assert_eq!(
            build(n).unwrap(),
            RegionTree::<3>::from_ball([side; 3], c, r).unwrap()
        );
    }
    for _ in 0..6 {
        let side = rng.gen_range(8..1000u32);
        let lo = [rng.gen_range(0..side), rng.gen_range(0..side)];
        let hi = [rng.gen_range(lo[0]..=side), rng.gen_range(lo[1]..=side)];
        let build =
            |limit| RegionTree::<2>::from_boxes_with_limit([side, side], &[(lo, hi)], limit);
        let n = smallest_limit(1 << 24, build);
        assert_eq!(
            build(n).unwrap(),
            RegionTree::<2>::from_boxes([side; 2], &[(lo, hi)]).unwrap()
        );
    }
    // A pixel function classifies every cell within the extent: exactly the limit passes.
    let build = |limit| RegionTree::<2>::from_fn_with_limit([37, 23], limit, |[x, y]| x > y);
    let n = smallest_limit(1 << 20, build);
    assert!(n >= 37 * 23);
    assert_eq!(
        build(n).unwrap(),
        RegionTree::<2>::from_fn([37, 23], |[x, y]| x > y).unwrap()
    );
}
