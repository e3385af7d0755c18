//! robofmu-analyses: the two robot analyses that are not FMUs, with no FMI and no
//! command line: the dexterity of planar 3-DOF manipulators (`dexterity`: serial
//! 1-RRR, parallel 2-RRR and 3-RRR) and the optimal joint paths of the dual-arm
//! cam-lock robot (`dual_arm`). The command line (robofmu-cli) writes their CSV and
//! PNG output.

/// The Runge-Kutta pairs of the robot library, which the dual-arm shooting integrates with.
use robofmu_dynamics::ode;

pub mod dexterity;
pub mod dual_arm;
