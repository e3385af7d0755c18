//! robofmu: the robot library in one namespace, with no FMI and no command line.
//!
//! Layering, enforced by the crate graph: this library (`pss3`, `computed_torque` and
//! `ode` from robofmu-dynamics, `control` from robofmu-control, and `closed_loop`, the
//! reference simulation of the closed loop that reads the scenario files) knows nothing
//! of FMI; the FMI layer (crates/fmu/fmi, robofmu-fmi) knows nothing of robots; each
//! FMU crate under fmus/ is a thin binding between them; the analyses that are no FMU
//! (crates/tools/analyses) and the command line (crates/tools/cli) sit on top, and the
//! command line owns plotting and file output.

pub use robofmu_control as control;
pub use robofmu_dynamics::computed_torque;
/// The Runge-Kutta pairs (DOPRI5, DOP853) the plant and the analyses integrate with.
pub use robofmu_dynamics::ode;
/// The 3-PSS spherical parallel robot: kinematics, workspace scans and dynamics.
pub use robofmu_dynamics::pss3;

pub mod closed_loop;
