//! Motion of one actuator chain (slider and S-S leg) as a linear map of the platform's
//! angular velocity omega, plus the velocity-product ("bias") accelerations.
//!
//! With Q = P + r the platform joint, M the slider joint, n = (Q - M)/a and
//! l_dot = j.omega (j the Jacobian row):
//!   v_M = u (j.omega),  v_Q = omega x r,  v_rel = v_Q - v_M,
//!   leg angular velocity  w = n x v_rel / a   (no spin about n),
//!   leg centre of mass    v_C = v_M + s v_rel  (s = leg_com_fraction).
//! Differentiating at omega_dot = 0 gives the bias accelerations:
//!   a_Q = omega x (omega x r),
//!   l_ddot = (n.a_Q + |v_rel|^2 / a) / (n.u)   (second derivative of |Q - M| = a),
//!   a_M = l_ddot u,  alpha = n x (a_Q - a_M) / a,  a_C = a_M + s (a_Q - a_M).
//! (d/dt of n x v_rel / a is n x a_rel / a because n_dot = v_rel / a.)

use nalgebra::{Matrix3, Vector3};

/// Velocity maps (V = A omega) and bias accelerations (at omega_dot = 0) of one chain.
pub(super) struct ChainMotion {
    /// Jacobian row j: l_dot = j.omega.
    pub jacobian_row: Vector3<f64>,
    /// A_C: velocity of the leg's centre of mass.
    pub leg_com_map: Matrix3<f64>,
    /// A_w: angular velocity of the leg.
    pub leg_angular_map: Matrix3<f64>,
    /// Slider acceleration along u at omega_dot = 0, m/s^2.
    pub slider_bias: f64,
    /// Acceleration of the leg's centre of mass at omega_dot = 0.
    pub leg_com_bias: Vector3<f64>,
    /// Angular acceleration of the leg at omega_dot = 0.
    pub leg_angular_bias: Vector3<f64>,
}

/// One chain's geometry at the current pose.
pub(super) struct ChainPose {
    /// Actuator direction u.
    pub u: Vector3<f64>,
    /// Platform joint relative to P, r = R b.
    pub r: Vector3<f64>,
    /// Unit leg direction n.
    pub n: Vector3<f64>,
    /// Jacobian row j.
    pub jacobian_row: Vector3<f64>,
    /// n.u.
    pub projection: f64,
}

impl ChainMotion {
    /// The chain's motion for leg length `a`, centre-of-mass fraction `s`, at `omega`.
    pub fn new(pose: &ChainPose, a: f64, s: f64, omega: &Vector3<f64>) -> Self {
        let ChainPose {
            u,
            r,
            n,
            jacobian_row: j,
            projection,
        } = pose;
        let slider_map = u * j.transpose();
        let joint_map = -r.cross_matrix();
        let relative_map = joint_map - slider_map;
        let leg_angular_map = n.cross_matrix() * relative_map / a;
        let leg_com_map = slider_map + s * relative_map;

        let l_dot = j.dot(omega);
        let v_rel = omega.cross(r) - l_dot * u;
        let joint_bias = omega.cross(&omega.cross(r));
        let slider_bias = (n.dot(&joint_bias) + v_rel.norm_squared() / a) / projection;
        let relative_bias = joint_bias - slider_bias * u;
        Self {
            jacobian_row: *j,
            leg_com_map,
            leg_angular_map,
            slider_bias,
            leg_com_bias: slider_bias * u + s * relative_bias,
            leg_angular_bias: n.cross(&relative_bias) / a,
        }
    }
}
