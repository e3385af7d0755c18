//! Optimal joint paths of the dual-arm cam-lock robot (issue 6).
//!
//! Two planar four-joint arms share one end-effector point; cam locks fix some joints.
//! The joint path that follows a given end-effector path with the least actuator effort
//! `PI = integral of |theta_dot|^2 dt` is found two independent ways:
//!
//! - [`shooting`]: Pontryagin's minimum principle ([`pmp`]), integrated backwards from
//!   the final time with an adaptive Dormand-Prince 8(5,3) integrator, the redundant final
//!   joints corrected by Newton until the start transversality condition holds;
//! - [`direct`]: the joint path discretised on a time grid, the sum of
//!   `|delta theta|^2 / delta t` minimised by a damped Newton method on the redundant
//!   joints of every node (the other joints follow by inverse kinematics).
//!
//! Pontryagin's conditions are necessary only, so the default answer is
//! [`multistart::best_path`]: the cheapest extremal the shooting reaches from several
//! starts, with a [`optimality`] check that it is a local minimum.
//!
//! Everything is SI: metres, radians, seconds.

pub mod direct;
mod error;
pub mod kinematics;
mod linalg;
pub mod locks;
pub mod multistart;
pub mod optimality;
pub mod paths;
pub mod pmp;
pub mod reach;
pub mod shooting;
pub mod trajectory;

pub use error::DualArmError;
