//! Every float parameter of the point trees' queries with NaN, the infinities, -0.0, 0,
//! `f64::MAX`, `f64::MIN_POSITIVE` and the smallest subnormal: refused with an error naming the
//! parameter and value, or answered as brute force answers (an infinite radius or maximum
//! distance holds everything, -0.0 is 0, a huge `eps` accepts any point), on `PointTree`,
//! `DynamicPointTree` and `CompressedTree`, on ordinary points and on points near `f64::MAX`.

use crate::common;

use orthtree::geom::FloatBits;
use orthtree::prelude::*;
use orthtree::query::{QueryError, Region};
use orthtree::{
    geom::AabbError, geom::RootGeometry, points::PointTreeBuilder, query::HalfSpace, Aabb, Ball,
    CompressedTree, DynamicPointTree, Error, PointTree, SkipQuadtree,
};
use rand::Rng;

const TINY: f64 = 5e-324;
const ODD: [f64; 9] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    -0.0,
    0.0,
    f64::MAX,
    f64::MIN_POSITIVE,
    TINY,
    -1.0,
];

/// Points on a grid of step 1/8 in [0, 4]^2 (so that distances are exact and far from the
/// underflow range), with duplicates.
fn grid_points(seed: u64, n: usize) -> Vec<([f64; 2], usize)> {
    let mut r = common::rng(seed);
    (0..n)
        .map(|i| {
            let p = [
                r.gen_range(0..=32) as f64 / 8.0,
                r.gen_range(0..=32) as f64 / 8.0,
            ];
            (p, i)
        })
        .collect()
}

/// Points spread over every magnitude up to ±f64::MAX, with duplicates.
fn extreme_points(seed: u64, n: usize) -> Vec<([f64; 2], usize)> {
    let mut r = common::rng(seed);
    let pick = |r: &mut rand::rngs::SmallRng| -> f64 {
        let m = match r.gen_range(0..6) {
            0 => f64::MAX,
            1 => f64::MAX * r.r#gen::<f64>(),
            2 => 10f64.powi(r.gen_range(-320..308)),
            3 => 0.0,
            4 => TINY * r.gen_range(1..4) as f64,
            _ => 1e200 * r.gen_range(1..4) as f64,
        };
        if r.r#gen() {
            -m
        } else {
            m
        }
    };
    (0..n).map(|i| ([pick(&mut r), pick(&mut r)], i)).collect()
}

/// The distance of `a` and `b` by scaling (an oracle independent of the crate's formulas): no
/// square overflows or underflows; infinite only when a difference exceeds `f64::MAX`.
fn distance(a: &[f64; 2], b: &[f64; 2]) -> f64 {
    let d = [(a[0] - b[0]).abs(), (a[1] - b[1]).abs()];
    let m = d[0].max(d[1]);
    if m == 0.0 || m == f64::INFINITY {
        return m;
    }
    m * ((d[0] / m).powi(2) + (d[1] / m).powi(2)).sqrt()
}

/// `true` when `a` and `b` are clearly apart and in the normal range, where a product with a
/// normal of magnitude near 1 cannot round them together.
fn clearly_apart(a: f64, b: f64) -> bool {
    let m = a.abs().max(b.abs());
    (a / 2.0 - b / 2.0).abs() > 1e-9 * m && m > 1e-290
}

/// The items a query found, sorted.
fn sorted(mut v: Vec<usize>) -> Vec<usize> {
    v.sort();
    v
}

/// Every parameter of every query of `$t` (items: input indices) on the entries `$e`.
macro_rules! check_parameters {
    ($t:expr, $e:expr) => {{
        let (t, e) = (&$t, &$e);
        let all: Vec<usize> = (0..e.len()).collect();
        let brute = |keep: &dyn Fn(&[f64; 2]) -> bool| -> Vec<usize> {
            (0..e.len()).filter(|&i| keep(&e[i].0)).collect()
        };
        let centres = [e[0].0, [0.0, 0.0], [1.0, -3.0]];
        for c in centres {
            for r in ODD.into_iter().chain([1.0, 1e200, 1e-300, 2.5]) {
                let found = t.in_ball(&c, r).map(|it| sorted(it.map(|(_, &i)| i).collect()));
                if r.is_nan() || r < 0.0 {
                    assert_eq!(found.err(), Some(QueryError::InvalidRadius { radius: r.into() }));
                    continue;
                }
                let found = found.unwrap();
                let ball = Ball::new(c, r).unwrap();
                // the region's own test, and the true distance wherever it is clearly in or out
                assert_eq!(found, brute(&|p| ball.contains(p)), "radius {r:e} at {c:?}");
                for (p, i) in e.iter() {
                    let d = distance(p, &c);
                    if r == f64::INFINITY || d < r * (1.0 - 1e-9) {
                        assert!(found.contains(i), "{p:?} at {d:e} within {r:e}");
                    } else if d > r * (1.0 + 1e-9) || (r == 0.0 && d > 0.0) {
                        assert!(!found.contains(i), "{p:?} at {d:e} beyond {r:e}");
                    }
                }
            }
            // maximum distances: refused when negative or NaN; otherwise the brute-force answer
            for max in ODD.into_iter().chain([1.0, 0.25]) {
                let near = t.nearest_within(&c, max);
                let k = t.k_nearest_within(&c, 3, max);
                let it = t.nearest_iter_within(&c, max).map(|it| it.count());
                if max.is_nan() || max < 0.0 {
                    let want = QueryError::InvalidMaxDistance { value: max.into() };
                    assert_eq!(near.err(), Some(want));
                    assert_eq!(k.err(), Some(want));
                    assert_eq!(it.err(), Some(want));
                    continue;
                }
                let d2 = |p: &[f64; 2]| (p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2);
                let mut within: Vec<f64> = e.iter().map(|(p, _)| d2(p)).filter(|&d| d <= max).collect();
                within.sort_by(f64::total_cmp);
                assert_eq!(near.unwrap().map(|n| n.distance), within.first().copied());
                let got: Vec<f64> = k.unwrap().iter().map(|n| n.distance).collect();
                assert_eq!(got, within[..within.len().min(3)]);
                assert_eq!(it.unwrap(), within.len());
            }
        }
        // boxes: NaN refused naming the axis; infinite and signed-zero bounds answered
        for x in ODD {
            for axis in 0..2 {
                let mut b = Aabb { min: [-1.0, -1.0], max: [2.0, 2.0] };
                b.max[axis] = x;
                let found = t.in_box(&b).map(|it| sorted(it.map(|(_, &i)| i).collect()));
                if x.is_nan() {
                    assert_eq!(found.err(), Some(QueryError::NanBound { axis }));
                    continue;
                }
                let want = brute(&|p| (0..2).all(|a| b.min[a] <= p[a] && p[a] <= b.max[a]));
                assert_eq!(found.unwrap(), want, "box {b:?}");
            }
        }
        let whole = Aabb { min: [-f64::MAX; 2], max: [f64::MAX; 2] };
        assert_eq!(sorted(t.in_box(&whole).unwrap().map(|(_, &i)| i).collect()), all);
        let inf = Aabb { min: [f64::NEG_INFINITY; 2], max: [f64::INFINITY; 2] };
        assert_eq!(sorted(t.in_box(&inf).unwrap().map(|(_, &i)| i).collect()), all);
        // half-spaces: a bad normal names the axis, a NaN offset is refused; others brute force
        for x in ODD {
            for axis in 0..2 {
                let mut n = [1.0, -1.0];
                n[axis] = x;
                let found = t.in_half_space(n, 0.5).map(|it| sorted(it.map(|(_, &i)| i).collect()));
                if !x.is_finite() {
                    assert_eq!(found.err(), Some(QueryError::InvalidNormal { axis }));
                    continue;
                }
                let h = HalfSpace::new(n, 0.5).unwrap();
                assert_eq!(found.unwrap(), brute(&|p| h.contains(p)));
            }
            let found = t.in_half_space([1.0, 0.0], x).map(|it| sorted(it.map(|(_, &i)| i).collect()));
            if x.is_nan() {
                assert_eq!(found.err(), Some(QueryError::NanOffset));
                continue;
            }
            let found = found.unwrap();
            let h = HalfSpace::new([1.0, 0.0], x).unwrap();
            assert_eq!(found, brute(&|p| h.contains(p)));
            // x_0 <= offset wherever the two are clearly apart (and everything for +inf)
            for (p, i) in e.iter() {
                if x == f64::INFINITY || clearly_apart(p[0], x) {
                    assert_eq!(found.contains(i), p[0] <= x, "{p:?} for offset {x:e}");
                }
            }
        }
        // normals whose products overflow unscaled: x <= y, x >= y
        for big in [f64::MAX, 1e300, 1e200] {
            for (n, keep) in [
                ([big, -big], (|p: &[f64; 2]| p[0] <= p[1]) as fn(&[f64; 2]) -> bool),
                ([-big, big], |p: &[f64; 2]| p[0] >= p[1]),
            ] {
                let found = sorted(t.in_half_space(n, 0.0).unwrap().map(|(_, &i)| i).collect());
                let h = HalfSpace::new(n, 0.0).unwrap();
                assert_eq!(found, brute(&|p| h.contains(p)));
                // wherever the two coordinates are clearly apart, the true answer
                for (p, i) in e.iter() {
                    if clearly_apart(p[0], p[1]) {
                        assert_eq!(found.contains(i), keep(p), "{p:?} for normal {n:?}");
                    }
                }
            }
        }
    }};
}

#[test]
fn query_parameters_on_ordinary_points() {
    for seed in 0..3 {
        let e = grid_points(seed, 200);
        check_parameters!(PointTree::new(&e).unwrap(), e);
        check_parameters!(PointTreeBuilder::new().bucket_size(1).build(&e).unwrap(), e);
        check_parameters!(DynamicPointTree::new(&e).unwrap(), e);
        check_parameters!(CompressedTree::new(&e).unwrap(), e);
    }
}

#[test]
fn query_parameters_on_points_near_f64_max() {
    for seed in 0..3 {
        let e = extreme_points(seed, 150);
        check_parameters!(PointTree::new(&e).unwrap(), e);
        check_parameters!(PointTreeBuilder::new().bucket_size(1).build(&e).unwrap(), e);
        check_parameters!(DynamicPointTree::new(&e).unwrap(), e);
        check_parameters!(CompressedTree::new(&e).unwrap(), e);
    }
}

/// `approx_nearest`'s `eps`: refused when negative or NaN; 0, -0.0 and subnormals give the exact
/// nearest; a huge or infinite `eps` (whose (1 + eps)^2 overflows) still gives a point.
#[test]
fn approx_nearest_eps() {
    for (seed, e) in [(0, grid_points(4, 300)), (1, extreme_points(5, 200))] {
        let s = SkipQuadtree::new(&e).unwrap();
        let mut r = common::rng(seed);
        for _ in 0..20 {
            let q = e[r.gen_range(0..e.len())].0.map(|x| x * 0.75);
            let d2 = |p: &[f64; 2]| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
            let best = e.iter().map(|(p, _)| d2(p)).fold(f64::INFINITY, f64::min);
            for eps in ODD.into_iter().chain([1e154, 1e155, 1e300, 0.5]) {
                let found = s.approx_nearest(&q, eps);
                if eps.is_nan() || eps < 0.0 {
                    assert_eq!(
                        found.err(),
                        Some(QueryError::InvalidEpsilon { value: eps.into() })
                    );
                    continue;
                }
                let n = found.unwrap().0.expect("a point on a non-empty tree");
                assert_eq!(d2(n.point), n.distance);
                assert!(e.iter().any(|(p, i)| p == n.point && i == n.item));
                if eps <= f64::MIN_POSITIVE {
                    assert_eq!(n.distance, best, "eps {eps:e}");
                } else if eps == 0.5 && best.is_finite() {
                    assert!(n.distance <= best * 2.25 * (1.0 + 1e-12));
                }
            }
        }
    }
}

/// Root boxes and cubes: NaN and infinite corners and sides are refused, naming the axis or the
/// side; ±f64::MAX boxes work.
#[test]
fn root_boxes_and_cubes() {
    let e = extreme_points(9, 100);
    for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for axis in 0..2 {
            let mut max = [f64::MAX; 2];
            max[axis] = x;
            let want = AabbError::NonFinite { axis };
            assert_eq!(Aabb::new([-f64::MAX; 2], max), Err(want));
            let root = Aabb {
                min: [-f64::MAX; 2],
                max,
            };
            let err = PointTreeBuilder::new()
                .root_box(root)
                .build(&e)
                .unwrap_err();
            assert_eq!(err, Error::InvalidRootBox(want));
            let mut min = [0.0; 2];
            min[axis] = x;
            assert_eq!(RootGeometry::<2>::try_new(min, 1.0), Err(want));
        }
        assert_eq!(
            RootGeometry::<2>::try_new([0.0; 2], x),
            Err(AabbError::InvalidSide {
                side: FloatBits::from(x)
            })
        );
    }
    assert!(RootGeometry::<2>::try_new([0.0; 2], -1.0).is_err());
    for side in [0.0, -0.0, TINY, f64::MIN_POSITIVE, f64::MAX] {
        let g = RootGeometry::<2>::try_new([-1.0, 0.0], side).unwrap();
        assert!(g.root_box().max[1] >= side && g.root_box().min == [-1.0, 0.0]);
    }
    let root = Aabb::new([-f64::MAX; 2], [f64::MAX; 2]).unwrap();
    let t = PointTreeBuilder::new().root_box(root).build(&e).unwrap();
    t.validate().unwrap();
    check_parameters!(t, e);
    // the extent of such a box overflows to infinity, as documented, without a panic
    assert_eq!(root.extent(0), f64::INFINITY);
}
