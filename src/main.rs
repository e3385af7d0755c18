//! `robofmu`: command-line front end of the robot analyses.

use clap::{Parser, Subcommand};
use std::process::ExitCode;

mod cli;

/// Robot models and analyses of the robofmu project (SI inside, degrees in labelled output).
#[derive(Parser)]
#[command(name = "robofmu", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Dexterity of planar 1-RRR, 2-RRR and 3-RRR manipulators.
    Dexterity(cli::dexterity::DexterityArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result: Result<(), cli::CliError> = match cli.command {
        Command::Dexterity(args) => cli::dexterity::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("robofmu: {e}");
            ExitCode::FAILURE
        }
    }
}
