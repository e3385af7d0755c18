//! Typed errors of the 3-PSS dynamics.

use crate::pss3::{KinematicsError, ParamError};
use std::fmt;

/// A plant parameter set that does not describe a physical robot.
#[derive(Debug, Clone, PartialEq)]
pub enum PlantParamError {
    /// The geometry is invalid.
    Geometry(ParamError),
    /// A parameter is NaN or infinite.
    NotFinite(&'static str),
    /// A parameter that must be zero or positive is negative.
    Negative(&'static str, f64),
    /// A parameter that must be strictly positive is not.
    NotPositive(&'static str, f64),
    /// A fraction that must lie in [0, 1] does not.
    OutsideUnitInterval(&'static str, f64),
    /// An inertia tensor is not one a rigid body can have (reason given).
    InertiaNotPhysical(&'static str),
}

impl fmt::Display for PlantParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Geometry(e) => write!(f, "{e}"),
            Self::NotFinite(name) => write!(f, "parameter {name} is not a finite number"),
            Self::Negative(name, v) => write!(f, "parameter {name} = {v} must not be negative"),
            Self::NotPositive(name, v) => write!(f, "parameter {name} = {v} must be positive"),
            Self::OutsideUnitInterval(name, v) => {
                write!(f, "parameter {name} = {v} must lie between 0 and 1")
            }
            Self::InertiaNotPhysical(reason) => write!(f, "platform inertia: {reason}"),
        }
    }
}

impl std::error::Error for PlantParamError {}

impl From<ParamError> for PlantParamError {
    fn from(e: ParamError) -> Self {
        Self::Geometry(e)
    }
}

/// A state, input or step that the dynamics cannot evaluate.
#[derive(Debug, Clone, PartialEq)]
pub enum DynamicsError {
    /// The pose cannot be assembled, the Jacobian or the Euler map is singular, or (with
    /// end stops set to stop the simulation) an actuator left its stroke.
    Kinematics(KinematicsError),
    /// An input or state component is NaN or infinite.
    NotFinite(&'static str),
    /// The mass matrix is not positive definite (cannot happen for valid parameters;
    /// reported rather than returning NaN).
    MassNotPositiveDefinite,
    /// An integration setting is out of range.
    InvalidSetting(&'static str, f64),
    /// The integrator could not reach the end of the step; `cause` is the last model
    /// error met in a trial stage, if any.
    Solver {
        message: String,
        cause: Option<Box<DynamicsError>>,
    },
}

impl fmt::Display for DynamicsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Kinematics(e) => write!(f, "{e}"),
            Self::NotFinite(what) => write!(f, "{what} is not a finite number"),
            Self::MassNotPositiveDefinite => {
                write!(f, "the mass matrix is not positive definite")
            }
            Self::InvalidSetting(name, v) => {
                write!(f, "integration setting {name} = {v} is invalid")
            }
            Self::Solver { message, cause } => match cause {
                Some(c) => write!(f, "integration failed: {message} (last model error: {c})"),
                None => write!(f, "integration failed: {message}"),
            },
        }
    }
}

impl std::error::Error for DynamicsError {}

impl From<KinematicsError> for DynamicsError {
    fn from(e: KinematicsError) -> Self {
        Self::Kinematics(e)
    }
}
