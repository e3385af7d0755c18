//! Files written by `pss3 workspace`: CSV tables (SI, units in the column names) and
//! PNG plots (degrees, labelled).

use super::csv::write_csv;
use crate::cli::CliError;
use crate::plot::{Axes, Grid, Series, heat_map, scatter_chart};
use robofmu::pss3::workspace::{EnvelopeBin, WorkspacePoint};
use std::path::Path;

/// Width of the roll bands of the tilt-versus-roll envelope, deg.
pub const ROLL_BAND_DEG: f64 = 1.0;
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

fn point_row(p: &WorkspacePoint) -> Vec<f64> {
    let mut row: Vec<f64> = p.l.iter().chain(p.euler.iter()).copied().collect();
    row.extend([p.tilt, p.det_j, p.cond_j, p.min_leg_projection]);
    row
}

/// Writes the CSV files and plots of the scans into `dir`.
pub fn write_outputs(
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
