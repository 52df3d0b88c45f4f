//! The rayon feature's point-tree entry points against their serial counterparts: `par_build`
//! gives the same tree and the same errors as `build`; the batch queries give, query by query,
//! what the serial queries give, and those agree with brute force (`points::queries`).
#![cfg(feature = "rayon")]

use orthtree::prelude::*;
use orthtree::query::Ball;
use orthtree::{Aabb, Error, PointTree};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

fn same_tree<const D: usize>(a: &PointTree<f64, u32, D>, b: &PointTree<f64, u32, D>) {
    assert_eq!(a.points(), b.points());
    assert_eq!(a.items(), b.items());
    assert_eq!(a.geometry(), b.geometry());
    assert!(a
        .leaves()
        .map(|l| (l.cell, l.points.len()))
        .eq(b.leaves().map(|l| (l.cell, l.points.len()))));
    b.validate().unwrap();
}

fn coordinate() -> impl Strategy<Value = f64> {
    // grid values (on split lines, repeated) and arbitrary ones
    prop_oneof![(0u8..=16).prop_map(|g| f64::from(g) / 16.0), -1e6f64..1e6]
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 48,
        rng_seed: RngSeed::Fixed(0x9a7a_11e1),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn par_build_equals_build(
        pts in proptest::collection::vec(proptest::array::uniform2(coordinate()), 0..3000),
        bucket in 1usize..20,
    ) {
        let entries: Vec<([f64; 2], u32)> =
            pts.iter().enumerate().map(|(i, &p)| (p, i as u32)).collect();
        let b = PointTree::builder().bucket_size(bucket);
        same_tree(&b.build(&entries).unwrap(), &b.par_build(&entries).unwrap());
    }
}

#[test]
fn par_build_on_large_inputs_with_duplicates() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand::rngs::SmallRng::seed_from_u64(3);
    // 200 000 points, each 8 times: the sort's parallel runs, long runs of equal keys
    let base: Vec<[f64; 3]> = (0..25_000)
        .map(|_| [rng.r#gen(), rng.r#gen(), rng.r#gen()])
        .collect();
    let entries: Vec<([f64; 3], u32)> = (0..200_000)
        .map(|i| (base[i % base.len()], i as u32))
        .collect();
    let b = PointTree::builder();
    same_tree(&b.build(&entries).unwrap(), &b.par_build(&entries).unwrap());
    // one cluster in a tiny corner of a given root box: leading key bytes all equal
    let root = Aabb::new([0.0; 3], [1.0; 3]).unwrap();
    let tiny: Vec<([f64; 3], u32)> = (0..100_000)
        .map(|i| {
            (
                [1e-9 * rng.r#gen::<f64>(), 1e-9 * rng.r#gen::<f64>(), 0.0],
                i,
            )
        })
        .collect();
    let b = PointTree::builder().root_box(root);
    same_tree(&b.build(&tiny).unwrap(), &b.par_build(&tiny).unwrap());
}

#[test]
fn par_build_reports_the_first_bad_point() {
    let mut entries: Vec<([f64; 2], u32)> = (0..300_000).map(|i| ([i as f64, 0.0], i)).collect();
    entries[250_000].0[1] = f64::NAN;
    entries[100_000].0[0] = f64::INFINITY;
    let b = PointTree::builder();
    let (serial, parallel) = (
        b.build(&entries).unwrap_err(),
        b.par_build(&entries).unwrap_err(),
    );
    assert!(matches!(
        parallel,
        Error::NonFiniteCoordinate {
            index: 100_000,
            axis: 0,
            ..
        }
    ));
    assert_eq!(serial.to_string(), parallel.to_string());
    let root = Aabb::new([0.0, 0.0], [1000.0, 1.0]).unwrap();
    let b = PointTree::builder().root_box(root);
    let parallel = b.par_build(&entries[..5000]).unwrap_err();
    assert!(matches!(
        parallel,
        Error::OutsideRootBox {
            index: 1001,
            axis: 0,
            ..
        }
    ));
}

#[test]
fn batch_queries_equal_serial_queries() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand::rngs::SmallRng::seed_from_u64(5);
    let entries: Vec<([f64; 2], u32)> = (0..20_000)
        .map(|i| ([rng.r#gen(), rng.r#gen()], i))
        .collect();
    let t = PointTree::builder().par_build(&entries).unwrap();
    let queries: Vec<[f64; 2]> = (0..500).map(|_| [rng.r#gen(), rng.r#gen()]).collect();
    let batch = t.par_k_nearest(&queries, 7).unwrap();
    for (q, answer) in queries.iter().zip(&batch) {
        let serial = t.k_nearest(q, 7).unwrap();
        assert!(answer
            .iter()
            .map(|n| n.index)
            .eq(serial.iter().map(|n| n.index)));
    }
    let balls: Vec<Ball<2>> = queries
        .iter()
        .map(|&q| Ball::new(q, 0.02).unwrap())
        .collect();
    let counts = t.par_query_count(&balls).unwrap();
    let found = t.par_query_indices(&balls).unwrap();
    for ((ball, &count), indices) in balls.iter().zip(&counts).zip(&found) {
        assert_eq!(count, t.query_count(ball).unwrap());
        let mut brute: Vec<usize> = (0..t.len())
            .filter(|&i| {
                let p = t.points()[i];
                (p[0] - ball.center[0]).powi(2) + (p[1] - ball.center[1]).powi(2) <= 0.02 * 0.02
            })
            .collect();
        brute.sort_unstable();
        assert_eq!(indices, &brute);
        assert_eq!(indices.len(), count);
    }
    // the first bad query is named
    let mut bad = queries.clone();
    bad[300] = [0.5, f64::NAN];
    bad[400] = [f64::INFINITY, 0.5];
    assert_eq!(t.par_k_nearest(&bad, 3).unwrap_err().index, 300);
    assert!(t.par_k_nearest(&[], 3).unwrap().is_empty());
}
