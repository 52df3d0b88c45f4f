//! Periodic domains with coordinates far outside the period box: the minimum-image metrics
//! ([`MinImage`]) and the periodic queries (k-nearest, the ball, pairs within a radius, the
//! k-nearest self-join) on trees of unwrapped and of wrapped points, against a scan that wraps
//! every point into the period box first ([`Torus::wrap`]) and then takes the minimum image of
//! each offset. Coordinates run from inside the box through a few periods out, 1e12 and 1e15
//! (where the rounded difference of two coordinates is off by a sizeable part of a period), up
//! to 1e300 and `f64::MAX` and `f64::MIN` (whose difference overflows), on periods of several
//! sizes and boxes with a nonzero lower corner. Both sides round, so distances are compared
//! within a few roundings of the period box's bounds; inside the period box the metric is the
//! plain minimum image of the rounded difference, bit for bit.

use crate::common::rng;
use core::ops::ControlFlow;
use orthtree::prelude::*;
use orthtree::query::{AxisMetric, Boundary, Metric, MinImage, OutsidePoints, Torus};
use orthtree::query::{Manhattan, SquaredEuclidean};
use orthtree::{CompressedTree, PointTree};
use rand::rngs::SmallRng;
use rand::Rng;

/// The period boxes: unit, a lower corner below 0, one far from 0 (whose wrap rounds), a small
/// one, and a large one; each axis wraps or not as the case says.
fn tori() -> Vec<Torus<3>> {
    vec![
        Torus::wrapping([0.0; 3], [1.0; 3]).unwrap(),
        Torus::new(
            [-2.5, 1e6, 0.1],
            [0.7, 1e6 + 0.75, 0.35],
            [true, true, true],
        )
        .unwrap(),
        Torus::new([-2.5, -1.0, 0.1], [0.7, 1.0, 0.35], [true, false, true]).unwrap(),
        Torus::new([1e-3, 0.0, -7.0], [3e-3, 1.0, 1e9], [true, false, true]).unwrap(),
        Torus::new([0.0, 3.0, 0.0], [1.0, 4.5, 1.0], [false, true, false]).unwrap(),
    ]
}

/// A coordinate along `axis` of `torus`: inside the box, a few periods out, a whole number of
/// periods out, far out (up to 1e300), the extremes of `f64` and numbers near `2^53`; on an
/// ordinary axis, one of `[-5, 5]`.
fn coordinate(r: &mut SmallRng, torus: &Torus<3>, axis: usize) -> f64 {
    if !torus.wraps()[axis] {
        return r.gen_range(-5.0..5.0);
    }
    let (lo, hi, l) = (torus.lo()[axis], torus.hi()[axis], torus.period(axis));
    let sign = if r.gen_bool(0.5) { 1.0 } else { -1.0 };
    match r.gen_range(0..10) {
        0..=2 => lo + r.r#gen::<f64>() * l,
        3 => lo + r.gen_range(-40.0..40.0) * l,
        4 => lo + f64::from(r.gen_range(-1_000_000..1_000_000)) * l + r.r#gen::<f64>() * l,
        5 => sign * r.gen_range(1.0..10.0) * 10f64.powi(r.gen_range(3..300)),
        6 => sign * r.r#gen::<f64>() * f64::MAX,
        7 => [
            f64::MAX,
            f64::MIN,
            9007199254740992.0,
            -9007199254740994.0,
            1e15 + 0.3,
            -1e12 - 0.7,
        ][r.gen_range(0..6)],
        8 => [lo, hi, hi + l, lo - l][r.gen_range(0..4)],
        _ => sign * r.gen_range(1.0..2.0) * 2f64.powi(r.gen_range(-30..1023)),
    }
}

fn point(r: &mut SmallRng, torus: &Torus<3>) -> [f64; 3] {
    [0, 1, 2].map(|a| coordinate(r, torus, a))
}

/// The minimum-image offsets of `a` and `b` wrapped into the period box first (`Torus::wrap`),
/// per axis.
fn wrapped_offsets(torus: &Torus<3>, a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    let (wa, wb) = (torus.wrap(a).unwrap(), torus.wrap(b).unwrap());
    core::array::from_fn(|i| {
        let d = (wa[i] - wb[i]).abs();
        if torus.wraps()[i] {
            let l = torus.period(i);
            d.min(l - d)
        } else {
            d
        }
    })
}

/// The scan's distance: the wrapped offsets combined as `M` combines them.
fn brute<M: AxisMetric>(torus: &Torus<3>, a: &[f64; 3], b: &[f64; 3]) -> f64 {
    wrapped_offsets(torus, a, b)
        .iter()
        .fold(0.0, |s, &d| M::combine(s, d))
}

/// A few roundings of the period box's bounds per wrapping axis: how far apart the scan's
/// offsets (its wraps round at the box's corner) and the metric's may lie.
fn axis_slack(torus: &Torus<3>) -> [f64; 3] {
    core::array::from_fn(|i| {
        if torus.wraps()[i] {
            8.0 * f64::EPSILON * (torus.lo()[i].abs() + torus.hi()[i].abs() + torus.period(i))
        } else {
            0.0
        }
    })
}

/// The slack of squared distances of at most `want`.
fn squared_slack(torus: &Torus<3>, want: f64) -> f64 {
    let s = axis_slack(torus);
    (0..3)
        .map(|i| {
            let half = if torus.wraps()[i] {
                torus.period(i) / 2.0
            } else {
                10.0
            };
            2.0 * (half + s[i]) * s[i] + s[i] * s[i]
        })
        .sum::<f64>()
        + 4.0 * f64::EPSILON * want
}

/// The metric's distance, against the scan, for `M`.
fn check_metric<M: AxisMetric + Copy>(
    torus: &Torus<3>,
    metric: MinImage<M, 3>,
    a: &[f64; 3],
    b: &[f64; 3],
    slack: f64,
) where
    MinImage<M, 3>: Metric<3>,
{
    let (got, want) = (metric.distance(a, b), brute::<M>(torus, a, b));
    assert!(
        (got - want).abs() <= slack,
        "{a:?} to {b:?} on {torus:?}: {got:e} against {want:e}"
    );
    assert_eq!(got.to_bits(), metric.distance(b, a).to_bits(), "symmetric");
}

#[test]
fn the_metrics_are_minimum_images_for_any_finite_coordinates() {
    // the cases that were wrong: a point 2^53 out, and the extremes of f64
    let t1 = Torus::<1>::wrapping([0.0], [1.0]).unwrap();
    let m = t1.squared_euclidean();
    assert_eq!(m.distance(&[9007199254740992.0], &[0.3]), 0.3 * 0.3);
    assert_eq!(m.distance(&[f64::MAX], &[f64::MIN]), 0.0);
    assert_eq!(m.distance(&[1e15 + 0.25], &[0.0]), 0.25 * 0.25);
    assert_eq!(t1.chebyshev().distance(&[-1e300], &[0.5]), 0.5);
    let far = PointTree::new(&[([0.3], 0), ([0.0], 1)]).unwrap();
    let near = far.periodic_k_nearest(&t1, &[2f64.powi(53)], 2).unwrap();
    assert_eq!((*near[0].item, near[0].distance), (1, 0.0));
    assert_eq!((*near[1].item, near[1].distance), (0, 0.3 * 0.3));
    for torus in tori() {
        let slack = axis_slack(&torus);
        let (sum, max) = (
            slack.iter().sum::<f64>(),
            slack.iter().fold(0.0f64, |m, &s| m.max(s)),
        );
        let mut r = rng(11);
        for _ in 0..4000 {
            let (a, b) = (point(&mut r, &torus), point(&mut r, &torus));
            let want = brute::<SquaredEuclidean>(&torus, &a, &b);
            check_metric(
                &torus,
                torus.squared_euclidean(),
                &a,
                &b,
                squared_slack(&torus, want),
            );
            let want = brute::<Manhattan>(&torus, &a, &b);
            check_metric(
                &torus,
                torus.manhattan(),
                &a,
                &b,
                sum + 4.0 * f64::EPSILON * want,
            );
            check_metric(&torus, torus.chebyshev(), &a, &b, max);
            // inside the period box: the minimum image of the rounded difference, bit for bit
            let (wa, wb) = (torus.wrap(&a).unwrap(), torus.wrap(&b).unwrap());
            let plain = (0..3).fold(0.0, |s, i| {
                let d = (wa[i] - wb[i]).abs();
                let l = torus.period(i);
                let d = if !torus.wraps()[i] {
                    d
                } else if d >= l {
                    d % l
                } else {
                    d
                };
                let d = if torus.wraps()[i] { d.min(l - d) } else { d };
                s + d * d
            });
            assert_eq!(
                torus.squared_euclidean().distance(&wa, &wb).to_bits(),
                plain.to_bits()
            );
        }
    }
}

/// Every point set here stores the input position of each point as its item.
trait Set: PointSet<3, Scalar = f64, Item = usize> + Sync {}
impl<P: PointSet<3, Scalar = f64, Item = usize> + Sync> Set for P {}

/// The k-nearest answers of `t` (over `pts`) to `q`: the scan's distances in order within the
/// slack, each neighbour at its own distance, each point once.
fn check_knn(t: &impl Set, torus: &Torus<3>, pts: &[[f64; 3]], q: &[f64; 3]) {
    let mut all: Vec<f64> = pts
        .iter()
        .map(|p| brute::<SquaredEuclidean>(torus, q, p))
        .collect();
    all.sort_by(f64::total_cmp);
    for k in [1, 4, pts.len() + 1] {
        let got = t.periodic_k_nearest(torus, q, k).unwrap();
        assert_eq!(got.len(), k.min(pts.len()));
        let mut seen: Vec<usize> = got.iter().map(|n| *n.item).collect();
        seen.sort_unstable();
        seen.dedup();
        assert_eq!(seen.len(), got.len(), "a point reported twice");
        for (n, want) in got.iter().zip(&all) {
            let slack = squared_slack(torus, *want);
            assert!(
                (n.distance - want).abs() <= slack,
                "{q:?} on {torus:?}, k = {k}: {} against {want}",
                n.distance
            );
            let own = brute::<SquaredEuclidean>(torus, q, &pts[*n.item]);
            assert!((n.distance - own).abs() <= slack);
        }
    }
}

/// The points of `t` in the periodic ball: every point well inside, none well outside.
fn check_ball(t: &impl Set, torus: &Torus<3>, pts: &[[f64; 3]], q: &[f64; 3], radius: f64) {
    let r2 = radius * radius;
    let slack = squared_slack(torus, r2);
    let got: Vec<usize> = t
        .periodic_in_ball(torus, q, radius)
        .unwrap()
        .map(|(_, &i)| i)
        .collect();
    for (i, p) in pts.iter().enumerate() {
        let d = brute::<SquaredEuclidean>(torus, q, p);
        if d <= r2 - slack {
            assert!(got.contains(&i), "{p:?} at {d} is within {radius} of {q:?}");
        }
        if d > r2 + slack {
            assert!(
                !got.contains(&i),
                "{p:?} at {d} is beyond {radius} of {q:?}"
            );
        }
    }
}

/// The pairs of `t` within `radius` and its k-nearest self-join against the scan.
fn check_joins(t: &impl Set, torus: &Torus<3>, pts: &[[f64; 3]], radius: f64) {
    let r2 = radius * radius;
    let slack = squared_slack(torus, r2);
    let mut got = Vec::new();
    let _ = t.periodic_pairs_within(torus, radius, Boundary::Inclusive, |s, u, d| {
        let (i, j) = (t.items()[s], t.items()[u]);
        got.push((i.min(j), i.max(j), d));
        ControlFlow::<()>::Continue(())
    });
    for &(i, j, d) in &got {
        let want = brute::<SquaredEuclidean>(torus, &pts[i], &pts[j]);
        assert!((d - want).abs() <= squared_slack(torus, want));
        assert!(
            want <= r2 + slack,
            "{:?} and {:?} at {want} beyond {radius}",
            pts[i],
            pts[j]
        );
    }
    for i in 0..pts.len() {
        for j in i + 1..pts.len() {
            if brute::<SquaredEuclidean>(torus, &pts[i], &pts[j]) <= r2 - slack {
                assert!(
                    got.iter().any(|&(a, b, _)| (a, b) == (i, j)),
                    "{i}, {j} missed"
                );
            }
        }
    }
    let k = 3;
    let table = t.periodic_k_nearest_self(torus, k);
    for s in 0..t.len() {
        let i = t.items()[s];
        let mut all: Vec<f64> = (0..pts.len())
            .filter(|&j| j != i)
            .map(|j| brute::<SquaredEuclidean>(torus, &pts[i], &pts[j]))
            .collect();
        all.sort_by(f64::total_cmp);
        let (_, distances) = table.row(s);
        assert_eq!(distances.len(), k.min(pts.len() - 1));
        for (got, want) in distances.iter().zip(&all) {
            assert!(
                (got - want).abs() <= squared_slack(torus, *want),
                "{got} against {want}"
            );
        }
    }
}

#[test]
fn periodic_queries_on_far_points_match_the_wrapped_scan() {
    for (c, torus) in tori().iter().enumerate() {
        for seed in 0..12u64 {
            let mut r = rng(100 * c as u64 + seed);
            let n = r.gen_range(1..50);
            let raw: Vec<[f64; 3]> = (0..n).map(|_| point(&mut r, torus)).collect();
            let wrapped = torus.prepare(&raw, OutsidePoints::Wrap).unwrap();
            let queries: Vec<[f64; 3]> = (0..6).map(|_| point(&mut r, torus)).collect();
            // the same distances from the unwrapped points and from their wrapped copies
            for pts in [&raw, &wrapped] {
                let e: Vec<([f64; 3], usize)> = pts.iter().copied().zip(0..).collect();
                let plain = PointTree::new(&e).unwrap();
                let compressed = CompressedTree::new(&e).unwrap();
                let scale = (0..3)
                    .filter(|&a| torus.wraps()[a])
                    .map(|a| torus.period(a))
                    .fold(0.0f64, f64::max);
                let radius = scale * r.gen_range(0.05..0.6);
                for q in &queries {
                    check_knn(&plain, torus, pts, q);
                    check_knn(&compressed, torus, pts, q);
                    check_ball(&plain, torus, pts, q, radius);
                    check_ball(&compressed, torus, pts, q, radius);
                }
                check_joins(&plain, torus, pts, radius);
                check_joins(&compressed, torus, pts, radius);
            }
        }
    }
}
