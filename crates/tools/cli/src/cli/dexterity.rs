//! `robofmu dexterity ...`: condition indices, load index and workspaces of the planar
//! 1-RRR, 2-RRR and 3-RRR manipulators. Angles on the command line are in degrees;
//! CSV files and plots label their units (cm, deg).

mod maps;
mod options;
mod output;
mod scalars;
mod sweeps;

use super::CliError;
use clap::{Args, Subcommand};

/// Dexterity analyses of planar RRR manipulators.
#[derive(Args)]
pub struct DexterityArgs {
    #[command(subcommand)]
    command: DexterityCommand,
}

#[derive(Subcommand)]
enum DexterityCommand {
    /// Print the largest LCI at one orientation (just the number).
    MaxLci(scalars::MaxLciArgs),
    /// Print the GCI of a manipulator (just the number).
    Gci(scalars::GciArgs),
    /// Print the GCI on successively refined grids (convergence table).
    GciConvergence(scalars::GciArgs),
    /// Write LCI maps over x, y at one orientation (each working mode and the best).
    LciMap(maps::MapArgs),
    /// Write load-index maps over x, y (by default at the orientation of the largest LCI).
    LoadMap(maps::LoadMapArgs),
    /// Write the reachable workspace of each manipulator and their common workspace.
    Workspace(maps::WorkspaceArgs),
    /// Write the largest LCI versus phi (own and common workspace) and time the sweep.
    PhiSweep(sweeps::SweepArgs),
    /// Print the largest LCI at one orientation for every reading of the parallel layouts.
    Readings(sweeps::ReadingsArgs),
}

/// Runs a `dexterity` subcommand.
pub fn run(args: DexterityArgs) -> Result<(), CliError> {
    match args.command {
        DexterityCommand::MaxLci(a) => scalars::max_lci(&a),
        DexterityCommand::Gci(a) => scalars::gci(&a),
        DexterityCommand::GciConvergence(a) => scalars::gci_convergence(&a),
        DexterityCommand::LciMap(a) => maps::lci_maps(&a),
        DexterityCommand::LoadMap(a) => maps::load_maps(&a),
        DexterityCommand::Workspace(a) => maps::workspaces(&a),
        DexterityCommand::PhiSweep(a) => sweeps::phi_sweep(&a),
        DexterityCommand::Readings(a) => sweeps::readings(&a),
    }
}
