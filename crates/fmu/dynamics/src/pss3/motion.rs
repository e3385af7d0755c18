//! Velocity and acceleration level kinematics: actuator rates and accelerations from
//! the platform's angular velocity and acceleration (inverse) and back (forward).
//!
//! With the leg vector a n_i = P + r_i - h_i - l_i u_i of fixed length a and
//! v_i = omega x r_i - l_dot_i u_i its velocity (a n_i_dot = v_i):
//! - n_i.v_i = 0 gives l_dot_i (n_i.u_i) = (r_i x n_i).omega, i.e. l_dot = J omega;
//! - its time derivative n_i_dot.v_i + n_i.v_i_dot = 0, with
//!   v_i_dot = omega_dot x r_i + omega x (omega x r_i) - l_ddot_i u_i, gives
//!   l_ddot = J omega_dot + c with
//!   c_i = (n_i.(omega x (omega x r_i)) + |v_i|^2 / a) / (n_i.u_i).
//!
//! c is J_dot omega, the velocity product of the acceleration relation.

use super::error::KinematicsError;
use super::fk::{FkOptions, forward_kinematics};
use super::ik::{Assembly, inverse_kinematics};
use super::jacobian::{Jacobian, jacobian};
use super::params::Geometry;
use super::rotation::{euler_accelerations, euler_rates};
use nalgebra::Vector3;

/// The mechanism in motion: pose, actuator and platform velocities and accelerations.
#[derive(Debug, Clone, PartialEq)]
pub struct Motion {
    /// Pose (Euler angles, rotation, l, leg vectors).
    pub assembly: Assembly,
    /// Actuator Jacobian at the pose.
    pub jacobian: Jacobian,
    /// Actuator velocities, m/s.
    pub l_dot: Vector3<f64>,
    /// Actuator accelerations, m/s^2.
    pub l_ddot: Vector3<f64>,
    /// Angular velocity of the platform in {A}, rad/s.
    pub omega: Vector3<f64>,
    /// Angular acceleration of the platform in {A}, rad/s^2.
    pub omega_dot: Vector3<f64>,
}

impl Motion {
    /// Euler-angle rates (thx_dot, thy_dot, thz_dot), rad/s.
    pub fn euler_rates(&self) -> Result<Vector3<f64>, KinematicsError> {
        euler_rates(&self.assembly.euler, &self.omega)
    }

    /// Euler-angle accelerations, rad/s^2.
    pub fn euler_accelerations(&self) -> Result<Vector3<f64>, KinematicsError> {
        euler_accelerations(&self.assembly.euler, &self.euler_rates()?, &self.omega_dot)
    }
}

/// J_dot omega at `assembly` for angular velocity `omega` and actuator rates `l_dot`
/// (which must be J omega): the term c of l_ddot = J omega_dot + c, m/s^2.
pub fn velocity_product(
    geometry: &Geometry,
    assembly: &Assembly,
    jacobian: &Jacobian,
    omega: &Vector3<f64>,
    l_dot: &Vector3<f64>,
) -> Vector3<f64> {
    Vector3::from_fn(|i, _| {
        let (r, n) = (assembly.r[i], assembly.n[i]);
        let centripetal = omega.cross(&omega.cross(&r));
        let leg_velocity = omega.cross(&r) - l_dot[i] * geometry.u[i];
        (n.dot(&centripetal) + leg_velocity.norm_squared() / geometry.params.a)
            / jacobian.leg_projection[i]
    })
}

/// Inverse kinematics of a motion: actuator displacements, rates and accelerations for
/// the orientation `euler` (rad), angular velocity `omega` (rad/s) and angular
/// acceleration `omega_dot` (rad/s^2), both in {A}.
pub fn inverse_motion(
    geometry: &Geometry,
    euler: &Vector3<f64>,
    omega: &Vector3<f64>,
    omega_dot: &Vector3<f64>,
) -> Result<Motion, KinematicsError> {
    check_finite(omega, "angular velocity")?;
    check_finite(omega_dot, "angular acceleration")?;
    let assembly = inverse_kinematics(geometry, euler)?;
    let jacobian = jacobian(geometry, &assembly)?;
    let l_dot = jacobian.actuator_rates(omega);
    let l_ddot = jacobian.actuator_rates(omega_dot)
        + velocity_product(geometry, &assembly, &jacobian, omega, &l_dot);
    Ok(Motion {
        assembly,
        jacobian,
        l_dot,
        l_ddot,
        omega: *omega,
        omega_dot: *omega_dot,
    })
}

/// Actuator state: displacements (m), velocities (m/s) and accelerations (m/s^2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ActuatorState {
    pub l: Vector3<f64>,
    pub l_dot: Vector3<f64>,
    pub l_ddot: Vector3<f64>,
}

/// Forward kinematics of a motion: the orientation by Newton's method from `seed`, then
/// omega = J^-1 l_dot and omega_dot = J^-1 (l_ddot - J_dot omega).
pub fn forward_motion(
    geometry: &Geometry,
    actuators: &ActuatorState,
    seed: &Vector3<f64>,
    options: &FkOptions,
) -> Result<Motion, KinematicsError> {
    check_finite(&actuators.l_dot, "actuator velocities")?;
    check_finite(&actuators.l_ddot, "actuator accelerations")?;
    let assembly = forward_kinematics(geometry, &actuators.l, seed, options)?.assembly;
    let jacobian = jacobian(geometry, &assembly)?;
    let omega = jacobian.angular_velocity(&actuators.l_dot)?;
    let c = velocity_product(geometry, &assembly, &jacobian, &omega, &actuators.l_dot);
    let omega_dot = jacobian.angular_velocity(&(actuators.l_ddot - c))?;
    Ok(Motion {
        assembly,
        jacobian,
        l_dot: actuators.l_dot,
        l_ddot: actuators.l_ddot,
        omega,
        omega_dot,
    })
}

fn check_finite(v: &Vector3<f64>, what: &'static str) -> Result<(), KinematicsError> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(KinematicsError::NotFinite(what))
    }
}
