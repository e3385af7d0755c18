//! The equations of motion in Euler-angle coordinates x = (thx, thy, thz), the form of
//! the thesis: M_x(x) x_ddot + C(x, x_dot) x_dot + G(x) = F.
//!
//! With omega = E x_dot and omega_dot = E x_ddot + E_dot x_dot, pre-multiplying the
//! omega form by E^T (the principle of virtual power) gives
//!   M_x = E^T M E,  C x_dot = E^T (M E_dot x_dot + c(q, E x_dot)),  G = E^T g,
//!   F = E^T Q  (Q the moment about P in {A}, e.g. J^T f + tau).
//! Only the product C x_dot is defined here (the factorisation into a matrix C is not
//! unique); `velocity` is that vector.

use super::error::DynamicsError;
use super::model::Model;
use crate::pss3::rotation::{euler_rate_matrix, euler_rate_matrix_dot};
use nalgebra::{Matrix3, Vector3};

/// M_x, C(x, x_dot) x_dot and G of the Euler-angle form at one state.
#[derive(Debug, Clone, PartialEq)]
pub struct EulerAngleForm {
    /// M_x = E^T M E, kg m^2.
    pub mass: Matrix3<f64>,
    /// C(x, x_dot) x_dot = E^T (M E_dot x_dot + c), N m.
    pub velocity: Vector3<f64>,
    /// G = E^T g, N m.
    pub gravity: Vector3<f64>,
}

impl EulerAngleForm {
    /// Euler-angle accelerations for the generalized force `force` (= E^T Q).
    pub fn accelerations(&self, force: &Vector3<f64>) -> Result<Vector3<f64>, DynamicsError> {
        let cholesky = self
            .mass
            .cholesky()
            .ok_or(DynamicsError::MassNotPositiveDefinite)?;
        Ok(cholesky.solve(&(force - self.velocity - self.gravity)))
    }
}

impl Model {
    /// The Euler-angle form at angles `euler` moving at rates `rates` (rad/s).
    pub fn euler_angle_form(
        &self,
        euler: &Vector3<f64>,
        rates: &Vector3<f64>,
    ) -> Result<EulerAngleForm, DynamicsError> {
        if rates.iter().any(|v| !v.is_finite()) {
            return Err(DynamicsError::NotFinite("Euler-angle rates"));
        }
        let e = euler_rate_matrix(euler);
        let terms = self.terms(euler, &(e * rates))?;
        let e_dot_rates = euler_rate_matrix_dot(euler, rates) * rates;
        Ok(EulerAngleForm {
            mass: e.tr_mul(&(terms.mass * e)),
            velocity: e.tr_mul(&(terms.mass * e_dot_rates + terms.velocity)),
            gravity: e.tr_mul(&terms.gravity),
        })
    }
}

/// Generalized force in Euler-angle coordinates, E^T Q, for a moment `moment` about P
/// in {A}.
pub fn euler_generalized_force(euler: &Vector3<f64>, moment: &Vector3<f64>) -> Vector3<f64> {
    euler_rate_matrix(euler).tr_mul(moment)
}
