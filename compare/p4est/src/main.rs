//! p4est 2.2's balance on the fractal that `orthtree dist-balance` balances (feature
//! `p4est`; the build script compiles `balance.c` against the system's p4est): run under
//! `mpirun -np P` beside `orthtree dist-balance` at the same P, it prints p4est's leaf counts before and
//! after balance (equal to orthtree's) and its balance time (maximum over ranks, median of the
//! runs).
//!
//! ```sh
//! apt-get install libp4est-dev
//! cargo build --release -p orthtree-p4est --features p4est --bin p4est_balance
//! mpirun -np 2 target/release/p4est_balance --dim 3 --level 8 --connect corner --reps 3
//! ```
//!
//! The program checks its arguments and then replaces itself with the C driver for the
//! dimension (same process, so `mpirun` sees it as the rank).

use clap::Parser;
use std::os::unix::process::CommandExt;
use std::process::Command;

/// p4est's balance on p4est's fractal (the driver compiled by the build script)
#[derive(Parser, Debug)]
struct Args {
    /// Dimension: 2 or 3
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u8).range(2..=3))]
    dim: u8,
    /// Refinement level: 0 to 29 in 2D, 0 to 18 in 3D (p4est's deepest quadrant levels)
    #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u8).range(0..=29))]
    level: u8,
    /// Balance across faces, edges or corners
    #[arg(long, default_value = "face", value_parser = ["face", "edge", "corner"])]
    connect: String,
    /// Balance runs, median reported
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u8).range(1..=100))]
    reps: u8,
}

fn main() {
    let args = Args::parse();
    if args.dim == 3 && args.level > 18 {
        eprintln!(
            "error: --level {}: p4est's deepest 3D level is 18",
            args.level
        );
        std::process::exit(2);
    }
    let driver = if args.dim == 2 {
        env!("P4EST_BALANCE_2D")
    } else {
        env!("P4EST_BALANCE_3D")
    };
    let error = Command::new(driver)
        .arg(args.level.to_string())
        .arg(&args.connect)
        .arg(args.reps.to_string())
        .exec();
    eprintln!("error: could not run {driver}: {error}");
    std::process::exit(1);
}
