//! What the two board readers ([`super::poly`] and [`super::board_text`]) share: splitting bytes
//! into lines, quoting a field in a message, integer coordinates and the board's side U; and the
//! first line of their writers.
//!
//! Lines: a UTF-8 byte-order mark at the very start is skipped; a line ends at `\n`, `\r\n` or a
//! lone `\r` (so Unix, Windows and classic Mac files all read the same); every line must be valid
//! UTF-8, else [`BoardError::InvalidUtf8`] names the line and the byte offset. `#` starts a
//! comment. Fields are separated by spaces and tabs only; any other byte, visible or not, belongs
//! to a field, and a field quoted in a message shows invisible characters escaped (`\0`, `\u{a0}`)
//! and is cut after [`SHOWN_CHARS`] characters, so no message grows with the input.

use crate::mesh::{Board, BoardError, Component};
use core::num::IntErrorKind;

/// The first line of both board writers: a comment naming the side and the component count.
pub(crate) fn board_comment(board: &Board) -> String {
    let (size, components) = (board.size(), board.components().len());
    format!("# orthtree board: side {size}, {components} components\n")
}

/// The largest board side, 2^30 (the limit of [`crate::mesh::Board::new`]).
pub(crate) const MAX_SIZE: i64 = 1 << 30;

/// The most characters of a field a message shows.
pub(crate) const SHOWN_CHARS: usize = 32;

/// One line of a board file.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Line<'a> {
    /// Its number, from 1.
    pub number: usize,
    /// The text before any `#`.
    pub content: &'a str,
    /// The text after the first `#`, if there is one.
    pub comment: Option<&'a str>,
}

impl<'a> Line<'a> {
    /// True when the line holds no field (blank, or only a comment).
    pub fn is_blank(&self) -> bool {
        self.content.bytes().all(|b| b == b' ' || b == b'\t')
    }

    /// The fields of the content, split at spaces and tabs.
    pub fn fields(&self) -> impl Iterator<Item = &'a str> + 'a + use<'a> {
        self.content
            .split([' ', '\t'])
            .filter(|field| !field.is_empty())
    }
}

/// The lines of a board file, read lazily from its bytes (see the module doc). After an error
/// it yields nothing more.
#[derive(Clone, Debug)]
pub(crate) struct Lines<'a> {
    bytes: &'a [u8],
    position: usize,
    number: usize,
}

impl<'a> Lines<'a> {
    /// The lines of `bytes`, skipping a leading UTF-8 byte-order mark.
    pub fn new(bytes: &'a [u8]) -> Self {
        // The mark's 3 bytes, if there.
        let position = 3 * usize::from(bytes.starts_with(b"\xEF\xBB\xBF"));
        Lines {
            bytes,
            position,
            number: 0,
        }
    }

    /// The number of the last line yielded (0 before the first).
    pub fn last_number(&self) -> usize {
        self.number
    }
}

impl<'a> Iterator for Lines<'a> {
    type Item = Result<Line<'a>, BoardError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.position >= self.bytes.len() {
            return None;
        }
        let start = self.position;
        let rest = &self.bytes[start..];
        let (length, terminator) = match rest.iter().position(|&b| b == b'\n' || b == b'\r') {
            Some(i) if rest[i] == b'\r' && rest.get(i + 1) == Some(&b'\n') => (i, 2),
            Some(i) => (i, 1),
            None => (rest.len(), 0),
        };
        self.position = start + length + terminator;
        self.number += 1;
        let text = match core::str::from_utf8(&rest[..length]) {
            Ok(text) => text,
            Err(e) => {
                self.position = self.bytes.len();
                return Some(Err(BoardError::InvalidUtf8 {
                    line: self.number,
                    offset: start + e.valid_up_to(),
                    byte: rest[e.valid_up_to()],
                }));
            }
        };
        let (content, comment) = text
            .split_once('#')
            .map_or((text, None), |(content, comment)| (content, Some(comment)));
        Some(Ok(Line {
            number: self.number,
            content,
            comment,
        }))
    }
}

/// A field as a message shows it: in backticks, invisible characters escaped, cut after
/// [`SHOWN_CHARS`] characters with the field's full length in bytes.
pub(crate) struct Quoted<'a>(pub &'a str);

impl core::fmt::Display for Quoted<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let field = self.0;
        f.write_str("`")?;
        for c in field.chars().take(SHOWN_CHARS) {
            write!(f, "{}", c.escape_debug())?;
        }
        if field.chars().nth(SHOWN_CHARS).is_some() {
            write!(f, "...` ({} bytes)", field.len())
        } else {
            f.write_str("`")
        }
    }
}

/// A [`BoardError::Parse`] on `line`.
pub(crate) fn parse_error(line: usize, message: impl Into<String>) -> BoardError {
    BoardError::Parse {
        line,
        message: message.into(),
    }
}

/// Parses an integer coordinate: decimal digits with an optional sign, optionally followed by a
/// point and zeros (`3`, `-2`, `3.0`, `3.`). The error is a message naming the field.
pub(crate) fn parse_coordinate(field: &str) -> Result<i64, String> {
    let (whole, fraction) = field.split_once('.').unwrap_or((field, ""));
    let digits = whole.strip_prefix(['+', '-']).unwrap_or(whole);
    let whole_ok = !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit());
    if !fraction.bytes().all(|b| b == b'0') || !whole_ok {
        return Err(if field.parse::<f64>().is_ok() {
            format!("coordinate {} is not an integer", Quoted(field))
        } else {
            format!("coordinate {} is not a number", Quoted(field))
        });
    }
    whole
        .parse()
        .map_err(|e: core::num::ParseIntError| match e.kind() {
            IntErrorKind::PosOverflow | IntErrorKind::NegOverflow => {
                format!("coordinate {} is out of range", Quoted(field))
            }
            _ => format!("coordinate {} is not a number", Quoted(field)),
        })
}

/// True for 1, 2, 4, ..., 2^30.
pub(crate) fn is_valid_size(size: i64) -> bool {
    (1..=MAX_SIZE).contains(&size) && size & (size - 1) == 0
}

/// U for a board read from a file, from the size the file gives (with its line), the caller's and
/// the components:
///
/// - a size the caller gives must be a power of two from 1 to 2^30, and so must the file's,
///   whether or not the other one is given ([`BoardError::SizeNotPowerOfTwo`], the caller's
///   checked first);
/// - given by both, they must be equal ([`BoardError::SizeMismatch`] naming both);
/// - given by neither, U is the smallest power of two at least the largest coordinate (at least
///   1, at most 2^30: larger coordinates are then reported as out of range by
///   [`crate::mesh::Board::new`]).
pub(crate) fn resolve_size(
    file: Option<(i64, usize)>,
    caller: Option<i64>,
    components: &[Component],
) -> Result<i64, BoardError> {
    if let Some(size) = caller.filter(|&u| !is_valid_size(u)) {
        return Err(BoardError::SizeNotPowerOfTwo { size });
    }
    if let Some((size, _)) = file.filter(|&(u, _)| !is_valid_size(u)) {
        return Err(BoardError::SizeNotPowerOfTwo { size });
    }
    match (file, caller) {
        (Some((file, line)), Some(caller)) if file != caller => {
            Err(BoardError::SizeMismatch { file, line, caller })
        }
        (Some((u, _)), _) | (None, Some(u)) => Ok(u),
        (None, None) => {
            let largest = components
                .iter()
                .flat_map(|c| c.outline.iter().flatten())
                .copied()
                .max()
                .unwrap_or(1)
                .clamp(1, MAX_SIZE);
            Ok((largest as u64).next_power_of_two() as i64)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(bytes: &[u8]) -> Vec<(usize, String)> {
        Lines::new(bytes)
            .map(|l| l.map(|l| (l.number, l.content.to_string())).unwrap())
            .collect()
    }

    #[test]
    fn line_endings_and_byte_order_mark() {
        let want: Vec<(usize, String)> = vec![(1, "a".into()), (2, "b".into()), (3, "".into())];
        for text in [
            &b"a\nb\n\n"[..],
            b"a\r\nb\r\n\r\n",
            b"a\rb\r\r",
            b"\xEF\xBB\xBFa\nb\r\r\n",
        ] {
            assert_eq!(lines(text), want, "{text:?}");
        }
        assert_eq!(lines(b""), vec![]);
        assert_eq!(lines(b"\xEF\xBB\xBF"), vec![]);
        // a byte-order mark later on is part of the line
        assert_eq!(lines(b"a\n\xEF\xBB\xBFb")[1].1, "\u{feff}b");
    }

    #[test]
    fn invalid_utf8_names_line_and_offset() {
        let mut it = Lines::new(b"ok\r\nfine\xff more\n");
        assert!(it.next().unwrap().is_ok());
        assert_eq!(
            it.next().unwrap().unwrap_err(),
            BoardError::InvalidUtf8 {
                line: 2,
                offset: 8,
                byte: 0xff
            }
        );
        assert!(it.next().is_none());
    }

    #[test]
    fn quoted_fields_are_escaped_and_short() {
        assert_eq!(Quoted("a\0b").to_string(), "`a\\0b`");
        assert_eq!(Quoted("\u{a0}\u{feff}").to_string(), "`\\u{a0}\\u{feff}`");
        let long = "x".repeat(1 << 20);
        let shown = Quoted(&long).to_string();
        assert!(shown.len() < 60, "{shown}");
        assert!(shown.ends_with("...` (1048576 bytes)"), "{shown}");
    }
}
