//! The k-nearest joins' copy compiled for newer x86-64 processors (see `cpu.rs`) against the
//! baseline copy, on the point trees of this layer: the query layer holds the check
//! ([`assert_copies_agree`]) but may not name the trees.

use super::{DynamicPointTree, PointTree};
use crate::query::assert_copies_agree;
use rand::{rngs::SmallRng, Rng, SeedableRng};

#[test]
fn the_fast_copy_fills_the_baseline_rows() {
    let mut rng = SmallRng::seed_from_u64(11);
    let mut pts: Vec<([f64; 3], usize)> = (0..3000)
        .map(|i| (core::array::from_fn(|_| rng.gen_range(-1.0..1.0)), i))
        .collect();
    // duplicates and points on a grid (ties, split lines)
    for i in 0..600 {
        let p = if i % 2 == 0 {
            pts[rng.gen_range(0..pts.len())].0
        } else {
            core::array::from_fn(|_| f64::from(rng.gen_range(-4i8..=4)) / 4.0)
        };
        pts.push((p, 3000 + i));
    }
    for k in [1, 7, 16] {
        let tree = PointTree::new(&pts).unwrap();
        assert_copies_agree(&tree, k);
        assert_copies_agree(&DynamicPointTree::from(tree), k);
    }
}
