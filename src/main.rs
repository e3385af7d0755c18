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
    /// FMU tooling: modelDescription files and packaging.
    Fmi(cli::fmi::FmiArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result: Result<(), cli::CliError> = match cli.command {
        Command::Fmi(args) => cli::fmi::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("robofmu: {e}");
            ExitCode::FAILURE
        }
    }
}
