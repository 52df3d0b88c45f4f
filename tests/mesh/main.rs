//! The board mesher: GENERATEMESH and its modes against an independent oracle, board input, and the
//! mesh writers.
//!
//! One test binary per area: each former test file is a module of it.

#[path = "../common/mod.rs"]
mod common;
#[path = "../mesh_oracle/mod.rs"]
mod mesh_oracle;

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
