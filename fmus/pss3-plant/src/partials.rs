//! Partial derivatives for fmi2GetDirectionalDerivative.
//!
//! Knowns: the states theta[i], omega[i] and the inputs. Unknowns:
//! - der(theta), der(omega), thetaDot, omegaDot: from `Plant::linearize` (state part by
//!   Richardson-extrapolated central differences, about 1e-9 relative; input part
//!   exact; the generalizedForceCommand columns are the torqueCommand columns times
//!   E^-T, exact);
//! - theta, omega, yaw, pitch, roll: exact (identity or sign);
//! - every other Real output: central differences with one Richardson extrapolation
//!   of the output itself (steps below).

use super::Pss3Plant;
use super::variables::*;
use nalgebra::Vector3;
use robofmu::pss3::rotation::moment_from_generalized_force;
use robofmu_fmi::core::Model;
use robofmu_fmi::core::variables::{Kind, find};

/// Finite-difference step for a state (rad, rad/s), scaled by 1 + |value|.
const STATE_STEP: f64 = 1e-4;
/// Finite-difference step for an input (N, N m), scaled by 1 + |value|. The outputs
/// are affine in the inputs, so the step only needs to beat round-off.
const INPUT_STEP: f64 = 1e-2;

/// A known variable: state index 0..5 (theta then omega) or input index 0..11
/// (actuatorForce, disturbanceTorque, torqueCommand, generalizedForceCommand: the
/// column order of `Linearization::inputs`, then the generalized force).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Known {
    State(usize),
    Input(usize),
}

fn known(vr: u32) -> Option<Known> {
    let (group, i) = split(vr);
    if i > 2 {
        return None;
    }
    Some(match group {
        THETA => Known::State(i),
        OMEGA => Known::State(3 + i),
        ACTUATOR_FORCE => Known::Input(i),
        DISTURBANCE_TORQUE => Known::Input(3 + i),
        TORQUE_COMMAND => Known::Input(6 + i),
        GENERALIZED_FORCE_COMMAND => Known::Input(9 + i),
        _ => return None,
    })
}

pub fn partial_derivative(m: &Pss3Plant, unknown: u32, known_vr: u32) -> Result<f64, String> {
    let k = known(known_vr)
        .ok_or_else(|| format!("value reference {known_vr} is neither a state nor an input"))?;
    let (group, i) = split(unknown);
    match group {
        DER_THETA | THETA_DOT if i < 3 => rate_partial(m, i, k),
        DER_OMEGA | OMEGA_DOT if i < 3 => rate_partial(m, 3 + i, k),
        THETA if i < 3 => Ok(identity(Known::State(i), k)),
        OMEGA if i < 3 => Ok(identity(Known::State(3 + i), k)),
        YAW_PITCH_ROLL if i < 3 => {
            let sign = if i == 1 { -1.0 } else { 1.0 };
            Ok(sign * identity(Known::State(i), k))
        }
        _ => output_partial(m, unknown, k),
    }
}

fn identity(state: Known, k: Known) -> f64 {
    if state == k { 1.0 } else { 0.0 }
}

/// d(row of the state derivative)/d(known) from the linearisation.
fn rate_partial(m: &Pss3Plant, row: usize, k: Known) -> Result<f64, String> {
    let state = m.current_state()?;
    let lin = m
        .plant()?
        .linearize(&state, &m.inputs)
        .map_err(|e| e.to_string())?;
    Ok(match k {
        Known::State(j) => lin.state[(row, j)],
        Known::Input(j) if j < 9 => lin.inputs[(row, j)],
        Known::Input(j) => {
            let mut unit = Vector3::zeros();
            unit[j - 9] = 1.0;
            let moment =
                moment_from_generalized_force(&state.euler, &unit).map_err(|e| e.to_string())?;
            (0..3).map(|c| lin.inputs[(row, 6 + c)] * moment[c]).sum()
        }
    })
}

/// The model with the known variable moved by `delta`.
fn moved(m: &Pss3Plant, k: Known, delta: f64) -> Result<Pss3Plant, String> {
    let mut copy = m.clone();
    copy.state = m.current_state()?;
    copy.started = true;
    copy.contacts = m.contacts;
    match k {
        Known::State(j) if j < 3 => copy.state.euler[j] += delta,
        Known::State(j) => copy.state.omega[j - 3] += delta,
        Known::Input(j) => {
            let field = match j / 3 {
                0 => &mut copy.inputs.forces,
                1 => &mut copy.inputs.disturbance_torque,
                2 => &mut copy.inputs.commanded_torque,
                _ => &mut copy.inputs.generalized_force,
            };
            field[j % 3] += delta;
        }
    }
    Ok(copy)
}

/// d(output)/d(known) by central differences with one Richardson extrapolation.
fn output_partial(m: &Pss3Plant, unknown: u32, k: Known) -> Result<f64, String> {
    let variable = find(Pss3Plant::variables(), unknown)
        .ok_or_else(|| format!("unknown value reference {unknown}"))?;
    let Kind::Real { get, .. } = &variable.kind else {
        return Err(format!("\"{}\" is not a Real variable", variable.name));
    };
    let value = |delta: f64| -> Result<f64, String> {
        let v = get(&moved(m, k, delta)?);
        if v.is_finite() {
            Ok(v)
        } else {
            Err(format!(
                "\"{}\" cannot be evaluated near this point",
                variable.name
            ))
        }
    };
    let current = match k {
        Known::State(j) => m.current_state()?.to_vector()[j],
        Known::Input(j) => {
            let inputs = &m.inputs;
            [
                inputs.forces,
                inputs.disturbance_torque,
                inputs.commanded_torque,
                inputs.generalized_force,
            ][j / 3][j % 3]
        }
    };
    let h = match k {
        Known::State(_) => STATE_STEP,
        Known::Input(_) => INPUT_STEP,
    } * (1.0 + current.abs());
    let central = |h: f64| -> Result<f64, String> { Ok((value(h)? - value(-h)?) / (2.0 * h)) };
    Ok((4.0 * central(0.5 * h)? - central(h)?) / 3.0)
}
