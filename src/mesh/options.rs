//! [`MeshOptions`]: the settings of the mesher, as a builder (in the manner of spade's
//! `RefinementParameters`), and [`OptionsError`], why a setting was refused.
//!
//! Every setting keeps the chapter's guarantees (Theorem 14.5's mesh: conforming, respecting the
//! input, every angle in [45, 90] degrees, regions right); the settings only choose which cells
//! are split (see the `refine` module for the rule):
//!
//! - the grid unit g: the board is meshed as if every coordinate were divided by g, so a board
//!   scaled by 2^k gives the same mesh scaled. By default g is detected: the largest power of
//!   two dividing every coordinate and U ([`Board::grid_unit`]);
//! - [`Mode::Book`]: the chapter's rule, cells meeting a component edge are split down to the
//!   near size (one grid unit unless set); [`Mode::Coarsest`]: a cell is split only where it must
//!   be, where a component edge crosses its interior other than as its diagonal or a component
//!   vertex lies on it other than at a corner (the near size, if set, applies as well);
//! - a maximum cell size everywhere, and a user size function (Chew's idea, "Guaranteed-quality
//!   mesh generation for curved surfaces", 1993: the user says where a cell is fine enough).

use super::budget::{TooManyTriangles, DEFAULT_MAX_TRIANGLES};
use super::generate::{generate, MeshOutcome};
use super::{Board, Point};
use core::fmt;
use std::sync::Arc;

/// A user size function: at a point (board coordinates), the largest cell side wanted there.
/// A cell is split while its side exceeds the value at its centre (and it is larger than one
/// grid unit). Values must be positive (infinity means "no limit"); values below one grid unit
/// ask for unit cells.
pub type SizeFn = dyn Fn([f64; 2]) -> f64 + Send + Sync;

/// Which cells the mesher splits (beyond the size limits, which apply in both modes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Mode {
    /// The chapter's GENERATEMESH: a cell meeting a component edge is split down to the near
    /// size, one grid unit by default.
    #[default]
    Book,
    /// Split a cell only where the triangulation could not respect the input otherwise: where a
    /// component edge crosses its interior other than as its diagonal, or a component vertex
    /// lies on its closed square other than at a corner.
    Coarsest,
}

/// The mesher's settings, built up from [`MeshOptions::new`] (the chapter's algorithm with a
/// detected grid unit); [`MeshOptions::generate`] meshes a board with them.
///
/// Sizes are in board coordinates. A cell side is always a power of two times the grid unit, so
/// a size limit h means cells of side at most h (a limit that is not a power of two times the
/// unit acts as the next smaller one).
///
/// ```
/// use orthtree::mesh::{Board, Component, MeshOptions, Mode};
/// // the chapter's Figure 14.2: a unit square near the top-left corner of a 16 x 16 board
/// let board = Board::new(16, vec![Component::new(vec![[1, 14], [2, 14], [2, 15], [1, 15]])])?;
/// let book = MeshOptions::new().generate(&board)?;
/// let coarse = MeshOptions::new().mode(Mode::Coarsest).generate(&board)?;
/// assert_eq!(book.mesh.triangles.len(), 94);
/// assert!(coarse.mesh.triangles.len() <= 52); // the book's own hand-made mesh has 52
/// assert!(coarse.mesh.validate(&board).is_ok());
/// // the same board drawn four times finer meshes to the same triangles, scaled
/// let fine = Board::new(64, vec![Component::new(vec![[4, 56], [8, 56], [8, 60], [4, 60]])])?;
/// let scaled = MeshOptions::new().mode(Mode::Coarsest).generate(&fine)?;
/// assert_eq!(scaled.grid_unit, 4);
/// assert_eq!(scaled.mesh.triangles.len(), coarse.mesh.triangles.len());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Default)]
pub struct MeshOptions {
    settings: MeshSettings,
    size_fn: Option<Arc<SizeFn>>,
}

/// The settings of [`MeshOptions`] but the size function: what serde writes of them.
#[derive(Clone, Copy, Debug, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct MeshSettings {
    mode: Mode,
    grid_unit: Option<i64>,
    near_size: Option<i64>,
    max_size: Option<i64>,
    max_triangles: Option<u64>,
}

impl fmt::Debug for MeshOptions {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = &self.settings;
        f.debug_struct("MeshOptions")
            .field("mode", &s.mode)
            .field("grid_unit", &s.grid_unit)
            .field("near_size", &s.near_size)
            .field("max_size", &s.max_size)
            .field(
                "size_fn",
                &self.size_fn.as_ref().map(|_| "Fn([f64; 2]) -> f64"),
            )
            .field("max_triangles", &s.max_triangles)
            .finish()
    }
}

impl MeshOptions {
    /// The chapter's algorithm ([`Mode::Book`]), grid unit detected, no size limits.
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets the mode.
    pub fn mode(mut self, mode: Mode) -> Self {
        self.settings.mode = mode;
        self
    }

    /// Fixes the grid unit (a power of two dividing U and every coordinate) instead of detecting
    /// it. `grid_unit(1)` is the chapter's unit whatever the board.
    pub fn grid_unit(mut self, unit: i64) -> Self {
        self.settings.grid_unit = Some(unit);
        self
    }

    /// Cells meeting a component edge get at most this side (at least one grid unit). In book
    /// mode the default is one grid unit; in coarsest mode there is no default limit.
    pub fn near_size(mut self, size: i64) -> Self {
        self.settings.near_size = Some(size);
        self
    }

    /// Every cell gets at most this side (at least one grid unit). Default: no limit.
    pub fn max_size(mut self, size: i64) -> Self {
        self.settings.max_size = Some(size);
        self
    }

    /// Cells are split while their side exceeds `f` at their centre (see [`SizeFn`]).
    pub fn size_fn(mut self, f: impl Fn([f64; 2]) -> f64 + Send + Sync + 'static) -> Self {
        self.size_fn = Some(Arc::new(f));
        self
    }

    /// Refuses, with [`OptionsError::TooManyTriangles`], a board whose mesh would have more than
    /// `limit` triangles, before spending the time and memory to make it. Default:
    /// [`DEFAULT_MAX_TRIANGLES`] (2 * 10^7, about 2.8 GiB at the measured
    /// [`PEAK_BYTES_PER_TRIANGLE`](super::PEAK_BYTES_PER_TRIANGLE)); `u64::MAX` for no limit. The check is exact (a board is
    /// refused only when its mesh has more triangles than the limit), and a refused board costs
    /// at most the work of `limit / 2` leaves; a refusal from the board's size and outlines alone
    /// (most of them) costs O(p(S)) time and no memory (see the `budget` module).
    ///
    /// ```
    /// use orthtree::mesh::{Board, Component, MeshOptions, OptionsError};
    /// let board = Board::new(16, vec![Component::new(vec![[1, 14], [2, 14], [2, 15], [1, 15]])])?;
    /// assert_eq!(MeshOptions::new().max_triangles(94).generate(&board)?.mesh.triangles.len(), 94);
    /// let err = MeshOptions::new().max_triangles(93).generate(&board).unwrap_err();
    /// assert!(matches!(err, OptionsError::TooManyTriangles(e) if e.at_least == 94));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn max_triangles(mut self, limit: u64) -> Self {
        self.settings.max_triangles = Some(limit);
        self
    }

    /// The triangle limit in force ([`MeshOptions::max_triangles`]).
    pub fn current_max_triangles(&self) -> u64 {
        self.settings.max_triangles.unwrap_or(DEFAULT_MAX_TRIANGLES)
    }

    /// The mode set.
    pub fn current_mode(&self) -> Mode {
        self.settings.mode
    }

    /// The settings as set (`None` where the default applies), and whether a size function is
    /// set: what serde writes.
    #[cfg(feature = "serde")]
    pub(crate) fn settings(&self) -> (MeshSettings, bool) {
        (self.settings, self.size_fn.is_some())
    }

    /// The options of `s`, with no size function, once the settings that do not depend on the
    /// board are checked: the grid unit a positive power of two, the size limits positive.
    ///
    /// # Errors
    /// [`OptionsError::GridUnitNotPowerOfTwo`] or [`OptionsError::SizeNotPositive`], naming the
    /// value.
    #[cfg(feature = "serde")]
    pub(crate) fn from_settings(s: MeshSettings) -> Result<Self, OptionsError> {
        if let Some(unit) = s.grid_unit.filter(|&u| u <= 0 || u & (u - 1) != 0) {
            return Err(OptionsError::GridUnitNotPowerOfTwo { unit });
        }
        for (option, size) in [("near size", s.near_size), ("maximum size", s.max_size)] {
            if let Some(size) = size.filter(|&v| v <= 0) {
                return Err(OptionsError::SizeNotPositive { option, size });
            }
        }
        Ok(MeshOptions {
            settings: s,
            size_fn: None,
        })
    }

    /// Meshes `board` with these options.
    ///
    /// # Errors
    /// An [`OptionsError`]: a grid unit that is not a power of two or does not divide a
    /// coordinate, a size limit that is not positive or below one grid unit, a size function
    /// returning NaN or a value that is not positive. Each names the offending value. A mesh of
    /// more triangles than [`MeshOptions::max_triangles`] is refused with the number it needs at
    /// least.
    ///
    /// # Complexity
    /// In book mode with unit 1, as the chapter's algorithm: O(p(S) log U) triangles in
    /// O(p(S) log^2 U) time (Theorem 14.5); in coarsest mode never more cells are split, and the
    /// work per split cell is the same.
    pub fn generate(&self, board: &Board) -> Result<MeshOutcome, OptionsError> {
        let unit = match self.settings.grid_unit {
            None => board.grid_unit(),
            Some(u) => check_unit(board, u)?,
        };
        let limit = |option: &'static str, size: Option<i64>| match size {
            None => Ok(i64::MAX),
            Some(size) if size <= 0 => Err(OptionsError::SizeNotPositive { option, size }),
            Some(size) if size < unit => Err(OptionsError::SizeBelowUnit { option, size, unit }),
            Some(size) => Ok(size / unit),
        };
        let near = match (self.settings.mode, self.settings.near_size) {
            (Mode::Book, None) => 1,
            (_, size) => limit("near size", size)?,
        };
        let max = limit("maximum size", self.settings.max_size)?;
        generate(
            board,
            unit,
            super::refine::SplitRule {
                near,
                max,
                unit,
                size_fn: self.size_fn.as_deref(),
            },
            self.current_max_triangles(),
        )
    }
}

/// Checks a grid unit given by the user against the board, and hands it back.
fn check_unit(board: &Board, unit: i64) -> Result<i64, OptionsError> {
    if unit <= 0 || unit & (unit - 1) != 0 {
        return Err(OptionsError::GridUnitNotPowerOfTwo { unit });
    }
    // The board's side first (as component 0, at `[U, U]`), then every outline vertex.
    let side = core::iter::once((0, [board.size(); 2]));
    let vertices = (board.components().iter().enumerate())
        .flat_map(|(i, c)| c.outline.iter().map(move |&p| (i + 1, p)));
    for (component, point) in side.chain(vertices) {
        if let Some(value) = point.into_iter().find(|c| c % unit != 0) {
            return Err(OptionsError::GridUnitDoesNotDivide {
                unit,
                value,
                component,
                point,
            });
        }
    }
    Ok(unit)
}

/// Mesher settings refused by [`MeshOptions::generate`], each naming the offending value.
///
/// ```
/// use orthtree::mesh::{Board, Component, MeshOptions, OptionsError};
/// let board = Board::new(8, vec![Component::new(vec![[2, 2], [6, 2], [6, 6], [2, 6]])])?;
/// // the detected unit is 2, so a near size of 1 is below it
/// let err = MeshOptions::new().near_size(1).generate(&board).unwrap_err();
/// assert_eq!(err.to_string(), "near size 1 is below the grid unit 2");
/// let err = MeshOptions::new().size_fn(|_| f64::NAN).generate(&board).unwrap_err();
/// assert_eq!(err.to_string(), "the size function returned NaN at (4, 4)");
/// let err = MeshOptions::new().grid_unit(4).generate(&board).unwrap_err();
/// assert!(matches!(err, OptionsError::GridUnitDoesNotDivide { value: 2, component: 1, .. }));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum OptionsError {
    /// The grid unit is not a positive power of two.
    GridUnitNotPowerOfTwo {
        /// The unit given.
        unit: i64,
    },
    /// The grid unit does not divide a coordinate of the board.
    GridUnitDoesNotDivide {
        /// The unit given.
        unit: i64,
        /// The coordinate it does not divide.
        value: i64,
        /// The component holding it (from 1), or 0 for the board's side U.
        component: usize,
        /// The vertex holding it (for U: `[U, U]`).
        point: Point,
    },
    /// A size limit is zero or negative.
    SizeNotPositive {
        /// Which option: "near size" or "maximum size".
        option: &'static str,
        /// The size given.
        size: i64,
    },
    /// A size limit is below one grid unit.
    SizeBelowUnit {
        /// Which option: "near size" or "maximum size".
        option: &'static str,
        /// The size given.
        size: i64,
        /// The grid unit.
        unit: i64,
    },
    /// The size function returned NaN.
    SizeFunctionNaN {
        /// Where (a cell centre, board coordinates).
        at: [f64; 2],
    },
    /// The size function returned zero or a negative value.
    SizeFunctionNotPositive {
        /// Where (a cell centre, board coordinates).
        at: [f64; 2],
        /// The value returned.
        value: f64,
    },
    /// The mesh would have more triangles than [`MeshOptions::max_triangles`] allows.
    TooManyTriangles(TooManyTriangles),
}

impl fmt::Display for OptionsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            OptionsError::GridUnitNotPowerOfTwo { unit } => {
                write!(f, "grid unit {unit} is not a positive power of two")
            }
            OptionsError::GridUnitDoesNotDivide {
                unit,
                value,
                component: 0,
                ..
            } => write!(
                f,
                "grid unit {unit} does not divide the board's side {value}"
            ),
            OptionsError::GridUnitDoesNotDivide {
                unit,
                value,
                component,
                point: [x, y],
            } => write!(
                f,
                "grid unit {unit} does not divide coordinate {value} of component {component}'s \
                 vertex ({x}, {y})"
            ),
            OptionsError::SizeNotPositive { option, size } => {
                write!(f, "{option} {size} is not positive")
            }
            OptionsError::SizeBelowUnit { option, size, unit } => {
                write!(f, "{option} {size} is below the grid unit {unit}")
            }
            OptionsError::SizeFunctionNaN { at: [x, y] } => {
                write!(f, "the size function returned NaN at ({x}, {y})")
            }
            OptionsError::SizeFunctionNotPositive { at: [x, y], value } => write!(
                f,
                "the size function returned {value} at ({x}, {y}); sizes must be positive"
            ),
            OptionsError::TooManyTriangles(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for OptionsError {}

impl From<TooManyTriangles> for OptionsError {
    fn from(e: TooManyTriangles) -> Self {
        OptionsError::TooManyTriangles(e)
    }
}
