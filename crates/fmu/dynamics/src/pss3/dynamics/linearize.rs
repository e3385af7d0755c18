//! Linearisation of the state derivative for Model Exchange directional derivatives.
//!
//! d(state_dot)/d(state): central differences with one Richardson extrapolation,
//! D = (4 D(h/2) - D(h)) / 3, truncation error O(h^4). Steps: 1e-3 rad for the
//! angles, 1e-3 (1 + |omega|) rad/s for omega. The omega columns are exact up to
//! rounding away from the end-stop contact edges (the derivative is quadratic in
//! omega plus terms linear in it), the angle columns accurate to about 1e-9 relative
//! (tests check 1e-7 against independent finite differences).
//! d(state_dot)/d(inputs): exact, the inputs enter linearly: omega_dot = M^-1 (J^T f +
//! tau_d + tau_c + ...), so the blocks are M^-1 J^T, M^-1 and M^-1.

use super::error::DynamicsError;
use super::integrate::StateVector;
use super::plant::{Plant, PlantInputs, PlantState};
use nalgebra::{Matrix3, SMatrix};

/// Derivative step for the Euler angles, rad.
const ANGLE_STEP: f64 = 1e-3;
/// Relative derivative step for the angular velocity.
const RATE_STEP: f64 = 1e-3;

/// Partial derivatives of the state derivative (x_dot, omega_dot).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Linearization {
    /// With respect to the state (thx, thy, thz, omega_x, omega_y, omega_z).
    pub state: SMatrix<f64, 6, 6>,
    /// With respect to the inputs (actuator forces, disturbance torque, commanded torque;
    /// three components each).
    pub inputs: SMatrix<f64, 6, 9>,
}

impl Plant {
    /// The linearisation at `state` under `inputs`.
    pub fn linearize(
        &self,
        state: &PlantState,
        inputs: &PlantInputs,
    ) -> Result<Linearization, DynamicsError> {
        let terms = self.evaluate(state, inputs)?.terms;
        let x = state.to_vector();
        let rate = |v: &StateVector| -> Result<StateVector, DynamicsError> {
            let d = self.derivative(&PlantState::from_vector(v), inputs)?;
            let mut out = StateVector::zeros();
            out.fixed_rows_mut::<3>(0).copy_from(&d.euler_rates);
            out.fixed_rows_mut::<3>(3).copy_from(&d.omega_dot);
            Ok(out)
        };
        let central = |k: usize, h: f64| -> Result<StateVector, DynamicsError> {
            let mut plus = x;
            let mut minus = x;
            plus[k] += h;
            minus[k] -= h;
            Ok((rate(&plus)? - rate(&minus)?) / (2.0 * h))
        };
        let mut state_jacobian = SMatrix::<f64, 6, 6>::zeros();
        for k in 0..6 {
            let h = if k < 3 {
                ANGLE_STEP
            } else {
                RATE_STEP * (1.0 + x[k].abs())
            };
            let column = (4.0 * central(k, 0.5 * h)? - central(k, h)?) / 3.0;
            state_jacobian.set_column(k, &column);
        }

        let mass_inverse: Matrix3<f64> = terms
            .mass
            .cholesky()
            .ok_or(DynamicsError::MassNotPositiveDefinite)?
            .inverse();
        let mut input_jacobian = SMatrix::<f64, 6, 9>::zeros();
        input_jacobian
            .fixed_view_mut::<3, 3>(3, 0)
            .copy_from(&(mass_inverse * terms.jacobian.matrix.transpose()));
        input_jacobian
            .fixed_view_mut::<3, 3>(3, 3)
            .copy_from(&mass_inverse);
        input_jacobian
            .fixed_view_mut::<3, 3>(3, 6)
            .copy_from(&mass_inverse);
        Ok(Linearization {
            state: state_jacobian,
            inputs: input_jacobian,
        })
    }
}
