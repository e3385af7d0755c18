//! The actuator Jacobian l_dot = J omega (omega in {A}) and its singularity measures.
//!
//! Differentiating |P + r_i - M_i| = a gives l_dot_i (n_i.u_i) = (r_i x n_i).omega, so
//! row i of J is (r_i x n_i)^T / (n_i.u_i). (The thesis's velocity equations drop the
//! leg direction; this form is derived in docs/3pss-model.md.)

use super::error::KinematicsError;
use super::ik::Assembly;
use super::params::Geometry;
use nalgebra::{Matrix3, Vector3};

/// |n_i.u_i| below which a leg counts as perpendicular to its actuator.
const SINGULAR_PROJECTION: f64 = 1e-12;

/// The Jacobian at one assembly, with its measures.
#[derive(Debug, Clone, PartialEq)]
pub struct Jacobian {
    /// J: l_dot = J omega, m/rad.
    pub matrix: Matrix3<f64>,
    /// n_i.u_i per leg: zero when leg i is perpendicular to its actuator.
    pub leg_projection: Vector3<f64>,
}

impl Jacobian {
    /// det J, m^3.
    pub fn det(&self) -> f64 {
        self.matrix.determinant()
    }

    /// 2-norm condition number sigma_max / sigma_min (infinite when singular).
    pub fn cond(&self) -> f64 {
        let s = self.matrix.singular_values();
        let (lo, hi) = (s.min(), s.max());
        if lo > 0.0 { hi / lo } else { f64::INFINITY }
    }

    /// Actuator velocities for a platform angular velocity omega (in {A}).
    pub fn actuator_rates(&self, omega: &Vector3<f64>) -> Vector3<f64> {
        self.matrix * omega
    }

    /// Angular velocity for actuator velocities: omega = J^-1 l_dot.
    pub fn angular_velocity(&self, l_dot: &Vector3<f64>) -> Result<Vector3<f64>, KinematicsError> {
        self.matrix
            .lu()
            .solve(l_dot)
            .ok_or(KinematicsError::Singular)
    }

    /// Statics: the moment about P of actuator forces f, tau = J^T f (N m).
    pub fn torque(&self, f: &Vector3<f64>) -> Vector3<f64> {
        self.matrix.transpose() * f
    }

    /// Statics: actuator forces that produce the moment tau about P, f = J^-T tau (N).
    pub fn forces(&self, tau: &Vector3<f64>) -> Result<Vector3<f64>, KinematicsError> {
        self.matrix
            .transpose()
            .lu()
            .solve(tau)
            .ok_or(KinematicsError::Singular)
    }
}

/// The Jacobian of the mechanism at `assembly`, or an error when a leg is
/// perpendicular to its actuator.
pub fn jacobian(geometry: &Geometry, assembly: &Assembly) -> Result<Jacobian, KinematicsError> {
    let mut matrix = Matrix3::zeros();
    let mut leg_projection = Vector3::zeros();
    for i in 0..3 {
        let projection = assembly.n[i].dot(&geometry.u[i]);
        if projection.abs() < SINGULAR_PROJECTION {
            return Err(KinematicsError::Singular);
        }
        leg_projection[i] = projection;
        let row = assembly.r[i].cross(&assembly.n[i]) / projection;
        matrix.set_row(i, &row.transpose());
    }
    Ok(Jacobian {
        matrix,
        leg_projection,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pss3::{assemble, rotation};

    #[test]
    fn jacobian_matches_finite_differences_of_ik() {
        // Truth: central differences of closed-form IK along Euler rates, mapped to omega.
        let g = Geometry::default();
        let th = Vector3::new(0.07, -0.05, 2.4);
        let rates = Vector3::new(0.3, -0.2, 0.5);
        let omega = rotation::euler_rate_matrix(&th) * rates;
        let dt = 1e-6;
        let l = |t: f64| assemble(&g, &(th + t * rates)).unwrap().l;
        let l_dot_fd = (l(dt) - l(-dt)) / (2.0 * dt);
        let j = jacobian(&g, &assemble(&g, &th).unwrap()).unwrap();
        let l_dot = j.actuator_rates(&omega);
        assert!(
            (l_dot - l_dot_fd).norm() < 1e-7 * l_dot.norm(),
            "{l_dot} vs {l_dot_fd}"
        );
        assert!((j.angular_velocity(&l_dot).unwrap() - omega).norm() < 1e-12);
    }

    #[test]
    fn statics_conserve_power() {
        // Truth: virtual power f.l_dot = tau.omega for tau = J^T f.
        let g = Geometry::default();
        let j = jacobian(&g, &assemble(&g, &Vector3::new(-0.1, 0.08, 2.2)).unwrap()).unwrap();
        let (f, omega) = (Vector3::new(12.0, -40.0, 7.5), Vector3::new(0.3, -1.2, 0.8));
        let tau = j.torque(&f);
        assert!((f.dot(&j.actuator_rates(&omega)) - tau.dot(&omega)).abs() < 1e-12);
        assert!((j.forces(&tau).unwrap() - f).norm() < 1e-10);
    }
}
