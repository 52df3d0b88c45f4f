//! Unit tests of the exact predicates used by the validator.

use super::*;

#[test]
fn incircle_signs() {
    let (a, b, c) = ([0, 0], [2, 0], [0, 2]);
    assert!(incircle(a, b, c, [1, 1]) > 0);
    assert_eq!(incircle(a, b, c, [2, 2]), 0); // cocircular
    assert!(incircle(a, b, c, [3, 3]) < 0);
    // extreme coordinates do not overflow
    let u = 1i64 << 30;
    assert!(incircle([0, 0], [u, 0], [0, u], [u, u]) == 0);
    assert!(incircle([0, 0], [u, 0], [0, u], [1, 1]) > 0);
}

#[test]
fn boundary_sides() {
    assert_eq!(boundary_side([0, 0], [1, 0], 2), Some((0, 0, 1)));
    assert_eq!(boundary_side([1, 0], [0, 0], 2), None);
    assert_eq!(boundary_side([2, 2], [1, 2], 2), Some((2, 0, 1)));
    assert_eq!(boundary_side([0, 1], [0, 0], 2), Some((3, 1, 2)));
    assert_eq!(half(7), "3.5");
    assert_eq!(half(8), "4");
    assert_eq!(half(-1), "-0.5");
}
