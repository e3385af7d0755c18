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
use super::variables::{
    ACTUATOR_FORCE, DER_OMEGA, DER_THETA, DISTURBANCE_TORQUE, GENERALIZED_FORCE_COMMAND, OMEGA,
    OMEGA_DOT, PITCH, ROLL, THETA, THETA_DOT, TORQUE_COMMAND, YAW, real_getter,
};
use nalgebra::Vector3;
use robofmu_dynamics::pss3::dynamics::{Linearization, PlantInputs, PlantState};
use robofmu_dynamics::pss3::rotation::moment_from_generalized_force;
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

/// The states in the order of `Known::State`.
const STATES: [Declaration<Pss3Plant>; 2] = [THETA, OMEGA];
/// The inputs in the order of `Known::Input`.
const INPUTS: [Declaration<Pss3Plant>; 4] = [
    ACTUATOR_FORCE,
    DISTURBANCE_TORQUE,
    TORQUE_COMMAND,
    GENERALIZED_FORCE_COMMAND,
];

fn known(e: Element) -> Option<Known> {
    if let Some(k) = STATES.iter().position(|d| d.is(e)) {
        return Some(Known::State(3 * k + e.index));
    }
    let k = INPUTS.iter().position(|d| d.is(e))?;
    Some(Known::Input(3 * k + e.index))
}

/// dvUnknown = J dvKnown for the unknowns and knowns given (see the module doc).
pub fn directional_derivative(
    m: &Pss3Plant,
    unknowns: &[Element],
    knowns: &[Element],
    seed: &[f64],
    out: &mut [f64],
) -> Result<(), String> {
    let knowns = knowns
        .iter()
        .map(|&e| known(e).ok_or_else(|| format!("\"{}\" is neither a state nor an input", e.name)))
        .collect::<Result<Vec<_>, _>>()?;
    let seeded: Vec<(Known, f64)> = knowns
        .into_iter()
        .zip(seed.iter().copied())
        .filter(|&(_, s)| s != 0.0)
        .collect();
    let mut linearization = None;
    let mut by_differences = Vec::new();
    for (o, &unknown) in out.iter_mut().zip(unknowns) {
        let i = unknown.index;
        let row = if DER_THETA.is(unknown) || THETA_DOT.is(unknown) {
            Some(i)
        } else if DER_OMEGA.is(unknown) || OMEGA_DOT.is(unknown) {
            Some(3 + i)
        } else {
            None
        };
        *o = if let Some(row) = row {
            if linearization.is_none() {
                linearization = Some(linearize(m)?);
            }
            let (state, lin) = linearization.as_ref().expect("just computed");
            let mut sum = 0.0;
            for &(k, s) in &seeded {
                sum += rate_partial(state, lin, row, k)? * s;
            }
            sum
        } else if THETA.is(unknown) {
            along(&seeded, |k| identity(Known::State(i), k))
        } else if OMEGA.is(unknown) {
            along(&seeded, |k| identity(Known::State(3 + i), k))
        } else if YAW.is(unknown) {
            along(&seeded, |k| identity(Known::State(0), k))
        } else if PITCH.is(unknown) {
            -along(&seeded, |k| identity(Known::State(1), k))
        } else if ROLL.is(unknown) {
            along(&seeded, |k| identity(Known::State(2), k))
        } else {
            by_differences.push(unknown);
            0.0
        };
    }
    if by_differences.is_empty() {
        return Ok(());
    }
    for &(k, s) in &seeded {
        let column = output_partials(m, &by_differences, k)?;
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
fn output_partials(m: &Pss3Plant, unknowns: &[Element], k: Known) -> Result<Vec<f64>, String> {
    let getters = unknowns
        .iter()
        .map(|&e| {
            real_getter(e.name)
                .map(|get| (get, e.index))
                .ok_or_else(|| format!("\"{}\" is not a Real variable", e.name))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let values = |delta: f64| -> Result<Vec<f64>, String> {
        let mut copy = moved(m, k, delta)?;
        copy.calculate_values()
            .map_err(|e| format!("the plant cannot be evaluated near this point: {e}"))?;
        Ok(getters
            .iter()
            .map(|(get, i)| get.read(&mut copy, *i))
            .collect())
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
