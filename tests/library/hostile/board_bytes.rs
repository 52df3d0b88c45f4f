//! Board files as bytes, for both readers: a UTF-8 byte-order mark is skipped; `\n`, `\r\n` and
//! lone `\r` line endings read the same; invalid UTF-8 is refused naming the line and byte
//! offset; NUL and other invisible characters are shown escaped and long fields cut short in
//! messages; extensions match without regard to case; and memory stays bounded by the data
//! whatever a header claims (measured with a counting allocator).

use crate::counting::peak_bytes;
use orthtree::io::board_text::{read_board_text_bytes, write_board_text};
use orthtree::io::poly::{read_poly_bytes, write_poly};
use orthtree::io::{read_board_file, BoardFileError, BoardFormat, BoardReadError};
use orthtree::mesh::{Board, BoardError, Component, Point};

type Reader = fn(&[u8], Option<i64>) -> Result<Board, BoardError>;
const READERS: [(&str, Reader); 2] = [("poly", read_poly_bytes), ("text", read_board_text_bytes)];

fn sample() -> Board {
    let square =
        |x: i64, y: i64| Component::new(vec![[x, y], [x + 2, y], [x + 2, y + 2], [x, y + 2]]);
    let diamond = Component::new(vec![[10, 8], [12, 10], [10, 12], [8, 10]]);
    Board::new(16, vec![square(1, 1), square(5, 1), diamond]).unwrap()
}

/// The sample written by each format's writer.
fn written() -> [(&'static str, Reader, String); 2] {
    let b = sample();
    [
        ("poly", read_poly_bytes as Reader, write_poly(&b).unwrap()),
        (
            "text",
            read_board_text_bytes as Reader,
            write_board_text(&b),
        ),
    ]
}

fn outlines(b: &Board) -> Vec<Vec<Point>> {
    b.components().iter().map(|c| c.outline.clone()).collect()
}

#[test]
fn byte_order_mark_and_line_endings() {
    for (name, read, text) in written() {
        let want = read(text.as_bytes(), None).unwrap();
        let variants = [
            format!("\u{feff}{text}"),
            text.replace('\n', "\r\n"),
            text.replace('\n', "\r"),
            format!("\u{feff}{}", text.replace('\n', "\r")),
            // mixed, and no newline at the end
            text.replacen('\n', "\r", 2)
                .replacen('\n', "\r\n", 2)
                .trim_end()
                .to_string(),
        ];
        for v in variants {
            let b = read(v.as_bytes(), None).unwrap_or_else(|e| panic!("{name} {v:?}: {e}"));
            assert_eq!(b, want, "{name} {v:?}"); // lines included: numbering is the same
        }
        // a byte-order mark after the start is no white space: refused, shown escaped
        let last = text.trim_end().rfind('\n').unwrap() + 1;
        let late = format!("{}\u{feff}{}", &text[..last], &text[last..]);
        let e = read(late.as_bytes(), None).unwrap_err().to_string();
        assert!(
            e.contains("\\u{feff}") && !e.contains('\u{feff}'),
            "{name}: {e}"
        );
    }
}

#[test]
fn invalid_utf8_names_line_and_offset() {
    for (name, read, text) in written() {
        let bytes = text.as_bytes();
        let newlines: Vec<usize> = (0..bytes.len()).filter(|&i| bytes[i] == b'\n').collect();
        // a stray byte at the start of line 1, in the middle of line 3 and at the very end; a
        // truncated two-byte sequence; an overlong encoding; a surrogate
        for (at, bad) in [
            (0, &b"\xff"[..]),
            (newlines[1] + 3, b"\x80"),
            (bytes.len(), b"\xfe"),
            (newlines[0] + 1, b"\xc3"),
            (newlines[2] + 1, b"\xc0\xaf"),
            (newlines[1] + 1, b"\xed\xa0\x80"),
        ] {
            let mut input = bytes[..at].to_vec();
            input.extend_from_slice(bad);
            input.extend_from_slice(&bytes[at..]);
            let line = 1 + newlines.iter().filter(|&&n| n < at).count();
            let e = read(&input, None).unwrap_err();
            assert_eq!(
                e,
                BoardError::InvalidUtf8 {
                    line,
                    offset: at,
                    byte: bad[0]
                },
                "{name}, {bad:?} at {at}"
            );
            assert!(
                e.to_string().starts_with(&format!(
                    "line {line} (byte offset {at}): byte 0x{:02x}",
                    bad[0]
                )),
                "{e}"
            );
        }
        // in a comment too: the file must be UTF-8 text
        let input = [b"# caf\xe9\n".as_slice(), bytes].concat();
        assert_eq!(
            read(&input, None).unwrap_err(),
            BoardError::InvalidUtf8 {
                line: 1,
                offset: 5,
                byte: 0xe9
            }
        );
        // valid UTF-8 in a comment is fine
        let input = [b"# caf\xc3\xa9 \xe2\x9c\x93\n".as_slice(), bytes].concat();
        assert!(read(&input, None).is_ok(), "{name}");
    }
}

/// Puts `field` where a coordinate of the written sample was, on the third data line of each
/// format, and returns the message.
fn message_for(field: &str) -> Vec<String> {
    let b = sample();
    let poly = write_poly(&b)
        .unwrap()
        .replacen("\n2 3 1\n", &format!("\n2 {field} 1\n"), 1);
    let text = write_board_text(&b).replacen("size 16\n1 1", &format!("size 16\n{field} 1"), 1);
    assert_ne!(poly, write_poly(&b).unwrap());
    assert_ne!(text, write_board_text(&b));
    [
        read_poly_bytes(poly.as_bytes(), None),
        read_board_text_bytes(text.as_bytes(), None),
    ]
    .map(|r| r.unwrap_err().to_string())
    .to_vec()
}

#[test]
fn invisible_characters_are_shown_escaped() {
    for (field, shown) in [
        ("3\0", "`3\\0`"),
        ("\u{0}3", "`\\03`"),
        ("3\u{a0}", "`3\\u{a0}`"),
        ("\u{200b}3", "`\\u{200b}3`"),
        ("3\u{7}", "`3\\u{7}`"),
        ("\u{1b}[31m3", "`\\u{1b}[31m3`"),
        ("3\u{c}", "`3\\u{c}`"),
        ("\u{202e}3", "`\\u{202e}3`"),
        ("3\u{85}", "`3\\u{85}`"),
    ] {
        for message in message_for(field) {
            assert!(message.contains(shown), "{field:?}: {message}");
            assert!(
                !message
                    .chars()
                    .any(|c| c.is_control() || c == '\u{a0}' || c == '\u{200b}'),
                "{field:?}: {message:?}"
            );
        }
    }
}

#[test]
fn long_fields_are_cut_short() {
    for length in [33usize, 1000, 1 << 20, 10 << 20] {
        for field in ["7".repeat(length), "x".repeat(length), "\0".repeat(length)] {
            for message in message_for(&field) {
                assert!(message.len() < 300, "{length}: {} bytes", message.len());
                assert!(
                    message.contains(&format!("...` ({length} bytes)")),
                    "{message}"
                );
            }
        }
    }
    // a long field in a header, in a size line and a size comment
    let long = "9".repeat(1 << 20);
    let poly_header = format!("{long} 2 0 0\n");
    let text_size = format!("size {long}\n");
    let poly_size = format!("# size {long}\n");
    for message in [
        read_poly_bytes(poly_header.as_bytes(), None),
        read_board_text_bytes(text_size.as_bytes(), None),
        read_poly_bytes(poly_size.as_bytes(), None),
    ]
    .map(|r| r.unwrap_err().to_string())
    {
        assert!(message.len() < 300, "{} bytes", message.len());
    }
}

#[test]
fn extensions_match_without_regard_to_case() {
    let dir = std::env::temp_dir().join(format!("orthtree-board-bytes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let b = sample();
    for (name, text) in [
        ("a.poly", write_poly(&b).unwrap()),
        ("b.POLY", write_poly(&b).unwrap()),
        ("c.Poly", write_poly(&b).unwrap()),
        ("d.txt", write_board_text(&b)),
        ("e.TXT", write_board_text(&b)),
        ("f.Txt", write_board_text(&b)),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        let back = read_board_file(&path, None).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(outlines(&back), outlines(&b), "{name}");
    }
    for name in ["g.node", "h", "i.poly.bak", "j.po1y", ".poly"] {
        let path = dir.join(name);
        std::fs::write(&path, write_poly(&b).unwrap()).unwrap();
        let e = read_board_file(&path, None).unwrap_err();
        assert!(
            matches!(e, BoardFileError::UnknownFormat { .. }),
            "{name}: {e}"
        );
        assert!(e.to_string().contains(name), "{e}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn any_reader_gives_the_same_board() {
    for (format, text) in [
        (BoardFormat::Poly, write_poly(&sample()).unwrap()),
        (BoardFormat::Text, write_board_text(&sample())),
    ] {
        let b = format.read(text.as_bytes(), None).unwrap();
        assert_eq!(outlines(&b), outlines(&sample()));
        // a reader that fails half way
        let failing = std::io::Read::chain(text.as_bytes(), Failing);
        assert!(matches!(
            format.read(failing, None),
            Err(BoardReadError::Io(_))
        ));
    }
}

struct Failing;

impl std::io::Read for Failing {
    fn read(&mut self, _: &mut [u8]) -> std::io::Result<usize> {
        Err(std::io::Error::other("the disk went away"))
    }
}

#[test]
fn memory_is_bounded_by_the_data_not_by_the_counts() {
    let huge = 1_000_000_000_000u64;
    let inputs: Vec<(String, &str)> = vec![
        (format!("{huge} 2 0 0\n1 0 0\n"), "vertex count"),
        (format!("{huge}\n"), "end of input"),
        (format!("3 2 {huge} 0\n1 0 0\n"), "fields"),
        (
            format!("3 2 0 0\n1 0 0\n2 4 0\n3 0 4\n{huge} 0\n1 1 2\n"),
            "segment count",
        ),
        (
            format!("3 2 0 0\n1 0 0\n2 4 0\n3 0 4\n3 0\n1 1 2\n2 2 3\n3 3 1\n{huge}\n"),
            "hole",
        ),
        (
            format!("3 2 0 0\n1 0 0\n2 4 0\n3 0 4\n3 0\n1 1 2\n2 2 3\n3 3 1\n0\n{huge}\n"),
            "regional",
        ),
        (format!("{} 2 0 0\n1 0 0\n", usize::MAX), "vertex count"),
    ];
    for (input, needle) in &inputs {
        let (result, peak) = peak_bytes(|| read_poly_bytes(input.as_bytes(), None));
        let message = result.unwrap_err().to_string();
        assert!(message.contains(needle), "{input:?}: {message}");
        assert!(peak < 4096, "{input:?}: {peak} bytes");
    }
    // many lines: the memory held grows with the data, a small multiple of it (the board
    // check's tables included)
    let count = 100_000;
    let mut poly = format!("{count} 2 0 0\n");
    let mut text = String::from("size 1048576\n");
    for i in 0..count {
        poly += &format!("{} {} 0\n", i + 1, 2 * i);
        text += &format!("{} 0 ", 2 * i);
    }
    text += "\n";
    for (name, read, input) in [
        ("poly", read_poly_bytes as Reader, &poly),
        ("text", read_board_text_bytes as Reader, &text),
    ] {
        let (result, peak) = peak_bytes(|| read(input.as_bytes(), None));
        assert!(result.is_err(), "{name}");
        assert!(
            peak < 32 * input.len() + 65536,
            "{name}: {peak} bytes for {}",
            input.len()
        );
    }
}

#[test]
fn both_readers_refuse_what_the_text_format_cannot_hold() {
    // separators only, no coordinates
    for line in ["(", ", ,", "()"] {
        let input = format!("size 8\n{line}\n");
        match read_board_text_bytes(input.as_bytes(), None) {
            Err(BoardError::Parse { line: 2, message }) => {
                assert!(message.contains("no coordinates"), "{message}")
            }
            other => panic!("{line:?}: {other:?}"),
        }
    }
    for (name, read) in READERS {
        assert!(read(b"\0", None).is_err(), "{name}");
    }
}
