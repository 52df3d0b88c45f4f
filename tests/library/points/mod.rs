//! The point trees (`PointTree`, `DynamicPointTree`): build, bounds, duplicates, queries against
//! brute force (the tree-against-tree queries are in the module `joins`), single and batch
//! updates, every dimension, bad input, the rayon entry points, and the saved-tree format (feature
//! `saved`) and serde (feature `serde`).

mod approx;
mod bad_input;
mod batch_updates;
mod best_within;
mod build_order;
mod duplicates;
mod dynamic;
mod every_dimension_points;
mod parallel;
mod periodic;
mod periodic_far;
mod periodic_images;
mod point_bounds;
mod point_sets;
mod point_tree;
mod queries;
#[cfg(feature = "saved")]
mod saved;
#[cfg(feature = "saved")]
mod saved_fuzz;
#[cfg(feature = "serde")]
mod serde_dynamic;
#[cfg(all(feature = "serde", feature = "saved"))]
mod serde_round_trips;
#[cfg(feature = "serde")]
mod serde_settings;
mod streaming;
mod updates;
mod updates_after_balance;
