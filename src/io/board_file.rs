//! [`read_board_file`]: a board for the mesher from a file, in the format its name says
//! (Triangle's `.poly`, or the plain text of [`super::board_text`] for `.txt`, in any case), with
//! errors that name the file; [`BoardFormat`] reads either format from bytes or from any
//! [`Read`].

use crate::mesh::{Board, BoardError};
use std::io::Read;
use std::path::{Path, PathBuf};

/// The two board file formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BoardFormat {
    /// Triangle's `.poly` ([`super::poly`]).
    Poly,
    /// The plain text format, one component per line ([`super::board_text`]).
    Text,
}

impl BoardFormat {
    /// The format a file name says: `.poly` or `.txt`, the extension compared without regard to
    /// case (`.POLY`, `.Txt`); `None` for any other name.
    ///
    /// ```
    /// use orthtree::io::BoardFormat;
    /// assert_eq!(BoardFormat::from_path("a/B.POLY"), Some(BoardFormat::Poly));
    /// assert_eq!(BoardFormat::from_path("board.Txt"), Some(BoardFormat::Text));
    /// assert_eq!(BoardFormat::from_path("board.node"), None);
    /// assert_eq!(BoardFormat::from_path("poly"), None);
    /// ```
    pub fn from_path(path: impl AsRef<Path>) -> Option<BoardFormat> {
        match path
            .as_ref()
            .extension()?
            .to_str()?
            .to_ascii_lowercase()
            .as_str()
        {
            "poly" => Some(BoardFormat::Poly),
            "txt" => Some(BoardFormat::Text),
            _ => None,
        }
    }

    /// Reads a board in this format from bytes; `size` is the caller's choice of U, which must
    /// agree with a size the file gives.
    ///
    /// # Errors
    ///
    /// Those of [`super::poly::read_poly_bytes`] or [`super::board_text::read_board_text_bytes`].
    ///
    /// # Complexity
    ///
    /// O(n + E log E) time and O(n) memory for n bytes and E edges.
    pub fn read_bytes(self, bytes: &[u8], size: Option<i64>) -> Result<Board, BoardError> {
        match self {
            BoardFormat::Poly => super::poly::read_poly_bytes(bytes, size),
            BoardFormat::Text => super::board_text::read_board_text_bytes(bytes, size),
        }
    }

    /// Reads a board in this format from `reader` to its end, as [`BoardFormat::read_bytes`],
    /// reading at most [`MAX_BOARD_FILE_BYTES`] (see [`BoardFormat::read_with_limit`]).
    ///
    /// # Errors
    ///
    /// [`BoardReadError::Io`] when reading fails, [`BoardReadError::TooLarge`] when the reader
    /// yields more than [`MAX_BOARD_FILE_BYTES`], [`BoardReadError::Board`] for a board that is
    /// refused.
    ///
    /// # Complexity
    ///
    /// As [`BoardFormat::read_bytes`]; at most [`MAX_BOARD_FILE_BYTES`] bytes of text held
    /// besides the board.
    ///
    /// ```
    /// use orthtree::io::BoardFormat;
    /// let board = BoardFormat::Text.read(&b"size 16\n4 4  8 4  8 8\n"[..], None).unwrap();
    /// assert_eq!(board.components().len(), 1);
    /// ```
    pub fn read(self, reader: impl Read, size: Option<i64>) -> Result<Board, BoardReadError> {
        self.read_with_limit(reader, size, MAX_BOARD_FILE_BYTES)
    }

    /// [`BoardFormat::read`] reading at most `max_bytes + 1` bytes, the last one only to tell
    /// that the reader goes on: memory stays within `max_bytes` bytes of text even for a reader
    /// that never ends.
    ///
    /// # Errors
    ///
    /// As [`BoardFormat::read`], with [`BoardReadError::TooLarge`] naming `max_bytes` when the
    /// reader yields more.
    ///
    /// ```
    /// use orthtree::io::{BoardFormat, BoardReadError};
    /// let text = b"size 16\n4 4  8 4  8 8\n"; // 22 bytes
    /// assert!(BoardFormat::Text.read_with_limit(&text[..], None, 22).is_ok());
    /// let err = BoardFormat::Text.read_with_limit(&text[..], None, 21).unwrap_err();
    /// assert!(matches!(err, BoardReadError::TooLarge { limit: 21 }));
    /// // An endless reader is stopped at the limit.
    /// let endless = std::io::repeat(b' ');
    /// let err = BoardFormat::Poly.read_with_limit(endless, None, 1000).unwrap_err();
    /// assert_eq!(err.to_string(), "the board holds more than 1000 bytes; the limit is 1000 bytes");
    /// ```
    pub fn read_with_limit(
        self,
        reader: impl Read,
        size: Option<i64>,
        max_bytes: u64,
    ) -> Result<Board, BoardReadError> {
        let bytes = read_bounded(reader, max_bytes)
            .map_err(BoardReadError::Io)?
            .ok_or(BoardReadError::TooLarge { limit: max_bytes })?;
        self.read_bytes(&bytes, size).map_err(BoardReadError::Board)
    }
}

/// The bytes of `reader` to its end, or `None` if it yields more than `max_bytes`. The buffer
/// grows by doubling but never past `max_bytes`, and the one byte that tells a reader longer than
/// the limit is read onto the stack, so at most `max_bytes` bytes are held (and `max_bytes + 1`
/// read) whatever the reader.
fn read_bounded(mut reader: impl Read, max_bytes: u64) -> std::io::Result<Option<Vec<u8>>> {
    // On a 32-bit target a limit past the address space is no limit.
    let limit = usize::try_from(max_bytes).unwrap_or(usize::MAX);
    let mut bytes = Vec::new();
    loop {
        let len = bytes.len();
        let grown = len.saturating_mul(2).max(1 << 13).min(limit);
        // Exactly: `resize` alone may round the capacity up past the limit.
        bytes.reserve_exact(grown - len);
        bytes.resize(grown, 0);
        let got = super::read_full(&mut reader, &mut bytes[len..])?;
        if len + got < grown {
            bytes.truncate(len + got);
            return Ok(Some(bytes));
        }
        if grown == limit {
            let more = super::read_full(&mut reader, &mut [0u8; 1])?;
            return Ok((more == 0).then_some(bytes));
        }
    }
}

/// Why a board could not be read from a [`Read`].
#[derive(Debug)]
pub enum BoardReadError {
    /// Reading failed.
    Io(std::io::Error),
    /// The reader yields more bytes than the limit ([`MAX_BOARD_FILE_BYTES`] unless
    /// [`BoardFormat::read_with_limit`] sets another).
    TooLarge {
        /// The limit, in bytes.
        limit: u64,
    },
    /// The bytes are not a valid board.
    Board(BoardError),
}

impl core::fmt::Display for BoardReadError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            BoardReadError::Io(error) => write!(f, "reading the board: {error}"),
            BoardReadError::TooLarge { limit } => write!(
                f,
                "the board holds more than {limit} bytes; the limit is {limit} bytes"
            ),
            BoardReadError::Board(error) => write!(f, "{error}"),
        }
    }
}

impl std::error::Error for BoardReadError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            BoardReadError::Io(error) => Some(error),
            BoardReadError::Board(error) => Some(error),
            BoardReadError::TooLarge { .. } => None,
        }
    }
}

/// A board file that could not be read or is not a valid board.
#[derive(Debug)]
#[non_exhaustive]
pub enum BoardFileError {
    /// The file could not be read.
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        error: std::io::Error,
    },
    /// The file's text is not a valid board (the error names the line, component or edge).
    Board {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        error: BoardError,
    },
    /// The file holds more bytes than the limit ([`MAX_BOARD_FILE_BYTES`] unless
    /// [`read_board_file_with_limit`] sets another); a device or pipe that never ends (such as
    /// `/dev/zero`) is stopped there.
    TooLarge {
        /// The file.
        path: PathBuf,
        /// The limit, in bytes.
        limit: u64,
    },
    /// The file's name ends neither in `.poly` nor in `.txt`.
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
}

impl core::fmt::Display for BoardFileError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            BoardFileError::Io { path, error } => write!(f, "{}: {error}", path.display()),
            BoardFileError::Board { path, error } => write!(f, "{}: {error}", path.display()),
            BoardFileError::TooLarge { path, limit } => write!(
                f,
                "{}: the file holds more than {limit} bytes; the limit for a board file is \
                 {limit} bytes",
                path.display()
            ),
            BoardFileError::UnknownFormat { path } => write!(
                f,
                "{}: unknown board format: the name must end in .poly (Triangle's format) or \
                 .txt (one component per line), in any case",
                path.display()
            ),
        }
    }
}

impl std::error::Error for BoardFileError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            BoardFileError::Io { error, .. } => Some(error),
            BoardFileError::Board { error, .. } => Some(error),
            BoardFileError::TooLarge { .. } | BoardFileError::UnknownFormat { .. } => None,
        }
    }
}

/// The most bytes [`read_board_file`] reads: 2^30 (1 GiB), far above the largest board the
/// mesher's default budget takes (a board of 10 MB already needs about 18 million triangles).
pub const MAX_BOARD_FILE_BYTES: u64 = 1 << 30;

/// Reads the board in `path`, in the format its name says ([`BoardFormat::from_path`]); `size`
/// is the caller's choice of U, which must agree with a size the file gives. At most
/// [`MAX_BOARD_FILE_BYTES`] are read, whatever the file is (a regular file, a pipe, a device);
/// see [`read_board_file_with_limit`].
///
/// # Errors
///
/// [`BoardFileError::UnknownFormat`] for a name ending neither in `.poly` nor in `.txt`
/// (checked before the file is opened), [`BoardFileError::Io`] when the file cannot be read,
/// [`BoardFileError::TooLarge`] for a file of more than [`MAX_BOARD_FILE_BYTES`], and
/// [`BoardFileError::Board`] with the reader's error (see [`BoardFormat::read_bytes`]).
///
/// # Complexity
///
/// O(n + E log E) time and O(n) memory for a file of n bytes and E edges.
///
/// ```
/// use orthtree::io::read_board_file;
/// let dir = std::env::temp_dir().join("orthtree-doc-board");
/// std::fs::create_dir_all(&dir).unwrap();
/// let path = dir.join("b.TXT");
/// std::fs::write(&path, "size 16\n4 4  8 4  8 8  4 8\n").unwrap();
/// assert_eq!(read_board_file(&path, None).unwrap().components().len(), 1);
/// assert_eq!(read_board_file(&path, Some(16)).unwrap().size(), 16);
/// let conflict = read_board_file(&path, Some(32)).unwrap_err();
/// assert!(conflict.to_string().contains("the file gives board size 16"));
/// let missing = read_board_file(dir.join("none.poly"), None).unwrap_err();
/// assert!(missing.to_string().contains("none.poly"));
/// ```
pub fn read_board_file(path: impl AsRef<Path>, size: Option<i64>) -> Result<Board, BoardFileError> {
    read_board_file_with_limit(path, size, MAX_BOARD_FILE_BYTES)
}

/// [`read_board_file`] reading at most `max_bytes + 1` bytes, the last one only to tell that
/// the file goes on, so memory stays within `max_bytes` bytes of text even for a file that
/// never ends.
///
/// ```
/// use orthtree::io::{read_board_file_with_limit, BoardFileError};
/// let dir = std::env::temp_dir().join("orthtree-doc-board-limit");
/// std::fs::create_dir_all(&dir).unwrap();
/// let path = dir.join("b.txt");
/// std::fs::write(&path, "size 16\n4 4  8 4  8 8  4 8\n").unwrap(); // 27 bytes
/// assert!(read_board_file_with_limit(&path, None, 27).is_ok());
/// let err = read_board_file_with_limit(&path, None, 26).unwrap_err();
/// assert!(matches!(err, BoardFileError::TooLarge { limit: 26, .. }));
/// ```
///
/// # Errors
///
/// As [`read_board_file`], with [`BoardFileError::TooLarge`] for more than `max_bytes` bytes.
pub fn read_board_file_with_limit(
    path: impl AsRef<Path>,
    size: Option<i64>,
    max_bytes: u64,
) -> Result<Board, BoardFileError> {
    let path = path.as_ref();
    let format = BoardFormat::from_path(path).ok_or_else(|| BoardFileError::UnknownFormat {
        path: path.to_path_buf(),
    })?;
    let file = std::fs::File::open(path).map_err(BoardReadError::Io);
    let path = path.to_path_buf();
    file.and_then(|file| format.read_with_limit(file, size, max_bytes))
        .map_err(|e| match e {
            BoardReadError::Io(error) => BoardFileError::Io { path, error },
            BoardReadError::TooLarge { limit } => BoardFileError::TooLarge { path, limit },
            BoardReadError::Board(error) => BoardFileError::Board { path, error },
        })
}
