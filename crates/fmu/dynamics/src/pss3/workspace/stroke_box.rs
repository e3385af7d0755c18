//! Forward-kinematics scan of the stroke box [min, max]^3 on a regular grid.
//!
//! Chunks of constant l1 run in parallel; inside a chunk every pose is seeded with its
//! grid neighbour, so Newton's method starts a few millimetres from the solution.

use super::WorkspacePoint;
use crate::pss3::{FkOptions, Geometry, KinematicsError, forward_kinematics, start_pose};
use nalgebra::Vector3;
use rayon::prelude::*;

/// Result of a stroke-box scan.
#[derive(Debug, Clone, PartialEq)]
pub struct StrokeScan {
    /// Grid points per actuator.
    pub steps: usize,
    /// Every grid point that assembled, ordered by (l1, l2, l3).
    pub points: Vec<WorkspacePoint>,
    /// Grid points where forward kinematics failed, with the reason.
    pub failures: Vec<(Vector3<f64>, KinematicsError)>,
}

/// Scans `steps`^3 actuator positions evenly spread over the stroke (steps >= 2).
pub fn scan_stroke_box(geometry: &Geometry, steps: usize, options: &FkOptions) -> StrokeScan {
    let steps = steps.max(2);
    let (min, max) = (geometry.params.stroke_min, geometry.params.stroke_max);
    let grid: Vec<f64> = (0..steps)
        .map(|k| min + (max - min) * k as f64 / (steps - 1) as f64)
        .collect();
    let chunks: Vec<_> = (0..steps)
        .into_par_iter()
        .map(|i| scan_chunk(geometry, &grid, i, options))
        .collect();
    let mut scan = StrokeScan {
        steps,
        points: Vec::with_capacity(steps.pow(3)),
        failures: Vec::new(),
    };
    for (points, failures) in chunks {
        scan.points.extend(points);
        scan.failures.extend(failures);
    }
    scan
}

type Chunk = (Vec<WorkspacePoint>, Vec<(Vector3<f64>, KinematicsError)>);

/// All points with l1 = grid[i]: walk from the start pose along l1 to the chunk's first
/// point, then along l2 and l3, carrying the seed.
fn scan_chunk(geometry: &Geometry, grid: &[f64], i: usize, options: &FkOptions) -> Chunk {
    let solve = |l: Vector3<f64>, seed: &Vector3<f64>| {
        let assembly = forward_kinematics(geometry, &l, seed, options)?.assembly;
        WorkspacePoint::measure(geometry, &assembly)
    };
    let mut corner_seed = start_pose();
    for &l1 in &grid[..=i] {
        if let Ok(p) = solve(Vector3::new(l1, grid[0], grid[0]), &corner_seed) {
            corner_seed = p.euler;
        }
    }
    let (mut points, mut failures) = (Vec::new(), Vec::new());
    let mut row_seed = corner_seed;
    for &l2 in grid {
        let mut seed = row_seed;
        for (k, &l3) in grid.iter().enumerate() {
            let l = Vector3::new(grid[i], l2, l3);
            match solve(l, &seed) {
                Ok(p) => {
                    seed = p.euler;
                    if k == 0 {
                        row_seed = p.euler;
                    }
                    points.push(p);
                }
                Err(e) => failures.push((l, e)),
            }
        }
    }
    (points, failures)
}
