//! Point location in a planar subdivision (exercise 14.10): faces from the half-edge structure
//! against the triangles of jittered grid triangulations; `PointLocator` against a brute-force
//! search for the triangle holding each query point; wheels (a vertex of high degree), features
//! closer than the finest cell, points outside, and refused input.

use super::workload;
use crate::common;

use common::points::config;
use orthtree::compressed::{FaceId, PointLocator, Subdivision, SubdivisionError};
use proptest::prelude::*;
use rand::Rng;

fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// The face left of the directed edge `a -> b` as the subdivision labels it.
fn face_left_of(s: &Subdivision, a: u32, b: u32) -> FaceId {
    let e = s
        .edges()
        .iter()
        .position(|x| *x == [a, b] || *x == [b, a])
        .unwrap();
    if s.edges()[e] == [a, b] {
        s.left_face(e)
    } else {
        s.right_face(e)
    }
}

proptest! {
    #![proptest_config(config(24, 901))]
    #[test]
    fn triangulations_locate_like_brute_force(k in 2usize..12, seed in any::<u64>(), queries in prop::collection::vec(proptest::array::uniform2(-1.5f64..13.0), 60)) {
        let (v, e, tri) = workload::triangulated_grid(k, seed);
        let s = Subdivision::new(v.clone(), e).unwrap();
        prop_assert_eq!(s.face_count(), tri.len() + 1);
        let faces: Vec<FaceId> = tri.iter().map(|&[a, b, c]| {
            let f = face_left_of(&s, a, b);
            assert_eq!(f, face_left_of(&s, b, c));
            assert_eq!(f, face_left_of(&s, c, a));
            f
        }).collect();
        let locator = PointLocator::new(s.clone()).unwrap();
        let exercise = PointLocator::with_exercise_rule(s.clone()).unwrap();
        prop_assert!(exercise.node_count() >= locator.node_count());
        for q in queries {
            let inside = tri.iter().position(|&[a, b, c]| {
                let [a, b, c] = [a, b, c].map(|x| v[x as usize]);
                orient(a, b, q) > 1e-9 && orient(b, c, q) > 1e-9 && orient(c, a, q) > 1e-9
            });
            let near_edge = tri.iter().any(|&[a, b, c]| {
                let [a, b, c] = [a, b, c].map(|x| v[x as usize]);
                [(a, b), (b, c), (c, a)].iter().any(|&(p, r)| orient(p, r, q).abs() <= 1e-9)
            });
            let got = locator.face(&q).unwrap();
            if !near_edge {
                prop_assert_eq!(got, exercise.face(&q).unwrap());
            }
            match inside {
                Some(t) => prop_assert_eq!(got, faces[t]),
                None if !near_edge => prop_assert_eq!(got, s.outer_face()),
                None => {}
            }
        }
    }
}

#[test]
fn a_wheel_answers_by_angle() {
    let spokes = 200;
    let mut v = vec![[0.0, 0.0]];
    let mut e = Vec::new();
    for i in 0..spokes {
        let a = i as f64 * std::f64::consts::TAU / spokes as f64;
        v.push([a.cos(), a.sin()]);
        e.push([0, i + 1]);
        e.push([i + 1, (i + 1) % spokes + 1]);
    }
    let s = Subdivision::new(v.clone(), e).unwrap();
    assert_eq!(s.face_count(), spokes as usize + 1);
    let locator = PointLocator::new(s.clone()).unwrap();
    for i in 0..spokes {
        let mid = (i as f64 + 0.5) * std::f64::consts::TAU / spokes as f64;
        for r in [1e-9, 0.01, 0.5, 0.99] {
            let q = [r * mid.cos(), r * mid.sin()];
            let want = face_left_of(&s, 0, i + 1);
            assert_eq!(locator.face(&q).unwrap(), want, "spoke {i}, r {r}");
        }
    }
    assert_eq!(locator.face(&[1.5, 0.0]).unwrap(), s.outer_face());
    assert_eq!(locator.face(&[9.0, 9.0]).unwrap(), s.outer_face());
}

#[test]
fn features_closer_than_the_finest_cell() {
    // two long edges 2^-40 apart: the tree stops at the finest cells and compares distances
    let d = (-40f64).exp2();
    let v = vec![[0.0, 0.0], [1.0, 0.0], [1.0, d], [0.0, d], [0.0, 1.0]];
    let e = vec![[0, 1], [1, 2], [2, 3], [3, 0], [3, 4], [4, 2]];
    let s = Subdivision::new(v, e).unwrap();
    let locator = PointLocator::new(s.clone()).unwrap();
    let sliver = s.left_face(0);
    let above = face_left_of(&s, 3, 2);
    assert_ne!(sliver, above);
    assert_eq!(locator.face(&[0.5, d / 2.0]).unwrap(), sliver);
    assert_eq!(locator.face(&[0.5, 2.0 * d]).unwrap(), above);
    assert_eq!(locator.face(&[0.5, -d]).unwrap(), s.outer_face());
    assert!(locator.height() <= 34);
}

#[test]
fn bad_subdivisions_are_refused_by_name() {
    let sq = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let err = |v: Vec<[f64; 2]>, e: Vec<[u32; 2]>| Subdivision::new(v, e).unwrap_err();
    assert_eq!(
        err(vec![[0.0, f64::NAN]], vec![]),
        SubdivisionError::NotFinite { vertex: 0, axis: 1 }
    );
    assert_eq!(
        err(sq.clone(), vec![[0, 4]]),
        SubdivisionError::NoSuchVertex { edge: 0, vertex: 4 }
    );
    assert_eq!(
        err(sq.clone(), vec![[1, 1]]),
        SubdivisionError::Loop { edge: 0 }
    );
    assert_eq!(
        err(sq.clone(), vec![[0, 1], [1, 2], [2, 3], [1, 0]]),
        SubdivisionError::DuplicateEdge { first: 0, edge: 3 }
    );
    assert_eq!(
        err(sq.clone(), vec![[0, 1], [2, 3]]),
        SubdivisionError::Disconnected { vertex: 2 }
    );
    assert_eq!(
        err(vec![[0.0, 0.0], [0.0, 0.0]], vec![[0, 1]]),
        SubdivisionError::DuplicateVertex {
            first: 0,
            vertex: 1
        }
    );
    // the two diagonals of the square cross
    let crossing = Subdivision::new(sq, vec![[0, 2], [1, 3], [0, 1], [1, 2]]).unwrap();
    assert!(matches!(
        PointLocator::new(crossing),
        Err(SubdivisionError::Crossing { .. })
    ));
    let one = PointLocator::new(Subdivision::new(vec![[2.0, 2.0]], vec![]).unwrap()).unwrap();
    assert_eq!(one.face(&[2.0, 2.0]).unwrap(), FaceId(0));
    assert!(one.locate(&[f64::NAN, 0.0]).is_err());
    assert!(one.face(&[0.0, f64::INFINITY]).is_err());
    assert_eq!(
        one.locate(&[2.0, 1e9]),
        Ok(orthtree::query::Location::Outside { axis: 1 })
    );
}

#[test]
fn size_and_height_of_grid_triangulations() {
    println!("k, vertices, edges, nodes, height, mean nodes + edges per query; same with the exercise's rule");
    for k in [4usize, 16, 64, 256] {
        let (v, e, _) = workload::triangulated_grid(k, 5);
        let (nv, ne) = (v.len(), e.len());
        let s = Subdivision::new(v, e).unwrap();
        let locator = PointLocator::new(s.clone()).unwrap();
        let exercise = PointLocator::with_exercise_rule(s).unwrap();
        let mean_work = |l: &PointLocator| {
            let mut rng = common::rng(6);
            let mut work = 0;
            for _ in 0..1000 {
                let q = [rng.gen_range(0.0..k as f64), rng.gen_range(0.0..k as f64)];
                work += l.locate_counted(&q).unwrap().1;
            }
            work as f64 / 1000.0
        };
        let (mean, mean_ex) = (mean_work(&locator), mean_work(&exercise));
        println!(
            "{k}, {nv}, {ne}, {}, {}, {mean:.1}; {}, {}, {mean_ex:.1}",
            locator.node_count(),
            locator.height(),
            exercise.node_count(),
            exercise.height()
        );
        assert!(locator.node_count() <= 8 * nv && exercise.node_count() <= 40 * ne);
        assert!(mean <= 2.0 * (nv as f64).log2() + 10.0);
    }
}

/// The exercise's rule on a sliver (two unit edges 2^-40 apart) stops at its square budget with a
/// typed error instead of running out of memory; the default rule builds a small tree.
#[test]
fn the_exercise_rule_refuses_slivers_by_budget() {
    let h = 2f64.powi(-40);
    let v = vec![[0.0, 0.0], [1.0, 0.0], [1.0, h], [0.0, h]];
    let e = vec![[0, 1], [1, 2], [2, 3], [3, 0]];
    let s = Subdivision::new(v, e).unwrap();
    let err = PointLocator::with_exercise_rule(s.clone()).unwrap_err();
    assert_eq!(
        err,
        SubdivisionError::TooManySquares {
            limit: 64 * 8 + 4096
        }
    );
    assert!(err.to_string().contains("PointLocator::new"));
    assert!(PointLocator::new(s).is_ok());
}
