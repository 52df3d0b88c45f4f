//! Board files are read through a bounded reader whatever they are (regular files, devices,
//! pipes), and a board the `.poly` format cannot hold is refused by the writer rather than
//! written as a file the reader refuses.

use orthtree::io::poly::{read_poly, write_poly, PolyWriteError};
use orthtree::io::{board_text::write_board_text, MAX_BOARD_FILE_BYTES};
use orthtree::io::{read_board_file, read_board_file_with_limit, BoardFileError};
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
