//! `orthtree`: the crate's command-line program.
//!
//! - `orthtree mesh [BOARD]`: the main job, the chapter's quadtree mesher on a circuit board;
//! - `orthtree heat [BOARD]`: steady heat on the board's mesh (with the `heat` feature);
//! - `orthtree image OP A [B] --out C` (or `--op OP`): Boolean operations on images with region trees;
//! - `orthtree balance`: p4est's fractal refinement, then 2:1 balance;
//! - `orthtree dist-balance`, `orthtree dist-points`: the forest and the point tree over MPI
//!   ranks, run under `mpirun` (with the `mpi` feature);
//! - `orthtree cloud info|downsample|outliers|diff|index`: point clouds (PLY, XYZ/CSV, LAS/LAZ).
//!
//! Every command answers `--help`. Exit codes: 0 success, 1 an input or processing error (a file
//! that cannot be read or written, a board the mesher refuses, a check that fails), 2 a usage
//! error (an unknown option, a bad value, work the arguments make too large); an error is one
//! `error:` line naming the argument or the file.

#[macro_use]
mod print;

mod balance;
mod cloud;
#[cfg(feature = "mpi")]
mod dist;
mod heat;
mod image;
mod limits;
mod mesh;
mod progress;
mod random_board;

use clap::error::ErrorKind;
use clap::{CommandFactory, Parser, Subcommand};
use std::process::ExitCode;

/// The exit codes, as `--help` lists them.
pub const EXIT_CODES: &str = "\
Exit codes:
  0  success
  1  an input or processing error (a file that cannot be read or written, a board the mesher
     refuses, a check that fails)
  2  a usage error (an unknown option, a bad value, work the arguments make too large)";

/// 2^D-trees at work: mesh a circuit board with the chapter's quadtree mesher, solve heat on it,
/// combine images with region quadtrees, balance p4est's fractal, voxelise point clouds.
#[derive(Parser, Debug)]
#[command(name = "orthtree", version, after_help = EXIT_CODES, propagate_version = true)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    Mesh(mesh::MeshArgs),
    Heat(heat::HeatArgs),
    Image(image::ImageArgs),
    Balance(balance::BalanceArgs),
    Cloud(cloud::CloudArgs),
    #[cfg(feature = "mpi")]
    DistBalance(dist::DistBalanceArgs),
    #[cfg(feature = "mpi")]
    DistPoints(dist::DistPointsArgs),
}

/// Why a command stopped.
#[derive(Debug)]
pub enum Failure {
    /// The arguments are wrong or ask for too much (exit code 2): the message names the argument.
    Usage(String),
    /// Reading, processing or writing failed (exit code 1): the message names the item.
    Input(String),
}

impl Failure {
    /// The exit code of this failure.
    fn code(&self) -> u8 {
        match self {
            Failure::Usage(_) => 2,
            Failure::Input(_) => 1,
        }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let (name, outcome) = match &cli.command {
        Command::Mesh(args) => ("mesh", mesh::run(args)),
        Command::Heat(args) => ("heat", heat::run(args)),
        Command::Image(args) => ("image", image::run(args)),
        Command::Balance(args) => ("balance", balance::run(args)),
        Command::Cloud(args) => ("cloud", cloud::run(args)),
        #[cfg(feature = "mpi")]
        Command::DistBalance(args) => ("dist-balance", dist::run_balance(args)),
        #[cfg(feature = "mpi")]
        Command::DistPoints(args) => ("dist-points", dist::run_points(args)),
    };
    match outcome {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Usage(message)) => {
            // clap's format, with the command's usage line and exit code 2.
            let mut command = Cli::command();
            let mut sub = command.find_subcommand_mut(name).map(|c| c.clone());
            let mut bin = format!("orthtree {name}");
            // A command with commands of its own (`cloud`): the one that ran.
            if let (Some(inner), Command::Cloud(args)) = (sub.as_mut(), &cli.command) {
                let leaf = args.name();
                if let Some(c) = inner.find_subcommand_mut(leaf).map(|c| c.clone()) {
                    bin = format!("{bin} {leaf}");
                    sub = Some(c);
                }
            }
            let mut target = sub.unwrap_or(command);
            target = target.bin_name(bin);
            target.error(ErrorKind::ValueValidation, message).exit()
        }
        Err(failure @ Failure::Input(_)) => {
            let (Failure::Input(message) | Failure::Usage(message)) = &failure;
            eprintln!("error: {message}");
            ExitCode::from(failure.code())
        }
    }
}
