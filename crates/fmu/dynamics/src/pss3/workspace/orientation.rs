//! Inverse-kinematics scan over a regular grid of Euler angles: which orientations the
//! strokes reach, and the Jacobian measures there.

use super::{EnvelopeBin, WorkspacePoint};
use crate::pss3::{Geometry, inverse_kinematics};
use nalgebra::Vector3;
use rayon::prelude::*;

/// A regular grid of Euler angles: `steps` values each of thx and thy in
/// [-tilt_limit, tilt_limit] and `roll_steps` values of thz in [roll_min, roll_max], rad
/// (a single value is the lower end).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrientationGrid {
    pub tilt_limit: f64,
    pub steps: usize,
    pub roll_min: f64,
    pub roll_max: f64,
    pub roll_steps: usize,
}

impl Default for OrientationGrid {
    /// thx, thy in [-16, 16] deg and thz in [118, 158] deg, both every 0.5 deg: a margin
    /// around the workspace in docs/3pss-model.md.
    fn default() -> Self {
        Self {
            tilt_limit: 16f64.to_radians(),
            steps: 65,
            roll_min: 118f64.to_radians(),
            roll_max: 158f64.to_radians(),
            roll_steps: 81,
        }
    }
}

impl OrientationGrid {
    /// The thx (and thy) grid values, rad.
    pub fn tilt_values(&self) -> Vec<f64> {
        spread(-self.tilt_limit, self.tilt_limit, self.steps)
    }

    /// The thz grid values, rad.
    pub fn roll_values(&self) -> Vec<f64> {
        spread(self.roll_min, self.roll_max, self.roll_steps)
    }
}

/// `n` evenly spaced values from `lo` to `hi` (just `lo` when n = 1).
fn spread(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    if n == 1 {
        return vec![lo];
    }
    (0..n)
        .map(|k| lo + (hi - lo) * k as f64 / (n - 1) as f64)
        .collect()
}

/// Result of an orientation scan.
#[derive(Debug, Clone, PartialEq)]
pub struct OrientationScan {
    /// The scanned grid.
    pub grid: OrientationGrid,
    /// Grid orientations within the strokes with a regular Jacobian, ordered by
    /// (thz, thx, thy).
    pub reachable: Vec<WorkspacePoint>,
    /// Grid orientations within the strokes where the Jacobian is singular.
    pub singular: Vec<Vector3<f64>>,
    /// Number of grid orientations tried.
    pub tried: usize,
}

/// Inverse kinematics at every orientation of `grid`, in parallel over thz.
pub fn scan_orientations(geometry: &Geometry, grid: &OrientationGrid) -> OrientationScan {
    let (tilts, rolls) = (grid.tilt_values(), grid.roll_values());
    let within_strokes: Vec<(Vector3<f64>, Option<WorkspacePoint>)> = rolls
        .par_iter()
        .flat_map_iter(|&thz| {
            let tilts = &tilts;
            tilts.iter().flat_map(move |&thx| {
                tilts.iter().filter_map(move |&thy| {
                    let euler = Vector3::new(thx, thy, thz);
                    let assembly = inverse_kinematics(geometry, &euler).ok()?;
                    Some((euler, WorkspacePoint::measure(geometry, &assembly).ok()))
                })
            })
        })
        .collect();
    let mut scan = OrientationScan {
        grid: *grid,
        reachable: Vec::with_capacity(within_strokes.len()),
        singular: Vec::new(),
        tried: rolls.len() * tilts.len() * tilts.len(),
    };
    for (euler, point) in within_strokes {
        match point {
            Some(p) => scan.reachable.push(p),
            None => scan.singular.push(euler),
        }
    }
    scan
}

impl OrientationScan {
    /// The largest reachable tilt at each grid roll value (the slice thz = const of the
    /// workspace); rolls with no reachable orientation are left out.
    pub fn max_tilt_per_roll(&self) -> Vec<EnvelopeBin> {
        self.reachable
            .chunk_by(|a, b| a.euler.z == b.euler.z)
            .map(|slice| EnvelopeBin {
                roll: slice[0].euler.z,
                max_tilt: slice.iter().map(|p| p.tilt).fold(0.0, f64::max),
                count: slice.len(),
            })
            .collect()
    }
}
