//! The planner -> PID -> 3-PSS plant loop as one continuous-time system, without FMI:
//! the independent reference for the co-simulation of the three FMUs, and the PID gain
//! design on the linearised plant. A scenario may choose the computed-torque law
//! (`crate::computed_torque`) instead of the PID (`controller`): it takes the planned
//! accelerations as well, no feedforward, and drives the same plant input u.
//!
//! Signals (the co-simulation scenarios connect the FMUs the same way):
//! - PID setpoint and setpoint rate = planned Euler angles q and rates q_dot;
//! - PID measurement and measured rate = plant Euler angles theta and rates theta_dot;
//! - PID feedforward = the plant's gravity compensation G_x(theta) = E^T g(theta);
//! - PID output u = generalized force in Euler-angle coordinates, realised by the
//!   actuators as tau = E^-T u about P and f = J^-T tau.
//!
//! State of the loop: (theta, omega, PID integral, PID filter), 12 values; the planner
//! is a function of time. With the controller sampled (`simulate_sampled`: the PID or
//! the computed-torque law at ticks of a fixed period, output held between them) the
//! continuous state is the plant's alone.

mod controller;
mod error;
mod form;
mod gains;
mod sampled;
mod scenario;
mod simulate;
mod summary;

pub use controller::{Controller, ControllerKind};
pub use error::LoopError;
pub use form::{GainRule, gain_rule};
pub use gains::{AxisDesign, design_gains, triple_pole_gains};
pub use sampled::simulate_sampled;
pub use scenario::{LoopSpec, parse_loop_scenario};
pub use simulate::{LoopSample, simulate};
pub use summary::{Tracking, tracking};
