//! `robofmu`: command-line front end of the robot analyses.

use clap::{Parser, Subcommand};
use std::process::ExitCode;

mod cli;
mod plot;

/// Robot models and analyses of the robofmu project (SI inside, degrees in labelled output).
#[derive(Parser)]
#[command(name = "robofmu", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Kinematics of the 3-PSS spherical parallel robot.
    #[command(subcommand)]
    Pss3(cli::pss3::Pss3Command),
    /// Optimal joint paths of the dual-arm cam-lock robot.
    #[command(name = "dual-arm")]
    DualArm(cli::dual_arm::DualArmArgs),
    /// The planner -> PID -> 3-PSS plant loop: Rust reference and PID gain design.
    #[command(subcommand, name = "closed-loop")]
    ClosedLoop(cli::closed_loop::ClosedLoopCommand),
    /// Dexterity of planar 1-RRR, 2-RRR and 3-RRR manipulators.
    Dexterity(cli::dexterity::DexterityArgs),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return cli::report::parse_error(&e),
    };
    let result: Result<(), cli::CliError> = match cli.command {
        Command::Pss3(command) => cli::pss3::run(command),
        Command::DualArm(args) => cli::dual_arm::run(args),
        Command::Dexterity(args) => cli::dexterity::run(args),
        Command::ClosedLoop(command) => cli::closed_loop::run(command),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => cli::report::failure(e.as_ref()),
    }
}
