//! Output derivatives for fmi2GetRealOutputDerivatives / fmi3GetOutputDerivatives:
//! only those that are exact at the current state (inputs held over the step):
//! - theta (and yaw, pitch, roll = thx, -thy, thz): order 1 the Euler-angle rates
//!   E^-1 omega, order 2 the Euler-angle accelerations E^-1 (omegaDot - E_dot thetaDot);
//! - l: order 1 lDot = J omega, order 2 the actuator accelerations
//!   J omegaDot + J_dot omega (the closed form of `robofmu::pss3::motion`);
//! - thetaDot and lDot: order 1 those accelerations;
//! - omega: order 1 omegaDot (the dynamics).
//!
//! Every other derivative (of omegaDot, forces, energies, det J, ...; order 2 of omega,
//! thetaDot, lDot) would need derivatives of the dynamics that the plant only has by
//! finite differences: it is refused (NotProvided).

use super::Pss3Plant;
use super::variables::*;
use nalgebra::Vector3;
use robofmu::pss3::rotation::euler_accelerations;
use robofmu::pss3::{assemble, jacobian, velocity_product};
use robofmu_fmi::prelude::OutputDerivativeError::{self, CannotEvaluate, NotProvided};

/// What the plant differentiates exactly, for the refusal message.
const PROVIDED: &str = "Pss3Plant provides exact output derivatives only of theta, yaw, \
                        pitch, roll, l (orders 1 and 2) and of thetaDot, lDot, omega (order 1)";

/// The Euler-angle accelerations at the current state and inputs.
fn theta_ddot(m: &Pss3Plant) -> Result<Vector3<f64>, String> {
    let c = m.computed.as_ref().map_err(Clone::clone)?;
    let state = m.current_state()?;
    euler_accelerations(&state.euler, &c.euler_rates, &c.outputs.omega_dot)
        .map_err(|e| e.to_string())
}

/// The actuator accelerations J omegaDot + J_dot omega at the current state and inputs
/// (also beyond a stroke end, where the end-stop springs act).
fn l_ddot(m: &Pss3Plant) -> Result<Vector3<f64>, String> {
    let c = m.computed.as_ref().map_err(Clone::clone)?;
    let state = m.current_state()?;
    let geometry = &m.plant()?.model().geometry;
    let assembly = assemble(geometry, &state.euler).map_err(|e| e.to_string())?;
    let j = jacobian(geometry, &assembly).map_err(|e| e.to_string())?;
    let l_dot = j.actuator_rates(&state.omega);
    let product = velocity_product(geometry, &assembly, &j, &state.omega, &l_dot);
    Ok(j.actuator_rates(&c.outputs.omega_dot) + product)
}

/// The `order`-th time derivative of the output `vr` (see the module doc).
pub fn output_derivative(m: &Pss3Plant, vr: u32, order: u32) -> Result<f64, OutputDerivativeError> {
    let (group, i) = split(vr);
    let c = m.computed.as_ref().map_err(|e| CannotEvaluate(e.clone()))?;
    let component = |f: fn(&Pss3Plant) -> Result<Vector3<f64>, String>| {
        f(m).map(|v| v[i]).map_err(CannotEvaluate)
    };
    let theta_rate = |order: u32| match order {
        1 => Ok(c.euler_rates[i]),
        _ => component(theta_ddot),
    };
    match (group, order) {
        (THETA, _) => theta_rate(order),
        (YAW_PITCH_ROLL, _) => theta_rate(order).map(|r| if i == 1 { -r } else { r }),
        (L, 1) => Ok(c.outputs.actuator_velocities[i]),
        (L, _) | (L_DOT, 1) => component(l_ddot),
        (THETA_DOT, 1) => component(theta_ddot),
        (OMEGA, 1) => Ok(c.outputs.omega_dot[i]),
        _ => Err(NotProvided(PROVIDED.to_string())),
    }
}
