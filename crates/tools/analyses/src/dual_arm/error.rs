//! Errors of the dual-arm analyses.

use std::fmt;

/// Why a dual-arm computation failed; never a silent wrong answer.
#[derive(Debug, Clone, PartialEq)]
pub enum DualArmError {
    /// A parameter or input value is out of its domain.
    InvalidInput(String),
    /// The end-effector point is out of reach of an arm for the given joints.
    Unreachable { t: f64, arm: &'static str },
    /// The path leaves an arm's reachable annulus: no joints at all reach it.
    OutsideReach {
        t: f64,
        arm: &'static str,
        distance: f64,
        inner: f64,
        outer: f64,
    },
    /// The constraint Jacobian lost rank (a kinematic singularity).
    Singular { t: f64 },
    /// The adaptive integrator gave up.
    Integration(String),
    /// The Newton iteration of the shooting or direct method did not converge.
    NotConverged {
        method: &'static str,
        iterations: usize,
        residual: f64,
        tolerance: f64,
    },
}

impl fmt::Display for DualArmError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidInput(m) => write!(f, "invalid input: {m}"),
            Self::Unreachable { t, arm } => write!(
                f,
                "the end-effector point at t = {t:.6} s is out of reach of the {arm} arm \
                 (inverse kinematics has no solution; try another initial guess)"
            ),
            Self::OutsideReach {
                t,
                arm,
                distance,
                inner,
                outer,
            } => write!(
                f,
                "the path at t = {t:.6} s is out of reach of the {arm} arm whatever its \
                 joints: {distance:.4} m from the arm's first free joint, outside [{inner:.4}, \
                 {outer:.4}] m"
            ),
            Self::Singular { t } => write!(
                f,
                "singular configuration near t = {t:.6} s (the constraint Jacobian lost rank)"
            ),
            Self::Integration(m) => write!(f, "integration failed: {m}"),
            Self::NotConverged {
                method,
                iterations,
                residual,
                tolerance,
            } => write!(
                f,
                "{method} did not converge: residual {residual:.3e} after {iterations} \
                 iterations (tolerance {tolerance:.1e}); try another initial guess"
            ),
        }
    }
}

impl std::error::Error for DualArmError {}
