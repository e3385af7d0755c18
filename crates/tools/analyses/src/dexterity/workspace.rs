//! Square grids of positions at a fixed orientation, and scalar maps over them: LCI
//! and load-index maps, the reachable workspace and the common workspace.

use super::{Manipulator, Pose, Robot};
use rayon::prelude::*;

/// Half-width of the paper's square of positions, `x, y in [-20, 20] cm`.
pub const PAPER_HALF_WIDTH: f64 = 0.20;

/// `points x points` positions over `[-half_width, half_width]^2` (m), ends included.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct XyGrid {
    pub half_width: f64,
    pub points: usize,
}

impl XyGrid {
    /// The paper's square `[-20, 20] cm` with `points` per axis.
    pub fn paper(points: usize) -> Self {
        Self {
            half_width: PAPER_HALF_WIDTH,
            points,
        }
    }

    /// A square that holds every position the manipulator can reach.
    pub fn own(robot: &impl Manipulator, points: usize) -> Self {
        Self {
            half_width: robot.reach(),
            points,
        }
    }

    /// A square that holds the positions all the manipulators can reach.
    pub fn common(robots: &[Robot], points: usize) -> Self {
        let half_width = robots
            .iter()
            .map(|r| r.reach())
            .fold(f64::INFINITY, f64::min);
        Self { half_width, points }
    }

    /// Grid spacing (m).
    pub fn step(&self) -> f64 {
        2.0 * self.half_width / (self.points.max(2) - 1) as f64
    }

    /// Coordinates along either axis (m).
    pub fn coordinates(&self) -> Vec<f64> {
        (0..self.points)
            .map(|i| -self.half_width + i as f64 * self.step())
            .collect()
    }

    /// Position of grid point `index` (row-major: `index = iy * points + ix`).
    pub fn position(&self, index: usize) -> (f64, f64) {
        let (ix, iy) = (index % self.points, index / self.points);
        let step = self.step();
        (
            -self.half_width + ix as f64 * step,
            -self.half_width + iy as f64 * step,
        )
    }

    /// Number of grid points.
    pub fn len(&self) -> usize {
        self.points * self.points
    }

    pub fn is_empty(&self) -> bool {
        self.points == 0
    }

    /// Evaluates `f` at every grid point at orientation `phi`, on all cores.
    pub fn map<T: Send>(&self, phi: f64, f: impl Fn(Pose) -> T + Sync) -> Vec<T> {
        (0..self.len())
            .into_par_iter()
            .map(|i| {
                let (x, y) = self.position(i);
                f(Pose::new(x, y, phi))
            })
            .collect()
    }
}

/// Which working mode a map or a maximum refers to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModeChoice {
    /// The largest value over the modes that reach the pose.
    Best,
    /// One working mode.
    Only(usize),
}

/// LCI at every grid point; `None` where the pose is out of reach.
pub fn lci_map(
    robot: &impl Manipulator,
    phi: f64,
    grid: &XyGrid,
    choice: ModeChoice,
) -> Vec<Option<f64>> {
    grid.map(phi, |pose| match choice {
        ModeChoice::Best => robot.best_lci(pose),
        ModeChoice::Only(mode) => robot.lci(pose, mode).ok(),
    })
}

/// Load index (1/m) at every grid point; `None` where the pose is out of reach.
pub fn load_index_map(
    robot: &impl Manipulator,
    phi: f64,
    grid: &XyGrid,
    choice: ModeChoice,
) -> Vec<Option<f64>> {
    let modes = robot.working_modes();
    grid.map(phi, |pose| match choice {
        ModeChoice::Best => (0..modes)
            .filter_map(|mode| robot.load_index(pose, mode).ok())
            .reduce(f64::max),
        ModeChoice::Only(mode) => robot.load_index(pose, mode).ok(),
    })
}

/// Whether each grid point is reachable (in some working mode).
pub fn reachable_map(robot: &impl Manipulator, phi: f64, grid: &XyGrid) -> Vec<bool> {
    grid.map(phi, |pose| robot.reaches(pose))
}

/// Whether each grid point is reachable by every one of `robots`.
pub fn common_map(robots: &[Robot], phi: f64, grid: &XyGrid) -> Vec<bool> {
    grid.map(phi, |pose| robots.iter().all(|r| r.reaches(pose)))
}
