//! Region trees of images: Boolean operations and their laws, bounds, PBM and PNG (feature `png`),
//! every dimension.

mod every_dimension_regions;
mod image_bounds;
mod image_laws;
mod image_malformed;
mod image_ops;
mod image_pbm;
mod image_png;
mod image_rows;
