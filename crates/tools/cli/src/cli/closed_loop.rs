//! `robofmu closed-loop`: the Rust reference of the co-simulated loop, and the PID gain
//! design on the linearised plant.

use super::args::{angles_deg, triple};
use super::bounds::samples;
use super::bounds::{bandwidth, finite, ode_tolerance};
use super::report::usage;
use super::{CliError, io_at};
use clap::{Args, Subcommand};
use robofmu::closed_loop::{LoopSample, LoopSpec, design_gains, parse_loop_scenario, simulate};
use robofmu::pss3::dynamics::{Plant, PlantParams};
use robofmu::pss3::rotation::{euler_accelerations, euler_rates};
use std::fmt::Write as _;
use std::path::PathBuf;

#[derive(Subcommand)]
pub enum ClosedLoopCommand {
    /// Simulate a scenario's loop as one continuous-time ODE (no FMI) and write the
    /// reference CSV (cross-check format) with its options file.
    Reference(ReferenceArgs),
    /// PID gains by pole placement (triple pole at -bandwidth) on the linearised plant.
    DesignGains(DesignArgs),
    /// Planner boundary conditions (Euler angles, rates, accelerations) from a pose and
    /// the angular velocity and acceleration in the base frame.
    Boundary(BoundaryArgs),
}

#[derive(Args)]
pub struct BoundaryArgs {
    /// Euler angles thx,thy,thz, degrees.
    #[arg(
        long,
        required = true,
        value_delimiter = ',',
        allow_hyphen_values = true,
        value_parser = finite
    )]
    angles: Vec<f64>,
    /// Angular velocity wx,wy,wz in the base frame, rad/s.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "0,0,0",
        value_parser = finite
    )]
    omega: Vec<f64>,
    /// Angular acceleration ax,ay,az in the base frame, rad/s^2.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "0,0,0",
        value_parser = finite
    )]
    omega_dot: Vec<f64>,
}

#[derive(Args)]
pub struct ReferenceArgs {
    /// Scenario file (TOML), as run by `python -m robofmu`.
    #[arg(long)]
    scenario: PathBuf,
    /// Output CSV; the options file is written beside it, the same name with the
    /// extension .opt (`X_ref.csv` -> `X_ref.opt`).
    #[arg(long)]
    out: PathBuf,
    /// Relative and absolute tolerance of the Dop853 integration (1e-14 to 1e-2).
    #[arg(long, default_value_t = 1e-11, allow_hyphen_values = true,
          value_parser = ode_tolerance)]
    tolerance: f64,
    /// Write every N-th communication point only (the first and last always).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    every: u32,
}

#[derive(Args)]
pub struct DesignArgs {
    /// Closed-loop bandwidth w, rad/s (triple pole at -w; > 0, at most 1e4).
    #[arg(long, allow_hyphen_values = true, value_parser = bandwidth)]
    bandwidth: f64,
    /// Poses of the motion, thx,thy,thz in degrees (repeat the option per pose).
    #[arg(
        long,
        required = true,
        value_delimiter = ',',
        allow_hyphen_values = true,
        value_parser = finite
    )]
    angles: Vec<f64>,
}

pub fn run(command: ClosedLoopCommand) -> Result<(), CliError> {
    match command {
        ClosedLoopCommand::Reference(args) => reference(args),
        ClosedLoopCommand::DesignGains(args) => design(args),
        ClosedLoopCommand::Boundary(args) => boundary(args),
    }
}

fn columns(spec: &LoopSpec) -> Vec<String> {
    let [planner, pid, plant] = &spec.aliases;
    let groups: [(&String, &str); 11] = [
        (planner, "q"),
        (planner, "qdot"),
        (planner, "qddot"),
        (plant, "theta"),
        (plant, "thetaDot"),
        (plant, "omega"),
        (plant, "omegaDot"),
        (plant, "gravityCompensation"),
        (plant, "force"),
        (plant, "l"),
        (pid, "u"),
    ];
    groups
        .iter()
        .flat_map(|(alias, name)| (1..=3).map(move |i| format!("{alias}.{name}[{i}]")))
        .collect()
}

fn row(s: &LoopSample) -> impl Iterator<Item = f64> + '_ {
    [
        &s.q,
        &s.qdot,
        &s.qddot,
        &s.theta,
        &s.theta_dot,
        &s.omega,
        &s.omega_dot,
        &s.gravity_compensation,
        &s.force,
        &s.l,
        &s.u,
    ]
    .into_iter()
    .flat_map(|v| v.iter().copied())
}

fn reference(args: ReferenceArgs) -> Result<(), CliError> {
    if args.out.extension().is_some_and(|e| e == "opt") {
        // The options file is `--out` with the extension .opt: it would replace the CSV.
        return Err(usage(format!(
            "--out {}: the options file is written beside the CSV with the extension \
             .opt and would replace it; give a .csv file",
            args.out.display()
        )));
    }
    let text = std::fs::read_to_string(&args.scenario).map_err(|e| {
        usage(format!(
            "{}: cannot read the scenario ({e})",
            args.scenario.display()
        ))
    })?;
    let spec = parse_loop_scenario(&text)
        .map_err(|e| usage(format!("{}: {e}", args.scenario.display())))?;
    let span = spec.stop_time - spec.start_time;
    samples(
        span,
        spec.step_size,
        "step_size",
        "the run (stop_time - start_time)",
    )
    .map_err(|e| usage(format!("{}: {e}", args.scenario.display())))?;
    super::check_output_file(&args.out)?;
    let samples = simulate(&spec, args.tolerance)?;
    let (csv, rows) = reference_csv(&spec, &samples, args.every as usize)?;
    std::fs::write(&args.out, csv).map_err(io_at(&args.out))?;
    let options = format!(
        "StartTime, {}\nStopTime, {}\nStepSize, {}\nRelTol, {:e}\n",
        spec.start_time, spec.stop_time, spec.step_size, args.tolerance
    );
    let opt = args.out.with_extension("opt");
    std::fs::write(&opt, options).map_err(io_at(&opt))?;
    outln!(
        "{}: {} samples of the continuous-time loop, {rows} written -> {}",
        spec.name,
        samples.len(),
        args.out.display()
    );
    Ok(())
}

/// The cross-check CSV of `samples`, every `every`-th one and the last, and its number
/// of data rows.
fn reference_csv(
    spec: &LoopSpec,
    samples: &[LoopSample],
    every: usize,
) -> Result<(String, usize), CliError> {
    let mut csv = String::from("\"time\"");
    for name in columns(spec) {
        write!(csv, ",\"{name}\"")?;
    }
    csv.push('\n');
    let last = samples.len().saturating_sub(1);
    let mut rows = 0;
    for (k, s) in samples.iter().enumerate() {
        if k % every != 0 && k != last {
            continue;
        }
        write!(csv, "{:e}", s.time)?;
        for v in row(s) {
            write!(csv, ",{v:e}")?;
        }
        csv.push('\n');
        rows += 1;
    }
    Ok((csv, rows))
}

fn boundary(args: BoundaryArgs) -> Result<(), CliError> {
    let angles = angles_deg(&args.angles, "angles")?;
    let omega = triple(&args.omega, "omega")?;
    let omega_dot = triple(&args.omega_dot, "omega-dot")?;
    let rates = euler_rates(&angles, &omega)?;
    let accelerations = euler_accelerations(&angles, &rates, &omega_dot)?;
    if !(rates
        .iter()
        .chain(accelerations.iter())
        .all(|v| v.is_finite()))
    {
        return Err(usage(
            "--angles, --omega and --omega-dot give non-finite Euler rates; \
             give a pose away from thy = +-90 deg and smaller rates",
        ));
    }
    outln!("# Euler angles (rad), rates (rad/s) and accelerations (rad/s^2): q, qdot, qddot");
    for (name, v) in [("q", angles), ("qdot", rates), ("qddot", accelerations)] {
        outln!("{name} = [{:.17e}, {:.17e}, {:.17e}]", v[0], v[1], v[2]);
    }
    Ok(())
}

fn design(args: DesignArgs) -> Result<(), CliError> {
    if !args.angles.len().is_multiple_of(3) {
        return Err(usage(format!(
            "--angles takes thx,thy,thz (three numbers) per pose, {} given",
            args.angles.len()
        )));
    }
    let poses = args
        .angles
        .chunks(3)
        .map(|pose| angles_deg(pose, "angles"))
        .collect::<Result<Vec<_>, _>>()?;
    let plant = Plant::new(PlantParams::default())?;
    let d = design_gains(&plant, &poses, args.bandwidth)?;
    let gains = d.gains.iter().flat_map(|g| [g.kp, g.ki, g.kd]);
    if !gains.chain(d.inertia.iter().copied()).all(f64::is_finite) {
        return Err(usage(format!(
            "--bandwidth {} rad/s gives non-finite gains; give a smaller bandwidth",
            args.bandwidth
        )));
    }
    outln!(
        "triple pole at -{} rad/s; inertia per Euler axis (largest diagonal of M_x over {} poses):",
        args.bandwidth,
        poses.len()
    );
    for (i, g) in d.gains.iter().enumerate() {
        outln!(
            "  axis {}: m = {:.6} kg m^2  Kp = {:.6} N m/rad  Ki = {:.6} N m/(rad s)  Kd = {:.6} N m s/rad",
            i + 1,
            d.inertia[i],
            g.kp,
            g.ki,
            g.kd
        );
    }
    Ok(())
}
