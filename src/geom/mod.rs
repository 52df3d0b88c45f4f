//! The vocabulary shared by every layer: [`Scalar`] coordinates, closed boxes ([`Aabb`]), exact
//! dyadic cells ([`Cell`]) with Morton keys, cells 64 levels deep on every axis ([`DeepCell`]),
//! [`Direction`]s with their [`Connectivity`], the [`RootGeometry`] that maps coordinates to
//! cells exactly (used by every tree and by the query engines), and the [`Halves`] test by which
//! a search tells an index the children of a box it may leave out.

mod aabb;
mod cell;
pub mod deep;
mod direction;
mod float_bits;
mod halves;
pub mod morton;
mod root;
mod root_deep;
mod scalar;

pub use aabb::{Aabb, AabbError};
pub use cell::Cell;
pub(crate) use cell::{digit, same_cell, Dim};
pub use deep::{DeepCell, DeepKey};
pub use direction::{Connectivity, Direction};
pub use float_bits::FloatBits;
pub(crate) use halves::halves_by_terms;
pub use halves::{Halves, Kept};
pub(crate) use root::child_box;
pub use root::RootGeometry;
pub(crate) use scalar::{check_point, exact_point, fault, Checked, Fault};
pub use scalar::{validate_point, Scalar};
