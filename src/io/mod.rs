//! Readers and writers at the edge of the crate: nothing in the trees depends on them.
//!
//! - [`svg`]: SVG pictures of 2D trees (cells, refinements, points), y axis up, written as
//!   plain strings with no dependencies.

pub mod svg;

pub use svg::{point_tree_svg, Style, Svg};
