//! `query_until`, the streaming region query with early stop, on every point tree: the points
//! it visits before a break at visit `m` are exactly the first `m` of `query_with`'s order (and
//! it stops after exactly `m` visits, returning the break's value), the full visit is the
//! brute-force answer, each point once; balls (radius results), boxes and half-spaces over grid
//! points (split lines, faces, duplicates) and spread points; a bad region calls nothing.

use core::ops::ControlFlow;
use orthtree::prelude::*;
use orthtree::query::{Ball, HalfSpace, QueryError, Region};
use orthtree::{Aabb, CompressedTree, DynamicPointTree, PointTree, SkipQuadtree};
use proptest::prelude::*;

/// `query_until` on `t` over `region` against `query_with`'s order and brute force `pts`.
fn check<P, R, const D: usize>(t: &P, pts: &[[f64; D]], region: R)
where
    P: PointSet<D, Scalar = f64, Item = usize>,
    R: Region<D> + Copy,
{
    t.validate().unwrap();
    let mut order = Vec::new();
    t.query_with(region, |p, &i| {
        assert_eq!(*p, pts[i]);
        order.push(i);
    })
    .unwrap();
    let want: Vec<usize> = (0..pts.len())
        .filter(|&i| region.contains(&pts[i]))
        .collect();
    let mut sorted = order.clone();
    sorted.sort_unstable();
    assert_eq!(sorted, want, "the full visit is the brute-force answer");
    // never breaking: every point, in the same order, and None
    let mut all = Vec::new();
    let flow = t.query_until(region, |_, &i| {
        all.push(i);
        ControlFlow::<()>::Continue(())
    });
    assert_eq!((flow, &all), (Ok(None), &order));
    // breaking at visit m: exactly m visits, the prefix, the m-th's value returned
    let stops: Vec<usize> = if order.len() <= 40 {
        (1..=order.len()).collect()
    } else {
        vec![1, 2, order.len() / 2, order.len() - 1, order.len()]
    };
    for m in stops {
        let mut seen = Vec::new();
        let flow = t.query_until(region, |p, &i| {
            assert_eq!(*p, pts[i]);
            seen.push(i);
            if seen.len() == m {
                ControlFlow::Break((i, seen.len()))
            } else {
                ControlFlow::Continue(())
            }
        });
        assert_eq!(flow, Ok(Some((order[m - 1], m))), "stops at visit {m}");
        assert_eq!(seen, order[..m], "a prefix of the full query");
    }
}

/// [`check`] on every point tree built from `pts` (item: input position).
fn all_trees<R: Region<D> + Copy, const D: usize>(pts: &[[f64; D]], region: R) {
    let entries: Vec<([f64; D], usize)> = pts.iter().enumerate().map(|(i, p)| (*p, i)).collect();
    let plain = PointTree::builder().bucket_size(3).build(&entries).unwrap();
    check(&plain, pts, region);
    check(&DynamicPointTree::from(plain), pts, region);
    let compressed = CompressedTree::new(&entries).unwrap();
    check(&compressed, pts, region);
    check(&SkipQuadtree::with_seed(compressed, 9), pts, region);
}

fn grid_point() -> impl Strategy<Value = [f64; 2]> {
    proptest::array::uniform2((0u8..=8).prop_map(|j| f64::from(j) / 4.0))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn query_until_is_a_prefix_of_the_full_query_on_grid_points(
        pts in prop::collection::vec(grid_point(), 0..200),
        c in grid_point(),
        r in prop_oneof![Just(0.0), Just(0.25), Just(0.5), Just(1.0), Just(10.0), 0.0f64..2.0],
        corner in grid_point(),
        offset in -1.0f64..3.0,
    ) {
        all_trees(&pts, Ball::new(c, r).unwrap());
        let (lo, hi) = ([c[0].min(corner[0]), c[1].min(corner[1])], [c[0].max(corner[0]), c[1].max(corner[1])]);
        all_trees(&pts, Aabb::new(lo, hi).unwrap());
        all_trees(&pts, HalfSpace::new([1.0, -0.5], offset).unwrap());
    }

    #[test]
    fn query_until_is_a_prefix_of_the_full_query_3d(
        pts in prop::collection::vec(proptest::array::uniform3(-1.0f64..1.0), 0..300),
        c in proptest::array::uniform3(-1.0f64..1.0),
        r in 0.0f64..1.5,
    ) {
        all_trees(&pts, Ball::new(c, r).unwrap());
    }
}

#[test]
fn a_bad_region_calls_nothing() {
    let t = PointTree::new(&[([0.0, 0.0], 0usize), ([1.0, 1.0], 1)]).unwrap();
    let never = |_: &[f64; 2], _: &usize| -> ControlFlow<()> { panic!("not called") };
    let nan_box = Aabb {
        min: [f64::NAN, 0.0],
        max: [1.0, 1.0],
    };
    assert_eq!(
        t.query_until(nan_box, never),
        Err(QueryError::NanBound { axis: 0 })
    );
    let none: Vec<([f64; 2], usize)> = Vec::new();
    let empty = PointTree::new(&none).unwrap();
    let ball = Ball::new([0.0, 0.0], 1.0).unwrap();
    assert_eq!(empty.query_until(ball, never), Ok(None));
}
