//! Dexterity of planar 3-DOF manipulators: a serial 1-RRR arm and the 2-RRR and 3-RRR
//! parallel manipulators.
//!
//! For each manipulator: geometry (the paper's values as defaults), inverse kinematics
//! in every working mode, the Jacobian `qdot = J Thetadot` with `q = (x, y, phi)`, the
//! dimensionally homogeneous Jacobian (velocities of two points of the end effector),
//! the local condition index (LCI), the load index, the reachable workspace and the
//! global condition index (GCI). Everything is SI: metres and radians.

mod dyad;
mod error;
pub mod gci;
pub mod indices;
pub mod layout;
mod manipulator;
pub mod parallel_2rrr;
pub mod parallel_3rrr;
mod robot;
pub mod serial_1rrr;
pub mod sweep;
pub mod workspace;

pub use error::DexterityError;
pub use manipulator::{Joints, Manipulator, Pose};
pub use robot::{Robot, RobotKind};
