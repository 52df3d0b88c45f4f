//! Board files and readers are read with a byte limit whatever they are (regular files, devices,
//! pipes, endless readers), holding at most the limit, and a board the `.poly` format cannot hold is refused by the writer rather than
//! written as a file the reader refuses.

use crate::counting::peak_bytes;
use orthtree::io::poly::{read_poly, write_poly, PolyWriteError};
use orthtree::io::{board_text::write_board_text, MAX_BOARD_FILE_BYTES};
use orthtree::io::{read_board_file, read_board_file_with_limit, BoardFileError};
use orthtree::io::{BoardFormat, BoardReadError};
use orthtree::mesh::{random_board, Board};
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// A fresh folder for this test's files.
fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("orthtree-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Asserts `result` is `TooLarge` naming `limit` and the file.
fn assert_too_large(result: Result<Board, BoardFileError>, limit: u64, file: &str) {
    match result {
        Err(e @ BoardFileError::TooLarge { limit: l, .. }) => {
            assert_eq!(l, limit);
            let message = e.to_string();
            assert!(message.contains(&limit.to_string()), "{message}");
            assert!(message.contains(file), "{message}");
        }
        other => panic!("expected TooLarge for {file}, got {other:?}"),
    }
}

#[cfg(unix)]
#[test]
fn endless_devices_are_stopped_at_the_limit() {
    let dir = folder("devices");
    for (device, name, limit) in [
        ("/dev/zero", "zero.poly", 1 << 20),
        ("/dev/zero", "zero.TXT", 1000),
        ("/dev/zero", "tiny.txt", 0),
        ("/dev/urandom", "random.txt", 1 << 16),
        ("/dev/urandom", "random.poly", 12345),
    ] {
        let path = dir.join(name);
        std::os::unix::fs::symlink(device, &path).unwrap();
        let started = Instant::now();
        assert_too_large(read_board_file_with_limit(&path, None, limit), limit, name);
        assert!(
            started.elapsed() < Duration::from_secs(5),
            "{device} read too long"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn regular_files_are_read_up_to_the_limit_exactly() {
    let dir = folder("regular");
    let board = random_board(3, 1 << 10, 20);
    let cases = [
        ("b.txt", write_board_text(&board)),
        ("b.poly", write_poly(&board).unwrap()),
    ];
    for (name, text) in cases {
        let path = dir.join(name);
        std::fs::write(&path, &text).unwrap();
        let n = text.len() as u64;
        for limit in [n, n + 1, MAX_BOARD_FILE_BYTES] {
            let back = read_board_file_with_limit(&path, None, limit).unwrap();
            assert_eq!(back.components().len(), 20);
        }
        assert_eq!(read_board_file(&path, None).unwrap().size(), board.size());
        for limit in [0, 1, n / 2, n - 1] {
            assert_too_large(read_board_file_with_limit(&path, None, limit), limit, name);
        }
    }
    // A sparse file of 8 MiB, limited to 1 MiB: refused without reading it all.
    let path = dir.join("sparse.poly");
    std::fs::File::create(&path)
        .unwrap()
        .set_len(8 << 20)
        .unwrap();
    assert_too_large(
        read_board_file_with_limit(&path, None, 1 << 20),
        1 << 20,
        "sparse",
    );
    // Under a limit that holds it, its bytes are read and refused as a board, not a size.
    let err = read_board_file_with_limit(&path, None, 8 << 20).unwrap_err();
    assert!(matches!(err, BoardFileError::Board { .. }), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_poly_writer_refuses_what_the_reader_would_refuse() {
    for size in [1, 2, 16, 1 << 20, 1 << 30] {
        let empty = Board::new(size, vec![]).unwrap();
        let err = write_poly(&empty).unwrap_err();
        assert_eq!(err, PolyWriteError::NoVertices { size });
        assert!(err.to_string().contains(&format!("side {size}")));
        // What an empty board would give: refused by the reader, as the error says.
        assert!(read_poly(&format!("# size {size}\n0 2 0 0\n0 0\n0\n"), None).is_err());
    }
    // Every board with a component is written, and reads back.
    for (seed, count) in [(1, 1), (2, 5), (3, 40), (4, 200)] {
        let board = random_board(seed, 1 << 12, count);
        let text = write_poly(&board).unwrap();
        let back = read_poly(&text, None).unwrap();
        assert_eq!(back.size(), board.size());
        assert_eq!(back.components().len(), count);
    }
}

/// A reader that counts the bytes it hands out.
struct Counted<R> {
    inner: R,
    handed: u64,
}

impl<R: std::io::Read> std::io::Read for Counted<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.handed += n as u64;
        Ok(n)
    }
}

#[test]
fn endless_readers_are_stopped_at_the_limit_holding_at_most_the_limit() {
    for format in [BoardFormat::Poly, BoardFormat::Text] {
        for (byte, limit) in [
            (b' ', 0),
            (b'0', 1),
            (b'\n', 1000),
            (0, 12345),
            (b'7', 1 << 20),
        ] {
            let mut reader = Counted {
                inner: std::io::repeat(byte),
                handed: 0,
            };
            let started = Instant::now();
            let (result, peak) = peak_bytes(|| format.read_with_limit(&mut reader, None, limit));
            match result {
                Err(e @ BoardReadError::TooLarge { limit: l }) => {
                    assert_eq!(l, limit);
                    assert!(e.to_string().contains(&format!("{limit} bytes")), "{e}");
                }
                other => panic!("expected TooLarge from {format:?} at {limit}, got {other:?}"),
            }
            assert_eq!(reader.handed, limit + 1, "read one byte past the limit");
            assert!(
                peak as u64 <= limit.max(64),
                "held {peak} bytes for a limit of {limit}"
            );
            assert!(started.elapsed() < Duration::from_secs(5));
        }
    }
}

#[test]
fn readers_up_to_the_limit_are_read_whole() {
    let board = random_board(5, 1 << 10, 30);
    for (format, text) in [
        (BoardFormat::Text, write_board_text(&board)),
        (BoardFormat::Poly, write_poly(&board).unwrap()),
    ] {
        let n = text.len() as u64;
        for limit in [n, n + 1, 2 * n, MAX_BOARD_FILE_BYTES] {
            let back = format
                .read_with_limit(text.as_bytes(), None, limit)
                .unwrap();
            assert_eq!(back.components().len(), 30);
        }
        // The plain read has the file reader's limit.
        assert_eq!(
            format
                .read(text.as_bytes(), None)
                .unwrap()
                .components()
                .len(),
            30
        );
        for limit in [0, 1, n / 2, n - 1] {
            let err = format
                .read_with_limit(text.as_bytes(), None, limit)
                .unwrap_err();
            assert!(matches!(err, BoardReadError::TooLarge { limit: l } if l == limit));
        }
        // One byte at a time, as a pipe may deliver them: the same.
        let slow = OneByte(text.as_bytes());
        assert!(format.read_with_limit(slow, None, n).is_ok());
        let slow = OneByte(text.as_bytes());
        assert!(format.read_with_limit(slow, None, n - 1).is_err());
    }
}

/// A reader that hands out one byte per call.
struct OneByte<'a>(&'a [u8]);

impl std::io::Read for OneByte<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        match (self.0.split_first(), buf.first_mut()) {
            (Some((&b, rest)), Some(slot)) => {
                *slot = b;
                self.0 = rest;
                Ok(1)
            }
            _ => Ok(0),
        }
    }
}
