//! Fuzzing both board readers (`.poly` and plain text) with proptest: random byte strings, byte
//! soup over each format's alphabet, and structure-aware mutations of valid files made by the
//! writers (bytes flipped, inserted and deleted, lines duplicated, dropped and swapped, numbers
//! replaced by extreme or malformed ones, truncation). Each case asserts that the reader returns
//! (no panic), that an error's message is short and free of control characters, and that an
//! accepted board round-trips through the writer and reader to the same board (and through the
//! other format when it can hold it).

use orthtree::io::board_text::{read_board_text_bytes, write_board_text};
use orthtree::io::poly::{read_poly_bytes, write_poly};
use orthtree::mesh::{Board, BoardError, Component, Point};
use proptest::prelude::*;
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

type Reader = fn(&[u8], Option<i64>) -> Result<Board, BoardError>;
type Writer = fn(&Board) -> String;

const POLY: (Reader, Writer) = (read_poly_bytes, poly_text);

/// `write_poly` of a board with a component (every board `.poly` reads, and every board the
/// checks below write as `.poly`, has one).
fn poly_text(board: &Board) -> String {
    write_poly(board).expect("a board with a component is written")
}
const TEXT: (Reader, Writer) = (read_board_text_bytes, write_board_text);

/// Pieces a mutation inserts or puts in place of a number.
const PIECES: &[&[u8]] = &[
    b"\0",
    b"\r",
    b"\n",
    b"\r\n",
    b"#",
    b" ",
    b"\t",
    b"-",
    b".",
    b"0",
    b"1",
    b"2",
    b"9",
    b"4.5",
    b"3.0",
    b"1e3",
    b"size",
    b"# size 32",
    b"# size: 32",
    b"1000000000000",
    b"18446744073709551616",
    b"-9223372036854775808",
    b"9223372036854775807",
    b"1073741824",
    b"\xEF\xBB\xBF",
    b"\xC2\xA0",
    b"\xFF",
    b"\xC3",
    b"(",
    b")",
    b",",
];

/// A random valid board: up to `count` squares, diamonds and triangles, one per cell of a grid
/// so that they never touch.
fn random_board(seed: u64, count: usize) -> Board {
    let mut r = SmallRng::seed_from_u64(seed);
    let size = 1i64 << r.gen_range(4..=10);
    let cells = 4i64;
    let cell = size / cells;
    let mut components = Vec::new();
    for k in 0..count.min((cells * cells) as usize) {
        let (x0, y0) = ((k as i64 % cells) * cell, (k as i64 / cells) * cell);
        let side = r.gen_range(1..=(cell - 2) / 2) * 2;
        let (x, y) = (
            x0 + 1 + r.gen_range(0..=cell - 2 - side),
            y0 + 1 + r.gen_range(0..=cell - 2 - side),
        );
        let h = side / 2;
        let outline: Vec<Point> = match r.gen_range(0..3) {
            0 => vec![[x, y], [x + side, y], [x + side, y + side], [x, y + side]],
            1 => vec![[x + h, y], [x + side, y + h], [x + h, y + side], [x, y + h]],
            _ => vec![[x, y], [x + side, y], [x, y + side]],
        };
        components.push(Component::new(outline));
    }
    Board::new(size, components).expect("the generator makes valid boards")
}

#[derive(Clone, Debug)]
enum Mutation {
    Set(usize, u8),
    Insert(usize, usize),
    Delete(usize, usize),
    DuplicateLine(usize),
    DeleteLine(usize),
    SwapLines(usize, usize),
    ReplaceNumber(usize, usize),
    Truncate(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let at = any::<usize>();
    prop_oneof![
        (at, any::<u8>()).prop_map(|(i, b)| Mutation::Set(i, b)),
        (at, 0..PIECES.len()).prop_map(|(i, p)| Mutation::Insert(i, p)),
        (at, 1usize..8).prop_map(|(i, n)| Mutation::Delete(i, n)),
        at.prop_map(Mutation::DuplicateLine),
        at.prop_map(Mutation::DeleteLine),
        (at, at).prop_map(|(a, b)| Mutation::SwapLines(a, b)),
        (at, 0..PIECES.len()).prop_map(|(i, p)| Mutation::ReplaceNumber(i, p)),
        (at, 0..PIECES.len()).prop_map(|(i, p)| Mutation::ReplaceNumber(i, p)),
        at.prop_map(Mutation::Truncate),
    ]
}

fn split_lines(bytes: &[u8]) -> Vec<Vec<u8>> {
    bytes.split(|&b| b == b'\n').map(<[u8]>::to_vec).collect()
}

fn apply(bytes: &mut Vec<u8>, m: &Mutation) {
    let len = bytes.len();
    let pick = |i: usize, n: usize| if n == 0 { 0 } else { i % n };
    match *m {
        Mutation::Set(i, b) if len > 0 => bytes[pick(i, len)] = b,
        Mutation::Insert(i, p) => {
            let at = pick(i, len + 1);
            bytes.splice(at..at, PIECES[p].iter().copied());
        }
        Mutation::Delete(i, n) if len > 0 => {
            let at = pick(i, len);
            bytes.drain(at..(at + n).min(len));
        }
        Mutation::DuplicateLine(i) | Mutation::DeleteLine(i) | Mutation::SwapLines(i, _) => {
            let mut lines = split_lines(bytes);
            let a = pick(i, lines.len());
            match *m {
                Mutation::DuplicateLine(_) => lines.insert(a, lines[a].clone()),
                Mutation::DeleteLine(_) => drop(lines.remove(a)),
                Mutation::SwapLines(_, j) => {
                    let b = pick(j, lines.len());
                    lines.swap(a, b);
                }
                _ => unreachable!(),
            }
            *bytes = lines.join(&b'\n');
        }
        Mutation::ReplaceNumber(i, p) => {
            let starts: Vec<usize> = (0..len)
                .filter(|&k| {
                    bytes[k].is_ascii_digit() && (k == 0 || !bytes[k - 1].is_ascii_digit())
                })
                .collect();
            if !starts.is_empty() {
                let start = starts[pick(i, starts.len())];
                let end = (start..len)
                    .find(|&k| !bytes[k].is_ascii_digit())
                    .unwrap_or(len);
                bytes.splice(start..end, PIECES[p].iter().copied());
            }
        }
        Mutation::Truncate(i) => bytes.truncate(pick(i, len + 1)),
        _ => {}
    }
}

fn outlines(b: &Board) -> Vec<Vec<Point>> {
    b.components().iter().map(|c| c.outline.clone()).collect()
}

/// Reads `bytes` and checks the outcome (see the module doc).
fn check(format: (Reader, Writer), bytes: &[u8], size: Option<i64>) -> Result<(), TestCaseError> {
    let (read, write) = format;
    match read(bytes, size) {
        Ok(board) => {
            let text = write(&board);
            let back = read(text.as_bytes(), None)
                .map_err(|e| TestCaseError::fail(format!("{text:?} does not read back: {e}")))?;
            prop_assert_eq!(back.size(), board.size());
            prop_assert_eq!(outlines(&back), outlines(&board));
            prop_assert_eq!(write(&back), text);
            // the other format, when it can hold the board (.poly needs a component)
            if !board.components().is_empty() {
                for (read, write) in [POLY, TEXT] {
                    let other = read(write(&board).as_bytes(), Some(board.size()))
                        .map_err(|e| TestCaseError::fail(e.to_string()))?;
                    prop_assert_eq!(outlines(&other), outlines(&board));
                }
            }
        }
        Err(e) => {
            let message = e.to_string();
            prop_assert!(message.len() < 600, "{} bytes: {}", message.len(), message);
            prop_assert!(!message.chars().any(char::is_control), "{:?}", message);
        }
    }
    Ok(())
}

fn size_argument() -> impl Strategy<Value = Option<i64>> {
    prop_oneof![
        6 => Just(None),
        1 => (0u32..12).prop_map(|j| Some(1i64 << j)),
        1 => prop_oneof![Just(0i64), Just(-1), Just(3), Just(i64::MAX)].prop_map(Some),
    ]
}

fn byte_soup(alphabet: &'static [u8]) -> impl Strategy<Value = Vec<u8>> {
    prop::collection::vec(prop::sample::select(alphabet), 0..300)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn mutated_poly_files(
        seed in any::<u64>(),
        count in 1usize..10,
        mutations in prop::collection::vec(mutation(), 1..6),
        size in size_argument(),
    ) {
        let mut bytes = poly_text(&random_board(seed, count)).into_bytes();
        for m in &mutations {
            apply(&mut bytes, m);
        }
        check(POLY, &bytes, size)?;
    }

    #[test]
    fn mutated_text_files(
        seed in any::<u64>(),
        count in 0usize..10,
        mutations in prop::collection::vec(mutation(), 1..6),
        size in size_argument(),
    ) {
        let mut bytes = write_board_text(&random_board(seed, count)).into_bytes();
        for m in &mutations {
            apply(&mut bytes, m);
        }
        check(TEXT, &bytes, size)?;
    }

    #[test]
    fn random_bytes(bytes in prop::collection::vec(any::<u8>(), 0..400), size in size_argument()) {
        check(POLY, &bytes, size)?;
        check(TEXT, &bytes, size)?;
    }

    #[test]
    fn byte_soup_of_the_formats(
        poly in byte_soup(b"0123 \n\n\n#-.\r\t"),
        text in byte_soup(b"01234 \n\n#-.(),size"),
    ) {
        check(POLY, &poly, None)?;
        check(TEXT, &text, None)?;
    }
}

/// The writers' files themselves read back unchanged (the mutations start from these).
#[test]
fn unmutated_files_round_trip() {
    for seed in 0..50 {
        for count in [0usize, 1, 5, 16] {
            let board = random_board(seed, count);
            let text = write_board_text(&board);
            let b = read_board_text_bytes(text.as_bytes(), None).unwrap();
            assert_eq!((b.size(), outlines(&b)), (board.size(), outlines(&board)));
            assert_eq!(write_board_text(&b), text);
            if count > 0 {
                let poly = poly_text(&board);
                let b = read_poly_bytes(poly.as_bytes(), None).unwrap();
                assert_eq!(outlines(&b), outlines(&board));
                assert_eq!(poly_text(&b), poly);
            }
        }
    }
}
