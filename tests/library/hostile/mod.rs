//! Hostile input: the readers' fuzz and hostile-file tests, board sizes and bytes, the mesher's
//! budget, random boards, float parameters and integer coordinates. No input may panic or exhaust
//! memory: CI also runs this module alone under an address-space limit (`prlimit
//! --as=4000000000 cargo test --test library hostile::`).

mod board_bytes;
mod board_file_limits;
mod board_fuzz;
mod board_size;
mod float_parameters;
mod image_budget;
mod image_fuzz;
mod image_hostile;
mod image_png_hostile;
mod integer_coordinates;
mod mesh_budget;
mod poly_strict;
mod random_board;
