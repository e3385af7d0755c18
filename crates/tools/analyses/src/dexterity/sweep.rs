//! Largest LCI over a grid of positions, and its dependence on the orientation `phi`.

use super::workspace::{ModeChoice, XyGrid, common_map};
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

/// Largest LCI at orientation `phi` over the grid points whose index satisfies
/// `inside`, in the working modes of `choice`; `None` if no such point is reachable.
pub fn max_lci(
    robot: &impl Manipulator,
    phi: f64,
    grid: &XyGrid,
    choice: ModeChoice,
    inside: impl Fn(usize) -> bool + Sync,
) -> Option<MaxLci> {
    (0..grid.len())
        .into_par_iter()
        .filter_map(|i| {
            if !inside(i) {
                return None;
            }
            let (x, y) = grid.position(i);
            let pose = Pose::new(x, y, phi);
            let (value, mode) = match choice {
                ModeChoice::Best => robot.best_lci_mode(pose)?,
                ModeChoice::Only(mode) => (robot.lci(pose, mode).ok()?, mode),
            };
            Some(MaxLci { value, pose, mode })
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
        Region::Paper => max_lci(robot, phi, &XyGrid::paper(points), choice, |_: usize| true),
        Region::Own => max_lci(
            robot,
            phi,
            &XyGrid::own(robot, points),
            choice,
            |_: usize| true,
        ),
        Region::Common => {
            let grid = XyGrid::common(robots, points);
            let common = common_map(robots, phi, &grid);
            max_lci(robot, phi, &grid, choice, |i| common[i])
        }
    }
}

/// One row of a phi sweep: the orientation and the largest LCI of each manipulator.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepRow {
    pub phi: f64,
    pub max: Vec<Option<MaxLci>>,
}

/// Largest LCI of each manipulator at every orientation of `phis`, in the working
/// modes `choices[k]` of manipulator `k`.
pub fn phi_sweep(
    robots: &[Robot],
    choices: &[ModeChoice],
    phis: &[f64],
    region: Region,
    points: usize,
) -> Vec<SweepRow> {
    phis.par_iter()
        .map(|&phi| {
            let max = if region == Region::Common {
                // One common-workspace mask per orientation, shared by the manipulators.
                let grid = XyGrid::common(robots, points);
                let common = common_map(robots, phi, &grid);
                robots
                    .iter()
                    .zip(choices)
                    .map(|(r, &choice)| max_lci(r, phi, &grid, choice, |i| common[i]))
                    .collect()
            } else {
                (0..robots.len())
                    .map(|k| max_lci_in(robots, k, phi, region, points, choices[k]))
                    .collect()
            };
            SweepRow { phi, max }
        })
        .collect()
}
