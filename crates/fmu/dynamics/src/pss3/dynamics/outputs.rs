//! The plant's outputs at one state.

use super::end_stops::StopContact;
use super::error::DynamicsError;
use super::plant::{Plant, PlantInputs, PlantState};
use nalgebra::Vector3;

/// Everything an FMU reports besides the state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlantOutputs {
    /// Euler angles (thx, thy, thz), rad.
    pub euler: Vector3<f64>,
    /// Angular velocity in {A}, rad/s.
    pub omega: Vector3<f64>,
    /// Angular acceleration in {A}, rad/s^2.
    pub omega_dot: Vector3<f64>,
    /// Actuator displacements l, m.
    pub actuator_displacements: Vector3<f64>,
    /// Actuator velocities l_dot, m/s.
    pub actuator_velocities: Vector3<f64>,
    /// Actuator forces f + J^-T tau_commanded, N.
    pub actuator_forces: Vector3<f64>,
    /// End-stop forces along u_i, N.
    pub end_stop_forces: Vector3<f64>,
    /// End-stop contacts (see `StopContact::code` for integer flags).
    pub end_stop_contacts: [StopContact; 3],
    /// det J, m^3.
    pub jacobian_det: f64,
    /// 2-norm condition number of J.
    pub jacobian_cond: f64,
    /// Kinetic energy, J.
    pub kinetic_energy: f64,
    /// Potential energy of gravity (zero at the height of C), J.
    pub potential_energy: f64,
    /// Energy stored in the end-stop springs, J.
    pub end_stop_energy: f64,
}

impl Plant {
    /// Outputs at `state` under `inputs`.
    pub fn outputs(
        &self,
        state: &PlantState,
        inputs: &PlantInputs,
    ) -> Result<PlantOutputs, DynamicsError> {
        let e = self.evaluate(state, inputs)?;
        let l = e.terms.assembly.l;
        let end_stop_energy = l
            .iter()
            .map(|&li| self.end_stops().potential_energy(li, self.stroke()))
            .sum();
        Ok(PlantOutputs {
            euler: state.euler,
            omega: state.omega,
            omega_dot: e.derivative.omega_dot,
            actuator_displacements: l,
            actuator_velocities: e.actuator_rates,
            actuator_forces: e.actuator_forces,
            end_stop_forces: e.stop_forces,
            end_stop_contacts: e.contacts,
            jacobian_det: e.terms.jacobian.det(),
            jacobian_cond: e.terms.jacobian.cond(),
            kinetic_energy: e.terms.kinetic_energy(&state.omega),
            potential_energy: self.model().potential_energy(&e.terms.assembly),
            end_stop_energy,
        })
    }
}
