//! The point trees in every dimension the crate supports, D = 1 to 8, on small random point sets
//! (uniform, clustered, with duplicates): [`PointTree`] (build against the chapter's definition,
//! balance with every option, locate, insert and remove), [`DynamicPointTree`],
//! [`CompressedTree`] and [`SkipQuadtree`], each validated after every update and queried (box,
//! ball, half-space, count, nearest, k nearest) against a scan of the points it holds.
//!
//! One generic check, instantiated for each D by `every_dimension!`.

use crate::common;

use common::points::check_all;
use common::{dist2, rng};
use core::ops::ControlFlow;
use orthtree::prelude::*;
use orthtree::{
    query::{Boundary, HalfSpace, Region},
    Aabb, Ball, Cell, CompressedTree, DynamicPointTree, PointTree, SkipQuadtree,
};
use rand::rngs::SmallRng;
use rand::Rng;

/// Random points in the unit cube: uniform ones, a tight cluster (so the trees get deep) and a
/// few exact duplicates. Items are the input positions.
fn sample_points<const D: usize>(rng: &mut SmallRng, n: usize) -> Vec<([f64; D], usize)> {
    let centre: [f64; D] = core::array::from_fn(|_| rng.gen_range(0.1..0.9));
    let mut pts: Vec<[f64; D]> = Vec::new();
    for i in 0..n {
        let p = match i % 4 {
            0 | 1 => core::array::from_fn(|_| rng.r#gen::<f64>()),
            2 => core::array::from_fn(|a| centre[a] + rng.gen_range(-1e-3..1e-3)),
            _ => pts[rng.gen_range(0..pts.len())],
        };
        pts.push(p);
    }
    pts.into_iter().enumerate().map(|(i, p)| (p, i)).collect()
}

/// The root box of every tree here, so that inserted points fall inside it.
fn unit_cube<const D: usize>() -> Aabb<f64, D> {
    Aabb::new([0.0; D], [1.0; D]).unwrap()
}

/// A compressed tree over `entries` with the unit cube as root box.
fn compressed<const D: usize>(entries: &[([f64; D], usize)]) -> CompressedTree<f64, usize, D> {
    CompressedTree::builder()
        .root_box(unit_cube())
        .build(entries)
        .unwrap()
}

/// A random closed box inside the unit cube.
fn sample_box<const D: usize>(rng: &mut SmallRng) -> Aabb<f64, D> {
    let (mut lo, mut hi) = ([0.0; D], [0.0; D]);
    for a in 0..D {
        let (x, y): (f64, f64) = (rng.r#gen(), rng.r#gen());
        (lo[a], hi[a]) = (x.min(y), x.max(y).max(x.min(y) + 0.3).min(1.0));
    }
    Aabb::new(lo, hi).unwrap()
}

/// The sorted items of `live` for which `keep` holds.
fn scan<const D: usize>(
    live: &[([f64; D], usize)],
    keep: impl Fn(&[f64; D]) -> bool,
) -> Vec<usize> {
    let mut v: Vec<usize> = live
        .iter()
        .filter(|(p, _)| keep(p))
        .map(|&(_, i)| i)
        .collect();
    v.sort_unstable();
    v
}

/// Every query of a point set against a scan of `live`, the (point, item) pairs it holds: one
/// generic function over the [`PointSet`] trait serves the three trees.
fn check_queries<P, const D: usize>(t: &P, live: &[([f64; D], usize)], rng: &mut SmallRng)
where
    P: PointSet<D, Scalar = f64, Item = usize>,
{
    for _ in 0..6 {
        let b = sample_box::<D>(rng);
        let mut got: Vec<usize> = t.query(&b).unwrap().map(|(_, &i)| i).collect();
        got.sort_unstable();
        let want = scan(live, |p| b.contains(p));
        assert_eq!(got, want, "D = {}, box {:?}", D, b);
        assert_eq!(t.query_count(b).unwrap(), want.len());
        let centre: [f64; D] = core::array::from_fn(|_| rng.r#gen());
        let radius = rng.gen_range(0.05..0.9);
        let ball = Ball::new(centre, radius).unwrap();
        let mut got: Vec<usize> = t
            .in_ball(&centre, radius)
            .unwrap()
            .map(|(_, &i)| i)
            .collect();
        got.sort_unstable();
        let want = scan(live, |p| dist2(p, &centre) <= radius * radius);
        assert_eq!(got, want, "D = {}, ball {:?}", D, ball);
        let normal: [f64; D] = core::array::from_fn(|_| rng.gen_range(-1.0..1.0));
        let h = HalfSpace::new(normal, rng.gen_range(-0.5..0.5)).unwrap();
        let mut got: Vec<usize> = t.query(&h).unwrap().map(|(_, &i)| i).collect();
        got.sort_unstable();
        let dot = |p: &[f64; D]| (0..D).map(|a| p[a] * normal[a]).sum::<f64>();
        let loose = scan(live, |p| dot(p) <= h.offset + 1e-12);
        let strict = scan(live, |p| dot(p) <= h.offset - 1e-12);
        assert!(got.iter().all(|i| loose.contains(i)) && strict.iter().all(|i| got.contains(i)));
        let mut dists: Vec<f64> = live.iter().map(|(p, _)| dist2(p, &centre)).collect();
        dists.sort_by(f64::total_cmp);
        let k = rng.gen_range(1..6);
        let near: Vec<f64> = t
            .k_nearest(&centre, k)
            .unwrap()
            .iter()
            .map(|n| n.distance)
            .collect();
        assert_eq!(
            near,
            dists[..k.min(dists.len())],
            "D = {}, {} nearest",
            D,
            k
        );
        let nearest = t.nearest(&centre).unwrap().map(|n| n.distance);
        assert_eq!(nearest, dists.first().copied());
    }
}

/// Removes the entry of item `item` from `live`.
fn forget<const D: usize>(live: &mut Vec<([f64; D], usize)>, item: usize) {
    let at = live.iter().position(|&(_, i)| i == item).unwrap();
    live.swap_remove(at);
}

/// Fresh points, with items numbered from `next`.
fn fresh<const D: usize>(rng: &mut SmallRng, next: usize, n: usize) -> Vec<([f64; D], usize)> {
    (0..n)
        .map(|i| (core::array::from_fn(|_| rng.r#gen::<f64>()), next + i))
        .collect()
}

fn check_point_tree<const D: usize>(rng: &mut SmallRng, entries: &[([f64; D], usize)]) {
    // Duplicates split down to the maximum depth; from 6-D on it is kept at 3 levels, as the
    // corner balance of a deeper 8-D chain has tens of thousands of leaves.
    let max_depth = if D >= 6 { 3 } else { Cell::<D>::MAX_LEVEL };
    let t = PointTree::builder()
        .root_box(unit_cube())
        .bucket_size(2)
        .max_depth(max_depth)
        .build(entries)
        .unwrap();
    check_all(&t, entries);
    let mut t = t;
    let mut live = entries.to_vec();
    check_queries(&t, &live, rng);
    for (p, i) in fresh::<D>(rng, entries.len(), 6) {
        t.insert(p, i).unwrap();
        live.push((p, i));
        t.validate().unwrap();
    }
    for _ in 0..6 {
        let (p, i) = live[rng.gen_range(0..live.len())];
        assert!(t.remove(&p, &i));
        forget(&mut live, i);
        t.validate().unwrap();
    }
    check_queries(&t, &live, rng);
    for (p, i) in &live {
        let leaf = t.locate(p).unwrap().inside().unwrap();
        assert!(t.tree().is_leaf(leaf) && t.node_items(leaf).contains(i));
    }
}

fn check_dynamic<const D: usize>(rng: &mut SmallRng, entries: &[([f64; D], usize)]) {
    let built = PointTree::builder()
        .root_box(unit_cube())
        .build(entries)
        .unwrap();
    let mut t = DynamicPointTree::from(built);
    t.validate().unwrap();
    t.tree().validate().unwrap();
    let mut live = entries.to_vec();
    check_queries(&t, &live, rng);
    for round in 0..2 {
        for (p, i) in fresh::<D>(rng, entries.len() + 10 * round, 8) {
            t.insert(p, i).unwrap();
            live.push((p, i));
            t.validate().unwrap();
        }
        for _ in 0..10 {
            let (p, i) = live[rng.gen_range(0..live.len())];
            assert!(t.remove(&p, &i));
            forget(&mut live, i);
            t.validate().unwrap();
            t.tree().validate().unwrap();
        }
        check_queries(&t, &live, rng);
    }
    assert_eq!(t.len(), live.len());
}

fn check_compressed<const D: usize>(rng: &mut SmallRng, entries: &[([f64; D], usize)]) {
    let mut t = compressed(entries);
    t.validate().unwrap();
    let mut live = entries.to_vec();
    check_queries(&t, &live, rng);
    for (p, i) in fresh::<D>(rng, entries.len(), 6) {
        t.insert(p, i).unwrap();
        live.push((p, i));
        t.validate().unwrap();
    }
    for _ in 0..8 {
        let (p, i) = live[rng.gen_range(0..live.len())];
        assert!(t.remove(&p, &i));
        forget(&mut live, i);
        t.validate().unwrap();
    }
    check_queries(&t, &live, rng);
    for (p, _) in &live {
        let at = t.locate(p).unwrap().inside().unwrap();
        assert!(at.leaf, "D = {D}: a stored point's finest cell is a leaf");
    }
}

fn check_skip<const D: usize>(rng: &mut SmallRng, entries: &[([f64; D], usize)]) {
    let mut t = SkipQuadtree::with_seed(compressed(entries), 7);
    t.validate().unwrap();
    let mut live = entries.to_vec();
    for (p, i) in fresh::<D>(rng, entries.len(), 6) {
        t.insert(p, i).unwrap();
        live.push((p, i));
        t.validate().unwrap();
    }
    for _ in 0..8 {
        let (p, _) = live[rng.gen_range(0..live.len())];
        let item = t.remove_point(&p).unwrap();
        assert_eq!(live.iter().find(|&&(_, i)| i == item).unwrap().0, p);
        forget(&mut live, item);
        t.validate().unwrap();
    }
    assert_eq!(t.len(), live.len());
    for _ in 0..8 {
        let q: [f64; D] = core::array::from_fn(|_| rng.r#gen());
        let best = live
            .iter()
            .map(|(p, _)| dist2(p, &q))
            .fold(f64::INFINITY, f64::min);
        for eps in [0.0, 0.5] {
            let (n, _) = t.approx_nearest(&q, eps).unwrap();
            let d = dist2(n.unwrap().point, &q);
            assert!(d <= best * (1.0 + eps) * (1.0 + eps), "D = {D}, eps {eps}");
        }
        assert!(t.locate(&q).is_ok());
    }
}

fn run<const D: usize>(seed: u64, sets: usize, n: usize) {
    let mut r = rng(seed);
    for _ in 0..sets {
        let entries = sample_points::<D>(&mut r, n);
        check_point_tree(&mut r, &entries);
        check_dynamic(&mut r, &entries);
        check_compressed(&mut r, &entries);
        check_skip(&mut r, &entries);
    }
}

macro_rules! every_dimension {
    ($($name:ident: $d:literal;)*) => {
        $(
            #[test]
            fn $name() {
                run::<$d>(2000 + $d, 4, 60);
            }
        )*
    };
}

every_dimension! {
    points_in_1d: 1;
    points_in_2d: 2;
    points_in_3d: 3;
    points_in_4d: 4;
    points_in_5d: 5;
    points_in_6d: 6;
    points_in_7d: 7;
    points_in_8d: 8;
}

/// Thousands of points from 4D up: the nodes hold more points than the nearest-neighbour
/// search scans whole and have 16 to 256 children each, which that search leaves out by
/// halves beyond its bound, and from 6D orders once pushed; buckets of 8 points, so that
/// the nodes it scans whole are inner nodes. Every tree against a scan, and the point tree's
/// k nearest, slots included,
/// against the first k of all points sorted by (distance, slot); its k-nearest self-join and
/// pair counts, whose traversals scan more per node there too.
fn many_points<const D: usize>(seed: u64) {
    let mut r = rng(seed);
    let entries = sample_points::<D>(&mut r, 3000);
    let t = PointTree::builder().bucket_size(8).build(&entries).unwrap();
    t.validate().unwrap();
    check_queries(&t, &entries, &mut r);
    let dynamic = DynamicPointTree::new(&entries).unwrap();
    check_queries(&dynamic, &entries, &mut r);
    check_queries(&compressed(&entries), &entries, &mut r);
    // every slot but `skip` by (distance from `q`, slot)
    let by_distance = |q: &[f64; D], skip: Option<usize>| {
        let mut all: Vec<(f64, usize)> = (0..t.len())
            .filter(|&s| Some(s) != skip)
            .map(|s| (dist2(t.point(s), q), s))
            .collect();
        all.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        all
    };
    for k in [1, 7, 40].repeat(10) {
        let random: [f64; D] = core::array::from_fn(|_| r.r#gen());
        // a stored point: its copies tie with it at 0
        let stored = *t.point(r.gen_range(0..t.len()));
        for q in [random, stored] {
            assert_eq!(
                nearest_pairs(&t, &q, k),
                by_distance(&q, None)[..k],
                "D = {D}, {k} nearest of {q:?}"
            );
        }
    }
    // the joins: each row the first k others by (distance, slot); pair counts by a double loop
    let k = 5;
    let table = t.k_nearest_self(k);
    for row in (0..t.len()).step_by(7) {
        let all = by_distance(t.point(row), Some(row));
        let (slots, dists) = table.row(row);
        let want: (Vec<usize>, Vec<f64>) = all[..k].iter().map(|&(d, s)| (s, d)).unzip();
        assert_eq!(
            (slots, dists),
            (&want.0[..], &want.1[..]),
            "D = {D}, row {row}"
        );
    }
    let radii = [0.0, 0.05, 0.4];
    let counts = t.count_pairs_within(&radii, Boundary::Inclusive).unwrap();
    for (r, &count) in radii.iter().zip(&counts) {
        let mut want = 0;
        for i in 0..t.len() {
            for j in i + 1..t.len() {
                want += u64::from(dist2(t.point(i), t.point(j)) <= r * r);
            }
        }
        assert_eq!(count, want, "D = {D}, pairs within {r}");
    }
}

#[test]
fn thousands_of_points_from_4d_to_8d() {
    many_points::<4>(41);
    many_points::<5>(51);
    many_points::<6>(61);
    many_points::<7>(71);
    many_points::<8>(81);
}

/// Points in 6D with their input positions as items.
type Entries6 = Vec<([f64; 6], usize)>;

/// 12 000 uniform 6-D points and their point tree in buckets of 8, validated.
fn uniform_6d_tree(r: &mut SmallRng) -> (Entries6, PointTree<f64, usize, 6>) {
    let entries: Entries6 = (0..12_000)
        .map(|i| (core::array::from_fn(|_| r.r#gen()), i))
        .collect();
    let t = PointTree::builder().bucket_size(8).build(&entries).unwrap();
    t.validate().unwrap();
    (entries, t)
}

/// Uniform points in 6D, 190 to a node of the first level on average, in buckets of 8: the
/// nearest-neighbour search scans such a node whole but for the children in the halves of
/// it beyond its bound. Its k nearest against the first k of all points by (distance, slot).
#[test]
fn nodes_scanned_but_for_their_far_halves_in_6d() {
    let mut r = rng(66);
    let (_, t) = uniform_6d_tree(&mut r);
    for k in [1, 3, 10].repeat(8) {
        let q: [f64; 6] = core::array::from_fn(|_| r.r#gen());
        let mut all: Vec<(f64, usize)> = (0..t.len()).map(|s| (dist2(t.point(s), &q), s)).collect();
        all.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        assert_eq!(nearest_pairs(&t, &q, k), all[..k], "{k} nearest of {q:?}");
    }
}

/// The same kind of tree: the region queries scan such a node whole but for the children in
/// the halves of it outside the region. Balls (one through a stored point, so that a point lies
/// on its sphere), boxes and half-spaces: the iterator, the count, the visitor and the visitor
/// that stops, against a scan of the items.
#[test]
fn region_queries_leave_out_far_halves_of_scanned_nodes_in_6d() {
    let mut r = rng(67);
    let (entries, t) = uniform_6d_tree(&mut r);
    let check = |region: &dyn Region<6>, what: &str| {
        let mut want: Vec<usize> = entries
            .iter()
            .filter(|(p, _)| region.contains(p))
            .map(|e| e.1)
            .collect();
        want.sort_unstable();
        let mut got: Vec<usize> = t.query(region).unwrap().map(|(_, &i)| i).collect();
        got.sort_unstable();
        assert_eq!(got, want, "{what}: iterator");
        assert_eq!(t.query_count(region).unwrap(), want.len(), "{what}: count");
        let mut visited = Vec::new();
        t.query_with(region, |_, &i| visited.push(i)).unwrap();
        visited.sort_unstable();
        assert_eq!(visited, want, "{what}: visitor");
        let mut seen = 0;
        let stop = t
            .query_until(region, |_, &i| {
                seen += 1;
                if seen == 5 {
                    ControlFlow::Break(i)
                } else {
                    ControlFlow::Continue(())
                }
            })
            .unwrap();
        assert_eq!(stop.is_some(), want.len() >= 5, "{what}: stopped");
        assert!(
            stop.is_none_or(|i| want.binary_search(&i).is_ok()),
            "{what}: stop item"
        );
    };
    for radius in [0.05, 0.15, 0.25, 0.4].repeat(4) {
        let c: [f64; 6] = core::array::from_fn(|_| r.r#gen());
        check(
            &Ball::new(c, radius).unwrap(),
            &format!("ball {c:?} {radius}"),
        );
        let on = entries[r.gen_range(0..entries.len())].0;
        let through = Ball::new(c, dist2(&on, &c).sqrt()).unwrap();
        check(&through, &format!("ball {c:?} through {on:?}"));
        let side = radius * 2.0;
        let b = Aabb::new(c.map(|x| x - side / 2.0), c.map(|x| x + side / 2.0)).unwrap();
        check(&b, &format!("box {b:?}"));
        let normal: [f64; 6] = core::array::from_fn(|_| r.gen_range(-1.0..1.0));
        let offset = normal.iter().zip(&c).map(|(n, x)| n * x).sum::<f64>() - radius;
        check(
            &HalfSpace::new(normal, offset).unwrap(),
            &format!("half-space {normal:?}"),
        );
    }
}

/// The `k` nearest points of `t` to `q` as (distance, slot) pairs.
fn nearest_pairs<const D: usize>(
    t: &PointTree<f64, usize, D>,
    q: &[f64; D],
    k: usize,
) -> Vec<(f64, usize)> {
    let found = t.k_nearest(q, k).unwrap();
    found.iter().map(|n| (n.distance, n.index)).collect()
}
