//! The out-of-core build (`io::saved::external`) against the in-memory build: the same saved
//! bytes for random clouds with duplicates, clusters, points on cell faces and a maximum depth,
//! under budgets from one point per run (many merge passes) to one run for all, also over points
//! whose root cube reaches beyond `f64::MAX`; sources that change between the passes refused
//! before anything is written; and the mapped tree's box queries against a scan of the points.

use orthtree::io::saved::external::ExternalBuild;
use orthtree::io::saved::write_point_tree;
use orthtree::points::PointTreeBuilder;
use orthtree::PointTree;
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};
use std::path::PathBuf;

/// A fresh folder for one test's files.
fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("orthtree-ooc-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `n` points: a uniform part, a tight cluster, exact duplicates and points on the halving
/// planes of a unit cube, each with its index as item.
fn cloud(seed: u64, n: usize) -> Vec<([f64; 3], u32)> {
    let mut rng = SmallRng::seed_from_u64(seed);
    (0..n as u32)
        .map(|i| {
            let p = match rng.gen_range(0..4) {
                0 => [rng.r#gen(), rng.r#gen(), rng.r#gen()],
                1 => [
                    0.3 + 1e-4 * rng.r#gen::<f64>(),
                    0.7,
                    0.2 + 1e-4 * rng.r#gen::<f64>(),
                ],
                2 => [0.25, 0.5, 0.75],
                _ => [0.5, f64::from(rng.gen_range(0..5u8)) / 4.0, rng.r#gen()],
            };
            (p, i)
        })
        .collect()
}

fn in_memory_bytes<T: bytemuck::Pod, const D: usize>(
    entries: &[([f64; D], T)],
    bucket: usize,
    max_depth: Option<u8>,
) -> Vec<u8> {
    let mut b = PointTreeBuilder::new().bucket_size(bucket);
    if let Some(d) = max_depth {
        b = b.max_depth(d);
    }
    let tree: PointTree<f64, T, D> = b.build(entries).unwrap();
    let mut bytes = Vec::new();
    write_point_tree(&tree, &mut bytes).unwrap();
    bytes
}

#[test]
fn external_build_equals_the_in_memory_build_for_every_budget() {
    let dir = folder("equal");
    let file = dir.join("t.tree");
    for (seed, n) in [(1u64, 0usize), (2, 1), (3, 65), (4, 600), (5, 20_000)] {
        let pts = cloud(seed, n);
        for (bucket, depth) in [(64, None), (1, None), (4, Some(3)), (8, Some(21))] {
            let want = in_memory_bytes(&pts, bucket, depth);
            // 44 bytes a point in 7/8 of the budget: runs of 1, 2, ~20, ~650 points and one run.
            for budget in [1u64, 100, 1000, 1 << 15, 1 << 30] {
                if n > 600 && budget < 1 << 15 {
                    continue; // thousands of tiny runs: slow, and covered at n = 600
                }
                let mut b = ExternalBuild::new(budget).bucket_size(bucket);
                if let Some(d) = depth {
                    b = b.max_depth(d);
                }
                let report = b.write(|| pts.iter().copied(), &file).unwrap();
                let got = std::fs::read(&file).unwrap();
                assert_eq!(
                    got.len(),
                    want.len(),
                    "seed {seed} n {n} bucket {bucket} depth {depth:?} budget {budget}"
                );
                assert!(
                    got == want,
                    "seed {seed} n {n} bucket {bucket} depth {depth:?} budget {budget}: bytes differ"
                );
                assert_eq!(report.points, n as u64);
                assert_eq!(report.file_bytes, want.len() as u64);
                let run = b.run_points::<f64, u32, 3>();
                assert_eq!(report.runs, (n as u64).div_ceil(run));
                // no temporary file is left
                let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
                assert_eq!(left.len(), 1, "temporary files left: {left:?}");
            }
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn external_build_in_two_dimensions_with_f32_and_small_items() {
    let dir = folder("2d");
    let file = dir.join("t.tree");
    let mut rng = SmallRng::seed_from_u64(9);
    let pts: Vec<([f32; 2], u16)> = (0..3000u16)
        .map(|i| {
            let p = if i % 3 == 0 {
                [0.5, 0.5]
            } else {
                [rng.gen_range(-10.0..10.0), rng.gen_range(0.0..1e-3)]
            };
            (p, i)
        })
        .collect();
    let tree: PointTree<f32, u16, 2> = PointTreeBuilder::new().bucket_size(5).build(&pts).unwrap();
    let mut want = Vec::new();
    write_point_tree(&tree, &mut want).unwrap();
    for budget in [1u64, 500, 1 << 20] {
        ExternalBuild::new(budget)
            .bucket_size(5)
            .write(|| pts.iter().copied(), &file)
            .unwrap();
        assert!(std::fs::read(&file).unwrap() == want, "budget {budget}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn external_build_refuses_bad_points_and_a_changed_source() {
    let dir = folder("refuse");
    let file = dir.join("t.tree");
    let pts = [([0.0, 0.0, 0.0], 0u32), ([1.0, f64::NAN, 0.0], 1)];
    let err = ExternalBuild::new(1 << 20)
        .write(|| pts.iter().copied(), &file)
        .unwrap_err();
    assert!(err.to_string().contains("point 1"), "{err}");
    let mut calls = 0;
    let err = ExternalBuild::new(1 << 20)
        .write(
            || {
                calls += 1;
                (0..if calls == 1 { 10u32 } else { 11 }).map(|i| ([f64::from(i), 0.0, 0.0], i))
            },
            &file,
        )
        .unwrap_err();
    assert!(err.to_string().contains("10 points, then 11"), "{err}");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0, "no file left");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A source giving `base` on its first pass and `base` changed by `change` on every later one.
fn second_pass<P: Clone>(base: &[P], change: impl Fn(&mut Vec<P>)) -> impl FnMut() -> Vec<P> {
    let mut calls = 0;
    move || {
        calls += 1;
        let mut pts = base.to_vec();
        if calls > 1 {
            change(&mut pts);
        }
        pts
    }
}

/// A source whose second pass yields as many points as the first but not the same: a point
/// moved outside the first pass's bounds (also inside the root cube chosen from them) is refused
/// naming its index and axis, a coordinate that is no longer finite as the in-memory build
/// refuses it, each before anything is written: a file already at the output is left as it was
/// and no temporary run is left, whatever runs were spilled. The same points in another order
/// (all within the bounds) still give a file that reads back valid.
#[test]
fn external_build_refuses_points_moved_between_passes() {
    use orthtree::io::saved::external::ExternalError;
    use orthtree::io::saved::read_point_tree;
    use orthtree::PointSet;
    let dir = folder("moved");
    let file = dir.join("t.tree");
    std::fs::write(&file, b"an older file").unwrap();
    let base: Vec<([f64; 3], u32)> = (0..40u32)
        .map(|i| ([f64::from(i % 8), f64::from(i / 8), 0.5], i))
        .collect();
    // The bounds are [0, 7] x [0, 4] x [0.5, 0.5], the root cube [0, 7]^3 from (0, 0, 0.5).
    for (index, axis, moved) in [
        (17, 1, [1.0, 9.0, 0.5]),
        (3, 2, [3.0, 0.0, 6.0]),
        (39, 0, [-1.0, 4.0, 0.5]),
    ] {
        for budget in [100u64, 1 << 20] {
            let err = ExternalBuild::new(budget)
                .bucket_size(2)
                .write(second_pass(&base, |pts| pts[index].0 = moved), &file)
                .unwrap_err();
            match err {
                ExternalError::PointChanged {
                    index: i,
                    axis: a,
                    value,
                    ..
                } => assert_eq!((i, a, value.get()), (index, axis, moved[axis])),
                e => panic!("{e}"),
            }
            let message = err.to_string();
            assert!(
                message.contains(&format!("point {index}"))
                    && message.contains(&format!("axis {axis}"))
                    && message.contains("changed between passes"),
                "{message}"
            );
            assert_eq!(std::fs::read(&file).unwrap(), b"an older file");
            assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1, "a run left");
        }
    }
    let err = ExternalBuild::new(100)
        .write(second_pass(&base, |pts| pts[30].0[1] = f64::NAN), &file)
        .unwrap_err();
    assert!(
        matches!(
            err,
            ExternalError::Build(orthtree::Error::NonFiniteCoordinate {
                index: 30,
                axis: 1,
                ..
            })
        ),
        "{err}"
    );
    assert_eq!(std::fs::read(&file).unwrap(), b"an older file");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1, "a run left");
    ExternalBuild::new(100)
        .bucket_size(2)
        .write(second_pass(&base, |pts| pts.reverse()), &file)
        .unwrap();
    let back = read_point_tree::<f64, u32, 3>(&std::fs::read(&file).unwrap()).unwrap();
    back.validate().unwrap();
    assert_eq!(back.len(), base.len());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The out-of-core build over points whose root cube's far side rounds beyond `f64::MAX`
/// writes the in-memory build's bytes (the domain stopping at `f64::MAX`), which read back,
/// open as a view and, with feature `mmap`, through a map.
#[test]
fn external_build_over_points_beyond_f64_max_reads_back() {
    use crate::common::points::{beyond_f64_max, beyond_f64_max_queries, same_answers};
    use orthtree::io::saved::{read_point_tree, PointTreeView};
    use orthtree::PointSet;
    let dir = folder("beyond");
    let file = dir.join("t.tree");
    for pts in beyond_f64_max(35) {
        let want = in_memory_bytes(&pts, 4, None);
        let tree: PointTree<f64, u32, 3> =
            PointTreeBuilder::new().bucket_size(4).build(&pts).unwrap();
        for budget in [100u64, 1 << 20] {
            ExternalBuild::new(budget)
                .bucket_size(4)
                .write(|| pts.iter().copied(), &file)
                .unwrap();
            let got = std::fs::read(&file).unwrap();
            assert!(got == want, "budget {budget}: bytes differ");
            let back = read_point_tree::<f64, u32, 3>(&got).unwrap();
            assert_eq!(back.domain(), tree.domain());
            assert!(back.domain().max.iter().all(|x| x.is_finite()));
            same_answers(&tree, &back, &beyond_f64_max_queries(&pts));
            let view = PointTreeView::<f64, u32, 3>::open(&got).unwrap();
            assert_eq!(view.domain(), tree.domain());
            #[cfg(feature = "mmap")]
            {
                use orthtree::io::saved::mapped::MappedTree;
                let mapped = MappedTree::<f64, u32, 3>::open(&file).unwrap();
                assert_eq!(&mapped.domain(), tree.domain());
                assert_eq!(mapped.view().unwrap().domain(), tree.domain());
                assert_eq!(mapped.to_tree().unwrap().points(), tree.points());
            }
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Box queries through the map equal a scan of the points, on a tree built out of core; a
/// damaged node section gives an error or an answer, never a panic.
#[cfg(feature = "mmap")]
#[test]
fn mapped_box_queries_equal_a_scan() {
    use orthtree::io::saved::mapped::MappedTree;
    use orthtree::Aabb;
    let dir = folder("mapped");
    let file = dir.join("t.tree");
    let pts = cloud(11, 30_000);
    ExternalBuild::new(1 << 16)
        .bucket_size(16)
        .write(|| pts.iter().copied(), &file)
        .unwrap();
    let mapped = MappedTree::<f64, u32, 3>::open(&file).unwrap();
    assert_eq!(mapped.len(), pts.len());
    let mut rng = SmallRng::seed_from_u64(12);
    for q in 0..200 {
        let (a, b): ([f64; 3], [f64; 3]) = (rng.r#gen(), rng.r#gen());
        let mut min: [f64; 3] = core::array::from_fn(|k| a[k].min(b[k]));
        let mut max: [f64; 3] = core::array::from_fn(|k| a[k].max(b[k]));
        if q % 4 == 0 {
            // faces through the duplicates and the points on halving planes
            min = [0.25, 0.25, 0.0];
            max = [0.5, 0.5 + f64::from(q % 3) / 8.0, 0.75];
        }
        let query = Aabb::new(min, max).unwrap();
        let mut got = Vec::new();
        let count = mapped.query_box(&query, |_, &i| got.push(i)).unwrap();
        got.sort_unstable();
        let want: Vec<u32> = pts
            .iter()
            .filter(|(p, _)| (0..3).all(|k| min[k] <= p[k] && p[k] <= max[k]))
            .map(|e| e.1)
            .collect();
        assert_eq!(count, want.len(), "query {q}");
        assert_eq!(got, want, "query {q}");
    }
    drop(mapped);
    let bytes = std::fs::read(&file).unwrap();
    let everything = Aabb::new([-1.0; 3], [2.0; 3]).unwrap();
    for k in 0..64 {
        let mut damaged = bytes.clone();
        let at = damaged.len() - 1 - (k * 7919) % (damaged.len() / 8);
        damaged[at] ^= 0xa5;
        std::fs::write(&file, &damaged).unwrap();
        if let Ok(m) = MappedTree::<f64, u32, 3>::open(&file) {
            let _ = m.query_box(&everything, |_, _| {});
            assert!(m.to_tree().is_err() || m.query_box(&everything, |_, _| {}).is_ok());
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// First children that share their blocks (a file damaged after it was written): the root's
/// last child holds every point and is a leaf, its other children have empty runs and share
/// block 1 as their children, every slot of block k has block k + 1 as its children (with empty
/// runs), down to block 30, whose slots are leaves. The runs partition their parents', but a
/// segment crosses two cells of each node, so a walk that follows the links would visit 2^31
/// cells; the query through the map reaches no slot twice and reports the damage.
#[cfg(feature = "mmap")]
#[test]
fn mapped_box_query_stops_on_first_children_shared_by_many_nodes() {
    use orthtree::io::saved::mapped::MappedTree;
    use orthtree::io::saved::SavedError;
    use orthtree::Aabb;
    let mut rng = SmallRng::seed_from_u64(15);
    let pts: Vec<([f64; 2], u32)> = (0..300)
        .map(|i| ([rng.gen_range(0.0..1.0), rng.gen_range(0.0..1.0)], i))
        .collect();
    let tree = PointTreeBuilder::new().bucket_size(1).build(&pts).unwrap();
    let mut bytes = Vec::new();
    write_point_tree(&tree, &mut bytes).unwrap();
    let slots = u64::from_le_bytes(bytes[40..48].try_into().unwrap()) as usize;
    assert!(slots > 1 + 4 * 31, "{slots} slots");
    // 2D: a header of 252 bytes, then points (n x 16), items (n x 4), run ends (slots x 4)
    // and first children (slots x 4), each from a multiple of 16
    let padded = |x: usize| x.div_ceil(16) * 16;
    let run_ends = padded(padded(padded(252) + 16 * pts.len()) + 4 * pts.len());
    let first_child = padded(run_ends + 4 * slots);
    for slot in 0..slots {
        let block = slot.saturating_sub(1) / 4;
        let (child, end) = match slot {
            0 => (1, pts.len() as u32),
            4 => (u32::MAX, pts.len() as u32),
            _ if block < 30 => (1 + 4 * (block as u32 + 1), 0),
            _ => (u32::MAX, 0),
        };
        bytes[run_ends + 4 * slot..][..4].copy_from_slice(&end.to_le_bytes());
        bytes[first_child + 4 * slot..][..4].copy_from_slice(&child.to_le_bytes());
    }
    let dir = folder("mapped-shared");
    let file = dir.join("t.tree");
    std::fs::write(&file, &bytes).unwrap();
    let mapped = MappedTree::<f64, u32, 2>::open(&file).unwrap();
    let d = mapped.domain();
    let x = d.min[0] + 0.3 * (d.max[0] - d.min[0]);
    let segment = Aabb::new([x, d.min[1]], [x, d.max[1]]).unwrap();
    let start = std::time::Instant::now();
    match mapped.query_box(&segment, |_, _| {}) {
        Err(SavedError::Corrupt { what, .. }) => assert_eq!(what, "node reached twice"),
        other => panic!("{other:?}"),
    }
    assert!(start.elapsed().as_secs() < 5);
    assert!(mapped.view().is_err() && mapped.to_tree().is_err());
    drop(mapped);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A node whose last child's run reaches past its own (a damaged run end): the points after
/// its run belong to other nodes, and a box query through the map must not report them twice.
#[cfg(feature = "mmap")]
#[test]
fn mapped_box_query_refuses_child_runs_that_leave_their_parents() {
    use orthtree::io::saved::mapped::MappedTree;
    use orthtree::io::saved::SavedError;
    use orthtree::Aabb;
    let mut rng = SmallRng::seed_from_u64(16);
    let pts: Vec<([f64; 2], u32)> = (0..300)
        .map(|i| ([rng.gen_range(0.0..1.0), rng.gen_range(0.0..1.0)], i))
        .collect();
    let tree = PointTreeBuilder::new().bucket_size(1).build(&pts).unwrap();
    let mut bytes = Vec::new();
    write_point_tree(&tree, &mut bytes).unwrap();
    let slots = u64::from_le_bytes(bytes[40..48].try_into().unwrap()) as usize;
    // 2D: a header of 252 bytes, then points (n x 16), items (n x 4), run ends (slots x 4)
    // and first children (slots x 4), each from a multiple of 16
    let padded = |x: usize| x.div_ceil(16) * 16;
    let run_ends = padded(padded(padded(252) + 16 * pts.len()) + 4 * pts.len());
    let first_child = padded(run_ends + 4 * slots);
    let word = |b: &[u8], at: usize| u32::from_le_bytes(b[at..at + 4].try_into().unwrap());
    // the root's first child (slot 1) runs from point 0; its last child now ends at the last
    // point instead of at its parent's end
    let block = word(&bytes, first_child + 4) as usize;
    assert!(block < slots, "slot 1 has children");
    bytes[run_ends + 4 * (block + 3)..][..4].copy_from_slice(&(pts.len() as u32).to_le_bytes());
    let dir = folder("mapped-runs");
    let file = dir.join("t.tree");
    std::fs::write(&file, &bytes).unwrap();
    let mapped = MappedTree::<f64, u32, 2>::open(&file).unwrap();
    let inner = Aabb::new([0.01; 2], [0.99; 2]).unwrap();
    match mapped.query_box(&inner, |_, _| {}) {
        Err(SavedError::Corrupt { what, .. }) => assert_eq!(what, "child runs"),
        other => panic!("{other:?}"),
    }
    drop(mapped);
    std::fs::remove_dir_all(&dir).unwrap();
}
