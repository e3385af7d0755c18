//! The 3-PSS spherical parallel robot: its kinematics and dynamics from
//! `robofmu-dynamics` (the crate the FMUs link), and the workspace scans, which run
//! on both cores (rayon) and so stay in this library.
//!
//! Conventions (see docs/3pss-model.md): base frame {A} with Z up; orientation
//! R = Rz(thz) Ry(thy) Rx(thx) of the platform frame {B} in {A}; Euler angles are
//! stored as `Vector3` (thx, thy, thz) in rad; angular velocities `omega` are in {A}.
//! Everything is SI.

pub use robofmu_dynamics::pss3::*;
pub mod workspace;
