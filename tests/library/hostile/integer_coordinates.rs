//! 64-bit integer coordinates: every tree refuses an integer `f64` cannot hold exactly (at build,
//! insert, extend, every query's point, box and centre, and the root box), naming the point and
//! axis; every accepted integer is compared exactly. Random points near 2^53, 2^63, `i64::MIN`
//! and `u64::MAX` (with duplicates and points on split lines) against brute force for box, ball,
//! nearest and k-nearest queries on `PointTree`, `DynamicPointTree`, `CompressedTree` and
//! `SkipQuadtree`.

use crate::common;

use orthtree::prelude::*;
use orthtree::query::{Ball, QueryError, Region};
use orthtree::{
    geom::AabbError, points::PointTreeBuilder, Aabb, CompressedTree, DynamicPointTree, Error,
    PointTree, Scalar, SkipQuadtree,
};
use proptest::prelude::*;

const P53: i64 = 1 << 53;

/// The smallest pair a conversion to f64 confuses: (2^53, 0) and (2^53 + 1, 0). The second has no f64: every tree refuses it,
/// naming point 1 and axis 0, at build, and at insert when built from the first alone.
#[test]
fn odd_integers_beyond_2_pow_53_are_refused_by_every_tree() {
    let e = [([P53, 0i64], 'a'), ([P53 + 1, 0], 'b')];
    let want = Error::InexactCoordinate {
        index: 1,
        axis: 0,
        value: (P53 + 1) as i128,
    };
    assert_eq!(PointTree::new(&e).unwrap_err(), want);
    assert_eq!(DynamicPointTree::new(&e).unwrap_err(), want);
    assert_eq!(CompressedTree::new(&e).unwrap_err(), want);
    assert_eq!(SkipQuadtree::new(&e).unwrap_err(), want);
    assert_eq!(
        PointTreeBuilder::new()
            .bucket_size(1)
            .build(&e)
            .unwrap_err(),
        want
    );
    let msg = want.to_string();
    assert!(
        msg.contains("point 1") && msg.contains("9007199254740993 on axis 0"),
        "{msg}"
    );

    let first = &e[..1];
    let mut p = PointTree::new(first).unwrap();
    assert_eq!(p.insert(e[1].0, 'b').unwrap_err().error, want);
    assert_eq!(p.extend_from_vec(vec![e[1]]).unwrap_err(), want);
    let mut d = DynamicPointTree::new(first).unwrap();
    assert_eq!(d.insert(e[1].0, 'b').unwrap_err().error, want);
    let mut c = CompressedTree::new(first).unwrap();
    assert_eq!(c.insert(e[1].0, 'b').unwrap_err().error, want);
    let mut s = SkipQuadtree::new(first).unwrap();
    assert_eq!(s.insert(e[1].0, 'b').unwrap_err().error, want);
    // nothing was added, and removing the inexact point never takes its neighbour
    assert!(!p.remove(&e[1].0, &'a') && p.remove_point(&e[1].0).is_none());
    assert!(!d.remove(&e[1].0, &'a') && d.remove_point(&e[1].0).is_none());
    assert!(!c.remove(&e[1].0, &'a') && c.remove_point(&e[1].0).is_none());
    assert!(!s.remove(&e[1].0, &'a') && s.remove_point(&e[1].0).is_none());
    assert_eq!((p.len(), d.len(), c.len(), s.len()), (1, 1, 1, 1));

    // the same near u64::MAX, on the second axis of the third point
    let u = [
        ([0u64, u64::MAX - 2047], 0),
        ([1, 2], 1),
        ([5, u64::MAX], 2),
    ];
    let want = Error::InexactCoordinate {
        index: 2,
        axis: 1,
        value: u64::MAX as i128,
    };
    assert_eq!(PointTree::new(&u).unwrap_err(), want);
    assert_eq!(DynamicPointTree::new(&u).unwrap_err(), want);
    assert_eq!(CompressedTree::new(&u).unwrap_err(), want);
    assert_eq!(SkipQuadtree::new(&u).unwrap_err(), want);
}

/// A root box with a corner `f64` cannot hold is refused, naming the axis and value.
#[test]
fn inexact_root_boxes_are_refused() {
    let e = [([0i64, 0], ())];
    for (min, max, axis, value) in [
        ([0, 0], [P53 + 1, P53], 0, P53 + 1),
        ([0, -P53 - 1], [P53, P53], 1, -P53 - 1),
        ([0, 0], [i64::MAX, 4], 0, i64::MAX),
    ] {
        let root = Aabb::new(min, max).unwrap();
        let want = Error::InvalidRootBox(AabbError::Inexact {
            axis,
            value: value as i128,
        });
        let err = PointTreeBuilder::new()
            .root_box(root)
            .build(&e)
            .unwrap_err();
        assert_eq!(err, want);
        assert!(err.to_string().contains(&value.to_string()));
        let err = CompressedTree::builder()
            .root_box(root)
            .build(&e)
            .unwrap_err();
        assert_eq!(err, want);
    }
    // exact corners beyond 2^53 are fine
    let root = Aabb::new([0, 0], [P53 + 2, i64::MAX - 1023]).unwrap();
    let t = PointTreeBuilder::new().root_box(root).build(&e).unwrap();
    assert_eq!(t.domain().max, [(P53 + 2) as f64, (i64::MAX - 1023) as f64]);
}

/// Every query of every tree refuses a point, box corner or ball centre `f64` cannot hold,
/// naming the axis and the value; the same queries at the exact neighbours answer exactly.
#[test]
fn queries_refuse_inexact_parameters_and_answer_exactly_beside_them() {
    // (2^53, 0) and (2^53 + 2, 0): both exact, 2 apart
    let e = [([P53, 0i64], 0usize), ([P53 + 2, 0], 1)];
    let bad = [P53 + 1, 0];
    let inexact = |axis| QueryError::Inexact {
        axis,
        value: (P53 + 1) as i128,
    };
    let only_first = Aabb::new([P53 - 4, -1], [P53, 1]).unwrap();
    let bad_box = Aabb::new([P53 - 4, -1], [P53 + 1, 1]).unwrap();
    let bad_min = Aabb::new([0, P53 + 1], [P53, P53 + 2]).unwrap();
    macro_rules! check {
        ($t:expr) => {{
            let t = $t;
            let found: Vec<usize> = t.in_box(&only_first).unwrap().map(|(_, &i)| i).collect();
            assert_eq!(found, [0], "the box up to 2^53 holds only the first point");
            assert_eq!(t.in_box(&bad_box).err(), Some(inexact(0)));
            assert_eq!(t.in_box(&bad_min).err(), Some(inexact(1)));
            let n = t.nearest(&[P53 + 2, 0]).unwrap().unwrap();
            assert_eq!((*n.item, n.distance), (1, 0.0));
            let n = t.nearest(&[P53 + 4, 0]).unwrap().unwrap();
            assert_eq!((*n.item, n.distance), (1, 4.0));
            let n = t.nearest(&[P53 - 2, 3]).unwrap().unwrap();
            assert_eq!((*n.item, n.distance), (0, 13.0));
            let k: Vec<(usize, f64)> = t
                .k_nearest(&[P53 + 8, 0], 2)
                .unwrap()
                .iter()
                .map(|n| (*n.item, n.distance))
                .collect();
            assert_eq!(k, [(1, 36.0), (0, 64.0)]);
            let ball: Vec<usize> = t
                .in_ball(&[P53 + 2, 0], 1.5)
                .unwrap()
                .map(|(_, &i)| i)
                .collect();
            assert_eq!(ball, [1]);
            assert_eq!(t.nearest(&bad).err(), Some(inexact(0)));
            assert_eq!(t.nearest_within(&bad, 1.0).err(), Some(inexact(0)));
            assert_eq!(t.k_nearest(&bad, 2).err(), Some(inexact(0)));
            assert_eq!(t.k_nearest_within(&bad, 2, 9.0).err(), Some(inexact(0)));
            assert_eq!(t.nearest_iter(&bad).err().unwrap(), inexact(0));
            assert_eq!(t.in_ball(&[0, P53 + 1], 1.0).err(), Some(inexact(1)));
            let msg = inexact(0).to_string();
            assert!(msg.contains("9007199254740993 on axis 0"), "{msg}");
        }};
    }
    check!(PointTree::new(&e).unwrap());
    check!(PointTreeBuilder::new().bucket_size(1).build(&e).unwrap());
    check!(DynamicPointTree::new(&e).unwrap());
    check!(CompressedTree::new(&e).unwrap());
    let s = SkipQuadtree::new(&e).unwrap();
    check!(s.base());
    let (n, _) = s.approx_nearest(&[P53 + 2, 0], 0.0).unwrap();
    assert_eq!(*n.unwrap().item, 1);
    assert_eq!(s.approx_nearest(&bad, 0.0).unwrap_err(), inexact(0));
    let q = QueryError::Inexact {
        axis: 0,
        value: (P53 + 1) as i128,
    };
    assert_eq!(PointTree::new(&e).unwrap().locate(&bad).unwrap_err(), q);
    assert_eq!(
        CompressedTree::new(&e).unwrap().locate(&bad).unwrap_err(),
        q
    );
    assert_eq!(s.locate(&bad).unwrap_err(), q);

    // u64 near u64::MAX: the exact values there are 2048 apart
    let top = u64::MAX - 2047;
    let e = [([top, 7u64], 0usize), ([top - 2048, 7], 1)];
    let t = PointTree::new(&e).unwrap();
    let b = Aabb::new([top, 0], [top, 7]).unwrap();
    assert_eq!(
        t.in_box(&b).unwrap().map(|(_, &i)| i).collect::<Vec<_>>(),
        [0]
    );
    let n = t.nearest(&[top - 2048, 7]).unwrap().unwrap();
    assert_eq!((*n.item, n.distance), (1, 0.0));
    assert_eq!(
        t.nearest(&[u64::MAX, 7]).err(),
        Some(QueryError::Inexact {
            axis: 0,
            value: u64::MAX as i128
        })
    );
}

/// The exact squared distance of two integer points.
fn dist2(a: &[i128; 2], b: &[i128; 2]) -> u128 {
    (0..2).map(|i| ((a[i] - b[i]).unsigned_abs()).pow(2)).sum()
}

/// Every query of `$t` (items: input indices) against brute force on the exact integers `pts`,
/// for the query points `qs` (exact integers) and boxes between pairs of them. The points lie on
/// a grid `base + j * step` with `j <= 16` and `step` a power of two at least the f64 spacing
/// there (so that points repeat and sit on the split lines), where differences, squares and
/// their sums are exact in f64 too: every distance is checked exactly.
macro_rules! against_brute_force {
    ($t:expr, $pts:expr, $qs:expr, $conv:expr) => {{
        let (t, pts, qs) = (&$t, &$pts, &$qs);
        let conv = $conv;
        for q in qs.iter() {
            // nearest and k-nearest: the exact distances (the grid's are exact in f64)
            let mut want: Vec<u128> = pts.iter().map(|p| dist2(p, q)).collect();
            want.sort();
            let n = t.nearest(&conv(q)).unwrap().unwrap();
            assert_eq!(n.distance as u128, want[0]);
            assert_eq!(dist2(&pts[*n.item], q), want[0]);
            let k = t.k_nearest(&conv(q), 5).unwrap();
            let got: Vec<u128> = k.iter().map(|n| n.distance as u128).collect();
            assert_eq!(got, want[..want.len().min(5)]);
            for n in &k {
                assert_eq!(dist2(&pts[*n.item], q), n.distance as u128);
            }
            // ball: the f64 definition (exact here), and its integer meaning
            let r2 = want[want.len() / 2];
            let r = (r2 as f64).sqrt();
            let ball = Ball::new(conv(q).map(Scalar::to_f64), r).unwrap();
            let mut got: Vec<usize> = t.in_ball(&conv(q), r).unwrap().map(|(_, &i)| i).collect();
            got.sort();
            let brute: Vec<usize> = (0..pts.len())
                .filter(|&i| ball.contains(&conv(&pts[i]).map(Scalar::to_f64)))
                .collect();
            assert_eq!(got, brute);
            assert!(got.iter().all(|&i| (dist2(&pts[i], q) as f64) <= r * r));
            // boxes from q to every other query point: exact integer comparisons
            for o in qs.iter() {
                let (lo, hi) = (
                    [q[0].min(o[0]), q[1].min(o[1])],
                    [q[0].max(o[0]), q[1].max(o[1])],
                );
                let b = Aabb::new(conv(&lo), conv(&hi)).unwrap();
                let mut got: Vec<usize> = t.in_box(&b).unwrap().map(|(_, &i)| i).collect();
                got.sort();
                let brute: Vec<usize> = (0..pts.len())
                    .filter(|&i| (0..2).all(|a| lo[a] <= pts[i][a] && pts[i][a] <= hi[a]))
                    .collect();
                assert_eq!(got, brute);
            }
        }
    }};
}

/// Builds every tree over `pts` (converted by `conv`) and checks it against brute force.
macro_rules! every_tree {
    ($pts:expr, $qs:expr, $conv:expr) => {{
        let (pts, qs) = (&$pts, &$qs);
        let entries: Vec<_> = pts.iter().enumerate().map(|(i, p)| ($conv(p), i)).collect();
        let p = PointTreeBuilder::new()
            .bucket_size(1)
            .build(&entries)
            .unwrap();
        p.validate().unwrap();
        against_brute_force!(p, pts, qs, $conv);
        against_brute_force!(PointTree::new(&entries).unwrap(), pts, qs, $conv);
        let d = DynamicPointTree::new(&entries).unwrap();
        d.validate().unwrap();
        against_brute_force!(d, pts, qs, $conv);
        let c = CompressedTree::new(&entries).unwrap();
        c.validate().unwrap();
        against_brute_force!(c, pts, qs, $conv);
        let s = SkipQuadtree::new(&entries).unwrap();
        for q in qs.iter() {
            let (n, _) = s.approx_nearest(&$conv(q), 0.0).unwrap();
            let best = pts.iter().map(|p| dist2(p, q)).min().unwrap();
            assert_eq!(n.unwrap().distance as u128, best);
        }
    }};
}

fn as_i64(p: &[i128; 2]) -> [i64; 2] {
    p.map(|x| i64::try_from(x).unwrap())
}

fn as_u64(p: &[i128; 2]) -> [u64; 2] {
    p.map(|x| u64::try_from(x).unwrap())
}

proptest! {
    #![proptest_config(common::points::config(48, 19))]

    /// Around 2^53 (spacing 1 below, 2 above), 2^62..2^63 (spacing 1024) and i64::MIN.
    #[test]
    fn i64_near_the_f64_limits(
        which in 0usize..4,
        shift in 0u32..6,
        pts in prop::collection::vec([0i128..=16, 0i128..=16], 1..60),
        qs in prop::collection::vec([0i128..=16, 0i128..=16], 1..6),
    ) {
        let (base, step) = match which {
            0 => (i128::from(P53) - 8 * 2, 2i128 << shift),
            1 => (i128::from(i64::MAX) + 1 - 1024 - 16 * (1024 << shift), 1024i128 << shift),
            2 => (i128::from(i64::MIN), 1024i128 << shift),
            _ => (-i128::from(P53) - 8 * 2, 2i128 << shift),
        };
        let at = |v: &Vec<[i128; 2]>| -> Vec<[i128; 2]> {
            v.iter().map(|[a, b]| [base + a * step, base + b * step]).collect()
        };
        let (pts, qs) = (at(&pts), at(&qs));
        every_tree!(pts, qs, as_i64);
    }

    /// Near u64::MAX (spacing 2048) and 2^53 in u64.
    #[test]
    fn u64_near_the_f64_limits(
        near_max in any::<bool>(),
        shift in 0u32..6,
        pts in prop::collection::vec([0i128..=16, 0i128..=16], 1..60),
        qs in prop::collection::vec([0i128..=16, 0i128..=16], 1..6),
    ) {
        let (base, step) = if near_max {
            let step = 2048i128 << shift;
            (i128::from(u64::MAX) + 1 - 2048 - 16 * step, step)
        } else {
            (i128::from(P53) - 16, 2i128 << shift)
        };
        let at = |v: &Vec<[i128; 2]>| -> Vec<[i128; 2]> {
            v.iter().map(|[a, b]| [base + a * step, base + b * step]).collect()
        };
        let (pts, qs) = (at(&pts), at(&qs));
        every_tree!(pts, qs, as_u64);
    }

    /// Random 64-bit integers, inexact ones refused naming the first bad point and axis, the
    /// exact ones (the same values rounded to their f64) stored and found exactly.
    #[test]
    fn random_integers_are_refused_or_exact(raw in prop::collection::vec(any::<[i64; 2]>(), 1..40)) {
        let entries: Vec<([i64; 2], usize)> = raw.iter().copied().zip(0..).collect();
        let first_bad = raw.iter().enumerate().find_map(|(i, p)| {
            (0..2).find(|&a| !p[a].converts_exactly()).map(|a| (i, a))
        });
        match (PointTree::new(&entries), first_bad) {
            (Ok(_), None) => {}
            (Err(Error::InexactCoordinate { index, axis, value }), Some((i, a))) => {
                prop_assert_eq!((index, axis, value), (i, a, i128::from(raw[i][a])));
            }
            (other, want) => prop_assert!(false, "{:?} for {:?}", other.err(), want),
        }
        // rounded to exact values (clamped below 2^63)
        let exact: Vec<[i64; 2]> = raw
            .iter()
            .map(|p| p.map(|x| ((x as f64) as i128).min(i128::from(i64::MAX) - 1023) as i64))
            .collect();
        let entries: Vec<([i64; 2], usize)> = exact.iter().copied().zip(0..).collect();
        let t = PointTree::new(&entries).unwrap();
        for p in &exact {
            let b = Aabb::new(*p, *p).unwrap();
            let mut got: Vec<usize> = t.in_box(&b).unwrap().map(|(_, &j)| j).collect();
            got.sort();
            let want: Vec<usize> = (0..exact.len()).filter(|&j| exact[j] == *p).collect();
            prop_assert_eq!(got, want);
            let n = t.nearest(p).unwrap().unwrap();
            prop_assert_eq!((n.point, n.distance), (p, 0.0));
        }
    }
}
