//! The circuit-board mesher of the chapter's section 14.3 (D = 2): a [`Board`] in, a conforming
//! triangle [`Mesh`] that respects the input, with every angle in [45, 90] degrees, out.

mod board;
mod box_index;
mod budget;
mod check;
mod error;
mod generate;
pub(crate) mod halfedge;
mod labels;
mod nesting;
mod options;
mod outline;
mod output;
mod pairing;
mod random_board;
mod refine;
mod samples;
mod validate;
mod vertices;

pub use board::{Board, Component, Point};
pub use budget::{TooManyTriangles, DEFAULT_MAX_TRIANGLES, PEAK_BYTES_PER_TRIANGLE};
pub use error::BoardError;
pub use generate::{generate_mesh, MeshOutcome};
pub use halfedge::{HalfEdgeError, HalfEdges};
#[cfg(feature = "serde")]
pub(crate) use options::MeshSettings;
pub use options::{MeshOptions, Mode, OptionsError, SizeFn};
pub use output::{Mesh, Segment, SegmentKind};
pub use random_board::{random_board, random_board_capacity, try_random_board, RandomBoardError};
pub use samples::sample_board;
pub use validate::{BoardSide, Check, MeshValidationError, RegionRule, ValidationReport};
