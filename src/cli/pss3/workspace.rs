//! `pss3 workspace`: stroke-box and orientation-grid scans, summary, CSV files and plots.

use super::csv::write_csv;
use crate::cli::CliError;
use clap::Args;
use robofmu::plot::{Axes, Grid, Series, heat_map, scatter_chart};
use robofmu::pss3::workspace::{
    EnvelopeBin, OrientationGrid, Summary, WorkspacePoint, scan_orientations, scan_stroke_box,
    summarize, tilt_envelope,
};
use robofmu::pss3::{FkOptions, Geometry};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Output directory and grid resolutions.
#[derive(Args)]
pub struct WorkspaceArgs {
    /// Directory for the CSV files and PNG plots (created if missing).
    #[arg(long)]
    out: PathBuf,
    /// Grid points per actuator over the stroke box (FK scan).
    #[arg(long, default_value_t = 31)]
    steps: usize,
    /// Spacing of the orientation grid (IK scan), deg.
    #[arg(long, default_value_t = 0.5)]
    angle_step: f64,
}

/// Width of the roll bands of the tilt-versus-roll envelope, deg.
const ROLL_BAND_DEG: f64 = 1.0;
/// Width of the tilt bands of the cond J map, deg.
const TILT_BAND_DEG: f64 = 0.5;

const POINT_COLUMNS: [&str; 10] = [
    "l1_m",
    "l2_m",
    "l3_m",
    "thx_rad",
    "thy_rad",
    "thz_roll_rad",
    "tilt_rad",
    "det_j_m3",
    "cond_j",
    "min_abs_n_dot_u",
];

pub fn run(args: &WorkspaceArgs) -> Result<(), CliError> {
    if !(args.angle_step.is_finite() && args.angle_step > 0.0) || args.steps < 2 {
        return Err("--angle-step must be positive and --steps at least 2".into());
    }
    std::fs::create_dir_all(&args.out)
        .map_err(|e| format!("cannot create {}: {e}", args.out.display()))?;
    let geometry = Geometry::default();

    let started = Instant::now();
    let stroke = scan_stroke_box(&geometry, args.steps, &FkOptions::default());
    let stroke_time = started.elapsed();
    println!(
        "stroke box: {}^3 = {} actuator positions, {} assembled, {} failed ({:.2} s, FK on {} threads)",
        stroke.steps,
        stroke.steps.pow(3),
        stroke.points.len(),
        stroke.failures.len(),
        stroke_time.as_secs_f64(),
        rayon::current_num_threads()
    );
    for (l, e) in stroke.failures.iter().take(5) {
        println!(
            "  failed at l = ({:.4}, {:.4}, {:.4}) m: {e}",
            l.x, l.y, l.z
        );
    }
    print_summary(summarize(&stroke.points).as_ref());

    let grid = orientation_grid(args.angle_step);
    let started = Instant::now();
    let orientations = scan_orientations(&geometry, &grid);
    println!(
        "orientation grid: {} orientations, {} within the strokes, {} of them singular ({:.2} s, IK)",
        orientations.tried,
        orientations.reachable.len() + orientations.singular.len(),
        orientations.singular.len(),
        started.elapsed().as_secs_f64()
    );
    print_summary(summarize(&orientations.reachable).as_ref());

    let slices = orientations.max_tilt_per_roll();
    let bands = tilt_envelope(&stroke.points, ROLL_BAND_DEG.to_radians());
    write_outputs(
        &args.out,
        &stroke.points,
        &orientations.reachable,
        &bands,
        &slices,
    )?;
    print_slices(&slices);
    println!("wrote CSV files and plots to {}", args.out.display());
    Ok(())
}

/// The default orientation box at the requested spacing.
fn orientation_grid(step_deg: f64) -> OrientationGrid {
    let base = OrientationGrid::default();
    let count = |span: f64| (span.to_degrees() / step_deg).round() as usize + 1;
    OrientationGrid {
        steps: count(2.0 * base.tilt_limit),
        roll_steps: count(base.roll_max - base.roll_min),
        ..base
    }
}

fn print_summary(summary: Option<&Summary>) {
    let Some(s) = summary else {
        println!("  nothing reachable");
        return;
    };
    let deg = |r: robofmu::pss3::workspace::Range| (r.min.to_degrees(), r.max.to_degrees());
    for (name, r) in [
        ("thx", s.thx),
        ("thy", s.thy),
        ("thz (roll)", s.thz),
        ("tilt", s.tilt),
    ] {
        let (lo, hi) = deg(r);
        println!("  {name}: {lo:.2} .. {hi:.2} deg");
    }
    println!(
        "  det J: {:.4e} .. {:.4e} m^3; cond J: {:.3} .. {:.3}; min |n_i.u_i| = {:.4}",
        s.det_j.min, s.det_j.max, s.cond_j.min, s.cond_j.max, s.min_leg_projection
    );
}

/// The largest tilt at whole-degree roll values of the orientation grid.
fn print_slices(slices: &[EnvelopeBin]) {
    println!("largest reachable tilt at fixed roll (orientation grid, whole degrees):");
    let whole = |b: &&EnvelopeBin| {
        let d = b.roll.to_degrees();
        (d - d.round()).abs() < 1e-6
    };
    for bin in slices.iter().filter(whole) {
        println!(
            "  roll {:6.1} deg: tilt up to {:5.2} deg ({} grid orientations)",
            bin.roll.to_degrees(),
            bin.max_tilt.to_degrees(),
            bin.count
        );
    }
}

fn point_row(p: &WorkspacePoint) -> Vec<f64> {
    let mut row: Vec<f64> = p.l.iter().chain(p.euler.iter()).copied().collect();
    row.extend([p.tilt, p.det_j, p.cond_j, p.min_leg_projection]);
    row
}

fn write_outputs(
    dir: &Path,
    stroke: &[WorkspacePoint],
    orientations: &[WorkspacePoint],
    bands: &[EnvelopeBin],
    slices: &[EnvelopeBin],
) -> Result<(), CliError> {
    write_csv(
        &dir.join("stroke_box.csv"),
        &POINT_COLUMNS,
        stroke.iter().map(point_row),
    )?;
    write_csv(
        &dir.join("orientation_grid.csv"),
        &POINT_COLUMNS,
        orientations.iter().map(point_row),
    )?;
    write_csv(
        &dir.join("tilt_roll_bands_stroke_box.csv"),
        &["thz_roll_band_centre_rad", "max_tilt_rad", "points"],
        bands
            .iter()
            .map(|b| vec![b.roll, b.max_tilt, b.count as f64]),
    )?;
    write_csv(
        &dir.join("tilt_at_roll_orientation_grid.csv"),
        &[
            "thz_roll_rad",
            "max_tilt_rad",
            "reachable_grid_orientations",
        ],
        slices
            .iter()
            .map(|b| vec![b.roll, b.max_tilt, b.count as f64]),
    )?;
    let degrees = |p: &WorkspacePoint| (p.euler.z.to_degrees(), p.tilt.to_degrees());
    scatter_chart(
        &dir.join("tilt_vs_roll.png"),
        &Axes {
            title: "3-PSS reachable tilt versus roll",
            x_label: "roll thz, deg",
            y_label: "tilt of the platform normal from Z, deg",
        },
        &[
            Series {
                label: "reachable poses (stroke box, FK)",
                points: stroke.iter().map(degrees).collect(),
            },
            Series {
                label: "largest tilt at fixed roll (orientation grid, IK)",
                points: slices
                    .iter()
                    .map(|b| (b.roll.to_degrees(), b.max_tilt.to_degrees()))
                    .collect(),
            },
        ],
    )?;
    heat_map(
        &dir.join("cond_j_map.png"),
        &Axes {
            title: "3-PSS worst cond J per (roll, tilt) cell (stroke box)",
            x_label: "roll thz, deg",
            y_label: "tilt of the platform normal from Z, deg",
        },
        &cond_map(stroke),
        "cond J",
    )?;
    Ok(())
}

/// Largest cond J per cell of roll (ROLL_BAND_DEG) and tilt (TILT_BAND_DEG) bands.
fn cond_map(points: &[WorkspacePoint]) -> Grid {
    let roll_lo = points
        .iter()
        .map(|p| p.euler.z.to_degrees())
        .fold(f64::INFINITY, f64::min);
    let roll_hi = points
        .iter()
        .map(|p| p.euler.z.to_degrees())
        .fold(f64::NEG_INFINITY, f64::max);
    let tilt_hi = points
        .iter()
        .map(|p| p.tilt.to_degrees())
        .fold(0.0, f64::max);
    let nx = ((roll_hi - roll_lo) / ROLL_BAND_DEG).floor() as usize + 1;
    let ny = (tilt_hi / TILT_BAND_DEG).floor() as usize + 1;
    let mut values: Vec<Option<f64>> = vec![None; nx * ny];
    for p in points {
        let ix = ((p.euler.z.to_degrees() - roll_lo) / ROLL_BAND_DEG).floor() as usize;
        let iy = (p.tilt.to_degrees() / TILT_BAND_DEG).floor() as usize;
        let cell = &mut values[iy * nx + ix];
        *cell = Some(cell.map_or(p.cond_j, |c| c.max(p.cond_j)));
    }
    Grid {
        xs: (0..nx)
            .map(|i| roll_lo + (i as f64 + 0.5) * ROLL_BAND_DEG)
            .collect(),
        ys: (0..ny).map(|i| (i as f64 + 0.5) * TILT_BAND_DEG).collect(),
        values,
    }
}
