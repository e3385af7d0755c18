//! Output derivatives for fmi2GetRealOutputDerivatives / fmi3GetOutputDerivatives: of
//! every Real output, orders 1 and 2 (maxOutputDerivativeOrder), at the current state
//! with the inputs held (the motion the plant follows when the importer holds them).
//! - Closed form of the kinematics and the dynamics:
//!   theta (and yaw, pitch, roll = thx, -thy, thz): order 1 the Euler-angle rates
//!   E^-1 omega, order 2 the Euler-angle accelerations E^-1 (omegaDot - E_dot thetaDot);
//!   l: order 1 lDot = J omega, order 2 the actuator accelerations J omegaDot +
//!   J_dot omega (`robofmu::pss3::motion`); thetaDot and lDot: order 1 those
//!   accelerations; omega: order 1 omegaDot (the dynamics).
//! - Every other (order 2 of omega, thetaDot, lDot; omegaDot, force, stopForce, detJ,
//!   condJ, the energies, gravityCompensation): the output's derivatives along the
//!   plant's local motion (`robofmu::pss3::dynamics::LocalMotion`: the state to
//!   second order in time, then central differences of the output along it with one
//!   Richardson extrapolation), about 1e-9 relative; across an end stop's edge (its
//!   spring and damper start there) the average slope.

use super::variables::*;
use super::{Computed, Pss3Plant};
use nalgebra::Vector3;
use robofmu::pss3::rotation::euler_accelerations;
use robofmu::pss3::{assemble, jacobian, velocity_product};
use robofmu_fmi::prelude::OutputDerivativeError::{self, CannotEvaluate, NotProvided};

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

/// The Real output with value reference `vr` read from `c` (the outputs of one state),
/// for those differentiated along the local motion.
fn value(vr: u32, c: &Computed) -> Option<f64> {
    let o = &c.outputs;
    Some(match vr {
        DET_J => o.jacobian_det,
        COND_J => o.jacobian_cond,
        KINETIC_ENERGY => o.kinetic_energy,
        POTENTIAL_ENERGY => o.potential_energy + o.end_stop_energy,
        _ => {
            let (group, i) = split(vr);
            let vector = match group {
                OMEGA => o.omega,
                THETA_DOT => c.euler_rates,
                OMEGA_DOT => o.omega_dot,
                L_DOT => o.actuator_velocities,
                FORCE => o.actuator_forces,
                STOP_FORCE => o.end_stop_forces,
                GRAVITY_COMPENSATION => c.gravity_compensation,
                _ => return None,
            };
            *vector.get(i)?
        }
    })
}

/// The `order`-th derivative (1 or 2) of output `vr` along the local motion.
fn along_motion(m: &Pss3Plant, vr: u32, order: u32) -> Result<f64, OutputDerivativeError> {
    let Some(_) = m.computed.as_ref().ok().and_then(|c| value(vr, c)) else {
        return Err(NotProvided(format!(
            "value reference {vr} is not a continuous Real output of Pss3Plant"
        )));
    };
    let evaluate = || -> Result<[f64; 2], String> {
        let state = m.current_state()?;
        let motion = m
            .plant()?
            .local_motion(&state, &m.inputs)
            .map_err(|e| e.to_string())?;
        motion.derivatives(|x| {
            let c = m.compute_at(x)?;
            Ok(value(vr, &c).unwrap_or(f64::NAN))
        })
    };
    let derivatives = evaluate().map_err(|e| {
        CannotEvaluate(format!(
            "the plant cannot be evaluated near the current state: {e}"
        ))
    })?;
    Ok(derivatives[order as usize - 1])
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
        _ => along_motion(m, vr, order),
    }
}
