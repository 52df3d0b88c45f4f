//! `Cell`: the deepest level per dimension, keys that round-trip, preorder, ancestors and
//! neighbours.

use orthtree::geom::{Cell, Direction};

#[test]
fn max_levels() {
    assert_eq!(Cell::<1>::MAX_LEVEL, 32);
    assert_eq!(Cell::<2>::MAX_LEVEL, 32);
    assert_eq!(Cell::<3>::MAX_LEVEL, 21);
    assert_eq!(Cell::<8>::MAX_LEVEL, 8);
}

#[test]
fn keys_round_trip_and_order_is_preorder() {
    let root = Cell::<3>::root();
    let c = root.child(5).child(3).child(6);
    assert_eq!(Cell::from_aligned_key(c.aligned_key(), 3), c);
    assert!(root < root.child(0));
    assert!(root.child(0) < root.child(0).child(7));
    assert!(root.child(0).child(7) < root.child(1));
    assert_eq!(c.ancestor(1), root.child(5));
    assert_eq!(root.child(1).neighbor(Direction::face(0, true)), None);
    assert_eq!(
        c.neighbor(Direction::face(0, true)).unwrap().coords(),
        [7, 3, 5]
    );
    let deep = Cell::<2>::new(32, [u32::MAX, 0]).unwrap();
    assert_eq!(deep.span(0), (u32::MAX as u64, 1 << 32));
    assert_eq!(Cell::<2>::new(33, [0, 0]), None);
    assert_eq!(Cell::<2>::new(2, [4, 0]), None);
}
