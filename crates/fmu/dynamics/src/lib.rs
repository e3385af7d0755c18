//! robofmu-dynamics: the 3-PSS spherical parallel robot (kinematics, workspace scans,
//! rigid-body dynamics, the plant with its end stops and integrator), its
//! computed-torque law, and the Runge-Kutta pairs the plant integrates with (`ode`:
//! DOPRI5, DOP853).
//!
//! This is the robot library that the Pss3Plant and ComputedTorque FMUs run: an FMU
//! links it and nothing of the scenario reader or the analyses (no toml or serde; no
//! rayon either, which only the workspace scans use, behind the feature `workspace`:
//! `cargo tree -e normal -p robofmu-pss3-plant-fmu`). The crate `robofmu` re-exports
//! its modules with the workspace scans on (`robofmu::pss3`, `robofmu::computed_torque`
//! and `robofmu::ode`). Like it, this crate knows nothing of FMI.

pub mod computed_torque;
pub mod ode;
pub mod pss3;
