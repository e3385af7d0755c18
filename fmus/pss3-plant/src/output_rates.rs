//! Output derivatives for fmi2GetRealOutputDerivatives / fmi3GetOutputDerivatives: of
//! every Real output, orders 1 and 2 (maxOutputDerivativeOrder), at the current state
//! with the inputs held (the motion the plant follows when the importer holds them).
//! - Closed form of the kinematics and the dynamics:
//!   theta (and yaw, pitch, roll = thx, -thy, thz): order 1 the Euler-angle rates
//!   E^-1 omega, order 2 the Euler-angle accelerations E^-1 (omegaDot - E_dot thetaDot);
//!   l: order 1 lDot = J omega, order 2 the actuator accelerations J omegaDot +
//!   J_dot omega (`robofmu_dynamics::pss3::motion`); thetaDot and lDot: order 1 those
//!   accelerations; omega: order 1 omegaDot (the dynamics).
//! - Every other (order 2 of omega, thetaDot, lDot; omegaDot, force, stopForce, detJ,
//!   condJ, the energies, gravityCompensation): the output's derivatives along the
//!   plant's local motion (`robofmu_dynamics::pss3::dynamics::LocalMotion`: the state to
//!   second order in time, then central differences of the output along it with one
//!   Richardson extrapolation), about 1e-9 relative; across an end stop's edge (its
//!   spring and damper start there) the average slope.
//!   All of them are differentiated together and kept for the point
//!   (`motion_cache`); gravityCompensation, the slope a master asks every step, in a
//!   pass of its own over the gravity torque alone, and thetaDot (order 2: a master
//!   passing input derivatives of order 2 asks it every step) over the Euler-angle
//!   rates alone.

use super::motion_cache::{Along, Derivatives, Entry, Point};
use super::{Computed, Pss3Plant};
use nalgebra::Vector3;
use robofmu_dynamics::pss3::dynamics::PlantState;
use robofmu_dynamics::pss3::rotation::{euler_accelerations, euler_rates};
use robofmu_dynamics::pss3::{assemble, jacobian, velocity_product};
use robofmu_fmi::prelude::OutputDerivativeError::{self, CannotEvaluate, NotProvided};

#[cfg(test)]
mod tests;

/// A Real output of Pss3Plant, named for its derivatives (element i passed with it:
/// 0..2 of a vector, the axis of yaw, pitch, roll, 0 for the other scalars).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Output {
    Theta,
    Omega,
    ThetaDot,
    OmegaDot,
    YawPitchRoll,
    L,
    LDot,
    Force,
    StopForce,
    GravityCompensation,
    DetJ,
    CondJ,
    KineticEnergy,
    PotentialEnergy,
}
use Output::*;

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

/// The scalar outputs differentiated along the local motion, in their slots 0..4.
const SCALARS: [Output; 4] = [DetJ, CondJ, KineticEnergy, PotentialEnergy];

/// The vector outputs differentiated along the local motion, 3 slots each after the
/// scalars.
const VECTORS: [Output; 7] = [
    Omega,
    ThetaDot,
    OmegaDot,
    LDot,
    Force,
    StopForce,
    GravityCompensation,
];

/// The slot in `Along` of element `i` of `output`, if it is one of those
/// differentiated along the local motion.
fn slot(output: Output, i: usize) -> Option<usize> {
    if let Some(k) = SCALARS.iter().position(|&s| s == output) {
        return Some(k);
    }
    let k = VECTORS.iter().position(|&v| v == output)?;
    (i < 3).then_some(SCALARS.len() + 3 * k + i)
}

/// Every output differentiated along the local motion, read from `c` (the outputs of
/// one state), in the order of `slot`.
fn samples(c: &Computed) -> Along {
    let o = &c.outputs;
    let scalars = [
        o.jacobian_det,
        o.jacobian_cond,
        o.kinetic_energy,
        o.potential_energy + o.end_stop_energy,
    ];
    let vectors = [
        o.omega,
        c.euler_rates,
        o.omega_dot,
        o.actuator_velocities,
        o.actuator_forces,
        o.end_stop_forces,
        c.gravity_compensation,
    ];
    let components = vectors.iter().flat_map(|v| [v.x, v.y, v.z]);
    Along::from_iterator(scalars.into_iter().chain(components))
}

/// `read` of the stored entry of the current point (`MotionCache`).
fn at_point<R>(m: &Pss3Plant, read: impl FnOnce(&mut Entry) -> R) -> Result<R, String> {
    let point = Point {
        params: m.params,
        state: m.current_state()?,
        inputs: m.inputs,
    };
    let motion = |p: &Point| {
        let plant = m.plant()?;
        plant
            .local_motion(&p.state, &p.inputs)
            .map_err(|e| e.to_string())
    };
    Ok(m.along.with(point, motion, read))
}

/// The first and second derivatives of every output in `Along` along the local motion
/// at the current point (evaluated once per point).
fn along_all(m: &Pss3Plant) -> Derivatives<Along> {
    at_point(m, |e| {
        let motion = &e.motion;
        let evaluate = || {
            let samples = |x: &PlantState| m.compute_at(x).map(|c| samples(&c));
            motion.clone()?.derivatives(samples)
        };
        e.all.get_or_insert_with(evaluate).clone()
    })?
}

/// The first and second derivatives of gravityCompensation along the local motion at
/// the current point (evaluated once per point): the same numbers as in `along_all`
/// (the same function of the same states), without the other outputs.
fn along_gravity(m: &Pss3Plant) -> Derivatives<Vector3<f64>> {
    at_point(m, |e| {
        let motion = &e.motion;
        let evaluate = || {
            let plant = m.plant()?;
            let gravity = |x: &PlantState| plant.gravity_compensation(&x.euler);
            let gravity = |x: &PlantState| gravity(x).map_err(|e| e.to_string());
            motion.clone()?.derivatives(gravity)
        };
        e.gravity.get_or_insert_with(evaluate).clone()
    })?
}

/// The first and second derivatives of thetaDot (the Euler-angle rates) along the
/// local motion at the current point (evaluated once per point): the same numbers as
/// in `along_all` (the same function of the same states), without the other outputs.
fn along_theta_dot(m: &Pss3Plant) -> Derivatives<Vector3<f64>> {
    at_point(m, |e| {
        let motion = &e.motion;
        let evaluate = || {
            let rates = |x: &PlantState| euler_rates(&x.euler, &x.omega).map_err(|e| e.to_string());
            motion.clone()?.derivatives(rates)
        };
        e.theta_dot.get_or_insert_with(evaluate).clone()
    })?
}

/// The `order`-th derivative (1 or 2) of element `i` of `output` along the local
/// motion.
fn along_motion(
    m: &Pss3Plant,
    output: Output,
    i: usize,
    order: u32,
) -> Result<f64, OutputDerivativeError> {
    let Some(k) = slot(output, i) else {
        return Err(NotProvided(format!(
            "{output:?} element {i} is not differentiated along the motion in Pss3Plant"
        )));
    };
    let derivatives = if output == GravityCompensation {
        along_gravity(m).map(|d| d[order as usize - 1][i])
    } else if output == ThetaDot {
        along_theta_dot(m).map(|d| d[order as usize - 1][i])
    } else {
        along_all(m).map(|d| d[order as usize - 1][k])
    };
    derivatives.map_err(|e| {
        CannotEvaluate(format!(
            "the plant cannot be evaluated near the current state: {e}"
        ))
    })
}

/// The `order`-th time derivative of element `i` of `output` (see the module doc).
pub fn output_derivative(
    m: &Pss3Plant,
    output: Output,
    i: usize,
    order: u32,
) -> Result<f64, OutputDerivativeError> {
    let c = m.computed.as_ref().map_err(|e| CannotEvaluate(e.clone()))?;
    let component = |f: fn(&Pss3Plant) -> Result<Vector3<f64>, String>| {
        f(m).map(|v| v[i]).map_err(CannotEvaluate)
    };
    let theta_rate = |order: u32| match order {
        1 => Ok(c.euler_rates[i]),
        _ => component(theta_ddot),
    };
    match (output, order) {
        (Theta, _) => theta_rate(order),
        (YawPitchRoll, _) => theta_rate(order).map(|r| if i == 1 { -r } else { r }),
        (L, 1) => Ok(c.outputs.actuator_velocities[i]),
        (L, _) | (LDot, 1) => component(l_ddot),
        (ThetaDot, 1) => component(theta_ddot),
        (Omega, 1) => Ok(c.outputs.omega_dot[i]),
        _ => along_motion(m, output, i, order),
    }
}
