//! `try_random_board` on hostile arguments: sizes that are not powers of two from 8 to 2^30 and
//! counts above the capacity `(U / 2)^2` are refused with a typed error naming them, before
//! anything is allocated; counts that fill the board early cost memory by the board placed,
//! never by the count asked (checked with a counting allocator).

use crate::counting::peak_bytes;
use orthtree::mesh::{random_board, random_board_capacity, try_random_board, RandomBoardError};

#[test]
fn sizes_that_are_not_powers_of_two_from_8_to_2_30_are_refused() {
    for size in [
        i64::MIN,
        -8,
        0,
        1,
        2,
        4,
        7,
        12,
        1000,
        (1 << 30) + 1,
        1 << 31,
        i64::MAX,
    ] {
        let e = try_random_board(0, size, 5).unwrap_err();
        assert_eq!(e, RandomBoardError::SizeNotPowerOfTwo { size });
        assert!(e.to_string().contains(&size.to_string()), "{e}");
    }
    for level in 3..=30 {
        assert!(try_random_board(0, 1 << level, 1).is_ok(), "U = 2^{level}");
    }
}

#[test]
fn counts_above_the_capacity_are_refused_without_allocating() {
    for (size, count) in [
        (8i64, 17usize),
        (8, 500),
        (16, 65),
        (1 << 10, 1 << 18 | 1),
        (1 << 20, usize::MAX),
        (1 << 30, usize::MAX),
    ] {
        let capacity = random_board_capacity(size);
        assert_eq!(capacity, ((size / 2) * (size / 2)) as u64);
        let (result, bytes) = peak_bytes(|| try_random_board(1, size, count));
        let e = result.unwrap_err();
        assert_eq!(
            e,
            RandomBoardError::TooManyComponents {
                count,
                size,
                capacity
            }
        );
        let message = e.to_string();
        for named in [count.to_string(), size.to_string(), capacity.to_string()] {
            assert!(message.contains(&named), "{message} names {named}");
        }
        assert!(
            bytes < 1024,
            "U = {size}, count {count}: {bytes} bytes allocated"
        );
    }
}

#[test]
fn counts_at_the_capacity_give_a_valid_board_with_fewer_components() {
    for (seed, size) in [(0u64, 8i64), (1, 16), (2, 32), (3, 64)] {
        let count = random_board_capacity(size) as usize;
        let board = try_random_board(seed, size, count).unwrap();
        assert!(!board.components().is_empty());
        assert!(
            board.components().len() < count,
            "U = {size} fills up early"
        );
        assert_eq!(board, random_board(seed, size, count), "the twins agree");
    }
}

#[test]
fn memory_follows_the_board_placed_not_the_count_asked() {
    // Counts at the capacity, which random shapes never reach: the peak (outlines, boxes and
    // `Board::new`'s check, measured about 1.35 KB per component) is bounded by the components
    // placed, whatever the count asked for.
    for (seed, size) in [(4u64, 512i64), (5, 256), (6, 1024), (7, 64)] {
        let count = random_board_capacity(size) as usize;
        let (board, bytes) = peak_bytes(|| try_random_board(seed, size, count).unwrap());
        let placed = board.components().len();
        assert!(placed < count / 4, "U = {size}: {placed} of {count} placed");
        assert!(
            bytes < 2000 * placed + 65536,
            "U = {size}: {bytes} bytes at peak for {placed} components"
        );
    }
}

#[test]
fn the_panicking_twin_names_the_refusal() {
    for (size, count, expected) in [
        (12i64, 5usize, "not a power of two"),
        (8, 17, "17 components cannot fit a board of size 8"),
    ] {
        let panic = std::panic::catch_unwind(|| random_board(0, size, count)).unwrap_err();
        let message = panic.downcast_ref::<String>().cloned().unwrap_or_default();
        assert!(message.contains(expected), "{message}");
    }
}
