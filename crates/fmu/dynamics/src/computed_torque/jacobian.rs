//! The partial derivatives of the computed-torque law, for directional and adjoint
//! derivatives of its FMU.
//!
//! With a = q_ddot + Kd (q_dot - theta_dot) + Kp (q - theta) + Ki I and
//! u_raw = ID(theta, theta_dot, a) (`ComputedTorque::inverse_dynamics`), u_raw is affine
//! in a with the Euler-angle mass matrix M_x = E^T M E as its slope, so the columns of
//! the setpoint, its rate and acceleration and the error integral are exact:
//! M_x diag(Kp), M_x diag(Kd), M_x and M_x diag(Ki), M_x from the model's mass matrix
//! (no differences). The measured angles and rates enter the error (-M_x diag(Kp),
//! -M_x diag(Kd), exact) and the configuration-dependent terms of ID at a fixed a:
//! - d ID/d theta_dot: ID is quadratic in theta_dot (velocity products, viscous friction
//!   linear), so a central difference is exact for any step; with a step of 1 rad/s
//!   only rounding remains (about 1e-13 relative);
//! - d ID/d theta: central differences with one Richardson extrapolation,
//!   (4 D(h/2) - D(h)) / 3, h = 1e-3 rad (truncation O(h^4)): about 1e-9 relative, the
//!   plant's linearisation's accuracy (`pss3::dynamics::Linearization`).
//!
//! The limits: on an axis whose raw output is outside [u_min, u_max] the output is the
//! limit, so its row is zero; inside or on a limit it is the raw output's row. The
//! integral's rate is the error q - theta (rows +1 and -1), zero on an axis whose
//! integration is stopped (conditional integration, `ComputedTorque::integral_rate`).

use super::law::{ComputedTorque, Inputs, Output};
use crate::pss3::dynamics::DynamicsError;
use crate::pss3::rotation::euler_rate_matrix;
use nalgebra::{Matrix3, Vector3};

/// Step for the measured angles' Richardson-extrapolated central differences, rad.
const ANGLE_STEP: f64 = 1e-3;
/// Step for the measured rates' central difference, rad/s (exact for a quadratic).
const RATE_STEP: f64 = 1.0;

/// A signal the law's output and integral rate depend on (a 3-vector each).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Known {
    /// The planned Euler angles q.
    Setpoint,
    /// The planned rates q_dot.
    SetpointRate,
    /// The planned accelerations q_ddot.
    SetpointAcceleration,
    /// The measured Euler angles theta.
    Measurement,
    /// The measured rates theta_dot.
    MeasuredRate,
    /// The error integral I.
    Integral,
}

/// The law's partial derivatives at one point: a 3 x 3 block per [`Known`] for the
/// output u (N m per unit of the known) and for the integral's rate.
#[derive(Debug, Clone, PartialEq)]
pub struct LawJacobian {
    output: [Matrix3<f64>; 6],
    integral_rate: [Matrix3<f64>; 6],
}

impl LawJacobian {
    /// du/d(known): row k the output of axis k, column j element j of the known.
    pub fn output(&self, known: Known) -> &Matrix3<f64> {
        &self.output[known as usize]
    }

    /// d(integral rate)/d(known).
    pub fn integral_rate(&self, known: Known) -> &Matrix3<f64> {
        &self.integral_rate[known as usize]
    }
}

impl ComputedTorque {
    /// The Euler-angle mass matrix M_x(theta) = E^T M E, kg m^2: the slope of the
    /// inverse dynamics in the commanded acceleration (u_raw = M_x a + terms of theta
    /// and theta_dot).
    pub fn euler_mass_matrix(&self, theta: &Vector3<f64>) -> Result<Matrix3<f64>, DynamicsError> {
        let terms = self.model().model().terms(theta, &Vector3::zeros())?;
        let e = euler_rate_matrix(theta);
        Ok(e.transpose() * terms.mass * e)
    }

    /// `block` (derivatives of the raw output) with the rows of the axes whose raw
    /// output is outside their limits set to zero: the limited output's derivatives.
    fn limited_rows(&self, out: &Output, block: Matrix3<f64>) -> Matrix3<f64> {
        let gains = self.gains();
        let passes = Vector3::from_fn(|k, _| match gains[k].limits {
            Some((min, max)) => (min..=max).contains(&out.u_raw[k]),
            None => true,
        });
        Matrix3::from_fn(|k, j| if passes[k] { block[(k, j)] } else { 0.0 })
    }

    /// The partial derivatives of the output and the integral's rate at the error
    /// integral `integral` and `inputs` (see the module documentation for how each
    /// block is computed and its accuracy).
    pub fn jacobian(
        &self,
        integral: &Vector3<f64>,
        inputs: &Inputs,
    ) -> Result<LawJacobian, DynamicsError> {
        let out = self.output(integral, inputs)?;
        let (theta, theta_dot, a) = (inputs.measurement, inputs.measured_rate, out.acceleration);
        let mass = self.euler_mass_matrix(&theta)?;
        let gains = self.gains();
        let diag =
            |f: &dyn Fn(usize) -> f64| Matrix3::from_diagonal(&Vector3::from_fn(|j, _| f(j)));
        let kp = mass * diag(&|j| gains[j].kp);
        let kd = mass * diag(&|j| gains[j].kd);
        let ki = mass * diag(&|j| gains[j].ki);
        let id = |theta: Vector3<f64>, theta_dot: Vector3<f64>| {
            self.inverse_dynamics(&theta, &theta_dot, &a)
        };
        let mut by_angle = Matrix3::zeros();
        let mut by_rate = Matrix3::zeros();
        for j in 0..3 {
            let unit = Vector3::from_fn(|i, _| if i == j { 1.0 } else { 0.0 });
            let central = |h: f64| -> Result<Vector3<f64>, DynamicsError> {
                Ok(
                    (id(theta + unit * h, theta_dot)? - id(theta - unit * h, theta_dot)?)
                        / (2.0 * h),
                )
            };
            let column = (central(0.5 * ANGLE_STEP)? * 4.0 - central(ANGLE_STEP)?) / 3.0;
            by_angle.set_column(j, &column);
            let step = unit * RATE_STEP;
            let column =
                (id(theta, theta_dot + step)? - id(theta, theta_dot - step)?) / (2.0 * RATE_STEP);
            by_rate.set_column(j, &column);
        }
        let raw = [kp, kd, mass, by_angle - kp, by_rate - kd, ki];
        let output = raw.map(|block| self.limited_rows(&out, block));
        let integrating = Vector3::from_fn(|k, _| !self.integration_stopped(k, &out));
        let identity = Matrix3::from_diagonal(&integrating.map(|on| if on { 1.0 } else { 0.0 }));
        let zero = Matrix3::zeros();
        let integral_rate = [identity, zero, zero, -identity, zero, zero];
        Ok(LawJacobian {
            output,
            integral_rate,
        })
    }
}
