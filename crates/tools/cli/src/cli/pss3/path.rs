//! `pss3 actuator-path`: actuators driven linearly in time, platform motion to CSV.

use super::csv::write_csv;
use crate::cli::CliError;
use crate::cli::args::{check_stroke, triple};
use crate::cli::bounds::{finite, positive, samples};
use clap::Args;
use robofmu::pss3::{FkOptions, Geometry, PathSample, Timing, linear_actuator_path};
use std::path::PathBuf;

/// Start and end displacements, timing and output file.
#[derive(Args)]
pub struct PathArgs {
    /// Start displacements l1,l2,l3 in m.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        required = true,
        value_parser = finite
    )]
    l0: Vec<f64>,
    /// End displacements l1,l2,l3 in m.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        required = true,
        value_parser = finite
    )]
    lf: Vec<f64>,
    /// Duration of the motion, s (> 0).
    #[arg(long, allow_hyphen_values = true, value_parser = positive)]
    duration: f64,
    /// Sampling step, s (> 0, at most the duration, at most 1e6 samples).
    #[arg(long, allow_hyphen_values = true, value_parser = positive)]
    dt: f64,
    /// Output CSV file.
    #[arg(long)]
    out: PathBuf,
}

/// Column names of the path CSV (SI units in the names).
const COLUMNS: [&str; 16] = [
    "time_s",
    "l1_m",
    "l2_m",
    "l3_m",
    "l1_dot_m_per_s",
    "l2_dot_m_per_s",
    "l3_dot_m_per_s",
    "thx_rad",
    "thy_rad",
    "thz_rad",
    "omega_x_rad_per_s",
    "omega_y_rad_per_s",
    "omega_z_rad_per_s",
    "omega_dot_x_rad_per_s2",
    "omega_dot_y_rad_per_s2",
    "omega_dot_z_rad_per_s2",
];

pub fn run(args: &PathArgs) -> Result<(), CliError> {
    let geometry = Geometry::default();
    let timing = Timing {
        duration: args.duration,
        dt: args.dt,
    };
    let (l0, lf) = (triple(&args.l0, "l0")?, triple(&args.lf, "lf")?);
    check_stroke(&geometry, &l0, "l0")?;
    check_stroke(&geometry, &lf, "lf")?;
    samples(args.duration, args.dt, "--dt", "--duration")?;
    crate::cli::check_output_file(&args.out)?;
    let path = linear_actuator_path(&geometry, &l0, &lf, &timing, &FkOptions::default())?;
    write_csv(&args.out, &COLUMNS, path.iter().map(row))?;
    outln!("wrote {} samples to {}", path.len(), args.out.display());
    for s in [path.first(), path.last()].into_iter().flatten() {
        print_sample(s);
    }
    Ok(())
}

fn row(s: &PathSample) -> Vec<f64> {
    let m = &s.motion;
    let mut row = vec![s.time];
    for v in [
        m.assembly.l,
        m.l_dot,
        m.assembly.euler,
        m.omega,
        m.omega_dot,
    ] {
        row.extend(v.iter());
    }
    row
}

fn print_sample(s: &PathSample) {
    let m = &s.motion;
    let deg = |v: nalgebra::Vector3<f64>| v.map(f64::to_degrees);
    let (th, w, wd) = (deg(m.assembly.euler), deg(m.omega), deg(m.omega_dot));
    outln!(
        "t = {:.3} s: thx, thy, thz = {:.3}, {:.3}, {:.3} deg; omega = ({:.3}, {:.3}, {:.3}) deg/s; \
         omega_dot = ({:.3}, {:.3}, {:.3}) deg/s^2",
        s.time,
        th[0],
        th[1],
        th[2],
        w[0],
        w[1],
        w[2],
        wd[0],
        wd[1],
        wd[2]
    );
}
