//! The 3-PSS spherical parallel robot: three horizontal prismatic actuators, three
//! S-S legs and a platform that rotates about a fixed spherical joint at P.
//!
//! Conventions (see docs/3pss-model.md): base frame {A} with Z up; orientation
//! R = Rz(thz) Ry(thy) Rx(thx) of the platform frame {B} in {A}; Euler angles are
//! stored as `Vector3` (thx, thy, thz) in rad; angular velocities `omega` are in {A}.
//! Everything is SI.

pub mod dynamics;
mod error;
mod fk;
mod ik;
mod jacobian;
mod motion;
mod params;
mod path;
pub mod rotation;
/// Workspace scans over the stroke box and the orientations, on every core (rayon):
/// feature `workspace`, which the robot library turns on and the FMUs leave off.
#[cfg(feature = "workspace")]
pub mod workspace;

pub use error::{KinematicsError, ParamError};
pub use fk::{FkOptions, ForwardSolution, START_ROLL_DEG, forward_kinematics, start_pose};
pub use ik::{Assembly, assemble, inverse_kinematics};
pub use jacobian::{Jacobian, jacobian};
pub use motion::{ActuatorState, Motion, forward_motion, inverse_motion, velocity_product};
pub use params::{Geometry, Params};
pub use path::{PathError, PathSample, Timing, linear_actuator_path};
