//! Bad input on one rank is the same typed error on every rank, and no rank is left waiting:
//! a bad point (NaN, outside the root box, an integer `f64` cannot hold), settings that
//! differ, and a bad query in each kind of batch. Each error equals what the single-process
//! tree gives for that rank's input.

use super::Check;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use orthtree::dist::{DistError, DistPointTreeBuilder};
use orthtree::points::PointTreeBuilder;
use orthtree::prelude::*;
use orthtree::{Aabb, Error, QueryError};

pub const CHECKS: &[Check] = &[
    ("bad_input::bad_point_on_one_rank", bad_point_on_one_rank),
    ("bad_input::settings_differ", settings_differ),
    (
        "bad_input::bad_queries_on_one_rank",
        bad_queries_on_one_rank,
    ),
];

/// Ten good points on each rank.
fn good(rank: usize) -> Vec<([f64; 2], u32)> {
    (0..10)
        .map(|i| ([i as f64 / 10.0, rank as f64 / 10.0], i))
        .collect()
}

fn bad_point_on_one_rank(world: &SimpleCommunicator) {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    let unit = Aabb::new([0.0, 0.0], [1.0, 1.0]).unwrap();
    for (bad, value) in [(size - 1, f64::NAN), (0, f64::INFINITY), (size / 2, 2.5)] {
        let mut mine = good(rank);
        if rank == bad {
            mine[3].0[1] = value;
            mine[7].0[0] = f64::NAN; // a later bad point: the first is reported
        }
        for root in [None, Some(unit)] {
            let mut b = DistPointTreeBuilder::new();
            let mut s = PointTreeBuilder::new();
            if let Some(r) = root {
                (b, s) = (b.root_box(r), s.root_box(r));
            }
            let got = b.build(world, &mine).unwrap_err();
            // The single-process error of the bad rank's input, by its index there.
            let mut theirs = good(bad);
            theirs[3].0[1] = value;
            theirs[7].0[0] = f64::NAN;
            let error = s.build(&theirs).unwrap_err();
            if value.is_finite() && root.is_none() {
                // 2.5 is a good point without a root box: the NaN at 7 is the first bad one
                assert!(matches!(
                    error,
                    Error::NonFiniteCoordinate {
                        index: 7,
                        axis: 0,
                        ..
                    }
                ));
            }
            assert_eq!(got, DistError::Input { rank: bad, error }, "rank {rank}");
        }
    }
    // Integers f64 cannot hold, on rank 0 only.
    let mine: Vec<([i64; 2], ())> = if rank == 0 {
        vec![([1, 2], ()), ([(1i64 << 60) + 1, 0], ())]
    } else {
        vec![([3, 4], ())]
    };
    let got = DistPointTreeBuilder::new().build(world, &mine).unwrap_err();
    assert!(matches!(
        got,
        DistError::Input {
            rank: 0,
            error: Error::InexactCoordinate {
                index: 1,
                axis: 0,
                ..
            }
        }
    ));
    // The communicator still works: a good build after the errors.
    let t = DistPointTreeBuilder::new()
        .build(world, &good(rank))
        .unwrap();
    assert_eq!(t.len(), 10 * size as u64);
}

fn settings_differ(world: &SimpleCommunicator) {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    let bucket = if rank == size - 1 && size > 1 { 3 } else { 8 };
    let got = DistPointTreeBuilder::new()
        .bucket_size(bucket)
        .build(world, &good(rank));
    if size > 1 {
        assert_eq!(
            got.unwrap_err(),
            DistError::SettingsDiffer { rank: size - 1 }
        );
    } else {
        got.unwrap();
    }
    // The same bad setting everywhere: the single-process error, from rank 0.
    let got = DistPointTreeBuilder::new()
        .bucket_size(0)
        .build(world, &good(rank))
        .unwrap_err();
    assert_eq!(
        got,
        DistError::Input {
            rank: 0,
            error: Error::ZeroBucketSize
        }
    );
    let got = DistPointTreeBuilder::new()
        .max_depth(40)
        .build(world, &good(rank))
        .unwrap_err();
    let want = PointTreeBuilder::<f64, 2>::new()
        .max_depth(40)
        .build(&good(0))
        .unwrap_err();
    assert_eq!(
        got,
        DistError::Input {
            rank: 0,
            error: want
        }
    );
}

fn bad_queries_on_one_rank(world: &SimpleCommunicator) {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    let t = DistPointTreeBuilder::new()
        .build(world, &good(rank))
        .unwrap();
    let serial = orthtree::Quadtree::new(&good(0)).unwrap();
    let bad = size - 1;
    let mut points = vec![[0.5, 0.5]; 4];
    if rank == bad {
        points[2] = [0.1, f64::NAN];
    }
    let want = serial.k_nearest(&[0.1, f64::NAN], 1).unwrap_err();
    assert!(matches!(want, QueryError::NotFinite { axis: 1, .. }));
    assert_eq!(
        t.k_nearest_batch(&points, 2).unwrap_err(),
        DistError::Query {
            rank: bad,
            index: 2,
            error: want
        }
    );
    let mut boxes = vec![Aabb::new([0.0, 0.0], [1.0, 1.0]).unwrap(); 3];
    if rank == 0 {
        boxes[1].max[0] = f64::NAN;
    }
    let got = t.in_box_batch(&boxes).unwrap_err();
    assert!(matches!(
        got,
        DistError::Query {
            rank: 0,
            index: 1,
            error: QueryError::NanBound { axis: 0 }
        }
    ));
    let mut balls = vec![([0.5, 0.5], 0.1); 5];
    if rank == bad {
        balls[4].1 = -1.0;
    }
    let want = serial.in_ball(&[0.5, 0.5], -1.0).map(|_| ()).unwrap_err();
    assert_eq!(
        t.in_ball_batch(&balls).unwrap_err(),
        DistError::Query {
            rank: bad,
            index: 4,
            error: want
        }
    );
    // The tree still answers afterwards.
    let near = t.k_nearest_batch(&[[0.0, 0.0]], 1).unwrap();
    assert_eq!(near[0][0].distance, 0.0);
}
