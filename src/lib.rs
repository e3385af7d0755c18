//! robofmu: robot models and analyses, with no FMI and no command line.
//!
//! Layering, enforced by the crate graph: this library (`pss3`, `dexterity`,
//! `dual_arm`, `computed_torque`, `closed_loop`, `ode`, and `control` from
//! robofmu-control)
//! knows nothing of FMI; the FMI layer (crates/fmu/fmi, robofmu-fmi) knows nothing of
//! robots; each FMU crate under fmus/ is a thin binding between them; the command line
//! (crates/tools/cli) sits on top and owns plotting and file output.

pub use robofmu_control as control;
pub use robofmu_dynamics::computed_torque;
/// The Runge-Kutta pairs (DOPRI5, DOP853) the plant and the analyses integrate with.
pub use robofmu_dynamics::ode;

pub mod closed_loop;
pub mod dexterity;
pub mod dual_arm;
pub mod pss3;
