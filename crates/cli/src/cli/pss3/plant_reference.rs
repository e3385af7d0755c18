//! `pss3 plant-reference`: the open-loop reference of the Pss3Plant FMU for the
//! thesis's path 1, from the library's kinematics and inverse dynamics (never the FMU).
//!
//! All actuators move linearly from 2 mm to 152 mm in 2 s. Along the path: the
//! orientation by forward kinematics, omega and omega_dot by the velocity and
//! acceleration kinematics, the actuator forces that produce that motion by
//! `Plant::inverse_dynamics`. Written into one reference directory:
//! - Pss3Plant_ref.csv: time, theta[1..3], omega[1..3] (the motion the FMU must follow);
//! - Pss3Plant_input.csv: time, actuatorForce[1..3] (what the importer feeds in);
//! - Pss3Plant_ref.opt and case.json: experiment, start values, tolerances.
//!
//! The path runs from one end stop to the other; the stroke parameters are widened
//! (0..160 mm) so that the stops, whose damping switches on exactly at the stroke ends,
//! stay out of an open-loop comparison. Nothing else depends on the stroke.

use super::csv::write_csv;
use crate::cli::CliError;
use clap::Args;
use nalgebra::Vector3;
use robofmu::pss3::dynamics::{Plant, PlantParams, PlantState};
use robofmu::pss3::{FkOptions, Params, Timing, linear_actuator_path};
use std::path::PathBuf;

/// Path 1 of the thesis: start and end displacements, m, and duration, s.
const L_START: f64 = 0.002;
const L_END: f64 = 0.152;
const DURATION: f64 = 2.0;
/// Stroke of the reference case, m (see the module comment).
const STROKE: (f64, f64) = (0.0, 0.16);
/// Tolerances of the comparison, rad and rad/s: the 1e-4 rad of the task for theta;
/// omega scaled by the path's rate of change (theta moves 0.56 rad in 2 s).
const THETA_TOLERANCE: f64 = 1e-4;
const OMEGA_TOLERANCE: f64 = 2e-4;

#[derive(Args)]
pub struct PlantReferenceArgs {
    /// Sampling step of the reference and of the input forces, s.
    #[arg(long, default_value_t = 1e-3)]
    dt: f64,
    /// Output directory.
    #[arg(long, default_value = "tests/references/Pss3Plant/path1")]
    out_dir: PathBuf,
}

pub fn run(args: &PlantReferenceArgs) -> Result<(), CliError> {
    let params = PlantParams {
        geometry: Params {
            stroke_min: STROKE.0,
            stroke_max: STROKE.1,
            ..Params::default()
        },
        ..PlantParams::default()
    };
    let plant = Plant::new(params)?;
    let timing = Timing {
        duration: DURATION,
        dt: args.dt,
    };
    let samples = linear_actuator_path(
        &plant.model().geometry,
        &Vector3::repeat(L_START),
        &Vector3::repeat(L_END),
        &timing,
        &FkOptions::default(),
    )?;
    let mut reference = Vec::with_capacity(samples.len());
    let mut forces = Vec::with_capacity(samples.len());
    for s in &samples {
        let m = &s.motion;
        let state = PlantState {
            euler: m.assembly.euler,
            omega: m.omega,
        };
        let f = plant.inverse_dynamics(&state, &m.omega_dot, &Vector3::zeros())?;
        let mut row = vec![s.time];
        row.extend(m.assembly.euler.iter().chain(m.omega.iter()));
        reference.push(row);
        forces.push(vec![s.time, f[0], f[1], f[2]]);
    }
    std::fs::create_dir_all(&args.out_dir)?;
    let reference_columns = [
        "time", "theta[1]", "theta[2]", "theta[3]", "omega[1]", "omega[2]", "omega[3]",
    ];
    write_csv(
        &args.out_dir.join("Pss3Plant_ref.csv"),
        &reference_columns,
        reference.into_iter(),
    )?;
    let input_columns = [
        "time",
        "actuatorForce[1]",
        "actuatorForce[2]",
        "actuatorForce[3]",
    ];
    write_csv(
        &args.out_dir.join("Pss3Plant_input.csv"),
        &input_columns,
        forces.into_iter(),
    )?;
    std::fs::write(
        args.out_dir.join("Pss3Plant_ref.opt"),
        format!(
            "StartTime, 0.0\nStopTime, {DURATION:?}\nStepSize, {:?}\nRelTol, 1e-10\n",
            args.dt
        ),
    )?;
    let first = &samples[0].motion;
    std::fs::write(
        args.out_dir.join("case.json"),
        case_json(&first.assembly.euler, &first.omega),
    )?;
    println!(
        "wrote {} samples of path 1 to {}",
        samples.len(),
        args.out_dir.display()
    );
    Ok(())
}

/// case.json: start values (stroke, initial state) and tolerances per interface.
fn case_json(theta0: &Vector3<f64>, omega0: &Vector3<f64>) -> String {
    let mut start = vec![
        format!("    \"strokeMin\": {:?}", STROKE.0),
        format!("    \"strokeMax\": {:?}", STROKE.1),
    ];
    for i in 0..3 {
        start.push(format!("    \"theta0[{}]\": {:?}", i + 1, theta0[i]));
        start.push(format!("    \"omega0[{}]\": {:?}", i + 1, omega0[i]));
    }
    let tolerances = |indent: &str| -> String {
        let mut t = Vec::new();
        for i in 1..=3 {
            t.push(format!("{indent}\"theta[{i}]\": {THETA_TOLERANCE:?}"));
            t.push(format!("{indent}\"omega[{i}]\": {OMEGA_TOLERANCE:?}"));
        }
        t.join(",\n")
    };
    format!(
        "{{\n  \"event_times\": [],\n  \"start_values\": {{\n{}\n  }},\n  \"tolerances\": {{\n    \
         \"CoSimulation\": {{\n{}\n    }},\n    \"ModelExchange\": {{\n{}\n    }}\n  }}\n}}\n",
        start.join(",\n"),
        tolerances("      "),
        tolerances("      ")
    )
}
