//! An update after `PointTree::balance` drops the refinement: the tree equals one built fresh.

use orthtree::query::{PointSet, PointSetMut};
use orthtree::{Aabb, Connectivity, Quadtree};

#[test]
fn updates_after_balance_drop_the_refinement() {
    let pts: Vec<([f64; 2], u32)> = (0..40)
        .map(|i| ([(i as f64 * 0.37) % 1.0, (i as f64 * 0.61) % 1.0], i))
        .collect();
    let root = Aabb::new([0.0, 0.0], [1.0, 1.0]).unwrap();
    let b = Quadtree::builder().root_box(root).bucket_size(2);
    let mut t = b.build(&pts).unwrap();
    t.balance(Connectivity::Corner);
    assert!(t.remove(&pts[3].0, &3));
    t.validate().unwrap();
    let fresh = b
        .build(&pts.iter().filter(|p| p.1 != 3).copied().collect::<Vec<_>>())
        .unwrap();
    let cells = |t: &Quadtree<u32>| t.leaves().map(|l| l.cell).collect::<Vec<_>>();
    assert_eq!(cells(&t), cells(&fresh));
    assert!(!t.remove(&[0.5, 0.5], &99));
    assert_eq!(t.remove_point(&[f64::NAN, 0.0]), None);
    assert_eq!(t.remove_point(&[7.0, 0.0]), None);
}
