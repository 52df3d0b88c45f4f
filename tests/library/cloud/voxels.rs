//! Voxel downsampling and occupancy on the tree's cells, against brute force: a sort of the
//! points by voxel key, on random clouds with duplicates, points on voxel faces and clouds in
//! one voxel. For integer clouds with power-of-two voxels the voxel of a point is also computed
//! by integer arithmetic alone: `ceil((x - min) / v) - 1`, the lowest voxel taking its lower face.

use crate::common::rng;
use orthtree::cloud::voxel::{Representative, VoxelGrid};
use orthtree::cloud::{Cloud, CloudError, Column};
use orthtree::{Cell, PointSet};
use proptest::prelude::*;
use rand::Rng;

/// The voxel cell of every point by integer arithmetic (integer clouds, voxel `2^k`, grid
/// corner at the points' minimum).
fn integer_voxels(points: &[[i32; 3]], voxel: i64, level: u8) -> Vec<Cell<3>> {
    let min: [i64; 3] = core::array::from_fn(|a| points.iter().map(|p| p[a] as i64).min().unwrap());
    points
        .iter()
        .map(|p| {
            let c = core::array::from_fn(|a| {
                let d = p[a] as i64 - min[a];
                let up = (d + voxel - 1) / voxel; // ceil
                (up - 1).max(0) as u32
            });
            Cell::new(level, c).unwrap()
        })
        .collect()
}

/// Groups of point indices by voxel, in Morton order of the voxels (indices ascending).
fn groups_by_sort(cells: &[Cell<3>]) -> Vec<(Cell<3>, Vec<usize>)> {
    let mut order: Vec<usize> = (0..cells.len()).collect();
    order.sort_by_key(|&i| (cells[i].morton(), i));
    let mut out: Vec<(Cell<3>, Vec<usize>)> = Vec::new();
    for i in order {
        match out.last_mut() {
            Some((c, g)) if *c == cells[i] => g.push(i),
            _ => out.push((cells[i], vec![i])),
        }
    }
    out
}

fn centroid(points: &[[f64; 3]], g: &[usize]) -> [f64; 3] {
    core::array::from_fn(|a| g.iter().map(|&i| points[i][a]).sum::<f64>() / g.len() as f64)
}

fn nearest(points: &[[f64; 3]], g: &[usize]) -> usize {
    let c = centroid(points, g);
    let d2 = |i: usize| (0..3).map(|a| (points[i][a] - c[a]).powi(2)).sum::<f64>();
    *g.iter()
        .min_by(|&&i, &&j| d2(i).total_cmp(&d2(j)).then(i.cmp(&j)))
        .unwrap()
}

/// Checks downsampling and occupancy of `cloud` on `grid` against the groups.
fn check(cloud: &Cloud<f64>, grid: &VoxelGrid<3>, groups: &[(Cell<3>, Vec<usize>)]) {
    let tree = grid.tree(&cloud.entries().unwrap()).unwrap();
    tree.validate().unwrap();
    let voxels = grid.voxels(&tree).unwrap();
    assert_eq!(voxels.len(), groups.len());
    for (v, (cell, g)) in voxels.iter().zip(groups) {
        assert_eq!(v.cell, *cell);
        let mut slots: Vec<usize> = v.slots.clone().map(|s| tree.items()[s] as usize).collect();
        slots.sort();
        assert_eq!(&slots, g);
    }
    let mean = grid.downsample(cloud, Representative::Centroid).unwrap();
    assert_eq!(mean.len(), groups.len());
    for (k, (_, g)) in groups.iter().enumerate() {
        let c = centroid(&cloud.points, g);
        for a in 0..3 {
            let tol = 1e-9 * (1.0 + c[a].abs());
            assert!(
                (mean.points[k][a] - c[a]).abs() <= tol,
                "voxel {k}: {:?} vs {c:?}",
                mean.points[k]
            );
        }
        if let Some(i) = &cloud.attributes.intensity {
            let m = g.iter().map(|&j| f64::from(i[j])).sum::<f64>() / g.len() as f64;
            assert_eq!(
                mean.attributes.intensity.as_ref().unwrap()[k],
                m.round() as u16
            );
        }
        if let Some(cl) = &cloud.attributes.classification {
            let count = |c: u8| g.iter().filter(|&&j| cl[j] == c).count();
            let best = (0..=255u8)
                .max_by_key(|&c| (count(c), std::cmp::Reverse(c)))
                .unwrap();
            assert_eq!(mean.attributes.classification.as_ref().unwrap()[k], best);
        }
    }
    // The point nearest the centroid: the brute-force choice, or a point as near up to the
    // rounding of the centroid's sum (two points at mirrored offsets tie only in exact
    // arithmetic); among copies of one point the lowest index. Extra column 0 is the index.
    let near = grid.downsample(cloud, Representative::Nearest).unwrap();
    let mut chosen = Vec::new();
    for (k, (_, g)) in groups.iter().enumerate() {
        let j = near.attributes.extra[0].values[k] as usize;
        let c = centroid(&cloud.points, g);
        let d2 = |i: usize| {
            (0..3)
                .map(|a| (cloud.points[i][a] - c[a]).powi(2))
                .sum::<f64>()
        };
        let best = d2(nearest(&cloud.points, g));
        assert!(
            g.contains(&j) && d2(j) <= best * (1.0 + 1e-9) + 1e-300,
            "voxel {k}: {j} in {g:?}"
        );
        let first_copy = g
            .iter()
            .find(|&&i| cloud.points[i] == cloud.points[j])
            .unwrap();
        assert_eq!(*first_copy, j);
        chosen.push(j);
    }
    assert_eq!(near, cloud.select(&chosen));

    let occupancy = grid.occupancy(&tree).unwrap();
    occupancy.validate().unwrap();
    assert_eq!(grid.occupancy_of(&cloud.points).unwrap(), occupancy);
    let cells: Vec<Cell<3>> = groups.iter().map(|(c, _)| *c).collect();
    assert_eq!(grid.occupied_voxels(&cloud.points).unwrap(), cells);
    assert_eq!(occupancy.len(), groups.len() as u64);
    let side = grid.side_voxels() as usize;
    if side <= 32 {
        let dense = occupancy.to_bools();
        let mut expect = vec![false; side * side * side];
        for (c, _) in groups {
            let [x, y, z] = c.coords().map(|v| v as usize);
            expect[x + side * (y + side * z)] = true;
        }
        assert_eq!(dense, expect);
    }
}

fn integer_cloud(points: Vec<[i32; 3]>, seed: u64) -> Cloud<f64> {
    let mut r = rng(seed);
    let n = points.len();
    let mut cloud = Cloud::from_points(points.iter().map(|p| p.map(f64::from)).collect());
    cloud.attributes.intensity = Some((0..n).map(|_| r.gen_range(0..1000)).collect());
    cloud.attributes.classification = Some((0..n).map(|_| r.gen_range(0..4)).collect());
    cloud.attributes.extra.push(Column {
        name: "w".into(),
        values: (0..n).map(|i| i as f64).collect(),
    });
    cloud
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// Integer lattices (many duplicates, most points on voxel faces), voxels of side 1..8.
    #[test]
    fn downsampling_and_occupancy_equal_a_sort_by_integer_voxel(
        points in proptest::collection::vec(proptest::array::uniform3(-8i32..9), 1..300),
        k in 0u32..4,
        seed in any::<u64>(),
    ) {
        let voxel = 1i64 << k;
        let grid = VoxelGrid::with_size(&points, voxel as f64).unwrap();
        prop_assert_eq!(grid.voxel_size(), voxel as f64);
        let cells = integer_voxels(&points, voxel, grid.level());
        let cloud = integer_cloud(points, seed);
        check(&cloud, &grid, &groups_by_sort(&cells));
    }

    /// Random float clouds with duplicates, voxels from 1/100 of the extent to beyond it (one
    /// voxel), against a sort by the grid's own voxel key.
    #[test]
    fn downsampling_and_occupancy_equal_a_sort_by_voxel_key(
        n in 1usize..400,
        copies in 0usize..50,
        voxel in prop_oneof![0.01f64..0.5, 1.0f64..10.0],
        seed in any::<u64>(),
    ) {
        let mut r = rng(seed);
        let mut points: Vec<[f64; 3]> = (0..n).map(|_| [r.r#gen(), r.r#gen(), r.r#gen::<f64>() * 0.5]).collect();
        for _ in 0..copies {
            let p = points[r.gen_range(0..points.len())];
            points.push(p);
        }
        let mut cloud = Cloud::from_points(points);
        cloud.attributes.intensity = Some((0..cloud.len()).map(|_| r.r#gen()).collect());
        cloud.attributes.extra.push(Column { name: "index".into(), values: (0..cloud.len()).map(|i| i as f64).collect() });
        let grid = VoxelGrid::with_size(&cloud.points, voxel).unwrap();
        let cells: Vec<Cell<3>> = cloud.points.iter().map(|p| grid.voxel_of(p)).collect();
        check(&cloud, &grid, &groups_by_sort(&cells));
    }
}

/// Grids so fine that a point's input index no longer fits below the voxel digits of its key
/// (the sort then moves 16-byte pairs), and the levels around that switch.
#[test]
fn fine_grids_group_points_like_a_sort_by_voxel_key() {
    let mut r = rng(21);
    for level in 15..=Cell::<3>::MAX_LEVEL {
        let mut points: Vec<[f64; 3]> = (0..600)
            .map(|_| [r.r#gen(), r.r#gen(), r.r#gen::<f64>()])
            .collect();
        // copies, and points one voxel apart on a voxel face
        let voxel = 1.0 / (1u64 << level) as f64;
        for i in 0..100 {
            points.push(points[i]);
            points.push(points[i].map(|x| (x / voxel).floor() * voxel));
        }
        let mut cloud = Cloud::from_points(points);
        cloud.attributes.extra.push(Column {
            name: "index".into(),
            values: (0..cloud.len()).map(|i| i as f64).collect(),
        });
        let grid = VoxelGrid::at_level([0.0; 3], 1.0, level).unwrap();
        let cells: Vec<Cell<3>> = cloud.points.iter().map(|p| grid.voxel_of(p)).collect();
        check(&cloud, &grid, &groups_by_sort(&cells));
    }
    // In 2-D the keys use all 64 bits: the coarsest and finest levels at both ends of them.
    let points: Vec<[f64; 2]> = (0..300).map(|_| [r.r#gen(), r.r#gen()]).collect();
    for level in [0, 1, 16, 31] {
        let grid = VoxelGrid::<2>::at_level([0.0; 2], 1.0, level).unwrap();
        let distinct: std::collections::BTreeSet<u64> =
            points.iter().map(|p| grid.voxel_of(p).morton()).collect();
        let occupancy = grid.occupancy_of(&points).unwrap();
        occupancy.validate().unwrap();
        assert_eq!(occupancy.len(), distinct.len() as u64, "level {level}");
    }
    // 2^32 voxels per axis: more than a region tree's side holds
    let grid = VoxelGrid::<2>::at_level([0.0; 2], 1.0, 32).unwrap();
    let err = grid.occupancy_of(&points).unwrap_err();
    assert!(matches!(err, CloudError::Image(_)), "{err}");
    assert!(err.to_string().contains("31"), "{err}");
}

#[test]
fn one_voxel_and_one_point_clouds() {
    let cloud = integer_cloud(vec![[3, 3, 3]; 10], 1);
    let grid = VoxelGrid::with_size(&cloud.points, 0.5).unwrap();
    assert_eq!(grid.level(), 0);
    let down = grid.downsample(&cloud, Representative::Centroid).unwrap();
    assert_eq!(down.points, [[3.0, 3.0, 3.0]]);
    assert_eq!(down.attributes.extra[0].values, [4.5]);
    let near = grid.downsample(&cloud, Representative::Nearest).unwrap();
    assert_eq!(near.attributes.extra[0].values, [0.0]); // ties to the lowest index
                                                        // no points: no voxels
    let empty = Cloud::<f64>::from_points(Vec::new());
    let grid = VoxelGrid::with_size(&empty.points, 1.0).unwrap();
    for representative in [Representative::Centroid, Representative::Nearest] {
        assert!(grid.downsample(&empty, representative).unwrap().is_empty());
    }
    assert_eq!(grid.occupancy_of(&empty.points).unwrap().len(), 0);
    // a point outside the grid's cube is refused, not clamped into a voxel
    let outside = Cloud::from_points(vec![[0.5, 0.5, 0.5], [9.0, 0.5, 0.5]]);
    let err = grid
        .downsample(&outside, Representative::Centroid)
        .unwrap_err();
    assert!(matches!(err, CloudError::Tree(_)), "{err}");
    assert!(err.to_string().contains("point 1"), "{err}");
    assert!(grid.occupancy_of(&outside.points).is_err());
}

#[test]
fn two_scans_xor_to_the_voxels_that_changed() {
    let mut r = rng(9);
    let a: Vec<[f64; 3]> = (0..2000)
        .map(|_| [r.r#gen(), r.r#gen(), r.r#gen()])
        .collect();
    let mut b = a.clone();
    b.truncate(1500);
    b.extend((0..300).map(|_| [r.r#gen::<f64>(), r.r#gen(), r.r#gen()]));
    let all: Vec<[f64; 3]> = a.iter().chain(&b).copied().collect();
    let grid = VoxelGrid::with_size(&all, 0.1).unwrap();
    let occ_a = grid.occupancy_of(&a).unwrap();
    let occ_b = grid.occupancy_of(&b).unwrap();
    let change = &occ_a ^ &occ_b;
    let set = |pts: &[[f64; 3]]| -> std::collections::BTreeSet<u64> {
        pts.iter().map(|p| grid.voxel_of(p).morton()).collect()
    };
    let (sa, sb) = (set(&a), set(&b));
    assert_eq!(change.len(), sa.symmetric_difference(&sb).count() as u64);
    assert_eq!((&occ_a & &occ_b).len(), sa.intersection(&sb).count() as u64);
}

#[test]
fn bad_grids_are_refused() {
    let pts = [[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]];
    assert!(VoxelGrid::with_size(&pts, 0.0).is_err());
    assert!(VoxelGrid::with_size(&pts, f64::NAN).is_err());
    let err = VoxelGrid::with_size(&pts, 1e-9).unwrap_err();
    assert!(err.to_string().contains("exceed 2^21"), "{err}");
    assert!(VoxelGrid::with_size(&[[f64::INFINITY, 0.0, 0.0]], 1.0).is_err());
    // the first bad coordinate is named, in whatever block of points the check reads it
    let mut many: Vec<[f64; 3]> = (0..3000).map(|i| [i as f64, 0.5, 0.25]).collect();
    for (index, axis, value) in [
        (2999, 2, f64::NEG_INFINITY),
        (1024, 1, f64::NAN),
        (1023, 0, f64::INFINITY),
    ] {
        many[index][axis] = value;
        match VoxelGrid::with_size(&many, 1.0).unwrap_err() {
            CloudError::BadCoordinate {
                index: i,
                axis: a,
                value: v,
            } => {
                assert_eq!((i, a), (index, axis));
                assert_eq!(v.is_nan(), value.is_nan());
                assert!(v.is_nan() || v == value);
            }
            other => panic!("expected BadCoordinate, got {other:?}"),
        }
    }
    // an integer cloud with a voxel that is not an integer has no integer root box
    let ints = [[0i32, 0, 0], [3, 3, 3]];
    let grid = VoxelGrid::with_size(&ints, 0.7).unwrap(); // side 5.6
    let entries: Vec<([i32; 3], ())> = ints.iter().map(|p| (*p, ())).collect();
    assert!(grid.tree(&entries).is_err());
}
