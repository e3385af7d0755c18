//! Largest LCI over a grid of positions, and its dependence on the orientation `phi`.

use super::workspace::{ModeChoice, XyGrid};
use super::{Manipulator, Pose, Robot};
use rayon::prelude::*;

/// The largest LCI found on a grid and where it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaxLci {
    pub value: f64,
    pub pose: Pose,
    pub mode: usize,
}

/// Where the largest LCI is sought.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Region {
    /// The paper's square `x, y in [-20, 20] cm`.
    Paper,
    /// The manipulator's own reachable workspace.
    Own,
    /// The workspace common to the three manipulators.
    Common,
}

/// Largest LCI at orientation `phi` over the grid points where `inside` holds, in the
/// working modes of `choice`; `None` if no such point is reachable.
pub fn max_lci(
    robot: &impl Manipulator,
    phi: f64,
    grid: &XyGrid,
    choice: ModeChoice,
    inside: impl Fn(Pose) -> bool + Sync,
) -> Option<MaxLci> {
    let modes: Vec<usize> = match choice {
        ModeChoice::Best => (0..robot.working_modes()).collect(),
        ModeChoice::Only(mode) => vec![mode],
    };
    (0..grid.len())
        .into_par_iter()
        .filter_map(|i| {
            let (x, y) = grid.position(i);
            let pose = Pose::new(x, y, phi);
            if !inside(pose) {
                return None;
            }
            modes
                .iter()
                .filter_map(|&mode| {
                    let value = robot.lci(pose, mode).ok()?;
                    Some(MaxLci { value, pose, mode })
                })
                .max_by(|a, b| a.value.total_cmp(&b.value))
        })
        .max_by(|a, b| a.value.total_cmp(&b.value))
}

/// Largest LCI of `robots[which]` at `phi` over `region`, on `points` per grid axis.
pub fn max_lci_in(
    robots: &[Robot],
    which: usize,
    phi: f64,
    region: Region,
    points: usize,
    choice: ModeChoice,
) -> Option<MaxLci> {
    let robot = &robots[which];
    match region {
        Region::Paper => max_lci(robot, phi, &XyGrid::paper(points), choice, |_| true),
        Region::Own => max_lci(robot, phi, &XyGrid::own(robot, points), choice, |_| true),
        Region::Common => max_lci(robot, phi, &XyGrid::common(robots, points), choice, |p| {
            robots.iter().all(|r| r.reaches(p))
        }),
    }
}

/// One row of a phi sweep: the orientation and the largest LCI of each manipulator.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepRow {
    pub phi: f64,
    pub max: Vec<Option<MaxLci>>,
}

/// Largest LCI (best working mode) of each manipulator at every orientation of `phis`.
pub fn phi_sweep(robots: &[Robot], phis: &[f64], region: Region, points: usize) -> Vec<SweepRow> {
    phis.par_iter()
        .map(|&phi| SweepRow {
            phi,
            max: (0..robots.len())
                .map(|k| max_lci_in(robots, k, phi, region, points, ModeChoice::Best))
                .collect(),
        })
        .collect()
}
