//! Typed errors of the 3-PSS library.

use std::fmt;

/// A parameter set that does not describe a buildable robot.
#[derive(Debug, Clone, PartialEq)]
pub enum ParamError {
    /// A length, angle or range bound is NaN or infinite.
    NotFinite(&'static str),
    /// A length that must be positive is not.
    NotPositive(&'static str, f64),
    /// The stroke range is empty or reversed (min, max), m.
    EmptyStroke(f64, f64),
    /// Leg `leg` (1-based) cannot connect its slider to the platform anywhere in the
    /// stroke: the leg length `a` lies outside the reachable span [min, max], m.
    LegCannotAssemble {
        leg: usize,
        a: f64,
        min: f64,
        max: f64,
    },
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite(name) => write!(f, "parameter {name} is not a finite number"),
            Self::NotPositive(name, v) => write!(f, "parameter {name} = {v} must be positive"),
            Self::EmptyStroke(lo, hi) => {
                write!(
                    f,
                    "stroke range [{lo}, {hi}] m is empty: min must be below max"
                )
            }
            Self::LegCannotAssemble { leg, a, min, max } => write!(
                f,
                "leg {leg} of length {a} m cannot assemble: over the stroke the slider joint \
                 is between {min} m and {max} m from the platform joints"
            ),
        }
    }
}

impl std::error::Error for ParamError {}

/// A pose or motion that the mechanism cannot take.
#[derive(Debug, Clone, PartialEq)]
pub enum KinematicsError {
    /// An input (angle, rate, length) is NaN or infinite.
    NotFinite(&'static str),
    /// Leg `leg` (1-based) cannot reach its platform joint at this orientation.
    CannotAssemble { leg: usize },
    /// Actuator `leg` (1-based) would have to move to `l` m, outside [min, max].
    OutsideStroke {
        leg: usize,
        l: f64,
        min: f64,
        max: f64,
    },
    /// The Jacobian is singular (a leg perpendicular to its actuator or dependent rows).
    Singular,
    /// The Euler-angle representation is singular (thy = +-90 deg).
    EulerSingular,
    /// Forward kinematics did not converge within `iterations`; last residual, m.
    NoConvergence { iterations: usize, residual: f64 },
}

impl fmt::Display for KinematicsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite(what) => write!(f, "{what} is not a finite number"),
            Self::CannotAssemble { leg } => {
                write!(
                    f,
                    "leg {leg} cannot reach its platform joint at this orientation"
                )
            }
            Self::OutsideStroke { leg, l, min, max } => write!(
                f,
                "actuator {leg} would be at {:.3} mm, outside its stroke [{:.3}, {:.3}] mm",
                l * 1e3,
                min * 1e3,
                max * 1e3
            ),
            Self::Singular => write!(f, "the actuator Jacobian is singular at this pose"),
            Self::EulerSingular => {
                write!(f, "Euler angles are singular at thy = +-90 deg")
            }
            Self::NoConvergence {
                iterations,
                residual,
            } => write!(
                f,
                "forward kinematics did not converge in {iterations} iterations \
                 (residual {residual:.3e} m)"
            ),
        }
    }
}

impl std::error::Error for KinematicsError {}
