//! The saved-tree format (`io::saved`, feature `saved`): round trips for D = 1, 2, 3, 8 over
//! f64, f32 and integer coordinates, zero-sized and array items, empty trees, duplicates, balanced
//! trees, trees with freed blocks (after removals) and trees over points whose root cube reaches
//! beyond `f64::MAX` (the domain stops there); the loaded tree validates, equals the one
//! written array for array, answers every query as it did and as brute force does, and takes
//! updates. Files read from disk equal slices. Wrong types are refused by name. The borrowed
//! view of the same bytes (`PointTreeView`, also from a misaligned slice, which copies) answers
//! every query kind (regions, nearest, k-nearest, the nearest iterator, joins, batches) as the
//! owned tree and as brute force do; points moved off their leaf's cell, onto a split line or to
//! an inexact 64-bit integer are refused by name.

use crate::common::points::{
    beyond_f64_max, beyond_f64_max_queries, check_domain_beyond_f64_max, config,
};
use orthtree::error::Invariant;
use orthtree::io::saved::{
    read_point_tree, read_point_tree_file, saved_len, write_point_tree, PointTreeView, SavedError,
    SavedScalar,
};
use orthtree::prelude::*;
use orthtree::query::{Boundary, HalfSpace, SquaredEuclidean};
use orthtree::{points::PointTreeBuilder, Aabb, Connectivity, Metric, PointTree, Scalar};
use proptest::prelude::*;

fn save<S: SavedScalar, T: bytemuck::Pod, const D: usize>(t: &PointTree<S, T, D>) -> Vec<u8> {
    let mut bytes = Vec::new();
    write_point_tree(t, &mut bytes).unwrap();
    assert_eq!(bytes.len() as u64, saved_len(t));
    assert_eq!(bytes.len() % 16, 0);
    bytes
}

fn f<S: Scalar, const D: usize>(p: &[S; D]) -> [f64; D] {
    p.map(Scalar::to_f64)
}

/// Checks `t`'s box and nearest queries against a scan of its own points and items, at the
/// query points `qs`.
pub fn check_against_brute<P, S, T, const D: usize>(t: &P, qs: &[[S; D]])
where
    P: PointSet<D, Scalar = S, Item = T>,
    S: Scalar,
    T: Copy + Ord + core::fmt::Debug,
{
    for (j, q) in qs.iter().enumerate() {
        let qf = f(q);
        let r = (j % 4) as f64 * 0.75;
        let b = Aabb::new(qf.map(|x| x - r), qf.map(|x| x + r)).unwrap();
        let mut want: Vec<T> = t
            .iter()
            .filter(|(p, _)| b.contains(&f(p)))
            .map(|(_, &i)| i)
            .collect();
        want.sort_unstable();
        let mut got: Vec<T> = t.query(b).unwrap().map(|(_, &i)| i).collect();
        got.sort_unstable();
        assert_eq!(got, want, "box around {qf:?}");
        let k = 1 + j % 7;
        let mut all: Vec<f64> = t
            .iter()
            .map(|(p, _)| SquaredEuclidean.distance(&qf, &f(p)))
            .collect();
        all.sort_by(f64::total_cmp);
        let near: Vec<f64> = t
            .k_nearest(q, k)
            .unwrap()
            .iter()
            .map(|n| n.distance)
            .collect();
        assert_eq!(near, all[..k.min(all.len())], "{k} nearest of {qf:?}");
    }
}

/// Writes `t`, reads it back from the bytes and from a file, and checks that the copy is the
/// same tree: arrays, topology, settings, and the answers to every query at `qs`.
fn round_trip<S, T, const D: usize>(t: &PointTree<S, T, D>, qs: &[[S; D]]) -> PointTree<S, T, D>
where
    S: SavedScalar,
    T: bytemuck::Pod + Ord + core::fmt::Debug + Sync,
{
    t.validate().unwrap();
    let bytes = save(t);
    let back = read_point_tree::<S, T, D>(&bytes).unwrap();
    back.validate().unwrap();
    assert_eq!(back.points(), t.points());
    assert_eq!(back.items(), t.items());
    assert_eq!(back.tree(), t.tree());
    assert_eq!(back.geometry(), t.geometry());
    assert_eq!(back.domain(), t.domain());
    assert_eq!(
        (back.bucket_size(), back.max_depth(), back.depth()),
        (t.bucket_size(), t.max_depth(), t.depth())
    );
    for id in t.tree().pre_order().map(|(id, _)| id) {
        assert_eq!(back.node_run(id), t.node_run(id));
    }
    for q in qs {
        assert_eq!(back.locate(q).unwrap(), t.locate(q).unwrap());
        assert_eq!(back.k_nearest(q, 5).unwrap(), t.k_nearest(q, 5).unwrap());
    }
    check_against_brute(&back, qs);
    // The same from a file, read array by array.
    let path = std::env::temp_dir().join(format!(
        "orthtree-saved-{}-{}-{D}.bin",
        std::process::id(),
        bytes.len()
    ));
    std::fs::write(&path, &bytes).unwrap();
    let from_file = read_point_tree_file::<S, T, D>(&path);
    std::fs::remove_file(&path).unwrap();
    let from_file = from_file.unwrap();
    assert_eq!(from_file.points(), t.points());
    assert_eq!(from_file.tree(), t.tree());
    // And the copy saves to the same bytes.
    assert_eq!(save(&back), bytes);
    check_view(t, &bytes, qs);
    back
}

/// Every query kind on `view` equals the owned tree `t`'s answer (same traversal, so the same
/// order) and a scan of the points.
fn view_equals_tree<S, T, const D: usize>(
    view: &PointTreeView<'_, S, T, D>,
    t: &PointTree<S, T, D>,
    qs: &[[S; D]],
) where
    S: SavedScalar,
    T: bytemuck::Pod + Ord + core::fmt::Debug + Sync,
{
    view.validate().unwrap();
    assert_eq!(view.points(), t.points());
    assert_eq!(view.items(), t.items());
    assert_eq!(view.domain(), t.domain());
    assert_eq!((view.len(), view.leaf_count()), (t.len(), t.leaf_count()));
    for (j, q) in qs.iter().enumerate() {
        let qf = f(q);
        let r = 0.5 + (j % 3) as f64;
        let b = Aabb::new(qf.map(|x| x - r), qf.map(|x| x + r)).unwrap();
        let got: Vec<(&[S; D], &T)> = view.query(b).unwrap().collect();
        assert_eq!(got, t.query(b).unwrap().collect::<Vec<_>>());
        let ball: Vec<T> = view.in_ball(q, r).unwrap().map(|(_, &i)| i).collect();
        let want: Vec<T> = t.in_ball(q, r).unwrap().map(|(_, &i)| i).collect();
        assert_eq!(ball, want, "ball around {qf:?}");
        let mut brute: Vec<T> = t
            .iter()
            .filter(|(p, _)| SquaredEuclidean.distance(&qf, &f(p)) <= r * r)
            .map(|(_, &i)| i)
            .collect();
        brute.sort_unstable();
        let mut ball = ball;
        ball.sort_unstable();
        assert_eq!(ball, brute, "ball around {qf:?} against a scan");
        let normal: [f64; D] = core::array::from_fn(|a| if a % 2 == 0 { 1.0 } else { -0.5 });
        let h = HalfSpace::new(normal, qf[0]).unwrap();
        assert_eq!(view.query_count(h).unwrap(), t.query_count(h).unwrap());
        assert_eq!(view.nearest(q).unwrap(), t.nearest(q).unwrap());
        assert_eq!(view.k_nearest(q, 4).unwrap(), t.k_nearest(q, 4).unwrap());
        let it: Vec<_> = view.nearest_iter(q).unwrap().take(6).collect();
        assert_eq!(it, t.nearest_iter(q).unwrap().take(6).collect::<Vec<_>>());
    }
    assert_eq!(view.k_nearest_self(3), t.k_nearest_self(3));
    assert_eq!(view.k_nearest_join(t, 2), t.k_nearest_join(t, 2));
    let radii = [0.0, 0.5, 2.0];
    assert_eq!(
        view.count_pairs_within(&radii, Boundary::Inclusive)
            .unwrap(),
        t.count_pairs_within(&radii, Boundary::Inclusive).unwrap()
    );
    #[cfg(feature = "rayon")]
    {
        let want: Vec<_> = qs.iter().map(|q| t.k_nearest(q, 3).unwrap()).collect();
        assert_eq!(view.par_k_nearest(qs, 3).unwrap(), want);
        assert_eq!(view.par_k_nearest_self(2), t.k_nearest_self(2));
    }
    check_against_brute(view, qs);
}

/// The view of `bytes` (the save of `t`) from the slice as it is, checked serially and in
/// parallel, and from a slice one byte off alignment (copied), answers as `t` does.
fn check_view<S, T, const D: usize>(t: &PointTree<S, T, D>, bytes: &[u8], qs: &[[S; D]])
where
    S: SavedScalar,
    T: bytemuck::Pod + Ord + core::fmt::Debug + Sync,
{
    let view = PointTreeView::<S, T, D>::open(bytes).unwrap();
    view_equals_tree(&view, t, qs);
    view_equals_tree(&PointTreeView::open_serial(bytes).unwrap(), t, qs);
    assert_eq!(view.to_tree().unwrap().tree(), t.tree());
    // A buffer of 16-byte words is aligned for every section; one byte in, nothing wider than
    // a byte is.
    let mut words = vec![0u128; bytes.len() / 16 + 1];
    let buf: &mut [u8] = bytemuck::cast_slice_mut(&mut words);
    buf[..bytes.len()].copy_from_slice(bytes);
    let aligned = PointTreeView::<S, T, D>::open(&buf[..bytes.len()]).unwrap();
    assert!(aligned.is_borrowed());
    assert_eq!(aligned.heap_bytes(), 0);
    buf.copy_within(..bytes.len(), 1);
    let off = PointTreeView::<S, T, D>::open(&buf[1..=bytes.len()]).unwrap();
    if core::mem::align_of::<S>() > 1 && !t.is_empty() {
        assert!(!off.is_borrowed());
    }
    view_equals_tree(&off, t, qs);
}

fn grid<const D: usize>(seed: u64, n: usize, side: u32) -> Vec<([f64; D], u32)> {
    let mut x = seed | 1;
    (0..n)
        .map(|i| {
            let p = core::array::from_fn(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                (x % side as u64) as f64 * 0.5
            });
            (p, i as u32)
        })
        .collect()
}

fn queries<const D: usize>(pts: &[([f64; D], u32)]) -> Vec<[f64; D]> {
    let mut qs: Vec<[f64; D]> = pts.iter().step_by(7).map(|p| p.0).take(12).collect();
    qs.push([0.3; D]);
    qs.push([-1.0; D]);
    qs
}

fn each_dimension<const D: usize>() {
    for (n, side, bucket) in [
        (0, 4, 4),
        (1, 4, 4),
        (300, 16, 4),
        (400, 3, 2),
        (200, 1000, 1),
    ] {
        let pts = grid::<D>(n as u64 + 7, n, side);
        let t = PointTreeBuilder::new()
            .bucket_size(bucket)
            .build(&pts)
            .unwrap();
        round_trip(&t, &queries(&pts));
    }
}

#[test]
fn round_trips_in_dimensions_1_2_3_8() {
    each_dimension::<1>();
    each_dimension::<2>();
    each_dimension::<3>();
    each_dimension::<8>();
}

#[test]
fn round_trips_over_f32_and_integer_coordinates() {
    let pts = grid::<3>(5, 500, 20);
    let p32: Vec<([f32; 3], u32)> = pts.iter().map(|(p, i)| (p.map(|x| x as f32), *i)).collect();
    let t = PointTreeBuilder::new().bucket_size(3).build(&p32).unwrap();
    let qs: Vec<[f32; 3]> = p32.iter().step_by(9).map(|p| p.0).collect();
    round_trip(&t, &qs);
    let pi: Vec<([i32; 2], u32)> = (0..400)
        .map(|i: i32| ([(i * 7919) % 61 - 30, (i * 104_729) % 37], i as u32))
        .collect();
    let t = PointTreeBuilder::new().bucket_size(2).build(&pi).unwrap();
    let qs: Vec<[i32; 2]> = pi.iter().step_by(11).map(|p| p.0).collect();
    round_trip(&t, &qs);
    // 64-bit integers far beyond 2^53 (multiples of the f64 spacing there).
    let pu: Vec<([u64; 2], u32)> = (0..200u64)
        .map(|i| ([(i % 13) << 60, (i % 7) << 58], i as u32))
        .collect();
    let t = PointTreeBuilder::new().bucket_size(4).build(&pu).unwrap();
    round_trip(&t, &[[0, 0], [1 << 62, 1 << 60]]);
}

#[test]
fn zero_sized_and_array_items_round_trip() {
    let pts = grid::<2>(3, 300, 30);
    let unit: Vec<([f64; 2], ())> = pts.iter().map(|(p, _)| (*p, ())).collect();
    let t = PointTree::new(&unit).unwrap();
    let back = round_trip(&t, &queries(&pts));
    assert_eq!(back.len(), 300);
    let arrays: Vec<([f64; 2], [u8; 3])> = pts
        .iter()
        .map(|(p, i)| (*p, [*i as u8, (*i >> 8) as u8, 7]))
        .collect();
    let t = PointTree::new(&arrays).unwrap();
    round_trip(&t, &queries(&pts));
}

#[test]
fn duplicates_and_a_root_box_round_trip() {
    // 300 copies of one point and a few others: a leaf at the maximum depth holds them all.
    let mut pts: Vec<([f64; 2], u32)> = (0..300).map(|i| ([0.25, 0.25], i)).collect();
    pts.extend((300..310).map(|i| ([1.0, i as f64 / 400.0], i)));
    let t = PointTreeBuilder::new()
        .bucket_size(2)
        .max_depth(6)
        .root_box(Aabb::new([-1.0, -2.0], [3.0, 1.0]).unwrap())
        .build(&pts)
        .unwrap();
    let back = round_trip(&t, &queries(&pts));
    assert_eq!(
        back.in_box(&Aabb::new([0.25; 2], [0.25; 2]).unwrap())
            .unwrap()
            .count(),
        300
    );
}

#[test]
fn balanced_trees_and_freed_blocks_round_trip_and_take_updates() {
    let pts = grid::<2>(11, 400, 64);
    let mut t = PointTreeBuilder::new().bucket_size(2).build(&pts).unwrap();
    t.balance(Connectivity::Corner);
    round_trip(&t, &queries(&pts));
    // Removals merge nodes and free their blocks: the free list is saved too.
    let mut t = PointTreeBuilder::new().bucket_size(2).build(&pts).unwrap();
    for (p, i) in pts.iter().skip(50) {
        assert!(t.remove(p, i));
    }
    let mut back = round_trip(&t, &queries(&pts));
    for (p, i) in pts.iter().skip(50).take(100) {
        back.insert(*p, *i).unwrap();
        t.insert(*p, *i).unwrap();
    }
    back.validate().unwrap();
    assert_eq!(back.tree(), t.tree());
    assert_eq!(back.items(), t.items());
    check_against_brute(&back, &queries(&pts));
}

#[test]
fn another_type_than_the_one_saved_is_refused_by_name() {
    let pts = grid::<2>(1, 50, 9);
    let bytes = save(&PointTree::new(&pts).unwrap());
    let field = |e: SavedError| match e {
        SavedError::Field { field, .. } => field,
        e => panic!("{e}"),
    };
    assert_eq!(
        field(read_point_tree::<f64, u32, 3>(&bytes).unwrap_err()),
        "dimension"
    );
    assert_eq!(
        field(read_point_tree::<f32, u32, 2>(&bytes).unwrap_err()),
        "scalar"
    );
    assert_eq!(
        field(read_point_tree::<f64, u64, 2>(&bytes).unwrap_err()),
        "item size"
    );
    assert_eq!(
        field(read_point_tree::<f64, [u8; 4], 2>(&bytes).unwrap_err()),
        "item alignment"
    );
    let e = read_point_tree::<f64, u32, 3>(&bytes).unwrap_err();
    assert_eq!(
        e.to_string(),
        "saved tree: `dimension` at byte 11 is 2, expected 3"
    );
    let mut more = bytes.clone();
    more.push(0);
    assert!(matches!(
        read_point_tree::<f64, u32, 2>(&more),
        Err(SavedError::Trailing { extra: 1, .. })
    ));
    let mut other = bytes;
    other[0] = b'X';
    assert!(matches!(
        read_point_tree::<f64, u32, 2>(&other),
        Err(SavedError::Field {
            field: "magic",
            offset: 0,
            ..
        })
    ));
    assert!(matches!(
        read_point_tree_file::<f64, u32, 2>("/nonexistent/orthtree.bin"),
        Err(SavedError::Io(_))
    ));
}

/// The first byte of the points section: the header, padded to 16 bytes.
fn points_offset<const D: usize>() -> usize {
    (72 + 24 * D + 4 * (orthtree::Cell::<D>::MAX_LEVEL as usize + 1)).div_ceil(16) * 16
}

/// The error's invariant, node and point, for a refusal by the check of the arrays.
fn refusal(e: SavedError) -> (Invariant, Option<u64>, Option<usize>) {
    match e {
        SavedError::Invalid(v) => (v.invariant, v.node, v.point),
        e => panic!("refused for another reason: {e}"),
    }
}

/// A point set exactly on its leaf's lower split line belongs to the cell below and is refused
/// by the view and the owned loader, naming the leaf and the point; one ulp above the line it is
/// in its cell, and the view answers as a scan of its points.
#[test]
fn points_on_split_lines_follow_the_lower_cell_convention() {
    let pts: Vec<([f64; 2], u32)> = (0..64u32)
        .map(|i| {
            (
                [f64::from(i % 8) / 4.0 + 0.1, f64::from(i / 8) / 4.0 + 0.1],
                i,
            )
        })
        .collect();
    let t = PointTreeBuilder::new().bucket_size(2).build(&pts).unwrap();
    let bytes = save(&t);
    let g = *t.geometry();
    let mut tried = 0;
    for leaf in t.leaves().filter(|l| !l.points.is_empty()) {
        let c = leaf.cell.coords()[0];
        if c == 0 {
            continue;
        }
        let line = g.boundary(0, u64::from(c), leaf.cell.level());
        let i = t.node_run(leaf.id).start;
        let at = points_offset::<2>() + i * 16;
        let mut b = bytes.clone();
        b[at..at + 8].copy_from_slice(&line.to_le_bytes());
        let want = (
            Invariant::InLeaf,
            Some(u64::from(leaf.id.index() as u32)),
            Some(i),
        );
        assert_eq!(
            refusal(PointTreeView::<f64, u32, 2>::open(&b).unwrap_err()),
            want
        );
        assert_eq!(
            refusal(read_point_tree::<f64, u32, 2>(&b).unwrap_err()),
            want
        );
        b[at..at + 8].copy_from_slice(&line.next_up().to_le_bytes());
        let view = PointTreeView::<f64, u32, 2>::open(&b).unwrap();
        assert_eq!(view.point(i)[0], line.next_up());
        check_against_brute(&view, &[[line, 0.3], [line.next_up(), leaf.points[0][1]]]);
        tried += 1;
    }
    assert!(tried > 10, "{tried} leaves off the first column");
}

/// Points swapped between leaves, and a 64-bit integer coordinate `f64` cannot hold, are
/// refused by name.
#[test]
fn points_out_of_place_or_inexact_are_refused_by_name() {
    let pts = grid::<3>(9, 500, 40);
    let t = PointTreeBuilder::new().bucket_size(4).build(&pts).unwrap();
    let mut b = save(&t);
    let (first, last) = (points_offset::<3>(), points_offset::<3>() + 499 * 24);
    let saved_first: Vec<u8> = b[first..first + 24].to_vec();
    b.copy_within(last..last + 24, first);
    b[last..last + 24].copy_from_slice(&saved_first);
    let (invariant, node, point) = refusal(PointTreeView::<f64, u32, 3>::open(&b).unwrap_err());
    assert_eq!((invariant, point), (Invariant::InLeaf, Some(0)));
    assert!(node.is_some());
    let pu: Vec<([u64; 2], u32)> = (0..100u64)
        .map(|i| ([(i % 13) << 60, (i % 7) << 58], i as u32))
        .collect();
    let t = PointTreeBuilder::new().bucket_size(4).build(&pu).unwrap();
    let mut b = save(&t);
    let at = points_offset::<2>() + 17 * 16;
    let x = u64::from_le_bytes(b[at..at + 8].try_into().unwrap());
    b[at..at + 8].copy_from_slice(&(x | 1 << 60 | 1).to_le_bytes());
    let e = PointTreeView::<u64, u32, 2>::open(&b).unwrap_err();
    assert!(e.to_string().contains("not exact as f64"), "{e}");
    assert_eq!(refusal(e).2, Some(17));
    assert!(read_point_tree::<u64, u32, 2>(&b).is_err());
}

/// Trees over points whose root cube's far side rounds beyond `f64::MAX`: the domain stops at
/// `f64::MAX` (its corners finite, every point inside, locatable), and the trees round-trip
/// through bytes, a file and the view like any other, also after updates. The header's domain
/// maximum set to infinity (not a finite box) or beyond the root cube is still refused as a
/// setting, by the view and the owned reader.
#[test]
fn trees_over_points_beyond_f64_max_round_trip() {
    for pts in beyond_f64_max(31) {
        let qs = beyond_f64_max_queries(&pts);
        for bucket in [1, 4, 64] {
            let t = PointTreeBuilder::new()
                .bucket_size(bucket)
                .build(&pts)
                .unwrap();
            check_domain_beyond_f64_max(&t, &pts);
            assert!(t.locate(&t.domain().max).unwrap().inside().is_some());
            let mut back = round_trip(&t, &qs);
            // Updates reach the domain's corners, and the updated tree saves and reads back too.
            let corner = t.domain().max;
            back.insert(corner, 1000).unwrap();
            assert!(back.remove(&pts[0].0, &pts[0].1));
            round_trip(&back, &qs);
        }
    }
    let t = PointTree::new(&beyond_f64_max(31)[0]).unwrap();
    assert_eq!(t.domain().max[1], f64::MAX);
    let bytes = save(&t);
    // 3D: half the side at 64, the halved lower corner at 72, the domain's minimum at 96 and
    // its maximum at 120.
    let max_at = |axis: usize| 120 + 8 * axis;
    let read = |b: &[u8]| f64::from_le_bytes(b[..8].try_into().unwrap());
    assert_eq!(read(&bytes[max_at(1)..]), f64::MAX);
    let root_max_0 = t.geometry().root_box().max[0];
    for (axis, bad) in [
        (1, f64::INFINITY),
        (2, f64::NAN),
        (0, f64::INFINITY),
        (0, root_max_0.next_up()),
    ] {
        let mut b = bytes.clone();
        b[max_at(axis)..max_at(axis) + 8].copy_from_slice(&bad.to_le_bytes());
        for e in [
            PointTreeView::<f64, u32, 3>::open(&b).unwrap_err(),
            read_point_tree::<f64, u32, 3>(&b).unwrap_err(),
        ] {
            let message = e.to_string();
            assert_eq!(refusal(e), (Invariant::Settings, None, None), "{message}");
            assert!(message.contains(&format!("axis {axis}")), "{message}");
        }
    }
}

proptest! {
    #![proptest_config(config(48, 0x5a7e_d001))]

    /// Random trees with duplicates and points on split lines (a grid of halves) round-trip.
    #[test]
    fn random_trees_round_trip(
        cells in proptest::collection::vec((0u8..12, 0u8..12, 0u8..12), 0..150),
        bucket in 1usize..6,
        depth in 1u8..12,
    ) {
        let pts: Vec<([f64; 3], u32)> = cells
            .iter()
            .enumerate()
            .map(|(i, &(a, b, c))| ([a as f64 / 2.0, b as f64 / 2.0, c as f64 / 2.0], i as u32))
            .collect();
        let t = PointTreeBuilder::new().bucket_size(bucket).max_depth(depth).build(&pts).unwrap();
        round_trip(&t, &queries(&pts));
    }
}
