//! `pss3 workspace`: stroke-box and orientation-grid scans, summary, CSV files and plots.

use super::workspace_output::{ROLL_BAND_DEG, write_outputs};
use crate::cli::CliError;
use crate::cli::bounds::{angle_step, count};
use clap::Args;
use robofmu::pss3::workspace::{
    EnvelopeBin, OrientationGrid, Summary, scan_orientations, scan_stroke_box, summarize,
    tilt_envelope,
};
use robofmu::pss3::{FkOptions, Geometry};
use std::path::PathBuf;
use std::time::Instant;

/// Output directory and grid resolutions.
#[derive(Args)]
pub struct WorkspaceArgs {
    /// Directory for the CSV files and PNG plots (created if missing).
    #[arg(long)]
    out: PathBuf,
    /// Grid points per actuator over the stroke box (FK scan), 2 to 101.
    #[arg(long, default_value_t = 31, allow_hyphen_values = true,
          value_parser = count::<2, 101>)]
    steps: usize,
    /// Spacing of the orientation grid (IK scan), deg (0.25 to 10).
    #[arg(long, default_value_t = 0.5, allow_hyphen_values = true,
          value_parser = angle_step)]
    angle_step: f64,
}

pub fn run(args: &WorkspaceArgs) -> Result<(), CliError> {
    std::fs::create_dir_all(&args.out).map_err(crate::cli::io_at(&args.out))?;
    let geometry = Geometry::default();

    let started = Instant::now();
    let stroke = scan_stroke_box(&geometry, args.steps, &FkOptions::default());
    let stroke_time = started.elapsed();
    outln!(
        "stroke box: {}^3 = {} actuator positions, {} assembled, {} failed ({:.2} s, FK on {} threads)",
        stroke.steps,
        stroke.steps.pow(3),
        stroke.points.len(),
        stroke.failures.len(),
        stroke_time.as_secs_f64(),
        rayon::current_num_threads()
    );
    for (l, e) in stroke.failures.iter().take(5) {
        outln!(
            "  failed at l = ({:.4}, {:.4}, {:.4}) m: {e}",
            l.x,
            l.y,
            l.z
        );
    }
    print_summary(summarize(&stroke.points).as_ref());

    let grid = orientation_grid(args.angle_step);
    let started = Instant::now();
    let orientations = scan_orientations(&geometry, &grid);
    outln!(
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
    outln!("wrote CSV files and plots to {}", args.out.display());
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
        outln!("  nothing reachable");
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
        outln!("  {name}: {lo:.2} .. {hi:.2} deg");
    }
    outln!(
        "  det J: {:.4e} .. {:.4e} m^3; cond J: {:.3} .. {:.3}; min |n_i.u_i| = {:.4}",
        s.det_j.min,
        s.det_j.max,
        s.cond_j.min,
        s.cond_j.max,
        s.min_leg_projection
    );
}

/// The largest tilt at whole-degree roll values of the orientation grid.
fn print_slices(slices: &[EnvelopeBin]) {
    outln!("largest reachable tilt at fixed roll (orientation grid, whole degrees):");
    let whole = |b: &&EnvelopeBin| {
        let d = b.roll.to_degrees();
        (d - d.round()).abs() < 1e-6
    };
    for bin in slices.iter().filter(whole) {
        outln!(
            "  roll {:6.1} deg: tilt up to {:5.2} deg ({} grid orientations)",
            bin.roll.to_degrees(),
            bin.max_tilt.to_degrees(),
            bin.count
        );
    }
}
