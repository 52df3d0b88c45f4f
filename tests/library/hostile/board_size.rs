//! The board's side U when read from a file: a size given by both the file and the caller must
//! agree, an invalid size (zero, negative, not a power of two, above 2^30) is refused wherever it
//! comes from, and given by neither U is guessed from the coordinates. Both readers and
//! `read_board_file`.

use orthtree::io::board_text::read_board_text;
use orthtree::io::poly::read_poly;
use orthtree::io::read_board_file;
use orthtree::mesh::{Board, BoardError};

/// A one-square board in each format, with a size line (`# size U`, `size U`) first when given.
fn poly(size: Option<i64>) -> String {
    let head = size.map_or(String::new(), |u| format!("# size {u}\n"));
    format!("{head}4 2 0 0\n1 1 1\n2 3 1\n3 3 3\n4 1 3\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n0\n")
}

fn text(size: Option<i64>) -> String {
    let head = size.map_or(String::new(), |u| format!("size {u}\n"));
    format!("{head}1 1  3 1  3 3  1 3\n")
}

type Reader = fn(&str, Option<i64>) -> Result<Board, BoardError>;
/// Makes a file, with a size line when given one.
type Maker = fn(Option<i64>) -> String;

const READERS: [(&str, Maker, Reader); 2] =
    [("poly", poly, read_poly), ("text", text, read_board_text)];

const INVALID: [i64; 9] = [0, -1, -16, 3, 6, 48, 1 << 31, i64::MAX, i64::MIN];

#[test]
fn file_and_caller_must_agree() {
    for (name, make, read) in READERS {
        for file in [1i64 << 2, 1 << 4, 1 << 10, 1 << 30] {
            // given by both and equal: that size
            assert_eq!(
                read(&make(Some(file)), Some(file)).unwrap().size(),
                file,
                "{name}"
            );
            // given by the file only
            assert_eq!(
                read(&make(Some(file)), None).unwrap().size(),
                file,
                "{name}"
            );
            for caller in [4i64, 8, 32, 1 << 20, 1 << 30] {
                if caller == file {
                    continue;
                }
                let e = read(&make(Some(file)), Some(caller)).unwrap_err();
                assert_eq!(
                    e,
                    BoardError::SizeMismatch {
                        file,
                        line: 1,
                        caller
                    },
                    "{name}"
                );
                let message = e.to_string();
                assert!(
                    message.contains(&format!("board size {file}"))
                        && message.contains(&format!("size {caller}"))
                        && message.starts_with("line 1: "),
                    "{name}: {message}"
                );
            }
        }
    }
}

#[test]
fn caller_size_alone_is_used_and_otherwise_guessed() {
    for (name, make, read) in READERS {
        for caller in [4i64, 8, 64, 1 << 30] {
            assert_eq!(
                read(&make(None), Some(caller)).unwrap().size(),
                caller,
                "{name}"
            );
        }
        // the largest coordinate is 3: U = 4
        assert_eq!(read(&make(None), None).unwrap().size(), 4, "{name}");
        // a caller's size the coordinates do not fit in is refused by the board check
        assert!(matches!(
            read(&make(None), Some(2)),
            Err(BoardError::OutOfRange { .. })
        ));
    }
}

#[test]
fn an_invalid_caller_size_is_always_refused() {
    for (name, make, read) in READERS {
        for size in INVALID {
            for file in [None, Some(4), Some(16)] {
                assert_eq!(
                    read(&make(file), Some(size)).unwrap_err(),
                    BoardError::SizeNotPowerOfTwo { size },
                    "{name}, file size {file:?}"
                );
            }
        }
    }
}

#[test]
fn an_invalid_file_size_is_always_refused() {
    for (name, make, read) in READERS {
        for size in INVALID {
            for caller in [None, Some(4), Some(size)] {
                assert_eq!(
                    read(&make(Some(size)), caller).unwrap_err(),
                    BoardError::SizeNotPowerOfTwo { size },
                    "{name}, caller {caller:?}"
                );
            }
        }
        // the caller's invalid size is named before the file's
        assert_eq!(
            read(&make(Some(3)), Some(5)).unwrap_err(),
            BoardError::SizeNotPowerOfTwo { size: 5 }
        );
    }
}

#[test]
fn read_board_file_follows_the_same_rule() {
    let dir = std::env::temp_dir().join(format!("orthtree-board-size-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, make, _) in READERS {
        let path = dir.join(if name == "poly" { "b.poly" } else { "b.txt" });
        std::fs::write(&path, make(Some(16))).unwrap();
        assert_eq!(read_board_file(&path, Some(16)).unwrap().size(), 16);
        assert_eq!(read_board_file(&path, None).unwrap().size(), 16);
        let e = read_board_file(&path, Some(32)).unwrap_err().to_string();
        assert!(
            e.contains("b.") && e.contains("board size 16") && e.contains("size 32"),
            "{e}"
        );
        let e = read_board_file(&path, Some(3)).unwrap_err().to_string();
        assert!(e.contains("board size 3 is not a power of two"), "{e}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
