//! Global condition index: the mean of the LCI over the workspace in `(x, y, phi)`.
//!
//! Integration method: the composite midpoint rule on a uniform box grid of cells over
//! `[-reach, reach]^2 x [phi_min, phi_max]`, with the workspace as an indicator: a cell
//! counts if its centre is reachable, and it contributes the LCI (best working mode, or
//! one fixed mode) at its centre. `GCI = sum(LCI) / count`, the cell volume cancelling. The workspace
//! boundary cuts cells, so the error decreases like the cell size (first order).

use super::workspace::ModeChoice;
use super::{Manipulator, Pose};
use rayon::prelude::*;

/// Cells of the midpoint rule.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GciGrid {
    /// Cells along x and along y.
    pub xy_cells: usize,
    /// Cells along phi.
    pub phi_cells: usize,
    /// Orientation range (rad).
    pub phi_min: f64,
    pub phi_max: f64,
}

impl GciGrid {
    /// The same range with every axis refined by `factor`.
    pub fn refined(self, factor: usize) -> Self {
        Self {
            xy_cells: self.xy_cells * factor,
            phi_cells: self.phi_cells * factor,
            ..self
        }
    }
}

/// A GCI and the workspace volume it was averaged over.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gci {
    pub value: f64,
    /// Workspace volume (m^2 rad): reachable cells times the cell volume.
    pub volume: f64,
}

/// GCI of `robot` in the working modes of `choice` by the midpoint rule on `grid`;
/// `None` if no cell centre is reachable. With a fixed mode the workspace is that
/// mode's reachable set.
pub fn gci(robot: &impl Manipulator, grid: &GciGrid, choice: ModeChoice) -> Option<Gci> {
    let half = robot.reach();
    let dx = 2.0 * half / grid.xy_cells as f64;
    let dphi = (grid.phi_max - grid.phi_min) / grid.phi_cells as f64;
    let n = grid.xy_cells;
    let (sum, count) = (0..grid.phi_cells * n)
        .into_par_iter()
        .map(|row| {
            let phi = grid.phi_min + (row / n) as f64 * dphi + dphi / 2.0;
            let y = -half + (row % n) as f64 * dx + dx / 2.0;
            (0..n)
                .filter_map(|ix| {
                    let x = -half + ix as f64 * dx + dx / 2.0;
                    let pose = Pose::new(x, y, phi);
                    match choice {
                        ModeChoice::Best => robot.best_lci(pose),
                        ModeChoice::Only(mode) => robot.lci(pose, mode).ok(),
                    }
                })
                .fold((0.0, 0usize), |(s, c), v| (s + v, c + 1))
        })
        .reduce(|| (0.0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
    (count > 0).then(|| Gci {
        value: sum / count as f64,
        volume: count as f64 * dx * dx * dphi,
    })
}
