//! The arena topology `Tree`: 2:1 balance in every connectivity, neighbour finding, every operation
//! in every dimension.

mod balance;
mod balance_levels;
mod cells;
mod directions;
mod every_dimension_tree;
mod module_graph;
mod neighbors;
mod public_surface;
mod split_balanced;
