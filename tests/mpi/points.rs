//! The distributed point tree against a single-process tree over the union of every rank's
//! input (rank 0's first): the same points in the same order, split by counts, and the same
//! answers to box, ball and k-nearest queries issued on every rank, ties included: uniform
//! and clustered points, duplicates on split lines, all points on one rank, empty ranks, no
//! points at all, integer and `f32` coordinates, D = 1, 2 and 3.

use super::Check;
use bytemuck::Pod;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use orthtree::dist::{DistNeighbor, DistPointTreeBuilder};
use orthtree::points::PointTreeBuilder;
use orthtree::prelude::*;
use orthtree::{Aabb, PointTree, Scalar};
use rand::{rngs::SmallRng, Rng, SeedableRng};
use std::fmt::Debug;

pub const CHECKS: &[Check] = &[
    ("points::uniform_2d", uniform_2d),
    ("points::lattice_duplicates", lattice_duplicates),
    ("points::all_on_one_rank", all_on_one_rank),
    ("points::fewer_points_than_ranks", fewer_points_than_ranks),
    ("points::integer_3d_root_box", integer_3d_root_box),
    ("points::clustered_f32_3d", clustered_f32_3d),
    ("points::line_1d", line_1d),
];

/// One case: every rank's input (each rank computes all of them from the seeds), settings,
/// and each rank's queries.
struct Case<S, T, const D: usize> {
    inputs: Vec<Vec<([S; D], T)>>,
    bucket_size: usize,
    max_depth: Option<u8>,
    root: Option<Aabb<S, D>>,
    points: Vec<[S; D]>,
    boxes: Vec<Aabb<S, D>>,
    balls: Vec<([S; D], f64)>,
}

/// Builds the case distributed and on one process and compares every answer.
fn compare<S, T, const D: usize>(world: &SimpleCommunicator, case: &Case<S, T, D>)
where
    S: Scalar + Pod + Debug,
    T: Pod + Debug + PartialEq,
{
    let rank = world.rank() as usize;
    let mut dist = DistPointTreeBuilder::new().bucket_size(case.bucket_size);
    let mut serial = PointTreeBuilder::new().bucket_size(case.bucket_size);
    if let Some(d) = case.max_depth {
        (dist, serial) = (dist.max_depth(d), serial.max_depth(d));
    }
    if let Some(r) = case.root {
        (dist, serial) = (dist.root_box(r), serial.root_box(r));
    }
    let union: Vec<([S; D], T)> = case.inputs.iter().flatten().copied().collect();
    let serial = serial.build(&union).unwrap();
    let t = dist.build(world, &case.inputs[rank]).unwrap();
    t.validate().unwrap();
    serial.validate().unwrap();
    assert_eq!(t.len(), union.len() as u64);
    assert_eq!(t.geometry().root_box(), serial.geometry().root_box());
    let range = t.partition().range(rank);
    let range = range.start as usize..range.end as usize;
    assert_eq!(t.local().points(), &serial.points()[range.clone()]);
    assert_eq!(t.local().items(), &serial.items()[range]);
    // counts evened out
    let counts: Vec<u64> = (0..t.partition().ranks())
        .map(|r| t.partition().count(r))
        .collect();
    assert!(
        counts.iter().max().unwrap() - counts.iter().min().unwrap() <= 1,
        "{counts:?}"
    );

    // k = 0 (empty answers) and more than the union holds (every point) too
    for k in [0, 1, 4, 13, union.len() + 2] {
        let answers = t.k_nearest_batch(&case.points, k).unwrap();
        assert_eq!(answers.len(), case.points.len());
        for (q, got) in case.points.iter().zip(&answers) {
            let want = serial.k_nearest(q, k).unwrap();
            assert_eq!(got.len(), want.len(), "k {k} at {q:?}");
            for (g, w) in got.iter().zip(&want) {
                assert_eq!(
                    (g.slot, g.distance, &g.point, &g.item),
                    (w.index as u64, w.distance, w.point, w.item),
                    "k {k} at {q:?}"
                );
            }
        }
    }
    let answers = t.in_box_batch(&case.boxes).unwrap();
    for (b, got) in case.boxes.iter().zip(&answers) {
        let want = serial.in_box(b).unwrap().map(|(p, i)| (*p, *i));
        same_points(&serial, want, got, &format!("box {b:?}"));
    }
    let answers = t.in_ball_batch(&case.balls).unwrap();
    for ((c, r), got) in case.balls.iter().zip(&answers) {
        let want = serial.in_ball(c, *r).unwrap().map(|(p, i)| (*p, *i));
        same_points(&serial, want, got, &format!("ball {c:?} {r}"));
        for n in got {
            let d: f64 = (0..D)
                .map(|a| (n.point[a].to_f64() - c[a].to_f64()).powi(2))
                .sum();
            assert!((n.distance - d).abs() <= 1e-12 * d.max(1.0));
            assert!(n.distance <= r * r * (1.0 + 1e-12));
        }
    }
}

/// A range answer holds the single-process answer's points and items (the serial engine's
/// order is its traversal's: compared as multisets), each at its global slot, in slot order.
fn same_points<S: Scalar + Pod, T: Pod + PartialEq, const D: usize>(
    serial: &PointTree<S, T, D>,
    want: impl Iterator<Item = ([S; D], T)>,
    got: &[DistNeighbor<S, T, D>],
    what: &str,
) {
    let bytes = |(p, i): ([S; D], T)| {
        let mut b: Vec<u8> = p
            .iter()
            .flat_map(|c| bytemuck::bytes_of(c).to_vec())
            .collect();
        b.extend_from_slice(bytemuck::bytes_of(&i));
        b
    };
    let mut want: Vec<Vec<u8>> = want.map(bytes).collect();
    let mut found: Vec<Vec<u8>> = got.iter().map(|n| bytes((n.point, n.item))).collect();
    want.sort();
    found.sort();
    assert!(
        want == found,
        "{what}: {} points, {} expected",
        found.len(),
        want.len()
    );
    for n in got {
        let s = n.slot as usize;
        assert!(
            serial.points()[s] == n.point && serial.items()[s] == n.item,
            "{what}"
        );
    }
    assert!(
        got.windows(2).all(|w| w[0].slot < w[1].slot),
        "{what}: slot order"
    );
}

/// Query points, boxes and balls (centre, radius).
type Queries<const D: usize> = (Vec<[f64; D]>, Vec<Aabb<f64, D>>, Vec<([f64; D], f64)>);

/// Queries for rank `rank`: a different number on each rank, some at input points (ties),
/// some outside the points' box.
fn queries<const D: usize>(
    rng: &mut SmallRng,
    rank: usize,
    lo: f64,
    hi: f64,
    at: &[[f64; D]],
) -> Queries<D> {
    let span = hi - lo;
    let point = |rng: &mut SmallRng| -> [f64; D] {
        core::array::from_fn(|_| rng.gen_range(lo - 0.1 * span..hi + 0.1 * span))
    };
    let n = 5 + 3 * rank;
    let mut points: Vec<[f64; D]> = (0..n).map(|_| point(rng)).collect();
    points.extend(at.iter().take(4));
    let boxes = (0..n)
        .map(|_| {
            let (a, b) = (point(rng), point(rng));
            Aabb::new(
                core::array::from_fn(|i| a[i].min(b[i])),
                core::array::from_fn(|i| a[i].max(b[i])),
            )
            .unwrap()
        })
        .collect();
    let balls = (0..n)
        .map(|_| (point(rng), rng.gen_range(0.0..0.3 * span)))
        .collect();
    (points, boxes, balls)
}

/// Rank r's count in a seeded case: some ranks empty.
fn count(rng: &mut SmallRng, max: usize) -> usize {
    if rng.gen_bool(0.2) {
        0
    } else {
        rng.gen_range(0..max)
    }
}

fn uniform_2d(world: &SimpleCommunicator) {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    for seed in 0..6u64 {
        let inputs: Vec<Vec<([f64; 2], u32)>> = (0..size)
            .map(|r| {
                let mut rng = SmallRng::seed_from_u64(seed * 100 + r as u64);
                let n = count(&mut rng, 3000);
                (0..n)
                    .map(|i| ([rng.r#gen(), rng.r#gen()], (r * 100_000 + i) as u32))
                    .collect()
            })
            .collect();
        let mut rng = SmallRng::seed_from_u64(seed * 7 + rank as u64);
        let at: Vec<[f64; 2]> = inputs.iter().flatten().map(|e| e.0).take(4).collect();
        let (points, boxes, balls) = queries(&mut rng, rank, 0.0, 1.0, &at);
        compare(
            world,
            &Case {
                inputs,
                bucket_size: 1 + seed as usize * 5,
                max_depth: None,
                root: None,
                points,
                boxes,
                balls,
            },
        );
    }
}

fn lattice_duplicates(world: &SimpleCommunicator) {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    for seed in 0..4u64 {
        // Coordinates on the split lines of a unit root box, many copies of each point.
        let inputs: Vec<Vec<([f64; 2], u64)>> = (0..size)
            .map(|r| {
                let mut rng = SmallRng::seed_from_u64(seed * 31 + r as u64);
                let n = count(&mut rng, 800);
                (0..n)
                    .map(|i| {
                        let p = [
                            rng.gen_range(0..5) as f64 / 4.0,
                            rng.gen_range(0..5) as f64 / 4.0,
                        ];
                        (p, (r * 10_000 + i) as u64)
                    })
                    .collect()
            })
            .collect();
        let mut rng = SmallRng::seed_from_u64(seed + 99 * rank as u64);
        let at = [[0.5, 0.5], [0.25, 0.75], [0.0, 1.0], [0.375, 0.5]];
        let (points, boxes, mut balls) = queries(&mut rng, rank, 0.0, 1.0, &at);
        balls.push(([0.5, 0.5], 0.25)); // the lattice neighbours on the boundary
        compare(
            world,
            &Case {
                inputs,
                bucket_size: 3,
                max_depth: Some(4 + seed as u8),
                root: Some(Aabb::new([0.0, 0.0], [1.0, 1.0]).unwrap()),
                points,
                boxes,
                balls,
            },
        );
    }
}

fn all_on_one_rank(world: &SimpleCommunicator) {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    for holder in [0, size - 1] {
        let inputs: Vec<Vec<([f64; 2], u32)>> = (0..size)
            .map(|r| {
                let mut rng = SmallRng::seed_from_u64(5 + r as u64);
                let n = if r == holder { 5000 } else { 0 };
                (0..n)
                    .map(|i| ([rng.gen_range(-3.0..5.0), rng.r#gen()], i as u32))
                    .collect()
            })
            .collect();
        let mut rng = SmallRng::seed_from_u64(11 + rank as u64);
        let (points, boxes, balls) = queries(&mut rng, rank, -3.0, 5.0, &[]);
        compare(
            world,
            &Case {
                inputs,
                bucket_size: 16,
                max_depth: None,
                root: None,
                points,
                boxes,
                balls,
            },
        );
    }
}

fn fewer_points_than_ranks(world: &SimpleCommunicator) {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    for total in [0usize, 1, 2, 3] {
        let inputs: Vec<Vec<([f64; 2], u32)>> = (0..size)
            .map(|r| {
                (0..total)
                    .filter(|i| i % size == r)
                    .map(|i| ([i as f64, 1.0 - i as f64], i as u32))
                    .collect()
            })
            .collect();
        let mut rng = SmallRng::seed_from_u64(rank as u64);
        let (points, boxes, balls) = queries(&mut rng, rank, 0.0, 3.0, &[]);
        compare(
            world,
            &Case {
                inputs,
                bucket_size: 1,
                max_depth: None,
                root: None,
                points,
                boxes,
                balls,
            },
        );
    }
}

fn integer_3d_root_box(world: &SimpleCommunicator) {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    for seed in 0..3u64 {
        let inputs: Vec<Vec<([i32; 3], [u16; 3])>> = (0..size)
            .map(|r| {
                let mut rng = SmallRng::seed_from_u64(seed * 13 + r as u64);
                let n = count(&mut rng, 1500);
                (0..n)
                    .map(|i| {
                        let p = [0; 3].map(|_: i32| rng.gen_range(-64..=64));
                        (p, [r as u16, i as u16, 7])
                    })
                    .collect()
            })
            .collect();
        let mut rng = SmallRng::seed_from_u64(seed * 5 + rank as u64);
        let (p, b, l) = queries(&mut rng, rank, -64.0, 64.0, &[[0.0; 3], [32.0, -32.0, 0.0]]);
        let round = |x: f64| x.round() as i32;
        compare(
            world,
            &Case {
                inputs,
                bucket_size: 8,
                max_depth: None,
                root: Some(Aabb::new([-64; 3], [64; 3]).unwrap()),
                points: p.iter().map(|q| q.map(round)).collect(),
                boxes: b
                    .iter()
                    .map(|b| Aabb::new(b.min.map(round), b.max.map(round)).unwrap())
                    .collect(),
                balls: l.iter().map(|(c, r)| (c.map(round), *r)).collect(),
            },
        );
    }
}

fn clustered_f32_3d(world: &SimpleCommunicator) {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    let centres: [[f32; 3]; 3] = [[0.1, 0.1, 0.1], [0.8, 0.2, 0.5], [0.5, 0.9, 0.9]];
    let inputs: Vec<Vec<([f32; 3], f32)>> = (0..size)
        .map(|r| {
            let mut rng = SmallRng::seed_from_u64(77 + r as u64);
            let n = count(&mut rng, 2500);
            (0..n)
                .map(|i| {
                    let c = centres[i % 3];
                    let p = c.map(|x| x + rng.gen_range(-0.01f32..0.01));
                    (p, i as f32)
                })
                .collect()
        })
        .collect();
    let mut rng = SmallRng::seed_from_u64(3 + rank as u64);
    let (p, b, l) = queries(&mut rng, rank, 0.0, 1.0, &[[0.1; 3], [0.8, 0.2, 0.5]]);
    compare(
        world,
        &Case {
            inputs,
            bucket_size: 10,
            max_depth: None,
            root: None,
            points: p.iter().map(|q| q.map(|x| x as f32)).collect(),
            boxes: b
                .iter()
                .map(|b| Aabb::new(b.min.map(|x| x as f32), b.max.map(|x| x as f32)).unwrap())
                .collect(),
            balls: l.iter().map(|(c, r)| (c.map(|x| x as f32), *r)).collect(),
        },
    );
}

fn line_1d(world: &SimpleCommunicator) {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    let inputs: Vec<Vec<([f64; 1], u8)>> = (0..size)
        .map(|r| {
            (0..300)
                .map(|i| ([((i * 7 + r * 3) % 50) as f64], r as u8))
                .collect()
        })
        .collect();
    let mut rng = SmallRng::seed_from_u64(rank as u64);
    let (points, boxes, balls) = queries(&mut rng, rank, 0.0, 50.0, &[[10.0], [25.0]]);
    compare(
        world,
        &Case {
            inputs,
            bucket_size: 2,
            max_depth: None,
            root: None,
            points,
            boxes,
            balls,
        },
    );
}
