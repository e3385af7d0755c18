//! Directional derivatives for fmi2GetDirectionalDerivative, for a whole seed vector in
//! one call: the plant is linearized once per call (not once per (unknown, known)
//! pair) and each seeded known is moved once for all the finite-difference unknowns.
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
use robofmu::pss3::dynamics::{Linearization, PlantInputs, PlantState};
use robofmu::pss3::rotation::moment_from_generalized_force;
use robofmu_fmi::core::variables::{Kind, find};
use robofmu_fmi::prelude::*;

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

/// dvUnknown = J dvKnown for the unknowns and knowns given (see the module doc).
pub fn directional_derivative(
    m: &Pss3Plant,
    table: &[Variable<Pss3Plant>],
    unknowns: &[u32],
    known_vrs: &[u32],
    seed: &[f64],
    out: &mut [f64],
) -> Result<(), String> {
    let knowns = known_vrs
        .iter()
        .map(|&vr| {
            known(vr).ok_or_else(|| format!("value reference {vr} is neither a state nor an input"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let seeded: Vec<(Known, f64)> = knowns
        .into_iter()
        .zip(seed.iter().copied())
        .filter(|&(_, s)| s != 0.0)
        .collect();
    let mut linearization = None;
    let mut by_differences = Vec::new();
    for (o, &unknown) in out.iter_mut().zip(unknowns) {
        let (group, i) = split(unknown);
        let row = match group {
            DER_THETA | THETA_DOT if i < 3 => Some(i),
            DER_OMEGA | OMEGA_DOT if i < 3 => Some(3 + i),
            _ => None,
        };
        *o = match (group, row) {
            (_, Some(row)) => {
                if linearization.is_none() {
                    linearization = Some(linearize(m)?);
                }
                let (state, lin) = linearization.as_ref().expect("just computed");
                let mut sum = 0.0;
                for &(k, s) in &seeded {
                    sum += rate_partial(state, lin, row, k)? * s;
                }
                sum
            }
            (THETA, _) if i < 3 => along(&seeded, |k| identity(Known::State(i), k)),
            (OMEGA, _) if i < 3 => along(&seeded, |k| identity(Known::State(3 + i), k)),
            (YAW_PITCH_ROLL, _) if i < 3 => {
                let sign = if i == 1 { -1.0 } else { 1.0 };
                sign * along(&seeded, |k| identity(Known::State(i), k))
            }
            _ => {
                by_differences.push(unknown);
                0.0
            }
        };
    }
    if by_differences.is_empty() {
        return Ok(());
    }
    for &(k, s) in &seeded {
        let column = output_partials(m, table, &by_differences, k)?;
        for (o, &unknown) in out.iter_mut().zip(unknowns) {
            if let Some(at) = by_differences.iter().position(|&u| u == unknown) {
                *o += column[at] * s;
            }
        }
    }
    Ok(())
}

fn along(seeded: &[(Known, f64)], partial: impl Fn(Known) -> f64) -> f64 {
    seeded.iter().map(|&(k, s)| partial(k) * s).sum()
}

fn identity(state: Known, k: Known) -> f64 {
    if state == k { 1.0 } else { 0.0 }
}

/// The current state and the linearisation there.
fn linearize(m: &Pss3Plant) -> Result<(PlantState, Linearization), String> {
    let state = m.current_state()?;
    let lin = m
        .plant()?
        .linearize(&state, &m.inputs)
        .map_err(|e| e.to_string())?;
    Ok((state, lin))
}

/// d(row of the state derivative)/d(known) from the linearisation.
fn rate_partial(
    state: &PlantState,
    lin: &Linearization,
    row: usize,
    k: Known,
) -> Result<f64, String> {
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

/// The value of the known `k` in `state` and `inputs`.
fn known_value<'a>(
    state: &'a mut PlantState,
    inputs: &'a mut PlantInputs,
    k: Known,
) -> &'a mut f64 {
    match k {
        Known::State(j) if j < 3 => &mut state.euler[j],
        Known::State(j) => &mut state.omega[j - 3],
        Known::Input(j) => {
            let field = match j / 3 {
                0 => &mut inputs.forces,
                1 => &mut inputs.disturbance_torque,
                2 => &mut inputs.commanded_torque,
                _ => &mut inputs.generalized_force,
            };
            &mut field[j % 3]
        }
    }
}

/// The model with the known variable moved by `delta`.
fn moved(m: &Pss3Plant, k: Known, delta: f64) -> Result<Pss3Plant, String> {
    let mut copy = m.clone();
    copy.state = m.current_state()?;
    copy.started = true;
    copy.contacts = m.contacts;
    *known_value(&mut copy.state, &mut copy.inputs, k) += delta;
    Ok(copy)
}

/// d(output)/d(known) of every output in `unknowns` by central differences with one
/// Richardson extrapolation: four evaluations of the moved plant for all of them.
fn output_partials(
    m: &Pss3Plant,
    table: &[Variable<Pss3Plant>],
    unknowns: &[u32],
    k: Known,
) -> Result<Vec<f64>, String> {
    let getters = unknowns
        .iter()
        .map(|&vr| match find(table, vr).map(|v| (v.name(), &v.kind)) {
            Some((_, Kind::Real { get, .. })) => Ok(get),
            Some((name, _)) => Err(format!("\"{name}\" is not a Real variable")),
            None => Err(format!("unknown value reference {vr}")),
        })
        .collect::<Result<Vec<_>, _>>()?;
    let values = |delta: f64| -> Result<Vec<f64>, String> {
        let mut copy = moved(m, k, delta)?;
        copy.calculate_values()
            .map_err(|e| format!("the plant cannot be evaluated near this point: {e}"))?;
        Ok(getters.iter().map(|get| get.call(&copy)).collect())
    };
    let current = *known_value(&mut m.current_state()?, &mut m.inputs.clone(), k);
    let h = match k {
        Known::State(_) => STATE_STEP,
        Known::Input(_) => INPUT_STEP,
    } * (1.0 + current.abs());
    let central = |h: f64| -> Result<Vec<f64>, String> {
        let (plus, minus) = (values(h)?, values(-h)?);
        Ok(plus
            .iter()
            .zip(&minus)
            .map(|(p, q)| (p - q) / (2.0 * h))
            .collect())
    };
    let (half, full) = (central(0.5 * h)?, central(h)?);
    Ok(half
        .iter()
        .zip(&full)
        .map(|(a, b)| (4.0 * a - b) / 3.0)
        .collect())
}
