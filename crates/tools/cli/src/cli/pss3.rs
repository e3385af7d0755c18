//! `robofmu pss3 ...`: kinematics of the 3-PSS robot with the default parameters of
//! docs/3pss-model.md. Angles are degrees on the command line and in the printout,
//! lengths metres; everything inside and in CSV files is SI.

mod csv;
mod ct_reference;
mod path;
mod plant_reference;
mod pose;
mod workspace;
mod workspace_output;

use super::CliError;
use clap::Subcommand;

/// Subcommands of `robofmu pss3`.
#[derive(Subcommand)]
pub enum Pss3Command {
    /// Inverse kinematics: actuator displacements and legs at one orientation.
    Ik(pose::IkArgs),
    /// Forward kinematics: the orientation for given actuator displacements.
    Fk(pose::FkArgs),
    /// The actuator Jacobian (l_dot = J omega), det, cond and leg projections at a pose.
    Jacobian(pose::IkArgs),
    /// Actuators driven linearly in time: platform motion sampled into a CSV file.
    ActuatorPath(path::PathArgs),
    /// Open-loop reference of the Pss3Plant FMU for path 1 (kinematics + inverse
    /// dynamics): reference motion, input forces, options and case file.
    PlantReference(plant_reference::PlantReferenceArgs),
    /// Reference of the ComputedTorque FMU at its defaults (Lagrange's inverse dynamics):
    /// output, options and case file.
    CtReference(ct_reference::CtReferenceArgs),
    /// Workspace scans (stroke box by FK, orientation grid by IK): CSV files and plots.
    Workspace(workspace::WorkspaceArgs),
}

/// Runs one `pss3` subcommand.
pub fn run(command: Pss3Command) -> Result<(), CliError> {
    match command {
        Pss3Command::Ik(args) => pose::run_ik(&args),
        Pss3Command::Fk(args) => pose::run_fk(&args),
        Pss3Command::Jacobian(args) => pose::run_jacobian(&args),
        Pss3Command::ActuatorPath(args) => path::run(&args),
        Pss3Command::PlantReference(args) => plant_reference::run(&args),
        Pss3Command::CtReference(args) => ct_reference::run(&args),
        Pss3Command::Workspace(args) => workspace::run(&args),
    }
}
