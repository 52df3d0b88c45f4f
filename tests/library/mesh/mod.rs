//! The board mesher: GENERATEMESH and its modes against an independent oracle, board input, and the
//! mesh writers.

mod board_input;
mod mesh_io;
mod mesh_modes;
mod mesh_writers;
mod mesher;
#[cfg(feature = "serde")]
mod serde_mesh;
mod svg_writer;
mod validate_errors;
mod writer_checksums;
