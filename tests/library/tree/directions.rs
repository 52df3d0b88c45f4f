//! `Direction`: how many each connectivity allows, offsets that round-trip, opposites, sums.

use orthtree::geom::Direction;
use orthtree::Connectivity;

#[test]
fn counts_and_round_trips() {
    assert_eq!(Direction::all::<1>(Connectivity::Corner).count(), 2);
    assert_eq!(Direction::all::<2>(Connectivity::Edge).count(), 8);
    assert_eq!(Direction::all::<4>(Connectivity::Corner).count(), 80);
    for d in Direction::all::<4>(Connectivity::Corner) {
        assert_eq!(Direction::from_offset(d.offset::<4>()), Some(d));
        assert_eq!(d.opposite().opposite(), d);
    }
    assert_eq!(Direction::from_offset([2, 0]), None);
    assert_eq!(Direction::from_offset([0, 0]), None);
    assert_eq!(Direction::NORTH.combine(Direction::SOUTH), None);
}
