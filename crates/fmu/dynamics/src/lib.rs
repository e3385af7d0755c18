//! robofmu-dynamics: the 3-PSS spherical parallel robot (kinematics, rigid-body
//! dynamics, the plant with its end stops and integrator), its computed-torque law, and
//! the Runge-Kutta pairs the plant integrates with (`ode`: DOPRI5, DOP853).
//!
//! This is the part of the robot library that the Pss3Plant and ComputedTorque FMUs
//! run, split off so that an FMU links the dynamics and nothing of the scenario
//! reader or the analyses (no toml, serde or rayon: `cargo tree -e normal -p
//! robofmu-pss3-plant-fmu`). The robot library `robofmu` re-exports its modules
//! (`robofmu::pss3`, with its workspace scans, `robofmu::computed_torque` and
//! `robofmu::ode`), so its users see one library. Like it, this crate knows nothing of FMI.

pub mod computed_torque;
pub mod ode;
pub mod pss3;
