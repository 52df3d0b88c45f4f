//! Point-tree oracles: the chapter's recursive quadtree definition (generalised to D dimensions,
//! buckets and a maximum depth) and a checker of every property a built or balanced
//! `PointTree` must have.

use super::{all_options, leaf_cells};
use orthtree::prelude::*;
use orthtree::query::{AxisMetric, Location, Metric};
use orthtree::{
    geom::RootGeometry, points::PointTreeBuilder, tree::BalanceOptions, Aabb, Cell, PointTree,
    Scalar,
};
use proptest::test_runner::{Config, RngSeed};

/// A proptest configuration with a fixed seed, `cases` cases and no regression files.
pub fn config(cases: u32, seed: u64) -> Config {
    Config {
        cases,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: None,
        ..Config::default()
    }
}

/// The chapter's recursive definition (section 14.2), generalised: a node whose closed cell holds
/// at most `bucket` points, or which is at `max_depth`, is a leaf; otherwise its cell is cut at
/// the midpoints `x_mid` of every axis and a point goes to the upper child on axis a exactly when
/// `p_a > x_mid` (so a point on a split line goes to the lower side), and all 2^D children are
/// built recursively. With `bucket == 1` and distinct points this is the chapter's quadtree.
///
/// The split values are the tree's own boundaries (`RootGeometry::boundary`), so the comparison
/// is exact. Returns the leaves in child-index pre-order with their sorted items.
pub fn reference_leaves<S: Scalar, const D: usize>(
    g: &RootGeometry<D>,
    entries: &[([S; D], usize)],
    bucket: usize,
    max_depth: u8,
) -> Vec<(Cell<D>, Vec<usize>)> {
    let pts: Vec<([f64; D], usize)> = entries
        .iter()
        .map(|(p, i)| (p.map(Scalar::to_f64), *i))
        .collect();
    let mut out = Vec::new();
    build_reference(g, Cell::root(), pts, bucket, max_depth, &mut out);
    out
}

fn build_reference<const D: usize>(
    g: &RootGeometry<D>,
    cell: Cell<D>,
    pts: Vec<([f64; D], usize)>,
    bucket: usize,
    max_depth: u8,
    out: &mut Vec<(Cell<D>, Vec<usize>)>,
) {
    if pts.len() <= bucket || cell.level() >= max_depth {
        let mut items: Vec<usize> = pts.iter().map(|p| p.1).collect();
        items.sort_unstable();
        out.push((cell, items));
        return;
    }
    let level = cell.level() + 1;
    let c = cell.coords();
    let mid: [f64; D] = core::array::from_fn(|a| g.boundary(a, 2 * u64::from(c[a]) + 1, level));
    let mut parts: Vec<Vec<([f64; D], usize)>> = vec![Vec::new(); 1 << D];
    for (p, item) in pts {
        let i = (0..D).fold(0usize, |i, a| i | (usize::from(p[a] > mid[a]) << a));
        parts[i].push((p, item));
    }
    for (i, part) in parts.into_iter().enumerate() {
        let coords: [u32; D] = core::array::from_fn(|a| (c[a] << 1) | ((i >> a) & 1) as u32);
        let child = Cell::new(level, coords).unwrap();
        build_reference(g, child, part, bucket, max_depth, out);
    }
}

/// Checks a point tree built from `entries` (items are the input positions): nothing lost; every
/// point in exactly one leaf, the one `locate` finds, whose closed box holds it with the split
/// convention; node runs nest; bucket and depth limits; `validate`. With `balanced` set, the
/// internal-node bucket rule is waived (balance splits small leaves) and the tree must be balanced.
pub fn check_points<S: Scalar, const D: usize>(
    t: &PointTree<S, usize, D>,
    entries: &[([S; D], usize)],
    balanced: Option<BalanceOptions>,
) {
    let n = entries.len();
    assert_eq!(t.len(), n);
    assert_eq!(t.is_empty(), n == 0);
    assert_eq!(t.points().len(), n);
    assert_eq!(t.items().len(), n);
    // the multiset of (point, item) is the input's
    let mut items: Vec<usize> = t.items().to_vec();
    items.sort_unstable();
    assert!(items.iter().copied().eq(0..n), "every item exactly once");
    for (p, &item) in t.iter() {
        assert_eq!(*p, entries[item].0, "item {item} keeps its point");
    }

    let g = t.geometry();
    let tree = t.tree();
    let bucket = t.bucket_size();
    let max_depth = t.max_depth();
    assert!(t.depth() <= max_depth);
    let mut seen = 0usize;
    for leaf in t.leaves() {
        assert!(tree.is_leaf(leaf.id));
        assert_eq!(tree.cell(leaf.id), leaf.cell);
        assert_eq!(leaf.points.len(), leaf.items.len());
        assert_eq!(leaf.points, t.node_points(leaf.id));
        assert_eq!(leaf.items, t.node_items(leaf.id));
        if leaf.points.len() > bucket {
            assert_eq!(
                leaf.cell.level(),
                max_depth,
                "over-full leaf above the maximum depth"
            );
        }
        let bx = t.cell_box(leaf.id);
        assert_eq!(bx, g.cell_box(&leaf.cell));
        for (p, &item) in leaf.points.iter().zip(leaf.items) {
            seen += 1;
            assert_eq!(*p, entries[item].0);
            assert_eq!(t.locate(p), Ok(Location::Inside(leaf.id)), "locate {p:?}");
            let q = p.map(Scalar::to_f64);
            assert!(t.domain().contains(&q), "{q:?} in the domain");
            assert_eq!(g.cell_of(&q, leaf.cell.level()), leaf.cell);
            for a in 0..D {
                assert!(
                    bx.min[a] <= q[a] && q[a] <= bx.max[a],
                    "point {q:?} outside its leaf box {bx:?} on axis {a}"
                );
                // (lo, hi]: the lower side belongs to the cell only on the root's lower side
                assert!(
                    q[a] > bx.min[a] || leaf.cell.coords()[a] == 0,
                    "point {q:?} on the lower side of {:?} on axis {a}",
                    leaf.cell
                );
            }
        }
    }
    assert_eq!(seen, n, "every point in exactly one leaf");

    // runs nest: a node's points are its children's
    for (id, _) in tree.pre_order() {
        let own = t.node_points(id).len();
        if tree.is_leaf(id) {
            continue;
        }
        let sum: usize = tree.children(id).map(|c| t.node_points(c).len()).sum();
        assert_eq!(own, sum);
        if balanced.is_none() {
            assert!(
                own > bucket,
                "an internal node holds more than the bucket size"
            );
        }
    }
    if let Some(opts) = balanced {
        assert!(tree.is_balanced(opts));
    }
    if let Err(e) = t.validate() {
        panic!("validate: {e}");
    }
}

/// The leaves of `t` with their sorted items, in pre-order.
pub fn leaves_with_items<S: Scalar, const D: usize>(
    t: &PointTree<S, usize, D>,
) -> Vec<(Cell<D>, Vec<usize>)> {
    t.leaves()
        .map(|l| {
            let mut items = l.items.to_vec();
            items.sort_unstable();
            (l.cell, items)
        })
        .collect()
}

/// Everything: the built tree's properties, equality with the chapter's recursive definition, and
/// the same properties after balance with every option (the topology being exactly
/// `Tree::balance`'s).
pub fn check_all<S: Scalar, const D: usize>(
    t: &PointTree<S, usize, D>,
    entries: &[([S; D], usize)],
) {
    check_points(t, entries, None);
    let reference = reference_leaves(t.geometry(), entries, t.bucket_size(), t.max_depth());
    assert_eq!(leaves_with_items(t), reference, "the chapter's definition");
    for opts in all_options() {
        let mut b = t.clone();
        let split = b.balance(opts);
        let mut topo = t.tree().clone();
        assert_eq!(split, topo.balance(opts));
        assert_eq!(b.tree(), &topo);
        assert_eq!(leaf_cells(b.tree()), leaf_cells(&topo));
        check_points(&b, entries, Some(opts));
    }
}

/// A builder over the unit root box with `bucket` and, when given, `max_depth`.
pub fn unit_builder<const D: usize>(
    bucket: usize,
    max_depth: Option<u8>,
) -> PointTreeBuilder<f64, D> {
    let b = PointTree::builder()
        .root_box(Aabb::new([0.0; D], [1.0; D]).unwrap())
        .bucket_size(bucket);
    match max_depth {
        Some(m) => b.max_depth(m),
        None => b,
    }
}

/// `back`, a copy of `original` read back (from a saved file, a serde document), checked: valid,
/// the same (point, item) pairs in the same slots, and for each query point the same answers as
/// `original` (box queries and k nearest, ties and slots included), both checked against a brute
/// force over `original`'s pairs.
pub fn same_answers<P, const D: usize>(original: &P, back: &P, qs: &[[f64; D]])
where
    P: PointSet<D, Scalar = f64, Item = u32>,
{
    let metric = orthtree::query::SquaredEuclidean;
    back.validate().unwrap();
    let pairs = |t: &P| -> Vec<([f64; D], u32)> { t.iter().map(|(p, &i)| (*p, i)).collect() };
    let all = pairs(original);
    assert_eq!(pairs(back), all, "the pairs by slot");
    for (j, q) in qs.iter().enumerate() {
        let r = (j % 4) as f64 * 0.75;
        let b = Aabb::new(q.map(|x| x - r), q.map(|x| x + r)).unwrap();
        let mut want: Vec<u32> = (all.iter().filter(|(p, _)| b.contains(p)))
            .map(|&(_, i)| i)
            .collect();
        want.sort_unstable();
        let mut got: Vec<u32> = back.query(b).unwrap().map(|(_, &i)| i).collect();
        got.sort_unstable();
        assert_eq!(got, want, "box around {q:?}");
        let k = 1 + j % 7;
        let mut dist: Vec<f64> = all.iter().map(|(p, _)| metric.distance(q, p)).collect();
        dist.sort_by(f64::total_cmp);
        let near = |t: &P| -> Vec<(usize, u32, f64)> {
            let found = t.k_nearest(q, k).unwrap();
            found
                .iter()
                .map(|n| (n.index, *n.item, n.distance))
                .collect()
        };
        let (got, want) = (near(back), near(original));
        assert_eq!(got, want, "{k} nearest of {q:?}");
        let got: Vec<f64> = got.iter().map(|n| n.2).collect();
        assert_eq!(
            got,
            dist[..k.min(dist.len())],
            "{k} nearest of {q:?} by brute force"
        );
    }
}

/// Point sets whose root cube's far side rounds beyond `f64::MAX` on some axis (points spanning
/// more than `f64::MAX` there, or near it on one axis and apart on another), numbered: the three
/// smallest such sets, then a cloud over every magnitude up to ±`f64::MAX` with duplicates (its
/// third coordinates not negative, so that the cube spans `2 f64::MAX` from about 0 there).
/// Every writer must write a tree over them and its reader read it back equal (the domain stops
/// at `f64::MAX` where the cube goes beyond it).
pub fn beyond_f64_max(seed: u64) -> Vec<Vec<([f64; 3], u32)>> {
    use rand::Rng;
    const M: f64 = f64::MAX;
    let numbered =
        |ps: &[[f64; 3]]| -> Vec<([f64; 3], u32)> { ps.iter().copied().zip(0..).collect() };
    let mut r = super::rng(seed);
    let mut pick = || -> f64 {
        let m = match r.gen_range(0..5) {
            0 => M,
            1 => M * r.r#gen::<f64>(),
            2 => 10f64.powi(r.gen_range(-300..308)),
            3 => 0.0,
            _ => f64::from(r.gen_range(1..4u8)),
        };
        if r.r#gen() {
            -m
        } else {
            m
        }
    };
    let mut cloud: Vec<[f64; 3]> = (0..300).map(|_| [pick(), pick(), pick().abs()]).collect();
    cloud.extend_from_within(..40);
    vec![
        numbered(&[[1e308, 0.0, 0.0], [-1e308, 0.0, 0.0]]),
        numbered(&[[M, M, M], [M, 1.0, 0.0]]),
        numbered(&[[-M, 0.0, 0.0], [M, 0.0, 0.0]]),
        numbered(&cloud),
    ]
}

/// Query points for [`beyond_f64_max`]'s sets: some of the points, the origin and corners at
/// `±f64::MAX`.
pub fn beyond_f64_max_queries(pts: &[([f64; 3], u32)]) -> Vec<[f64; 3]> {
    const M: f64 = f64::MAX;
    let mut qs: Vec<[f64; 3]> = pts.iter().step_by(13).map(|p| p.0).collect();
    qs.extend([[0.0; 3], [M; 3], [-M, M, 0.0], [1e308, 1.0, -1.0]]);
    qs
}

/// The domain of a tree built over `pts` without a root box, checked: finite corners (a box
/// `Aabb::new` takes), every point inside, and the root cube's box where that is finite,
/// `f64::MAX` where its far side rounds beyond.
pub fn check_domain_beyond_f64_max<P: PointSet<3, Scalar = f64>>(t: &P, pts: &[([f64; 3], u32)]) {
    let d = *t.domain();
    assert_eq!(Aabb::new(d.min, d.max), Ok(d), "finite corners");
    assert!(pts.iter().all(|(p, _)| d.contains(p)), "every point inside");
    if let Some(g) = pts.first().map(|_| RootGeometry::enclosing(&bounds(pts))) {
        let root = g.root_box();
        assert_eq!(d.min, root.min);
        assert_eq!(d.max, root.max.map(|x| x.min(f64::MAX)));
        assert!(root.max.contains(&f64::INFINITY), "a cube beyond f64::MAX");
    }
}

/// The bounding box of `pts` (not empty).
fn bounds<const D: usize>(pts: &[([f64; D], u32)]) -> Aabb<f64, D> {
    let mut b = Aabb {
        min: pts[0].0,
        max: pts[0].0,
    };
    for (p, _) in pts {
        b.min = core::array::from_fn(|a| b.min[a].min(p[a]));
        b.max = core::array::from_fn(|a| b.max[a].max(p[a]));
    }
    b
}

/// Asserts that the fields `keys` of the serde document `v` (sequences of `f64` or an `f64`:
/// a root cube, a domain) hold numbers only: JSON has no infinities, and writes them as `null`.
pub fn assert_numbers(v: &serde_json::Value, keys: &[&str]) {
    for k in keys {
        let ok = match &v[*k] {
            serde_json::Value::Array(xs) => xs.iter().all(serde_json::Value::is_f64),
            x => x.is_f64(),
        };
        assert!(ok, "`{k}` holds numbers only: {}", v[*k]);
    }
}

/// The period box `[LO, HI)` of the periodic tests along every axis (period `L`): dyadic
/// ends, so every distance between grid points is exact.
pub const LO: f64 = -0.5;
pub const HI: f64 = 0.75;
pub const L: f64 = HI - LO;

/// The minimum over all images of `b` along the wrapping axes of `combine`d offsets: `3^k`
/// shifted copies tried one by one.
pub fn brute_distance<M: AxisMetric, const D: usize>(
    wraps: &[bool; D],
    a: &[f64; D],
    b: &[f64; D],
) -> f64 {
    let k = wraps.iter().filter(|&&w| w).count();
    let mut best = f64::INFINITY;
    for code in 0..3usize.pow(k as u32) {
        let (mut c, mut s) = (code, 0.0);
        for axis in 0..D {
            let mut shift = 0.0;
            if wraps[axis] {
                shift = (c % 3) as f64 - 1.0;
                c /= 3;
            }
            s = M::combine(s, (a[axis] - (b[axis] + shift * L)).abs());
        }
        best = best.min(s);
    }
    best
}
