//! `pss3 ct-reference`: the reference of the ComputedTorque FMU at its defaults (the
//! case the FMI cross-check layout can express: no start values, no inputs), from
//! Lagrange's equations of the library (a second formulation of the dynamics; the FMU
//! uses Kane's method), never the FMU.
//!
//! The FMU's defaults: gains by a triple pole at -30 rad/s (Kp = 2700, Kd = 90, Ki =
//! 27000), the model the plant's, measured at rest in the start pose theta0 (0, 0,
//! 122.07 deg), planned at rest 0.5, -0.5 and 1 deg away (e constant). The integral is
//! e t, so a(t) = Kp e + Ki e t and, at rest, u(t) = M_L(theta0) a(t) + G_L(theta0).

use super::csv::write_csv;
use crate::cli::{CliError, io_at};
use clap::Args;
use nalgebra::Vector3;
use robofmu::computed_torque::pole_placement;
use robofmu::pss3::dynamics::lagrange::lagrange_form;
use robofmu::pss3::dynamics::{Plant, PlantParams};
use robofmu::pss3::start_pose;
use std::path::PathBuf;

/// The FMU's default bandwidth, rad/s, and planned offset from the measured pose, deg.
const BANDWIDTH: f64 = 30.0;
const PLANNED_OFFSET_DEG: [f64; 3] = [0.5, -0.5, 1.0];
/// The FMU's default experiment, s.
const STOP_TIME: f64 = 2.0;
const STEP: f64 = 1e-3;
/// Absolute tolerance, N m: the held-input integral of both interfaces is exact, and
/// Lagrange's and Kane's formulations differ by rounding (measured 4e-12 N m on u up
/// to 120 N m).
const TOLERANCE: f64 = 1e-9;

#[derive(Args)]
pub struct CtReferenceArgs {
    /// Output directory.
    #[arg(long, default_value = "tests/references/ComputedTorque/defaults")]
    out_dir: PathBuf,
}

pub fn run(args: &CtReferenceArgs) -> Result<(), CliError> {
    let plant = Plant::new(PlantParams::default())?;
    let theta = start_pose();
    let error = Vector3::from(PLANNED_OFFSET_DEG).map(f64::to_radians);
    let gains = pole_placement(BANDWIDTH, true)?;
    let form = lagrange_form(plant.model(), &theta, &Vector3::zeros())?;
    let steps = (STOP_TIME / STEP).round() as usize;
    let rows = (0..=steps).map(|k| {
        let t = k as f64 * STEP;
        let a = error * (gains.kp + gains.ki * t);
        let u = form.mass * a + form.gravity;
        vec![t, u.x, u.y, u.z]
    });
    std::fs::create_dir_all(&args.out_dir).map_err(io_at(&args.out_dir))?;
    let columns = ["time", "u[1]", "u[2]", "u[3]"];
    write_csv(&args.out_dir.join("ComputedTorque_ref.csv"), &columns, rows)?;
    write_inputs(args, &theta, &(theta + error))?;
    let opt = args.out_dir.join("ComputedTorque_ref.opt");
    let options =
        format!("StartTime, 0.0\nStopTime, {STOP_TIME:?}\nStepSize, {STEP:?}\nRelTol, 1e-08\n");
    std::fs::write(&opt, options).map_err(io_at(&opt))?;
    let tolerances = (1..=3)
        .map(|i| format!("      \"u[{i}]\": {TOLERANCE:?}"))
        .collect::<Vec<_>>()
        .join(",\n");
    let case = format!(
        "{{\n  \"event_times\": [],\n  \"start_values\": {{}},\n  \"tolerances\": {{\n    \
         \"CoSimulation\": {{\n{tolerances}\n    }},\n    \"ModelExchange\": {{\n{tolerances}\n    }}\n  }}\n}}\n"
    );
    let case_file = args.out_dir.join("case.json");
    std::fs::write(&case_file, case).map_err(io_at(&case_file))?;
    outln!("wrote {} samples to {}", steps + 1, args.out_dir.display());
    Ok(())
}

/// ComputedTorque_input.csv: the default inputs, constant (the cross-check layout gives
/// a model with inputs its input file): measured theta0, planned `planned`, at rest.
fn write_inputs(
    args: &CtReferenceArgs,
    theta: &Vector3<f64>,
    planned: &Vector3<f64>,
) -> Result<(), CliError> {
    let names = [
        "setpoint",
        "setpointRate",
        "setpointAcceleration",
        "measurement",
        "measuredRate",
    ];
    let values = [
        *planned,
        Vector3::zeros(),
        Vector3::zeros(),
        *theta,
        Vector3::zeros(),
    ];
    let mut columns = vec!["time".to_string()];
    let mut row = Vec::new();
    for (name, value) in names.iter().zip(&values) {
        for i in 0..3 {
            columns.push(format!("{name}[{}]", i + 1));
            row.push(value[i]);
        }
    }
    let columns: Vec<&str> = columns.iter().map(String::as_str).collect();
    let rows = [0.0, STOP_TIME].map(|t| [vec![t], row.clone()].concat());
    let path = args.out_dir.join("ComputedTorque_input.csv");
    write_csv(&path, &columns, rows.into_iter())
}
