//! orthtree side by side with other spatial crates: the programs `compare` (point queries and
//! updates beside kiddo and rstar), `joins_compare` (periodic and join queries beside kiddo and
//! scipy's cKDTree, [`joins`] and [`scipy`]) and `mesh_compare` (the mesher beside spade's refined
//! Delaunay triangulation), and the criterion benches `build` and `queries`.
//!
//! Every crate sits behind one small adapter ([`rivals::Rival`]), so every crate runs exactly
//! the same workload on the same seeded points ([`points`]), and the answers are checked equal
//! across the crates where they hand back the same thing.

/// `println!` that ignores a closed standard output (a pipe into `head`) instead of panicking;
/// the comparison programs print their tables through it.
#[macro_export]
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout(), $($arg)*);
    }};
}

/// `print!` that ignores a closed standard output, as [`say!`] does.
#[macro_export]
macro_rules! say_raw {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = write!(std::io::stdout(), $($arg)*);
    }};
}

pub mod joins;
#[path = "../../benches/common/mod.rs"]
pub mod points;
pub mod python;
pub mod rivals;
pub mod scipy;
pub mod timing;

#[path = "../../cli/src/limits.rs"]
pub mod limits;
