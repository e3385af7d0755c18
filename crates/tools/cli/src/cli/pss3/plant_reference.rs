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
//!
//! With `--from-default-pose`, a case at the FMU's default parameters instead (the kind
//! the FMI cross-check layout can express: it has no start values): from rest at the
//! default pose (all actuators at 77 mm), the actuators move rest to rest to
//! (110, 80, 50) mm in 2 s on a quintic in time; inputs and reference as for path 1.

use super::csv::write_csv;
use crate::cli::{CliError, io_at};
use clap::Args;
use nalgebra::Vector3;
use robofmu::pss3::dynamics::{Plant, PlantParams, PlantState};
use robofmu::pss3::{
    ActuatorState, FkOptions, Geometry, Params, PathError, PathSample, Timing, forward_motion,
    linear_actuator_path, start_pose,
};
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
/// The Pss3Plant FMU's default actuator displacement (parameter l0), m.
const DEFAULT_DISPLACEMENT: f64 = 0.077;
/// End displacements of the move from the default pose, m.
const DEFAULT_POSE_MOVE_END: [f64; 3] = [0.11, 0.08, 0.05];

#[derive(Args)]
pub struct PlantReferenceArgs {
    /// Sampling step of the reference and of the input forces, s (> 0, at most 1e6 samples).
    #[arg(long, default_value_t = 1e-3, allow_hyphen_values = true,
          value_parser = crate::cli::bounds::positive)]
    dt: f64,
    /// Output directory.
    #[arg(long, default_value = "tests/references/Pss3Plant/path1")]
    out_dir: PathBuf,
    /// Write the move from the FMU's default pose (default parameters) instead of path 1.
    #[arg(long)]
    from_default_pose: bool,
}

/// Actuator displacements at the start and the end, m, and the stroke, m, of a case.
struct Case {
    l_start: Vector3<f64>,
    l_end: Vector3<f64>,
    stroke: (f64, f64),
}

impl Case {
    fn of(args: &PlantReferenceArgs) -> Self {
        if args.from_default_pose {
            let defaults = Params::default();
            Case {
                l_start: Vector3::repeat(DEFAULT_DISPLACEMENT),
                l_end: Vector3::from(DEFAULT_POSE_MOVE_END),
                stroke: (defaults.stroke_min, defaults.stroke_max),
            }
        } else {
            Case {
                l_start: Vector3::repeat(L_START),
                l_end: Vector3::repeat(L_END),
                stroke: STROKE,
            }
        }
    }
}

/// Actuators moved rest to rest from l0 to lf along s(tau) = 10 tau^3 - 15 tau^4 + 6 tau^5
/// (zero rate and acceleration at both ends); the platform motion by forward kinematics,
/// each sample seeded with the previous pose.
fn rest_to_rest_path(
    geometry: &Geometry,
    l0: &Vector3<f64>,
    lf: &Vector3<f64>,
    timing: &Timing,
) -> Result<Vec<PathSample>, PathError> {
    let t_total = timing.duration;
    let mut seed = start_pose();
    let mut samples = Vec::new();
    for time in timing.times()? {
        let tau = time / t_total;
        let s = tau.powi(3) * (10.0 - 15.0 * tau + 6.0 * tau * tau);
        let s_dot = 30.0 * tau * tau * (1.0 - tau).powi(2) / t_total;
        let s_ddot = 60.0 * tau * (1.0 - tau) * (1.0 - 2.0 * tau) / (t_total * t_total);
        let actuators = ActuatorState {
            l: l0 + (lf - l0) * s,
            l_dot: (lf - l0) * s_dot,
            l_ddot: (lf - l0) * s_ddot,
        };
        let motion = forward_motion(geometry, &actuators, &seed, &FkOptions::default())
            .map_err(|source| PathError::Kinematics { time, source })?;
        seed = motion.assembly.euler;
        samples.push(PathSample { time, motion });
    }
    Ok(samples)
}

pub fn run(args: &PlantReferenceArgs) -> Result<(), CliError> {
    crate::cli::bounds::samples(DURATION, args.dt, "--dt", "the path's duration")?;
    let case = Case::of(args);
    let params = PlantParams {
        geometry: Params {
            stroke_min: case.stroke.0,
            stroke_max: case.stroke.1,
            ..Params::default()
        },
        ..PlantParams::default()
    };
    let plant = Plant::new(params)?;
    let timing = Timing {
        duration: DURATION,
        dt: args.dt,
    };
    let geometry = &plant.model().geometry;
    let samples = if args.from_default_pose {
        rest_to_rest_path(geometry, &case.l_start, &case.l_end, &timing)?
    } else {
        linear_actuator_path(
            geometry,
            &case.l_start,
            &case.l_end,
            &timing,
            &FkOptions::default(),
        )?
    };
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
    std::fs::create_dir_all(&args.out_dir).map_err(io_at(&args.out_dir))?;
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
    let opt = args.out_dir.join("Pss3Plant_ref.opt");
    std::fs::write(
        &opt,
        format!(
            "StartTime, 0.0\nStopTime, {DURATION:?}\nStepSize, {:?}\nRelTol, 1e-10\n",
            args.dt
        ),
    )
    .map_err(io_at(&opt))?;
    let first = &samples[0].motion;
    let start_values = if args.from_default_pose {
        Vec::new() // every parameter at the FMU's default
    } else {
        path1_start_values(&first.assembly.euler, &first.omega)
    };
    let case_file = args.out_dir.join("case.json");
    std::fs::write(&case_file, case_json(&start_values)).map_err(io_at(&case_file))?;
    outln!(
        "wrote {} samples of {} to {}",
        samples.len(),
        if args.from_default_pose {
            "the move from the default pose"
        } else {
            "path 1"
        },
        args.out_dir.display()
    );
    Ok(())
}

/// The start values of path 1: stroke and initial state, as case.json lines.
fn path1_start_values(theta0: &Vector3<f64>, omega0: &Vector3<f64>) -> Vec<String> {
    let mut start = vec![
        format!("    \"strokeMin\": {:?}", STROKE.0),
        format!("    \"strokeMax\": {:?}", STROKE.1),
    ];
    for i in 0..3 {
        start.push(format!("    \"theta0[{}]\": {:?}", i + 1, theta0[i]));
        start.push(format!("    \"omega0[{}]\": {:?}", i + 1, omega0[i]));
    }
    start
}

/// case.json: start values and tolerances per interface.
fn case_json(start: &[String]) -> String {
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
