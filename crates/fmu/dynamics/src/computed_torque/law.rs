//! The computed-torque law, its gains and its anti-windup (see the module
//! documentation for the equations).

use crate::pss3::dynamics::{
    DynamicsError, Plant, PlantParamError, PlantParams, euler_generalized_force,
};
use crate::pss3::rotation::{angular_acceleration, euler_rate_matrix};
use nalgebra::Vector3;
use std::fmt;

/// Gains and output limits of one Euler-angle axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisGains {
    /// Acceleration per angle error, 1/s^2.
    pub kp: f64,
    /// Acceleration per rate error, 1/s.
    pub kd: f64,
    /// Acceleration per integrated error, 1/s^3 (0: no integral action).
    pub ki: f64,
    /// Output limits (u_min, u_max), N m, or None for an unlimited output.
    pub limits: Option<(f64, f64)>,
}

/// Why a computed-torque controller cannot be built.
#[derive(Debug, Clone, PartialEq)]
pub enum ControllerError {
    /// A gain or limit of an axis (1-based) is NaN or infinite.
    NonFinite(usize, &'static str),
    /// u_min >= u_max on an axis (1-based).
    EmptyLimits { axis: usize, min: f64, max: f64 },
    /// The pole-placement bandwidth is not a positive number.
    Bandwidth(f64),
    /// The controller's model parameters do not describe a physical robot.
    Model(PlantParamError),
    /// The sample period of the sampled law is not a positive finite number, s.
    SamplePeriod(f64),
}

impl fmt::Display for ControllerError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite(axis, what) => write!(f, "axis {axis}: {what} is not finite"),
            Self::EmptyLimits { axis, min, max } => write!(
                f,
                "axis {axis}: the output limits are empty: u_min = {min} >= u_max = {max}"
            ),
            Self::Bandwidth(w) => write!(f, "the bandwidth {w} rad/s must be positive"),
            Self::Model(e) => write!(f, "controller model: {e}"),
            Self::SamplePeriod(p) => write!(
                f,
                "the sample period {p} s must be a positive finite number of seconds"
            ),
        }
    }
}

impl std::error::Error for ControllerError {}

impl AxisGains {
    fn validate(&self, axis: usize) -> Result<(), ControllerError> {
        for (v, name) in [(self.kp, "Kp"), (self.kd, "Kd"), (self.ki, "Ki")] {
            if !v.is_finite() {
                return Err(ControllerError::NonFinite(axis, name));
            }
        }
        if let Some((min, max)) = self.limits {
            if !(min.is_finite() && max.is_finite()) {
                return Err(ControllerError::NonFinite(axis, "an output limit"));
            }
            if min >= max {
                return Err(ControllerError::EmptyLimits { axis, min, max });
            }
        }
        Ok(())
    }

    fn limit(&self, u: f64) -> f64 {
        match self.limits {
            Some((min, max)) => u.clamp(min, max),
            None => u,
        }
    }
}

/// The controller's inputs: the planned motion and the measured one (Euler angles,
/// rad, and their first and second time derivatives).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Inputs {
    pub setpoint: Vector3<f64>,
    pub setpoint_rate: Vector3<f64>,
    pub setpoint_acceleration: Vector3<f64>,
    pub measurement: Vector3<f64>,
    pub measured_rate: Vector3<f64>,
}

/// The output and its parts at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Output {
    /// Limited generalized force in Euler-angle coordinates, N m.
    pub u: Vector3<f64>,
    /// The same before the limits.
    pub u_raw: Vector3<f64>,
    /// Tracking error q - theta, rad.
    pub error: Vector3<f64>,
    /// The commanded Euler-angle acceleration a, rad/s^2.
    pub acceleration: Vector3<f64>,
}

/// A validated computed-torque controller: its model of the robot and its gains.
#[derive(Debug, Clone, PartialEq)]
pub struct ComputedTorque {
    model: Plant,
    gains: [AxisGains; 3],
}

impl ComputedTorque {
    /// Builds the controller on the model `model` (geometry, inertia, gravity and
    /// friction are used; end stops are not).
    pub fn new(model: PlantParams, gains: [AxisGains; 3]) -> Result<Self, ControllerError> {
        for (k, g) in gains.iter().enumerate() {
            g.validate(k + 1)?;
        }
        let model = Plant::new(model).map_err(ControllerError::Model)?;
        Ok(Self { model, gains })
    }

    /// The controller's model of the robot.
    pub fn model(&self) -> &Plant {
        &self.model
    }

    /// The gains of the three axes.
    pub fn gains(&self) -> &[AxisGains; 3] {
        &self.gains
    }

    /// Inverse dynamics in Euler-angle coordinates: the generalized force (N m) that
    /// gives the accelerations `theta_ddot` at angles `theta` moving at `theta_dot`,
    /// against inertia, velocity terms, gravity and viscous friction of the model:
    /// E^T (M omega_dot + c + g + J^T c_s l_dot + c_P omega).
    pub fn inverse_dynamics(
        &self,
        theta: &Vector3<f64>,
        theta_dot: &Vector3<f64>,
        theta_ddot: &Vector3<f64>,
    ) -> Result<Vector3<f64>, DynamicsError> {
        if theta_ddot.iter().any(|v| !v.is_finite()) {
            return Err(DynamicsError::NotFinite("commanded acceleration"));
        }
        let omega = euler_rate_matrix(theta) * theta_dot;
        let omega_dot = angular_acceleration(theta, theta_dot, theta_ddot);
        let terms = self.model.model().terms(theta, &omega)?;
        let friction = self.model.friction();
        let slider_losses = friction.slider * terms.jacobian.actuator_rates(&omega);
        let losses = terms.jacobian.torque(&slider_losses) + friction.pivot * omega;
        let moment = terms.required_force(&omega_dot) + losses;
        Ok(euler_generalized_force(theta, &moment))
    }

    /// The output for the error integral `integral` (rad s per axis) and `inputs`.
    pub fn output(
        &self,
        integral: &Vector3<f64>,
        inputs: &Inputs,
    ) -> Result<Output, DynamicsError> {
        let error = inputs.setpoint - inputs.measurement;
        let rate_error = inputs.setpoint_rate - inputs.measured_rate;
        let acceleration = Vector3::from_fn(|k, _| {
            let g = &self.gains[k];
            inputs.setpoint_acceleration[k]
                + g.kd * rate_error[k]
                + g.kp * error[k]
                + g.ki * integral[k]
        });
        let u_raw =
            self.inverse_dynamics(&inputs.measurement, &inputs.measured_rate, &acceleration)?;
        let u = Vector3::from_fn(|k, _| self.gains[k].limit(u_raw[k]));
        Ok(Output {
            u,
            u_raw,
            error,
            acceleration,
        })
    }

    /// Time derivative of the error integral: the error, except on an axis whose output
    /// is at a limit while Ki e pushes it further out (conditional integration, as the
    /// PID; the push of the integral on its own axis is M_x,kk Ki e with M_x,kk > 0).
    pub fn integral_rate(&self, output: &Output) -> Vector3<f64> {
        Vector3::from_fn(|k, _| {
            if self.integration_stopped(k, output) {
                0.0
            } else {
                output.error[k]
            }
        })
    }

    /// Whether the integral of axis `k` (0-based) is stopped at `output`: its output is
    /// at a limit and Ki e pushes it further out.
    pub(super) fn integration_stopped(&self, k: usize, output: &Output) -> bool {
        let g = &self.gains[k];
        let push = g.ki * output.error[k];
        let raw = output.u_raw[k];
        match g.limits {
            Some((min, max)) => (raw >= max && push > 0.0) || (raw <= min && push < 0.0),
            None => false,
        }
    }
}
