//! Errors of the closed-loop reference.

use crate::control::pid::PidError;
use crate::control::trajectory::TrajectoryError;
use crate::pss3::dynamics::{DynamicsError, PlantParamError};
use std::fmt;

/// Why a closed-loop scenario cannot be set up or simulated.
#[derive(Debug)]
pub enum LoopError {
    /// The scenario file is not valid TOML or lacks/mistypes a field (named).
    Scenario(String),
    Trajectory(TrajectoryError),
    Pid(PidError),
    Plant(PlantParamError),
    Dynamics(DynamicsError),
    /// The integrator failed at time t (s).
    Integration {
        time: f64,
        message: String,
    },
}

impl fmt::Display for LoopError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Scenario(m) => write!(f, "scenario: {m}"),
            Self::Trajectory(e) => write!(f, "planner: {e}"),
            Self::Pid(e) => write!(f, "PID: {e}"),
            Self::Plant(e) => write!(f, "plant parameters: {e}"),
            Self::Dynamics(e) => write!(f, "plant: {e}"),
            Self::Integration { time, message } => {
                write!(f, "integration failed at t = {time} s: {message}")
            }
        }
    }
}

impl std::error::Error for LoopError {}

impl From<TrajectoryError> for LoopError {
    fn from(e: TrajectoryError) -> Self {
        Self::Trajectory(e)
    }
}

impl From<PidError> for LoopError {
    fn from(e: PidError) -> Self {
        Self::Pid(e)
    }
}

impl From<PlantParamError> for LoopError {
    fn from(e: PlantParamError) -> Self {
        Self::Plant(e)
    }
}

impl From<DynamicsError> for LoopError {
    fn from(e: DynamicsError) -> Self {
        Self::Dynamics(e)
    }
}
