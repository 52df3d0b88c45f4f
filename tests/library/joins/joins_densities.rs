//! The k-nearest joins on points whose density changes by orders of magnitude from one place to
//! the next (tight clusters beside sparse ones, a dense surface beside far outliers), against
//! nested loops: a group of the querying tree tries first the radius its neighbouring group
//! needed, so these sets make it gather its candidates again, once or several times, and fall
//! back on a radius taken from the tree. Every row must still be the single-tree answer and the
//! brute-force distances, serially and on rayon's threads, for every kind of tree.

use super::{check_knn, entries};
use orthtree::prelude::*;
use orthtree::{CompressedTree, DynamicPointTree, PointTree};
use proptest::prelude::*;
use rand::Rng;

/// Clusters of 1 to 80 points around centres of the unit cube, each with its own spread from 1
/// down to 1e-6 (and some exactly on their centre: duplicates).
fn clusters<const D: usize>() -> impl Strategy<Value = Vec<[f64; D]>> {
    let cluster = (
        proptest::array::uniform::<_, D>(0.0f64..1.0),
        0i32..7,
        1usize..80,
        any::<u64>(),
    );
    prop::collection::vec(cluster, 1..6).prop_map(|cs| {
        let mut out = Vec::new();
        for (centre, e, n, seed) in cs {
            let mut rng = crate::common::rng(seed);
            let spread = if e == 6 { 0.0 } else { 10f64.powi(-e) };
            for _ in 0..n {
                out.push(core::array::from_fn(|a| {
                    centre[a] + spread * (rng.r#gen::<f64>() - 0.5)
                }));
            }
        }
        out
    })
}

/// The self-join and the join of `pa` in `pb` on point trees of two bucket sizes, a dynamic
/// tree and a compressed tree, for several `k`, against nested loops; the parallel forms equal
/// to the serial ones.
fn check_every_tree<const D: usize>(pa: &[[f64; D]], pb: &[[f64; D]]) {
    let (ea, eb) = (entries(pa), entries(pb));
    let a = PointTree::new(&ea).unwrap();
    let small = PointTree::builder().bucket_size(2).build(&ea).unwrap();
    let b = CompressedTree::new(&eb).unwrap();
    let db = DynamicPointTree::from(PointTree::new(&eb).unwrap());
    for k in [1, 5, 16, 40] {
        check_knn(&a, pa, &a, pa, k, true);
        check_knn(&small, pa, &small, pa, k, true);
        check_knn(&a, pa, &b, pb, k, false);
        check_knn(&small, pa, &db, pb, k, false);
        check_knn(&b, pb, &b, pb, k, true);
        #[cfg(feature = "rayon")]
        {
            assert_eq!(a.par_k_nearest_self(k), a.k_nearest_self(k));
            assert_eq!(small.par_k_nearest_join(&b, k), small.k_nearest_join(&b, k));
            assert_eq!(db.par_k_nearest_self(k), db.k_nearest_self(k));
        }
    }
}

proptest! {
    #![proptest_config(crate::common::points::config(24, 2114))]

    #[test]
    fn knn_joins_over_changing_densities_equal_nested_loops_3d(
        pa in clusters::<3>(),
        pb in clusters::<3>(),
    ) {
        check_every_tree(&pa, &pb);
    }

    #[test]
    fn knn_joins_over_changing_densities_equal_nested_loops_2d(
        pa in clusters::<2>(),
        pb in clusters::<2>(),
    ) {
        check_every_tree(&pa, &pb);
    }
}

#[test]
fn knn_joins_on_a_dense_surface_with_far_outliers_equal_nested_loops() {
    let mut rng = crate::common::rng(2115);
    let mut pa: Vec<[f64; 3]> = (0..700)
        .map(|_| {
            let (x, y): (f64, f64) = (rng.r#gen(), rng.r#gen());
            [
                x,
                y,
                0.5 + 0.1 * (6.0 * x).sin() + 1e-3 * rng.r#gen::<f64>(),
            ]
        })
        .collect();
    // a few points far off the surface, alone in their cells, and a pile of duplicates
    pa.extend((0..12).map(|i| [f64::from(i) * 0.09, 0.95, 0.05]));
    pa.extend(core::iter::repeat_n([0.25, 0.25, 0.5], 30));
    let pb: Vec<[f64; 3]> = pa
        .iter()
        .step_by(3)
        .map(|p| [p[0], p[1], 1.0 - p[2]])
        .collect();
    check_every_tree(&pa, &pb);
}
