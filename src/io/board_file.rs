//! [`read_board_file`]: a board for the mesher from a file, in the format its name says
//! (Triangle's `.poly`, else the plain text of [`super::board_text`]), with errors that name the
//! file.

use crate::mesh::{Board, BoardError};
use std::path::{Path, PathBuf};

/// A board file that could not be read or is not a valid board.
#[derive(Debug)]
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
}

impl core::fmt::Display for BoardFileError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            BoardFileError::Io { path, error } => write!(f, "{}: {error}", path.display()),
            BoardFileError::Board { path, error } => write!(f, "{}: {error}", path.display()),
        }
    }
}

impl std::error::Error for BoardFileError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            BoardFileError::Io { error, .. } => Some(error),
            BoardFileError::Board { error, .. } => Some(error),
        }
    }
}

/// Reads the board in `path`: [`super::poly::read_poly`] for a name ending in `.poly`, else
/// [`super::board_text::read_board_text`]; `size` overrides the board size the file gives.
///
/// ```
/// use orthtree::io::read_board_file;
/// let dir = std::env::temp_dir().join("orthtree-doc-board");
/// std::fs::create_dir_all(&dir).unwrap();
/// let path = dir.join("b.txt");
/// std::fs::write(&path, "size 16\n4 4  8 4  8 8  4 8\n").unwrap();
/// assert_eq!(read_board_file(&path, None).unwrap().components().len(), 1);
/// let missing = read_board_file(dir.join("none.poly"), None).unwrap_err();
/// assert!(missing.to_string().contains("none.poly"));
/// ```
pub fn read_board_file(path: impl AsRef<Path>, size: Option<i64>) -> Result<Board, BoardFileError> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|error| BoardFileError::Io {
        path: path.to_path_buf(),
        error,
    })?;
    let board = if path.extension().is_some_and(|e| e == "poly") {
        super::poly::read_poly(&text, size)
    } else {
        super::board_text::read_board_text(&text, size)
    };
    board.map_err(|error| BoardFileError::Board {
        path: path.to_path_buf(),
        error,
    })
}
