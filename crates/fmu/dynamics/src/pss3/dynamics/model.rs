//! The rigid-body model in omega coordinates (Kane's method / projected Newton-Euler):
//!
//!   M(q) omega_dot + c(q, omega) + g(q) = Q,
//!
//! q the orientation, omega the platform's angular velocity in {A}, Q the generalized
//! force (a moment about P, in {A}) of the applied loads. Every body velocity is
//! V_k = A_k(q) omega, so M = sum A_k^T m_k A_k, c = sum A_k^T (m_k a_k) plus the
//! platform's gyroscopic term omega x (I_P omega), with a_k the bias accelerations, and
//! g = -sum A_k^T m_k g_vec is the gradient of the potential energy (dV/dt = g.omega).

use super::error::{DynamicsError, PlantParamError};
use super::inertia::Inertia;
use super::legs::{ChainMotion, ChainPose};
use crate::pss3::{Assembly, Geometry, Jacobian, assemble, jacobian};
use nalgebra::{Matrix3, Vector3};

/// Standard gravity of the spec, in {A}, m/s^2.
pub const DEFAULT_GRAVITY: Vector3<f64> = Vector3::new(0.0, 0.0, -9.81);

/// Geometry, mass properties and gravity: everything the equations of motion need.
#[derive(Debug, Clone, PartialEq)]
pub struct Model {
    /// The validated geometry.
    pub geometry: Geometry,
    /// The validated mass properties.
    pub inertia: Inertia,
    /// Gravitational acceleration in {A}, m/s^2.
    pub gravity: Vector3<f64>,
}

/// The terms of M omega_dot + c + g = Q at one state, with the kinematics they used.
#[derive(Debug, Clone, PartialEq)]
pub struct Terms {
    /// The assembly (pose, actuator displacements, leg directions).
    pub assembly: Assembly,
    /// The actuator Jacobian, l_dot = J omega.
    pub jacobian: Jacobian,
    /// M(q), kg m^2, symmetric positive definite.
    pub mass: Matrix3<f64>,
    /// c(q, omega), N m: velocity-product terms (quadratic in omega).
    pub velocity: Vector3<f64>,
    /// g(q), N m: gravity terms, the gradient of the potential energy.
    pub gravity: Vector3<f64>,
}

impl Terms {
    /// Kinetic energy 1/2 omega.M omega, J.
    pub fn kinetic_energy(&self, omega: &Vector3<f64>) -> f64 {
        0.5 * omega.dot(&(self.mass * omega))
    }

    /// Angular acceleration for the generalized force `applied` (N m, about P in {A}):
    /// omega_dot = M^-1 (applied - c - g).
    pub fn angular_acceleration(
        &self,
        applied: &Vector3<f64>,
    ) -> Result<Vector3<f64>, DynamicsError> {
        let cholesky = self
            .mass
            .cholesky()
            .ok_or(DynamicsError::MassNotPositiveDefinite)?;
        Ok(cholesky.solve(&(applied - self.velocity - self.gravity)))
    }

    /// Generalized force needed for the angular acceleration `omega_dot`:
    /// M omega_dot + c + g.
    pub fn required_force(&self, omega_dot: &Vector3<f64>) -> Vector3<f64> {
        self.mass * omega_dot + self.velocity + self.gravity
    }
}

impl Model {
    /// Validates the mass properties and gravity for a validated geometry.
    pub fn new(
        geometry: Geometry,
        inertia: Inertia,
        gravity: Vector3<f64>,
    ) -> Result<Self, PlantParamError> {
        inertia.validate()?;
        if gravity.iter().any(|v| !v.is_finite()) {
            return Err(PlantParamError::NotFinite("gravity"));
        }
        Ok(Self {
            geometry,
            inertia,
            gravity,
        })
    }

    /// M, c and g at orientation `euler` (thx, thy, thz) and angular velocity `omega`
    /// (in {A}). The pose is assembled without a stroke check.
    pub fn terms(
        &self,
        euler: &Vector3<f64>,
        omega: &Vector3<f64>,
    ) -> Result<Terms, DynamicsError> {
        if omega.iter().any(|v| !v.is_finite()) {
            return Err(DynamicsError::NotFinite("angular velocity"));
        }
        let assembly = assemble(&self.geometry, euler)?;
        let jacobian = jacobian(&self.geometry, &assembly)?;
        let inertia = &self.inertia;
        let a = self.geometry.params.a;
        let rotation = assembly.rotation;

        let platform_inertia = rotation * inertia.platform_inertia * rotation.transpose();
        let com = rotation * inertia.platform_com;
        let mut mass = platform_inertia;
        let mut velocity = omega.cross(&(platform_inertia * omega));
        let mut gravity = -inertia.platform_mass * com.cross(&self.gravity);

        for i in 0..3 {
            let pose = ChainPose {
                u: self.geometry.u[i],
                r: assembly.r[i],
                n: assembly.n[i],
                jacobian_row: jacobian.matrix.row(i).transpose(),
                projection: jacobian.leg_projection[i],
            };
            let chain = ChainMotion::new(&pose, a, inertia.leg_com_fraction, omega);
            let j = chain.jacobian_row;
            let (com_map, angular_map) = (&chain.leg_com_map, &chain.leg_angular_map);

            mass += inertia.slider_mass * j * j.transpose()
                + inertia.leg_mass * com_map.tr_mul(com_map)
                + inertia.leg_transverse_inertia * angular_map.tr_mul(angular_map);
            velocity += inertia.slider_mass * chain.slider_bias * j
                + inertia.leg_mass * com_map.tr_mul(&chain.leg_com_bias)
                + inertia.leg_transverse_inertia * angular_map.tr_mul(&chain.leg_angular_bias);
            gravity -= inertia.slider_mass * pose.u.dot(&self.gravity) * j
                + inertia.leg_mass * com_map.tr_mul(&self.gravity);
        }
        Ok(Terms {
            assembly,
            jacobian,
            mass,
            velocity,
            gravity,
        })
    }

    /// Potential energy of gravity, J, zero at height 0 of {A}: platform, legs and
    /// sliders (slider centres of mass taken at their joint centres M_i).
    pub fn potential_energy(&self, assembly: &Assembly) -> f64 {
        let inertia = &self.inertia;
        let g = &self.geometry;
        let s = inertia.leg_com_fraction;
        let platform_com = g.p + assembly.rotation * inertia.platform_com;
        let mut weighted = inertia.platform_mass * platform_com;
        for i in 0..3 {
            let slider = g.slider_joint(i, assembly.l[i]);
            let joint = g.p + assembly.r[i];
            weighted +=
                inertia.slider_mass * slider + inertia.leg_mass * (slider + s * (joint - slider));
        }
        -weighted.dot(&self.gravity)
    }
}
