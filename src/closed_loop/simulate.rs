//! The loop as one ODE, integrated with Dop853 at a tight tolerance and sampled at the
//! scenario's communication points.
//!
//! Time is carried as the first state (t' = 1) so that the right-hand side is
//! autonomous: ode_solvers 0.6.2's Dop853 evaluates its last stage at a wrong time,
//! which only autonomous systems do not notice. Each communication interval is
//! integrated on its own, so every sample is an accepted end point (no dense output)
//! and the kinks of the planner at t0 and tf, which lie on sample points, are never
//! stepped across.

use super::error::LoopError;
use super::scenario::LoopSpec;
use crate::control::pid::{self, PidInputs, PidState};
use crate::pss3::dynamics::{Plant, PlantInputs, PlantState, euler_generalized_force};
use crate::pss3::rotation::euler_rates;
use nalgebra::{SVector, Vector3};
use ode_solvers::{Dop853, OutputType, System};
use std::cell::RefCell;

/// t, theta (3), omega (3), PID integrals (3), PID filter states (3).
type LoopVector = SVector<f64, 13>;

/// Every connected signal of the loop at one instant (SI).
#[derive(Debug, Clone, PartialEq)]
pub struct LoopSample {
    pub time: f64,
    /// Planned angles, rates and accelerations.
    pub q: Vector3<f64>,
    pub qdot: Vector3<f64>,
    pub qddot: Vector3<f64>,
    /// Plant Euler angles, their rates, omega and omega_dot in {A}.
    pub theta: Vector3<f64>,
    pub theta_dot: Vector3<f64>,
    pub omega: Vector3<f64>,
    pub omega_dot: Vector3<f64>,
    /// The plant's gravity compensation E^T g (PID feedforward), N m.
    pub gravity_compensation: Vector3<f64>,
    /// PID output: generalized force in Euler-angle coordinates, N m.
    pub u: Vector3<f64>,
    /// Actuator forces that realise u, N.
    pub force: Vector3<f64>,
    /// Actuator displacements, m.
    pub l: Vector3<f64>,
}

struct Evaluation {
    sample: LoopSample,
    pid_rates: [PidState; 3],
}

fn pid_state(y: &LoopVector, axis: usize) -> PidState {
    PidState {
        integral: y[7 + axis],
        filter: y[10 + axis],
    }
}

fn evaluate(spec: &LoopSpec, plant: &Plant, y: &LoopVector) -> Result<Evaluation, LoopError> {
    let time = y[0];
    let theta = y.fixed_rows::<3>(1).into_owned();
    let omega = y.fixed_rows::<3>(4).into_owned();
    let planned: [_; 3] = std::array::from_fn(|i| spec.trajectories[i].sample(time));
    let theta_dot =
        euler_rates(&theta, &omega).map_err(crate::pss3::dynamics::DynamicsError::from)?;
    let gravity = plant.model().terms(&theta, &omega)?.gravity;
    let gravity_compensation = euler_generalized_force(&theta, &gravity);
    let mut u = Vector3::zeros();
    let mut pid_rates = [PidState::default(); 3];
    for axis in 0..3 {
        let inputs = PidInputs {
            setpoint: planned[axis].q,
            measurement: theta[axis],
            setpoint_rate: planned[axis].qdot,
            measured_rate: theta_dot[axis],
            feedforward: gravity_compensation[axis],
        };
        let gains = &spec.gains[axis];
        u[axis] = pid::output(gains, &pid_state(y, axis), &inputs).u;
        pid_rates[axis] = pid::derivatives(gains, &pid_state(y, axis), &inputs);
    }
    // The plant realises u as the moment tau = E^-T u about P (f = J^-T tau).
    let inputs = PlantInputs {
        generalized_force: u,
        ..PlantInputs::default()
    };
    let state = PlantState {
        euler: theta,
        omega,
    };
    let outputs = plant.outputs(&state, &inputs)?;
    let sample = LoopSample {
        time,
        q: Vector3::from_fn(|i, _| planned[i].q),
        qdot: Vector3::from_fn(|i, _| planned[i].qdot),
        qddot: Vector3::from_fn(|i, _| planned[i].qddot),
        theta,
        theta_dot,
        omega,
        omega_dot: outputs.omega_dot,
        gravity_compensation,
        u,
        force: outputs.actuator_forces,
        l: outputs.actuator_displacements,
    };
    Ok(Evaluation { sample, pid_rates })
}

struct Flow<'a> {
    spec: &'a LoopSpec,
    plant: &'a Plant,
    error: &'a RefCell<Option<LoopError>>,
}

impl System<f64, LoopVector> for Flow<'_> {
    fn system(&self, _s: f64, y: &LoopVector, dy: &mut LoopVector) {
        if y.iter().any(|v| !v.is_finite()) {
            dy.fill(f64::NAN);
            return;
        }
        match evaluate(self.spec, self.plant, y) {
            Ok(e) => {
                dy[0] = 1.0;
                dy.fixed_rows_mut::<3>(1).copy_from(&e.sample.theta_dot);
                dy.fixed_rows_mut::<3>(4).copy_from(&e.sample.omega_dot);
                for axis in 0..3 {
                    dy[7 + axis] = e.pid_rates[axis].integral;
                    dy[10 + axis] = e.pid_rates[axis].filter;
                }
            }
            Err(e) => {
                *self.error.borrow_mut() = Some(e);
                dy.fill(f64::NAN);
            }
        }
    }
}

/// Integrates one interval of length h from y; returns the end state.
fn advance(
    spec: &LoopSpec,
    plant: &Plant,
    y: &LoopVector,
    h: f64,
    tolerance: f64,
) -> Result<LoopVector, LoopError> {
    let error = RefCell::new(None);
    let flow = Flow {
        spec,
        plant,
        error: &error,
    };
    let mut solver = Dop853::from_param(
        flow,
        0.0,
        h,
        h,
        *y,
        tolerance,
        tolerance,
        0.9,
        0.0,
        0.333,
        6.0,
        h,
        0.0,
        1_000_000,
        u32::MAX,
        OutputType::Sparse,
    );
    let outcome = solver.integrate();
    let end = solver.y_out().last().copied();
    drop(solver);
    let fail = |message: String| LoopError::Integration {
        time: y[0],
        message,
    };
    if let Some(e) = error.into_inner() {
        return Err(fail(e.to_string()));
    }
    outcome.map_err(|e| fail(e.to_string()))?;
    let end = end.ok_or_else(|| fail("no output".into()))?;
    if end.iter().any(|v| !v.is_finite()) {
        return Err(fail("the state became non-finite".into()));
    }
    Ok(end)
}

/// Simulates the loop of `spec` from its start to its stop time with relative and
/// absolute tolerance `tolerance`, sampled at every communication point.
pub fn simulate(spec: &LoopSpec, tolerance: f64) -> Result<Vec<LoopSample>, LoopError> {
    let plant = Plant::new(spec.plant)?;
    let initial = plant.initial_state(spec.theta0, spec.omega0)?;
    let mut y = LoopVector::zeros();
    y[0] = spec.start_time;
    y.fixed_rows_mut::<3>(1).copy_from(&initial.euler);
    y.fixed_rows_mut::<3>(4).copy_from(&initial.omega);
    let steps = ((spec.stop_time - spec.start_time) / spec.step_size).round() as usize;
    let mut samples = Vec::with_capacity(steps + 1);
    samples.push(evaluate(spec, &plant, &y)?.sample);
    for k in 1..=steps {
        let next = spec.start_time + k as f64 * spec.step_size;
        y = advance(spec, &plant, &y, next - y[0], tolerance)?;
        y[0] = next;
        samples.push(evaluate(spec, &plant, &y)?.sample);
    }
    Ok(samples)
}
