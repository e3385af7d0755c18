//! The loop as one ODE, integrated with Dop853 at a tight tolerance and sampled at the
//! scenario's communication points.
//!
//! Time is carried as the first state (t' = 1), so the right-hand side is autonomous
//! (ode_solvers 0.6.2's Dop853, integrated with before, evaluated its twelfth stage at
//! a wrong time, which autonomous systems do not notice; [`crate::ode`] has no such
//! fault, and the form is kept so that results stay bit for bit). Each interval is
//! integrated on its own, so every sample is an accepted end point (no dense output)
//! and the kinks of the planner at t0 and tf, which lie on sample points, are never
//! stepped across.

use super::controller::Controller;
use super::error::LoopError;
use super::scenario::LoopSpec;
use crate::computed_torque::{ComputedTorque, Inputs};
use crate::control::pid::{self, PidGains, PidInputs, PidState};
use crate::control::trajectory::Sample;
use crate::ode::{self, Settings};
use crate::pss3::dynamics::{DynamicsError, Plant, PlantInputs, PlantState};
use crate::pss3::rotation::euler_rates;
use nalgebra::{SVector, Vector3};

/// t, theta (3), omega (3), PID (or computed-torque) integrals (3), PID filter states
/// (3).
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
    /// Controller output: generalized force in Euler-angle coordinates, N m.
    pub u: Vector3<f64>,
    /// Actuator forces that realise u, N.
    pub force: Vector3<f64>,
    /// Actuator displacements, m.
    pub l: Vector3<f64>,
}

/// The controller's side of the loop at one state: everything but the plant's response.
struct Control {
    planned: [Sample; 3],
    theta_dot: Vector3<f64>,
    gravity_compensation: Vector3<f64>,
    /// Controller output, realised by the plant as tau = E^-T u about P (f = J^-T tau).
    u: Vector3<f64>,
    pid_rates: [PidState; 3],
}

fn pid_state(y: &LoopVector, axis: usize) -> PidState {
    PidState {
        integral: y[7 + axis],
        filter: y[10 + axis],
    }
}

fn plant_state(y: &LoopVector) -> PlantState {
    PlantState {
        euler: y.fixed_rows::<3>(1).into_owned(),
        omega: y.fixed_rows::<3>(4).into_owned(),
    }
}

fn control(spec: &LoopSpec, plant: &Plant, y: &LoopVector) -> Result<Control, LoopError> {
    let state = plant_state(y);
    let trajectories = spec.trajectories_at(y[0]);
    let planned: [_; 3] = std::array::from_fn(|i| trajectories[i].sample(y[0]));
    let theta_dot = euler_rates(&state.euler, &state.omega).map_err(DynamicsError::from)?;
    let gravity_compensation = plant.gravity_compensation(&state.euler)?;
    let (u, pid_rates) = match &spec.controller {
        Controller::Pid(gains) => pid_control(
            gains,
            y,
            &planned,
            &state,
            &theta_dot,
            &gravity_compensation,
        ),
        Controller::ComputedTorque(law) => {
            computed_torque_control(law, y, &planned, &state, &theta_dot)?
        }
    };
    Ok(Control {
        planned,
        theta_dot,
        gravity_compensation,
        u,
        pid_rates,
    })
}

/// One axis's PID inputs: the planned angle and rate against the plant's, the plant's
/// gravity compensation as feedforward (the continuous and the sampled loop alike).
pub(super) fn pid_inputs(
    axis: usize,
    planned: &[Sample; 3],
    state: &PlantState,
    theta_dot: &Vector3<f64>,
    gravity_compensation: &Vector3<f64>,
) -> PidInputs {
    PidInputs {
        setpoint: planned[axis].q,
        measurement: state.euler[axis],
        setpoint_rate: planned[axis].qdot,
        measured_rate: theta_dot[axis],
        feedforward: gravity_compensation[axis],
    }
}

/// The PID's output and state rates (the feedforward is the plant's gravity
/// compensation).
fn pid_control(
    gains: &[PidGains; 3],
    y: &LoopVector,
    planned: &[Sample; 3],
    state: &PlantState,
    theta_dot: &Vector3<f64>,
    gravity_compensation: &Vector3<f64>,
) -> (Vector3<f64>, [PidState; 3]) {
    let mut u = Vector3::zeros();
    let mut pid_rates = [PidState::default(); 3];
    for axis in 0..3 {
        let inputs = pid_inputs(axis, planned, state, theta_dot, gravity_compensation);
        let gains = &gains[axis];
        u[axis] = pid::output(gains, &pid_state(y, axis), &inputs).u;
        pid_rates[axis] = pid::derivatives(gains, &pid_state(y, axis), &inputs);
    }
    (u, pid_rates)
}

/// The computed-torque law's output and integral rates (its error integrals share the
/// PID integrals' slots of the state; the filter slots stay at zero).
fn computed_torque_control(
    law: &ComputedTorque,
    y: &LoopVector,
    planned: &[Sample; 3],
    state: &PlantState,
    theta_dot: &Vector3<f64>,
) -> Result<(Vector3<f64>, [PidState; 3]), LoopError> {
    let planned_vector = |f: fn(&Sample) -> f64| Vector3::from_fn(|i, _| f(&planned[i]));
    let inputs = Inputs {
        setpoint: planned_vector(|s| s.q),
        setpoint_rate: planned_vector(|s| s.qdot),
        setpoint_acceleration: planned_vector(|s| s.qddot),
        measurement: state.euler,
        measured_rate: *theta_dot,
    };
    let integral = y.fixed_rows::<3>(7).into_owned();
    let output = law.output(&integral, &inputs)?;
    let integral_rate = law.integral_rate(&output);
    let rates = std::array::from_fn(|i| PidState {
        integral: integral_rate[i],
        filter: 0.0,
    });
    Ok((output.u, rates))
}

fn plant_inputs(c: &Control) -> PlantInputs {
    PlantInputs {
        generalized_force: c.u,
        ..PlantInputs::default()
    }
}

/// State derivative of the loop (the integrator's right-hand side).
fn rates(spec: &LoopSpec, plant: &Plant, y: &LoopVector) -> Result<LoopVector, LoopError> {
    let c = control(spec, plant, y)?;
    let d = plant.derivative(&plant_state(y), &plant_inputs(&c))?;
    let mut dy = LoopVector::zeros();
    dy[0] = 1.0;
    dy.fixed_rows_mut::<3>(1).copy_from(&d.euler_rates);
    dy.fixed_rows_mut::<3>(4).copy_from(&d.omega_dot);
    for axis in 0..3 {
        dy[7 + axis] = c.pid_rates[axis].integral;
        dy[10 + axis] = c.pid_rates[axis].filter;
    }
    Ok(dy)
}

/// Every signal of the loop at state y (for the output samples).
fn sample(spec: &LoopSpec, plant: &Plant, y: &LoopVector) -> Result<LoopSample, LoopError> {
    let c = control(spec, plant, y)?;
    let state = plant_state(y);
    let outputs = plant.outputs(&state, &plant_inputs(&c))?;
    let planned = |f: fn(&Sample) -> f64| Vector3::from_fn(|i, _| f(&c.planned[i]));
    Ok(LoopSample {
        time: y[0],
        q: planned(|s| s.q),
        qdot: planned(|s| s.qdot),
        qddot: planned(|s| s.qddot),
        theta: state.euler,
        theta_dot: c.theta_dot,
        omega: state.omega,
        omega_dot: outputs.omega_dot,
        gravity_compensation: c.gravity_compensation,
        u: c.u,
        force: outputs.actuator_forces,
        l: outputs.actuator_displacements,
    })
}

struct Flow<'a> {
    spec: &'a LoopSpec,
    plant: &'a Plant,
    error: Option<LoopError>,
}

impl Flow<'_> {
    /// The loop's rates at `y`, NaN where they cannot be evaluated.
    fn evaluate(&mut self, y: &LoopVector, dy: &mut LoopVector) {
        if y.iter().any(|v| !v.is_finite()) {
            dy.fill(f64::NAN);
            return;
        }
        match rates(self.spec, self.plant, y) {
            Ok(rates) => *dy = rates,
            Err(e) => {
                self.error = Some(e);
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
    let mut flow = Flow {
        spec,
        plant,
        error: None,
    };
    let settings = Settings {
        max_steps: 1_000_000,
        ..Settings::dop853(tolerance, h)
    };
    let outcome = ode::dop853(|_s, y, dy| flow.evaluate(y, dy), 0.0, h, *y, &settings);
    let fail = |message: String| LoopError::Integration {
        time: y[0],
        message,
    };
    if let Some(e) = flow.error {
        return Err(fail(e.to_string()));
    }
    let end = outcome.map_err(|e| fail(e.to_string()))?.y;
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
    samples.push(sample(spec, &plant, &y)?);
    for k in 1..=steps {
        let next = spec.start_time + k as f64 * spec.step_size;
        y = advance(spec, &plant, &y, next - y[0], tolerance)?;
        y[0] = next;
        samples.push(sample(spec, &plant, &y)?);
    }
    Ok(samples)
}
